//! How finely a run resolved the approach to gross slip, for the refinement's acceptance.
//!
//! A *zone* is a stretch of steps in one state of the row: which Coulomb limits part of the
//! contact is at (`+`, `−`, both or none) and whether part of it is stuck (none: gross slip).
//! Where a zone with a stuck part gives way to gross slip, the stuck part shrinks to nothing:
//! the gap of the mean displacement to its gross-slip value closes like `(t_G − t)^{3/2}`
//! (γ = 2, α = 1.45, elastic: the gap over the last four steps at 4096 steps is
//! 1.64–1.70e-4 × their distance to the onset in steps to the power 3/2), and the friction force
//! bends sharply over that zone (`dF/dt` from +0.95 to −2.6 within 0.007 `t_c` there). Until the
//! zone spans several steps its error does not fall like `1/N²`, and the levels' differences
//! can look second order while the value is still far off: there the error times `N²` is
//! −0.27, +0.23, +0.72, +0.70, +0.96, +0.99 from 256 to 8192 steps, almost all of the change
//! gained over that zone, and the refinement at tol 1e-6 accepted 512 steps (the zone 4.1 steps
//! long) with an estimate of 5.1e-7 where the error was 2.6e-6. So a level is accepted only
//! when every zone that ends in gross slip and lasts at least [`ZONE_MIN`] `t_c` spans at least
//! [`ZONE_STEPS`] grid steps ([`Level::resolved`]); shorter ones (a zone being born, next to a
//! fold) are left to the estimate, which bounds the extra levels this rule can ask for at
//! `ZONE_STEPS / ZONE_MIN` = 2000 steps. Over 609 points of γ 1.95–2.15, α 1.2–2.6 this took
//! the levels accepted above their tolerance from 3 to 1 at tol 1e-6 and from 4 to 2 at 2e-6,
//! for 0.4–2.3 % more steps over random points (`docs/solver.md`, "Error estimates"). Shorter
//! zones cost more than they bring: counting those from 0.002 `t_c` took the 2e-6 grid to 1
//! above its tolerance but cost 33 % more steps over random points in partial slip (γ 1–3.5),
//! where no error was above its tolerance either way, and `configs/full.toml` took 41 % longer
//! to build; counting every zone, not only those that end in gross slip, 13–21 % over random
//! points.

/// Fewest grid steps (the zone's length over `t_c/N`) that a zone ending in gross slip must
/// span for its level to be accepted. Steps split at events inside the zone, or graded near
/// the separation, do not count more: they are not what resolves the zone.
pub const ZONE_STEPS: f64 = 8.0;

/// Zones shorter than this fraction of the contact time are not counted by [`ZONE_STEPS`].
pub const ZONE_MIN: f64 = 0.004;

/// Share of the contact time below which a counted zone that ends in gross slip
/// ([`Level::shortest_zone`]) is brief: the run is next to a fold where such a zone is born,
/// and its error estimate is at least [`BRIEF_ZONE_SCATTER`]`/N²` ([`Level::brief_zone_floor`]).
pub const BRIEF_ZONE: f64 = 0.05;

/// The error estimate's floor `BRIEF_ZONE_SCATTER/N²` at `N` steps where a zone that ends in
/// gross slip is brief ([`BRIEF_ZONE`]).
///
/// Next to the fold where a gross-slip episode of the restitution phase is born (the elastic
/// stick patch at γ ≈ 1.95–2.15, α ≈ 1.2–2.6), `P` at `N` steps scatters around its smooth
/// convergence by up to about `1.2/N²` (γ = 2.11, α = 1.40: `stepscan` 0.15/N² rms over 64
/// consecutive `N`, errors of the accepted answers up to 1.18/N²), with differences between
/// levels that look converged: on the grid of 609 points there (`docs/solver.md`, "Error
/// estimates") 65 answers at tol 1e-6 stated estimates below their errors (up to 6.3×, most
/// of them the row's `0.1/N²`), 77 at 2e-6 and 51 at 1e-7. Where the zone before gross slip
/// lasts under 0.05 `t_c` (counted from [`ZONE_MIN`]) this floor leaves 11 (worst 3.2×), 17
/// and 4, all at α 1.2–1.35 where no zone is counted at the finer levels (the episode is
/// shorter than `ZONE_MIN` or gone), for 0.1–0.6 % more steps on that grid and 0.5–2.7 % over
/// 800 random points (`levelneed` at 2e-6, 1e-6 and 1e-7).
pub const BRIEF_ZONE_SCATTER: f64 = 1.5;

/// The bit of a zone's state that says part of the contact is stuck.
const STUCK: u8 = 4;

