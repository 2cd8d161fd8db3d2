//! The MDR row of tangential springs under Thornton's law, in the continuum limit: exact in
//! space, with Coulomb limits that are not linear in the profile height.
//!
//! The spring at profile height `y = x²/R*` is bounded by `±c Λ(y, t)`, `c = μ E*/G*`:
//! - loading: `Λ = Q(d − y)`, the truncated line density of [`super::line::Truncated`]
//!   (`d − y` up to `d_y`: the elastic row's limit);
//! - unloading: `Λ = (D − y)/ρ` with the reach `D = ρ (d − d_p)` ([`super::normal::Unloading`]);
//! - at the switch between them the limits jump (centre up, edge down) with the total force
//!   unchanged: every spring keeps its displacement and is clipped against the new limits.
//!
//! The time rule is the elastic row's ([`crate::continuum`]): every spring in contact receives
//! the increment `Δw` of the step; a spring entering contact during the step receives
//! `w(h) − w(θh)`; the field is clipped against the limits at the end of the step; a spring at
//! a limit that sticks again inside the step receives the part of the limit's change it missed,
//! `∫₀^τ (L̇ − ẇ) dt` with the rate gap `g = L̇ ∓ ẇ` linear over the step. Where the limit is not
//! linear in `y`, `L̇ = c Q′(d − y) ḋ` differs from spring to spring, so the springs of one run at
//! a limit stick again one after the other: the run is cut where `g` changes sign at the
//! start or the end of the step (closed form: `Q′(s) = (2/π) arcsin √(d_y/s)`), each part
//! sticks again or slips on as a whole, and the part that sticks inside the step receives the
//! correction as a quadratic in `y` through three of its points (exact where `Q′` is uniform;
//! the part is `O(h)` wide where it is not, so the interpolation error is `O(h⁴)`).
//!
//! So a stuck piece holds `ũ − W = a + b z + q z² + k Q(D_f − y)`, `z = y − y_ref`: the
//! quadratic of the elastic row plus, for a part that stuck again at a curved limit, the limit
//! it left (`k = ±c`, `D_f` the indentation then). Its integral is exact (Gauss for the
//! quadratic, [`super::line::Truncated::integral`] for the rest); where a curved limit or a
//! curved piece meets a limit, the crossing is found by bracketing on a few samples between
//! the kinks of `Q` and bisection to the rounding.

use super::line::Truncated;
use crate::continuum::{roots_inside, GAUSS};
use crate::springs::{StepMotion, StepResult};

/// Which law a piece follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// Stuck: `ũ = W + a + b z + q z² + k Q(D_f − y)`.
    Stuck,
    /// At the `+` limit `ũ = c Λ(y)`.
    Plus,
    /// At the `−` limit `ũ = −c Λ(y)`.
    Minus,
}

/// One piece of the field on `y0 ≤ y ≤ y1`.
#[derive(Debug, Clone, Copy)]
struct Piece {
    kind: Kind,
    y0: f64,
    y1: f64,
    x0: f64,
    x1: f64,
    y_ref: f64,
    a: f64,
    b: f64,
    q: f64,
    /// Factor of the curved part `k Q(D_f − y)` (0: none).
    k: f64,
    /// `D_f` of the curved part (m).
    top: f64,
    /// `∫ (ũ − W) dx` over a stuck piece (m²).
    rel: f64,
    /// Bounds of `ũ − W` over a stuck piece: `lo ≤ ũ − W ≤ hi`.
    lo: f64,
    hi: f64,
    /// `upper ≥ max (ũ − W + s y)` and `lower ≤ min (ũ − W − s y)` over a stuck piece for the
    /// limit slope `s = slope` (NaN until computed): it is inside the linear limits
    /// `±s (D − y)` while `upper ≤ s D − W` and `lower ≥ −s D − W`.
    upper: f64,
    lower: f64,
    slope: f64,
}

impl Piece {
    /// A stuck piece; a curved part that is linear over the piece (`D_f − y0 ≤ d_y`) is folded
    /// into the quadratic.
    #[allow(clippy::too_many_arguments)]
    fn stuck(
        y0: f64,
        y1: f64,
        y_ref: f64,
        (a, b, q): (f64, f64, f64),
        k: f64,
        top: f64,
        line: &Truncated,
        radius: f64,
    ) -> Self {
        let (mut a, mut b, mut k) = (a, b, k);
        if k != 0.0 && top - y0 <= line.yield_indentation {
            a += k * (top - y_ref);
            b -= k;
            k = 0.0;
        }
        Piece {
            kind: Kind::Stuck,
            y0,
            y1,
            x0: (radius * y0).sqrt(),
            x1: (radius * y1).sqrt(),
            y_ref,
            a,
            b,
            q,
            k,
            top,
            rel: 0.0,
            lo: 0.0,
            hi: 0.0,
            upper: 0.0,
            lower: 0.0,
            slope: f64::NAN,
        }
        .refreshed(line, radius)
    }

