//! The line density of Thornton's loading pressure in the MDR: what bounds each tangential
//! spring (`physics.md`, "Elastic–plastic impacts", tangential part).
//!
//! The MDR spring at `x` is pressed by `s = d − x²/R*` (its normal displacement). Under a Hertz
//! pressure the line density of the pressure is `q(x) = E* s`; truncated at the limiting
//! pressure `p_y` it is `q = E* Q(s)` with, in `d_y` (the yield indentation) alone,
//!
//! `Q(s) = s` for `s ≤ d_y`, and `Q(s) = s (1 − 2θ/π) + (2/π) √(d_y (s − d_y))`,
//! `θ = arctan √((s − d_y)/d_y)`, beyond:
//!
//! `physics.md`'s form in `(a, r_y, θ)` written in the spring's own `s` (`a² − x² = R* s`,
//! `r_y² − x² = R* (s − d_y)`). `Q` is concave, `Q′(s) = 1 − 2θ/π = (2/π) arcsin √(d_y/s)`
//! (continuous at `d_y`, where `Q″` has a `(s − d_y)^{−1/2}` singularity). In unloading the
//! density is `E* (reach − y)/ρ` ([`super::normal::Unloading::reach`]), linear in `y = x²/R*`.

use std::f64::consts::FRAC_2_PI;

/// The truncated line density `Q(s)` of one yield indentation `d_y` (m; `∞` for no truncation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Truncated {
    /// Yield indentation `d_y` (m).
    pub yield_indentation: f64,
}

impl Truncated {
    /// `Q(s)` (m): `s` up to `d_y`, the truncated density beyond; `0` for `s ≤ 0`.
    pub fn value(&self, s: f64) -> f64 {
        let dy = self.yield_indentation;
        if s <= dy {
            return s.max(0.0);
        }
        let excess = s - dy;
        let theta = (excess / dy).sqrt().atan();
        s * (1.0 - FRAC_2_PI * theta) + FRAC_2_PI * (dy * excess).sqrt()
    }

    /// `Q′(s) = 1 − 2θ/π` (1 up to `d_y`; 0 for `s ≤ 0`).
    pub fn slope(&self, s: f64) -> f64 {
        let dy = self.yield_indentation;
        if s <= 0.0 {
            0.0
        } else if s <= dy {
            1.0
        } else {
            1.0 - FRAC_2_PI * ((s - dy) / dy).sqrt().atan()
        }
    }

    /// `−Q″(s) = (1/π) √d_y / (s √(s − d_y))` (1/m) for `s > d_y`, 0 below (where `Q` is
    /// linear): how fast the slope falls in the truncated part, decreasing in `s` there and
    /// unbounded as `s → d_y⁺`.
    pub fn curvature(&self, s: f64) -> f64 {
        let dy = self.yield_indentation;
        if s > dy {
            std::f64::consts::FRAC_1_PI * dy.sqrt() / (s * (s - dy).sqrt())
        } else {
            0.0
        }
    }

    /// Bounds `(min, max)` of `−Q″(T − y)` (1/m) for `y` inside `(a, b)`, `a < b`: `(0, 0)`
    /// where `Q(T − y)` is linear there, `(−∞, ∞)` where its kink at `T − y = 0` is inside (or
    /// an end is NaN), and
    /// `(0, ∞)` where its kink at `d_y` is (by the rounding of a stretch's end at a kink).
    pub fn curvature_range(&self, top: f64, a: f64, b: f64) -> (f64, f64) {
        let dy = self.yield_indentation;
        let (s_lo, s_hi) = (top - b, top - a);
        if s_lo.is_nan() || s_hi.is_nan() || (s_lo < 0.0 && s_hi > 0.0) {
            return (f64::NEG_INFINITY, f64::INFINITY);
        }
        if s_hi <= dy {
            return (0.0, 0.0);
        }
        if s_lo < dy {
            return (0.0, f64::INFINITY);
        }
        let high = if s_lo > dy {
            self.curvature(s_lo)
        } else {
            f64::INFINITY
        };
        (self.curvature(s_hi), high)
    }

