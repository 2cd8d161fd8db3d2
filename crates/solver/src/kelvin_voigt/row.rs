//! The Kelvin–Voigt tangential row in the continuum limit: the field of tangential spring
//! states over the contact, exact in space, for springs with relaxation time `τ`.
//!
//! A spring at profile height `y = x²/R*` holds an elastic displacement `u` and carries the
//! force `G* v` per unit length, `v = u + τ u̇`. With the load `D = d + τ ḋ` its Coulomb limit is
//! `|v| ≤ c (D − y)`, `c = μ E*/G*` (`physics.md`):
//!
//! - stuck, `u̇ = ẇ` (the contact point's velocity): `v = u + τ ẇ`, as long as that is within
//!   the limit;
//! - slipping with sign `s`: `v = s c (D − y)`, and `u` relaxes, `τ u̇ = v − u`; with
//!   `δ = u − s c (D − y)` that reads `τ δ̇ = −δ − τ L̇`, `L̇ = s c Ḋ` the same for every spring,
//!   so one step maps every slipping spring's `δ` by the same `δ ↦ E δ + K_s`, `E = e^{−h/τ}`;
//! - a slipping spring sticks again where `s (δ + τ ẇ) ≤ 0` (where `u̇` of the relaxation falls
//!   to `ẇ`; `u̇` is continuous across both transitions);
//! - springs enter contact with `u = 0` while the contact grows (`y < d` in compression) and
//!   leave it for good as it shrinks (`y < D` in restitution, non-adhesive).
//!
//! As in the elastic row ([`crate::continuum::ContinuumRow`]), every field the update produces
//! is piecewise quadratic in `y`: a stuck piece holds `u − W` (`W` the accumulated increment of
//! `w`), a slipping piece `δ` in the frame of its sign (`δ = A_s δ̃ + B_s`, with `A_s`, `B_s`
//! accumulating the uniform relaxation, so a step that changes no state costs O(1) per chunk).
//! `∫ v dx` is integrated exactly. Transitions happen at the end of a step (local error O(h²)
//! once per spring: second order overall).

use crate::continuum::{install, lower_to, raise, roots_inside, truncate, Kind, Piece, PieceChunk};
use crate::springs::{StepMotion, StepResult};

/// A piece of this row on `[y0, y1]` with `z = y − y_ref` (the elastic row's [`Piece`]): a
/// stuck one holds `u − W = a + b z + q z²`, a slipping one (`Kind::Plus`, `Kind::Minus`) its
/// state `δ̃ = a + b z + q z²` in the frame of its sign (and `x1³ − x0³` in `rel_integral`).
fn piece(kind: Kind, y0: f64, y1: f64, y_ref: f64, abq: (f64, f64, f64), c: f64, r: f64) -> Piece {
    let mut p = Piece {
        kind,
        y0,
        y1,
        x0: (r * y0).sqrt(),
        x1: (r * y1).sqrt(),
        y_ref,
        a: abq.0,
        b: abq.1,
        q: abq.2,
        rel_integral: 0.0,
        upper: 0.0,
        lower: 0.0,
    };
    refresh(&mut p, c, r);
    p
}

/// Recompute a piece's sums after its ends changed: for a stuck piece those of the elastic
/// row, for a slipping one `upper = max δ̃`, `lower = min δ̃` and, in `rel_integral` (unused
/// at a limit), `x1³ − x0³` (m³, [`cube`]: read by every summation of its chunk, computed once
/// per change of its ends).
fn refresh(p: &mut Piece, c: f64, r: f64) {
    match p.kind {
        Kind::Stuck => Piece::refresh(p, c, r),
        Kind::Plus | Kind::Minus => {
            // Both extremes at once: δ̃ at both ends and at the vertex inside.
            let (v0, v1) = (p.value(p.y0), p.value(p.y1));
            let (mut upper, mut lower) = (v0.max(v1), v0.min(v1));
            if p.q != 0.0 {
                let y = p.y_ref - p.b / (2.0 * p.q);
                if y > p.y0 && y < p.y1 {
                    let v = p.value(y);
                    upper = upper.max(v);
                    lower = lower.min(v);
                }
            }
            p.upper = upper;
            p.lower = lower;
            p.rel_integral = cube(p);
        }
    }
}

/// `x1³ − x0³` of a piece (m³): held by a slipping piece ([`refresh`]).
fn cube(p: &Piece) -> f64 {
    p.x1 * p.x1 * p.x1 - p.x0 * p.x0 * p.x0
}

/// Index of a slipping kind's frame and entry state: 0 for `+`, 1 for `−`.
fn sign_index(kind: Kind) -> usize {
    usize::from(kind == Kind::Minus)
}

/// Whether [`push_slip`] merges the slipping piece `p` into `last`: the same kind, adjacent,
/// both holding the same uniform state.
#[inline]
fn merges(last: &Piece, p: &Piece) -> bool {
    // The test that fails first for most pieces (those of a clipped stuck piece) first.
    p.b == 0.0
        && p.q == 0.0
        && last.b == 0.0
        && last.q == 0.0
        && last.kind == p.kind
        && last.kind != Kind::Stuck
        && last.y1 == p.y0
        && last.a == p.a
}

/// Append a slipping piece, merged into the last one when both hold the same uniform state
/// (the entry state: every spring that entered slipping and kept slipping).
fn push_slip(out: &mut Vec<Piece>, p: Piece, c: f64, r: f64) {
    if let Some(last) = out.last_mut() {
        if merges(last, &p) {
            last.y1 = p.y1;
            last.x1 = p.x1;
            refresh(last, c, r);
            return;
        }
    }
    out.push(p);
}

/// The sums over a run of pieces that a step needs (a `Copy` value: the frozen chunks' sums
/// and the row's total are built without touching a piece vector).
#[derive(Debug, Clone, Copy)]
struct Sums {
    /// Stuck: `Σ ∫ (u − W) dx` (m²), `Σ Δx` (m), `max upper`, `min lower` (m).
    rel_integral: f64,
    stuck_length: f64,
    upper: f64,
    lower: f64,
    /// Slipping at `+`/`−`: number of pieces, `Σ Δx` (m), `Σ Δ(x³)` (m³), `min δ̃` (`+`) and
    /// `max δ̃` (`−`) (m).
    slipping: [u32; 2],
    slip_length: [f64; 2],
    slip_cube: [f64; 2],
    plus_min: f64,
    minus_max: f64,
}

impl Sums {
    /// The sums of no piece.
    const EMPTY: Sums = Sums {
        rel_integral: 0.0,
        stuck_length: 0.0,
        upper: f64::NEG_INFINITY,
        lower: f64::INFINITY,
        slipping: [0; 2],
        slip_length: [0.0; 2],
        slip_cube: [0.0; 2],
        plus_min: f64::INFINITY,
        minus_max: f64::NEG_INFINITY,
    };
}

impl Default for Sums {
    fn default() -> Self {
        Sums::EMPTY
    }
}

/// Consecutive pieces with the sums a step needs.
#[derive(Debug, Clone, Default)]
struct Chunk {
    pieces: Vec<Piece>,
    sums: Sums,
}

/// Pieces per chunk above which a chunk is split in two. Smaller than the elastic row's 48: a
/// chunk is rebuilt whenever one of its slipping pieces may stick again, and slipping pieces
/// merge less (instructions per run at 2048 steps, mean of ten, the first also integrating the
/// normal motion; γ = 3, α = 0.3, e_n = 0.9: 10.0e6 with 48,
/// 8.5e6 with 24, 8.3e6 with 16; at γ = 0.5, α = 1: 15.5e6, 14.6e6, 15.7e6).
const CHUNK_MAX: usize = 24;

