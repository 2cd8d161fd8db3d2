//! `build_table`: a table build (`oblique_sweep::job`) from Python, interruptible with Ctrl-C.
//!
//! The build runs on a worker thread of its own with the GIL released; the calling thread waits
//! for it in steps of [`POLL`], and between steps hands the build's progress to the Python
//! callback and runs the interpreter's signal handlers. A `KeyboardInterrupt` there (or any
//! exception of the callback) sets the build's stop flag; the build stops after its current
//! batch of impacts, with every finished node in the checkpoint, and the exception is raised
//! once it has.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError, Sender};
use std::sync::Arc;
use std::time::{Duration, Instant};

use pyo3::exceptions::{
    PyFileExistsError, PyKeyboardInterrupt, PyOSError, PyRuntimeError, PyValueError,
};
use pyo3::prelude::*;

use oblique_sweep::config::Config;
use oblique_sweep::job::{CheckpointAfter, Earlier, Job, JobError, Note, Outcome};
use oblique_sweep::nodestore::LockError;
use oblique_sweep::{Built, Progress, RunError};
use oblique_table::write::{OutputPathError, StorageError};

/// How long the calling thread waits for the build between two looks at signals and progress.
const POLL: Duration = Duration::from_millis(100);

/// What the build reports to the calling thread.
enum Msg {
    Phase(String, String),
    Total(u64),
    Inc(u64),
    Note(String),
    Done(Result<(), JobError>),
}

/// The build's [`Progress`]: every report goes to the calling thread.
struct Reporter {
    tx: Sender<Msg>,
}

impl Reporter {
    fn send(&self, m: Msg) {
        // The calling thread outlives the build: a failed send only means it is gone.
        let _ = self.tx.send(m);
    }
}

impl Progress for Reporter {
    fn phase(&self, stage: &str, detail: &str) {
        self.send(Msg::Phase(stage.to_string(), detail.to_string()));
    }
    fn total(&self, n: u64) {
        self.send(Msg::Total(n));
    }
    fn inc(&self, n: u64) {
        self.send(Msg::Inc(n));
    }
    fn note(&self, note: &Note<'_>) {
        self.send(Msg::Note(note.to_string()));
    }
}

/// Where the build is, as the callback sees it.
struct State {
    stages: Vec<String>,
    /// Index of the current stage in `stages`.
    step: usize,
    stage: String,
    detail: String,
    done: u64,
    total: Option<u64>,
    /// Impacts finished since the callback last heard.
    counted: bool,
}

impl State {
    /// Call `callback(kind, step, steps, stage, detail, done, total, message)`.
    fn report(&self, callback: &Bound<'_, PyAny>, kind: &str, message: &str) -> PyResult<()> {
        callback.call1((
            kind,
            self.step + 1,
            self.stages.len(),
            self.stage.as_str(),
            self.detail.as_str(),
            self.done,
            self.total,
            message,
        ))?;
        Ok(())
    }

    /// Take in one message; report it at once unless it is a count (counts are reported once
    /// per poll, by [`State::flush`]).
    fn take(&mut self, m: Msg, callback: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
        match m {
            Msg::Phase(stage, detail) => {
                if let Some(i) = self.stages.iter().position(|s| *s == stage) {
                    self.step = i;
                }
                self.stage = stage;
                self.detail = detail;
                self.done = 0;
                self.total = None;
                self.counted = false;
                if let Some(cb) = callback {
                    self.report(cb, "stage", "")?;
                }
            }
            Msg::Total(n) => {
                self.total = Some(n);
                self.done = 0;
                self.counted = true;
            }
            Msg::Inc(n) => {
                self.done += n;
                self.counted = true;
            }
            Msg::Note(text) => {
                if let Some(cb) = callback {
                    self.report(cb, "note", &text)?;
                }
            }
            Msg::Done(_) => {}
        }
        Ok(())
    }

    /// Report the counts, if any came since the last report.
    fn flush(&mut self, callback: Option<&Bound<'_, PyAny>>) -> PyResult<()> {
        if std::mem::take(&mut self.counted) {
            if let Some(cb) = callback {
                self.report(cb, "count", "")?;
            }
        }
        Ok(())
    }
}

/// The messages that arrive within [`POLL`] (fewer when the build ends), and the receiver.
/// Runs with the GIL released.
fn wait(rx: Receiver<Msg>) -> (Receiver<Msg>, Vec<Msg>, bool) {
    let deadline = Instant::now() + POLL;
    let mut msgs = Vec::new();
    loop {
        match rx.recv_timeout(deadline.saturating_duration_since(Instant::now())) {
            Ok(m @ Msg::Done(_)) => {
                msgs.push(m);
                return (rx, msgs, true);
            }
            Ok(m) => msgs.push(m),
            Err(RecvTimeoutError::Timeout) => return (rx, msgs, false),
            // The worker ended without a result: it panicked (reported by `join`).
            Err(RecvTimeoutError::Disconnected) => return (rx, msgs, true),
        }
    }
}

