//! The field of [`super::ThorntonRow`]: its pieces, the Coulomb limit of one instant, the
//! chunks a step visits, and the root finding and merging they share.

use super::super::line::Truncated;
use crate::continuum::GAUSS;

/// Which law a piece follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Kind {
    /// Stuck: `ũ = W + a + b z + q z² + k Q(D_f − y)`.
    Stuck,
    /// At the `+` limit `ũ = c Λ(y)`.
    Plus,
    /// At the `−` limit `ũ = −c Λ(y)`.
    Minus,
}

/// One piece of the field on `y0 ≤ y ≤ y1`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Piece {
    pub(super) kind: Kind,
    pub(super) y0: f64,
    pub(super) y1: f64,
    pub(super) x0: f64,
    pub(super) x1: f64,
    pub(super) y_ref: f64,
    pub(super) a: f64,
    pub(super) b: f64,
    pub(super) q: f64,
    /// Factor of the curved part `k Q(D_f − y)` (0: none).
    pub(super) k: f64,
    /// `D_f` of the curved part (m).
    pub(super) top: f64,
    /// `∫ (ũ − W) dx` over a stuck piece (m²).
    pub(super) rel: f64,
    /// Bounds of `ũ − W` over a stuck piece: `lo ≤ ũ − W ≤ hi`.
    pub(super) lo: f64,
    pub(super) hi: f64,
    /// `upper ≥ max (ũ − W + s y)` and `lower ≤ min (ũ − W − s y)` over a stuck piece for the
    /// limit slope `s = slope` (NaN until computed): it is inside the linear limits
    /// `±s (D − y)` while `upper ≤ s D − W` and `lower ≥ −s D − W`.
    pub(super) upper: f64,
    pub(super) lower: f64,
    pub(super) slope: f64,
    /// The curved part `k Q(D_f − y)` of a stuck piece at `y0`, `y1` and the middle, and its
    /// slope in `y` at the middle (zeros where `k = 0`): what its range and bounds need, kept
    /// so that bounding a piece for a new slope takes no arctangent.
    pub(super) curve: [f64; 4],
    /// While the limits only grow (loading): the offsets `W` up to which a stuck piece stays
    /// inside the `+` limit (`W ≤ caps[0]`) and the `−` limit (`−W ≤ caps[1]`), measured
    /// against the limit of one step (NaN until measured; [`Chunk::measure`]).
    pub(super) caps: [f64; 2],
}

