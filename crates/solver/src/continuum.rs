//! The continuum limit of the MDR row of tangential springs: the displacement field `ũ_x(x)`
//! over the whole contact, exact in space.
//!
//! The spring row ([`super::springs::SpringRow`]) samples `ũ_x` at `N` points, and its error at
//! a thin slip ring (large α, where only the outermost springs ever slip) falls slowly and
//! irregularly with `N`. In the limit `N → ∞` of the same time-stepping rule, every update maps
//! a field that is piecewise quadratic in the profile height `y = g(x) = x²/R*` to another one:
//!
//! - every point in contact receives the same increment `Δw` (a constant);
//! - the Coulomb limits `±c (d − y)` are linear in `y`, so clipping a quadratic piece against
//!   them cuts it at the roots of two quadratics, and a clipped part is the linear limit itself;
//! - a point that enters contact during the step receives `w(h) − w(θ h)` with `θ` linear in
//!   `y` and `w` quadratic in time: a quadratic in `y`;
//! - the release correction of a point at a limit (`super::springs::StepMotion`) is the same
//!   for every point at that limit: a constant.
//!
//! So the field is held exactly as an ordered list of pieces, each a quadratic in `y` (or one of
//! the two limits), and `∫₀^a ũ_x dx` is integrated exactly. The number of pieces grows by at
//! most a few per step (one entry piece per compression step, one cut per moving slip front);
//! adjacent pieces at the same limit merge. The time discretisation is that of the spring row,
//! so this row is the spring row's limit for infinitely many springs: only the time error is
//! left.
//!
//! By symmetry only the half-row `x ≥ 0` is held; integrals are over `[0, a]` and the caller
//! doubles them.

use super::springs::{StepMotion, StepResult};

/// Which law a piece follows (shared with the Kelvin–Voigt row,
/// [`crate::kelvin_voigt::row`], where `Plus`/`Minus` slip with a state of their own).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Stuck: `ũ = W + a + b z + q z²`, `z = y − y_ref`, with `W` the row's accumulated
    /// increment: it moves rigidly with `w`.
    Stuck,
    /// At the `+` Coulomb limit `ũ = c (d − y)`.
    Plus,
    /// At the `−` Coulomb limit `ũ = −c (d − y)`.
    Minus,
}

/// One piece of the field on `y0 ≤ y ≤ y1`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Piece {
    pub(crate) kind: Kind,
    /// Lower and upper profile height (m).
    pub(crate) y0: f64,
    pub(crate) y1: f64,
    /// The matching positions `x = √(R* y)` (m).
    pub(crate) x0: f64,
    pub(crate) x1: f64,
    /// Reference height of the local coordinate `z = y − y_ref` (m).
    pub(crate) y_ref: f64,
    /// Coefficients of a stuck piece `ũ − W = a + b z + q z²` (m, 1, 1/m); unused at a limit
    /// here (the Kelvin–Voigt row keeps a slipping piece's state in them).
    pub(crate) a: f64,
    pub(crate) b: f64,
    pub(crate) q: f64,
    /// `∫ (ũ − W) dx` over a stuck piece (m²); unused at a limit here (the Kelvin–Voigt row
    /// keeps a slipping piece's `x1³ − x0³` in it, m³).
    pub(crate) rel_integral: f64,
    /// `max (ũ − W + c y)` and `min (ũ − W − c y)` over a stuck piece (m): it stays inside the
    /// limits `±c (d − y)` while `upper ≤ c d − W` and `lower ≥ −c d − W`.
    pub(crate) upper: f64,
    pub(crate) lower: f64,
}

/// Three-point Gauss–Legendre nodes on `[0, 1]` and weights: exact for `ũ(x)`, a polynomial
/// of degree 4 in `x`.
pub(crate) const GAUSS: [(f64, f64); 3] = [
    (0.112_701_665_379_258_31, 5.0 / 18.0),
    (0.5, 8.0 / 18.0),
    (0.887_298_334_620_741_7, 5.0 / 18.0),
];

impl Piece {
    /// A stuck piece `ũ − W = a + b z + q z²` on `[y0, y1]`; `c` is the limit factor (for the
    /// bounds).
    fn stuck(y0: f64, y1: f64, y_ref: f64, abq: (f64, f64, f64), c: f64, radius: f64) -> Self {
        let mut p = Self::unrefreshed(y0, y1, y_ref, abq, radius);
        p.refresh(c, radius);
        p
    }

    /// A stuck piece as [`Piece::stuck`] before [`Piece::refresh`]: its integral and bounds
    /// zero, for [`ContinuumRow::clip`] to refresh where it keeps the piece whole.
    fn unrefreshed(y0: f64, y1: f64, y_ref: f64, abq: (f64, f64, f64), radius: f64) -> Self {
        Self {
            kind: Kind::Stuck,
            y0,
            y1,
            x0: (radius * y0).sqrt(),
            x1: (radius * y1).sqrt(),
            y_ref,
            a: abq.0,
            b: abq.1,
            q: abq.2,
            rel_integral: 0.0,
            upper: 0.0,
            lower: 0.0,
        }
    }

