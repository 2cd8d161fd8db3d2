//! `sweep query`: answer `P(γ, α)` or `P(γ, α, e_n)` from a table (no simulation), one point
//! or a batch.

use crate::failure::outln;
use std::io::{BufRead, BufWriter, Write};
use std::path::PathBuf;

use oblique_physics::regimes::tangential_restitution;

use crate::failure::{Context, Failure, Result};
use clap::Args;
use serde_json::json;

use oblique_lookup::columns::{Column, PointColumns};
use oblique_lookup::{LookupError, OutOfDomain, Table};
use oblique_table::surface::{linear_limit_dissipative, Region, Surface};

#[derive(Args)]
pub struct QueryArgs {
    /// Table file written by `sweep run` (HDF5, schema v2 to v5). Default: the table built into
    /// sweep, tables/default.h5 (Kelvin-Voigt law: 1.3 <= gamma <= 2.2, alpha from 0 to inf,
    /// 0.3 <= e_n <= 1; every body of the material catalogue; stated error bound 8.1e-6).
    table: Option<PathBuf>,
    /// Material group gamma = sqrt((m*/m_t) G*/E*) (`sweep gamma`); a finite number > 0.
    #[arg(long, value_parser = crate::args::parse_table_gamma, allow_hyphen_values = true,
          conflicts_with = "batch", requires = "alpha")]
    gamma: Option<f64>,
    /// Friction group alpha = (2/7)(m*/m_t) mu v_z0/|u0|; >= 0, or `inf` for no slip.
    #[arg(long, value_parser = crate::args::parse_alpha, allow_hyphen_values = true,
          conflicts_with = "batch", requires = "gamma")]
    alpha: Option<f64>,
    /// Normal restitution e_n of the impact, in the table's e_n range (a table built with
    /// domain.e_n_min and e_n_max); an elastic table answers e_n = 1 only. Default 1.
    #[arg(long = "e-n", value_name = "E_N", value_parser = crate::args::parse_f64, allow_hyphen_values = true,
          conflicts_with = "batch")]
    e_n: Option<f64>,
    /// The value of an axis beyond gamma and alpha, AXIS=VALUE (repeatable; `sweep inspect`
    /// lists a table's axes): `--at e_n=0.8` is `--e-n 0.8`. An axis not given is at its
    /// fixed value (e_n = 1).
    #[arg(long = "at", value_name = "AXIS=VALUE", value_parser = parse_at,
          conflicts_with = "batch")]
    at: Vec<(&'static str, f64)>,
    /// Read lines `gamma,alpha` (or `gamma,alpha,e_n`) from FILE (`-` for stdin) and write
    /// lines `gamma,alpha,P,e_t` (or `gamma,alpha,e_n,P,e_t`) in the same order.
    #[arg(long, value_name = "FILE")]
    batch: Option<PathBuf>,
    /// Answer a gamma (alpha) outside the table's domain at the nearest gamma (alpha_max) of
    /// the table instead of refusing it.
    #[arg(long)]
    clamp: bool,
    /// Print one JSON object (single query only; alpha = inf is written as the string "inf").
    #[arg(long, conflicts_with = "batch")]
    json: bool,
}

/// `--at AXIS=VALUE`: an axis of [`oblique_lookup::EXTRA_AXES`] and a number.
fn parse_at(s: &str) -> std::result::Result<(&'static str, f64), String> {
    let names = || {
        oblique_lookup::EXTRA_AXES
            .iter()
            .map(|a| a.name)
            .collect::<Vec<_>>()
            .join(", ")
    };
    let Some((name, value)) = s.split_once('=') else {
        return Err(format!(
            "`{s}` is not AXIS=VALUE (e.g. e_n=0.8); the axes beyond gamma and alpha are {}",
            names()
        ));
    };
    let axis = oblique_lookup::ExtraAxis::named(name.trim()).ok_or_else(|| {
        format!(
            "unknown axis `{name}`: the axes beyond gamma and alpha are {} (gamma and alpha \
             are --gamma and --alpha)",
            names()
        )
    })?;
    Ok((axis.name, crate::args::parse_f64(value)?))
}

/// A bad query or batch line: exit status 2 (as for a table that cannot be read). The
/// arguments were checked when they were parsed, so a query the table refuses lies outside its
/// domain, and the message names the flag that answers there anyway.
fn usage(e: LookupError) -> Failure {
    match e {
        LookupError::Query { .. } | LookupError::Batch { .. } => {
            Failure::usage(format!("{e} (--clamp)"))
        }
        other => other.into(),
    }
}

