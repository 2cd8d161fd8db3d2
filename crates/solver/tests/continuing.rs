//! A refinement continued from the levels of an earlier one (`Request::solve_continuing`)
//! answers with the bits of a refinement from scratch, and simulates only the levels beyond
//! those kept.

use oblique_solver::{Accuracy, KeptLevels, Law, RefineEvent, Request};

/// The levels a refinement of `req` runs (reported by the observer).
fn levels_run(req: &Request) -> usize {
    let mut n = 0;
    req.solve_observed(&mut |e| {
        if let RefineEvent::Finished { .. } = e {
            n += 1;
        }
    })
    .expect("solve");
    n
}

#[test]
fn a_continued_refinement_has_the_bits_of_one_from_scratch() {
    for (gamma, alpha, e_n, law) in [
        (1.754, 1.0, 1.0, Law::Elastic),
        (2.2, 0.98, 0.3, Law::KelvinVoigt),
        (1.9, 3.0, 0.85, Law::KelvinVoigt),
    ] {
        let at = |tol: f64| {
            Request::new(gamma, alpha)
                .e_n(e_n)
                .law(law)
                .accuracy(Accuracy::Tolerance(tol))
        };
        let mut kept = KeptLevels::new();
        let first = at(1.5e-6).solve_continuing(&mut kept).expect("first");
        assert_eq!(kept.len(), levels_run(&at(1.5e-6)));
        let coarse_levels = kept.len();
        let again = at(6e-7).solve_continuing(&mut kept).expect("again");
        let fresh = at(6e-7).solve().expect("fresh");
        assert_eq!(again.p.to_bits(), fresh.p.to_bits(), "γ {gamma}, α {alpha}");
        assert_eq!(
            again.error_estimate.to_bits(),
            fresh.error_estimate.to_bits()
        );
        assert_eq!(again.resolution, fresh.resolution);
        // Every level of the first solve was reused: the kept levels are the finer run's.
        assert_eq!(kept.len(), levels_run(&at(6e-7)));
        assert!(kept.len() >= coarse_levels);
        // The first answer is unchanged by keeping.
        assert_eq!(
            first.p.to_bits(),
            at(1.5e-6).solve().expect("plain").p.to_bits()
        );
    }
}

#[test]
fn levels_kept_for_another_request_are_dropped() {
    let req = |alpha: f64| {
        Request::new(1.754, alpha)
            .e_n(0.8)
            .law(Law::KelvinVoigt)
            .accuracy(Accuracy::Tolerance(1e-6))
    };
    let mut kept = KeptLevels::new();
    req(1.0).solve_continuing(&mut kept).expect("first");
    assert!(!kept.is_empty());
    // Another α: the levels of α = 1 would answer the wrong impact; they are dropped.
    let other = req(0.5).solve_continuing(&mut kept).expect("other");
    let fresh = req(0.5).solve().expect("fresh");
    assert_eq!(other.p.to_bits(), fresh.p.to_bits());
    assert_eq!(kept.len(), levels_run(&req(0.5)));
}