    fn limit(kind: Kind, y0: f64, y1: f64, radius: f64) -> Self {
        Self {
            kind,
            y0,
            y1,
            x0: (radius * y0).sqrt(),
            x1: (radius * y1).sqrt(),
            y_ref: y0,
            a: 0.0,
            b: 0.0,
            q: 0.0,
            rel_integral: 0.0,
            upper: 0.0,
            lower: 0.0,
        }
    }

    /// Recompute the integral and the bounds of a stuck piece after its ends changed.
    pub(crate) fn refresh(&mut self, c: f64, radius: f64) {
        let dx = self.x1 - self.x0;
        let total: f64 = GAUSS
            .iter()
            .map(|&(t, w)| {
                let x = self.x0 + t * dx;
                w * self.value(x * x / radius)
            })
            .sum();
        self.rel_integral = total * dx;
        if c.is_finite() {
            // `max (ũ − W + c y)` and `min (ũ − W − c y)`: at an end or at the vertex inside,
            // with `ũ − W` at the ends evaluated once for both.
            let (v0, v1) = (self.value(self.y0), self.value(self.y1));
            let mut upper = (v0 + c * self.y0).max(v1 + c * self.y1);
            let mut lower = (v0 + -c * self.y0).min(v1 + -c * self.y1);
            if self.q != 0.0 {
                let y = self.y_ref - (self.b + c) / (2.0 * self.q);
                if y > self.y0 && y < self.y1 {
                    upper = upper.max(self.value(y) + c * y);
                }
                let y = self.y_ref - (self.b + -c) / (2.0 * self.q);
                if y > self.y0 && y < self.y1 {
                    lower = lower.min(self.value(y) + -c * y);
                }
            }
            self.upper = upper;
            self.lower = lower;
        }
    }

    /// `ũ − W` at height `y` for a stuck piece.
    pub(crate) fn value(&self, y: f64) -> f64 {
        let z = y - self.y_ref;
        self.a + z * (self.b + self.q * z)
    }
}

/// Roots of `A + B z + Q z² = 0` strictly inside `(lo, hi)`, passed to `out` (at most two).
#[inline]
pub(crate) fn roots_inside(a: f64, b: f64, q: f64, lo: f64, hi: f64, mut out: impl FnMut(f64)) {
    let mut push = |r: f64| {
        if r > lo && r < hi {
            out(r);
        }
    };
    if q == 0.0 {
        if b != 0.0 {
            push(-a / b);
        }
        return;
    }
    let disc = b * b - 4.0 * q * a;
    if disc < 0.0 {
        return;
    }
    // Stable form: one root from the quadratic formula without cancellation, the other from
    // the product of the roots (a tiny `q` then gives −a/b and a far-away root).
    let s = -0.5 * (b + disc.sqrt().copysign(b));
    if s != 0.0 {
        push(s / q);
        push(a / s);
    } else {
        push(0.0);
    }
}

/// `*bound = bound.max(v)` for the bounds of a chunk, which only comparisons read: a NaN `v`
/// leaves the bound as `max` does, and where the two differ (the sign of a zero) no comparison
/// tells them apart. A compare and a move instead of `max` and its NaN handling.
#[inline]
pub(crate) fn raise(bound: &mut f64, v: f64) {
    if v > *bound {
        *bound = v;
    }
}

/// `*bound = bound.min(v)`, as [`raise`].
#[inline]
pub(crate) fn lower_to(bound: &mut f64, v: f64) {
    if v < *bound {
        *bound = v;
    }
}

