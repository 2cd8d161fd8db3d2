//! The shipped configs as a user runs them: each parses, and its output goes to the git-ignored
//! `out/` folder, so the README's main command leaves the checkout unchanged.

use std::path::Path;

use oblique_sweep::Config;

#[test]
fn shipped_configs_write_outside_the_tracked_tables() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let ignore = std::fs::read_to_string(root.join(".gitignore")).expect(".gitignore");
    assert!(
        ignore.lines().any(|l| l.trim() == "/out/"),
        ".gitignore must ignore /out/"
    );
    for name in [
        "full",
        "isotropic",
        "quick",
        "dissipative-demo",
        "dissipative",
        "dissipative-pair",
        "dissipative-fold",
        "thornton-demo",
        "thornton-solid",
    ] {
        let path = root.join("configs").join(format!("{name}.toml"));
        let (cfg, _) = Config::load(&path).expect("shipped config parses");
        assert_eq!(
            cfg.output,
            Path::new("out").join(format!("{name}.h5")),
            "{name}.toml"
        );
    }
}