fn region_name(surface: &Surface, gamma: f64, alpha: f64, e_n: f64) -> &'static str {
    let inside = gamma >= surface.gamma_min() && gamma <= surface.gamma_max();
    match surface.region_at(gamma, alpha, e_n) {
        Region::Line => "full-slip line (closed form)",
        _ if !inside || alpha > surface.alpha_max() => "outside the table (clamped)",
        // A table without the closed-form line (Thornton's law) interpolates full slip too.
        Region::PartialHigh if alpha <= linear_limit_dissipative(gamma, e_n) => {
            "full slip, alpha <= alpha_c1 (interpolated)"
        }
        Region::PartialHigh => "partial slip (interpolated)",
        Region::StickLow | Region::StickHigh if alpha.is_infinite() => {
            "no slip, alpha = inf (interpolated)"
        }
        Region::StickLow | Region::StickHigh => "stick (interpolated)",
    }
}

pub fn run(args: QueryArgs) -> Result<()> {
    let (table, name) = match &args.table {
        Some(path) => (Table::open(path)?, path.display().to_string()),
        None => (Table::embedded()?, oblique_lookup::embedded_name()),
    };
    let outside = if args.clamp {
        OutOfDomain::Clamp
    } else {
        OutOfDomain::Error
    };
    if let Some(path) = &args.batch {
        return batch(&table, path, outside);
    }
    let (Some(gamma), Some(alpha)) = (args.gamma, args.alpha) else {
        return Err(Failure::usage(
            "nothing to answer: give --gamma G --alpha A for one point, or --batch FILE for \
             lines `gamma,alpha` (FILE `-` reads standard input)"
                .into(),
        ));
    };
    // The extra axes: `--e-n` is `--at e_n=`.
    let extra: Vec<(&str, f64)> = args
        .e_n
        .map(|e| (oblique_lookup::E_N.name, e))
        .into_iter()
        .chain(args.at.iter().copied())
        .collect();
    let e_n = extra
        .iter()
        .find(|a| a.0 == oblique_lookup::E_N.name)
        .map_or(1.0, |a| a.1);
    let e_n_flag = if args.e_n.is_some() { "--e-n" } else { "--at" };
    let p = table
        .p_axes_with(gamma, alpha, &extra, outside)
        .map_err(|e| match e {
            LookupError::Query { name: "e_n", .. } => Failure::usage(format!("{e_n_flag}: {e}")),
            LookupError::Axis { .. } => Failure::usage(format!("--at: {e}")),
            LookupError::Query { name: "gamma", .. } if args.table.is_none() => {
                let other = if e_n < 1.0 {
                    "build a table with an e_n range that holds this gamma (sweep run \
                     configs/dissipative.toml: 1 <= gamma <= 2.6, or your own config)"
                } else {
                    "give tables/full.h5 of the repository for 0.1 <= gamma <= 3.5"
                };
                Failure::usage(format!(
                    "{e} (--clamp); the built-in table is {} (1.3 <= gamma <= 2.2): {other}",
                    oblique_lookup::EMBEDDED_TABLE
                ))
            }
            other => usage(other),
        })?;
    let region = region_name(table.surface(), gamma, alpha, e_n);
    let error = if table.surface().region_at(gamma, alpha, e_n) == Region::Line {
        0.0
    } else {
        table.error_bound()
    };
    if args.json {
        let out = json!({
            "gamma": gamma,
            "alpha": crate::args::json_number(alpha),
            "e_n": e_n,
            "P": p,
            "e_t": tangential_restitution(p),
            "region": region,
            "error_bound": error,
            "table": name,
        });
        outln!("{out}")?;
    } else {
        let e_n_words: String = extra
            .iter()
            .map(|(n, v)| format!(", {n} = {}", crate::args::fmt_num(*v)))
            .collect();
        outln!(
            "P(gamma = {}, alpha = {}{e_n_words}) = {p:.9}  +/- {error:.1e}",
            crate::args::fmt_num(gamma),
            crate::args::fmt_num(alpha)
        )?;
        outln!(
            "e_t = (2P + 5)/7 = {:.9}   (solid sphere, no initial spin)",
            tangential_restitution(p)
        )?;
        outln!("{region}, from {name}")?;
    }
    Ok(())
}

/// The longest batch line, in bytes before its line end: a longer one is refused after reading
/// at most this many bytes of it (`--batch /dev/zero` has no line end at all).
const MAX_LINE: usize = 4096;

/// The most characters of a line or field that a message quotes.
const QUOTE_CHARS: usize = 60;

/// Points answered at a time: the answers of one chunk are held, never a whole column of them.
const CHUNK: usize = 1 << 16;

/// `text` as a message quotes it: whole when short, else its first [`QUOTE_CHARS`] characters
/// and its length.
fn excerpt(text: &str) -> String {
    match text.char_indices().nth(QUOTE_CHARS) {
        None => text.to_string(),
        Some((end, _)) => format!("{}... ({} bytes)", &text[..end], text.len()),
    }
}