/// Sums over a run of pieces that a step needs.
#[derive(Debug, Clone, Copy)]
struct Sums {
    /// `Σ ∫ (ũ − W) dx` and `Σ Δx` over the stuck pieces (m², m).
    rel_integral: f64,
    stuck_length: f64,
    /// `max upper` and `min lower` over the stuck pieces (m).
    upper: f64,
    lower: f64,
    /// Number of pieces at the `+` and `−` limit.
    slipping: [u32; 2],
    /// `Σ Δx` and `Σ Δ(x³)` over the pieces at the `+` and `−` limit (m, m³): their integral
    /// at indentation `d` is `± c (d Σ Δx − Σ Δ(x³)/(3 R*))`.
    slip_length: [f64; 2],
    slip_cube: [f64; 2],
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
    };

    /// These sums with one more piece.
    #[inline]
    fn with(mut self, p: &Piece) -> Sums {
        let dx = p.x1 - p.x0;
        if p.kind == Kind::Stuck {
            self.rel_integral += p.rel_integral;
            self.stuck_length += dx;
            raise(&mut self.upper, p.upper);
            lower_to(&mut self.lower, p.lower);
        } else {
            let i = usize::from(p.kind == Kind::Minus);
            self.slipping[i] += 1;
            self.slip_length[i] += dx;
            self.slip_cube[i] += dx * (p.x0 * p.x0 + p.x0 * p.x1 + p.x1 * p.x1);
        }
        self
    }

    /// The sums over two runs of pieces.
    #[inline]
    fn merge(self, o: &Sums) -> Sums {
        let (mut upper, mut lower) = (self.upper, self.lower);
        raise(&mut upper, o.upper);
        lower_to(&mut lower, o.lower);
        Sums {
            rel_integral: self.rel_integral + o.rel_integral,
            stuck_length: self.stuck_length + o.stuck_length,
            upper,
            lower,
            slipping: [
                self.slipping[0] + o.slipping[0],
                self.slipping[1] + o.slipping[1],
            ],
            slip_length: [
                self.slip_length[0] + o.slip_length[0],
                self.slip_length[1] + o.slip_length[1],
            ],
            slip_cube: [
                self.slip_cube[0] + o.slip_cube[0],
                self.slip_cube[1] + o.slip_cube[1],
            ],
        }
    }

    /// Whether a run with these sums changes in a step: a slipping piece sticks again
    /// (`resticks`, per sign) or a stuck piece crosses a limit (`upper > t_plus` or
    /// `lower < t_minus`).
    #[inline]
    fn changes(&self, resticks: [bool; 2], t_plus: f64, t_minus: f64) -> bool {
        (self.slipping[0] > 0 && resticks[0])
            || (self.slipping[1] > 0 && resticks[1])
            || self.upper > t_plus
            || self.lower < t_minus
    }

    /// `∫ ũ dx` over the run at indentation `d`, offset `W`, limit factor `c` (every piece
    /// lies below `d`).
    #[inline]
    fn integral(&self, w: f64, c: f64, d: f64, radius: f64) -> f64 {
        let mut total = self.rel_integral + w * self.stuck_length;
        if self.slipping[0] + self.slipping[1] > 0 {
            let slip =
                |i: usize| c * (d * self.slip_length[i] - self.slip_cube[i] / (3.0 * radius));
            total += slip(0) - slip(1);
        }
        total
    }

    /// These sums without a piece they hold (`upper` and `lower` are left as they are: still
    /// bounds).
    #[inline]
    fn without(mut self, p: &Piece) -> Sums {
        let dx = p.x1 - p.x0;
        if p.kind == Kind::Stuck {
            self.rel_integral -= p.rel_integral;
            self.stuck_length -= dx;
        } else {
            let i = usize::from(p.kind == Kind::Minus);
            self.slipping[i] -= 1;
            if self.slipping[i] == 0 {
                // Exactly nothing, not the rounding left by the subtraction.
                self.slip_length[i] = 0.0;
                self.slip_cube[i] = 0.0;
            } else {
                self.slip_length[i] -= dx;
                self.slip_cube[i] -= dx * (p.x0 * p.x0 + p.x0 * p.x1 + p.x1 * p.x1);
            }
        }
        self
    }
}

/// Consecutive pieces with the sums the step needs, so that a chunk of stuck pieces that stays
/// inside the limits costs O(1) per step.
///
/// A piece appended at the outer end (every compression step) or removed or cut there (every
/// restitution step) updates the sums in O(1): added or subtracted, with `upper` and `lower`
/// left as they were on a removal (still bounds, so at worst the chunk is updated and summed
/// again one step early); a chunk whose pieces change inside is summed again.
#[derive(Debug, Clone, Default)]
struct Chunk {
    pieces: Vec<Piece>,
    sums: Sums,
}

impl Default for Sums {
    fn default() -> Self {
        Sums::EMPTY
    }
}

/// Pieces per chunk above which a chunk is split in two.
const CHUNK_MAX: usize = 48;

/// A run of consecutive pieces of a row with the sums a step needs.
pub(crate) trait PieceChunk: Default {
    /// The piece type.
    type Piece;
    /// The pieces, in order.
    fn pieces_mut(&mut self) -> &mut Vec<Self::Piece>;
    /// Recompute the sums after the pieces changed.
    fn summarize(&mut self);
    /// Remove the last piece and update the sums.
    fn remove_last(&mut self) {
        self.pieces_mut().pop();
        self.summarize();
    }
    /// Update the sums after the last piece, `old` before, changed.
    fn replace_last(&mut self, _old: &Self::Piece) {
        self.summarize();
    }
}