impl Piece {
    /// A stuck piece; a curved part that is linear over the piece (`D_f − y0 ≤ d_y`) is folded
    /// into the quadratic.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn stuck(
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
        let mut p = Piece {
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
            curve: [0.0; 4],
            caps: [f64::NAN; 2],
        };
        p.refresh(line, radius);
        p
    }

    pub(super) fn limit(kind: Kind, y0: f64, y1: f64, radius: f64) -> Self {
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
            curve: [0.0; 4],
            caps: [f64::NAN; 2],
        }
    }

    /// The same piece on `[y0, y1]` (a stuck one with its sums recomputed).
    pub(super) fn part(&self, y0: f64, y1: f64, line: &Truncated, radius: f64) -> Self {
        let mut p = Piece {
            y0,
            y1,
            x0: (radius * y0).sqrt(),
            x1: (radius * y1).sqrt(),
            slope: f64::NAN,
            ..*self
        };
        if p.kind == Kind::Stuck {
            p.refresh(line, radius);
        }
        p
    }

    /// Compute a stuck piece's integral and range (in place: a `Piece` is large to copy).
    pub(super) fn refresh(&mut self, line: &Truncated, radius: f64) {
        self.caps = [f64::NAN; 2];
        self.curve = if self.k == 0.0 {
            [0.0; 4]
        } else {
            let ym = 0.5 * (self.y0 + self.y1);
            [
                self.k * line.value(self.top - self.y0),
                self.k * line.value(self.top - self.y1),
                self.k * line.value(self.top - ym),
                -self.k * line.slope(self.top - ym),
            ]
        };
        self.rel = self.integral(line, radius);
        (self.lo, self.hi) = self.range();
        self.slope = f64::NAN;
    }

    /// A stuck piece with its bounds for the limit slope `s` ([`Piece::upper`]).
    pub(super) fn bounded(mut self, s: f64) -> Self {
        (self.upper, self.lower) = self.bounds(s);
        self.slope = s;
        self
    }

    /// `(upper, lower)` of [`Piece::upper`] for the limit slope `s`.
    pub(super) fn bounds(&self, s: f64) -> (f64, f64) {
        // The curved part k Q(D_f − y) between two lines: its chord and its tangent at the
        // middle (Q(D_f − y) is concave in y; k < 0 swaps them).
        let (cu, cl) = if self.k == 0.0 {
            ((0.0, 0.0), (0.0, 0.0))
        } else {
            let (y0, y1) = (self.y0, self.y1);
            let ym = 0.5 * (y0 + y1);
            let [v0, v1, vm, t_slope] = self.curve;
            let chord_slope = if y1 > y0 { (v1 - v0) / (y1 - y0) } else { 0.0 };
            let chord = (v0 - chord_slope * (y0 - self.y_ref), chord_slope);
            let tangent = (vm - t_slope * (ym - self.y_ref), t_slope);
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
        (
            ext(self.a + cu.0 + y_ref_term, self.b + cu.1 + s, true),
            ext(self.a + cl.0 - y_ref_term, self.b + cl.1 - s, false),
        )
    }

    /// `ũ − W` of a stuck piece at `y`.
    pub(super) fn value(&self, y: f64, line: &Truncated) -> f64 {
        let z = y - self.y_ref;
        let quad = self.a + z * (self.b + self.q * z);
        if self.k == 0.0 {
            quad
        } else {
            quad + self.k * line.value(self.top - y)
        }
    }

    /// `ũ − W` of a stuck piece at `y0` and at `y1`: [`Piece::value`] there, the curved part
    /// taken from [`Piece::curve`] (the same doubles, without its arctangents).
    pub(super) fn end_values(&self) -> (f64, f64) {
        let at = |y: f64, curved: f64| {
            let z = y - self.y_ref;
            let quad = self.a + z * (self.b + self.q * z);
            if self.k == 0.0 {
                quad
            } else {
                quad + curved
            }
        };
        (at(self.y0, self.curve[0]), at(self.y1, self.curve[1]))
    }

    /// `∫ (ũ − W) dx` over a stuck piece (m²).
    pub(super) fn integral(&self, line: &Truncated, radius: f64) -> f64 {
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

    /// Bounds `(min, max)` of `ũ − W` over a stuck piece (its curved part's values kept in
    /// [`Piece::curve`]).
    pub(super) fn range(&self) -> (f64, f64) {
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
            let (u, v) = (self.curve[0], self.curve[1]);
            lo += u.min(v);
            hi += u.max(v);
        }
        (lo, hi)
    }
}

/// The Coulomb limit at one instant: `c_κ Λ(y) = c_κ Q(D − y)`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Limit {
    /// `c κ`: `c` in loading, `c/ρ` in unloading.
    pub(super) c: f64,
    /// The reach `D` (m): `d` in loading, `ρ (d − d_p)` in Thornton's unloading, `d_max` in
    /// the MDR unloading.
    pub(super) reach: f64,
    /// The uniform shortening `σ` of every spring (m): `d_max − d` in the MDR unloading, 0
    /// elsewhere; the limit is `c_κ (Q(D − y) − σ)`.
    pub(super) shift: f64,
    /// The line density's truncation (none in unloading).
    pub(super) line: Truncated,
}

impl Limit {
    pub(super) fn at(&self, y: f64) -> f64 {
        self.c * (self.line.value(self.reach - y) - self.shift)
    }

    /// The profile height where the limit falls to 0: the contact's edge.
    pub(super) fn edge(&self) -> f64 {
        if self.shift > 0.0 {
            (self.reach - self.line.inverse(self.shift)).max(0.0)
        } else {
            self.reach
        }
    }

