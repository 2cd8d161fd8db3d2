//! Figures of a table (`oblique_study::figures`): every plotted grid, curve, region and point
//! is checked against independent queries of the table (`Table::p`, `Table::p_e`, its
//! held-out checks, the critical values). `sweep plot` itself is checked in the root
//! package's `tests/cli_plot.rs`.

use std::path::PathBuf;
use std::sync::OnceLock;

use oblique_lookup::Table;
use oblique_physics::regimes::{no_slip_fit, Regime};
use oblique_plot::{Series, Style};
use oblique_study::figures::{self, alpha_at, compact, Source, REGIME_LABELS};
use oblique_table::surface::{alpha_c1, alpha_c2, linear_limit};

/// The repository root, where the shipped tables are.
fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn full() -> &'static Table {
    static T: OnceLock<Table> = OnceLock::new();
    T.get_or_init(|| Table::open(root().join("tables/full.h5")).expect("shipped table full.h5"))
}

fn quick() -> &'static Table {
    static T: OnceLock<Table> = OnceLock::new();
    T.get_or_init(|| Table::open(root().join("tables/quick.h5")).expect("shipped table quick.h5"))
}

fn src() -> Source {
    Source {
        table: "tables/full.h5".into(),
        command: "sweep plot tables/full.h5 -o out".into(),
    }
}

fn series<'a>(all: &'a [Series], label: &str) -> &'a Series {
    all.iter()
        .find(|s| s.label == label)
        .unwrap_or_else(|| panic!("no series '{label}' in {:?}", labels(all)))
}

fn labels(all: &[Series]) -> Vec<&str> {
    all.iter().map(|s| s.label.as_str()).collect()
}

/// The critical curves and the isotropic band, as every (γ, α) figure draws them.
fn check_overlays(all: &[Series], t: &Table) {
    let c2 = series(all, "α_c2 = 2γ²/7");
    let c1 = series(all, "α_c1 = 2γ²/(7(2γ² − 1)), γ > 1");
    assert!(c2.points.len() > 100 && c1.points.len() > 100);
    for &(g, y) in &c2.points {
        assert!((alpha_at(y) - alpha_c2(g)).abs() < 1e-12 * alpha_c2(g).max(1.0));
    }
    for &(g, y) in &c1.points {
        assert!(
            g >= 1.0,
            "α_c1 drawn at γ = {g} < 1, where it marks nothing"
        );
        assert!((alpha_at(y) - alpha_c1(g)).abs() < 1e-12);
    }
    let (lo, hi) = (t.surface().gamma_min(), t.surface().gamma_max());
    assert_eq!(c2.points.first().unwrap().0, lo);
    assert_eq!(c2.points.last().unwrap().0, hi);
    let band: Vec<f64> = all
        .iter()
        .filter(|s| s.style == Style::Dotted)
        .map(|s| {
            assert_eq!(s.points[0].0, s.points[1].0, "band edges are vertical");
            s.points[0].0
        })
        .collect();
    assert_eq!(band, vec![1.52, 2.16]);
}