/// Unchanged pieces after the last changed one of an updated chunk from which on they go to a
/// chunk of their own ([`ViscoelasticRow::update_chunk`]). The chunk that a step changes is
/// mostly the same one for many steps (the edge of the stuck centre as it shrinks in the
/// restitution, the stuck centre itself at full slip), and its update adds a band that started
/// to slip there: a band carries the state it was relaxed to from its own instant, so bands do
/// not merge as the elastic row's limit pieces do. Left in that chunk, they were copied and
/// summed again every step until it split at [`CHUNK_MAX`]; peeled off, they wait in chunks that
/// no step visits ([`RunningSums`]). Warm solves (`solveloop`, instructions, at γ = 1.754, α = 1,
/// e_n = 0.8; γ = 1.754, α = 0.3, e_n = 0.8; γ = 3, α = 0.3, e_n = 0.6): 6.40, 3.83, 4.14 M
/// with 8; 7.17, 3.90, 4.32 M with 4; 6.36, 3.89, 4.19 M with 12; 6.64, 4.28, 4.84 M without
/// (and without the suffix sums of [`RunningSums`]).
const PEEL: usize = 8;

impl PieceChunk for Chunk {
    type Piece = Piece;
    fn pieces_mut(&mut self) -> &mut Vec<Piece> {
        &mut self.pieces
    }
    fn summarize(&mut self) {
        Chunk::summarize(self);
    }
    #[inline]
    fn remove_last(&mut self) {
        if let Some(p) = self.pieces.pop() {
            self.sums.remove(&p);
        }
    }
    // Every truncation and every merge at the outer end (`#[inline]` alone left it a call, as
    // in the elastic row).
    #[inline(always)]
    fn replace_last(&mut self, old: &Piece) {
        if let Some(p) = self.pieces.last() {
            self.sums.replace(old, p);
        }
    }
}

impl Chunk {
    /// Sum the pieces again, in their order.
    fn summarize(&mut self) {
        let mut sums = Sums::EMPTY;
        for p in &self.pieces {
            sums.add(p);
        }
        self.sums = sums;
    }

    /// A chunk of no piece with room for a full one.
    fn fresh() -> Self {
        Chunk {
            pieces: Vec::with_capacity(CHUNK_MAX + 1),
            sums: Sums::EMPTY,
        }
    }

    /// Append one piece at the outer end ([`push_slip`] for a slipping one) and update the
    /// sums.
    fn push(&mut self, p: Piece, c: f64, r: f64) {
        let before = self.pieces.last().copied();
        let len = self.pieces.len();
        if p.kind == Kind::Stuck {
            self.pieces.push(p);
        } else {
            push_slip(&mut self.pieces, p, c, r);
        }
        match before {
            Some(old) if self.pieces.len() == len => self.replace_last(&old),
            _ => self.sums.add(&p),
        }
    }
}

impl Sums {
    /// Add the sums of another run to these.
    #[inline]
    fn absorb(&mut self, o: &Sums) {
        self.rel_integral += o.rel_integral;
        self.stuck_length += o.stuck_length;
        raise(&mut self.upper, o.upper);
        lower_to(&mut self.lower, o.lower);
        for i in 0..2 {
            self.slipping[i] += o.slipping[i];
            self.slip_length[i] += o.slip_length[i];
            self.slip_cube[i] += o.slip_cube[i];
        }
        lower_to(&mut self.plus_min, o.plus_min);
        raise(&mut self.minus_max, o.minus_max);
    }

    /// Whether a step changes a run with these sums: a slipping piece may stick again
    /// (`scale · δ̃` past `release`, per sign) or a stuck piece crosses a limit.
    #[inline]
    fn changes(&self, frames: &[Frame; 2], releases: [f64; 2], t_plus: f64, t_minus: f64) -> bool {
        (self.slipping[0] > 0 && frames[0].scale * self.plus_min <= releases[0])
            || (self.slipping[1] > 0 && frames[1].scale * self.minus_max >= releases[1])
            || self.upper > t_plus
            || self.lower < t_minus
    }

    /// Add a piece to the sums.
    #[inline]
    fn add(&mut self, p: &Piece) {
        match p.kind {
            Kind::Stuck => {
                self.rel_integral += p.rel_integral;
                self.stuck_length += p.x1 - p.x0;
                raise(&mut self.upper, p.upper);
                lower_to(&mut self.lower, p.lower);
            }
            Kind::Plus => {
                self.slipping[0] += 1;
                self.slip_length[0] += p.x1 - p.x0;
                self.slip_cube[0] += p.rel_integral;
                lower_to(&mut self.plus_min, p.lower);
            }
            Kind::Minus => {
                self.slipping[1] += 1;
                self.slip_length[1] += p.x1 - p.x0;
                self.slip_cube[1] += p.rel_integral;
                raise(&mut self.minus_max, p.upper);
            }
        }
    }

    /// Replace a piece the sums hold by `p` of the same kind (its ends moved: a truncation, an
    /// extension): the differences added, the bounds widened by `p`'s (as [`Sums::remove`]
    /// then [`Sums::add`], rounded otherwise).
    #[inline(always)]
    fn replace(&mut self, old: &Piece, p: &Piece) {
        let dx = (p.x1 - p.x0) - (old.x1 - old.x0);
        let d_rel = p.rel_integral - old.rel_integral;
        match (old.kind, p.kind) {
            (Kind::Stuck, Kind::Stuck) => {
                self.rel_integral += d_rel;
                self.stuck_length += dx;
                raise(&mut self.upper, p.upper);
                lower_to(&mut self.lower, p.lower);
            }
            (Kind::Plus, Kind::Plus) => {
                self.slip_length[0] += dx;
                self.slip_cube[0] += d_rel;
                lower_to(&mut self.plus_min, p.lower);
            }
            (Kind::Minus, Kind::Minus) => {
                self.slip_length[1] += dx;
                self.slip_cube[1] += d_rel;
                raise(&mut self.minus_max, p.upper);
            }
            _ => {
                self.remove(old);
                self.add(p);
            }
        }
    }

    /// Take a piece the sums hold out of them; the bounds (`upper`, `lower`, `plus_min`,
    /// `minus_max`) stay as they are, still bounds: at worst the chunk is updated and summed
    /// again one step early.
    #[inline]
    fn remove(&mut self, p: &Piece) {
        match p.kind {
            Kind::Stuck => {
                self.rel_integral -= p.rel_integral;
                self.stuck_length -= p.x1 - p.x0;
            }
            Kind::Plus | Kind::Minus => {
                let i = sign_index(p.kind);
                self.slipping[i] -= 1;
                if self.slipping[i] == 0 {
                    // Exactly nothing, not the rounding left by the subtraction.
                    self.slip_length[i] = 0.0;
                    self.slip_cube[i] = 0.0;
                } else {
                    self.slip_length[i] -= p.x1 - p.x0;
                    self.slip_cube[i] -= p.rel_integral;
                }
            }
        }
    }
}

/// The chunks before the last (the frozen ones), summed outwards from a pivot chunk `g`:
/// below it `sums[j]` holds the sums of chunks `0..=j` (chunk 0 first, each one after it added
/// to the sums before it), from it on the sums of chunks `j..n` (`n` frozen chunks, chunk
/// `n − 1` first, each one before it added to the sums after it).
///
/// A step changes mostly one chunk inside the row and the last one (springs entering and
/// leaving contact), and the chunk inside moves slowly: in the compression the stuck centre
/// shrinks by a band of springs a step, in the first chunk; in the restitution at `γ = 3`,
/// `α = 1`, `e_n = 0.9` the slip that starts at the edge of the contact eats into the ~100
/// chunks of stuck bands (each band that slipped and stuck again holds its own state, so they
/// do not merge) from the last of them inwards. Running sums from either end would be tested
/// and added again from the changed chunk to that end, every step (the elastic row's
/// [`crate::continuum::Frozen`] sums from the first chunk on; summed from the last one on,
/// that solve tested about ten chunks a step and added ten running sums again, averaged over
/// its finest level, up to ~95 in the restitution). Here the pivot moves to the first chunk
/// that changed, so a step adds again only the sums between the pivot and the chunks it
/// changed, on both sides (warm solve at γ = 3, α = 1, e_n = 0.9: 15.34 M instructions
/// summed from the end, 13.04 M with the pivot; the other cases of the nine within ±1 %, or
/// less where they had many chunks).
///
/// The step does not visit the frozen chunks that do not change ([`Sums::changes`] is
/// monotone: adding pieces only widens the bounds): before the pivot the first chunk that may
/// change is the first `j` whose `sums[j]` says so (a bisection; once a chunk before the
/// pivot changed, those after it up to the pivot are tested one by one), from the pivot on no
/// chunk from `j` to the last frozen one changes where `sums[j]` says that nothing does.
///
/// A chunk dropped at the end (the truncation in the restitution every few steps) or appended
/// (a full chunk of entering springs in the compression) changes every running sum from the
/// pivot on: they are added again; the sums before it keep their chunks.
///
/// The sums are those of the chunks in another order than from the first one on, so they
/// round otherwise: `P` of `kvbits 1000` moved by at most 1e-15 at 2 973 of its 3 000 values,
/// by up to 5.7e-12 at the others (γ > 3, e_n ≥ 0.89, with [`PEEL`], summed from the end);
/// the pivot moved it again, by at most 1e-15 at 2 975 values, up to 2.1e-12 at the others
/// (γ > 3, e_n ≥ 0.9, five above 1e-13), the steps all the same.
#[derive(Debug, Clone)]
struct RunningSums {
    sums: Vec<Sums>,
    /// The pivot `g`: `sums[j]` sums chunks `0..=j` below it, `j..n` from it on.
    pivot: usize,
    /// From the pivot on, `sums[j]` holds its chunks' sums for `j ≥ valid` (those from the
    /// pivot to `valid` were thawed, and still hold bounds of their chunks: a truncation only
    /// shrinks pieces and drops them, and every other change thaws them).
    valid: usize,
    /// The first frozen chunk this step changed (`usize::MAX`: none yet); the sums below it
    /// are current.
    first: usize,
    /// Whether a frozen chunk or their end changed since the last [`RunningSums::total`].
    stale: bool,
}