impl PieceChunk for Chunk {
    type Piece = Piece;
    fn pieces_mut(&mut self) -> &mut Vec<Piece> {
        &mut self.pieces
    }
    fn summarize(&mut self) {
        self.sums = self.pieces.iter().fold(Sums::EMPTY, Sums::with);
    }
    #[inline]
    fn remove_last(&mut self) {
        if let Some(p) = self.pieces.pop() {
            self.sums = self.sums.without(&p);
        }
    }
    // Every truncation and every merge at the outer end: `#[inline]` alone left it a call.
    #[inline(always)]
    fn replace_last(&mut self, old: &Piece) {
        if let Some(p) = self.pieces.last() {
            self.sums = self.sums.without(old).with(p);
        }
    }
}

/// Drop every part of `chunks` at `y ≥ top` (points leaving contact drop to zero): whole
/// pieces from the end, and the piece across `top` cut there and passed to `refresh`.
pub(crate) fn truncate<C: PieceChunk<Piece = Piece>>(
    chunks: &mut Vec<C>,
    top: f64,
    radius: f64,
    refresh: impl Fn(&mut Piece),
) {
    while let Some(ch) = chunks.last_mut() {
        while ch.pieces_mut().last().is_some_and(|p| p.y0 >= top) {
            ch.remove_last();
        }
        if ch.pieces_mut().is_empty() {
            chunks.pop();
            continue;
        }
        if let Some(p) = ch.pieces_mut().last_mut() {
            if p.y1 > top {
                let old = *p;
                p.y1 = top;
                p.x1 = (radius * top).sqrt();
                refresh(p);
                ch.replace_last(&old);
            }
        }
        break;
    }
}

/// Put `pieces` into chunk `k` of `chunks`, splitting it in two when it holds more than `max`;
/// returns the number of chunks they occupy (0 when empty: the chunk is removed). `spare` is
/// the scratch buffer of the next update.
pub(crate) fn install<C: PieceChunk>(
    chunks: &mut Vec<C>,
    spare: &mut Vec<C::Piece>,
    k: usize,
    mut pieces: Vec<C::Piece>,
    max: usize,
) -> usize {
    let mut count = 1;
    if pieces.len() > max {
        count = 2;
        let tail = pieces.split_off(pieces.len() / 2);
        let mut next = C::default();
        *next.pieces_mut() = tail;
        next.summarize();
        chunks.insert(k + 1, next);
    }
    let ch = &mut chunks[k];
    std::mem::swap(ch.pieces_mut(), &mut pieces);
    // Keep whichever buffer has room as the scratch of the next update: the chunk's old vector
    // was often taken (left empty, without capacity), and dropping the spare instead made every
    // chunk update allocate anew.
    if pieces.capacity() > spare.capacity() {
        *spare = pieces;
    }
    ch.summarize();
    if ch.pieces_mut().is_empty() {
        chunks.remove(k);
        count = 0;
    }
    count
}

/// The first chunks of a row, every one but the last (which the entry piece extends), summed
/// into one `S`: while those sums say that none of them changes in a step, the step neither
/// visits nor integrates them one by one. Shared by the elastic and the Kelvin–Voigt row.
#[derive(Debug, Clone)]
pub(crate) struct Frozen<S> {
    /// Number of frozen chunks.
    count: usize,
    sums: S,
    /// Whether `sums` must be summed again (a frozen chunk changed).
    dirty: bool,
}

impl<S: Clone> Frozen<S> {
    /// No frozen chunk; `empty` is the sums of none.
    pub(crate) fn new(empty: S) -> Self {
        Self {
            count: 0,
            sums: empty,
            dirty: false,
        }
    }

    /// The sums of the frozen chunks.
    pub(crate) fn sums(&self) -> &S {
        &self.sums
    }

    /// The first chunk a step visits: 0 where the frozen sums say that one of them changes
    /// (`changes`), else the first chunk after them.
    pub(crate) fn first_visited(&self, changes: bool) -> usize {
        if changes {
            0
        } else {
            self.count
        }
    }

    /// Chunk `k` changes (or every chunk, `k = 0`): it and those after it leave the frozen
    /// ones.
    pub(crate) fn thaw(&mut self, k: usize) {
        if k < self.count {
            self.count = k;
            self.dirty = true;
        }
    }

    /// After the step: freeze every chunk of `chunks` but the last (summed again from `empty`
    /// where one of them changed, or where the row lost chunks so that a frozen one became
    /// the last) and return the sums of all of them; `add` adds a chunk's sums.
    pub(crate) fn total<C>(&mut self, chunks: &[C], empty: S, add: impl Fn(&mut S, &C)) -> S {
        let last = chunks.len().saturating_sub(1);
        self.thaw(last);
        if self.dirty {
            (self.count, self.sums, self.dirty) = (0, empty, false);
        }
        for ch in &chunks[self.count..last] {
            add(&mut self.sums, ch);
        }
        self.count = last;
        let mut all = self.sums.clone();
        for ch in &chunks[last..] {
            add(&mut all, ch);
        }
        all
    }
}