#[test]
fn surface_map_is_the_table_on_its_grid_up_to_alpha_infinity() {
    let t = full();
    let sheet = figures::surface(t, &src()).unwrap();
    assert_eq!(sheet.charts.len(), 1);
    let chart = &sheet.charts[0];
    let grid = chart.map.as_ref().expect("colour map");
    let (nx, ny) = (grid.xs.len(), grid.ys.len());
    assert!(nx >= 200 && ny >= 200, "{nx} x {ny}");
    assert_eq!(grid.values.len(), nx * ny);
    // The grid spans the whole domain; the top row is α = ∞.
    assert_eq!(grid.xs[0], t.surface().gamma_min());
    assert_eq!(grid.xs[nx - 1], t.surface().gamma_max());
    assert_eq!(grid.ys[0], 0.0);
    assert_eq!(grid.ys[ny - 1], 1.0);
    assert!(alpha_at(grid.ys[ny - 1]).is_infinite());
    for (i, &g) in grid.xs.iter().enumerate() {
        for (j, &y) in grid.ys.iter().enumerate() {
            let want = t.p(g, alpha_at(y)).unwrap();
            assert_eq!(grid.value(i, j), want, "node γ = {g}, y = {y}");
        }
    }
    // Physics the map must show: the exact line below the linear limit, P = −1 near γ = 1 for
    // large α, the no-slip limit near seed 001's fit on the top edge.
    let mut line_nodes = 0;
    for (i, &g) in grid.xs.iter().enumerate() {
        for (j, &y) in grid.ys.iter().enumerate() {
            let a = alpha_at(y);
            if a <= linear_limit(g) {
                assert!((grid.value(i, j) - (1.0 - 7.0 * a)).abs() < 1e-12);
                line_nodes += 1;
            }
        }
        // Seed 001's fit holds to about 0.02 up to γ ≈ 2.8 and drifts away beyond.
        assert!(
            g > 2.8 || (grid.value(i, ny - 1) - no_slip_fit(g)).abs() < 0.03,
            "no-slip edge at γ = {g}: {} vs fit {}",
            grid.value(i, ny - 1),
            no_slip_fit(g)
        );
    }
    assert!(line_nodes > nx * 5, "full-slip part covered");
    let scale = chart.color_scale.as_ref().expect("colour bar");
    assert_eq!(scale.range, (-1.0, 1.0));
    assert!(scale.label.contains('P'));
    let ct = chart.contours.as_ref().expect("contours");
    assert_eq!(ct.bold, vec![0.0]);
    assert_eq!(ct.levels.len(), 8);
    check_overlays(&chart.series, t);
    // Labelled axes, α = ∞ at the end of the α axis.
    assert!(chart.x.label.contains('γ') && chart.y.label.contains('α'));
    match &chart.y.ticks {
        oblique_plot::Ticks::Fixed(ticks) => {
            assert_eq!(ticks.last().unwrap(), &(1.0, "∞".to_string()));
        }
        other => panic!("α axis needs fixed ticks with ∞, got {other:?}"),
    }
    // Provenance caption.
    assert!(sheet.caption[0].contains("tables/full.h5"));
    assert!(sheet.caption[0].contains(&t.provenance().created));
    assert!(sheet.caption[1].contains("sweep plot tables/full.h5"));
}