    fn limit(kind: Kind, y0: f64, y1: f64, radius: f64) -> Self {
        Piece {
            kind,
            y0,
            y1,
            x0: (radius * y0).sqrt(),
            x1: (radius * y1).sqrt(),
            y_ref: y0,
            a: 0.0,
            b: 0.0,
            q: 0.0,
            k: 0.0,
            top: 0.0,
            rel: 0.0,
            lo: 0.0,
            hi: 0.0,
            upper: 0.0,
            lower: 0.0,
            slope: f64::NAN,
        }
    }

    /// The same piece on `[y0, y1]` (a stuck one with its sums recomputed).
    fn part(&self, y0: f64, y1: f64, line: &Truncated, radius: f64) -> Self {
        let p = Piece {
            y0,
            y1,
            x0: (radius * y0).sqrt(),
            x1: (radius * y1).sqrt(),
            slope: f64::NAN,
            ..*self
        };
        if p.kind == Kind::Stuck {
            p.refreshed(line, radius)
        } else {
            p
        }
    }

    /// A stuck piece with its integral and range computed.
    fn refreshed(mut self, line: &Truncated, radius: f64) -> Self {
        self.rel = self.integral(line, radius);
        (self.lo, self.hi) = self.range(line);
        self.slope = f64::NAN;
        self
    }

    /// A stuck piece with its bounds for the limit slope `s` ([`Piece::upper`]).
    fn bounded(mut self, s: f64, line: &Truncated) -> Self {
        // The curved part k Q(D_f − y) between two lines: its chord and its tangent at the
        // middle (Q(D_f − y) is concave in y; k < 0 swaps them).
        let (cu, cl) = if self.k == 0.0 {
            ((0.0, 0.0), (0.0, 0.0))
        } else {
            let (y0, y1) = (self.y0, self.y1);
            let ym = 0.5 * (y0 + y1);
            let (v0, v1) = (
                self.k * line.value(self.top - y0),
                self.k * line.value(self.top - y1),
            );
            let chord_slope = if y1 > y0 { (v1 - v0) / (y1 - y0) } else { 0.0 };
            let chord = (v0 - chord_slope * (y0 - self.y_ref), chord_slope);
            let t_slope = -self.k * line.slope(self.top - ym);
            let tangent = (
                self.k * line.value(self.top - ym) - t_slope * (ym - self.y_ref),
                t_slope,
            );
            if self.k > 0.0 {
                (tangent, chord)
            } else {
                (chord, tangent)
            }
        };
        // max of (a + cu.0) + (b + cu.1 + s) z + q z², min of (a + cl.0) + (b + cl.1 − s) z + q z².
        let ext = |a: f64, b: f64, max: bool| {
            let (z0, z1) = (self.y0 - self.y_ref, self.y1 - self.y_ref);
            let f = |z: f64| a + z * (b + self.q * z);
            let pick = |u: f64, v: f64| if max { u.max(v) } else { u.min(v) };
            let mut best = pick(f(z0), f(z1));
            if self.q != 0.0 {
                let z = -b / (2.0 * self.q);
                if z > z0 && z < z1 {
                    best = pick(best, f(z));
                }
            }
            best
        };
        let y_ref_term = s * self.y_ref;
        self.upper = ext(self.a + cu.0 + y_ref_term, self.b + cu.1 + s, true);
        self.lower = ext(self.a + cl.0 - y_ref_term, self.b + cl.1 - s, false);
        self.slope = s;
        self
    }

    /// `ũ − W` of a stuck piece at `y`.
    fn value(&self, y: f64, line: &Truncated) -> f64 {
        let z = y - self.y_ref;
        let quad = self.a + z * (self.b + self.q * z);
        if self.k == 0.0 {
            quad
        } else {
            quad + self.k * line.value(self.top - y)
        }
    }

    /// `∫ (ũ − W) dx` over a stuck piece (m²).
    fn integral(&self, line: &Truncated, radius: f64) -> f64 {
        let dx = self.x1 - self.x0;
        let quad: f64 = GAUSS
            .iter()
            .map(|&(t, w)| {
                let x = self.x0 + t * dx;
                let z = x * x / radius - self.y_ref;
                w * (self.a + z * (self.b + self.q * z))
            })
            .sum::<f64>()
            * dx;
        if self.k == 0.0 {
            quad
        } else {
            quad + self.k
                * (line.integral(self.top, self.x1, radius)
                    - line.integral(self.top, self.x0, radius))
        }
    }

    /// Bounds `(min, max)` of `ũ − W` over a stuck piece.
    fn range(&self, line: &Truncated) -> (f64, f64) {
        let quad = |y: f64| {
            let z = y - self.y_ref;
            self.a + z * (self.b + self.q * z)
        };
        let (mut lo, mut hi) = {
            let (u, v) = (quad(self.y0), quad(self.y1));
            (u.min(v), u.max(v))
        };
        if self.q != 0.0 {
            let y = self.y_ref - self.b / (2.0 * self.q);
            if y > self.y0 && y < self.y1 {
                lo = lo.min(quad(y));
                hi = hi.max(quad(y));
            }
        }
        if self.k != 0.0 {
            // Q(D_f − y) falls with y.
            let (u, v) = (
                self.k * line.value(self.top - self.y0),
                self.k * line.value(self.top - self.y1),
            );
            lo += u.min(v);
            hi += u.max(v);
        }
        (lo, hi)
    }
}

