//! The table built into the library (`Table::embedded`): the shipped tables/isotropic.h5, the
//! same answers to the bit, opened through a private temporary file that does not outlive the
//! call. (One test in this file: it sets TMPDIR for the whole process.)

use oblique_lookup::{Table, EMBEDDED_TABLE};

#[test]
fn embedded_table_is_the_shipped_isotropic_table_and_leaves_no_file() {
    assert_eq!(EMBEDDED_TABLE, "tables/isotropic.h5");
    let shipped = Table::open(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../tables/isotropic.h5"
    ))
    .expect("isotropic.h5");
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
    for i in 0..20_000 {
        let g = 1.52 + 0.64 * next();
        let a = if i % 50 == 0 {
            f64::INFINITY
        } else {
            3.0 * next()
        };
        let (x, y) = (built_in.p(g, a).unwrap(), shipped.p(g, a).unwrap());
        assert_eq!(x.to_bits(), y.to_bits(), "gamma {g}, alpha {a}");
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
        text.contains("built-in tables/isotropic.h5") && text.contains("TMPDIR"),
        "{text}"
    );
    std::env::set_var("TMPDIR", &tmp);
    eprintln!("Table::embedded: {:.1} ms", elapsed.as_secs_f64() * 1e3);
    let _ = std::fs::remove_dir_all(&tmp);
}