impl Chunk {
    /// Append one piece ([`push_merged`]) and add it to the sums.
    fn push(&mut self, p: Piece) {
        if p.x1 <= p.x0 {
            return;
        }
        let merged = self
            .pieces
            .last()
            .filter(|last| p.kind != Kind::Stuck && last.kind == p.kind)
            .copied();
        push_merged(&mut self.pieces, p);
        if let Some(old) = merged {
            self.replace_last(&old);
        } else {
            self.sums = self.sums.with(&p);
        }
    }
}

/// The exact (continuum) half-row of tangential springs.
#[derive(Debug, Clone)]
pub struct ContinuumRow {
    radius: f64,
    chunks: Vec<Chunk>,
    /// Accumulated increment `W = Σ Δw` (m), the common offset of the stuck pieces.
    offset: f64,
    spare: Vec<Piece>,
    /// Scratch for the clipped parts of the entry piece.
    entry: Vec<Piece>,
    /// The chunks before the last, summed ([`Frozen`]).
    frozen: Frozen<Sums>,
    at_limit: (bool, bool),
    /// Whether some piece is stuck after the last step.
    stuck: bool,
}

/// What the step does to the pieces: the limit factor, the indentations, the increment and
/// the release corrections.
#[derive(Clone, Copy)]
struct Update {
    c: f64,
    d0: f64,
    d1: f64,
    dw: f64,
    plus: f64,
    minus: f64,
}

impl ContinuumRow {
    /// An unloaded row for effective radius `R*` (m).
    pub fn new(radius: f64) -> Self {
        Self {
            radius,
            chunks: Vec::new(),
            offset: 0.0,
            spare: Vec::new(),
            entry: Vec::new(),
            frozen: Frozen::new(Sums::EMPTY),
            at_limit: (false, false),
            stuck: false,
        }
    }

    /// Append the parts of the entry piece at the outer end of the field: into the last chunk
    /// with its sums updated in place (a whole re-summation per step cost a quarter of the
    /// solve), or into a new chunk once the last one is full.
    fn append(&mut self, parts: &[Piece]) {
        for &p in parts {
            if self
                .chunks
                .last()
                .is_none_or(|ch| ch.pieces.len() >= CHUNK_MAX)
            {
                self.chunks.push(Chunk::default());
            }
            if let Some(ch) = self.chunks.last_mut() {
                ch.push(p);
            }
        }
    }

    /// Whether some part of the contact sits at the `+` / `−` Coulomb limit (after the last
    /// step).
    pub fn at_limit(&self) -> (bool, bool) {
        self.at_limit
    }

    /// Whether some part of the contact is stuck (below both limits) after the last step.
    pub fn stuck(&self) -> bool {
        self.stuck
    }

    /// Number of pieces the field is made of now (diagnostics).
    pub fn pieces(&self) -> usize {
        self.chunks.iter().map(|c| c.pieces.len()).sum()
    }

    /// `ũ` at the centre `y = 0` at indentation `d`.
    fn center(&self, c: f64, d: f64) -> f64 {
        let first = self.chunks.first().and_then(|ch| ch.pieces.first());
        first.map_or(0.0, |p| match p.kind {
            Kind::Stuck => self.offset + p.value(0.0),
            Kind::Plus => c * d,
            Kind::Minus => -c * d,
        })
    }