/// Parse one batch line `gamma,alpha` (`fields = 2`) or `gamma,alpha,e_n` (`fields = 3`)
/// (1-based `number` for messages, which quote at most [`QUOTE_CHARS`] characters of it).
fn parse_line(line: &str, number: usize, fields: usize) -> Result<(f64, f64, f64)> {
    let expected = if fields == 3 {
        "`gamma,alpha,e_n` like the first line (e.g. `1.75,0.3,0.8`, alpha may be `inf`)"
    } else {
        "`gamma,alpha` like the first line (e.g. `1.75,0.3`, alpha may be `inf`), or \
         `gamma,alpha,e_n` on every line"
    };
    let bad =
        |what: String| Failure::usage(format!("batch line {number}: {what}; expected {expected}"));
    let count = line.split(',').count();
    if count != fields {
        return Err(bad(format!("{count} field(s) in {:?}", excerpt(line))));
    }
    let mut parts = line.split(',');
    let mut field = |name: &str| {
        let text = parts.next().unwrap_or_default();
        // The message quotes the field: a long one only in part.
        crate::args::parse_f64(text)
            .map_err(|e| bad(format!("{name}: {}", e.replacen(text, &excerpt(text), 1))))
    };
    let g = field("gamma")?;
    let a = field("alpha")?;
    let e = if fields == 3 { field("e_n")? } else { 1.0 };
    Ok((g, a, e))
}

/// What [`read_line`] found.
enum LineRead {
    /// A line, in the buffer without its `\n`.
    Line,
    /// Longer than the limit (the buffer holds a part of it at most).
    TooLong,
    /// The end of the input.
    End,
}

/// Read the next line of `input` into `buf` (without its `\n`), holding at most `max` bytes of
/// it: a longer line is [`LineRead::TooLong`], and the rest of it is not read.
fn read_line(input: &mut dyn BufRead, buf: &mut Vec<u8>, max: usize) -> std::io::Result<LineRead> {
    buf.clear();
    loop {
        let available = match input.fill_buf() {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => return Err(e),
        };
        if available.is_empty() {
            return Ok(if buf.is_empty() {
                LineRead::End
            } else {
                LineRead::Line
            });
        }
        let (take, end) = match available.iter().position(|&b| b == b'\n') {
            Some(i) => (i, true),
            None => (available.len(), false),
        };
        if buf.len() + take > max {
            return Ok(LineRead::TooLong);
        }
        buf.extend_from_slice(&available[..take]);
        input.consume(take + usize::from(end));
        if end {
            return Ok(LineRead::Line);
        }
    }
}

