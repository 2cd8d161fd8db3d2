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

/// The four arguments `GAMMA_LO GAMMA_HI E_LO E_HI` of a probe over a box of (γ, `e_n`);
/// `tool` names it in the usage message.
pub fn gamma_e_box(tool: &str) -> Result<[f64; 4]> {
    let a: Vec<f64> = args()
        .iter()
        .map(|s| s.parse())
        .collect::<Result<_, _>>()
        .with_context(|| format!("usage: {tool} GAMMA_LO GAMMA_HI E_LO E_HI"))?;
    let [g0, g1, e0, e1] = a[..] else {
        bail!("usage: {tool} GAMMA_LO GAMMA_HI E_LO E_HI");
    };
    Ok([g0, g1, e0, e1])
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

/// Least squares `min |A c − b|` by Householder QR (`A` is `m × n`, rows).
#[allow(clippy::needless_range_loop)] // Householder reflections read clearest with indices.
pub fn least_squares(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
    let (m, n) = (a.len(), a[0].len());
    for k in 0..n {
        let norm = (k..m).map(|i| a[i][k] * a[i][k]).sum::<f64>().sqrt();
        let alpha = if a[k][k] > 0.0 { -norm } else { norm };
        let mut v: Vec<f64> = (k..m).map(|i| a[i][k]).collect();
        v[0] -= alpha;
        let vv: f64 = v.iter().map(|x| x * x).sum();
        if vv == 0.0 {
            continue;
        }
        for j in k..n {
            let s: f64 = (k..m).map(|i| v[i - k] * a[i][j]).sum::<f64>() * 2.0 / vv;
            for i in k..m {
                a[i][j] -= s * v[i - k];
            }
        }
        let s: f64 = (k..m).map(|i| v[i - k] * b[i]).sum::<f64>() * 2.0 / vv;
        for i in k..m {
            b[i] -= s * v[i - k];
        }
    }
    let mut c = vec![0.0; n];
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|j| a[k][j] * c[j]).sum();
        c[k] = (b[k] - s) / a[k][k];
    }
    c
}

/// `T_0(u) … T_{n-1}(u)`.
pub fn chebyshev(u: f64, n: usize) -> Vec<f64> {
    let mut t = vec![1.0, u];
    while t.len() < n {
        let k = t.len();
        t.push(2.0 * u * t[k - 1] - t[k - 2]);
    }
    t.truncate(n);
    t
}

/// The points of `thornhonest` (and `thornshare`), `(γ, α, e_n)`: the nine benchmark points at
/// `e_n` 0.9 and 0.6, the cusp of Thornton's stick patch at γ = 1.9182, α = 3.1582,
/// `e_n` = 0.9143, then `n` random points of seed `seed`: γ 0.3–3.5 log-uniform, `e_n` uniform
/// in 0.3–1; α a tenth at ∞, a third within 1e-4–1e-1 (relative) of α = 2/7, the
/// Kelvin–Voigt `α_c1(γ, e_n)` or `α_c2`, the rest log-uniform over 0.01–30.
pub fn thornton_honesty_points(n: usize, seed: u64) -> Vec<(f64, f64, f64)> {
    use oblique_physics::regimes;
    let mut rnd = xorshift(seed);
    let mut points = Vec::new();
    for e in [0.9, 0.6] {
        for g in [0.5, 1.754, 3.0] {
            for a in [0.3, 1.0, f64::INFINITY] {
                points.push((g, a, e));
            }
        }
    }
    points.push((1.9182, 3.1582, 0.9143));
    for _ in 0..n {
        let g = 0.3 * (3.5f64 / 0.3).powf(rnd());
        let e = 0.3 + 0.7 * rnd();
        let pick = rnd();
        let a = if pick < 0.1 {
            f64::INFINITY
        } else if pick < 0.43 {
            let c1 = if g > 1.0 {
                regimes::alpha_c1_dissipative(g, e)
            } else {
                regimes::alpha_c2(g)
            };
            let curve = [2.0 / 7.0, c1, regimes::alpha_c2(g)][(rnd() * 3.0) as usize];
            let off = 10f64.powf(-4.0 + 3.0 * rnd()) * if rnd() < 0.5 { -1.0 } else { 1.0 };
            curve * (1.0 + off)
        } else {
            0.01 * 3000f64.powf(rnd())
        };
        points.push((g, a, e));
    }
    points
}
