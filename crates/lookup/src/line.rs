//! `P(α)` of one pair of materials at one normal restitution through a table with an `e_n`
//! axis, with the rule's bits: [`PairLine`], stored in a [`crate::Prepared`] by
//! [`crate::Table::prepare`].
//!
//! At a fixed `(γ, e_n)` the rule's `γ`- and `e_n`-only parts are the same for every query:
//! the end of the full-slip line `α_c1(γ, e_n)`, `α_c2(γ)`, the coordinates' constants, and in
//! each patch the descent along `γ` and `e_n`, their stencils and the leaf's rows along `e_n`
//! ([`PatchLine`]). A pair line computes them once, with the rule's operations, and answers
//! with the rest: the same bits as [`Table::p_e_with`](crate::Table::p_e_with) (tested), for
//! about the cost of an elastic lookup. The domain policy is the rule's own
//! ([`Surface::apply_domain_e`]).

use oblique_table::line::PatchLine;
use oblique_table::surface::{
    alpha_c2, check_query, full_slip_line, partial_coord_from, partial_ratio_e, stick_coord_parts,
    stick_parts, OutOfDomain, PartialMap, PatchKind, Region, Surface,
};

use crate::LookupError;

/// The parts of the rule at the `γ` where the line's off-line queries are answered (the pair's,
/// or the nearest of the table's range when it is clamped).
#[derive(Debug, Clone, PartialEq)]
struct LineAt {
    gamma: f64,
    /// The table's partial-slip map ([`Surface::partial_map`]).
    map: PartialMap,
    /// [`partial_ratio_e`] and the logarithm of the ratio.
    ratio: f64,
    two_g2: f64,
    ln_ratio: f64,
    /// [`stick_parts`] with the table's `alpha_max`.
    stick: (f64, f64, Option<f64>),
    /// Per patch (indexed by `PatchId::index`), its kind and its line.
    patches: [Option<(PatchKind, PatchLine)>; 3],
}

impl LineAt {
    fn new(surface: &Surface, gamma: f64, e_n: f64) -> Option<LineAt> {
        let (ratio, two_g2) = partial_ratio_e(gamma, e_n);
        let mut patches = [None, None, None];
        for (id, p) in surface.patches() {
            patches[id.index()] = Some((p.kind(), p.line(gamma, e_n)?));
        }
        Some(LineAt {
            gamma,
            map: surface.partial_map(),
            ratio,
            two_g2,
            ln_ratio: ratio.ln(),
            stick: stick_parts(gamma, surface.alpha_max()),
            patches,
        })
    }

    /// `Surface::eval_in(region, γ, α, e_n)` at this line's `γ`, bit for bit.
    #[inline(always)]
    fn eval_in(&self, region: Region, alpha: f64, e_n: f64) -> f64 {
        let patch = region
            .patch_id()
            .and_then(|id| self.patches[id.index()].as_ref());
        match patch {
            Some((kind, line)) => {
                let c = match kind {
                    PatchKind::PartialSlip => {
                        partial_coord_from(self.map, alpha, self.ratio, self.two_g2, self.ln_ratio)
                    }
                    PatchKind::Stick => stick_coord_parts(alpha, self.stick),
                };
                line.interpolate(c.clamp(0.0, 1.0))
            }
            None => -e_n,
        }
    }
}

/// `P(α)` at one `(γ, e_n)` of a table with an `e_n` axis, with one domain choice: the rule's
/// `γ`- and `e_n`-only parts computed once ([`PairLine::p`]).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PairLine {
    /// The table it was built from ([`crate::Table`]'s identity).
    table: u64,
    /// `γ` as the rule takes it ([`Surface::rule_gamma`]), `e_n`, the domain choice.
    gamma: f64,
    e_n: f64,
    outside: OutOfDomain,
    /// [`Surface::line_end`]`(γ, e_n)` (`−∞` in a table without the line) and
    /// [`alpha_c2`]`(γ)`.
    line_end: f64,
    /// [`Surface::has_line`]: the region is [`Region::of_limits`], else [`Region::off_line`].
    has_line: bool,
    c2: f64,
    /// Off the full-slip line; `None` where every such query is refused (`γ` outside the
    /// table's range without clamping).
    at: Option<LineAt>,
}

impl PairLine {
    /// The line of `(γ, e_n)` with the domain choice `outside` through `surface` (the table
    /// `table`), or `None` where there is none: a table without an `e_n` axis or with another
    /// stencil than the cubic one, an `e_n` or `γ` it refuses, a line too deep for its index
    /// ([`oblique_table::line::MAX_LINE_ENTRIES`]).
    pub(crate) fn new(
        table: u64,
        surface: &Surface,
        gamma: f64,
        e_n: f64,
        outside: OutOfDomain,
    ) -> Option<PairLine> {
        if surface.restitution().is_none() || surface.stencil() != 4 {
            return None;
        }
        surface.check_e_n(e_n).ok()?;
        let gamma = surface.rule_gamma(gamma);
        check_query(gamma, 0.0).ok()?;
        let (lo, hi) = (surface.gamma_min(), surface.gamma_max());
        let at = if gamma >= lo && gamma <= hi {
            Some(LineAt::new(surface, gamma, e_n)?)
        } else if outside == OutOfDomain::Clamp {
            Some(LineAt::new(surface, gamma.clamp(lo, hi), e_n)?)
        } else {
            None
        };
        Some(PairLine {
            table,
            gamma,
            e_n,
            outside,
            line_end: surface.line_end(gamma, e_n),
            has_line: surface.has_line(),
            c2: alpha_c2(gamma),
            at,
        })
    }

