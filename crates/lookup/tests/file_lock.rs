//! A table opens while another process holds a lock on its file: an h5py session that has it
//! open, or a child process that inherited the descriptor of a writer (HDF5 locks files with
//! `flock`, and such a lock lives as long as any process keeps the descriptor). Reading takes
//! no lock, so `Table::open` must not fail with "unable to lock file". Fails (naming what is
//! missing) when `python3` is not available.

use std::io::{BufRead, BufReader, Write};
use std::path::PathBuf;
use std::process::{Command, Stdio};

use oblique_lookup::Table;

fn repo() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// Holds an exclusive `flock` on `path` (the lock HDF5 takes for writing) from the line
/// "locked" on its standard output until its standard input closes.
const HOLD_LOCK: &str = "import fcntl, sys\n\
                         f = open(sys.argv[1], 'rb')\n\
                         fcntl.flock(f, fcntl.LOCK_EX | fcntl.LOCK_NB)\n\
                         print('locked', flush=True)\n\
                         sys.stdin.read()\n";

#[test]
fn a_table_locked_by_another_process_still_opens() {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("file_lock-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch directory");
    for name in ["quick.h5", "dissipative-pair.h5"] {
        let path = dir.join(name);
        std::fs::copy(repo().join("tables").join(name), &path).expect("copy a shipped table");
        let mut child = Command::new("python3")
            .arg("-c")
            .arg(HOLD_LOCK)
            .arg(&path)
            .stdin(Stdio::piped())
            .stdout(Stdio::piped())
            .spawn()
            .expect("python3 is needed by this test (CI installs it)");
        let mut line = String::new();
        BufReader::new(child.stdout.take().expect("stdout"))
            .read_line(&mut line)
            .expect("read the child's output");
        assert_eq!(line.trim(), "locked", "the child could not lock {name}");
        let opened = Table::open(&path);
        let mut stdin = child.stdin.take().expect("stdin");
        stdin.write_all(b"done").expect("release the child");
        drop(stdin);
        assert!(child.wait().expect("wait").success());
        let t = opened.unwrap_or_else(|e| panic!("{name} locked elsewhere: {e}"));
        let shipped = Table::open(repo().join("tables").join(name)).expect(name);
        assert_eq!(
            format!("{:?}", t.surface()),
            format!("{:?}", shipped.surface())
        );
    }
    std::fs::remove_dir_all(&dir).expect("remove the scratch directory");
}

/// A table that this process has open through the `hdf5` crate (HDF5's default locking)
/// opens too: HDF5 refuses a second open of one file with another locking setting, so the
/// reader keeps the default unless a lock is in the way.
#[test]
fn a_table_open_in_this_process_through_hdf5_still_opens() {
    let path = repo().join("tables/quick.h5");
    let held = hdf5::File::open(&path).expect("open with the hdf5 crate");
    let group = held
        .group("patches")
        .expect("a group, which keeps the file open");
    drop(held);
    let t = Table::open(&path).unwrap_or_else(|e| panic!("quick.h5 open elsewhere: {e}"));
    assert!(t.p(1.5, 1.0).is_ok());
    drop(group);
}
