//! Shared argument handling of the developer probes in `src/bin/` (each prints numbers that
//! `docs/` cites; run one with `cargo run --release -p oblique-tools --bin NAME -- ARGS`).

use anyhow::{bail, Context, Result};

/// Argument `i` (0-based, after the program name) parsed as `T`, or `default` when absent.
pub fn arg_or<T: std::str::FromStr>(args: &[String], i: usize, name: &str, default: T) -> Result<T>
where
    T::Err: std::error::Error + Send + Sync + 'static,
{
    match args.get(i) {
        Some(s) => s
            .parse()
            .with_context(|| format!("argument {name} = '{s}'")),
        None => Ok(default),
    }
}

/// A required argument `i` parsed as `T`.
pub fn arg<T: std::str::FromStr>(args: &[String], i: usize, name: &str) -> Result<T>
where
    T::Err: std::error::Error + Send + Sync + 'static,
{
    let Some(s) = args.get(i) else {
        bail!("missing argument {name}")
    };
    s.parse()
        .with_context(|| format!("argument {name} = '{s}'"))
}

/// A point `gamma,alpha` (`inf` allowed for α).
pub fn point(s: &str) -> Result<(f64, f64)> {
    let (g, a) = s
        .split_once(',')
        .with_context(|| format!("'{s}': expected gamma,alpha"))?;
    let g: f64 = g.parse().with_context(|| format!("gamma in '{s}'"))?;
    let a: f64 = a.parse().with_context(|| format!("alpha in '{s}'"))?;
    Ok((g, a))
}

/// The command-line arguments after the program name.
pub fn args() -> Vec<String> {
    std::env::args().skip(1).collect()
}

/// The rows `tag,x_1,…,x_n[,…]` of standard input with `n` numbers after the tag: each as the
/// tag and its first `n` numbers; a line with fewer fields or a number that does not parse (a
/// header, a comment) is skipped.
pub fn tagged_rows(n: usize) -> Result<Vec<(String, Vec<f64>)>> {
    use std::io::BufRead;
    let mut rows = Vec::new();
    for line in std::io::stdin().lock().lines() {
        let line = line.context("reading standard input")?;
        let f: Vec<&str> = line.trim().split(',').collect();
        if f.len() <= n {
            continue;
        }
        let Ok(x) = f[1..=n].iter().map(|s| s.parse::<f64>()).collect() else {
            continue;
        };
        rows.push((f[0].to_string(), x));
    }
    Ok(rows)
}

/// Uniform numbers in `[0, 1)` from `seed` (xorshift64, 53 bits a draw): the draw of the tools
/// whose seeds the docs cite (`ladder`, `kvhonest`, `thornhonest`), unchanged so that they
/// print what the docs show.
pub fn xorshift(mut seed: u64) -> impl FnMut() -> f64 {
    move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64
    }
}
