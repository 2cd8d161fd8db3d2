//! `oblique_sweep::job`: a whole build of configs/quick.toml (about a second) reports every stage
//! in order and leaves only the table; a stop during the pre-flight touches nothing; an earlier
//! run's checkpoint is refused unless resumed, and resuming gives the same table.

use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Mutex;

use oblique_sweep::job::{Earlier, Job, JobError, Note, Outcome};
use oblique_sweep::{Config, Progress};

/// The stages and notes a job reported, in order.
#[derive(Default)]
struct Heard {
    stages: Mutex<Vec<String>>,
    notes: Mutex<Vec<String>>,
    /// Set when the second patch's refinement starts: stops the build there, with the first
    /// patch's nodes in the checkpoint.
    stop_at_build: Option<&'static AtomicBool>,
}

impl Progress for Heard {
    fn phase(&self, stage: &str, _: &str) {
        if let Ok(mut s) = self.stages.lock() {
            if s.last().map(String::as_str) != Some(stage) {
                s.push(stage.to_string());
            }
        }
        if let Some(stop) = self.stop_at_build {
            if stage == "partial_high refinement" {
                stop.store(true, Ordering::SeqCst);
            }
        }
    }
    fn total(&self, _: u64) {}
    fn inc(&self, _: u64) {}
    fn note(&self, note: &Note<'_>) {
        if let Ok(mut n) = self.notes.lock() {
            n.push(note.to_string());
        }
    }
}

fn dir(name: &str) -> PathBuf {
    let d = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("sweep-job-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).expect("scratch folder");
    d
}

/// configs/quick.toml writing `out`.
fn quick(out: &std::path::Path) -> Job {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../configs/quick.toml");
    let (mut cfg, text) = Config::load(path.as_ref()).expect("configs/quick.toml");
    cfg.output = out.to_path_buf();
    cfg.run.threads = 2;
    Job::new(cfg, text, "job test")
}

fn files(d: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(d)
        .expect("read folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

#[test]
fn a_job_reports_every_stage_in_order_and_leaves_only_the_table() {
    let d = dir("whole");
    let job = quick(&d.join("t.h5"));
    let stages = job.stages();
    let heard = Heard::default();
    let stop = AtomicBool::new(false);
    let outcome = job.run(&heard, &stop).expect("the build");
    assert!(matches!(outcome, Outcome::Table { .. }));
    assert_eq!(*heard.stages.lock().expect("stages"), stages);
    let notes = heard.notes.lock().expect("notes");
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert!(notes[0].starts_with("preflight: tolerances reachable"));
    assert_eq!(files(&d), ["t.h5"]);
}

#[test]
fn a_stop_during_the_preflight_touches_nothing() {
    let d = dir("early");
    let stop = AtomicBool::new(true);
    let e = quick(&d.join("t.h5"))
        .run(&Heard::default(), &stop)
        .expect_err("stopped");
    assert!(matches!(e, JobError::InterruptedEarly), "{e}");
    assert!(!e.user_can_fix());
    assert!(files(&d).is_empty(), "{:?}", files(&d));
}

#[test]
fn an_interrupted_job_is_refused_until_resumed_and_resumes_to_the_same_table() {
    static STOP: AtomicBool = AtomicBool::new(false);
    let d = dir("resume");
    let out = d.join("t.h5");
    let heard = Heard {
        stop_at_build: Some(&STOP),
        ..Heard::default()
    };
    let e = quick(&out).run(&heard, &STOP).expect_err("stopped");
    let ckpt = d.join("t.h5.ckpt");
    assert!(
        matches!(&e, JobError::Interrupted { checkpoint } if *checkpoint == ckpt),
        "{e}"
    );
    assert_eq!(files(&d), ["t.h5.ckpt"]);

    let stop = AtomicBool::new(false);
    let e = quick(&out)
        .run(&Heard::default(), &stop)
        .expect_err("refused");
    assert!(
        matches!(&e, JobError::CheckpointPending { checkpoint, .. } if *checkpoint == ckpt),
        "{e}"
    );
    assert!(e.user_can_fix());
    // Library messages name no command-line flags: the caller says how to go on.
    assert!(!e.to_string().contains("--"), "{e}");

    let mut job = quick(&out);
    job.earlier = Earlier::Resume;
    let heard = Heard::default();
    let Outcome::Table { built: resumed, .. } = job.run(&heard, &stop).expect("resumed") else {
        panic!("a table")
    };
    let notes = heard.notes.lock().expect("notes");
    assert!(
        notes
            .iter()
            .any(|n| n.starts_with("resuming from ") && !n.contains(": 0 nodes")),
        "{notes:?}"
    );
    assert_eq!(files(&d), ["t.h5"]);

    // The same table as an uninterrupted job's: every node value and check, bit for bit
    // (`Debug` writes each f64 as the shortest text that reads back to it).
    let Outcome::Table { built: whole, .. } = quick(&d.join("whole.h5"))
        .run(&Heard::default(), &stop)
        .expect("whole")
    else {
        panic!("a table")
    };
    assert_eq!(format!("{resumed:?}"), format!("{whole:?}"));
}
