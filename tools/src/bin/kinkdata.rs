//! Trace the Kelvin–Voigt kink surfaces that table builds take from
//! `crates/sweep/data/kink_surfaces.txt` (`oblique_sweep::kink::stored`) and print that file:
//! `cargo run --release -p oblique-tools --bin kinkdata > crates/sweep/data/kink_surfaces.txt`
//! (about 30 s on 2 cores).
fn main() -> anyhow::Result<()> {
    print!("{}", oblique_sweep::kink::stored::trace_all()?);
    Ok(())
}