/// The Coulomb limit at one instant: `c_κ Λ(y) = c_κ Q(D − y)`.
#[derive(Debug, Clone, Copy)]
struct Limit {
    /// `c κ`: `c` in loading, `c/ρ` in unloading.
    c: f64,
    /// The reach `D` (m): `d` in loading, `ρ (d − d_p)` in Thornton's unloading, `d_max` in
    /// the MDR unloading.
    reach: f64,
    /// The uniform shortening `σ` of every spring (m): `d_max − d` in the MDR unloading, 0
    /// elsewhere; the limit is `c_κ (Q(D − y) − σ)`.
    shift: f64,
    /// The line density's truncation (none in unloading).
    line: Truncated,
}

impl Limit {
    fn at(&self, y: f64) -> f64 {
        self.c * (self.line.value(self.reach - y) - self.shift)
    }

    /// The profile height where the limit falls to 0: the contact's edge.
    fn edge(&self) -> f64 {
        if self.shift > 0.0 {
            (self.reach - self.line.inverse(self.shift)).max(0.0)
        } else {
            self.reach
        }
    }

    /// Whether the limit is linear in `y` from `y0` on (`D − y0 ≤ d_y`).
    fn linear_from(&self, y0: f64) -> bool {
        self.reach - y0 <= self.line.yield_indentation
    }

    /// `∫ c_κ Λ dx` over `[x0, x1]` (m²).
    fn integral(&self, x0: f64, x1: f64, radius: f64) -> f64 {
        self.c
            * (self.line.integral(self.reach, x1, radius)
                - self.line.integral(self.reach, x0, radius)
                - self.shift * (x1 - x0))
    }
}

/// The half-row ([module docs](self)).
#[derive(Debug, Clone)]
pub struct ThorntonRow {
    radius: f64,
    /// The loading's line density (its yield indentation `d_y`).
    line: Truncated,
    /// `ρ = R_p/R*` of Thornton's unloading.
    ratio: f64,
    /// Plastic indentation `d_p` (m) of Thornton's unloading.
    plastic_indentation: f64,
    /// The maximum indentation (m) of an unloading by the MDR rule (every spring shortens by
    /// `d_max − d`; NaN for Thornton's unloading).
    mdr_from: f64,
    /// The field, in chunks of at most [`CHUNK_MAX`] pieces: a step visits only the chunks
    /// whose sums say that something may change.
    chunks: Vec<Chunk>,
    spare: Vec<Piece>,
    /// Accumulated increment `W` (m).
    offset: f64,
    unloading: bool,
    at_limit: (bool, bool),
    cuts: Vec<f64>,
}

/// Pieces per chunk above which a chunk is split.
const CHUNK_MAX: usize = 24;

/// Consecutive pieces with the sums a step needs.
#[derive(Debug, Clone, Default)]
struct Chunk {
    pieces: Vec<Piece>,
    /// Over the stuck pieces: `Σ Δx`, `Σ ∫ (ũ − W) dx`, `min lo`, `max hi`, `max upper`,
    /// `min lower` (the bounds for the limit slope `slope`).
    stuck_length: f64,
    rel: f64,
    lo: f64,
    hi: f64,
    upper: f64,
    lower: f64,
    slope: f64,
    /// Whether some piece is at a limit, and whether one is at the `+` / `−` limit.
    limits: bool,
    signs: [bool; 2],
}

impl Chunk {
    /// The chunk of `pieces` with its sums, the stuck pieces bounded for the slope `s`.
    fn new(mut pieces: Vec<Piece>, s: f64, line: &Truncated) -> Self {
        let mut ch = Chunk {
            stuck_length: 0.0,
            rel: 0.0,
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
            upper: f64::NEG_INFINITY,
            lower: f64::INFINITY,
            slope: s,
            limits: false,
            signs: [false, false],
            pieces: Vec::new(),
        };
        for p in &mut pieces {
            if p.kind == Kind::Stuck {
                if p.slope != s {
                    *p = p.bounded(s, line);
                }
                ch.stuck_length += p.x1 - p.x0;
                ch.rel += p.rel;
                ch.lo = ch.lo.min(p.lo);
                ch.hi = ch.hi.max(p.hi);
                ch.upper = ch.upper.max(p.upper);
                ch.lower = ch.lower.min(p.lower);
            } else {
                ch.limits = true;
                ch.signs[usize::from(p.kind == Kind::Minus)] = true;
            }
        }
        ch.pieces = pieces;
        ch
    }