    /// The continuum form of [`super::springs::SpringRow::step_accurate`]: the same update for
    /// every point of the contact, applied to the whole field at once. Returns `∫₀^a ũ_x dx`
    /// (m²), exact for the field, and the mean displacement over the contact.
    pub fn step_accurate(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult {
        let (d0, h, v, acc) = (m.d0, m.h, m.slip_velocity, m.slip_accel);
        let dw = h * v + 0.5 * h * h * acc;
        let radius = self.radius;
        let finite = c.is_finite();
        // Read only where the contact vanishes without a limit.
        let center = if finite { 0.0 } else { self.center(c, d0) };
        self.offset += dw;
        let w = self.offset;
        self.truncate(d1.max(0.0), c);
        // Slipping pieces stick again (all of one sign at once) when the increment falls
        // behind the limit's own change.
        let resticks = [dw < c * (d1 - d0), -dw < c * (d1 - d0)];
        // The release corrections are read only by the pieces that stick again: computed where
        // the row held pieces of a sign that sticks again after the last step (truncation only
        // removes pieces), else left at zero.
        let (any_plus, any_minus) = self.at_limit;
        let (plus, minus) = if finite && ((any_plus && resticks[0]) || (any_minus && resticks[1])) {
            m.release_corrections(c)
        } else {
            (0.0, 0.0)
        };
        let up = Update {
            c,
            d0,
            d1,
            dw,
            plus,
            minus,
        };
        // Thresholds of the stuck bounds: inside the limits iff upper ≤ c d1 − W and
        // lower ≥ −c d1 − W (never violated without a limit).
        let (t_plus, t_minus) = if finite {
            (c * d1 - w, -c * d1 - w)
        } else {
            (f64::INFINITY, f64::NEG_INFINITY)
        };
        // The frozen chunks are visited only when their sums say that one of them changes.
        let mut k = self
            .frozen
            .first_visited(self.frozen.sums().changes(resticks, t_plus, t_minus));
        while k < self.chunks.len() {
            // Slipping pieces stick again (all of one sign at once) when the increment falls
            // behind the limit's own change; otherwise they stay at the limit and the chunk
            // changes only where a stuck piece crosses a limit.
            k += if self.chunks[k].sums.changes(resticks, t_plus, t_minus) {
                self.frozen.thaw(k);
                self.update_chunk(k, &up, resticks, t_plus, t_minus)
            } else {
                1
            };
        }
        // Points entering contact: ũ = w(h) − w(θh), θ = (y − d0)/(d1 − d0), w quadratic in
        // time: (K1 − K2) + (2K2 − K1) θ − K2 θ², K1 = h v + a h², K2 = a h²/2.
        if d1 > d0 {
            let span = d1 - d0;
            let k1 = h * v + acc * h * h;
            let k2 = 0.5 * acc * h * h;
            let entry = Piece::unrefreshed(
                d0.max(0.0),
                d1,
                d0,
                (k1 - k2 - w, (2.0 * k2 - k1) / span, -k2 / (span * span)),
                radius,
            );
            let mut parts = std::mem::take(&mut self.entry);
            parts.clear();
            self.clip(entry, &up, &mut parts, false);
            self.append(&parts);
            self.entry = parts;
        }
        let total = self
            .frozen
            .total(&self.chunks, Sums::EMPTY, |s, ch| *s = s.merge(&ch.sums));
        let integral = total.integral(w, c, d1, radius);
        let (any_plus, any_minus) = (total.slipping[0] > 0, total.slipping[1] > 0);
        self.stuck = total.stuck_length > 0.0;
        self.at_limit = if finite {
            (any_plus, any_minus)
        } else {
            (false, false)
        };
        let a1 = (radius * d1.max(0.0)).sqrt();
        let mean = if a1 > 0.0 && self.chunks.iter().any(|ch| !ch.pieces.is_empty()) {
            integral / a1
        } else if finite {
            // Contact vanished: the Coulomb limit at the last point in contact is zero.
            0.0
        } else {
            // No slip: the last point carries its displacement to the end.
            center + dw
        };
        StepResult { integral, mean }
    }

    /// Drop everything at `y ≥ top` (points leaving contact drop to zero).
    fn truncate(&mut self, top: f64, c: f64) {
        let radius = self.radius;
        truncate(&mut self.chunks, top, radius, |p| {
            if p.kind == Kind::Stuck {
                p.refresh(c, radius);
            }
        });
    }

    /// Apply the step to every piece of chunk `k` (after the offset moved by `dw`); returns the
    /// number of chunks that now hold its pieces (0, 1 or 2). `resticks` says per sign whether
    /// the slipping pieces stick again.
    fn update_chunk(
        &mut self,
        k: usize,
        up: &Update,
        resticks: [bool; 2],
        t_plus: f64,
        t_minus: f64,
    ) -> usize {
        let radius = self.radius;
        let c = up.c;
        let w = self.offset;
        let mut out = std::mem::take(&mut self.spare);
        out.clear();
        let old = std::mem::take(&mut self.chunks[k].pieces);
        // A piece that this step leaves as it is: a stuck one within the limits, a slipping one
        // that keeps slipping.
        let unchanged = |p: &Piece| match p.kind {
            Kind::Stuck => !(p.upper > t_plus || p.lower < t_minus),
            Kind::Plus => !resticks[0],
            Kind::Minus => !resticks[1],
        };
        let mut i = 0;
        while let Some(&p) = old.get(i) {
            i += 1;
            if !unchanged(&p) {
                if p.kind == Kind::Stuck {
                    self.clip(p, up, &mut out, true);
                } else {
                    // At the limit s c (d0 − y) before the step; it sticks again: the increment
                    // falls behind the limit's own change.
                    let (s, corr) = if p.kind == Kind::Plus {
                        (1.0, up.plus)
                    } else {
                        (-1.0, up.minus)
                    };
                    let a = s * c * (up.d0 - p.y0) + up.dw + corr - w;
                    let stuck = Piece::unrefreshed(p.y0, p.y1, p.y0, (a, -s * c, 0.0), radius);
                    self.clip(stuck, up, &mut out, false);
                }
                continue;
            }
            if p.kind == Kind::Stuck {
                out.push(p);
            } else if p.x1 > p.x0 {
                push_merged(&mut out, p);
            } else {
                // Dropped by `push_merged`: the next piece meets the last one out, not this one.
                continue;
            }
            // The unchanged pieces after it go over as they are, in one copy, up to the first
            // that `push_merged` would drop or merge into its predecessor: the last piece out
            // is the previous old piece, or (merged into it) one of its kind.
            let rest = &old[i..];
            let mut prev = p.kind;
            let mut run = 0;
            for q in rest {
                if !unchanged(q) || (q.kind != Kind::Stuck && (q.x1 <= q.x0 || q.kind == prev)) {
                    break;
                }
                prev = q.kind;
                run += 1;
            }
            out.extend_from_slice(&rest[..run]);
            i += run;
        }
        self.spare = old;
        self.install(k, out)
    }

    /// Put `pieces` into chunk `k` ([`install`]).
    fn install(&mut self, k: usize, pieces: Vec<Piece>) -> usize {
        install(&mut self.chunks, &mut self.spare, k, pieces, CHUNK_MAX)
    }

    /// Clip a stuck piece (after the increment) against the limits `±c (d1 − y)` and append the
    /// parts: stuck where inside, limit pieces where outside. `refreshed`: whether `p` holds its
    /// integral and bounds ([`Piece::refresh`]); if not, they are computed where `p` is kept
    /// whole (only then: the parts of a cut piece are refreshed on their own).
    fn clip(&mut self, p: Piece, up: &Update, out: &mut Vec<Piece>, refreshed: bool) {
        let radius = self.radius;
        let (c, d1) = (up.c, up.d1);
        if p.x1 <= p.x0 {
            return;
        }
        let whole = |mut p: Piece| {
            if !refreshed {
                p.refresh(c, radius);
            }
            p
        };
        if !c.is_finite() {
            out.push(whole(p));
            return;
        }
        // In z = y − y_ref, with a' = a + W: ũ − c(d1 − y) = (a' − c(d1 − y_ref)) + (b + c) z
        // + q z², and ũ + c(d1 − y) = (a' + c(d1 − y_ref)) + (b − c) z + q z².
        let w = self.offset;
        let abs_a = p.a + w;
        let lim_ref = c * (d1 - p.y_ref);
        let (z0, z1) = (p.y0 - p.y_ref, p.y1 - p.y_ref);
        // At most two roots per limit, in a fixed array.
        let mut cuts = [0.0; 4];
        let mut n = 0;
        let mut push = |z: f64| {
            if let Some(slot) = cuts.get_mut(n) {
                *slot = z;
                n += 1;
            }
        };
        roots_inside(abs_a - lim_ref, p.b + c, p.q, z0, z1, &mut push);
        roots_inside(abs_a + lim_ref, p.b - c, p.q, z0, z1, &mut push);
        let cuts = &mut cuts[..n];
        let classify = |y: f64| {
            let u = w + p.value(y);
            let lim = c * (d1 - y);
            if u > lim {
                Kind::Plus
            } else if u < -lim {
                Kind::Minus
            } else {
                Kind::Stuck
            }
        };
        // In increasing order (`total_cmp`, as `sort_by`): an insertion sort of at most four.
        for i in 1..cuts.len() {
            let mut j = i;
            while j > 0 && cuts[j - 1].total_cmp(&cuts[j]).is_gt() {
                cuts.swap(j - 1, j);
                j -= 1;
            }
        }
        let mut lo = p.y0;
        let ends = cuts.iter().map(|z| z + p.y_ref);
        for hi in ends.chain(std::iter::once(p.y1)) {
            let hi = hi.clamp(lo, p.y1);
            if hi > lo {
                let kind = classify(0.5 * (lo + hi));
                let part = if kind != Kind::Stuck {
                    Piece::limit(kind, lo, hi, radius)
                } else if lo == p.y0 && hi == p.y1 {
                    whole(p)
                } else {
                    Piece::stuck(lo, hi, p.y_ref, (p.a, p.b, p.q), c, radius)
                };
                push_merged(out, part);
            }
            lo = hi;
        }
    }
}

/// Append a piece, merging it into the last one when both sit at the same limit.
fn push_merged(out: &mut Vec<Piece>, p: Piece) {
    if p.x1 <= p.x0 {
        return;
    }
    if let Some(last) = out.last_mut() {
        if p.kind != Kind::Stuck && last.kind == p.kind {
            // `Piece::limit(p.kind, last.y0, p.y1, radius)`: a limit piece holds `y_ref = y0`,
            // zero coefficients and sums, and `x = √(R* y)` at both ends, so only its upper end
            // moves, to that of `p`.
            last.y1 = p.y1;
            last.x1 = p.x1;
            return;
        }
    }
    out.push(p);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::springs::motion;

    #[test]
    fn full_slip_integral_is_exact() {
        // Slip everywhere: ũ = c (d − x²), whose integral over [0, √d] is (2/3) c d^{3/2}.
        let mut row = ContinuumRow::new(1.0);
        let d = 0.49;
        let got = row.step_accurate(&motion(10.0, 0.0), d, 1.0).integral;
        let exact = 2.0 / 3.0 * d.powf(1.5);
        assert!((got - exact).abs() < 1e-15, "{got} vs {exact}");
        assert_eq!(row.pieces(), 1);
    }

    #[test]
    fn stuck_entry_integral_is_exact() {
        // No slip, one step from d0 = 0 with constant velocity: ũ = dw (1 − y/d1), whose
        // integral over x ∈ [0, √d1] is dw √d1 (1 − 1/3).
        let mut row = ContinuumRow::new(1.0);
        let d = 0.36;
        let got = row
            .step_accurate(&motion(0.2, 0.0), d, f64::INFINITY)
            .integral;
        let exact = 0.2 * 0.6 * (2.0 / 3.0);
        assert!((got - exact).abs() < 1e-15, "{got} vs {exact}");
    }

    /// Check what the step relies on after every step of a loading and unloading with
    /// reversals: the pieces tile `[0, d]` in order (but for slivers `x1 = x0` that are
    /// dropped, an ulp or so of `y`); a limit piece holds `y_ref = y0`, zero
    /// coefficients and sums and `x = √(R* y)` at both ends (a merge moves only its upper end);
    /// no two neighbours of a chunk sit at the same limit (they would have been merged).
    #[test]
    fn pieces_tile_the_contact_and_limit_pieces_stay_canonical() {
        let radius = 0.7;
        let mut row = ContinuumRow::new(radius);
        let n = 600;
        let (mut d0, mut slipped, mut restuck) = (0.0f64, false, false);
        for i in 1..=n {
            let t = f64::from(i) / f64::from(n);
            let d1 = 0.5 * (std::f64::consts::PI * t).sin();
            // Reversals of the tangential motion while the contact grows and shrinks.
            let dw = 0.004 * (7.0 * std::f64::consts::PI * t).cos();
            row.step_accurate(&motion(dw, d0), d1, 1.0);
            let mut top = 0.0;
            for ch in &row.chunks {
                for (j, p) in ch.pieces.iter().enumerate() {
                    let gap = p.y0 - top;
                    assert!((0.0..=1e-15).contains(&gap), "step {i}: gap {gap}");
                    top = p.y1;
                    if p.kind == Kind::Stuck {
                        restuck |= slipped;
                        continue;
                    }
                    slipped = true;
                    assert_eq!(p.y_ref, p.y0, "step {i}");
                    assert_eq!((p.a, p.b, p.q), (0.0, 0.0, 0.0), "step {i}");
                    assert_eq!((p.rel_integral, p.upper, p.lower), (0.0, 0.0, 0.0));
                    assert_eq!(p.x0, (radius * p.y0).sqrt(), "step {i}");
                    assert_eq!(p.x1, (radius * p.y1).sqrt(), "step {i}");
                    if j > 0 {
                        assert_ne!(ch.pieces[j - 1].kind, p.kind, "step {i}: unmerged");
                    }
                }
            }
            let short = d1.max(0.0) - top;
            assert!(
                (0.0..=1e-15).contains(&short),
                "step {i}: ends {short} short"
            );
            d0 = d1;
        }
        assert!(slipped && restuck, "the motion must slip and stick again");
    }

    #[test]
    fn clipping_cuts_a_piece_at_the_limit() {
        // Stuck entry with ũ = dw (1 − y/d1) against c (d1 − y) with c d1 < dw: everything at
        // the + limit.
        let mut row = ContinuumRow::new(1.0);
        row.step_accurate(&motion(1.0, 0.0), 0.25, 1.0);
        assert_eq!(row.pieces(), 1);
        assert_eq!(row.at_limit(), (true, false));
        // Reverse: the centre part sticks (ũ = c(d − y) − δ), the edge slips to −c(d − y).
        let r = row.step_accurate(&motion(-0.2, 0.25), 0.25, 1.0);
        assert_eq!(row.pieces(), 2);
        // Stuck where c(d − y) − 0.2 ≥ −c(d − y), i.e. y ≤ d − 0.1 = 0.15.
        let (ys, a1) = (0.15f64, 0.5f64);
        let xs = ys.sqrt();
        let stuck = 0.25 * xs - xs.powi(3) / 3.0 - 0.2 * xs;
        let slip = -(0.25 * (a1 - xs) - (a1.powi(3) - xs.powi(3)) / 3.0);
        assert!((r.integral - (stuck + slip)).abs() < 1e-14);
    }
}