    /// Whether this line was built from the table `table` ([`crate::Table`]'s identity).
    #[inline(always)]
    pub(crate) fn serves(&self, table: u64) -> bool {
        self.table == table
    }

    /// [`crate::Table::p_e_with`]`(γ, α, e_n, outside)` of the line, bit for bit.
    #[inline(always)]
    pub(crate) fn p(&self, surface: &Surface, alpha: f64) -> Result<f64, LookupError> {
        let (gamma, e_n) = (self.gamma, self.e_n);
        check_query(gamma, alpha)?;
        // `Surface::region_at`, from the γ- and e_n-only parts.
        let region = if self.has_line {
            Region::of_limits(gamma, alpha, self.line_end, || self.c2)
        } else {
            Region::off_line(gamma, alpha, || self.c2)
        };
        if region == Region::Line {
            return Ok(full_slip_line(alpha, e_n));
        }
        surface.apply_domain_e(region, gamma, alpha, e_n, self.outside, |r, g, a| {
            match &self.at {
                Some(at) if g == at.gamma => at.eval_in(r, a, e_n),
                // Not reached: `g` is the line's γ, or the clamped one it was built at.
                _ => surface.eval_in(r, g, a, e_n),
            }
        })
    }

    /// Bytes held by the patches' lines.
    pub(crate) fn bytes(&self) -> usize {
        self.at.as_ref().map_or(0, |at| {
            at.patches.iter().flatten().map(|(_, l)| l.bytes()).sum()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Table;

    fn table(name: &str) -> Table {
        Table::open(format!(
            "{}/../../tables/{name}",
            env!("CARGO_MANIFEST_DIR")
        ))
        .expect(name)
    }

    /// `x` moved by `k` units in the last place (`k` of either sign).
    fn ulps(x: f64, k: i64) -> f64 {
        f64::from_bits((x.to_bits() as i64 + k) as u64)
    }

    /// The line's answers against the table's at `α` over every region, on its edges (one
    /// unit in the last place either side), and invalid ones; returns the number compared.
    fn compare(t: &Table, line: &PairLine, gamma: f64, e_n: f64, o: OutOfDomain) -> usize {
        let mut alphas = vec![0.0, 1e-300, f64::INFINITY, f64::NAN, -1.0, 1e300];
        for edge in [line.line_end, line.c2] {
            alphas.extend((-2..=2).map(|k| ulps(edge, k)));
        }
        alphas.extend((0..=600).map(|i| 10f64.powf(-3.0 + 6.0 * i as f64 / 600.0)));
        for &alpha in &alphas {
            let fast = line.p(t.surface(), alpha);
            let rule = t.p_e_with(gamma, alpha, e_n, o);
            match (&fast, &rule) {
                (Ok(a), Ok(b)) => assert_eq!(
                    a.to_bits(),
                    b.to_bits(),
                    "({gamma}, {alpha}, {e_n}, {o:?}): {a} against {b}"
                ),
                _ => assert_eq!(
                    fast.map_err(|e| e.to_string()),
                    rule.map_err(|e| e.to_string()),
                    "({gamma}, {alpha}, {e_n}, {o:?})"
                ),
            }
        }
        alphas.len()
    }

    #[test]
    fn a_pair_line_gives_the_bits_of_the_table() {
        let mut compared = 0;
        for name in ["dissipative-demo.h5", "dissipative-pair.h5"] {
            let t = table(name);
            let s = t.surface();
            let (glo, ghi) = (s.gamma_min(), s.gamma_max());
            let mut gammas = vec![glo, ghi, 0.9, 1.0, 1.1, 2.5, ulps(glo, -1), ulps(ghi, 1)];
            gammas.extend((0..9).map(|i| glo + (ghi - glo) * (0.05 + 0.11 * i as f64)));
            if let Some(g) = s.pair_gamma() {
                // Within the pair's tolerance, and beyond it.
                gammas.extend([g * (1.0 + 5e-10), g * (1.0 - 5e-10), g * (1.0 + 1e-6)]);
            }
            let (elo, ehi) = s.restitution().expect("an e_n axis");
            let mut es = vec![elo, ehi];
            es.extend((0..7).map(|i| elo + (ehi - elo) * (0.03 + 0.15 * i as f64)));
            for &g in &gammas {
                for &e in &es {
                    for o in [OutOfDomain::Error, OutOfDomain::Clamp] {
                        let line = PairLine::new(t.id(), s, g, e, o).expect("a line");
                        assert!(line.serves(t.id()) && !line.serves(t.id() + 1));
                        compared += compare(&t, &line, g, e, o);
                    }
                }
            }
            // No line where the table refuses the e_n, or for an elastic table.
            for e in [ulps(elo, -1), ulps(ehi, 1), f64::NAN] {
                assert!(PairLine::new(t.id(), s, glo, e, OutOfDomain::Clamp).is_none());
            }
        }
        let elastic = table("quick.h5");
        let s = elastic.surface();
        assert!(PairLine::new(elastic.id(), s, 1.5, 1.0, OutOfDomain::Clamp).is_none());
        assert!(compared > 100_000, "{compared}");
    }
}