    /// Whether the limit is linear in `y` from `y0` on (`D − y0 ≤ d_y`).
    pub(super) fn linear_from(&self, y0: f64) -> bool {
        self.reach - y0 <= self.line.yield_indentation
    }

    /// `∫ c_κ Λ dx` over `[x0, x1]` (m²).
    pub(super) fn integral(&self, x0: f64, x1: f64, radius: f64) -> f64 {
        self.c
            * (self.line.integral(self.reach, x1, radius)
                - self.line.integral(self.reach, x0, radius)
                - self.shift * (x1 - x0))
    }
}

/// Pieces per chunk above which a chunk is split.
pub(super) const CHUNK_MAX: usize = 24;

/// Consecutive pieces with the sums a step needs.
#[derive(Debug, Clone, Default)]
pub(super) struct Chunk {
    pub(super) pieces: Vec<Piece>,
    /// Over the stuck pieces: `Σ Δx`, `Σ ∫ (ũ − W) dx`, `min lo`, `max hi`, `max upper`,
    /// `min lower` (the bounds for the limit slope `slope`).
    pub(super) stuck_length: f64,
    pub(super) rel: f64,
    pub(super) lo: f64,
    pub(super) hi: f64,
    pub(super) upper: f64,
    pub(super) lower: f64,
    pub(super) slope: f64,
    /// Whether some piece is at the `+` / `−` limit (exact: the row's limits held are read
    /// from it).
    pub(super) signs: [bool; 2],
    /// The smallest [`Piece::caps`] of the stuck pieces (NaN while one is not measured): while
    /// the limits only grow (loading), the chunk is inside them as long as `W ≤ caps[0]` and
    /// `−W ≤ caps[1]`.
    pub(super) caps: [f64; 2],
}

impl Chunk {
    /// The chunk of `pieces` with its sums, the stuck pieces bounded for the slope `s`.
    pub(super) fn new(pieces: Vec<Piece>, s: f64) -> Self {
        let mut ch = Chunk::empty(s);
        ch.pieces = pieces;
        ch.count_from(0);
        ch
    }

    /// A chunk without pieces, for the limit slope `s`.
    pub(super) fn empty(s: f64) -> Self {
        Chunk {
            stuck_length: 0.0,
            rel: 0.0,
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
            upper: f64::NEG_INFINITY,
            lower: f64::INFINITY,
            slope: s,
            signs: [false, false],
            caps: [f64::INFINITY; 2],
            pieces: Vec::new(),
        }
    }

    /// Add the shares of the pieces from index `from` on to the sums (those before counted).
    pub(super) fn count_from(&mut self, from: usize) {
        let mut pieces = std::mem::take(&mut self.pieces);
        for p in pieces.iter_mut().skip(from) {
            self.count(p);
        }
        self.pieces = pieces;
    }

    /// Add a piece's share to the sums (a stuck piece bounded for the chunk's slope first).
    #[inline]
    pub(super) fn count(&mut self, p: &mut Piece) {
        if p.kind == Kind::Stuck {
            if p.slope != self.slope {
                if self.slope.is_finite() {
                    *p = p.bounded(self.slope);
                } else {
                    // Without slip (`c = ∞`) no limit is ever tested: no bounds to compute.
                    p.slope = self.slope;
                }
            }
            self.stuck_length += p.x1 - p.x0;
            self.rel += p.rel;
            self.lo = self.lo.min(p.lo);
            self.hi = self.hi.max(p.hi);
            self.upper = self.upper.max(p.upper);
            self.lower = self.lower.min(p.lower);
            self.caps = low_caps(self.caps, p.caps);
        } else {
            self.signs[usize::from(p.kind == Kind::Minus)] = true;
        }
    }

    /// Append `p` ([`push_merged`]) with its share of the sums: the same chunk as
    /// [`Chunk::new`] of all its pieces, without visiting the others.
    pub(super) fn append(&mut self, p: Piece) {
        let n = self.pieces.len();
        push_merged(&mut self.pieces, p);
        if self.pieces.len() > n {
            let mut last = self.pieces[n];
            self.count(&mut last);
            self.pieces[n] = last;
        }
    }