    /// Whether the step may change the chunk: it holds a piece at a limit of a sign whose
    /// springs may stick again in the step (`release`, `+` and `−`), or its stuck pieces may
    /// cross the limit `lim` with the offset `w`.
    fn changes(&self, lim: &Limit, w: f64, release: [bool; 2]) -> bool {
        let (Some(first), Some(last)) = (self.pieces.first(), self.pieces.last()) else {
            return false;
        };
        if !lim.c.is_finite() {
            return false;
        }
        if (self.signs[0] && release[0]) || (self.signs[1] && release[1]) {
            return true;
        }
        if lim.linear_from(first.y0) && self.slope == lim.c {
            let top = lim.c * (lim.reach - lim.shift);
            return !(self.upper <= top - w && self.lower >= -top - w);
        }
        let floor = lim.at(last.y1);
        !(w + self.hi < floor && w + self.lo > -floor)
    }
}

/// Samples per stretch between kinks when bracketing a crossing with a curved limit or piece.
const SAMPLES: usize = 8;

impl ThorntonRow {
    /// An unloaded row for effective radius `R*` (m), yield indentation `d_y` (m), and the
    /// unloading's `ρ` and `d_p` (m) ([`super::normal::Unloading`]).
    pub fn new(radius: f64, yield_indentation: f64, ratio: f64, plastic_indentation: f64) -> Self {
        ThorntonRow {
            radius,
            line: Truncated { yield_indentation },
            ratio,
            plastic_indentation,
            mdr_from: f64::NAN,
            chunks: Vec::new(),
            spare: Vec::new(),
            offset: 0.0,
            unloading: false,
            at_limit: (false, false),
            cuts: Vec::new(),
        }
    }

    /// An unloaded row of the same loading whose unloading follows the MDR rule from the
    /// maximum indentation `d_max` (m): the limit of the spring at `y` is
    /// `c (Q(d_max − y) − (d_max − d))`, continuous at the switch.
    pub fn with_mdr_unloading(radius: f64, yield_indentation: f64, max_indentation: f64) -> Self {
        ThorntonRow {
            mdr_from: max_indentation,
            ..Self::new(radius, yield_indentation, 1.0, 0.0)
        }
    }

    /// Whether some part of the contact is at the `+` / `−` limit.
    pub fn at_limit(&self) -> (bool, bool) {
        self.at_limit
    }

    /// Number of pieces (diagnostics).
    pub fn pieces(&self) -> usize {
        self.chunks.iter().map(|c| c.pieces.len()).sum()
    }

    /// Put `pieces` in place of chunk `k` (split in chunks of at most [`CHUNK_MAX`], none if
    /// empty), with their sums for the limit slope `s`; returns the number of chunks now there.
    fn install(&mut self, k: usize, pieces: Vec<Piece>, s: f64) -> usize {
        let line = self.line;
        if pieces.is_empty() {
            self.spare = std::mem::take(&mut self.chunks[k].pieces);
            self.chunks.remove(k);
            return 0;
        }
        if pieces.len() <= CHUNK_MAX {
            let old = std::mem::replace(&mut self.chunks[k], Chunk::new(pieces, s, &line));
            if old.pieces.capacity() > self.spare.capacity() {
                self.spare = old.pieces;
            }
            return 1;
        }
        let parts: Vec<Chunk> = pieces
            .chunks(CHUNK_MAX)
            .map(|c| Chunk::new(c.to_vec(), s, &line))
            .collect();
        let n = parts.len();
        self.chunks.splice(k..=k, parts);
        n
    }

    /// Join runs at one limit that a chunk boundary splits, and neighbouring chunks that fit
    /// in one, so that a run at a limit is one piece (one integral a step) and the chunks stay
    /// few.
    fn compact(&mut self, s: f64) {
        let line = self.line;
        let mut k = 0;
        while k + 1 < self.chunks.len() {
            let joins = match (
                self.chunks[k].pieces.last(),
                self.chunks[k + 1].pieces.first(),
            ) {
                (Some(a), Some(b)) => {
                    a.kind != Kind::Stuck
                        && a.kind == b.kind
                        && (b.y0 - a.y1).abs() <= 8.0 * f64::EPSILON * b.y1.abs()
                }
                _ => false,
            };
            let fits = self.chunks[k].pieces.len() + self.chunks[k + 1].pieces.len() <= CHUNK_MAX;
            if !(joins || fits) {
                k += 1;
                continue;
            }
            let next = self.chunks.remove(k + 1).pieces;
            let mut pieces = std::mem::take(&mut self.chunks[k].pieces);
            for p in next {
                push_merged(&mut pieces, p);
            }
            if pieces.len() <= CHUNK_MAX {
                self.chunks[k] = Chunk::new(pieces, s, &line);
            } else {
                let tail = pieces.split_off(CHUNK_MAX);
                self.chunks[k] = Chunk::new(pieces, s, &line);
                self.chunks.insert(k + 1, Chunk::new(tail, s, &line));
                k += 1;
            }
        }
    }

    /// The pieces of every chunk, in order (the chunks emptied).
    fn take_all(&mut self) -> Vec<Piece> {
        let mut all = Vec::new();
        for ch in self.chunks.drain(..) {
            all.extend(ch.pieces);
        }
        all
    }

