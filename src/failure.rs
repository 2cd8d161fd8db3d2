//! How a command fails: the error to print, and whether the user can fix it (exit status 2) or
//! not (exit status 1). Each library error type says which it is (`user_can_fix`); the
//! conversion into [`Failure`] asks it, so `main` only reads the answer.

use std::fmt::Display;
use std::process::ExitCode;

/// `println!` that returns an error instead of panicking when standard output cannot be
/// written (a full disk, `/dev/full`, a closed pipe with SIGPIPE ignored): the command then
/// fails with exit status 1 and a message on standard error.
macro_rules! outln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        writeln!(std::io::stdout().lock(), $($arg)*).map_err(|e| {
            $crate::failure::Failure::from(anyhow::Error::new(e).context("cannot write to standard output"))
        })
    }};
}
pub(crate) use outln;

/// Refuse, before any work, an output folder (`flag`, e.g. `-o`) that exists as something other
/// than a folder, or below such a thing (`notdir/sub`): a usage error (exit status 2), where
/// creating it would fail only after everything was computed.
pub fn check_output_folder(path: &std::path::Path, flag: &str) -> Result<()> {
    match not_a_folder(path) {
        Some(blocker) => Err(not_a_folder_error(path, &blocker, flag)),
        None => Ok(()),
    }
}

/// Create the output folder `path` (`flag`, e.g. `-o`) and its parents. Something in the way
/// that is not a folder is a usage error (exit status 2, like [`check_output_folder`]); another
/// failure (permissions, a full disk) is an I/O error (exit status 1).
pub fn create_output_folder(path: &std::path::Path, flag: &str) -> Result<()> {
    std::fs::create_dir_all(path).map_err(|e| match not_a_folder(path) {
        Some(blocker) => not_a_folder_error(path, &blocker, flag),
        None => Failure::from(
            anyhow::Error::new(e)
                .context(format!("cannot create output folder {}", path.display())),
        ),
    })
}

/// The first of `path` and its parents that exists and is not a folder (following symbolic
/// links, as creating the folder would).
fn not_a_folder(path: &std::path::Path) -> Option<std::path::PathBuf> {
    path.ancestors()
        .filter(|p| !p.as_os_str().is_empty())
        .find_map(|p| match std::fs::metadata(p) {
            Ok(m) if m.is_dir() => Some(None),
            Ok(_) => Some(Some(p.to_path_buf())),
            // Missing (or below something that is not a folder): look further up.
            Err(_) => None,
        })
        .flatten()
}

fn not_a_folder_error(path: &std::path::Path, blocker: &std::path::Path, flag: &str) -> Failure {
    if blocker == path {
        Failure::usage(format!(
            "{flag} {}: exists and is not a folder (give a folder, new or existing)",
            path.display()
        ))
    } else {
        Failure::usage(format!(
            "{flag} {}: {} exists and is not a folder (give a folder, new or existing)",
            path.display(),
            blocker.display()
        ))
    }
}

/// A failed command.
#[derive(Debug)]
pub struct Failure {
    /// The user can fix the cause (argument, config, input file, output path): exit status 2.
    usage: bool,
    /// The error and its causes.
    error: anyhow::Error,
}

/// The result of a command or of a step of one.
pub type Result<T, E = Failure> = std::result::Result<T, E>;

impl Failure {
    /// A mistake in what the user asked for, found by the command itself (exit status 2).
    pub fn usage(message: String) -> Self {
        Failure {
            usage: true,
            error: anyhow::Error::msg(message),
        }
    }

    /// The error, for printing.
    pub fn error(&self) -> &anyhow::Error {
        &self.error
    }

    /// 2 when the user can fix the cause, 1 otherwise.
    pub fn exit_code(&self) -> ExitCode {
        ExitCode::from(if self.usage { 2 } else { 1 })
    }
}

/// An error type that says whether the user can fix its cause.
pub trait UserFixable: std::error::Error + Send + Sync + 'static {
    /// True when a different argument, config or input file would avoid it.
    fn user_can_fix(&self) -> bool;
}

impl<E: UserFixable> From<E> for Failure {
    fn from(e: E) -> Self {
        Failure {
            usage: e.user_can_fix(),
            error: e.into(),
        }
    }
}

/// An error of the machine or the program (I/O, threads): exit status 1.
impl From<anyhow::Error> for Failure {
    fn from(error: anyhow::Error) -> Self {
        Failure {
            usage: false,
            error,
        }
    }
}

/// An I/O error (exit status 1; a path the user gave is checked before it is used).
impl From<std::io::Error> for Failure {
    fn from(e: std::io::Error) -> Self {
        anyhow::Error::from(e).into()
    }
}

/// Worker threads that could not start (exit status 1).
impl From<rayon::ThreadPoolBuildError> for Failure {
    fn from(e: rayon::ThreadPoolBuildError) -> Self {
        anyhow::Error::from(e).into()
    }
}

/// Context for an error that keeps whether the user can fix it.
pub trait Context<T> {
    /// The error, preceded by `context`.
    fn context<C: Display + Send + Sync + 'static>(self, context: C) -> Result<T>;
    /// The error, preceded by the context `f` computes.
    fn with_context<C: Display + Send + Sync + 'static>(self, f: impl FnOnce() -> C) -> Result<T>;
}

impl<T, E: Into<Failure>> Context<T> for std::result::Result<T, E> {
    fn context<C: Display + Send + Sync + 'static>(self, context: C) -> Result<T> {
        self.with_context(|| context)
    }

    fn with_context<C: Display + Send + Sync + 'static>(self, f: impl FnOnce() -> C) -> Result<T> {
        self.map_err(|e| {
            let Failure { usage, error } = e.into();
            Failure {
                usage,
                error: error.context(f()),
            }
        })
    }
}

impl<T> Context<T> for Option<T> {
    fn context<C: Display + Send + Sync + 'static>(self, context: C) -> Result<T> {
        self.ok_or_else(|| anyhow::Error::msg(context.to_string()).into())
    }

    fn with_context<C: Display + Send + Sync + 'static>(self, f: impl FnOnce() -> C) -> Result<T> {
        self.ok_or_else(|| anyhow::Error::msg(f().to_string()).into())
    }
}

/// The library errors a command can meet, each classified by its own crate.
macro_rules! user_fixable {
    ($($t:ty),* $(,)?) => {
        $(impl UserFixable for $t {
            fn user_can_fix(&self) -> bool {
                <$t>::user_can_fix(self)
            }
        })*
    };
}

user_fixable!(
    oblique_solver::PhysicsError,
    oblique_table::TableError,
    oblique_table::write::StorageError,
    oblique_output::OutputError,
    oblique_output::OutputPathError,
    oblique_sweep::SweepError,
    oblique_sweep::RunError,
    oblique_sweep::job::JobError,
    oblique_sweep::config::ConfigError,
    oblique_sweep::nodestore::NodeFileError,
    oblique_sweep::nodestore::LockError,
    oblique_plot::PlotError,
    oblique_study::figures::FigureError,
    oblique_study::scene::SceneError,
    oblique_study::reference::ReferenceError,
);

/// The error and its causes on one line, each cause once: a library error whose message
/// already quotes its source (`cannot read config X: No such file …`) is not followed by that
/// source again.
pub fn error_text(e: &anyhow::Error) -> String {
    let mut text = String::new();
    for cause in e.chain() {
        let part = cause.to_string();
        if text.is_empty() {
            text = part;
        } else if !text.contains(&part) {
            text.push_str(": ");
            text.push_str(&part);
        }
    }
    text
}