/// `P` of one run at a fixed resolution and how finely it resolved the approach to gross slip.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Level {
    /// Tangential restitution `P` of the run.
    pub p: f64,
    /// Length of the shortest zone that ended in gross slip and lasted at least [`ZONE_MIN`]
    /// `t_c`, in grid steps `t_c/N` (`∞` where the run did not watch its zones, or had none).
    pub shortest_zone: f64,
}

impl Level {
    /// A run whose zones were not watched: only its value counts.
    pub fn unwatched(p: f64) -> Self {
        Self {
            p,
            shortest_zone: f64::INFINITY,
        }
    }

    /// Whether every zone counted ([`Level::shortest_zone`]) spans [`ZONE_STEPS`] grid steps or
    /// more.
    pub fn resolved(&self) -> bool {
        self.shortest_zone >= ZONE_STEPS
    }

    /// The floor of the error estimate of this level at `steps` steps:
    /// [`BRIEF_ZONE_SCATTER`]`/N²` where its shortest counted zone lasts under [`BRIEF_ZONE`]
    /// of the contact time (`shortest_zone < BRIEF_ZONE · N` grid steps), else 0.
    pub fn brief_zone_floor(&self, steps: usize) -> f64 {
        let n = steps as f64;
        if self.shortest_zone < BRIEF_ZONE * n {
            BRIEF_ZONE_SCATTER / (n * n)
        } else {
            0.0
        }
    }
}

/// The zones of one run so far: the state and length of the current zone, and the length of
/// the shortest zone that ended in gross slip and lasted at least [`ZONE_MIN`] `t_c`.
#[derive(Debug, Clone)]
pub(crate) struct ZoneClock {
    contact_time: f64,
    steps: usize,
    state: Option<u8>,
    length: f64,
    shortest: f64,
    /// Every finished zone as `(state, length)` (s or dimensionless), where the clock keeps
    /// them ([`ZoneClock::logging`]; a diagnostic, [`ZoneLog`]).
    log: Option<Vec<(u8, f64)>>,
}

impl ZoneClock {
    /// A clock for a contact of duration `contact_time` (s, or dimensionless) on a grid of
    /// `steps` steps.
    pub(crate) fn new(contact_time: f64, steps: usize) -> Self {
        Self {
            contact_time,
            steps,
            state: None,
            length: 0.0,
            shortest: f64::INFINITY,
            log: None,
        }
    }

    /// [`ZoneClock::new`] that also keeps every zone ([`ZoneClock::log`]).
    pub(crate) fn logging(contact_time: f64, steps: usize) -> Self {
        Self {
            log: Some(Vec::new()),
            ..Self::new(contact_time, steps)
        }
    }

    /// Count one step of length `h` that left the row in `state`.
    #[inline]
    pub(crate) fn record(&mut self, state: u8, h: f64) {
        if self.state != Some(state) {
            self.enter(state);
        }
        self.length += h;
    }

    /// The zone in `state` begins: the one before ends (rare against the steps, so out of the
    /// steps' line of code).
    #[cold]
    #[inline(never)]
    fn enter(&mut self, state: u8) {
        // A zone with a stuck part ends in gross slip.
        let onset = state & STUCK == 0 && self.state.is_some_and(|s| s & STUCK != 0);
        if onset && self.length >= ZONE_MIN * self.contact_time {
            self.shortest = self.shortest.min(self.length);
        }
        if let (Some(log), Some(s)) = (self.log.as_mut(), self.state) {
            log.push((s, self.length));
        }
        self.state = Some(state);
        self.length = 0.0;
    }

    /// The shortest zone counted, in grid steps ([`Level::shortest_zone`]).
    pub(crate) fn shortest(self) -> f64 {
        self.shortest * self.steps as f64 / self.contact_time
    }

    /// Every zone of the run, the last one included (empty where the clock did not keep them,
    /// [`ZoneClock::logging`]).
    pub(crate) fn log(self) -> ZoneLog {
        let scale = self.steps as f64 / self.contact_time;
        let mut zones: Vec<Zone> = self
            .log
            .unwrap_or_default()
            .into_iter()
            .map(|(state, length)| Zone {
                state,
                steps: length * scale,
            })
            .collect();
        if let Some(state) = self.state {
            zones.push(Zone {
                state,
                steps: self.length * scale,
            });
        }
        ZoneLog {
            zones,
            steps: self.steps,
        }
    }
}

/// One zone of a run ([`ZoneLog`]): its state (`+` limit bit 1, `−` limit bit 2, stuck bit 4)
/// and its length in grid steps `t_c/N`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Zone {
    /// The state of the row over the zone ([`state`]).
    pub state: u8,
    /// The zone's length in grid steps.
    pub steps: f64,
}

