//! One patch coordinate for the builder and the readers: `PatchKind::coord_at` (the warp's
//! knots, the kink probes) gives the bits of the readers' `partial_coord`, `partial_coord_e`
//! and `stick_coord` at random points of every patch kind, every partial-slip map, with and
//! without `e_n`; the slip map of a table of Thornton's law and where a surface takes it.

use oblique_table::surface::{
    partial_coord, partial_coord_e, partial_coord_from, partial_ratio_e, stick_coord, PartialMap,
    PatchKind,
};

/// Uniform numbers in [0, 1) from a fixed seed (xorshift64*).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
}

#[test]
fn the_builder_and_the_readers_compute_the_same_coordinate_bits() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut compared = 0;
    for _ in 0..100_000 {
        let gamma = 1.0 + 2.6 * rng.next();
        let e_n = if rng.next() < 0.2 {
            1.0
        } else {
            0.3 + 0.7 * rng.next()
        };
        let c2 = gamma * gamma * 2.0 / 7.0;
        let c1 = c2 / (gamma * gamma * (1.0 + e_n) - e_n);
        // Partial slip: α between α_c1(γ, e_n) and α_c2, log-uniform.
        let alpha = c1 * (c2 / c1).powf(rng.next());
        let kind = PatchKind::PartialSlip;
        if e_n == 1.0 {
            let builder = kind.coord_at(PartialMap::SqrtEnd, gamma, alpha, 1.0, f64::INFINITY);
            assert_eq!(
                builder.to_bits(),
                partial_coord(gamma, alpha).to_bits(),
                "({gamma}, {alpha})"
            );
        }
        let builder = kind.coord_at(PartialMap::SqrtBoth, gamma, alpha, e_n, f64::INFINITY);
        assert_eq!(
            builder.to_bits(),
            partial_coord_e(gamma, alpha, e_n).to_bits(),
            "({gamma}, {alpha}, {e_n})"
        );
        let (ratio, two_g2) = partial_ratio_e(gamma, e_n);
        let builder = kind.coord_at(PartialMap::SqrtEnd, gamma, alpha, e_n, f64::INFINITY);
        let reader = partial_coord_from(PartialMap::SqrtEnd, alpha, ratio, two_g2, ratio.ln());
        assert_eq!(
            builder.to_bits(),
            reader.to_bits(),
            "({gamma}, {alpha}, {e_n})"
        );
        // Stick: α above α_c2 (γ from 0.1), up to a finite or an infinite α_max.
        let gamma = 0.1 + 3.5 * rng.next();
        let c2 = gamma * gamma * 2.0 / 7.0;
        let alpha_max = if rng.next() < 0.5 {
            f64::INFINITY
        } else {
            c2 * (1.0 + 1e3 * rng.next())
        };
        let top = if alpha_max.is_infinite() {
            1e6 * c2
        } else {
            alpha_max
        };
        let alpha = c2 * (top / c2).powf(rng.next());
        let builder = PatchKind::Stick.coord_at(PartialMap::SqrtEnd, gamma, alpha, e_n, alpha_max);
        assert_eq!(
            builder.to_bits(),
            stick_coord(gamma, alpha, alpha_max).to_bits(),
            "({gamma}, {alpha}, α_max {alpha_max})"
        );
        compared += 4;
    }
    // The ends: α = ∞ and α = α_max give 1 exactly.
    for gamma in [0.3, 1.0, 2.5] {
        assert_eq!(
            PatchKind::Stick.coord(gamma, f64::INFINITY, f64::INFINITY),
            1.0
        );
        assert_eq!(PatchKind::Stick.coord(gamma, 7.0, 7.0), 1.0);
    }
    assert_eq!(compared, 400_000);
}

