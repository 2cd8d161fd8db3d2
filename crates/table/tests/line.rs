//! The rule along one line (`Patch::line`): the bits of `Patch::interpolate_at` at every
//! coordinate, on every patch of the shipped tables, at lines through leaf edges and
//! random ones.

use oblique_table::surface::Patch;

fn patches(name: &str) -> Vec<Patch> {
    let path = format!("{}/../../tables/{name}", env!("CARGO_MANIFEST_DIR"));
    let c = oblique_table::read::read(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    c.surface.patches().map(|(_, p)| p.clone()).collect()
}

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

/// The line's answer against the rule's at random coordinates, at the edges of cells down to
/// below the deepest leaf, and outside [0, 1] (clamped); returns the number compared.
fn compare(patch: &Patch, gamma: f64, e_n: f64, rng: &mut Rng) -> usize {
    let Some(line) = patch.line(gamma, e_n) else {
        panic!("no line at ({gamma}, {e_n})");
    };
    let mut cs: Vec<f64> = (0..400).map(|_| rng.next()).collect();
    let blocks = patch.blocks_coord();
    for d in 0..=10 {
        let n = blocks << d;
        cs.extend((0..=n).map(|j| j as f64 / n as f64));
    }
    cs.extend([-0.5, -1e-300, 1.0 + 1e-15, 3.0, f64::MIN_POSITIVE]);
    for &c in &cs {
        let rule = patch.interpolate_at(gamma, c, e_n, 4);
        let fast = line.interpolate(c);
        assert_eq!(
            fast.to_bits(),
            rule.to_bits(),
            "{} patch, line ({gamma}, {e_n}) at c = {c}: {fast} against {rule}",
            patch.kind().name()
        );
    }
    cs.len()
}

#[test]
fn a_line_gives_the_bits_of_the_rule_on_every_shipped_table() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    let mut lines = 0;
    let mut points = 0;
    for name in [
        "dissipative-demo.h5",
        "dissipative-pair.h5",
        "quick.h5",
        "full.h5",
        "isotropic.h5",
    ] {
        for patch in patches(name) {
            let (glo, ghi) = (patch.gamma_lo(), patch.gamma_hi());
            let (elo, ehi) = patch.restitution().map_or((1.0, 1.0), |r| (r.lo(), r.hi()));
            // Root and leaf edges along γ and e_n (dyadic fractions), random values, the ends.
            let mut gs = vec![glo, ghi];
            let mut es = vec![elo, ehi, 1.0_f64.min(ehi)];
            for k in 1..16 {
                let t = k as f64 / 16.0;
                gs.push(glo + (ghi - glo) * t);
                es.push(elo + (ehi - elo) * t);
            }
            for _ in 0..12 {
                gs.push(glo + (ghi - glo) * rng.next());
                es.push(elo + (ehi - elo) * rng.next());
            }
            for (i, &g) in gs.iter().enumerate() {
                // Every e_n with a few γ, every γ with a few e_n.
                for (j, &e) in es.iter().enumerate() {
                    if (i + 3 * j) % 7 != 0 {
                        continue;
                    }
                    if patch.warp().is_some() {
                        assert!(patch.line(g, e).is_none(), "a warped patch has no line");
                        continue;
                    }
                    points += compare(&patch, g, e, &mut rng);
                    lines += 1;
                }
            }
        }
    }
    assert!(lines > 500, "{lines} lines");
    println!("{lines} lines, {points} points: the rule's bits");
}