/// Every zone of one run, of any kind, in order from touch to separation: a diagnostic of how
/// finely a level resolves its slip history (the refinement counts only the zones that end in
/// gross slip, [`Level::shortest_zone`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ZoneLog {
    /// The zones in order.
    pub zones: Vec<Zone>,
    /// The grid steps of the run.
    pub steps: usize,
}

impl ZoneLog {
    /// The shortest zone in grid steps (`∞` with no zone); with `interior`, leaving out the
    /// first zone (cut by the touch) and the last (cut by the separation), `∞` where there
    /// are fewer than three zones.
    pub fn shortest(&self, interior: bool) -> f64 {
        let zones = if interior {
            self.zones
                .get(1..self.zones.len().saturating_sub(1))
                .unwrap_or(&[])
        } else {
            &self.zones[..]
        };
        zones.iter().map(|z| z.steps).fold(f64::INFINITY, f64::min)
    }
}

/// The state of the zone a row is in after a step: whether part of the contact is at the `+`
/// and at the `−` limit (`TangentialModel::at_limit`), and whether part of it is stuck
/// (`TangentialModel::stuck`).
#[inline(always)]
pub(crate) fn state((plus, minus): (bool, bool), stuck: bool) -> u8 {
    u8::from(plus) | u8::from(minus) << 1 | if stuck { STUCK } else { 0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_zones_that_end_in_gross_slip_count() {
        // 200 grid steps of 0.005 t_c; states: 4 stuck, 5 stuck and at +, 1 gross slip at +.
        let mut clock = ZoneClock::new(1.0, 200);
        for _ in 0..100 {
            clock.record(4, 0.005);
        }
        // Two steps of 0.001 (0.002 t_c, not shorter than ZONE_MIN), back to stuck: no onset.
        clock.record(5, 0.001);
        clock.record(5, 0.001);
        for _ in 0..10 {
            clock.record(4, 0.005);
        }
        assert_eq!(clock.clone().shortest(), f64::INFINITY);
        // A zone of 0.015 t_c in 5 steps, one of them split, then gross slip: 3 grid steps.
        for h in [0.005, 0.004, 0.001, 0.0025, 0.0025] {
            clock.record(5, h);
        }
        for _ in 0..50 {
            clock.record(1, 0.005);
        }
        assert!((clock.clone().shortest() - 3.0).abs() < 1e-9);
        // A shorter zone than ZONE_MIN before gross slip does not count.
        clock.record(5, 0.001);
        clock.record(1, 0.005);
        assert!((clock.shortest() - 3.0).abs() < 1e-9);
        let level = Level {
            p: 0.5,
            shortest_zone: 3.0,
        };
        assert!(!level.resolved());
        assert!(Level::unwatched(0.5).resolved());
    }

    /// A logging clock keeps every zone, of any kind, the last one included, in grid steps.
    #[test]
    fn a_logging_clock_keeps_every_zone() {
        let mut clock = ZoneClock::logging(1.0, 100);
        for (state, steps) in [(4, 30), (5, 2), (4, 40), (1, 28)] {
            for _ in 0..steps {
                clock.record(state, 0.01);
            }
        }
        let log = clock.log();
        let got: Vec<(u8, f64)> = log.zones.iter().map(|z| (z.state, z.steps)).collect();
        let want = [(4, 30.0), (5, 2.0), (4, 40.0), (1, 28.0)];
        assert_eq!(got.len(), want.len());
        for ((s, l), (ws, wl)) in got.iter().zip(want) {
            assert!(*s == ws && (l - wl).abs() < 1e-9, "{got:?}");
        }
        assert!((log.shortest(false) - 2.0).abs() < 1e-9);
        assert!((log.shortest(true) - 2.0).abs() < 1e-9);
        assert_eq!(ZoneClock::new(1.0, 100).log().zones, Vec::new());
    }

    /// The brief-zone floor is 1.5/N² exactly where the shortest counted zone lasts under 0.05
    /// of the contact time (`shortest_zone < 0.05 N`), and none without such a zone.
    #[test]
    fn a_brief_zone_before_gross_slip_floors_the_estimate() {
        let at = |zone: f64| Level {
            p: 0.5,
            shortest_zone: zone,
        };
        assert_eq!(Level::unwatched(0.5).brief_zone_floor(2048), 0.0);
        assert_eq!(at(0.05 * 2048.0).brief_zone_floor(2048), 0.0);
        let f = at(0.049 * 2048.0).brief_zone_floor(2048);
        assert!((f - 1.5 / 2048f64.powi(2)).abs() < 1e-20, "{f:e}");
        assert!(at(9.4).brief_zone_floor(2048) > 0.0 && at(9.4).brief_zone_floor(128) == 0.0);
    }
}