/// The coordinate of a table of Thornton's law (`PartialMap::Slip`): `α/(2α_c1)` up to
/// `α_c1(γ, e_n)`, which is `c = 1/2`, the Kelvin–Voigt coordinate halved above; the builder's
/// inverse (`alpha_at`) gives back `α`, and at `γ = 1` (`α_c1 = α_c2`) every `α < α_c2` is
/// below `c = 1/2`, never a NaN.
#[test]
fn the_slip_coordinate_puts_alpha_c1_at_one_half_and_inverts() {
    let kind = PatchKind::PartialSlip;
    let map = PartialMap::Slip;
    let mut rng = Rng(0x5EED_0000_7407_0001);
    for _ in 0..20_000 {
        let gamma = 1.0 + 2.0 * rng.next();
        let e_n = 0.3 + 0.7 * rng.next();
        let c2 = gamma * gamma * 2.0 / 7.0;
        let c1 = c2 / (gamma * gamma * (1.0 + e_n) - e_n);
        let alpha = c2 * rng.next();
        let c = kind.coord_at(map, gamma, alpha, e_n, f64::INFINITY);
        assert!((0.0..=1.0).contains(&c), "({gamma}, {alpha}, {e_n}): {c}");
        if alpha <= c1 {
            assert!(
                (c - 0.5 * alpha / c1).abs() <= 1e-15,
                "({gamma}, {alpha}, {e_n})"
            );
        } else {
            let kv = kind.coord_at(PartialMap::SqrtBoth, gamma, alpha, e_n, f64::INFINITY);
            assert!(
                (c - (0.5 + 0.5 * kv)).abs() <= 1e-15,
                "({gamma}, {alpha}, {e_n})"
            );
        }
        let back = kind.alpha_at(map, gamma, c, e_n, f64::INFINITY);
        assert!(
            (back - alpha).abs() <= 1e-12 * c2,
            "({gamma}, {alpha}, {e_n}): {back}"
        );
        // The reader's operations.
        let (ratio, two_g2) = partial_ratio_e(gamma, e_n);
        let reader = partial_coord_from(map, alpha, ratio, two_g2, ratio.ln());
        assert_eq!(c.to_bits(), reader.to_bits());
    }
    // α_c1 itself and the ends.
    for (gamma, e_n) in [(1.3, 0.5), (1.754, 0.8), (2.2, 0.99)] {
        let c1 = kind.alpha_at(map, gamma, 0.5, e_n, f64::INFINITY);
        let c2 = kind.alpha_at(map, gamma, 1.0, e_n, f64::INFINITY);
        assert!(
            (c1 - 2.0 * gamma * gamma / (7.0 * (gamma * gamma * (1.0 + e_n) - e_n))).abs() < 1e-15
        );
        assert!((c2 - gamma * gamma * 2.0 / 7.0).abs() < 1e-14);
        assert_eq!(kind.coord_at(map, gamma, 0.0, e_n, f64::INFINITY), 0.0);
    }
    // γ = 1: α_c1 = α_c2 = 2/7; below it the coordinate is linear, finite, under 1/2.
    for e_n in [0.3, 0.7, 0.95, 1.0] {
        for k in 0..=100 {
            let alpha = (2.0 / 7.0) * f64::from(k) / 100.0 * (1.0 - 1e-15);
            let c = kind.coord_at(map, 1.0, alpha, e_n, f64::INFINITY);
            assert!(
                c.is_finite() && (0.0..0.5).contains(&c),
                "{e_n}, {alpha}: {c}"
            );
        }
    }
}

/// A surface takes the slip map only with an `e_n` axis over a range of `γ ≥ 1`, and then
/// answers no query from the full-slip line; each refusal names the coordinate.
#[test]
fn the_slip_map_is_for_a_gamma_range_above_one_with_an_e_n_axis() {
    use oblique_table::surface::{OutOfDomain, Region};
    let read = |name: &str| {
        let path = format!("{}/../../tables/{name}", env!("CARGO_MANIFEST_DIR"));
        oblique_table::read::read(&path)
            .unwrap_or_else(|e| panic!("{path}: {e}"))
            .surface
    };
    let kv = read("dissipative-demo.h5");
    assert_eq!(kv.partial_map(), PartialMap::SqrtBoth);
    assert!(kv.has_line());
    let slip = kv
        .clone()
        .with_partial_map(PartialMap::Slip)
        .expect("gamma 1.2-2");
    assert!(!slip.has_line());
    assert_eq!(slip.line_end(1.5, 0.8), f64::NEG_INFINITY);
    let c1 = 2.0 * 2.25 / (7.0 * (2.25 * 1.8 - 0.8));
    assert_eq!(kv.region_at(1.5, 0.5 * c1, 0.8), Region::Line);
    assert_eq!(slip.region_at(1.5, 0.5 * c1, 0.8), Region::PartialHigh);
    assert_eq!(slip.region_at(1.0, 0.2, 0.8), Region::PartialHigh);
    assert_eq!(slip.region_at(1.0, 2.0 / 7.0, 0.8), Region::StickHigh);
    // Below the γ range: refused, never the line.
    assert!(slip.eval_point(1.1, 0.01, 0.8, OutOfDomain::Error).is_err());
    assert!(kv.eval_point(1.1, 0.01, 0.8, OutOfDomain::Error).is_ok());
    // map_patches keeps the map.
    let again = slip
        .map_patches(|_, p| Ok(p.clone()))
        .expect("same patches");
    assert_eq!(again.partial_map(), PartialMap::Slip);
    for (name, map) in [
        ("quick.h5", PartialMap::Slip),
        ("dissipative-pair.h5", PartialMap::Slip),
        ("quick.h5", PartialMap::SqrtBoth),
        ("dissipative-demo.h5", PartialMap::SqrtEnd),
    ] {
        let e = read(name).with_partial_map(map).expect_err(name);
        assert!(e.contains("partial-slip coordinate"), "{name}: {e}");
    }
}