impl Default for RunningSums {
    fn default() -> Self {
        RunningSums {
            sums: Vec::new(),
            pivot: 0,
            valid: 0,
            first: usize::MAX,
            stale: false,
        }
    }
}

impl RunningSums {
    /// The number of frozen chunks at the last [`RunningSums::total`] (followed by
    /// [`RunningSums::replaced`]).
    fn len(&self) -> usize {
        self.sums.len()
    }

    /// The first chunk from `k` on that may change (`changes` of its running sums), or the
    /// number of frozen chunks (at the last [`RunningSums::total`], followed by
    /// [`RunningSums::replaced`]) where none of them does: the last chunk is tested by the caller.
    #[inline(always)]
    fn next(&self, k: usize, changes: impl Fn(&Sums) -> bool) -> usize {
        if k < self.pivot {
            return self.next_below(k, changes);
        }
        match self.sums.get(k) {
            Some(s) if !changes(s) => self.sums.len(),
            _ => k,
        }
    }

    /// [`RunningSums::next`] from a chunk `k` before the pivot.
    #[inline]
    fn next_below(&self, k: usize, changes: impl Fn(&Sums) -> bool) -> usize {
        if self.first != usize::MAX {
            // The sums before the pivot were thawed this step: the chunks one by one.
            return k;
        }
        // Before any change: the first `j ≥ k` whose sums from chunk 0 say that it may change
        // (those before `k` said not), else on from the pivot.
        let g = self.pivot;
        let prefix = &self.sums[..g];
        if prefix.last().is_some_and(&changes) {
            return k + prefix[k..].partition_point(|s| !changes(s));
        }
        match self.sums.get(g) {
            Some(s) if !changes(s) => self.sums.len(),
            _ => g,
        }
    }

    /// Chunk `k` was updated into `count` chunks ([`install`]): it and the running sums
    /// between it and the pivot are added again; the others keep their chunks, at indices
    /// moved by the split (`count = 2`) or the removal (`count = 0`). The last chunk is no
    /// frozen one: where it is split or removed, the frozen ones change at their end.
    fn replaced(&mut self, k: usize, count: usize) {
        if k >= self.sums.len() {
            if count != 1 {
                self.end_changed();
            }
            return;
        }
        self.stale = true;
        self.first = self.first.min(k);
        self.valid = self.valid.max(k + 1);
        match count {
            0 => {
                self.sums.remove(k);
                self.valid -= 1;
                if k < self.pivot {
                    self.pivot -= 1;
                }
            }
            2 => {
                self.sums.insert(k + 1, Sums::EMPTY);
                self.valid += 1;
                if k < self.pivot {
                    self.pivot += 1;
                }
            }
            _ => {}
        }
    }

    /// The last frozen chunks changed (chunks dropped by a truncation or appended at the end):
    /// every running sum from the pivot on is added again; the bounds still bound the chunks
    /// that remain.
    fn end_changed(&mut self) {
        self.stale = true;
        self.valid = self.sums.len();
    }

    /// Every chunk's bounds changed (the frames were rewritten): nothing of the running sums
    /// is kept.
    fn clear(&mut self) {
        self.sums.clear();
        self.pivot = 0;
        self.valid = 0;
        self.first = usize::MAX;
        self.stale = true;
    }

    /// After the step: move the pivot to the first frozen chunk that changed (it stays where
    /// none did), sum the frozen chunks again from the current running sums towards it on both
    /// sides, and return the sums of all chunks (the sums before the pivot, those from it on
    /// and the last chunk's, in that order).
    fn total(&mut self, chunks: &[Chunk]) -> Sums {
        if self.stale {
            self.sum_again(chunks);
        }
        let g = self.pivot;
        let below = g.checked_sub(1).and_then(|j| self.sums.get(j));
        let mut all = match (below, self.sums.get(g)) {
            (Some(below), Some(above)) => {
                let mut all = *below;
                all.absorb(above);
                all
            }
            (Some(only), None) | (None, Some(only)) => *only,
            (None, None) => Sums::EMPTY,
        };
        if let Some(last) = chunks.last() {
            all.absorb(&last.sums);
        }
        all
    }

    /// Sum the frozen chunks again where some of them or their end changed (the first part of
    /// [`RunningSums::total`]).
    fn sum_again(&mut self, chunks: &[Chunk]) {
        let n = chunks.len().saturating_sub(1);
        // Before the pivot the sums are current below `first` (and below `n`: chunks dropped
        // at the end take their sums along).
        let current = self.first.min(self.pivot).min(n);
        if self.sums.len() != n {
            self.sums.resize(n, Sums::EMPTY);
            self.valid = n;
        }
        let g = if self.first == usize::MAX {
            self.pivot
        } else {
            self.first
        }
        .min(n);
        // Sums of chunks `0..=j` up to the new pivot.
        if current < g {
            let mut below = current.checked_sub(1).map_or(Sums::EMPTY, |j| self.sums[j]);
            for (j, ch) in chunks.iter().enumerate().take(g).skip(current) {
                below.absorb(&ch.sums);
                self.sums[j] = below;
            }
        }
        // Sums of chunks `j..n` down to it (those from `valid` on are current).
        let start = self.valid.max(g);
        let mut above = self.sums.get(start).copied().unwrap_or(Sums::EMPTY);
        for j in (g..start).rev() {
            above.absorb(&chunks[j].sums);
            self.sums[j] = above;
        }
        self.pivot = g;
        self.valid = g;
        self.first = usize::MAX;
        self.stale = false;
    }
}

/// The uniform relaxation of the slipping springs of one sign: `δ = A δ̃ + B`.
#[derive(Debug, Clone, Copy)]
struct Frame {
    scale: f64,
    shift: f64,
}

impl Frame {
    const IDENTITY: Frame = Frame {
        scale: 1.0,
        shift: 0.0,
    };
    fn actual(&self, stored: f64) -> f64 {
        self.scale * stored + self.shift
    }
}

/// Below this scale the frames are reset at the start of a step (every slipping piece
/// rewritten in the identity frame).
const FRAME_FLOOR: f64 = 1e-100;

/// A relaxation that would take the scale below this rewrites the pieces at once instead.
const FRAME_UNDERFLOW: f64 = 1e-250;

