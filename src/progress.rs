//! Progress display of the CLI: an indicatif bar on a terminal, plain periodic lines otherwise,
//! nothing with `--quiet`.

use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressStyle};
use oblique::sweep::Progress;

/// Progress sink chosen from the terminal and `--quiet`.
pub struct CliProgress {
    bar: Option<ProgressBar>,
    plain: Option<Mutex<Plain>>,
}

struct Plain {
    done: u64,
    total: u64,
    start: Instant,
    last: Instant,
    phase: String,
}

impl CliProgress {
    /// A bar on a terminal, plain lines every 5 s otherwise, nothing when `quiet`.
    pub fn new(quiet: bool) -> Self {
        if quiet {
            return Self {
                bar: None,
                plain: None,
            };
        }
        if std::io::stderr().is_terminal() {
            let bar = ProgressBar::new(0);
            let style = ProgressStyle::with_template(
                "{msg:32} [{bar:30}] {pos}/{len} impacts  {per_sec}  ETA {eta}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> ");
            bar.set_style(style);
            bar.enable_steady_tick(Duration::from_millis(200));
            Self {
                bar: Some(bar),
                plain: None,
            }
        } else {
            let now = Instant::now();
            Self {
                bar: None,
                plain: Some(Mutex::new(Plain {
                    done: 0,
                    total: 0,
                    start: now,
                    last: now,
                    phase: String::new(),
                })),
            }
        }
    }

    /// Remove the bar.
    pub fn finish(&self) {
        if let Some(b) = &self.bar {
            b.finish_and_clear();
        }
    }
}

impl Plain {
    fn line(&self) {
        let el = self.start.elapsed().as_secs_f64();
        let rate = self.done as f64 / el.max(1e-9);
        let eta = (self.total.saturating_sub(self.done)) as f64 / rate.max(1e-9);
        eprintln!(
            "[sweep] {}: {}/{} impacts, {:.0}/s, elapsed {:.0} s, ETA {:.0} s (this phase)",
            self.phase, self.done, self.total, rate, el, eta
        );
    }
}

impl Progress for CliProgress {
    fn add(&self, n: u64) {
        if let Some(b) = &self.bar {
            b.inc_length(n);
        }
        if let Some(p) = &self.plain {
            if let Ok(mut p) = p.lock() {
                p.total += n;
            }
        }
    }

    fn inc(&self, n: u64) {
        if let Some(b) = &self.bar {
            b.inc(n);
        }
        if let Some(p) = &self.plain {
            if let Ok(mut p) = p.lock() {
                p.done += n;
                if p.last.elapsed() >= Duration::from_secs(5) {
                    p.last = Instant::now();
                    p.line();
                }
            }
        }
    }

    fn phase(&self, msg: &str) {
        if let Some(b) = &self.bar {
            b.set_message(msg.to_string());
        }
        if let Some(p) = &self.plain {
            if let Ok(mut p) = p.lock() {
                p.phase = msg.to_string();
                eprintln!("[sweep] {msg}");
            }
        }
    }
}