#[test]
fn slices_are_the_table_along_fixed_gamma_and_fixed_alpha() {
    let t = full();
    let gammas = [0.5, 1.0, 1.754, 3.2];
    let alphas = [0.2, 1.0, 12.0, f64::INFINITY];
    let sheet = figures::slices(t, &src(), &gammas, &alphas).unwrap();
    assert_eq!(sheet.charts.len(), 2);
    let (a, b) = (&sheet.charts[0], &sheet.charts[1]);

    // (a) P against α: one curve per γ, from α = 0 to α = ∞, equal to the table.
    for (k, &g) in gammas.iter().enumerate() {
        let s = &a.series[k];
        assert_eq!(s.label, format!("γ = {g}"));
        assert_eq!(s.points.first().unwrap().0, 0.0);
        assert_eq!(s.points.last().unwrap().0, 1.0, "curve reaches α = ∞");
        assert!(s.points.windows(2).all(|w| w[0].0 < w[1].0));
        for &(y, p) in &s.points {
            assert_eq!(p, t.p(g, alpha_at(y)).unwrap(), "γ = {g}, y = {y}");
        }
        // The kinks are sampled exactly.
        for crit in [alpha_c1(g), alpha_c2(g)] {
            if g > 1.0 || crit == alpha_c2(g) {
                assert!(
                    s.points.iter().any(|&(y, _)| y == compact(crit)),
                    "γ = {g}: no point at α_c = {crit}"
                );
            }
        }
        // Dots at the critical values, on the curve.
        let dots = &a.series[gammas.len() + k];
        assert_eq!(dots.style, Style::Markers);
        let want: Vec<f64> = if g > 1.0 {
            vec![alpha_c1(g), alpha_c2(g)]
        } else {
            vec![alpha_c2(g)]
        };
        assert_eq!(dots.points.len(), want.len());
        for (&(y, p), &ac) in dots.points.iter().zip(&want) {
            assert_eq!(y, compact(ac));
            assert_eq!(p, t.p(g, ac).unwrap());
        }
    }
    let line = series(&a.series, "full slip: P = 1 − 7α");
    for &(y, p) in &line.points {
        assert!((p - (1.0 - 7.0 * alpha_at(y))).abs() < 1e-12 || !p.is_finite());
    }

    // (b) P against γ: one curve per α (∞ included), over the whole domain.
    for (k, &al) in alphas.iter().enumerate() {
        let s = &b.series[k];
        if al.is_infinite() {
            assert_eq!(s.label, "α = ∞ (no slip)");
        } else {
            assert_eq!(s.label, format!("α = {al}"));
        }
        assert_eq!(s.points.first().unwrap().0, t.surface().gamma_min());
        assert_eq!(s.points.last().unwrap().0, t.surface().gamma_max());
        for &(g, p) in &s.points {
            assert_eq!(p, t.p(g, al).unwrap(), "α = {al}, γ = {g}");
        }
        assert!(s.points.iter().any(|&(g, _)| g == 1.0), "γ = 1 is sampled");
    }
    let fit = series(&b.series, "seed 001 fit (29) of P(γ, ∞)");
    for &(g, p) in &fit.points {
        assert_eq!(p, no_slip_fit(g));
        let want = (-1.0 + 2.0 * (-0.195 * g).exp() * (1.685 * (g - 0.061)).cos().powi(2)) - p;
        assert!(want.abs() < 1e-15);
    }
    // The table's no-slip curve and the fit agree to about 0.02 up to γ ≈ 2.8 (a fit, not
    // the truth: physics.md), and not beyond: at γ = 3.5 they differ by about 0.25.
    let inf = &b.series[alphas.len() - 1];
    let dev = |range: std::ops::RangeInclusive<f64>| {
        inf.points
            .iter()
            .filter(|(g, _)| range.contains(g))
            .map(|&(g, p)| (p - no_slip_fit(g)).abs())
            .fold(0.0, f64::max)
    };
    let near = dev(0.0..=2.8);
    assert!(
        near > 1e-3 && near < 0.03,
        "max |table − fit|, γ ≤ 2.8: {near}"
    );
    assert!(dev(3.3..=3.5) > 0.1);
}

#[test]
fn default_families_and_bad_families() {
    let t = quick();
    let g = figures::default_gammas(t);
    assert!(g.len() >= 4);
    assert!(g
        .iter()
        .all(|&x| x >= t.surface().gamma_min() && x <= t.surface().gamma_max()));
    assert!(g.contains(&1.52) && g.contains(&2.16));
    let a = figures::default_alphas(t);
    assert!(a.last().unwrap().is_infinite());
    // The sheet holds one curve per γ (P against the compact α, the table's values at the
    // critical α included) and one per α (P against γ), each |P| ≤ 1.
    let sheet = figures::slices(t, &src(), &g, &a).expect("slices");
    assert_eq!(sheet.charts.len(), 2);
    for (k, &gamma) in g.iter().enumerate() {
        let curve = &sheet.charts[0].series[k];
        assert!(curve.points.len() >= figures::SLICE_SAMPLES);
        for &(y, p) in &curve.points {
            let want = t.p(gamma, figures::alpha_at(y)).expect("in the domain");
            assert_eq!(p.to_bits(), want.to_bits(), "gamma {gamma}, y {y}");
        }
    }
    for (k, &alpha) in a.iter().enumerate() {
        let curve = &sheet.charts[1].series[k];
        assert!(curve.points.len() >= 341);
        for &(gamma, p) in &curve.points {
            assert!(p.abs() <= 1.0);
            assert_eq!(p.to_bits(), t.p(gamma, alpha).expect("P").to_bits());
        }
    }
    for (gs, al, what) in [
        (vec![0.2], a.clone(), "gammas"),
        (vec![2.6], a.clone(), "gammas"),
        (vec![], a.clone(), "gammas"),
        (g.clone(), vec![-0.1], "alphas"),
        (g.clone(), vec![f64::NAN], "alphas"),
        (g.clone(), vec![1.0; 17], "alphas"),
    ] {
        let err = figures::slices(t, &src(), &gs, &al).unwrap_err();
        assert!(
            matches!(err, figures::FigureError::Invalid { name, .. } if name == what),
            "{err}"
        );
    }
}