    /// Whether some piece is at a limit.
    pub(super) fn has_limits(&self) -> bool {
        self.signs[0] || self.signs[1]
    }

    /// Whether the step may change the chunk: it holds a piece at a limit of a sign whose
    /// springs may stick again in the step (`release`, `+` and `−`), or its stuck pieces may
    /// cross the limit `lim` with the offset `w` (`grow`: the limits have only grown since the
    /// chunk's margins were measured).
    #[inline]
    pub(super) fn changes(&mut self, lim: &Limit, w: f64, release: [bool; 2], grow: bool) -> bool {
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
        // Caps measured while the limits grow: O(1) a step.
        if grow && inside(self.caps, w) {
            return false;
        }
        let floor = lim.at(last.y1);
        if w + self.hi < floor && w + self.lo > -floor {
            return false;
        }
        if !grow {
            return true;
        }
        self.measure(lim, w);
        !inside(self.caps, w)
    }

    /// Measure the caps ([`Piece::caps`]) of the stuck pieces that have none or whose caps the
    /// offset `w` passes against `±lim` (the limits have grown since), and the chunk's: for
    /// each, its bounds against the limit's line (a linear limit) or chord (a curved one, which
    /// is above its chord).
    #[inline(never)]
    pub(super) fn measure(&mut self, lim: &Limit, w: f64) {
        let mut caps = [f64::INFINITY; 2];
        // The limit at the last piece's end, where the next piece mostly starts.
        let mut last = (f64::NAN, f64::NAN);
        let mut at = |y: f64| {
            if y != last.0 {
                last = (y, lim.at(y));
            }
            last.1
        };
        for p in self.pieces.iter_mut().filter(|p| p.kind == Kind::Stuck) {
            if !inside(p.caps, w) {
                let ((upper, lower), top) = if lim.linear_from(p.y0) {
                    let b = if p.slope == lim.c {
                        (p.upper, p.lower)
                    } else {
                        p.bounds(lim.c)
                    };
                    (b, lim.c * (lim.reach - lim.shift))
                } else {
                    let l0 = at(p.y0);
                    let floor = at(p.y1);
                    let span = p.y1 - p.y0;
                    let s = if span > 0.0 { (l0 - floor) / span } else { 0.0 };
                    (p.bounds(s), floor + s * p.y1)
                };
                // Inside while ũ − W + W ≤ L: W ≤ top − upper, and −W ≤ top + lower.
                p.caps = [top - upper, top + lower];
            }
            caps = low_caps(caps, p.caps);
        }
        self.caps = caps;
    }
}

/// Whether the offset `w` is within the caps ([`Chunk::caps`]; false while one is NaN).
fn inside(caps: [f64; 2], w: f64) -> bool {
    w <= caps[0] && -w <= caps[1]
}

/// The smaller of two caps, each side, NaN where either is NaN.
fn low_caps(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    let low = |u: f64, v: f64| {
        if u.is_nan() || v.is_nan() {
            f64::NAN
        } else {
            u.min(v)
        }
    };
    [low(a[0], b[0]), low(a[1], b[1])]
}

/// Halvings of a stretch between kinks past which [`crossings`] stops refining: a part
/// `2⁻⁴⁰` of the stretch wide is judged by the signs at its ends.
pub(super) const DEPTH: u32 = 40;

/// Evaluations of the gap per stretch past which [`crossings`] stops refining (the parts left
/// are judged by the signs at their ends): a gap that stays within its rounding of zero over a
/// wide range would otherwise be split down to [`DEPTH`] everywhere.
pub(super) const BUDGET: usize = 256;

