//! The table built into the library (`Table::embedded`): the shipped tables/default.h5, the
//! same answers to the bit, opened through a private temporary file that does not outlive the
//! call. (One test in this file: it sets TMPDIR for the whole process.)

use oblique_lookup::{Table, EMBEDDED_TABLE};

#[test]
fn embedded_table_is_the_shipped_default_table_and_leaves_no_file() {
    assert_eq!(EMBEDDED_TABLE, "tables/default.h5");
    let shipped = Table::open(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tables/default.h5"
    ))
    .expect("default.h5");
    let tmp = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("embedded-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&tmp);
    std::fs::create_dir_all(&tmp).expect("tmp");
    std::env::set_var("TMPDIR", &tmp);
    let start = std::time::Instant::now();
    let built_in = Table::embedded().expect("the built-in table");
    let elapsed = start.elapsed();
    assert_eq!(built_in.provenance(), shipped.provenance());
    assert_eq!(built_in.error_bound(), shipped.error_bound());
    assert_eq!(built_in.checks().len(), shipped.checks().len());
    let mut next = oblique_lookup::testing::uniform(7);
    // The catalogue's bodies (`sweep gamma --catalogue`): solid spheres 1.58-1.75, thin
    // shells down to 1.33; one isotropic material up to 2.16.
    let (lo, hi) = (
        built_in.surface().gamma_min(),
        built_in.surface().gamma_max(),
    );
    assert!(lo <= 1.33 && hi >= 2.16, "gamma range [{lo}, {hi}]");
    assert_eq!(built_in.surface().restitution(), Some((0.3, 1.0)));
    assert!(built_in.error_bound() <= 1e-5, "{}", built_in.error_bound());
    for i in 0..20_000 {
        let g = lo + (hi - lo) * next();
        let a = if i % 50 == 0 {
            f64::INFINITY
        } else {
            3.0 * next()
        };
        let e = if i % 10 == 0 { 1.0 } else { 0.3 + 0.7 * next() };
        let (x, y) = (
            built_in.p_e(g, a, e).unwrap(),
            shipped.p_e(g, a, e).unwrap(),
        );
        assert_eq!(x.to_bits(), y.to_bits(), "gamma {g}, alpha {a}, e_n {e}");
        if e == 1.0 {
            // No e_n given: the elastic surface.
            assert_eq!(built_in.p(g, a).unwrap().to_bits(), x.to_bits());
        }
    }
    // Threads open it at once: each its own temporary file.
    std::thread::scope(|s| {
        for _ in 0..4 {
            s.spawn(|| Table::embedded().expect("concurrent"));
        }
    });
    let left: Vec<_> = std::fs::read_dir(&tmp).expect("tmp").collect();
    assert!(left.is_empty(), "temporary files left behind: {left:?}");
    // A temporary folder that cannot be written: an error naming it, no panic.
    std::env::set_var("TMPDIR", tmp.join("missing"));
    let e = Table::embedded().expect_err("no temporary folder");
    let text = e.to_string();
    assert!(
        text.contains("built-in tables/default.h5") && text.contains("TMPDIR"),
        "{text}"
    );
    std::env::set_var("TMPDIR", &tmp);
    eprintln!("Table::embedded: {:.1} ms", elapsed.as_secs_f64() * 1e3);
    let _ = std::fs::remove_dir_all(&tmp);
}