/// Ray casting: is `p` inside the polygon?
fn inside(poly: &[(f64, f64)], (x, y): (f64, f64)) -> bool {
    let mut c = false;
    let n = poly.len();
    for i in 0..n {
        let (xi, yi) = poly[i];
        let (xj, yj) = poly[(i + n - 1) % n];
        if (yi > y) != (yj > y) && x < (xj - xi) * (y - yi) / (yj - yi) + xi {
            c = !c;
        }
    }
    c
}

#[test]
fn regime_diagram_classifies_the_plane_like_the_physics() {
    let t = full();
    let sheet = figures::regimes(t, &src());
    let chart = &sheet.charts[0];
    let labels: Vec<&str> = chart.regions.iter().map(|r| r.label.as_str()).collect();
    assert_eq!(labels, REGIME_LABELS.to_vec());
    let regime_of_region = [Regime::FullSlip, Regime::PartialSlip, Regime::Stick];
    let (lo, hi) = (t.surface().gamma_min(), t.surface().gamma_max());
    let mut checked = [0usize; 3];
    for i in 0..=70 {
        let g = lo + (hi - lo) * (i as f64 + 0.5) / 71.0;
        for j in 0..=60 {
            let y = (j as f64 + 0.5) / 61.0;
            // Skip points within 0.01 (in y) of a boundary: the polygons are sampled curves.
            let near = [alpha_c1(g), alpha_c2(g), linear_limit(g)]
                .iter()
                .any(|&a| a > 0.0 && (compact(a) - y).abs() < 0.01);
            if near {
                continue;
            }
            let want = Regime::of(g, alpha_at(y));
            let hits: Vec<usize> = chart
                .regions
                .iter()
                .enumerate()
                .filter(|(_, r)| inside(&r.polygon, (g, y)))
                .map(|(k, _)| k)
                .collect();
            assert_eq!(hits.len(), 1, "(γ, y) = ({g}, {y}) in regions {hits:?}");
            assert_eq!(
                regime_of_region[hits[0]],
                want,
                "(γ, α) = ({g}, {})",
                alpha_at(y)
            );
            checked[hits[0]] += 1;
        }
    }
    assert!(checked.iter().all(|&n| n > 100), "{checked:?}");
    check_overlays(&chart.series, t);
}

#[test]
fn quality_map_shows_every_held_out_check_with_its_true_error() {
    let t = full();
    let sheet = figures::quality(t, &src());
    let chart = &sheet.charts[0];
    let sc = chart.scatter.as_ref().expect("held-out points");
    assert_eq!(sc.points.len(), t.checks().len());
    assert!(t.checks().len() >= 100);
    for (&(g, y, err), c) in sc.points.iter().zip(t.checks()) {
        assert_eq!(g, c.gamma);
        assert_eq!(y, compact(c.alpha));
        assert_eq!(err, c.interpolation_error);
        // The stored error is the table's actual error there: recompute it by a lookup.
        let recomputed = (t.p(c.gamma, c.alpha).unwrap() - c.p_simulated).abs();
        assert!(
            (recomputed - err).abs() < 1e-12,
            "check at ({}, {}): stored {err}, lookup gives {recomputed}",
            c.gamma,
            c.alpha
        );
    }
    // The colour bar covers every error.
    let scale = chart.color_scale.as_ref().unwrap();
    let max = t
        .checks()
        .iter()
        .map(|c| c.interpolation_error)
        .fold(0.0, f64::max);
    assert!(scale.range.0 <= max && max <= scale.range.1);
    assert!(sheet.subtitle.contains(&format!("max {max:.1e}")));
    // One closed outline per quadtree leaf, inside the domain.
    let s = &t.surface();
    let leaves: usize = s.patches().map(|(_, p)| p).map(|p| p.leaves()).sum();
    assert_eq!(chart.outlines.len(), leaves);
    for o in &chart.outlines {
        assert_eq!(o.first(), o.last());
        for &(g, y) in o {
            assert!(g >= s.gamma_min() - 1e-12 && g <= s.gamma_max() + 1e-12);
            assert!((0.0..=1.0).contains(&y));
        }
    }
    check_overlays(&chart.series, t);
}