    /// `d(−Q″)/ds = −(−Q″(s)) (1/s + 1/(2 (s − d_y)))` (1/m²) for `s > d_y`, 0 below: negative
    /// and rising towards 0 with `s` (`−Q″` is convex and falling in the truncated part).
    pub fn curvature_slope(&self, s: f64) -> f64 {
        let dy = self.yield_indentation;
        if s > dy {
            -self.curvature(s) * (1.0 / s + 0.5 / (s - dy))
        } else {
            0.0
        }
    }

    /// Bounds `(min, max)` of `−Q″(R − y) − (−Q″(T − y))` (1/m) for `y` inside `(a, b)`,
    /// `a < b`, where both `R − y` and `T − y` stay in the truncated part (`> d_y`; `None`
    /// elsewhere or for a NaN): by the mean value theorem it is `(R − T) d(−Q″)/ds` at some
    /// `s` between `min(R, T) − b` and `max(R, T) − a`, where [`Truncated::curvature_slope`]
    /// is bounded by its values at these ends. Small where `R` and `T` are close, as the
    /// difference of the two bounds of [`Truncated::curvature_range`] is not.
    pub fn curvature_difference(&self, reach: f64, top: f64, a: f64, b: f64) -> Option<(f64, f64)> {
        let dy = self.yield_indentation;
        let span = reach - top;
        let s_min = reach.min(top) - b;
        let s_max = reach.max(top) - a;
        if !(dy.is_finite() && span.is_finite() && s_min > dy && s_max.is_finite()) {
            return None;
        }
        let (u, v) = (self.curvature_slope(s_min), self.curvature_slope(s_max));
        Some(if span >= 0.0 {
            (span * u, span * v)
        } else {
            (span * v, span * u)
        })
    }

    /// `s` with `Q(s) = q` (`q ≥ 0`): `q` up to `d_y`, beyond by Newton from below (`Q` is
    /// concave and increasing there, so the iterates rise monotonically to the root).
    pub fn inverse(&self, q: f64) -> f64 {
        let dy = self.yield_indentation;
        if q <= dy {
            return q.max(0.0);
        }
        let mut s = q;
        for _ in 0..100 {
            let next = s + (q - self.value(s)) / self.slope(s);
            if next.is_nan() || next <= s {
                break;
            }
            s = next;
        }
        s
    }

