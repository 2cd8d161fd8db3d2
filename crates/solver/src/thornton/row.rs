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
//! `±∫₀^τ (L̇ ∓ ẇ) dt` at the `±` limit, with the rate gap `g = L̇ ∓ ẇ` linear over the step
//! (the row is the same under `u → −u`). Where the limit is not
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
//! curved piece meets a limit, the crossing is found between the kinks of `Q`: from the gap's
//! values at a stretch's ends where the bounds of its second derivative say that it is convex
//! or concave there, else by bracketing on a few samples, then closed to the rounding. While
//! the limits grow, each stuck piece keeps the offsets up to which it stays inside them
//! ([`field::Piece::caps`]), so that a step clips only the pieces that may have changed.

mod field;

use super::line::Truncated;
use crate::continuum::roots_inside;
use crate::springs::{StepMotion, StepResult};
use field::{crossings, front, push_merged, Chunk, Kind, Limit, Piece, CHUNK_MAX};

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
    /// The first chunk changed since the last [`ThorntonRow::compact`] (the pairs before it
    /// were left as they are then).
    dirty: usize,
}

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
            dirty: 0,
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

    /// Whether the whole contact is at one Coulomb limit (gross slip, `F_t = ±μF_N`):
    /// `Some(true)` at `+`, `Some(false)` at `−`, `None` where a piece of positive length is
    /// stuck, where both limits are held, or where nothing is in contact.
    pub fn gross_slip(&self) -> Option<bool> {
        let (mut plus, mut minus) = (false, false);
        for p in self.chunks.iter().flat_map(|c| &c.pieces) {
            match p.kind {
                Kind::Plus => plus = true,
                Kind::Minus => minus = true,
                Kind::Stuck if p.x1 > p.x0 => return None,
                Kind::Stuck => {}
            }
        }
        match (plus, minus) {
            (true, false) => Some(true),
            (false, true) => Some(false),
            _ => None,
        }
    }

    /// Lengths (m, along the row's `x`) of the parts of the contact at the `+` limit and at the
    /// `−` limit, the length stuck, and the numbers of separate zones at the `+` and at the `−`
    /// limit (diagnostics: partial-slip zones that gross slip does not show).
    pub fn slip_extent(&self) -> (f64, f64, f64, usize, usize) {
        let (mut plus, mut minus, mut stuck) = (0.0, 0.0, 0.0);
        let (mut zp, mut zm) = (0, 0);
        let mut last: Option<Kind> = None;
        for p in self.chunks.iter().flat_map(|c| &c.pieces) {
            let len = (p.x1 - p.x0).max(0.0);
            if len <= 0.0 {
                continue;
            }
            match p.kind {
                Kind::Plus => plus += len,
                Kind::Minus => minus += len,
                Kind::Stuck => stuck += len,
            }
            if last != Some(p.kind) {
                match p.kind {
                    Kind::Plus => zp += 1,
                    Kind::Minus => zm += 1,
                    Kind::Stuck => {}
                }
            }
            last = Some(p.kind);
        }
        (plus, minus, stuck, zp, zm)
    }

    /// The zones of the contact in order from the centre (diagnostics): `(kind, x0, x1)` with
    /// `kind` +1 at the `+` limit, −1 at the `−` limit, 0 stuck, `x0`, `x1` (m) along the
    /// row; neighbouring pieces of one kind joined, pieces of zero length left out.
    pub fn zones(&self) -> Vec<(i8, f64, f64)> {
        let mut out: Vec<(i8, f64, f64)> = Vec::new();
        for p in self.chunks.iter().flat_map(|c| &c.pieces) {
            if p.x1 <= p.x0 {
                continue;
            }
            let kind = match p.kind {
                Kind::Plus => 1,
                Kind::Minus => -1,
                Kind::Stuck => 0,
            };
            match out.last_mut() {
                Some(last) if last.0 == kind => last.2 = p.x1,
                _ => out.push((kind, p.x0, p.x1)),
            }
        }
        out
    }

    /// Number of pieces (diagnostics).
    pub fn pieces(&self) -> usize {
        self.chunks.iter().map(|c| c.pieces.len()).sum()
    }

    /// Put `pieces` in place of chunk `k` (split in chunks of at most [`CHUNK_MAX`], none if
    /// empty), with their sums for the limit slope `s`; returns the number of chunks now there.
    fn install(&mut self, k: usize, pieces: Vec<Piece>, s: f64) -> usize {
        self.dirty = self.dirty.min(k);
        if pieces.is_empty() {
            let old = self.chunks.remove(k).pieces;
            self.keep_spare(old);
            return 0;
        }
        if pieces.len() <= CHUNK_MAX {
            let mut chunk = Chunk::empty(s);
            chunk.pieces = pieces;
            return self.install_counted(k, chunk, 0);
        }
        let parts: Vec<Chunk> = pieces
            .chunks(CHUNK_MAX)
            .map(|c| Chunk::new(c.to_vec(), s))
            .collect();
        let n = parts.len();
        self.chunks.splice(k..=k, parts);
        n
    }

    /// Put `chunk`, whose sums count its first `counted` pieces, in place of chunk `k` (as
    /// [`ThorntonRow::install`]); returns the number of chunks now there.
    fn install_counted(&mut self, k: usize, mut chunk: Chunk, counted: usize) -> usize {
        if chunk.pieces.is_empty() || chunk.pieces.len() > CHUNK_MAX {
            let s = chunk.slope;
            return self.install(k, chunk.pieces, s);
        }
        self.dirty = self.dirty.min(k);
        chunk.count_from(counted);
        let old = std::mem::replace(&mut self.chunks[k], chunk);
        self.keep_spare(old.pieces);
        1
    }

    /// Keep `pieces`' allocation as the scratch vector where it is the larger one.
    fn keep_spare(&mut self, pieces: Vec<Piece>) {
        if pieces.capacity() > self.spare.capacity() {
            self.spare = pieces;
        }
    }

    /// Join runs at one limit that a chunk boundary splits, and neighbouring chunks that fit
    /// in one, so that a run at a limit is one piece (one integral a step) and the chunks stay
    /// few.
    fn compact(&mut self, s: f64) {
        // A pass leaves no pair to join: only pairs with a changed chunk are looked at.
        let mut k = self.dirty.saturating_sub(1);
        self.dirty = usize::MAX;
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
                self.chunks[k] = Chunk::new(pieces, s);
            } else {
                let tail = pieces.split_off(CHUNK_MAX);
                self.chunks[k] = Chunk::new(pieces, s);
                let next = Chunk::new(tail, s);
                self.chunks.insert(k + 1, next);
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
        let grow = !self.unloading;
        // Thornton's unloading: linear limits ±c_κ (D − y) everywhere, below `top1` − c_κ y.
        let lines = !grow && lim1.line.yield_indentation == f64::INFINITY;
        let top1 = lim1.c * (lim1.reach - lim1.shift);
        let mut k = 0;
        // Without slip (c = ∞) no chunk changes.
        while lim1.c.is_finite() && k < self.chunks.len() {
            let w = self.offset;
            if !self.chunks[k].changes(&lim1, w, release, grow) {
                k += 1;
                continue;
            }
            // A stuck piece inside the limits by its caps while they grow, or by its bounds
            // against the lines of Thornton's unloading, is unchanged.
            let kept = |p: &Piece| {
                p.kind == Kind::Stuck
                    && ((grow && w <= p.caps[0] && -w <= p.caps[1])
                        || (lines
                            && p.slope == lim1.c
                            && p.x1 > p.x0
                            && p.upper <= top1 - w
                            && p.lower >= -top1 - w))
            };
            // The unchanged pieces before the first that may change stay where they are (the
            // new chunk's sums count them as they are found); the rest are moved aside and
            // pushed back as the step leaves them.
            let mut chunk = Chunk::empty(lim1.c);
            let mut pieces = std::mem::take(&mut self.chunks[k].pieces);
            let mut first = 0;
            while first < pieces.len() && kept(&pieces[first]) {
                chunk.count(&mut pieces[first]);
                first += 1;
            }
            let mut rest = std::mem::take(&mut self.spare);
            rest.clear();
            rest.extend_from_slice(&pieces[first..]);
            pieces.truncate(first);
            for p in &rest {
                if kept(p) {
                    pieces.push(*p);
                    continue;
                }
                match p.kind {
                    Kind::Stuck => self.clip(p, &lim1, &mut pieces),
                    Kind::Plus | Kind::Minus => {
                        self.slip(*p, (&lim0, &lim1), rates, m, w_old, &mut pieces);
                    }
                }
            }
            self.spare = rest;
            chunk.pieces = pieces;
            k += self.install_counted(k, chunk, first);
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
            self.clip(&entry, &lim1, &mut out);
            // Into the last chunk while it has room.
            let last = self.chunks.len();
            if last > 0 && self.chunks[last - 1].pieces.len() + out.len() <= CHUNK_MAX {
                self.dirty = self.dirty.min(last - 1);
                let chunk = &mut self.chunks[last - 1];
                if chunk.slope == lim1.c {
                    for &p in &out {
                        chunk.append(p);
                    }
                } else {
                    let mut pieces = std::mem::take(&mut chunk.pieces);
                    for &p in &out {
                        push_merged(&mut pieces, p);
                    }
                    self.install(last - 1, pieces, lim1.c);
                }
            } else if !out.is_empty() {
                self.chunks.push(Chunk::default());
                self.install(last, std::mem::take(&mut out), lim1.c);
            }
            self.keep_spare(out);
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
            self.clip(&stuck, &new_limit, &mut out);
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
                // Sticks again: ũ = s L0(y) + Δw + corr(y), stored less the new offset, with
                // corr = s ∫₀^τ g dt the part of the limit's change the spring missed before it
                // stuck again at τ (the spring at the − limit moves with −L: the sign s). Where g
                // stays negative to the end of the step (only at a part's ends, where the rate
                // gap's front cuts it, g₁ = 0 to the rounding) the spring reaches the limit at
                // the end, ∫₀^h g dt: the same value at g₁ = 0, so that the correction is
                // continuous in y and a rounding of g₁ does not move the part's interpolation.
                let corr = |y: f64| {
                    let (b0, b1) = (g0(y), g1(y));
                    let missed = if b0 >= 0.0 {
                        0.0
                    } else if b1 > 0.0 {
                        -b0 * b0 * h / (2.0 * (b1 - b0))
                    } else {
                        0.5 * (b0 + b1) * h
                    };
                    s * missed
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
                self.clip(&stuck, lim1, out);
            }
            lo = hi;
        }
    }

    /// Clip a stuck piece (after the increment) against `±` the limit `lim` and append the
    /// parts: stuck where inside, limit pieces where outside.
    fn clip(&mut self, p: &Piece, lim: &Limit, out: &mut Vec<Piece>) {
        if p.x1 <= p.x0 {
            return;
        }
        if !lim.c.is_finite() {
            out.push(*p);
            return;
        }
        let w = self.offset;
        let line = self.line;
        self.cuts.clear();
        let mut p = *p;
        // `None`: the crossings are found (a quadratic against a line); else whether the `+` /
        // `−` limit may be crossed, to be searched, and the limit at the piece's ends.
        let general = if lim.linear_from(p.y0) {
            // Linear limits ±s (D − y): the piece's bounds for slope s decide most steps.
            if p.slope != lim.c {
                p = p.bounded(lim.c);
            }
            let top = lim.c * (lim.reach - lim.shift);
            let sides = (p.upper > top - w, p.lower < -top - w);
            if !(sides.0 || sides.1) {
                // Inside while W + upper ≤ top and W + lower ≥ −top (the caps, while the
                // limits grow).
                p.caps = [top - p.upper, top + p.lower];
                out.push(p);
                return;
            }
            if p.k == 0.0 {
                // ũ ∓ c(D − y) in z: (a + W ∓ c(D − y_ref)) + (b ± c) z + q z².
                let lim_ref = lim.c * (lim.reach - lim.shift - p.y_ref);
                let (z0, z1) = (p.y0 - p.y_ref, p.y1 - p.y_ref);
                let abs_a = p.a + w;
                roots_inside(abs_a - lim_ref, p.b + lim.c, p.q, z0, z1, |r| {
                    self.cuts.push(r)
                });
                roots_inside(abs_a + lim_ref, p.b - lim.c, p.q, z0, z1, |r| {
                    self.cuts.push(r)
                });
                for z in &mut self.cuts {
                    *z += p.y_ref;
                }
                None
            } else {
                Some((sides, (lim.at(p.y0), lim.at(p.y1))))
            }
        } else {
            // A curved limit: above its smallest value on the piece, and above its chord (it
            // is concave in y), which is a linear limit of slope s through (y1, L(y1)).
            let floor = lim.at(p.y1);
            // The caps by the floor: inside while W + hi ≤ floor and W + lo ≥ −floor.
            p.caps = [floor - p.hi, floor + p.lo];
            if w + p.hi < floor && w + p.lo > -floor {
                out.push(p);
                return;
            }
            let span = p.y1 - p.y0;
            let l0 = lim.at(p.y0);
            let s = if span > 0.0 { (l0 - floor) / span } else { 0.0 };
            let (upper, lower) = p.bounds(s);
            let top = floor + s * p.y1;
            // Each limit is crossed only where neither its floor nor its chord says otherwise.
            let sides = (
                w + p.hi >= floor && upper > top - w,
                w + p.lo <= -floor && lower < -top - w,
            );
            if !(sides.0 || sides.1) {
                p.caps = [p.caps[0].max(top - upper), p.caps[1].max(top + lower)];
                out.push(p);
                return;
            }
            Some((sides, (l0, floor)))
        };
        if let Some(((plus_side, minus_side), ends)) = general {
            let kinks = [
                p.top - line.yield_indentation,
                lim.reach - lim.line.yield_indentation,
            ];
            // ũ ∓ c_κ Λ has the second derivative 2q − k Q″-magnitude of the piece's curved
            // part ± c_κ that of the limit (−Q″ ≥ 0 in both, bounded on each stretch).
            let (k, c) = (p.k, lim.c);
            let curvature = |a: f64, b: f64, sign: f64| {
                let piece = if k == 0.0 {
                    (0.0, 0.0)
                } else {
                    scaled(-k, line.curvature_range(p.top, a, b))
                };
                let limit = scaled(sign * c, lim.line.curvature_range(lim.reach, a, b));
                let (mut low, mut high) =
                    (2.0 * p.q + piece.0 + limit.0, 2.0 * p.q + piece.1 + limit.1);
                // Where the piece's curved part follows the same line as the limit, the two
                // nearly cancel when D_f ≈ D (a piece stuck again from the limit): bound the sum
                // as (±c_κ − k) (−Q″(D − y)) + k [−Q″(D − y) − (−Q″(D_f − y))] too.
                if k != 0.0 && line == lim.line {
                    if let Some(gap) = line.curvature_difference(lim.reach, p.top, a, b) {
                        let rest = scaled(sign * c - k, lim.line.curvature_range(lim.reach, a, b));
                        let gap = scaled(k, gap);
                        low = low.max(2.0 * p.q + rest.0 + gap.0);
                        high = high.min(2.0 * p.q + rest.1 + gap.1);
                    }
                }
                (low, high)
            };
            let mut cuts = std::mem::take(&mut self.cuts);
            // The gaps' values at the piece's ends, from the piece's and the limit's values
            // there (the same doubles as the closures give).
            let (v0, v1) = p.end_values();
            let (l0, l1) = ends;
            if plus_side {
                let plus = |y: f64| w + p.value(y, &line) - lim.at(y);
                crossings(
                    &plus,
                    &|a, b| curvature(a, b, 1.0),
                    (p.y0, w + v0 - l0),
                    (p.y1, w + v1 - l1),
                    &kinks,
                    &mut cuts,
                );
            }
            if minus_side {
                let minus = |y: f64| w + p.value(y, &line) + lim.at(y);
                crossings(
                    &minus,
                    &|a, b| curvature(a, b, -1.0),
                    (p.y0, w + v0 + l0),
                    (p.y1, w + v1 + l1),
                    &kinks,
                    &mut cuts,
                );
            }
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
        let (line, radius) = (self.line, self.radius);
        while self
            .chunks
            .last()
            .is_some_and(|ch| ch.pieces.first().is_none_or(|p| p.y0 >= top))
        {
            self.chunks.pop();
            self.dirty = self.dirty.min(self.chunks.len());
        }
        let k = self.chunks.len();
        if k == 0 {
            return;
        }
        let chunk = &mut self.chunks[k - 1];
        if chunk.pieces.last().is_none_or(|p| p.y1 <= top) {
            return;
        }
        // The pieces from `from` on are cut (the first, where it starts below `top`) or
        // dropped. Their shares of the stuck pieces' sums are taken out and the cut piece's
        // added: O(1) a step instead of counting the chunk again (every step of the
        // restitution cuts the outermost stuck piece). The bounds are left as they are: still
        // bounds.
        let from = chunk.pieces.partition_point(|p| p.y1 <= top);
        for p in chunk.pieces[from..]
            .iter()
            .filter(|p| p.kind == Kind::Stuck)
        {
            chunk.stuck_length -= p.x1 - p.x0;
            chunk.rel -= p.rel;
        }
        let keep = chunk.pieces.partition_point(|p| p.y0 < top);
        chunk.pieces.truncate(keep);
        if keep > from {
            let mut cut = chunk.pieces[from].part(chunk.pieces[from].y0, top, &line, radius);
            if cut.kind == Kind::Stuck {
                chunk.count(&mut cut);
            }
            chunk.pieces[from] = cut;
        }
        if chunk.pieces.iter().all(|p| p.kind != Kind::Stuck) {
            // Exactly nothing, not the rounding the subtractions left.
            chunk.stuck_length = 0.0;
            chunk.rel = 0.0;
        }
        chunk.signs =
            [Kind::Plus, Kind::Minus].map(|kind| chunk.pieces.iter().any(|p| p.kind == kind));
        self.dirty = self.dirty.min(k - 1);
    }

    /// Whether some piece sits at the `+` / `−` limit.
    fn limits_held(&self) -> (bool, bool) {
        self.chunks.iter().fold((false, false), |held, ch| {
            (held.0 || ch.signs[0], held.1 || ch.signs[1])
        })
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

    /// How far the chunks' sums have drifted from their pieces (a test of the sums kept by
    /// differences): the largest gap of `Σ Δx` and `Σ ∫ (ũ − W) dx` over the stuck pieces to
    /// their recount, relative to the recount's scale, and whether every chunk's bounds still
    /// bound its stuck pieces (`lo`, `hi`, and `upper`, `lower` for the chunk's slope).
    #[cfg(test)]
    pub(crate) fn sums_drift(&self) -> (f64, bool) {
        let mut drift: f64 = 0.0;
        let mut bounded = true;
        for ch in &self.chunks {
            let stuck = ch.pieces.iter().filter(|p| p.kind == Kind::Stuck);
            let (mut length, mut rel, mut scale) = (0.0, 0.0, 0.0f64);
            for p in stuck {
                length += p.x1 - p.x0;
                rel += p.rel;
                scale = scale.max(p.rel.abs());
                bounded &= ch.lo <= p.lo && ch.hi >= p.hi;
                if ch.slope.is_finite() && p.slope == ch.slope {
                    bounded &= ch.upper >= p.upper && ch.lower <= p.lower;
                }
            }
            let x = ch.pieces.last().map_or(0.0, |p| p.x1);
            if x > 0.0 {
                drift = drift.max((ch.stuck_length - length).abs() / x);
            }
            if scale > 0.0 {
                drift = drift.max((ch.rel - rel).abs() / (scale * ch.pieces.len() as f64));
            }
        }
        (drift, bounded)
    }

    /// `∫₀^a ũ dx` (m²) of the field under the limit `lim`.
    #[inline(never)]
    fn integral(&self, lim: &Limit) -> f64 {
        let w = self.offset;
        let mut total = 0.0;
        for ch in &self.chunks {
            total += w * ch.stuck_length + ch.rel;
            if ch.has_limits() {
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

/// Bounds of `f m` for `m` within `(m0, m1)` (`(0, 0)` for `f = 0`, whatever the bounds).
fn scaled(f: f64, (m0, m1): (f64, f64)) -> (f64, f64) {
    if f == 0.0 {
        (0.0, 0.0)
    } else if f > 0.0 {
        (f * m0, f * m1)
    } else {
        (f * m1, f * m0)
    }
}