/// What one step does to the pieces: the limit, the end state and the kinematics of the step
/// (for the instants of the transitions inside it).
#[derive(Debug, Clone, Copy)]
struct Update {
    c: f64,
    /// Load at the end of the step `D1` (m).
    load: f64,
    /// `τ ẇ1` (m).
    viscous: f64,
    /// Step `h` (s) and relaxation time `τ` (s).
    h: f64,
    tau: f64,
    /// `ẇ0` (m/s) and `ẅ0` (m/s²): `w` is quadratic over the step.
    vel: f64,
    acc: f64,
    /// `D0` (m), `Ḋ0` (m/s) and the slope `β` (m/s²) of `Ḋ`, linear over the step: `β` the
    /// slope between the end values of `Ḋ = ḋ + τ d̈`, `Ḋ0` such that `∫₀^h Ḋ dt = D1 − D0`
    /// exactly (`D` quadratic through both nodes). Next to first touch `d̈ ∝ −√t` (the viscous
    /// normal force `(3/2) k τ ḋ √d`), where the trapezoid of `Ḋ` errs by `O(h^{3/2})` in the
    /// first step and `O(h³ t^{−3/2})` in later ones: `O(h^{3/2})` in all, kept by the
    /// slipping state shared from first touch ([`ViscoelasticRow::enter`]) and passed to the
    /// whole contact when it sticks again (measured at γ = 2.2, α = 0.98, e_n = 0.3: ratios of
    /// differences 2.8–2.9 from 1 024 to 32 768 steps; 3.96–4.00 with the exact integral).
    load0: f64,
    load_rate0: f64,
    beta: f64,
    /// The frames of the slipping pieces at the start of the step.
    prev: [Frame; 2],
}

impl Update {
    /// `w(h) − w(t)` (m).
    fn w_after(&self, t: f64) -> f64 {
        let h = self.h;
        self.vel * (h - t) + 0.5 * self.acc * (h * h - t * t)
    }

    /// `ẇ(t)` (m/s).
    fn w_rate(&self, t: f64) -> f64 {
        self.vel + self.acc * t
    }

    /// `D(t)` (m).
    fn load_at(&self, t: f64) -> f64 {
        self.load0 + t * (self.load_rate0 + 0.5 * self.beta * t)
    }

    /// `e^{−Δ/τ}` and `1 − e^{−Δ/τ}` (one [`expm1`]).
    fn decay(&self, span: f64) -> (f64, f64) {
        let one_minus = -expm1(-span / self.tau);
        (1.0 - one_minus, one_minus)
    }

    /// `∫_{ta}^{tb} e^{−(tb − t)/τ} Ḋ(t) dt` (m): the relaxation of a slipping spring from
    /// `ta` to `tb` maps `δ ↦ e^{−(tb−ta)/τ} δ − s c ·` this; `decay` is
    /// [`Update::decay`]`(tb − ta)`.
    fn forcing(&self, ta: f64, tb: f64, (e, one_minus): (f64, f64)) -> f64 {
        let (tau, span) = (self.tau, tb - ta);
        (self.load_rate0 + self.beta * tb) * tau * one_minus
            - self.beta * (tau * tau * one_minus - tau * span * e)
    }
}

/// `e^x − 1`: below `|x| = 1/32` (the steps of a solve are much shorter than `τ`) its Taylor
/// polynomial to `x⁹/9!` (the rest below 1e-17 relative), else `f64::exp_m1`. About 20
/// instructions against 80 (a band that starts to slip takes one, a spring that sticks again
/// up to 13); it rounds otherwise, within a few ulp.
#[inline]
fn expm1(x: f64) -> f64 {
    if x.abs() < 1.0 / 32.0 {
        const C: [f64; 8] = [
            1.0 / 2.0,
            1.0 / 6.0,
            1.0 / 24.0,
            1.0 / 120.0,
            1.0 / 720.0,
            1.0 / 5_040.0,
            1.0 / 40_320.0,
            1.0 / 362_880.0,
        ];
        let mut p = C[7];
        for c in C[..7].iter().rev() {
            p = p * x + c;
        }
        // `x (1 + x p)`: `expm1(−0) = −0`, as `exp_m1`.
        x * (1.0 + x * p)
    } else {
        x.exp_m1()
    }
}

/// The cut points of a piece, on the stack: at most four roots `z` (two per quadratic) in the
/// piece's local coordinate.
mod cut_list {
    use std::cmp::Ordering;

    /// At most four values; a fifth is not kept (two quadratics have no more roots).
    #[derive(Debug, Default, Clone, Copy)]
    pub struct Cuts {
        values: [f64; 4],
        len: usize,
    }

    impl Cuts {
        #[inline]
        pub fn push(&mut self, v: f64) {
            if let Some(slot) = self.values.get_mut(self.len) {
                *slot = v;
                self.len += 1;
            }
        }

        /// The heights `z + y_ref` in increasing order (`total_cmp`, as `sort_by`: values
        /// that compare equal are the same bits, so any sort gives the same list): an
        /// insertion sort of at most four.
        #[inline]
        pub fn heights(mut self, y_ref: f64) -> Cuts {
            let v = &mut self.values[..self.len];
            for i in 1..v.len() {
                let mut j = i;
                while j > 0 && v[j - 1].total_cmp(&v[j]) == Ordering::Greater {
                    v.swap(j - 1, j);
                    j -= 1;
                }
            }
            for z in v.iter_mut() {
                *z += y_ref;
            }
            self
        }

        pub fn iter(&self) -> std::slice::Iter<'_, f64> {
            self.values[..self.len].iter()
        }
    }
}

/// The root of `g` on `[0, h]` by the Illinois method, to 1e-6 h (12 iterations at most: an
/// error `ε` in a transition's instant moves the state by O(ε²), `u̇` being continuous across
/// it).
/// 0 when `g(0) ≥ 0`, `h` when `g(h) < 0`.
fn crossing(h: f64, g: impl Fn(f64) -> f64) -> f64 {
    crossing_from(h, (g(0.0), g(h)), g)
}

/// [`crossing`] with `g(0)` and `g(h)` given (evaluated by the caller where it has them
/// cheaper, the same bits).
fn crossing_from(h: f64, (g0, gh): (f64, f64), g: impl Fn(f64) -> f64) -> f64 {
    let (mut lo, mut hi) = (0.0, h);
    let (mut g_lo, mut g_hi) = (g0, gh);
    if g_lo >= 0.0 {
        return 0.0;
    }
    if g_hi < 0.0 {
        return h;
    }
    let mut side = 0;
    for _ in 0..12 {
        let mut t = (lo * g_hi - hi * g_lo) / (g_hi - g_lo);
        if !(t > lo && t < hi) {
            t = 0.5 * (lo + hi);
        }
        let gt = g(t);
        if gt < 0.0 {
            (lo, g_lo) = (t, gt);
            if side == -1 {
                g_hi *= 0.5;
            }
            side = -1;
        } else {
            (hi, g_hi) = (t, gt);
            if side == 1 {
                g_lo *= 0.5;
            }
            side = 1;
        }
        if hi - lo <= 1e-6 * h {
            break;
        }
    }
    0.5 * (lo + hi)
}

/// The first instant in `[0, h]` at which `g(t) = a t² + b t + g0` is no longer negative, as
/// [`crossing`] finds it for a continuous `g`, in closed form: 0 when `g(0) ≥ 0`, `h` when
/// `g(h) < 0`, else the one root in `(0, h]` (where `g` rises through 0: `2at + b ≥ 0`), by
/// the cancellation-free pair `q/a`, `g0/q` with `q = −(b + sgn(b)√(b² − 4a g0))/2`.
fn quadratic_crossing(h: f64, a: f64, b: f64, g0: f64) -> f64 {
    let g = |t: f64| (a * t + b) * t + g0;
    if g0 >= 0.0 {
        return 0.0;
    }
    if g(h) < 0.0 {
        return h;
    }
    let root = (b * b - 4.0 * a * g0).max(0.0).sqrt();
    let q = -0.5 * (b + root.copysign(b));
    [g0 / q, q / a]
        .into_iter()
        .filter(|t| t.is_finite() && (0.0..=h).contains(t) && 2.0 * a * t + b >= 0.0)
        .reduce(f64::min)
        // Rounding at a double root or at an end of the step: the bracketed search.
        .unwrap_or_else(|| crossing(h, g))
}