fn dissipative() -> &'static Table {
    static T: OnceLock<Table> = OnceLock::new();
    T.get_or_init(|| {
        Table::open(root().join("tables/dissipative-demo.h5")).expect("shipped dissipative table")
    })
}

/// `p_restitution`: every point of every curve is an independent `Table::p_e` query, `e_n = 1`
/// is the elastic curve, the full-slip lines are `1 − (7/2)(1 + e_n)α` and the dots sit at
/// `α_c1(e_n)`.
#[test]
fn restitution_figure_plots_the_table_at_each_e_n_beside_the_elastic_curve() {
    let t = dissipative();
    let gammas = figures::default_restitution_gammas(t);
    let e_ns = figures::default_restitutions(t);
    assert_eq!(gammas, [1.52, 1.84]);
    assert_eq!(e_ns, [0.5, 0.7, 0.9, 1.0]);
    let sheet = figures::restitution(t, &src(), &gammas, &e_ns).unwrap();
    assert_eq!(sheet.charts.len(), 2);
    for (chart, &g) in sheet.charts.iter().zip(&gammas) {
        let all = &chart.series;
        for (k, &e) in e_ns.iter().enumerate() {
            let label = if e == 1.0 {
                "elastic (e_n = 1)".to_string()
            } else {
                format!("e_n = {e}")
            };
            let curve = series(all, &label);
            assert!(std::ptr::eq(curve, &all[k]));
            assert_eq!(curve.points.len(), figures::SLICE_SAMPLES + 1);
            for &(y, p) in &curve.points {
                assert_eq!(p.to_bits(), t.p_e(g, alpha_at(y), e).unwrap().to_bits());
            }
            if e == 1.0 {
                assert_eq!(curve.color, (0, 0, 0));
                // The e_n = 1 slice is the elastic surface (within the table's bound).
                for &(y, p) in curve.points.iter().step_by(40) {
                    let a = alpha_at(y);
                    if a.is_finite() {
                        let el = oblique_solver::Request::new(g, a).solve().unwrap().p;
                        assert!((p - el).abs() < t.error_bound() + 1e-5, "γ {g} α {a}");
                    }
                }
            }
            let c1 = oblique_physics::regimes::alpha_c1_dissipative(g, e);
            let line = &all[e_ns.len() + 2 * k];
            assert_eq!(line.style, Style::Dashed);
            assert!(!line.points.is_empty());
            for &(y, p) in &line.points {
                let a = alpha_at(y);
                assert!((p - (1.0 - 3.5 * (1.0 + e) * a)).abs() < 1e-12);
            }
            let dots = &all[e_ns.len() + 2 * k + 1];
            assert_eq!(dots.points, [(compact(c1), t.p_e(g, c1, e).unwrap())]);
            // The table holds the exact full-slip line up to α_c1(e_n).
            assert!(
                (t.p_e(g, 0.9 * c1, e).unwrap() - (1.0 - 3.5 * (1.0 + e) * 0.9 * c1)).abs() < 1e-9
            );
        }
    }
    // Bad requests name the option.
    let bad = |r: Result<_, figures::FigureError>, name: &str| match r {
        Err(figures::FigureError::Invalid { name: n, .. }) => assert_eq!(n, name),
        other => panic!("{name}: {:?}", other.map(|_: oblique_plot::Sheet| ())),
    };
    bad(figures::restitution(t, &src(), &[1.52], &[0.3]), "e-n");
    bad(figures::restitution(t, &src(), &[2.5], &[0.7]), "gammas");
    bad(
        figures::restitution(t, &src(), &[1.3, 1.5, 1.7], &[0.7]),
        "gammas",
    );
    bad(
        figures::restitution(quick(), &src(), &[1.52], &[1.0]),
        "figure",
    );
}
