//! `oblique_sweep::solve_points` solves its points grouped by `e_n` (a thread then computes a
//! dissipative law's normal motion once per run of one `e_n`) and answers them in their own
//! order, each as if solved alone.

use oblique_solver::{Accuracy, Law, Request};
use oblique_sweep::solve_points;
use oblique_table::surface::Point;

#[test]
fn points_are_answered_in_their_order_whatever_order_they_are_solved_in() {
    let law = Law::from_name("kelvin-voigt").unwrap();
    let e = [0.8, 0.5, 1.0, 0.8, 0.65, 0.5, 1.0, 0.8];
    let points: Vec<Point> = e
        .iter()
        .enumerate()
        .map(|(i, &e_n)| Point::new(1.5 + 0.05 * i as f64, 0.4 + 0.1 * i as f64, e_n))
        .collect();
    let all = solve_points(&points, 1e-5, law, &oblique_sweep::Silent).unwrap();
    for (pt, (p, est)) in points.iter().zip(all) {
        let alone = Request::new(pt.gamma, pt.alpha)
            .e_n(pt.e_n)
            .law(law)
            .accuracy(Accuracy::Tolerance(1e-5))
            .solve()
            .unwrap();
        assert_eq!(
            (p.to_bits(), est.to_bits()),
            (alone.p.to_bits(), alone.error_estimate.to_bits()),
            "gamma {}, alpha {}, e_n {}",
            pt.gamma,
            pt.alpha,
            pt.e_n
        );
    }
}