    /// `∫₀^X Q(D − x²/R) dx` (m²) for `0 ≤ X ≤ √(R D)` (the springs of a contact of reach `D`
    /// up to `X`), in closed form: `∫ s dx` less the truncated part
    /// `E(s) = s − Q(s) = (2/π)[s θ − √(d_y (s − d_y))]` over `x² < R (D − d_y)`, integrated by
    /// parts (`t = √(ρ² − x²)`, `ρ² = D − d_y`, `β = √d_y`, `M = D`, in `x/√R`):
    /// `∫₀^X s θ dx = A(X) θ(X) + β [I₂/3 − (2M/3) I₀ + (2M²/3) I_M]`, `A = M x − x³/3`,
    /// `I₀ = arcsin(X/ρ)`, `I₂ = (ρ² I₀ − X t)/2`, `I_M = arctan(X β/(√M t))/(β √M)`.
    pub fn integral(&self, reach: f64, x: f64, radius: f64) -> f64 {
        let sr = radius.sqrt();
        let big = reach;
        let xs = (x / sr).clamp(0.0, big.max(0.0).sqrt());
        let plain = big * xs - xs * xs * xs / 3.0;
        let dy = self.yield_indentation;
        if big.is_nan() || big <= dy || !dy.is_finite() {
            return sr * plain;
        }
        let rho2 = big - dy;
        let rho = rho2.sqrt();
        let xc = xs.min(rho);
        // (ρ − x)(ρ + x): exactly 0 at x = ρ (ρ² − x² would leave a rounding there, which the
        // square root amplifies).
        let t = ((rho - xc) * (rho + xc)).max(0.0).sqrt();
        let beta = dy.sqrt();
        let theta = (t / beta).atan();
        let i0 = (xc / rho).min(1.0).asin();
        let i2 = 0.5 * (rho2 * i0 - xc * t);
        let sm = big.sqrt();
        let im = (xc * beta).atan2(sm * t) / (beta * sm);
        let a = big * xc - xc * xc * xc / 3.0;
        let s_theta =
            a * theta + beta * (i2 / 3.0 - 2.0 * big / 3.0 * i0 + 2.0 * big * big / 3.0 * im);
        let root = beta * 0.5 * (xc * t + rho2 * i0);
        sr * (plain - FRAC_2_PI * (s_theta - root))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// `physics.md`'s form: `q = (a² − x²) − 2[(a² − x²)(θ + sin θ cos θ)/π − p_y √(r_y² − x²)]`,
    /// `sin²θ = (r_y² − x²)/(a² − x²)`, `R* = E* = 1`, `p_y = (2/π)√d_y`, `r_y² = a² − d_y`.
    fn physics_md(a2: f64, dy: f64, x: f64) -> f64 {
        let ry2 = a2 - dy;
        let base = a2 - x * x;
        if x * x >= ry2 {
            return base;
        }
        let py = 2.0 / PI * dy.sqrt();
        let th = ((ry2 - x * x) / base).sqrt().asin();
        base - 2.0 * (base * (th + th.sin() * th.cos()) / PI - py * (ry2 - x * x).sqrt())
    }

    /// `q(x) = 2 ∫_x^a r p(r)/√(r² − x²) dr` with `p = min((2/π)√(a² − r²), p_y)`, by the
    /// substitution `r = √(x² + u²)` (`dr r/√(r² − x²) = du`): `q = 2 ∫₀^{√(a² − x²)} p du`,
    /// midpoint rule on 2·10⁵ points.
    fn numeric(a2: f64, dy: f64, x: f64) -> f64 {
        let py = 2.0 / PI * dy.sqrt();
        let top = (a2 - x * x).max(0.0).sqrt();
        let n = 200_000;
        let h = top / n as f64;
        2.0 * (0..n)
            .map(|i| {
                let u = (i as f64 + 0.5) * h;
                let r2 = x * x + u * u;
                (2.0 / PI * (a2 - r2).max(0.0).sqrt()).min(py)
            })
            .sum::<f64>()
            * h
    }

    #[test]
    fn the_density_is_physics_md_and_the_pressure_it_integrates() {
        let q = Truncated {
            yield_indentation: 0.3,
        };
        for d in [0.2f64, 0.31, 0.5, 1.3] {
            for i in 0..=20 {
                let x = d.sqrt() * i as f64 / 20.0;
                let got = q.value(d - x * x);
                let want = physics_md(d, 0.3, x);
                assert!((got - want).abs() < 2e-15, "d {d} x {x}: {got} {want}");
                let direct = numeric(d, 0.3, x);
                assert!((got - direct).abs() < 2e-8, "d {d} x {x}: {got} {direct}");
            }
        }
    }

    #[test]
    fn the_slope_is_the_derivative() {
        let q = Truncated {
            yield_indentation: 0.3,
        };
        for s in [0.1, 0.29, 0.31, 0.5, 2.0, 40.0] {
            let h = 1e-6;
            let numeric = (q.value(s + h) - q.value(s - h)) / (2.0 * h);
            assert!((numeric - q.slope(s)).abs() < 1e-8, "s {s}");
        }
        for s in [0.31, 0.5, 2.0, 40.0] {
            let h = 1e-5 * s;
            let numeric = -(q.slope(s + h) - q.slope(s - h)) / (2.0 * h);
            assert!(
                (numeric - q.curvature(s)).abs() < 1e-6 * q.curvature(s),
                "s {s}: {numeric} {}",
                q.curvature(s)
            );
        }
        assert_eq!(q.curvature(0.29), 0.0);
        // Over y in (a, b), T − y runs over (T − b, T − a): the bounds are the curvature at its
        // ends, and cover samples inside.
        let (lo, hi) = q.curvature_range(1.0, 0.2, 0.6);
        assert_eq!((lo, hi), (q.curvature(0.8), q.curvature(0.4)));
        for i in 1..10 {
            let m = q.curvature(1.0 - (0.2 + 0.04 * i as f64));
            assert!(m >= lo && m <= hi);
        }
        assert_eq!(q.curvature_range(1.0, 0.75, 0.9), (0.0, 0.0));
        let quarter = Truncated {
            yield_indentation: 0.25,
        };
        assert_eq!(
            quarter.curvature_range(1.0, 0.5, 0.75),
            (quarter.curvature(0.5), f64::INFINITY)
        );
        assert_eq!(q.curvature_range(1.0, 0.5, 0.8), (0.0, f64::INFINITY));
        assert_eq!(q.curvature_range(1.0, 0.5, 1.2).1, f64::INFINITY);
        assert_eq!(q.curvature_range(1.0, 0.9, 1.2).0, f64::NEG_INFINITY);
        // The slope of the curvature, and the bounds of a difference of two curvatures
        // against samples (R = 1.3, T = 1.2 over y in (0.1, 0.7)).
        for s in [0.31, 0.5, 2.0] {
            let h = 1e-6 * s;
            let numeric = (q.curvature(s + h) - q.curvature(s - h)) / (2.0 * h);
            let exact = q.curvature_slope(s);
            assert!((numeric - exact).abs() < 1e-6 * exact.abs(), "s {s}");
        }
        for (reach, top) in [(1.3, 1.2), (1.2, 1.3)] {
            let (lo, hi) = q
                .curvature_difference(reach, top, 0.1, 0.7)
                .unwrap_or_default();
            assert!(lo < hi && (lo > 0.0 || hi < 0.0), "{lo} {hi}");
            for i in 0..=20 {
                let y = 0.1 + 0.03 * i as f64;
                let d = q.curvature(reach - y) - q.curvature(top - y);
                assert!(d >= lo && d <= hi, "{reach} {top} y {y}: {d} {lo} {hi}");
            }
        }
        assert!(q.curvature_difference(1.3, 1.2, 0.1, 0.95).is_none());
        assert!(q.curvature_difference(1.3, f64::NAN, 0.1, 0.5).is_none());
        assert_eq!(q.slope(0.3), 1.0);
        assert!(q.slope(1e6) > 0.0 && q.slope(1e6) < 1e-2);
        for s in [0.0, 0.1, 0.3, 0.300001, 0.7, 5.0, 1e4] {
            let back = q.inverse(q.value(s));
            assert!((back - s).abs() <= 1e-13 * s.max(1.0), "s {s}: {back}");
        }
    }

    /// The density over the whole contact, `2 ∫₀^a q dx`, is the loading force `F(d)` of
    /// [`super::super::normal::Loading`] (`R* = E* = 1`, `k = 4/3`); and the closed-form integral
    /// against a midpoint quadrature of `Q` on parts of the contact.
    #[test]
    fn the_integral_is_the_force_and_the_quadrature() {
        for (dy, d) in [
            (0.3f64, 0.2f64),
            (0.3, 0.5),
            (0.01, 0.8),
            (0.3, 0.300001),
            (1e-4, 2.0),
        ] {
            let q = Truncated {
                yield_indentation: dy,
            };
            let loading = crate::thornton::normal::Loading {
                stiffness: 4.0 / 3.0,
                yield_indentation: dy,
            };
            let total = 2.0 * q.integral(d, d.sqrt(), 1.0);
            let force = loading.force(d);
            assert!(
                (total - force).abs() < 1e-14 * force.max(1.0),
                "d_y {dy} d {d}: {total} {force}"
            );
            for radius in [1.0, 2.5e-3] {
                let a = (radius * d).sqrt();
                for (lo, hi) in [(0.0, 0.3), (0.2, 0.9), (0.5, 1.0)] {
                    let (x0, x1) = (lo * a, hi * a);
                    let n = 100_000;
                    let h = (x1 - x0) / n as f64;
                    let quad: f64 = (0..n)
                        .map(|i| {
                            let x = x0 + (i as f64 + 0.5) * h;
                            q.value(d - x * x / radius)
                        })
                        .sum::<f64>()
                        * h;
                    let exact = q.integral(d, x1, radius) - q.integral(d, x0, radius);
                    assert!(
                        (quad - exact).abs() < 1e-9 * (d * a),
                        "d_y {dy} d {d} R {radius} [{lo}, {hi}]: {quad} {exact}"
                    );
                }
            }
        }
        // Without truncation: ∫₀^X (D − x²) dx.
        let q = Truncated {
            yield_indentation: f64::INFINITY,
        };
        assert_eq!(q.integral(1.0, 0.5, 1.0), 0.5 - 0.125 / 3.0);
    }
}