/// The height `y` where `g(y) = c_κ Q′(D − y) Ḋ − u` changes sign (`u = s ẇ`), NaN where it
/// does not inside the curved part (`Q′(σ) = (2/π) arcsin √(d_y/σ) = u/(c_κ Ḋ)`, so
/// `σ = d_y / sin²(π r/2)`).
pub(super) fn front(lim: &Limit, rate: f64, u: f64) -> f64 {
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

/// The sign changes of `f` inside `(y0, y1)`, appended to `out`, on each stretch between the
/// `kinks` (where `f` is smooth), decided by the bounds `curvature(a, b) = (min, max)` of `f″`
/// on `(a, b)` rather than by sampling, so that a zone where `f` changes sign twice between two
/// points is not missed however narrow it is (down to `2⁻⁴⁰` of the stretch, [`DEPTH`]):
///
/// - where `f″ ≤ 0` (concave) the ends' signs decide, except where `f ≤ 0` at both ends: there
///   `f` may rise above 0 between two crossings, and the stretch is halved until a point with
///   `f > 0` brackets both, or the bound of a concave `f` by its neighbouring chords (and first
///   `f ≤ chord + |min f″| (y − a)(b − y)/2`) shows `f ≤ 0` on every part ([`Search::rise`]); where
///   `f″ ≥ 0` (convex) the same for `−f`;
/// - where `f″` takes both signs the stretch is halved until each part is convex or concave,
///   or `f` keeps its sign between the chord ± `max |f″| (y − a)(b − y)/2`, or a part is
///   `2⁻⁴⁰` of the stretch wide (judged by its ends).
///
/// Each bracket is closed to the rounding ([`bisect`]); exact zeros met inside `(y0, y1)` are
/// kept as they are. At most [`BUDGET`] evaluations of `f` per stretch refine it. The ends come
/// with their values, `(y0, f(y0))` and `(y1, f(y1))`, which the caller mostly has at hand.
pub(super) fn crossings(
    f: &dyn Fn(f64) -> f64,
    curvature: &dyn Fn(f64, f64) -> (f64, f64),
    (y0, f0): (f64, f64),
    (y1, f1): (f64, f64),
    kinks: &[f64],
    out: &mut Vec<f64>,
) {
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
    let mut start = (y0, f0);
    for pair in ends.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if b <= a {
            continue;
        }
        let end = (b, if b == y1 { f1 } else { f(b) });
        let mut search = Search {
            f,
            curvature,
            budget: BUDGET,
            out: &mut *out,
        };
        search.stretch(start, end, 0);
        start = end;
        if end.1 == 0.0 && b < y1 {
            out.push(b);
        }
    }
}

/// Whether `u` and `v` have strictly opposite signs.
fn differ(u: f64, v: f64) -> bool {
    (u < 0.0 && v > 0.0) || (u > 0.0 && v < 0.0)
}

/// `max` over `t ∈ [0, 1]` of `u + (v − u) t + w t (1 − t)` (`w ≥ 0`): the largest value of a
/// function from `u` to `v` on a stretch `h` wide whose second derivative is at least
/// `−2w/h²`.
fn peak(u: f64, v: f64, w: f64) -> f64 {
    if w <= 0.0 {
        return u.max(v);
    }
    if !w.is_finite() {
        // Unbounded (or unknown) curvature: no bound.
        return f64::INFINITY;
    }
    let t = (0.5 + (v - u) / (2.0 * w)).clamp(0.0, 1.0);
    u + (v - u) * t + w * t * (1.0 - t)
}

/// An upper bound of a concave `g` on `[l, r]` from `g(l) = gl`, `g(r) = gr` and the slopes
/// `sl` of its chord on the part just left of `l` and `sr` of the one just right of `r`
/// (`+∞` and `−∞`: none): a concave function lies below each of its chords extended, so
/// `g(y) ≤ min(gl + sl (y − l), gr + sr (y − r))`.
fn cap(l: f64, gl: f64, r: f64, gr: f64, sl: f64, sr: f64) -> f64 {
    let h = r - l;
    match (sl.is_finite(), sr.is_finite()) {
        (false, false) => f64::INFINITY,
        (true, false) => gl.max(gl + sl * h),
        (false, true) => gr.max(gr - sr * h),
        (true, true) => {
            let mut best = gl.min(gr - sr * h).max((gl + sl * h).min(gr));
            if sl > sr {
                // Where the two lines meet.
                let y = (gr - gl + sl * l - sr * r) / (sl - sr);
                if y > l && y < r {
                    best = best.max(gl + sl * (y - l));
                }
            }
            best
        }
    }
}

