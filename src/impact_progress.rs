//! Progress of `sweep impact`'s automatic refinement on stderr: the level being run, its
//! resolution and the last error estimate against the tolerance. Never on stdout, so `--json`
//! output stays one object.
//!
//! On a terminal one line is redrawn in place once the solve has taken [`TERMINAL_DELAY`] and is
//! erased at the end; with `--progress` every event is a plain line from the start; otherwise
//! nothing is shown.

use std::io::{IsTerminal, Write};
use std::time::{Duration, Instant};

use oblique_solver::RefineEvent;

/// Time after which a terminal shows the progress line (fast solves print nothing extra).
const TERMINAL_DELAY: Duration = Duration::from_secs(1);

enum Mode {
    Off,
    Terminal { drawn: bool },
    Lines,
}

/// Progress sink of one `sweep impact`.
pub struct ImpactProgress {
    mode: Mode,
    start: Instant,
    /// Last estimate reached and the tolerance asked for.
    last: Option<(f64, f64)>,
}

impl ImpactProgress {
    /// Plain lines when `always`, a redrawn line on a terminal, else nothing.
    pub fn new(always: bool) -> Self {
        let mode = if always {
            Mode::Lines
        } else if std::io::stderr().is_terminal() {
            Mode::Terminal { drawn: false }
        } else {
            Mode::Off
        };
        Self {
            mode,
            start: Instant::now(),
            last: None,
        }
    }

    fn estimate_text(&self) -> String {
        match self.last {
            Some((est, tol)) => format!("last estimate {est:.1e} (tol {tol:.1e})"),
            None => "no estimate yet (needs three levels)".to_string(),
        }
    }

    /// Show one refinement event.
    pub fn report(&mut self, event: RefineEvent) {
        if let RefineEvent::Finished {
            estimate: Some(est),
            tol,
            ..
        } = event
        {
            self.last = Some((est, tol));
        }
        let elapsed = self.start.elapsed();
        let line = match event {
            RefineEvent::Started { level, resolution } => format!(
                "impact: level {level} running, {resolution}; {}; {:.1} s",
                self.estimate_text(),
                elapsed.as_secs_f64()
            ),
            RefineEvent::Finished {
                level, resolution, ..
            } => format!(
                "impact: level {level} done, {resolution}; {}; {:.1} s",
                self.estimate_text(),
                elapsed.as_secs_f64()
            ),
        };
        let mut err = std::io::stderr().lock();
        // A progress line that cannot be written is not worth failing the solve for.
        match &mut self.mode {
            Mode::Off => {}
            Mode::Lines => {
                let _ = writeln!(err, "{line}");
            }
            Mode::Terminal { drawn } => {
                if elapsed >= TERMINAL_DELAY {
                    let _ = write!(err, "\r\x1b[K{line}");
                    let _ = err.flush();
                    *drawn = true;
                }
            }
        }
    }

    /// Erase the terminal line, if one was drawn.
    pub fn finish(&mut self) {
        if let Mode::Terminal { drawn: true } = self.mode {
            let mut err = std::io::stderr().lock();
            let _ = write!(err, "\r\x1b[K");
            let _ = err.flush();
        }
    }
}
