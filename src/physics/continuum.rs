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

/// Which law a piece follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    /// Stuck: `ũ = a + b z + q z²`, `z = y − y_ref`, moving rigidly with `w`.
    Stuck,
    /// At the `+` Coulomb limit `ũ = c (d − y)`.
    Plus,
    /// At the `−` Coulomb limit `ũ = −c (d − y)`.
    Minus,
}

/// One piece of the field on `y0 ≤ y ≤ y1`.
#[derive(Debug, Clone, Copy)]
struct Piece {
    kind: Kind,
    /// Lower and upper profile height (m).
    y0: f64,
    y1: f64,
    /// The matching positions `x = √(R* y)` (m).
    x0: f64,
    x1: f64,
    /// Reference height of the local coordinate `z = y − y_ref` (m).
    y_ref: f64,
    /// Coefficients of a stuck piece `ũ = a + b z + q z²` (m, 1, 1/m); unused at a limit.
    a: f64,
    b: f64,
    q: f64,
    /// `∫ (b z + q z²) dx` over the piece (m²): the part of the integral that moves with it.
    shape: f64,
}

/// Three-point Gauss–Legendre nodes on `[0, 1]` and weights: exact for `ũ(x)`, a polynomial
/// of degree 4 in `x`.
const GAUSS: [(f64, f64); 3] = [
    (0.112_701_665_379_258_31, 5.0 / 18.0),
    (0.5, 8.0 / 18.0),
    (0.887_298_334_620_741_7, 5.0 / 18.0),
];

impl Piece {
    fn stuck(y0: f64, y1: f64, y_ref: f64, abq: (f64, f64, f64), radius: f64) -> Self {
        let mut p = Self {
            kind: Kind::Stuck,
            y0,
            y1,
            x0: (radius * y0).sqrt(),
            x1: (radius * y1).sqrt(),
            y_ref,
            a: abq.0,
            b: abq.1,
            q: abq.2,
            shape: 0.0,
        };
        p.shape = p.shape_integral(radius);
        p
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
            shape: 0.0,
        }
    }

    /// `∫ (b z + q z²) dx` by three-point Gauss–Legendre in `x` (exact).
    fn shape_integral(&self, radius: f64) -> f64 {
        let dx = self.x1 - self.x0;
        if dx <= 0.0 {
            return 0.0;
        }
        let total: f64 = GAUSS
            .iter()
            .map(|&(t, w)| {
                let x = self.x0 + t * dx;
                let z = x * x / radius - self.y_ref;
                w * z * (self.b + self.q * z)
            })
            .sum();
        total * dx
    }

    /// `∫ ũ dx` over the piece at indentation `d` with limit factor `c` (m²).
    fn integral(&self, c: f64, d: f64, radius: f64) -> f64 {
        let dx = self.x1 - self.x0;
        match self.kind {
            Kind::Stuck => self.a * dx + self.shape,
            Kind::Plus | Kind::Minus => {
                // ±c ∫ (d − x²/R) dx, with x1³ − x0³ = dx (x0² + x0 x1 + x1²).
                let cube = dx * (self.x0 * self.x0 + self.x0 * self.x1 + self.x1 * self.x1);
                let v = c * (d * dx - cube / (3.0 * radius));
                if self.kind == Kind::Plus {
                    v
                } else {
                    -v
                }
            }
        }
    }

    /// `ũ` at height `y` for a stuck piece.
    fn value(&self, y: f64) -> f64 {
        let z = y - self.y_ref;
        self.a + z * (self.b + self.q * z)
    }
}

