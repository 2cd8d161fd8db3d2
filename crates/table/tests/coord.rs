//! One patch coordinate for the builder and the readers: `PatchKind::coord_at` (the warp's
//! knots, the kink probes) gives the bits of the readers' `partial_coord`, `partial_coord_e`
//! and `stick_coord` at random points of every patch kind, both partial-slip maps, with and
//! without `e_n`.

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