/// The search of one smooth stretch of [`crossings`].
struct Search<'a> {
    f: &'a dyn Fn(f64) -> f64,
    curvature: &'a dyn Fn(f64, f64) -> (f64, f64),
    /// Evaluations of `f` left for refining.
    budget: usize,
    out: &'a mut Vec<f64>,
}

impl Search<'_> {
    /// The middle of `[l, r]` and `f` there (an exact zero kept), `None` where the part is not
    /// to be halved: `depth` halvings already, the budget spent, or no double between its ends.
    fn split(&mut self, l: f64, r: f64, depth: u32) -> Option<(f64, f64)> {
        if depth >= DEPTH || self.budget == 0 {
            return None;
        }
        let m = 0.5 * (l + r);
        if !(m > l && m < r) {
            return None;
        }
        self.budget -= 1;
        let fm = (self.f)(m);
        if fm == 0.0 {
            self.out.push(m);
        }
        Some((m, fm))
    }

    /// The sign changes inside the smooth part from `l = (y, f(y))` to `r`, `depth` halvings
    /// into its stretch.
    fn stretch(&mut self, l: (f64, f64), r: (f64, f64), depth: u32) {
        let (low, high) = (self.curvature)(l.0, r.0);
        if high <= 0.0 {
            self.hump(1.0, l, r, low, depth);
            return;
        }
        if low >= 0.0 {
            self.hump(-1.0, l, r, -high, depth);
            return;
        }
        // f″ of both signs (or unbounded): f lies between the chord ± the parabolas of its
        // bounds.
        let h = r.0 - l.0;
        let h2 = 0.5 * h * h;
        let below = l.1 <= 0.0 && r.1 <= 0.0 && peak(l.1, r.1, -low * h2) <= 0.0;
        let above = l.1 >= 0.0 && r.1 >= 0.0 && peak(-l.1, -r.1, high * h2) <= 0.0;
        if below || above {
            return;
        }
        match self.split(l.0, r.0, depth) {
            Some(m) => {
                self.stretch(l, m, depth + 1);
                self.stretch(m, r, depth + 1);
            }
            None => {
                if differ(l.1, r.1) {
                    self.out.push(bisect(self.f, l, r));
                }
            }
        }
    }

    /// The sign changes on a part where `g = sign · f` is concave with `g″ ≥ low`: one where
    /// the ends differ in sign, none where `g ≥ 0` at both (`g` is above its chord), and
    /// otherwise two or none, as [`Search::rise`] finds.
    fn hump(&mut self, sign: f64, l: (f64, f64), r: (f64, f64), low: f64, depth: u32) {
        let (gl, gr) = (sign * l.1, sign * r.1);
        if differ(gl, gr) {
            self.out.push(bisect(self.f, l, r));
            return;
        }
        if gl >= 0.0 && gr >= 0.0 {
            return;
        }
        let h = r.0 - l.0;
        if peak(gl, gr, -low * 0.5 * h * h) <= 0.0 {
            return;
        }
        self.rise(sign, l, r, (f64::INFINITY, f64::NEG_INFINITY), depth);
    }

    /// Look for a point where the concave `g = sign · f` (`≤ 0` at both ends of `[l, r]`) is
    /// positive, halving the parts where its bound by the neighbouring chords (`slopes`,
    /// [`cap`]) is positive; found, the crossings on both sides of it are bracketed (one each:
    /// `{g > 0}` is an interval) and `true` returned.
    fn rise(
        &mut self,
        sign: f64,
        l: (f64, f64),
        r: (f64, f64),
        (sl, sr): (f64, f64),
        depth: u32,
    ) -> bool {
        let (gl, gr) = (sign * l.1, sign * r.1);
        if cap(l.0, gl, r.0, gr, sl, sr) <= 0.0 {
            return false;
        }
        let Some(m) = self.split(l.0, r.0, depth) else {
            return false;
        };
        let gm = sign * m.1;
        if gm > 0.0 {
            if gl < 0.0 {
                self.out.push(bisect(self.f, l, m));
            }
            if gr < 0.0 {
                self.out.push(bisect(self.f, m, r));
            }
            return true;
        }
        let left = (gm - gl) / (m.0 - l.0);
        let right = (gr - gm) / (r.0 - m.0);
        self.rise(sign, l, m, (sl, right), depth + 1)
            || self.rise(sign, m, r, (left, sr), depth + 1)
    }
}

