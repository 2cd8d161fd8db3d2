//! Progress display of `sweep run`: an indicatif bar on a terminal, plain lines otherwise,
//! nothing with `--quiet`.
//!
//! A run is a known list of steps (`oblique_sweep::job::Job::stages`: pre-flight, the stages
//! of the build, writing), shown as "step K/N NAME", with the job's notes between them. Counts and an ETA are shown only where the total is known: within
//! one refinement round (its new nodes are placed before it starts) and for the held-out
//! checks. How many rounds a patch needs is not known in advance, so no ETA is claimed for the
//! whole run.

use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};
use oblique_sweep::job::Note;
use oblique_sweep::{Progress, STAGE_CHECKS};

/// Seconds between two plain progress lines within a phase.
const PLAIN_EVERY: Duration = Duration::from_secs(5);

/// Progress sink chosen from the terminal and `--quiet`.
pub struct CliProgress {
    bar: Option<ProgressBar>,
    state: Option<Mutex<State>>,
}

struct State {
    steps: Vec<String>,
    /// Index of the current step in `steps`.
    step: usize,
    detail: String,
    /// Impacts of the current phase, once known.
    total: Option<u64>,
    done: u64,
    phase_start: Instant,
    run_start: Instant,
    last_line: Instant,
}

impl State {
    fn label(&self) -> String {
        format!(
            "step {}/{} {}",
            self.step + 1,
            self.steps.len(),
            self.steps.get(self.step).map_or("", String::as_str)
        )
    }

    /// What the ETA of the current phase covers.
    fn eta_scope(&self) -> &'static str {
        if self.steps.get(self.step).is_some_and(|s| s == STAGE_CHECKS) {
            "of the checks"
        } else {
            "of this round"
        }
    }

    /// A plain line with the counts of the phase (only when its total is known and not zero).
    fn counts_line(&self) -> String {
        let el = self.phase_start.elapsed().as_secs_f64();
        let run = self.run_start.elapsed().as_secs_f64();
        match self.total {
            Some(total) if total > 0 => {
                let rate = self.done as f64 / el.max(1e-9);
                let left = total.saturating_sub(self.done) as f64;
                let eta = if self.done > 0 {
                    format!("{:.0} s", left / rate.max(1e-9))
                } else {
                    "unknown yet".into()
                };
                format!(
                    "[sweep] {}: {}/{total} impacts, {rate:.0}/s, ETA {} {eta} (run elapsed {run:.0} s)",
                    self.label(),
                    self.done,
                    self.eta_scope()
                )
            }
            _ => format!("[sweep] {} (run elapsed {run:.0} s)", self.label()),
        }
    }
}

fn spinner_style() -> ProgressStyle {
    ProgressStyle::with_template("{spinner} [{prefix}] {msg}  {elapsed}")
        .unwrap_or_else(|_| ProgressStyle::default_spinner())
}

fn bar_style(eta_scope: &str) -> ProgressStyle {
    ProgressStyle::with_template(&format!(
        "[{{prefix}}] {{msg}} [{{bar:30}}] {{pos}}/{{len}} impacts  ETA {eta_scope} {{eta}}"
    ))
    .unwrap_or_else(|_| ProgressStyle::default_bar())
    .progress_chars("=> ")
}

impl CliProgress {
    /// A bar on a terminal, plain lines otherwise, nothing when `quiet`. `steps` is the whole
    /// run in order (see the module doc).
    pub fn new(quiet: bool, steps: Vec<String>) -> Self {
        if quiet {
            return Self {
                bar: None,
                state: None,
            };
        }
        let now = Instant::now();
        let state = State {
            steps,
            step: 0,
            detail: String::new(),
            total: None,
            done: 0,
            phase_start: now,
            run_start: now,
            last_line: now,
        };
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = ProgressBar::new_spinner();
            bar.set_style(spinner_style());
            bar.enable_steady_tick(Duration::from_millis(200));
            bar
        });
        Self {
            bar,
            state: Some(Mutex::new(state)),
        }
    }

    /// Print a line of information (on a terminal: above the bar, which stays below it). Also
    /// printed with `--quiet`'s sink, which callers skip themselves.
    pub fn println(&self, msg: &str) {
        match &self.bar {
            Some(b) => b.println(msg),
            None => eprintln!("{msg}"),
        }
    }

    /// Remove the bar.
    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

impl Progress for CliProgress {
    fn phase(&self, stage: &str, detail: &str) {
        let Some(state) = &self.state else { return };
        let Ok(mut s) = state.lock() else { return };
        // A stage that recurs (one per patch) is the next of that name from the current one.
        let from = s.step;
        let next = s.steps.iter().skip(from).position(|x| x == stage);
        if let Some(i) = next
            .map(|i| from + i)
            .or_else(|| s.steps.iter().position(|x| x == stage))
        {
            s.step = i;
        }
        s.detail = detail.to_string();
        s.total = None;
        s.done = 0;
        s.phase_start = Instant::now();
        s.last_line = s.phase_start;
        let label = s.label();
        match &self.bar {
            Some(b) => {
                b.set_style(spinner_style());
                b.reset();
                b.set_prefix(label);
                b.set_message(detail.to_string());
            }
            None if detail.is_empty() => eprintln!("[sweep] {label}"),
            None => eprintln!("[sweep] {label}: {detail}"),
        }
    }

    fn total(&self, n: u64) {
        let Some(state) = &self.state else { return };
        let Ok(mut s) = state.lock() else { return };
        s.total = Some(n);
        s.done = 0;
        if let Some(b) = &self.bar {
            if n > 0 {
                b.set_style(bar_style(s.eta_scope()));
                b.set_length(n);
                b.set_position(0);
                b.reset_eta();
            } else {
                b.set_message(format!("{} (all from the checkpoint)", s.detail));
            }
        }
    }

    fn note(&self, note: &Note<'_>) {
        if self.state.is_some() {
            self.println(&note.to_string());
        }
    }

    fn inc(&self, n: u64) {
        let Some(state) = &self.state else { return };
        let Ok(mut s) = state.lock() else { return };
        s.done += n;
        match &self.bar {
            Some(b) => b.inc(n),
            None => {
                if s.last_line.elapsed() >= PLAIN_EVERY {
                    s.last_line = Instant::now();
                    eprintln!("{}", s.counts_line());
                }
            }
        }
    }
}