/// Roots of `A + B z + Q z² = 0` strictly inside `(lo, hi)`, appended to `out`.
fn roots_inside(a: f64, b: f64, q: f64, lo: f64, hi: f64, out: &mut Vec<f64>) {
    let mut push = |r: f64| {
        if r > lo && r < hi {
            out.push(r);
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

/// The exact (continuum) half-row of tangential springs.
#[derive(Debug, Clone)]
pub struct ContinuumRow {
    radius: f64,
    pieces: Vec<Piece>,
    spare: Vec<Piece>,
    cuts: Vec<f64>,
    at_limit: (bool, bool),
}

impl ContinuumRow {
    /// An unloaded row for effective radius `R*` (m).
    pub fn new(radius: f64) -> Self {
        Self {
            radius,
            pieces: Vec::new(),
            spare: Vec::new(),
            cuts: Vec::new(),
            at_limit: (false, false),
        }
    }

    /// Whether some part of the contact sits at the `+` / `−` Coulomb limit (after the last
    /// step).
    pub fn at_limit(&self) -> (bool, bool) {
        self.at_limit
    }

    /// Number of pieces the field is made of now (diagnostics).
    pub fn pieces(&self) -> usize {
        self.pieces.len()
    }

    /// The continuum form of [`super::springs::SpringRow::step_accurate`]: the same update for
    /// every point of the contact, applied to the whole field at once. Returns `∫₀^a ũ_x dx`
    /// (m²), exact for the field, and the mean displacement over the contact.
    pub fn step_accurate(&mut self, m: &StepMotion, d1: f64, c: f64) -> StepResult {
        let (d0, h, v, acc) = (m.d0, m.h, m.slip_velocity, m.slip_accel);
        let dw = h * v + 0.5 * h * h * acc;
        let radius = self.radius;
        let center = self.pieces.first().map_or(0.0, |p| match p.kind {
            Kind::Stuck => p.value(0.0),
            Kind::Plus => c * d0,
            Kind::Minus => -c * d0,
        });
        let finite = c.is_finite();
        let (plus, minus) = if finite {
            m.release_corrections(c)
        } else {
            (0.0, 0.0)
        };
        let top = d1.max(0.0);
        let mut out = std::mem::take(&mut self.spare);
        out.clear();
        let old = std::mem::take(&mut self.pieces);
        for p in &old {
            if p.y0 >= top {
                break;
            }
            let mut p = *p;
            if p.y1 > top {
                p.y1 = top;
                p.x1 = (radius * top).sqrt();
                if p.kind == Kind::Stuck {
                    p.shape = p.shape_integral(radius);
                }
            }
            // The increment, and the release of a limit piece that sticks again in the step.
            match p.kind {
                Kind::Stuck => p.a += dw,
                Kind::Plus => {
                    if dw < c * (d1 - d0) {
                        p = Piece::stuck(
                            p.y0,
                            p.y1,
                            p.y0,
                            (c * (d0 - p.y0) + dw + plus, -c, 0.0),
                            radius,
                        );
                    } else {
                        push_merged(&mut out, p, radius);
                        continue;
                    }
                }
                Kind::Minus => {
                    if dw > -c * (d1 - d0) {
                        p = Piece::stuck(
                            p.y0,
                            p.y1,
                            p.y0,
                            (-c * (d0 - p.y0) + dw + minus, c, 0.0),
                            radius,
                        );
                    } else {
                        push_merged(&mut out, p, radius);
                        continue;
                    }
                }
            }
            self.clip(p, c, d1, &mut out);
        }
        // Points entering contact: ũ = w(h) − w(θh), θ = (y − d0)/(d1 − d0), w quadratic in
        // time; with s = 1 − θ: (K1 − K2) + (2K2 − K1) θ − K2 θ², K1 = h v + a h², K2 = a h²/2.
        if d1 > d0 {
            let y0 = d0.max(0.0);
            let span = d1 - d0;
            let k1 = h * v + acc * h * h;
            let k2 = 0.5 * acc * h * h;
            let entry = Piece::stuck(
                y0,
                d1,
                d0,
                (k1 - k2, (2.0 * k2 - k1) / span, -k2 / (span * span)),
                radius,
            );
            self.clip(entry, c, d1, &mut out);
        }
        self.spare = old;
        self.pieces = out;
        let (mut any_plus, mut any_minus) = (false, false);
        let mut integral = 0.0;
        for p in &self.pieces {
            integral += p.integral(c, d1, radius);
            let lim_positive = p.y0 < d1;
            any_plus |= p.kind == Kind::Plus && lim_positive;
            any_minus |= p.kind == Kind::Minus && lim_positive;
        }
        self.at_limit = if finite {
            (any_plus, any_minus)
        } else {
            (false, false)
        };
        let a1 = (radius * d1.max(0.0)).sqrt();
        let mean = if a1 > 0.0 && !self.pieces.is_empty() {
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

    /// Clip a stuck piece (after its increment) against the limits `±c (d1 − y)` and append the
    /// parts: stuck where inside, limit pieces where outside.
    fn clip(&mut self, p: Piece, c: f64, d1: f64, out: &mut Vec<Piece>) {
        let radius = self.radius;
        if p.y1 <= p.y0 {
            return;
        }
        if !c.is_finite() {
            push_merged(out, p, radius);
            return;
        }
        // In z = y − y_ref: ũ − c(d1 − y) = (a − c(d1 − y_ref)) + (b + c) z + q z², and
        // ũ + c(d1 − y) = (a + c(d1 − y_ref)) + (b − c) z + q z².
        let lim_ref = c * (d1 - p.y_ref);
        let (z0, z1) = (p.y0 - p.y_ref, p.y1 - p.y_ref);
        self.cuts.clear();
        roots_inside(p.a - lim_ref, p.b + c, p.q, z0, z1, &mut self.cuts);
        roots_inside(p.a + lim_ref, p.b - c, p.q, z0, z1, &mut self.cuts);
        let classify = |y: f64| {
            let u = p.value(y);
            let lim = c * (d1 - y);
            if u > lim {
                Kind::Plus
            } else if u < -lim {
                Kind::Minus
            } else {
                Kind::Stuck
            }
        };
        if self.cuts.is_empty() {
            let kind = classify(0.5 * (p.y0 + p.y1));
            if kind == Kind::Stuck {
                push_merged(out, p, radius);
            } else {
                push_merged(out, Piece::limit(kind, p.y0, p.y1, radius), radius);
            }
            return;
        }
        self.cuts.sort_by(|a, b| a.total_cmp(b));
        let mut lo = p.y0;
        let ends = self.cuts.iter().map(|z| z + p.y_ref);
        for hi in ends.chain(std::iter::once(p.y1)) {
            let hi = hi.clamp(lo, p.y1);
            if hi > lo {
                let kind = classify(0.5 * (lo + hi));
                let part = if kind == Kind::Stuck {
                    Piece::stuck(lo, hi, p.y_ref, (p.a, p.b, p.q), radius)
                } else {
                    Piece::limit(kind, lo, hi, radius)
                };
                push_merged(out, part, radius);
            }
            lo = hi;
        }
    }
}

/// Append a piece, merging it into the last one when both sit at the same limit.
fn push_merged(out: &mut Vec<Piece>, p: Piece, radius: f64) {
    if p.x1 <= p.x0 {
        return;
    }
    if let Some(last) = out.last_mut() {
        if p.kind != Kind::Stuck && last.kind == p.kind {
            *last = Piece::limit(p.kind, last.y0, p.y1, radius);
            return;
        }
    }
    out.push(p);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn motion(dw: f64, d0: f64) -> StepMotion {
        StepMotion {
            h: 1.0,
            d0,
            rate0: 0.0,
            accel0: 0.0,
            slip_velocity: dw,
            slip_accel: 0.0,
        }
    }

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