/// The exact (continuum) Kelvin–Voigt half-row of tangential springs.
#[derive(Debug, Clone)]
pub struct ViscoelasticRow {
    radius: f64,
    tau: f64,
    chunks: Vec<Chunk>,
    /// Accumulated increment `W` (m).
    offset: f64,
    /// Frames of the `+` and `−` slipping pieces.
    frames: [Frame; 2],
    /// Contact reach `b` (m) after the last step: springs with `y < b` are in contact.
    reach: f64,
    /// The stored `δ̃` (`+`, `−`) of the slipping state every spring that enters contact
    /// slipping shares: the relaxation of `δ = −s c τ ḋ₀` from first touch (see
    /// [`ViscoelasticRow::enter`]); `None` before the first step with a finite limit.
    entry: [f64; 2],
    entry_set: bool,
    /// Length of the half-row stuck after the last step (m).
    stuck: f64,
    /// The last step length and its [`Update::decay`] (the grid's steps repeat).
    last_decay: (f64, (f64, f64)),
    /// Whether this step's relaxation forgot the slipping states' start values (the decay
    /// `e^{−h/τ}` underflowed the frames; only for `h ≫ τ`, where that memory is lost anyway).
    memoryless: bool,
    at_limit: (bool, bool),
    spare: Vec<Piece>,
    /// Scratch for the pieces of the springs entering contact in a step.
    entering: Vec<Piece>,
    /// The chunks before the last, summed outwards from a pivot ([`RunningSums`]).
    frozen: RunningSums,
}

impl ViscoelasticRow {
    /// An unloaded row for effective radius `R*` (m) and relaxation time `τ` (s, > 0).
    pub fn new(radius: f64, tau: f64) -> Self {
        Self {
            radius,
            tau,
            chunks: Vec::new(),
            offset: 0.0,
            frames: [Frame::IDENTITY; 2],
            reach: 0.0,
            entry: [0.0; 2],
            entry_set: false,
            stuck: 0.0,
            last_decay: (f64::NAN, (0.0, 0.0)),
            memoryless: false,
            at_limit: (false, false),
            spare: Vec::new(),
            entering: Vec::new(),
            frozen: RunningSums::default(),
        }
    }

    /// Relaxation time `τ` (s).
    pub fn tau(&self) -> f64 {
        self.tau
    }

    /// Length (m) of the half-row that is stuck after the last step.
    pub fn stuck_length(&self) -> f64 {
        self.stuck
    }

    /// Whether some part of the contact slips at the `+` / `−` limit (after the last step).
    pub fn at_limit(&self) -> (bool, bool) {
        self.at_limit
    }

    /// Number of pieces (diagnostics).
    pub fn pieces(&self) -> usize {
        self.chunks.iter().map(|c| c.pieces.len()).sum()
    }

    fn frame(&self, kind: Kind) -> Frame {
        self.frames[sign_index(kind)]
    }