/// The root of `f` between `(lo, f(lo))` and `(hi, f(hi))` of opposite signs, to adjacent
/// doubles: a bracketed secant (Illinois) step, halving where it would leave the bracket or
/// stall, so that a smooth `f` takes a few evaluations where bisection took about 50.
pub(super) fn bisect(
    f: &dyn Fn(f64) -> f64,
    (mut lo, mut f_lo): (f64, f64),
    (mut hi, mut f_hi): (f64, f64),
) -> f64 {
    let mut side = 0;
    for _ in 0..200 {
        let mut x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
        if !(x > lo && x < hi) {
            x = 0.5 * (lo + hi);
        }
        if x <= lo || x >= hi {
            break;
        }
        let fx = f(x);
        if fx == 0.0 {
            return x;
        }
        if (fx < 0.0) == (f_lo < 0.0) {
            (lo, f_lo) = (x, fx);
            if side == -1 {
                f_hi *= 0.5;
            }
            side = -1;
        } else {
            (hi, f_hi) = (x, fx);
            if side == 1 {
                f_lo *= 0.5;
            }
            side = 1;
        }
        // Adjacent doubles (or a bracket at the rounding of its ends): done.
        if hi - lo <= 2.0 * f64::EPSILON * lo.abs().max(hi.abs()) {
            break;
        }
    }
    0.5 * (lo + hi)
}