/// The error and its causes on one line, each cause once.
fn chain(e: &dyn std::error::Error) -> String {
    let mut text = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        let part = c.to_string();
        if !text.contains(&part) {
            text.push_str(": ");
            text.push_str(&part);
        }
        cause = c.source();
    }
    text
}

/// `OSError` with the message `text` and the errno of the first I/O error among the causes of
/// `e` (Python then raises the matching subclass: `PermissionError`, `IsADirectoryError`, …).
fn os_error(e: &(dyn std::error::Error + 'static), text: String) -> PyErr {
    let mut cause: Option<&(dyn std::error::Error + 'static)> = Some(e);
    while let Some(c) = cause {
        if let Some(code) = c
            .downcast_ref::<std::io::Error>()
            .and_then(std::io::Error::raw_os_error)
        {
            return PyOSError::new_err((code, text));
        }
        cause = c.source();
    }
    PyOSError::new_err(text)
}

/// `OSError` for an output path that cannot be written (`IsADirectoryError` for a folder),
/// `ValueError` for an output that is an input.
fn output_path_error(e: &OutputPathError) -> PyErr {
    match e {
        OutputPathError::IsInput { .. } => PyValueError::new_err(e.to_string()),
        OutputPathError::NotAFile { kind, .. } if kind == "a directory" => {
            PyOSError::new_err((21, e.to_string()))
        }
        _ => os_error(e, chain(e)),
    }
}

/// A failed build as a Python exception: a config's fault (a key to change) as `ValueError`,
/// an earlier run's checkpoint in the way as `FileExistsError`, file system failures as
/// `OSError`, the rest (another run on the output, a defect of the build) as `RuntimeError`.
fn job_error(e: JobError) -> PyErr {
    let text = chain(&e);
    match e {
        JobError::Threads { .. } => PyValueError::new_err(text),
        JobError::OutputPath(p) => output_path_error(&p),
        JobError::CheckpointPending { checkpoint, nodes } => PyFileExistsError::new_err(format!(
            "{} holds the checkpoint of an interrupted run ({nodes} nodes) of this config: \
             continue it with resume=True or discard it and start afresh with restart=True",
            checkpoint.display()
        )),
        ref e @ JobError::CheckpointForeign { ref checkpoint, .. } => {
            let (what, why) = e.foreign_checkpoint_words().unwrap_or_default();
            PyFileExistsError::new_err(format!(
                "{} holds {what}: {why} discard it and start afresh with restart=True",
                checkpoint.display()
            ))
        }
        JobError::Lock(LockError::Held { .. }) => PyRuntimeError::new_err(text),
        JobError::Preflight(ref s) if !s.user_can_fix() => PyRuntimeError::new_err(text),
        JobError::Preflight(_) => PyValueError::new_err(text),
        // A failure of the config (a key to change) or of the build; not of the machine.
        JobError::Build { ref error, .. }
            if matches!(**error, RunError::Sweep(_) | RunError::Missing { .. }) =>
        {
            let t = with_checkpoint(text, &e);
            if error.user_can_fix() {
                PyValueError::new_err(t)
            } else {
                PyRuntimeError::new_err(t)
            }
        }
        JobError::Pool(_) => PyRuntimeError::new_err(text),
        // The table's checks contradict its bound: the message names the keys to change.
        JobError::Write(StorageError::BoundContradicted { .. }) => PyValueError::new_err(text),
        JobError::Interrupted { checkpoint } => {
            PyKeyboardInterrupt::new_err(interrupted(&checkpoint.display().to_string()))
        }
        JobError::InterruptedEarly => PyKeyboardInterrupt::new_err(text),
        ref other => {
            let t = with_checkpoint(text, other);
            os_error(other, t)
        }
    }
}

/// `text`, followed by what became of the checkpoint of a failed build.
fn with_checkpoint(text: String, e: &JobError) -> String {
    match e {
        JobError::Build {
            checkpoint, after, ..
        } => match after {
            CheckpointAfter::Removed => text,
            CheckpointAfter::NotRemoved(r) => {
                format!("{text} (and the checkpoint of this build could not be removed: {r})")
            }
            CheckpointAfter::Kept => format!(
                "{text}; finished nodes are kept in {}: resume=True continues, restart=True \
                 discards them",
                checkpoint.display()
            ),
        },
        _ => text,
    }
}

/// The last note of a build, as `sweep run` ends: what was written to `output`.
fn written(output: &Path, built: &Built, wall_s: f64) -> String {
    let nodes: usize = built.patches.iter().map(|p| p.unique_nodes).sum();
    let simulated: usize = built.patches.iter().map(|p| p.simulated).sum();
    let max_error = built
        .checks
        .iter()
        .map(|c| c.interpolation_error)
        .fold(0.0, f64::max);
    format!(
        "wrote {}: {nodes} nodes ({simulated} simulated) + {} held-out checks, max check error \
         {max_error:.2e}, {wall_s:.1} s",
        output.display(),
        built.checks.len()
    )
}

/// The message of an interrupted build.
fn interrupted(checkpoint: &str) -> String {
    format!(
        "interrupted: finished nodes are saved in {checkpoint}; build_table(..., resume=True) \
         continues the build"
    )
}

/// Build the table of the config `config_text` (named `config_name` in messages; read from
/// `config_path`, if any, which the output must not be) into `output` (else the config's
/// `output`), on `threads` worker threads (else `run.threads`; 0 = one per core), resuming or
/// restarting from an earlier run's checkpoint. `progress(kind, step, steps, stage, detail,
/// done, total, message)` hears the build (kind "stage", "count" or "note"). Returns the path
/// of the table.
#[pyfunction]
#[pyo3(signature = (config_text, config_name, config_path, output, resume, restart, threads, progress))]
#[allow(clippy::too_many_arguments)]
pub fn build_table(
    py: Python<'_>,
    config_text: &str,
    config_name: &str,
    config_path: Option<PathBuf>,
    output: Option<PathBuf>,
    resume: bool,
    restart: bool,
    threads: Option<usize>,
    progress: Option<Bound<'_, PyAny>>,
) -> PyResult<PathBuf> {
    if resume && restart {
        return Err(PyValueError::new_err(
            "resume=True and restart=True exclude each other: resume continues the checkpoint, \
             restart discards it",
        ));
    }
    let mut config = Config::parse(config_text, config_name)
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    if let Some(o) = output {
        config.output = o;
    }
    if let Some(t) = threads {
        config.run.threads = t;
    }
    let out = config.output.clone();
    let mut job = Job::new(config, config_text.to_string(), "oblique.build_table");
    job.inputs.extend(config_path);
    job.earlier = match (resume, restart) {
        (true, _) => Earlier::Resume,
        (_, true) => Earlier::Restart,
        _ => Earlier::Refuse,
    };
    let mut state = State {
        stages: job.stages(),
        step: 0,
        stage: String::new(),
        detail: String::new(),
        done: 0,
        total: None,
        counted: false,
    };
    let stop = Arc::new(AtomicBool::new(false));
    let (tx, rx) = mpsc::channel();
    let worker = {
        let stop = Arc::clone(&stop);
        let written_to = out.clone();
        std::thread::Builder::new()
            .name("oblique-build".into())
            .spawn(move || {
                let reporter = Reporter { tx };
                let result = job.run(&reporter, &stop).map(|outcome| {
                    if let Outcome::Table { built, wall_s } = outcome {
                        reporter.send(Msg::Note(written(&written_to, &built, wall_s)));
                    }
                });
                reporter.send(Msg::Done(result));
            })
            .map_err(|e| PyRuntimeError::new_err(format!("cannot start the build thread: {e}")))?
    };
    // The first exception of the callback or of a signal handler; the build is stopped then,
    // and the callback hears no more.
    let mut raised: Option<PyErr> = None;
    let mut result = None;
    let mut rx = rx;
    let mut finished = false;
    while !finished {
        let (r, msgs, done) = py.detach(move || wait(rx));
        rx = r;
        finished = done;
        for m in msgs {
            if let Msg::Done(r) = m {
                result = Some(r);
                continue;
            }
            let cb = if raised.is_none() {
                progress.as_ref()
            } else {
                None
            };
            if let Err(e) = state.take(m, cb) {
                raised = Some(e);
                stop.store(true, Ordering::SeqCst);
            }
        }
        if raised.is_none() {
            if let Err(e) = state.flush(progress.as_ref()) {
                raised = Some(e);
                stop.store(true, Ordering::SeqCst);
            }
        }
        // Signal handlers run here (Ctrl-C: KeyboardInterrupt). Once the build is being
        // stopped, a second Ctrl-C changes nothing: it stops at its next batch anyway.
        if let Err(e) = py.check_signals() {
            if raised.is_none() {
                raised = Some(e);
                stop.store(true, Ordering::SeqCst);
            }
        }
    }
    if py.detach(|| worker.join()).is_err() {
        return Err(PyRuntimeError::new_err(
            "the build thread panicked (a defect: please report it)",
        ));
    }
    let Some(result) = result else {
        return Err(PyRuntimeError::new_err(
            "the build thread ended without a result (a defect: please report it)",
        ));
    };
    match (raised, result) {
        // The user's Ctrl-C, with what became of the build.
        (Some(e), Err(stopped @ (JobError::Interrupted { .. } | JobError::InterruptedEarly)))
            if e.is_instance_of::<PyKeyboardInterrupt>(py) =>
        {
            Err(job_error(stopped))
        }
        (Some(e), _) => Err(e),
        (None, Ok(())) => Ok(out),
        (None, Err(e)) => Err(job_error(e)),
    }
}