    /// Advance over one step of motion `m` to indentation `d1` with Coulomb limit factor `c`
    /// (`∞`: no slip). Returns `∫₀^a v dx` (m²) at the end of the step and the mean `v`.
    pub fn step(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult {
        let (h, vel, acc) = (m.h, m.slip_velocity, m.slip_accel);
        let tau = self.tau;
        let dw = h * vel + 0.5 * h * h * acc;
        let w_rate1 = vel + h * acc;
        let load1 = d1 + tau * m.rate1;
        let reach0 = self.reach;
        let reach1 = if m.rate1 < 0.0 { load1.max(0.0) } else { d1 };
        let finite = c.is_finite();
        if finite && self.frames[0].scale < FRAME_FLOOR {
            self.reset_frames(c);
        }
        self.memoryless = false;
        if finite && !self.entry_set {
            // First touch: a spring entering slipping has δ = −s c τ ḋ₀ (frames identity).
            let delta = c * tau * m.rate0;
            self.entry = [-delta, delta];
            self.entry_set = true;
        }
        let load0 = m.d0 + tau * m.rate0;
        let beta = (m.rate1 + tau * m.accel1 - (m.rate0 + tau * m.accel0)) / h;
        let load_rate0 = (load1 - load0) / h - 0.5 * beta * h;
        let up = Update {
            c,
            load: load1,
            viscous: tau * w_rate1,
            h,
            tau,
            vel,
            acc,
            load0,
            load_rate0,
            beta,
            prev: self.frames,
        };
        if finite {
            self.relax(&up);
        }
        // Read only where the contact vanishes without a limit.
        let center = if finite {
            0.0
        } else {
            self.center(c, up.load0)
        };
        self.offset += dw;
        let w = self.offset;
        let count = self.chunks.len();
        self.truncate(reach1, c);
        if self.chunks.len() < count {
            self.frozen.end_changed();
        }
        let (t_plus, t_minus) = if finite {
            (c * load1 - w - up.viscous, -c * load1 - w - up.viscous)
        } else {
            (f64::INFINITY, f64::NEG_INFINITY)
        };
        let releases = [
            -up.viscous - self.frames[0].shift,
            -up.viscous - self.frames[1].shift,
        ];
        let frames = self.frames;
        let changes = |s: &Sums| s.changes(&frames, releases, t_plus, t_minus);
        let mut k = self.frozen.next(0, changes);
        while k < self.chunks.len() {
            if changes(&self.chunks[k].sums) {
                let count = self.update_chunk(k, &up, t_plus, t_minus);
                self.frozen.replaced(k, count);
                k += count;
            } else {
                k += 1;
            }
            if k < self.frozen.len() {
                k = self.frozen.next(k, changes);
            }
        }
        if reach1 > reach0 {
            let count = self.chunks.len();
            self.enter(m, (reach0, reach1), &up);
            if self.chunks.len() != count {
                self.frozen.end_changed();
            }
        }
        self.reach = reach1;
        let r = self.radius;
        let all = self.frozen.total(&self.chunks);
        let mut integral = all.rel_integral + (w + up.viscous) * all.stuck_length;
        let stuck = all.stuck_length;
        let (mut any_plus, mut any_minus) = (false, false);
        if finite {
            let lim = |i: usize| c * (load1 * all.slip_length[i] - all.slip_cube[i] / (3.0 * r));
            integral += lim(0) - lim(1);
            any_plus = all.slipping[0] > 0;
            any_minus = all.slipping[1] > 0;
        }
        self.at_limit = (any_plus, any_minus);
        self.stuck = stuck;
        let a1 = (r * reach1).sqrt();
        // Chunks are removed when they empty: pieces exist iff a chunk does.
        let mean = if a1 > 0.0 && !self.chunks.is_empty() {
            integral / a1
        } else if finite {
            0.0
        } else {
            center + dw + up.viscous
        };
        StepResult { integral, mean }
    }

    /// Springs entering contact over the band `y ∈ [b0, b1]` (entry time `θ h`,
    /// `θ = (y − b0)/(b1 − b0)`). A spring enters stuck where `|ẇ| ≤ c ḋ` at its entry (its
    /// force `τ ẇ` within the limit `c τ ḋ` of `y = d`) and then moves with the contact point,
    /// `u = w(h) − w(θh)`. Otherwise it enters slipping with sign `s` of `ẇ`, and
    /// `u = s c (d(t) − y)` solves its relaxation exactly: `δ = −s c τ ḋ(t)`, the same for all
    /// of them at every instant. The row holds that shared state as the relaxation of
    /// `δ = −s c τ ḋ₀` from first touch (second order, like every relaxation of the row), so
    /// that all such springs carry one `δ̃` and their pieces merge, as the limit pieces of the
    /// elastic row do. The entry law switches where `±ẇ = c ḋ` (both linear over the step).
    fn enter(&mut self, m: &StepMotion, (b0, b1): (f64, f64), up: &Update) {
        let (h, vel, acc) = (m.h, m.slip_velocity, m.slip_accel);
        let c = up.c;
        let r = self.radius;
        let w = self.offset;
        let span = b1 - b0;
        let mut cuts = [0.0, 1.0, 1.0, 1.0];
        let mut n = 1;
        if c.is_finite() {
            for sign in [1.0, -1.0] {
                // sign ẇ(θ) − c ḋ(θ) = A + B θ.
                let a0 = sign * vel - c * m.rate0;
                let b = sign * acc * h - c * (m.rate1 - m.rate0);
                if b != 0.0 {
                    let t = -a0 / b;
                    if t > 0.0 && t < 1.0 {
                        cuts[n] = t;
                        n += 1;
                    }
                }
            }
        }
        if n == 1 && self.extend_slipping(m, (b0, b1), up) {
            return;
        }
        let cuts = &mut cuts[..=n];
        cuts[n] = 1.0;
        cuts.sort_by(|a, b| a.total_cmp(b));
        let k1 = h * vel + acc * h * h;
        let k2 = 0.5 * acc * h * h;
        let mut out = std::mem::take(&mut self.entering);
        out.clear();
        for pair in cuts.windows(2) {
            let (t0, t1) = (pair[0], pair[1]);
            if t1 <= t0 {
                continue;
            }
            let (y0, y1) = (b0 + t0 * span, if t1 >= 1.0 { b1 } else { b0 + t1 * span });
            let t = 0.5 * (t0 + t1);
            let w_rate = vel + acc * h * t;
            let bound = c * (m.rate0 + (m.rate1 - m.rate0) * t);
            if c.is_finite() && w_rate.abs() > bound {
                let s = w_rate.signum();
                let kind = if s > 0.0 { Kind::Plus } else { Kind::Minus };
                let abq = (self.entry[sign_index(kind)], 0.0, 0.0);
                let slip = piece(kind, y0, y1, b0, abq, c, r);
                self.release(&slip, up, &mut out, None);
            } else {
                let abq = (k1 - k2 - w, (2.0 * k2 - k1) / span, -k2 / (span * span));
                let stuck = piece(Kind::Stuck, y0, y1, b0, abq, c, r);
                self.clip(&stuck, up, &mut out);
            }
        }
        // Into the last chunk with its sums updated in place (a whole re-summation per step
        // cost about a quarter of a solve in the elastic row), or into a new one once it is
        // full.
        for &p in &out {
            if self
                .chunks
                .last()
                .is_none_or(|ch| ch.pieces.len() >= CHUNK_MAX)
            {
                self.chunks.push(Chunk::fresh());
            }
            if let Some(ch) = self.chunks.last_mut() {
                ch.push(p, c, r);
            }
        }
        self.entering = out;
    }

    /// [`ViscoelasticRow::enter`] where the entry law does not switch within the step (no cut
    /// inside the band) and the whole band enters slipping with the shared entry state, keeps
    /// slipping over the step and continues the last piece of the row (of the same sign, with
    /// the same uniform state, below [`CHUNK_MAX`] pieces in its chunk): that piece is
    /// extended to `b1` and its chunk's sums updated, the same arithmetic as building the
    /// band's piece, releasing it and merging it into the last one ([`Chunk::push`]), at about
    /// a third of the instructions (the compression of a partial slip: every step). Returns
    /// whether it did.
    #[inline]
    fn extend_slipping(&mut self, m: &StepMotion, (b0, b1): (f64, f64), up: &Update) -> bool {
        let c = up.c;
        if !c.is_finite() {
            return false;
        }
        // The band's midpoint θ = 1/2, as in `enter`.
        let t = 0.5;
        let w_rate = m.slip_velocity + m.slip_accel * m.h * t;
        let bound = c * (m.rate0 + (m.rate1 - m.rate0) * t);
        let slips = w_rate.abs() > bound;
        if !slips {
            return false;
        }
        let kind = if w_rate.signum() > 0.0 {
            Kind::Plus
        } else {
            Kind::Minus
        };
        // `δ̃` of the band: its `upper` and `lower` (the test of `release`).
        let a = self.entry[sign_index(kind)];
        let v = self.frame(kind).actual(a) + up.viscous;
        let keeps = if kind == Kind::Plus { v > 0.0 } else { v < 0.0 };
        let r = self.radius;
        let Some(ch) = self.chunks.last_mut() else {
            return false;
        };
        if !keeps || ch.pieces.len() >= CHUNK_MAX {
            return false;
        }
        let Some(last) = ch.pieces.last_mut() else {
            return false;
        };
        // `merges` of the band's piece (`y0 = b0`, `b = q = 0`).
        if !(last.b == 0.0 && last.q == 0.0 && last.kind == kind && last.y1 == b0 && last.a == a) {
            return false;
        }
        let old = *last;
        last.y1 = b1;
        last.x1 = (r * b1).sqrt();
        // `refresh` of a uniform piece: its extremes are `a`, as they were; only the cube.
        last.rel_integral = cube(last);
        ch.replace_last(&old);
        true
    }

    /// How far the chunks' sums have drifted from their pieces (a test of the sums kept by
    /// differences): the largest gaps of `Σ ∫ (u − W) dx` (m²), of the lengths `Σ Δx` (stuck
    /// and per sign, m) and of `Σ Δ(x³)` (per sign, m³) to their recounts, the scales they are
    /// measured against (the largest `Σ |∫ (u − W) dx|` of a chunk, the contact's extent and
    /// its cube), and whether the counts of slipping pieces are exact and every bound still
    /// bounds the pieces.
    #[cfg(test)]
    pub(crate) fn sums_drift(&self) -> ([f64; 3], [f64; 3], bool) {
        let mut gaps = [0.0f64; 3];
        let mut rel_scale = 0.0f64;
        let mut exact = true;
        for ch in &self.chunks {
            let mut recount = Sums::EMPTY;
            for p in &ch.pieces {
                recount.add(p);
            }
            rel_scale = rel_scale.max(
                ch.pieces
                    .iter()
                    .filter(|p| p.kind == Kind::Stuck)
                    .map(|p| p.rel_integral.abs())
                    .sum(),
            );
            let (s, r) = (&ch.sums, &recount);
            gaps[0] = gaps[0].max((s.rel_integral - r.rel_integral).abs());
            gaps[1] = gaps[1].max((s.stuck_length - r.stuck_length).abs());
            for i in 0..2 {
                gaps[1] = gaps[1].max((s.slip_length[i] - r.slip_length[i]).abs());
                gaps[2] = gaps[2].max((s.slip_cube[i] - r.slip_cube[i]).abs());
            }
            exact &= s.slipping == r.slipping
                && s.upper >= r.upper
                && s.lower <= r.lower
                && s.plus_min <= r.plus_min
                && s.minus_max >= r.minus_max;
        }
        let x = self
            .chunks
            .last()
            .and_then(|ch| ch.pieces.last())
            .map_or(0.0, |p| p.x1);
        (gaps, [rel_scale, x, x * x * x], exact)
    }

    /// `u` at the centre (for the no-slip end of contact).
    fn center(&self, c: f64, load: f64) -> f64 {
        let first = self.chunks.first().and_then(|ch| ch.pieces.first());
        first.map_or(0.0, |p| match p.kind {
            Kind::Stuck => self.offset + p.value(0.0),
            Kind::Plus => c * load + self.frames[0].actual(p.value(0.0)),
            Kind::Minus => -c * load + self.frames[1].actual(p.value(0.0)),
        })
    }

    /// The uniform relaxation of every slipping spring over the step:
    /// `δ₁ = E δ₀ − s c ∫₀^h e^{−(h−t)/τ} Ḋ dt`, `E = e^{−h/τ}`, with `Ḋ = ḋ + τ d̈` linear over
    /// the step ([`Update::forcing`]).
    fn relax(&mut self, up: &Update) {
        let decay = self.step_decay(up);
        let e = decay.0;
        let k = -up.c * up.forcing(0.0, up.h, decay);
        if self.frames[0].scale * e < FRAME_UNDERFLOW {
            // Rewrite every slipping piece in the identity frame with its relaxed δ.
            self.rewrite_frames(up.c, e, k);
            self.memoryless = true;
            return;
        }
        for (frame, s) in self.frames.iter_mut().zip([1.0, -1.0]) {
            frame.scale *= e;
            frame.shift = e * frame.shift + s * k;
        }
    }

    /// [`Update::decay`]`(h)`, over the whole step, kept from the last step of the same length
    /// (the grid's steps repeat).
    fn step_decay(&mut self, up: &Update) -> (f64, f64) {
        if up.h != self.last_decay.0 {
            self.last_decay = (up.h, up.decay(up.h));
        }
        self.last_decay.1
    }

    /// Rewrite every slipping piece in the identity frame.
    fn reset_frames(&mut self, c: f64) {
        self.rewrite_frames(c, 1.0, 0.0);
    }

    /// Rewrite every slipping piece (and the entry state) in the identity frame, its actual
    /// `δ` mapped by `δ ↦ e δ + s k` on the way (`e = 1`, `k = 0`: unchanged).
    fn rewrite_frames(&mut self, c: f64, e: f64, k: f64) {
        let frames = self.frames;
        let r = self.radius;
        for ch in &mut self.chunks {
            for p in &mut ch.pieces {
                let (f, s) = match p.kind {
                    Kind::Stuck => continue,
                    Kind::Plus => (frames[0], 1.0),
                    Kind::Minus => (frames[1], -1.0),
                };
                p.a = e * f.actual(p.a) + s * k;
                p.b *= e * f.scale;
                p.q *= e * f.scale;
                refresh(p, c, r);
            }
            ch.summarize();
        }
        self.frozen.clear();
        for (i, s) in [(0, 1.0), (1, -1.0)] {
            self.entry[i] = e * frames[i].actual(self.entry[i]) + s * k;
        }
        self.frames = [Frame::IDENTITY; 2];
    }

    /// Drop everything at `y ≥ top` ([`truncate`]).
    fn truncate(&mut self, top: f64, c: f64) {
        let r = self.radius;
        truncate(&mut self.chunks, top, r, |p| refresh(p, c, r));
    }

    /// Apply the step to chunk `k` (a piece that this step changes is clipped or released,
    /// the others go over as they are); returns the number of chunks that now hold its pieces
    /// (0, 1 or 2: split at [`CHUNK_MAX`] or, after the last changed piece, at [`PEEL`]).
    fn update_chunk(&mut self, k: usize, up: &Update, t_plus: f64, t_minus: f64) -> usize {
        let mut out = std::mem::take(&mut self.spare);
        out.clear();
        let old = std::mem::take(&mut self.chunks[k].pieces);
        let (c, r) = (up.c, self.radius);
        let [plus, minus] = self.frames;
        // A piece that this step leaves as it is: a stuck one within the limits, a slipping one
        // that keeps slipping as a whole (the test of `release`).
        let unchanged = |p: &Piece| match p.kind {
            Kind::Stuck => !(p.upper > t_plus || p.lower < t_minus),
            Kind::Plus => plus.actual(p.lower) + up.viscous > 0.0,
            Kind::Minus => minus.actual(p.upper) + up.viscous < 0.0,
        };
        let mut i = 0;
        let mut changed_end = 0;
        // The number of changed pieces, the last one's index and where its parts start in `out`.
        let mut changes = 0;
        let (mut changed_at, mut changed_start) = (0, 0);
        while let Some(p) = old.get(i) {
            if !unchanged(p) {
                changed_start = out.len();
                if p.kind == Kind::Stuck {
                    self.clip(p, up, &mut out);
                } else {
                    self.release(p, up, &mut out, None);
                }
                changes += 1;
                changed_at = i;
                changed_end = out.len();
                i += 1;
                continue;
            }
            if p.kind == Kind::Stuck {
                out.push(*p);
            } else {
                push_slip(&mut out, *p, c, r);
            }
            // The unchanged pieces after it go over as they are, in one copy, up to the first
            // that `push_slip` would merge into its predecessor. A merged piece agrees with the
            // last piece merged into it in everything that test reads (kind, upper end, zero
            // `b` and `q`, `a`), so comparing with the previous old piece is comparing with
            // the last piece out.
            let rest = &old[i + 1..];
            let mut prev = p;
            let mut run = 0;
            for q in rest {
                if !unchanged(q) || merges(prev, q) {
                    break;
                }
                prev = q;
                run += 1;
            }
            out.extend_from_slice(&rest[..run]);
            i += 1 + run;
        }
        // One stuck piece clipped, no piece merged (`out` holds the others and its parts) and a
        // stuck part kept: the chunk's sums are updated by the difference, in place (the bounds
        // of the clipped piece stay, still bounds); every other way sums the chunk again.
        let mut incremental = false;
        if let (1, Some(p)) = (changes, old.get(changed_at)) {
            let parts = &out[changed_start..changed_end];
            if p.kind == Kind::Stuck
                && out.len() + 1 == old.len() + parts.len()
                && parts.iter().any(|q| q.kind == Kind::Stuck)
            {
                let sums = &mut self.chunks[k].sums;
                sums.remove(p);
                for q in parts {
                    sums.add(q);
                }
                incremental = true;
            }
        }
        self.spare = old;
        // A run of at least `PEEL` unchanged pieces after the last changed one goes to a chunk
        // of its own, after this one (both within `CHUNK_MAX`: `install` keeps this one whole).
        let tail = out.len() - changed_end;
        if changed_end > 0 && tail >= PEEL && changed_end <= CHUNK_MAX && tail <= CHUNK_MAX {
            let rest = out.split_off(changed_end);
            let mut next = Chunk {
                pieces: rest,
                sums: Sums::EMPTY,
            };
            next.summarize();
            self.chunks.insert(k + 1, next);
            return self.install(k, out) + 1;
        }
        if incremental && out.len() <= CHUNK_MAX {
            self.chunks[k].pieces = out;
            return 1;
        }
        self.install(k, out)
    }

    /// A slipping piece: the parts where `s (δ + τ ẇ₁) ≤ 0` stick again (and are clipped
    /// against the limits), the rest keeps slipping. `start` is `δ` at the start of the step
    /// (coefficients in the piece's `z`), `None` for the piece's own, from the frame then.
    ///
    /// A part that sticks again does so at the instant `t*` where `s (δ(t) + τ ẇ(t))` falls to
    /// 0 (at its midpoint); it then moves with the contact point:
    /// `u(h) = s c (D(t*) − y) + δ(t*) + w(h) − w(t*)`. Across `t*` `u̇` is continuous, so
    /// taking the end of the step instead would cost O(h²) locally, coherent over a region
    /// released at once (as the elastic row's release corrections say); with `t*` the local
    /// error is O(h³).
    fn release(
        &mut self,
        p: &Piece,
        up: &Update,
        out: &mut Vec<Piece>,
        start: Option<(f64, f64, f64)>,
    ) {
        let r = self.radius;
        let c = up.c;
        let s = if p.kind == Kind::Plus { 1.0 } else { -1.0 };
        let f = self.frame(p.kind);
        // δ + τẇ₁ in z: (A a + B + τẇ₁) + A b z + A q z².
        let g = |y: f64| f.actual(p.value(y)) + up.viscous;
        let whole = if s > 0.0 {
            f.actual(p.lower) + up.viscous > 0.0
        } else {
            f.actual(p.upper) + up.viscous < 0.0
        };
        if whole {
            push_slip(out, *p, c, r);
            return;
        }
        let start = start.unwrap_or_else(|| {
            let f0 = if self.memoryless {
                f
            } else {
                up.prev[if s > 0.0 { 0 } else { 1 }]
            };
            (f0.actual(p.a), f0.scale * p.b, f0.scale * p.q)
        });
        let mut cuts = cut_list::Cuts::default();
        let (z0, z1) = (p.y0 - p.y_ref, p.y1 - p.y_ref);
        roots_inside(
            f.actual(p.a) + up.viscous,
            f.scale * p.b,
            f.scale * p.q,
            z0,
            z1,
            |r| cuts.push(r),
        );
        let cuts = cuts.heights(p.y_ref);
        let mut lo = p.y0;
        for hi in cuts.iter().copied().chain(std::iter::once(p.y1)) {
            let hi = hi.clamp(lo, p.y1);
            if hi > lo {
                let mid = 0.5 * (lo + hi);
                if s * g(mid) > 0.0 {
                    let keep = piece(p.kind, lo, hi, p.y_ref, (p.a, p.b, p.q), c, r);
                    push_slip(out, keep, c, r);
                } else {
                    let zm = mid - p.y_ref;
                    let delta0 = start.0 + zm * (start.1 + start.2 * zm);
                    // −s (δ(t) + τ ẇ(t)), `decay` = (e^{−t/τ}, 1 − e^{−t/τ}). At the ends of the
                    // step without an `expm1`, the same bits: `decay(0)` is (1, 0) exactly
                    // (`expm1(−0) = −0`), `decay(h)` the step's own (a ninth of the `expm1`
                    // calls of a release at γ = 3, α = 1, e_n = 0.9, where ~800 slip bands
                    // stick again).
                    let rises = |t: f64, decay: (f64, f64)| {
                        -s * (decay.0 * delta0 - s * c * up.forcing(0.0, t, decay)
                            + up.tau * up.w_rate(t))
                    };
                    let step = self.step_decay(up);
                    let ends = (rises(0.0, (1.0, 0.0)), rises(up.h, step));
                    let t = crossing_from(up.h, ends, |t| rises(t, up.decay(t)));
                    let decay = if t == up.h { step } else { up.decay(t) };
                    let e = decay.0;
                    let shift = -s * c * up.forcing(0.0, t, decay);
                    // u − W, in the piece's z.
                    let w = self.offset;
                    let abq = (
                        s * c * (up.load_at(t) - p.y_ref) + e * start.0 + shift + up.w_after(t) - w,
                        -s * c + e * start.1,
                        e * start.2,
                    );
                    let stuck = piece(Kind::Stuck, lo, hi, p.y_ref, abq, c, r);
                    self.clip(&stuck, up, out);
                }
            }
            lo = hi;
        }
    }

    fn install(&mut self, k: usize, pieces: Vec<Piece>) -> usize {
        install(&mut self.chunks, &mut self.spare, k, pieces, CHUNK_MAX)
    }

    /// Clip a stuck piece (after the increment) against `|u + τẇ₁| ≤ c (D₁ − y)`: the parts
    /// outside start to slip with `δ = u − s c (D₁ − y)`.
    fn clip(&mut self, p: &Piece, up: &Update, out: &mut Vec<Piece>) {
        let r = self.radius;
        let c = up.c;
        if p.x1 <= p.x0 {
            return;
        }
        if !c.is_finite() {
            out.push(*p);
            return;
        }
        let w = self.offset;
        let abs_a = p.a + w + up.viscous;
        let lim_ref = c * (up.load - p.y_ref);
        let (z0, z1) = (p.y0 - p.y_ref, p.y1 - p.y_ref);
        let mut cuts = cut_list::Cuts::default();
        roots_inside(abs_a - lim_ref, p.b + c, p.q, z0, z1, |r| cuts.push(r));
        roots_inside(abs_a + lim_ref, p.b - c, p.q, z0, z1, |r| cuts.push(r));
        let cuts = cuts.heights(p.y_ref);
        let mut lo = p.y0;
        for hi in cuts.iter().copied().chain(std::iter::once(p.y1)) {
            let hi = hi.clamp(lo, p.y1);
            if hi > lo {
                let mid = 0.5 * (lo + hi);
                let v = w + up.viscous + p.value(mid);
                let lim = c * (up.load - mid);
                let kind = if v > lim {
                    Kind::Plus
                } else if v < -lim {
                    Kind::Minus
                } else {
                    Kind::Stuck
                };
                let part = match kind {
                    Kind::Stuck if lo == p.y0 && hi == p.y1 => *p,
                    Kind::Stuck => piece(kind, lo, hi, p.y_ref, (p.a, p.b, p.q), c, r),
                    _ => {
                        // The part starts to slip at t* where s (u + τẇ) = c (D − y) (at its
                        // midpoint, along the stuck path u(t) = u(h) − (w(h) − w(t))); there
                        // δ(t*) = u(t*) − s c (D(t*) − y), relaxed from t* to h.
                        // `w` is quadratic over the step and `D` too, so the condition is a
                        // quadratic in t, solved in closed form.
                        let s = if kind == Kind::Plus { 1.0 } else { -1.0 };
                        let u_mid = w + p.value(mid);
                        let h = up.h;
                        let t = quadratic_crossing(
                            h,
                            0.5 * (s * up.acc - c * up.beta),
                            s * (up.vel + up.tau * up.acc) - c * up.load_rate0,
                            s * (u_mid - up.vel * h - 0.5 * up.acc * h * h + up.tau * up.vel)
                                - c * (up.load0 - mid),
                        );
                        let decay = up.decay(up.h - t);
                        let e = decay.0;
                        let shift = -s * c * up.forcing(t, up.h, decay);
                        let lim_t = c * (up.load_at(t) - p.y_ref);
                        let f = self.frame(kind);
                        let abq = (
                            (e * (w + p.a - up.w_after(t) - s * lim_t) + shift - f.shift) / f.scale,
                            e * (p.b + s * c) / f.scale,
                            e * p.q / f.scale,
                        );
                        piece(kind, lo, hi, p.y_ref, abq, c, r)
                    }
                };
                out.push(part);
            }
            lo = hi;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn motion(dw: f64, d0: f64, rate: f64) -> StepMotion {
        StepMotion {
            h: 1.0,
            d0,
            rate0: rate,
            accel0: 0.0,
            slip_velocity: dw,
            slip_accel: 0.0,
            rate1: rate,
            accel1: 0.0,
        }
    }

    #[test]
    fn the_closed_form_slip_start_is_the_root_of_the_condition() {
        // Quadratics over one step with every shape (rising, falling then rising, linear,
        // nearly a double root), against bisection to the last bit; the ends as the bracketed
        // search gives them. (The search stops after 12 iterations: a linear condition can
        // leave it 1.2e-4 h off, where the closed form is exact.)
        let mut rng = oblique_physics::sample::SplitMix(7);
        let mut inside = 0;
        for _ in 0..20_000 {
            let h = 10f64.powf(-4.0 + 2.0 * rng.uniform());
            let scale = 10f64.powf(-3.0 + 3.0 * rng.uniform());
            let a = scale * (rng.uniform() - 0.5) / (h * h);
            let b = scale * (rng.uniform() - 0.3) / h;
            let g0 = scale * (rng.uniform() - 0.7);
            let a = if rng.uniform() < 0.1 { 0.0 } else { a };
            let g = |t: f64| (a * t + b) * t + g0;
            let closed = quadratic_crossing(h, a, b, g0);
            let search = crossing(h, g);
            if g0 >= 0.0 || g(h) < 0.0 {
                assert_eq!(closed, search);
                continue;
            }
            inside += 1;
            let (mut lo, mut hi) = (0.0, h);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if g(mid) < 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            assert!(
                (closed - hi).abs() <= 1e-12 * h,
                "{a} {b} {g0} {h}: {closed} vs {hi}"
            );
        }
        assert!(inside > 2_000, "{inside}");
    }

    #[test]
    fn the_short_expm1_is_exp_m1_to_a_few_ulp() {
        let mut rng = oblique_physics::sample::SplitMix(11);
        for _ in 0..100_000 {
            let x = (rng.uniform() - 0.5) / 16.0 * 10f64.powf(-6.0 * rng.uniform());
            let (got, exact) = (expm1(x), x.exp_m1());
            assert!(
                (got - exact).abs() <= 4.0 * f64::EPSILON * exact.abs(),
                "{x}"
            );
        }
        assert!(expm1(-0.0) == 0.0 && expm1(-0.0).is_sign_negative());
        assert_eq!(expm1(0.5), 0.5f64.exp_m1());
    }

    #[test]
    fn full_slip_carries_the_limit_of_the_load() {
        // Everything slips: v = c (D − y) over y < d (compression), ∫ = c (D a − a³/3).
        let tau = 0.1;
        let mut row = ViscoelasticRow::new(1.0, tau);
        let (d, rate) = (0.49, 0.5);
        let got = row.step(&motion(10.0, 0.0, rate), d, 1.0).integral;
        let (load, a) = (d + tau * rate, d.sqrt());
        let exact = load * a - a * a * a / 3.0;
        assert!((got - exact).abs() < 1e-14, "{got} vs {exact}");
        assert_eq!(row.at_limit(), (true, false));
    }

    #[test]
    fn a_stuck_entry_carries_the_viscous_force() {
        // No slip, one step from d0 = 0 at constant w rate: u = dw (1 − y/d1), v = u + τ ẇ.
        let tau = 0.1;
        let mut row = ViscoelasticRow::new(1.0, tau);
        let d = 0.36;
        let got = row.step(&motion(0.2, 0.0, 0.5), d, f64::INFINITY).integral;
        let exact = 0.2 * 0.6 * (2.0 / 3.0) + tau * 0.2 * 0.6;
        assert!((got - exact).abs() < 1e-15, "{got} vs {exact}");
    }
}