    /// The limit of the current phase at indentation `d` with factor `c`.
    fn limit(&self, d: f64, c: f64) -> Limit {
        if !self.unloading {
            Limit {
                c,
                reach: d.max(0.0),
                shift: 0.0,
                line: self.line,
            }
        } else if self.mdr_from.is_nan() {
            Limit {
                c: c / self.ratio,
                reach: (self.ratio * (d - self.plastic_indentation)).max(0.0),
                shift: 0.0,
                line: Truncated {
                    yield_indentation: f64::INFINITY,
                },
            }
        } else {
            Limit {
                c,
                reach: self.mdr_from,
                shift: (self.mdr_from - d).max(0.0),
                line: self.line,
            }
        }
    }

    /// The rates `(Ḋ, σ̇)` of the limit's reach and shift at the indentation rate `ḋ`.
    fn limit_rates(&self, rate: f64) -> (f64, f64) {
        if !self.unloading {
            (rate, 0.0)
        } else if self.mdr_from.is_nan() {
            (self.ratio * rate, 0.0)
        } else {
            (0.0, -rate)
        }
    }

    /// One step ([module docs](self)): the motion `m` to indentation `d1` (m) with limit factor
    /// `c` (`∞`: no slip). Returns `∫₀^a ũ dx` (m²) and the mean displacement.
    pub fn step(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult {
        if !self.unloading && (m.rate0 < 0.0 || m.rate1 < 0.0) {
            if self.mdr_from.is_nan() {
                self.switch(m.d0, c);
            } else {
                self.unloading = true;
            }
        }
        let lim0 = self.limit(m.d0, c);
        let lim1 = self.limit(d1, c);
        let rates = (self.limit_rates(m.rate0), self.limit_rates(m.rate1));
        let (h, v, acc) = (m.h, m.slip_velocity, m.slip_accel);
        let dw = h * v + 0.5 * h * h * acc;
        let center = self.center(&lim0);
        let w_old = self.offset;
        self.offset += dw;
        self.truncate(lim1.edge());
        // Whether springs at the `+` / `−` limit may stick again in this step: the rate gap
        // g = c_κ (Q′ Ḋ − σ̇) ∓ ẇ of `slip` is at most c_κ (max(Ḋ, 0) − σ̇) ∓ ẇ (0 ≤ Q′ ≤ 1);
        // where it stays negative at the start and not positive at the end, every run slips on.
        let ((rate0, shift0), (rate1, shift1)) = rates;
        let v1 = v + acc * h;
        let release = [1.0, -1.0].map(|sign: f64| {
            let g0 = lim0.c * (rate0.max(0.0) - shift0) - sign * v;
            let g1 = lim1.c * (rate1.max(0.0) - shift1) - sign * v1;
            !(g0 < 0.0 && g1 <= 0.0)
        });
        let mut k = 0;
        while k < self.chunks.len() {
            if !self.chunks[k].changes(&lim1, self.offset, release) {
                k += 1;
                continue;
            }
            let old = std::mem::take(&mut self.chunks[k].pieces);
            let mut out = std::mem::take(&mut self.spare);
            out.clear();
            for &p in &old {
                match p.kind {
                    Kind::Stuck => self.clip(p, &lim1, &mut out),
                    Kind::Plus | Kind::Minus => {
                        self.slip(p, (&lim0, &lim1), rates, m, w_old, &mut out);
                    }
                }
            }
            self.chunks[k].pieces = old;
            k += self.install(k, out, lim1.c);
        }
        // Points entering contact: ũ = w(h) − w(θh), θ = (y − D0)/(D1 − D0).
        let (r0, r1) = (lim0.reach, lim1.reach);
        if r1 > r0 {
            let span = r1 - r0;
            let k1 = h * v + acc * h * h;
            let k2 = 0.5 * acc * h * h;
            let w = self.offset;
            let entry = Piece::stuck(
                r0,
                r1,
                r0,
                (k1 - k2 - w, (2.0 * k2 - k1) / span, -k2 / (span * span)),
                0.0,
                0.0,
                &self.line,
                self.radius,
            );
            let mut out = std::mem::take(&mut self.spare);
            out.clear();
            self.clip(entry, &lim1, &mut out);
            // Into the last chunk while it has room.
            let last = self.chunks.len();
            if last > 0 && self.chunks[last - 1].pieces.len() + out.len() <= CHUNK_MAX {
                let mut pieces = std::mem::take(&mut self.chunks[last - 1].pieces);
                for &p in &out {
                    push_merged(&mut pieces, p);
                }
                self.install(last - 1, pieces, lim1.c);
            } else if !out.is_empty() {
                self.chunks.push(Chunk::default());
                self.install(last, std::mem::take(&mut out), lim1.c);
            }
            if out.capacity() > self.spare.capacity() {
                self.spare = out;
            }
        }
        self.compact(lim1.c);
        let integral = self.integral(&lim1);
        let finite = c.is_finite();
        self.at_limit = if finite {
            self.limits_held()
        } else {
            (false, false)
        };
        let a1 = (self.radius * lim1.edge()).sqrt();
        let mean = if a1 > 0.0 && self.chunks.iter().any(|ch| !ch.pieces.is_empty()) {
            integral / a1
        } else if finite {
            0.0
        } else {
            center + dw
        };
        StepResult { integral, mean }
    }

    /// The switch to unloading at the start of a step from `start = (d, ḋ)` to `end` (the node
    /// where `ḋ` turns negative): the field clipped against the unloading limits, its
    /// `∫₀^a ũ dx` (m²) and mean displacement there; `None` at every other step.
    pub fn jump(&mut self, start: (f64, f64), end: (f64, f64), c: f64) -> Option<StepResult> {
        if self.unloading || !(start.1 < 0.0 || end.1 < 0.0) {
            return None;
        }
        if !self.mdr_from.is_nan() {
            // The MDR unloading's limits are continuous at the switch: no jump.
            self.unloading = true;
            return None;
        }
        self.switch(start.0, c);
        let lim = self.limit(start.0, c);
        let integral = self.integral(&lim);
        let a = (self.radius * lim.reach).sqrt();
        self.at_limit = self.limits_held();
        Some(StepResult {
            integral,
            mean: if a > 0.0 { integral / a } else { 0.0 },
        })
    }

    /// The switch to unloading at the maximum indentation `d_max` (m): every spring keeps its
    /// displacement (a spring at a limit holds the loading limit's value) and is clipped against
    /// the unloading limits.
    fn switch(&mut self, max_indentation: f64, c: f64) {
        let old_limit = self.limit(max_indentation, c);
        self.unloading = true;
        let new_limit = self.limit(max_indentation, c);
        let old = self.take_all();
        let mut out = Vec::with_capacity(old.len() + 8);
        let w = self.offset;
        for &p in &old {
            let stuck = match p.kind {
                Kind::Stuck => p,
                Kind::Plus | Kind::Minus => {
                    let s = if p.kind == Kind::Plus { 1.0 } else { -1.0 };
                    Piece::stuck(
                        p.y0,
                        p.y1,
                        p.y0,
                        (-w, 0.0, 0.0),
                        s * old_limit.c,
                        old_limit.reach,
                        &self.line,
                        self.radius,
                    )
                }
            };
            self.clip(stuck, &new_limit, &mut out);
        }
        self.chunks.push(Chunk::default());
        self.install(0, out, new_limit.c);
    }

    /// A run at the limit of sign `s` through the step: cut where the rate gap
    /// `g = L̇ − s ẇ` changes sign at the start or the end of the step; each part slips on where
    /// `g` stays negative and sticks again otherwise, with the missed part of the limit's
    /// change `−g₀² h/(2 (g₁ − g₀))` where it sticks inside the step.
    fn slip(
        &mut self,
        p: Piece,
        (lim0, lim1): (&Limit, &Limit),
        ((rate0, shift0), (rate1, shift1)): ((f64, f64), (f64, f64)),
        m: &StepMotion,
        w_old: f64,
        out: &mut Vec<Piece>,
    ) {
        let s = if p.kind == Kind::Plus { 1.0 } else { -1.0 };
        let (h, v, acc) = (m.h, m.slip_velocity, m.slip_accel);
        let v1 = v + acc * h;
        let g0 = |y: f64| lim0.c * (lim0.line.slope(lim0.reach - y) * rate0 - shift0) - s * v;
        let g1 = |y: f64| lim1.c * (lim1.line.slope(lim1.reach - y) * rate1 - shift1) - s * v1;
        let mut cuts = [p.y0, f64::NAN, f64::NAN, p.y1];
        cuts[1] = front(lim0, rate0, lim0.c * shift0 + s * v);
        cuts[2] = front(lim1, rate1, lim1.c * shift1 + s * v1);
        let mut inner: Vec<f64> = cuts[1..3]
            .iter()
            .copied()
            .filter(|&y| y > p.y0 && y < p.y1)
            .collect();
        inner.sort_by(f64::total_cmp);
        let mut lo = p.y0;
        for hi in inner.into_iter().chain(std::iter::once(p.y1)) {
            if hi <= lo {
                continue;
            }
            let mid = 0.5 * (lo + hi);
            let (a0, a1) = (g0(mid), g1(mid));
            if a1 <= 0.0 && a0 < 0.0 {
                push_merged(out, Piece::limit(p.kind, lo, hi, self.radius));
            } else {
                // Sticks again: ũ = s L0(y) + Δw + corr(y), stored less the new offset.
                let corr = |y: f64| {
                    let (b0, b1) = (g0(y), g1(y));
                    if b0 < 0.0 && b1 > 0.0 {
                        -b0 * b0 * h / (2.0 * (b1 - b0))
                    } else {
                        0.0
                    }
                };
                let (c_lo, c_mid, c_hi) = if a0 < 0.0 {
                    (corr(lo), corr(mid), corr(hi))
                } else {
                    (0.0, 0.0, 0.0)
                };
                // The quadratic through the three values in z = y − lo.
                let span = hi - lo;
                let qc = 2.0 * (c_hi - 2.0 * c_mid + c_lo) / (span * span);
                let bc = (c_hi - c_lo) / span - qc * span;
                let (a, b, k) = if lim0.line.yield_indentation.is_finite() {
                    (-s * lim0.c * lim0.shift, 0.0, s * lim0.c)
                } else {
                    (s * lim0.c * (lim0.reach - lo), -s * lim0.c, 0.0)
                };
                let stuck = Piece::stuck(
                    lo,
                    hi,
                    lo,
                    (a + c_lo - w_old, b + bc, qc),
                    k,
                    lim0.reach,
                    &self.line,
                    self.radius,
                );
                self.clip(stuck, lim1, out);
            }
            lo = hi;
        }
    }

    /// Clip a stuck piece (after the increment) against `±` the limit `lim` and append the
    /// parts: stuck where inside, limit pieces where outside.
    fn clip(&mut self, p: Piece, lim: &Limit, out: &mut Vec<Piece>) {
        if p.x1 <= p.x0 {
            return;
        }
        if !lim.c.is_finite() {
            out.push(p);
            return;
        }
        let w = self.offset;
        let line = self.line;
        self.cuts.clear();
        let mut p = p;
        let general = if lim.linear_from(p.y0) {
            // Linear limits ±s (D − y): the piece's bounds for slope s decide most steps.
            if p.slope != lim.c {
                p = p.bounded(lim.c, &line);
            }
            let top = lim.c * (lim.reach - lim.shift);
            if p.upper <= top - w && p.lower >= -top - w {
                out.push(p);
                return;
            }
            if p.k == 0.0 {
                // ũ ∓ c(D − y) in z: (a + W ∓ c(D − y_ref)) + (b ± c) z + q z².
                let lim_ref = lim.c * (lim.reach - lim.shift - p.y_ref);
                let (z0, z1) = (p.y0 - p.y_ref, p.y1 - p.y_ref);
                let abs_a = p.a + w;
                roots_inside(abs_a - lim_ref, p.b + lim.c, p.q, z0, z1, &mut self.cuts);
                roots_inside(abs_a + lim_ref, p.b - lim.c, p.q, z0, z1, &mut self.cuts);
                for z in &mut self.cuts {
                    *z += p.y_ref;
                }
                false
            } else {
                true
            }
        } else {
            // A curved limit: above its smallest value on the piece, and above its chord (it
            // is concave in y), which is a linear limit of slope s through (y1, L(y1)).
            let floor = lim.at(p.y1);
            if w + p.hi < floor && w + p.lo > -floor {
                out.push(p);
                return;
            }
            let span = p.y1 - p.y0;
            let s = if span > 0.0 {
                (lim.at(p.y0) - floor) / span
            } else {
                0.0
            };
            let b = p.bounded(s, &line);
            let top = floor + s * p.y1;
            p.slope = f64::NAN;
            if b.upper <= top - w && b.lower >= -top - w {
                out.push(p);
                return;
            }
            true
        };
        if general {
            let kinks = [
                p.top - line.yield_indentation,
                lim.reach - lim.line.yield_indentation,
            ];
            let plus = |y: f64| w + p.value(y, &line) - lim.at(y);
            let minus = |y: f64| w + p.value(y, &line) + lim.at(y);
            let mut cuts = std::mem::take(&mut self.cuts);
            crossings(&plus, p.y0, p.y1, &kinks, &mut cuts);
            crossings(&minus, p.y0, p.y1, &kinks, &mut cuts);
            self.cuts = cuts;
        }
        self.cuts.sort_by(f64::total_cmp);
        let classify = |y: f64| {
            let u = w + p.value(y, &line);
            let l = lim.at(y);
            if u > l {
                Kind::Plus
            } else if u < -l {
                Kind::Minus
            } else {
                Kind::Stuck
            }
        };
        let mut lo = p.y0;
        let n = self.cuts.len();
        for i in 0..=n {
            let hi = if i < n { self.cuts[i] } else { p.y1 };
            let hi = hi.clamp(lo, p.y1);
            if hi > lo {
                let kind = classify(0.5 * (lo + hi));
                let part = if kind != Kind::Stuck {
                    Piece::limit(kind, lo, hi, self.radius)
                } else if lo == p.y0 && hi == p.y1 {
                    p
                } else {
                    p.part(lo, hi, &line, self.radius)
                };
                push_merged(out, part);
            }
            lo = hi;
        }
    }

    /// Drop everything at `y ≥ top` (springs leaving contact drop their state).
    fn truncate(&mut self, top: f64) {
        let line = self.line;
        while self
            .chunks
            .last()
            .is_some_and(|ch| ch.pieces.first().is_none_or(|p| p.y0 >= top))
        {
            self.chunks.pop();
        }
        let k = self.chunks.len();
        if k == 0 {
            return;
        }
        let needs = self.chunks[k - 1].pieces.last().is_some_and(|p| p.y1 > top);
        if needs {
            let mut pieces = std::mem::take(&mut self.chunks[k - 1].pieces);
            pieces.retain(|p| p.y0 < top);
            if let Some(last) = pieces.last_mut() {
                if last.y1 > top {
                    *last = last.part(last.y0, top, &line, self.radius);
                }
            }
            let s = self.chunks[k - 1].slope;
            self.install(k - 1, pieces, s);
        }
    }

    /// Whether some piece sits at the `+` / `−` limit.
    fn limits_held(&self) -> (bool, bool) {
        let mut held = (false, false);
        for ch in self.chunks.iter().filter(|ch| ch.limits) {
            for p in &ch.pieces {
                held.0 |= p.kind == Kind::Plus;
                held.1 |= p.kind == Kind::Minus;
            }
        }
        held
    }

    /// `ũ` at the centre.
    fn center(&self, lim: &Limit) -> f64 {
        let first = self.chunks.first().and_then(|ch| ch.pieces.first());
        first.map_or(0.0, |p| match p.kind {
            Kind::Stuck => self.offset + p.value(0.0, &self.line),
            Kind::Plus => lim.at(0.0),
            Kind::Minus => -lim.at(0.0),
        })
    }

    /// `∫₀^a ũ dx` (m²) of the field under the limit `lim`.
    fn integral(&self, lim: &Limit) -> f64 {
        let w = self.offset;
        let mut total = 0.0;
        for ch in &self.chunks {
            total += w * ch.stuck_length + ch.rel;
            if ch.limits {
                for p in &ch.pieces {
                    match p.kind {
                        Kind::Stuck => {}
                        Kind::Plus => total += lim.integral(p.x0, p.x1, self.radius),
                        Kind::Minus => total -= lim.integral(p.x0, p.x1, self.radius),
                    }
                }
            }
        }
        total
    }
}

/// The height `y` where `g(y) = c_κ Q′(D − y) Ḋ − u` changes sign (`u = s ẇ`), NaN where it
/// does not inside the curved part (`Q′(σ) = (2/π) arcsin √(d_y/σ) = u/(c_κ Ḋ)`, so
/// `σ = d_y / sin²(π r/2)`).
fn front(lim: &Limit, rate: f64, u: f64) -> f64 {
    let dy = lim.line.yield_indentation;
    let scale = lim.c * rate;
    if !dy.is_finite() || scale == 0.0 || !scale.is_finite() {
        return f64::NAN;
    }
    let r = u / scale;
    if !(r > 0.0 && r < 1.0) {
        return f64::NAN;
    }
    let s = (std::f64::consts::FRAC_PI_2 * r).sin();
    lim.reach - dy / (s * s)
}

/// The sign changes of `f` inside `(y0, y1)`, appended to `out`: `f` sampled at [`SAMPLES`]
/// points on each stretch between the `kinks` (where it is smooth), each bracket bisected to
/// the rounding.
fn crossings(f: &dyn Fn(f64) -> f64, y0: f64, y1: f64, kinks: &[f64], out: &mut Vec<f64>) {
    let mut ends = [y0, f64::NAN, f64::NAN, y1];
    let mut n = 1;
    for &k in kinks {
        if k > y0 && k < y1 {
            ends[n] = k;
            n += 1;
        }
    }
    ends[n] = y1;
    let ends = &mut ends[..=n];
    ends.sort_by(f64::total_cmp);
    for pair in ends.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if b <= a {
            continue;
        }
        let mut prev = (a, f(a));
        for i in 1..=SAMPLES {
            let y = if i == SAMPLES {
                b
            } else {
                a + (b - a) * i as f64 / SAMPLES as f64
            };
            let fy = f(y);
            if (prev.1 < 0.0 && fy > 0.0) || (prev.1 > 0.0 && fy < 0.0) {
                out.push(bisect(f, prev, (y, fy)));
            } else if fy == 0.0 && y > y0 && y < y1 {
                out.push(y);
            }
            prev = (y, fy);
        }
    }
}

/// The root of `f` between `(lo, f(lo))` and `(hi, f(hi))` of opposite signs, to adjacent
/// doubles.
fn bisect(f: &dyn Fn(f64) -> f64, (mut lo, f_lo): (f64, f64), (mut hi, _): (f64, f64)) -> f64 {
    let neg = f_lo < 0.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if (f(mid) < 0.0) == neg {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Append a piece, merging it into the last one when both sit at the same limit (their ends
/// a few ulps apart: an end found by bisection and one set by the motion), and letting a
/// limit piece absorb a sliver a few ulps wide that follows it.
fn push_merged(out: &mut Vec<Piece>, p: Piece) {
    if p.x1 <= p.x0 {
        return;
    }
    if let Some(last) = out.last_mut() {
        let close = 8.0 * f64::EPSILON * p.y1.abs();
        let joins = last.kind == p.kind && (p.y0 - last.y1).abs() <= close;
        let sliver = p.y1 - p.y0 <= close;
        if last.kind != Kind::Stuck && (joins || sliver) {
            last.y1 = p.y1;
            last.x1 = p.x1;
            return;
        }
    }
    out.push(p);
}