/// Append a piece, merging it into the last one when both sit at the same limit (their ends
/// a few ulps apart: an end found by bisection and one set by the motion), and letting a
/// limit piece absorb a sliver a few ulps wide that follows it.
pub(super) fn push_merged(out: &mut Vec<Piece>, p: Piece) {
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    /// The crossings of `f` on `(y0, y1)` with the kinks, sorted, and the evaluations of `f`.
    fn found(
        f: &dyn Fn(f64) -> f64,
        curvature: &dyn Fn(f64, f64) -> (f64, f64),
        (y0, y1): (f64, f64),
        kinks: &[f64],
    ) -> (Vec<f64>, usize) {
        let calls = Cell::new(0);
        let counted = |y: f64| {
            calls.set(calls.get() + 1);
            f(y)
        };
        let mut out = Vec::new();
        let ends = ((y0, counted(y0)), (y1, counted(y1)));
        crossings(&counted, curvature, ends.0, ends.1, kinks, &mut out);
        out.sort_by(f64::total_cmp);
        (out, calls.get())
    }

    fn close(got: &[f64], want: &[f64], tol: f64) -> bool {
        got.len() == want.len() && got.iter().zip(want).all(|(g, w)| (g - w).abs() < tol)
    }

    #[test]
    fn a_narrow_hump_between_eighths_is_found() {
        // Concave, negative at both ends, positive on (0.5625 ∓ 0.0316), between the points
        // k/8: found with its two crossings, and the mirror image (a convex dip) too.
        let (c, h) = (0.5625, 1e-3f64);
        let hump = |y: f64| h - (y - c) * (y - c);
        let want = [c - h.sqrt(), c + h.sqrt()];
        let (got, _) = found(&hump, &|_, _| (-2.0, -2.0), (0.0, 1.0), &[]);
        assert!(close(&got, &want, 1e-12), "{got:?}");
        let dip = |y: f64| -hump(y);
        let (got, _) = found(&dip, &|_, _| (2.0, 2.0), (0.0, 1.0), &[]);
        assert!(close(&got, &want, 1e-12), "{got:?}");
        // Only the concavity's bound (f″ ≥ −2, unbounded above): the same.
        let (got, _) = found(&hump, &|_, _| (-2.0, f64::INFINITY), (0.0, 1.0), &[]);
        assert!(close(&got, &want, 1e-12), "{got:?}");
        // Kinks between: each stretch searched.
        let (got, _) = found(&hump, &|_, _| (-2.0, -2.0), (0.0, 1.0), &[0.2, 0.7]);
        assert!(close(&got, &want, 1e-12), "{got:?}");
    }

    #[test]
    fn a_hump_below_zero_costs_few_evaluations_and_a_tiny_one_is_found() {
        // max f = −1e-3: decided by the chord and f″ ≥ −2 on the stretch, from its ends.
        let below = |y: f64| -1e-3 - (y - 0.5625) * (y - 0.5625);
        let (got, calls) = found(&below, &|_, _| (-2.0, -2.0), (0.0, 1.0), &[]);
        assert!(got.is_empty() && calls <= 4, "{got:?} {calls}");
        // Concave without a bound below: the neighbouring chords decide in a few halvings.
        let (got, calls) = found(&below, &|_, _| (f64::NEG_INFINITY, -2.0), (0.0, 1.0), &[]);
        assert!(got.is_empty() && calls <= 16, "{got:?} {calls}");
        // A zone 2e-6 wide, 1e-12 high: still two crossings.
        let tiny = |y: f64| 1e-12 - (y - 0.5625) * (y - 0.5625);
        let (got, calls) = found(&tiny, &|_, _| (-2.0, -2.0), (0.0, 1.0), &[]);
        assert!(
            close(&got, &[0.5625 - 1e-6, 0.5625 + 1e-6], 1e-12),
            "{got:?}"
        );
        assert!(calls < 200, "{calls}");
    }

    #[test]
    fn a_hump_next_to_an_unbounded_curvature_is_found() {
        // f = √(1 − y) − 4 (1 − y) − 0.0624: concave, f″ = −(1 − y)^{−3/2}/4 unbounded at
        // y = 1, negative at both ends and positive on (0.983 1, 0.985 6).
        let f = |y: f64| (1.0 - y).sqrt() - 4.0 * (1.0 - y) - 0.0624;
        let curvature = |a: f64, b: f64| {
            let at = |y: f64| -0.25 * (1.0 - y).powf(-1.5);
            (at(b), at(a))
        };
        let root = |t: f64| 1.0 - t * t;
        let d = (1.0f64 - 16.0 * 0.0624).sqrt();
        let want = [root((1.0 + d) / 8.0), root((1.0 - d) / 8.0)];
        let (got, _) = found(&f, &curvature, (0.0, 1.0), &[]);
        assert!(close(&got, &want, 1e-12), "{got:?} {want:?}");
    }

    #[test]
    fn narrow_humps_where_the_curvature_changes_sign_are_found() {
        // sin(40 y) > 0.999 on seven zones 2.2e-3 wide in (0, 1): f″ = −1600 sin(40 y) takes
        // both signs, bounded on each part by the range of the sine.
        let f = |y: f64| (40.0 * y).sin() - 0.999;
        let sine_range = |u: f64, v: f64| {
            let (mut lo, mut hi) = (u.sin().min(v.sin()), u.sin().max(v.sin()));
            let turn = std::f64::consts::FRAC_PI_2;
            let mut k = (u / turn).ceil();
            while k * turn <= v {
                let s = (k * turn).sin();
                lo = lo.min(s);
                hi = hi.max(s);
                k += 1.0;
            }
            (lo, hi)
        };
        let curvature = |a: f64, b: f64| {
            let (lo, hi) = sine_range(40.0 * a, 40.0 * b);
            (-1600.0 * hi, -1600.0 * lo)
        };
        let half = 0.999f64.acos();
        let mut want = Vec::new();
        for k in 0..7 {
            let centre = std::f64::consts::FRAC_PI_2 + 2.0 * std::f64::consts::PI * k as f64;
            want.extend([(centre - half) / 40.0, (centre + half) / 40.0]);
        }
        let (got, calls) = found(&f, &curvature, (0.0, 1.0), &[]);
        assert!(close(&got, &want, 1e-12), "{got:?}");
        assert!(calls < 2 * BUDGET, "{calls}");
    }
}