/// Read a whole batch: every line is checked before anything is answered, so a bad line anywhere
/// (or a point outside the domain) stops the batch with no output at all, whatever its size.
///
/// Memory: the points are held as columns of `f64`, two for `gamma,alpha` lines and three for
/// `gamma,alpha,e_n` (16 or 24 bytes a point; the columns grow by reallocation, which on Linux
/// moves pages instead of copying them, and pages not yet written take no memory); the rare
/// lines copied unchanged (blank, `#`, the header) are kept with their position, and a point's
/// line number is derived from them when a message needs it. The answers are computed twice, a
/// chunk at a time: once to check every point, once to write them, so that no column of
/// answers is held.
fn batch(table: &Table, path: &PathBuf, outside: OutOfDomain) -> Result<()> {
    let input: Box<dyn BufRead> = if path.as_os_str() == "-" {
        Box::new(std::io::stdin().lock())
    } else {
        let f = std::fs::File::open(path)
            .map_err(|e| Failure::usage(format!("--batch {}: cannot open: {e}", path.display())))?;
        Box::new(std::io::BufReader::new(f))
    };
    let (mut gammas, mut alphas, mut e_ns) = (Vec::new(), Vec::new(), Vec::new());
    // Fields per line, fixed by the first point (or the header): 2, or 3 with e_n.
    let mut fields: Option<usize> = None;
    // (line index, text) of the lines copied unchanged, in order.
    let mut verbatim: Vec<(usize, String)> = Vec::new();
    let mut header_allowed = true;
    let mut buf = Vec::new();
    let mut input = input;
    let mut i = 0usize;
    loop {
        let number = i + 1;
        let read = read_line(&mut *input, &mut buf, MAX_LINE)
            .map_err(|e| Failure::usage(format!("batch line {number}: cannot read: {e}")))?;
        match read {
            LineRead::End => break,
            LineRead::TooLong => {
                return Err(Failure::usage(format!(
                    "batch line {number}: longer than {MAX_LINE} bytes, the limit of a batch \
                     line (the rest of it is not read); a line is `gamma,alpha` or \
                     `gamma,alpha,e_n`"
                )))
            }
            LineRead::Line => {}
        }
        let line = std::str::from_utf8(&buf).map_err(|e| {
            Failure::usage(format!(
                "batch line {number}: not UTF-8 text (byte {} of the line)",
                e.valid_up_to() + 1
            ))
        })?;
        let line = line.strip_suffix('\r').unwrap_or(line);
        let line = if number == 1 {
            line.strip_prefix('\u{feff}').unwrap_or(line)
        } else {
            line
        };
        let text = line.trim();
        if text.is_empty() || text.starts_with('#') {
            verbatim.push((i, line.trim_end().to_owned()));
        } else if header_allowed && text.replace(' ', "").eq_ignore_ascii_case("gamma,alpha") {
            header_allowed = false;
            fields = Some(2);
            verbatim.push((i, "gamma,alpha,P,e_t".into()));
        } else if header_allowed
            && text
                .replace(' ', "")
                .eq_ignore_ascii_case("gamma,alpha,e_n")
        {
            header_allowed = false;
            fields = Some(3);
            verbatim.push((i, "gamma,alpha,e_n,P,e_t".into()));
        } else {
            header_allowed = false;
            let n = *fields.get_or_insert(text.split(',').count().clamp(2, 3));
            let (g, a, e) = parse_line(text, number, n)?;
            gammas.push(g);
            alphas.push(a);
            if n == 3 {
                e_ns.push(e);
            }
        }
        i += 1;
    }
    gammas.shrink_to_fit();
    alphas.shrink_to_fit();
    e_ns.shrink_to_fit();
    // The line number of point `k`: its index plus the copied lines before it, plus one.
    let line_of = |k: usize| {
        let mut line = k;
        for &(at, _) in &verbatim {
            if at <= line {
                line += 1;
            } else {
                break;
            }
        }
        line + 1
    };
    let with_e_n = fields == Some(3);
    let failed = |e: LookupError| match e {
        LookupError::Batch { index, source } => {
            // e_n is never clamped: no hint for it.
            let hint = match *source {
                LookupError::Query { name: "e_n", .. } => "",
                _ => " (--clamp)",
            };
            Failure::usage(format!("batch line {}: {source}{hint}", line_of(index)))
        }
        other => usage(other),
    };
    // P of the points `start..start + out.len()` into `out` (`Table::p_columns_par`); an error
    // names the point's line.
    let answer = |start: usize, out: &mut [f64]| -> Result<()> {
        let end = start + out.len();
        let points = PointColumns::new(
            Column::scalar("gamma", &gammas[start..end]),
            Column::scalar("alpha", &alphas[start..end]),
            with_e_n.then(|| Column::scalar("e_n", &e_ns[start..end])),
        )
        .map_err(anyhow::Error::from)?;
        table
            .p_columns_par(&points, out, outside)
            .map_err(|e| match e {
                LookupError::Batch { index, source } => LookupError::Batch {
                    index: start + index,
                    source,
                },
                other => other,
            })
            .map_err(failed)
    };
    let mut ps = vec![0.0; CHUNK.min(gammas.len())];
    // Every point first: a point the table refuses stops the batch before any output.
    for start in (0..gammas.len()).step_by(CHUNK) {
        let n = CHUNK.min(gammas.len() - start);
        answer(start, &mut ps[..n])?;
    }
    let stdout = std::io::stdout();
    let mut out = BufWriter::new(stdout.lock());
    let mut copied = verbatim.iter().peekable();
    let mut done = 0usize;
    for index in 0..i {
        if copied.peek().is_some_and(|(at, _)| *at == index) {
            if let Some((_, text)) = copied.next() {
                writeln!(out, "{text}").context("writing the output")?;
            }
            continue;
        }
        if done >= gammas.len() {
            // Every line is a copied one or a point: not reached.
            continue;
        }
        let k = done % CHUNK;
        if k == 0 {
            let n = CHUNK.min(gammas.len() - done);
            answer(done, &mut ps[..n])?;
        }
        let (g, a, p) = (gammas[done], alphas[done], ps[k]);
        let e_n = if with_e_n {
            format!(",{}", crate::args::fmt_num(e_ns[done]))
        } else {
            String::new()
        };
        done += 1;
        writeln!(
            out,
            "{},{}{e_n},{},{}",
            crate::args::fmt_num(g),
            crate::args::fmt_num(a),
            crate::args::fmt_num(p),
            crate::args::fmt_num(tangential_restitution(p))
        )
        .context("writing the output")?;
    }
    out.flush().context("writing the output")?;
    Ok(())
}
