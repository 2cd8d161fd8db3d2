//! The export format: a table (and optionally per-γ curves) as one flat little-endian byte
//! string that a dependency-free evaluator reads in place (memory-mapped, or compiled in as a C
//! array): `include/oblique_eval.h`. The layout is documented in `docs/export-format.md`; this
//! module is its only writer, next to the HDF5 schema of [`crate::format`].
//!
//! Every offset is in bytes from the start of the export; every array starts at a multiple of
//! 8. Integers are unsigned little-endian (`u32`, `u64`), reals IEEE binary64, the tree `i32`.
//!
//! An elastic table is written as layout version 1, byte for byte as before the `e_n` axis
//! existed; a table with an `e_n` axis (schema 4) as version 2: a 112-byte header that ends
//! with the `e_n` range, octree patches with `blocks_e_n` in their record and `(m+1)³` nodes
//! per leaf, no curves (a reader of version 1 only refuses it by its version); the table of one
//! pair (axes `alpha,e_n`, [`Surface::pair_gamma`]) as version 3: version 2 with `gamma_min =
//! gamma_max` and patches of a single `γ` (`gamma_lo = gamma_hi`, `blocks_gamma = 1`), whose
//! trees are quadtrees over `(c, e_n)` (masks 1 to 3) with `(m+1)²` nodes per leaf (a reader of
//! version 2 only refuses it by its version); a table of Thornton's law (no closed-form
//! full-slip line, [`Surface::has_line`]) as version 4: version 2 with the flag `1` at offset
//! 68 (`0` in versions 1 to 3), whose partial-slip patch covers `0 ≤ α ≤ α_c2` with the
//! coordinate [`crate::surface::PartialMap::Slip`] (a reader of version 2 only refuses it by its
//! version instead of answering `α ≤ α_c1` from a line this law does not have); a table with an
//! `e_n` axis whose partial-slip patch has knots ([`crate::surface::Knots`]) as version 5:
//! version 2 (flag `0` at offset 68) or version 4 (flag `1`) with the knots in a block named by
//! the partial-slip record at offset 152 (a reader of version 4 only refuses it by its version
//! instead of answering from the coordinate without its knots); such a table whose stick patch
//! `stick_high` has knots too as version 7: version 5 whose `stick_high` record names its knots
//! block at the same offset, and whose `partial_high` record may name none (a reader of version
//! 5 only refuses it by its version instead of answering the stick patch without its knots); an
//! elastic table one of whose
//! patches has split masks (`nodes.anisotropic`: cells that halve only the axes they need) as
//! version 6: version 1 (its header and records) whose patch records name the masks at offset
//! 144, as version 2 does, and whose patches with masks have no fine index (a reader of version
//! 1 only refuses it by its version instead of descending as if every split halved both axes);
//! a table over a range of `γ` whose `e_n` axis is mapped ([`crate::surface::AxisMap`], schema
//! 5) as version 8: version 2, 4, 5 or 7 (the flag at offset 68 and the records' knots blocks
//! say which) with the map at offset 84 (`0`, reserved, in versions 1 to 7), whose patches'
//! trees are over the mapped coordinate (a reader of versions 1 to 7 only refuses it by its
//! version instead of answering it over a linear `e_n` axis).

use crate::format::fnv1a64;
use crate::surface::{AxisMap, PatchId, PatchKind, Surface, MAX_INDEX_ENTRIES};

/// The first 8 bytes of an export.
pub const MAGIC: &[u8; 8] = b"OBLQEVAL";
/// Layout version of the export of an elastic table (readers refuse versions they do not know).
pub const VERSION: u32 = 1;
/// Layout version of the export of a table with an `e_n` axis.
pub const VERSION_E_N: u32 = 2;
/// Layout version of the export of the table of one pair (axes `alpha,e_n`).
pub const VERSION_PAIR: u32 = 3;
/// Layout version of the export of a table without a closed-form full-slip line (Thornton's
/// law, [`crate::surface::PartialMap::Slip`]): version 2 with the flag [`NO_LINE_AT`] set.
pub const VERSION_NO_LINE: u32 = 4;
/// Layout version of the export of a table with an `e_n` axis whose partial-slip coordinate has
/// knots: version 2 or 4 (the flag [`NO_LINE_AT`] says which) with the knots block.
pub const VERSION_KNOTS: u32 = 5;
/// Layout version of the export of an elastic table with split masks: version 1 whose patch
/// records may name the masks of their cells at [`SPLIT_AT`] (bit 2 `γ`, bit 1 `c`).
pub const VERSION_SPLIT: u32 = 6;
/// Layout version of the export of a table with an `e_n` axis whose stick patch `stick_high`
/// has knots: version 5 whose `stick_high` record names a knots block too, and whose
/// `partial_high` record may name none.
pub const VERSION_STICK_KNOTS: u32 = 7;
/// Offset, in a patch record, of the `u64` offset of its split masks (`u8[cells]`; versions 2,
/// 3 and 6, or 0: every split halves every axis).
pub const SPLIT_AT: usize = 144;
/// Layout version of the export of a table over a range of `γ` whose `e_n` axis is mapped
/// ([`crate::surface::AxisMap`] other than linear): version 2, 4, 5 or 7 with the map at
/// [`E_N_MAP_AT`].
pub const VERSION_E_N_MAP: u32 = 8;
/// Offset of the `u32` map of the `e_n` axis: [`E_N_MAP_QUARTER_ROOT`] in version 8, `0`
/// (reserved) in versions 1 to 7.
pub const E_N_MAP_AT: usize = 84;
/// The map [`crate::surface::AxisMap::QuarterRoot`] at [`E_N_MAP_AT`]: `x_e = (m(e_n) −
/// m(e_n_min))/(m(e_n_max) − m(e_n_min))`, `m(e) = −√√(1 − e)`.
pub const E_N_MAP_QUARTER_ROOT: u32 = 1;
/// Offset of the `u32` flag of a table without a full-slip line: `1` in version 4, `0` in
/// versions 1 to 3 and 6, either in versions 5, 7 and 8 (a reader checks it against the
/// version).
pub const NO_LINE_AT: usize = 68;
/// Offset, in the record of `partial_high` (versions 5, 7 and 8) and of `stick_high` (versions
/// 7 and 8), of the `u64` offset of its knots block (reserved, 0, in every other record and
/// version; 0 in a record of version 7 or 8 without knots but that of `stick_high` of version
/// 7).
pub const KNOTS_AT: usize = 152;
/// Bytes of the knots block before its arrays: `k`, `n_γ`, `n_e` and a reserved `u32`, the
/// grid's `gamma_0`, `gamma_step`, `e_n_0`, `e_n_step`, the `region` (4 `f64`) and the grades
/// (`u8[8]`); then `c_star` (`f64[k]`) and the knot values (`f64[k][n_γ][n_e]`).
pub const KNOTS_HEAD_BYTES: usize = 88;
/// Bytes of the header (version 1).
pub const HEADER_BYTES: usize = 96;
/// Bytes of the header of versions 2 to 5, 7 and 8: the version-1 header, then `e_n_min` and
/// `e_n_max`.
pub const HEADER_BYTES_E_N: usize = 112;
/// Bytes of one patch record (three follow the header when the export holds the surface).
pub const PATCH_BYTES: usize = 160;
/// Bytes of one curve record.
pub const CURVE_BYTES: usize = 168;
/// Offset of the checksum field; the checksum covers every byte after it.
pub const CHECKSUM_AT: usize = 24;

/// One patch of a curve: the cubic `a0 + a1 s + a2 s² + a3 s³` of each of `n` intervals of the
/// patch coordinate, and the warp of the line (its `K(γ)` and `c_star`) if the rule warps it.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvePiece {
    /// `[a0, a1, a2, a3]` per interval, in the local coordinate `s = c·n − i − 1/2`.
    pub coef: Vec<[f64; 4]>,
    /// `(K, c_star)` when the coordinate is warped on this line.
    pub warp: Option<(f64, f64)>,
}

/// The precomputed `P(α)` of one `γ` (what `oblique_lookup::Curve` holds), inside the table's
/// domain.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveData {
    /// `γ`.
    pub gamma: f64,
    /// End of the full-slip line, `α_c1` (`γ > 1`) or `α_c2`.
    pub alpha_lin: f64,
    /// `α_c2 = 2γ²/7`: partial slip below (for `γ > 1`), stick above.
    pub alpha_c2: f64,
    /// `2γ²`, `2γ² − 1` and `ln(2γ² − 1)` of the partial-slip coordinate.
    pub g2: f64,
    /// `2γ² − 1`.
    pub ratio: f64,
    /// `ln(2γ² − 1)`.
    pub ln_ratio: f64,
    /// `α_c2` as the stick coordinate computes it (`γ²·(2/7)`).
    pub stick_c2: f64,
    /// `ρ α_c2`.
    pub rho_c2: f64,
    /// `S(α_max)` (`None` for `α_max = ∞`).
    pub s_max: Option<f64>,
    /// The table's `α_max`.
    pub alpha_max: f64,
    /// `γ > 1`.
    pub high: bool,
    /// The line through `partial_high` (`γ > 1`, if the table has it).
    pub partial: Option<CurvePiece>,
    /// The line through the stick patch of its side.
    pub stick: Option<CurvePiece>,
}

fn align8(v: &mut Vec<u8>) {
    while !v.len().is_multiple_of(8) {
        v.push(0);
    }
}

fn put_u32(v: &mut [u8], at: usize, x: u32) {
    v[at..at + 4].copy_from_slice(&x.to_le_bytes());
}

fn put_u64(v: &mut [u8], at: usize, x: u64) {
    v[at..at + 8].copy_from_slice(&x.to_le_bytes());
}

fn put_f64(v: &mut [u8], at: usize, x: f64) {
    v[at..at + 8].copy_from_slice(&x.to_le_bytes());
}

/// Append `values` (8-byte aligned) and return their offset.
fn push_f64s(v: &mut Vec<u8>, values: impl IntoIterator<Item = f64>) -> u64 {
    align8(v);
    let at = v.len() as u64;
    for x in values {
        v.extend_from_slice(&x.to_le_bytes());
    }
    at
}

/// The export of `surface` (with `error_bound`, the table's stated bound) when `with_surface`,
/// and of `curves`, as bytes. An export without the surface answers only its curves.
///
/// A surface with an `e_n` axis ([`Surface::restitution`]) is written as version 2, the table of
/// one pair ([`Surface::pair_gamma`]) as version 3, a surface without the full-slip line
/// ([`Surface::has_line`]: Thornton's law) as version 4, and one whose partial-slip patch has
/// knots as version 5 (with the flag of version 4 when it has no full-slip line), one whose stick
/// patch `stick_high` has knots as version 7 (version 5 with that patch's knots), and an elastic
/// surface one of whose patches has split masks ([`crate::surface::Patch::split`]) as version 6
/// (version 1 otherwise, byte for byte as before version 6 existed); curves belong to elastic
/// tables only. A surface whose `e_n` axis is mapped ([`Surface::e_n_map`], schema 5) is written
/// as version 8: the version it would have with a linear axis (2, 4, 5 or 7) with the map's
/// code at [`E_N_MAP_AT`]; its trees, node values and knots are stored as they are, and a
/// reader takes `x_e` through the map.
///
/// # Panics
///
/// For a surface with an `e_n` axis and `curves` or without `with_surface` (`sweep export`
/// refuses `--gamma` for such a table before it gets here), and for a surface without the
/// full-slip line that is not a table with an `e_n` axis over a range of `γ` (which
/// [`Surface::with_partial_map`] never makes), and for knots in a patch other than the
/// partial-slip patch and `stick_high` of such a table (which the reader and the writer
/// refuse), and for the table of one pair whose `e_n` axis is mapped (which the builder never
/// makes; `sweep export` refuses such a table before it gets here).
pub fn export(
    surface: &Surface,
    error_bound: f64,
    with_surface: bool,
    curves: &[CurveData],
) -> Vec<u8> {
    let axis = surface.restitution();
    assert!(
        axis.is_none() || (with_surface && curves.is_empty()),
        "the export of a table with an e_n axis holds its surface and no curves"
    );
    let e_map = map_code(surface.e_n_map());
    assert!(
        e_map == 0 || surface.pair_gamma().is_none(),
        "the export layout holds the e_n map of a table over a range of gamma only"
    );
    let knotted = surface.patches().any(|(_, p)| p.knots().is_some());
    let stick_knotted = surface
        .patch_by_id(PatchId::StickHigh)
        .is_some_and(|p| p.knots().is_some());
    assert!(
        surface.patches().all(|(id, p)| p.knots().is_none()
            || (matches!(id, PatchId::PartialHigh | PatchId::StickHigh)
                && axis.is_some()
                && surface.pair_gamma().is_none())),
        "only the partial-slip patch and stick_high of a table with an e_n axis over a range of \
         gamma have knots"
    );
    assert!(
        surface.has_line() || (axis.is_some() && surface.pair_gamma().is_none()),
        "only a table with an e_n axis over a range of gamma has no full-slip line"
    );
    // The masks of an elastic table are written only with its surface (a curves-only export
    // stays version 1).
    let masked = with_surface && surface.patches().any(|(_, p)| p.split().is_some());
    let (version, header) = match (axis, surface.pair_gamma(), surface.has_line()) {
        (Some(_), None, _) if stick_knotted => (VERSION_STICK_KNOTS, HEADER_BYTES_E_N),
        (Some(_), None, _) if knotted => (VERSION_KNOTS, HEADER_BYTES_E_N),
        (Some(_), None, false) => (VERSION_NO_LINE, HEADER_BYTES_E_N),
        (Some(_), Some(_), _) => (VERSION_PAIR, HEADER_BYTES_E_N),
        (Some(_), None, true) => (VERSION_E_N, HEADER_BYTES_E_N),
        (None, _, _) if masked => (VERSION_SPLIT, HEADER_BYTES),
        (None, _, _) => (VERSION, HEADER_BYTES),
    };
    // A mapped e_n axis: version 8 over any of the versions above with the axis (the flag at
    // 68 and the knots blocks tell 2, 4, 5 and 7 apart).
    let version = if e_map != 0 { VERSION_E_N_MAP } else { version };
    let mut v = vec![0u8; header];
    v[..8].copy_from_slice(MAGIC);
    put_u32(&mut v, 8, version);
    put_u32(&mut v, 12, header as u32);
    if !surface.has_line() {
        put_u32(&mut v, NO_LINE_AT, 1);
    }
    if e_map != 0 {
        put_u32(&mut v, E_N_MAP_AT, e_map);
    }
    if let Some((lo, hi)) = axis {
        put_f64(&mut v, 96, lo);
        put_f64(&mut v, 104, hi);
    }
    put_f64(&mut v, 32, surface.gamma_min());
    put_f64(&mut v, 40, surface.gamma_max());
    put_f64(&mut v, 48, surface.alpha_max());
    put_f64(&mut v, 56, error_bound);
    put_u32(&mut v, 64, surface.stencil() as u32);
    put_u32(&mut v, 80, curves.len() as u32);
    if with_surface {
        let dir = v.len();
        put_u64(&mut v, 72, dir as u64);
        v.resize(dir + 3 * PATCH_BYTES, 0);
        for (k, id) in [PatchId::StickLow, PatchId::PartialHigh, PatchId::StickHigh]
            .into_iter()
            .enumerate()
        {
            let Some(p) = surface.patch_by_id(id) else {
                continue;
            };
            let r = dir + k * PATCH_BYTES;
            put_u32(&mut v, r, 1);
            put_u32(&mut v, r + 4, u32::from(p.kind() == PatchKind::PartialSlip));
            put_f64(&mut v, r + 8, p.gamma_lo());
            put_f64(&mut v, r + 16, p.gamma_hi());
            put_u32(&mut v, r + 24, p.blocks_gamma() as u32);
            put_u32(&mut v, r + 28, p.blocks_coord() as u32);
            put_u32(&mut v, r + 32, p.leaf_intervals() as u32);
            put_u32(&mut v, r + 36, p.tree().len() as u32);
            put_u32(&mut v, r + 40, p.leaves() as u32);
            if let Some(e) = p.restitution() {
                // The octree's third axis (the quadtree's second in a patch of one pair, whose
                // `blocks_gamma` is 1); its range is the table's (header, offset 96).
                put_u32(&mut v, r + 136, e.blocks() as u32);
            }
            align8(&mut v);
            let tree_at = v.len() as u64;
            for t in p.tree() {
                v.extend_from_slice(&t.to_le_bytes());
            }
            put_u64(&mut v, r + 48, tree_at);
            let p_at = push_f64s(&mut v, p.p().iter().copied());
            put_u64(&mut v, r + 56, p_at);
            if let Some(split) = p.split() {
                // The axes each split cell halves (versions 2, 3 and 6): `u8[cells]`.
                let at = v.len() as u64;
                v.extend_from_slice(split);
                put_u64(&mut v, r + SPLIT_AT, at);
            }
            // The fine index of a patch whose cells halve both axes; a patch with masks
            // (version 6) is descended from its roots: an index over cells of unequal sides
            // would need a scale per axis, and it saved about 5% of a random lookup in C
            // (docs/export-format.md, "Version 6").
            let fine = match p.split() {
                Some(_) => None,
                None => p.fine_index(MAX_INDEX_ENTRIES),
            };
            if let Some(fine) = fine {
                put_u32(&mut v, r + 112, fine.depth[0]);
                align8(&mut v);
                let at = v.len() as u64;
                for e in &fine.index {
                    v.extend_from_slice(&e.to_le_bytes());
                }
                put_u64(&mut v, r + 120, at);
                let cells_at = push_f64s(
                    &mut v,
                    fine.cells
                        .iter()
                        .flat_map(|c| [c.scale[0], c.origin[0], c.origin[1]]),
                );
                put_u64(&mut v, r + 128, cells_at);
            }
            if let Some(w) = p.warp() {
                put_u32(&mut v, r + 44, 1);
                put_f64(&mut v, r + 64, w.start());
                put_f64(&mut v, r + 72, w.gamma_0());
                put_f64(&mut v, r + 80, w.gamma_step());
                put_f64(&mut v, r + 88, w.c_star());
                put_u32(&mut v, r + 96, w.knot().len() as u32);
                let k_at = push_f64s(&mut v, w.knot().iter().copied());
                put_u64(&mut v, r + 104, k_at);
            }
            if let Some(k) = p.knots() {
                // The knots block (versions 5 and 7): the counts, the grid, the region, the grades,
                // then `c_star` and the knot values `[k][n_γ][n_e]`.
                align8(&mut v);
                let at = v.len();
                let [n, n_gamma, n_e_n] = k.shape();
                for x in [n, n_gamma, n_e_n, 0] {
                    v.extend_from_slice(&(x as u32).to_le_bytes());
                }
                let region = k.region();
                for x in [k.gamma_0(), k.gamma_step(), k.e_n_0(), k.e_n_step()]
                    .into_iter()
                    .chain(region)
                {
                    v.extend_from_slice(&x.to_le_bytes());
                }
                let mut grades = [0u8; crate::surface::MAX_KNOTS];
                grades[..n].copy_from_slice(&k.grade_values());
                v.extend_from_slice(&grades);
                debug_assert_eq!(v.len() - at, KNOTS_HEAD_BYTES);
                push_f64s(&mut v, k.c_star().iter().copied());
                push_f64s(&mut v, k.values().iter().copied());
                put_u64(&mut v, r + KNOTS_AT, at as u64);
            }
        }
    }
    if !curves.is_empty() {
        align8(&mut v);
        let dir = v.len();
        put_u64(&mut v, 88, dir as u64);
        v.resize(dir + curves.len() * CURVE_BYTES, 0);
        for (k, c) in curves.iter().enumerate() {
            let r = dir + k * CURVE_BYTES;
            for (i, x) in [
                c.gamma,
                c.alpha_lin,
                c.alpha_c2,
                c.g2,
                c.ratio,
                c.ln_ratio,
                c.stick_c2,
                c.rho_c2,
                c.s_max.unwrap_or(f64::NAN),
                c.alpha_max,
            ]
            .into_iter()
            .enumerate()
            {
                put_f64(&mut v, r + 8 * i, x);
            }
            put_u32(&mut v, r + 80, u32::from(c.high));
            for (slot, piece) in [(88, &c.partial), (128, &c.stick)] {
                let Some(piece) = piece else { continue };
                let at = r + slot;
                put_u32(&mut v, at, 1);
                put_u32(&mut v, at + 4, piece.coef.len() as u32);
                let coef_at = push_f64s(&mut v, piece.coef.iter().flatten().copied());
                put_u64(&mut v, at + 8, coef_at);
                if let Some((k, c_star)) = piece.warp {
                    put_u32(&mut v, at + 16, 1);
                    put_f64(&mut v, at + 24, k);
                    put_f64(&mut v, at + 32, c_star);
                }
            }
        }
    }
    align8(&mut v);
    let len = v.len() as u64;
    put_u64(&mut v, 16, len);
    let sum = fnv1a64(&v[CHECKSUM_AT + 8..]);
    put_u64(&mut v, CHECKSUM_AT, sum);
    v
}

/// The code of the `e_n` axis's map at [`E_N_MAP_AT`]: `0` linear, [`E_N_MAP_QUARTER_ROOT`].
fn map_code(map: AxisMap) -> u32 {
    match map {
        AxisMap::Linear => 0,
        AxisMap::QuarterRoot => E_N_MAP_QUARTER_ROOT,
    }
}

/// The export as a C source file: the bytes as an array of `unsigned long long` words (8-byte
/// aligned, in the byte order of a little-endian machine) named `name`, and its length in bytes
/// as `name_size`, for codes that compile the table in (`oblq_open(&t, name, name_size)`).
/// `what` goes into the opening comment. A `name` that a C or C++ compiler would refuse is
/// refused ([`check_c_name`]).
pub fn c_source(bytes: &[u8], name: &str, what: &str) -> Result<String, CNameError> {
    use std::fmt::Write;
    check_c_name(name)?;
    // A `*/` in `what` (a file name) would end the comment early.
    let what = what.replace("*/", "* /");
    let mut s = String::with_capacity(bytes.len() * 3 + 512);
    let words = bytes.len().div_ceil(8);
    let _ = writeln!(
        s,
        "/* {what}\n * Generated by `sweep export`; layout: docs/export-format.md. Little-endian \
         machines only.\n * Read with oblq_open(&table, {name}, {name}_size) from oblique_eval.h. */\n\
         #include <stddef.h>\n\n\
         const size_t {name}_size = {};\n\
         const unsigned long long {name}[{words}] = {{",
        bytes.len()
    );
    for (i, chunk) in bytes.chunks(8).enumerate() {
        let mut w = [0u8; 8];
        w[..chunk.len()].copy_from_slice(chunk);
        if i % 4 == 0 {
            s.push_str("\n   ");
        }
        let _ = write!(s, " 0x{:016x}ULL,", u64::from_le_bytes(w));
    }
    s.push_str("\n};\n");
    Ok(s)
}

/// A name that cannot be the array of a C source ([`c_source`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum CNameError {
    /// Not a C identifier: letters, digits and `_`, not starting with a digit.
    #[error("{0:?} is not a C identifier (letters, digits and _, not starting with a digit)")]
    NotIdentifier(String),
    /// A keyword of C or C++: a compiler refuses it as a name.
    #[error("{0:?} is a C or C++ keyword; give another name")]
    Keyword(String),
    /// A name that the C source's own `#include <stddef.h>` defines (`size_t`, `NULL`, …).
    #[error("{0:?} is defined by <stddef.h>, which the C source includes; give another name")]
    Stddef(String),
    /// Reserved for the compiler and the standard library: `__x` or `_X`.
    #[error(
        "{0:?} is reserved for the compiler (a name starting with two underscores, or an \
         underscore and a capital letter); give another name"
    )]
    Reserved(String),
}

/// The keywords of C (C23, with the spellings of C99 and C11) and C++ (C++23, with the
/// alternative tokens), which no declared name may be.
const C_KEYWORDS: &[&str] = &[
    // C
    "alignas",
    "alignof",
    "auto",
    "bool",
    "break",
    "case",
    "char",
    "const",
    "constexpr",
    "continue",
    "default",
    "do",
    "double",
    "else",
    "enum",
    "extern",
    "false",
    "float",
    "for",
    "goto",
    "if",
    "inline",
    "int",
    "long",
    "nullptr",
    "register",
    "restrict",
    "return",
    "short",
    "signed",
    "sizeof",
    "static",
    "static_assert",
    "struct",
    "switch",
    "thread_local",
    "true",
    "typedef",
    "typeof",
    "typeof_unqual",
    "union",
    "unsigned",
    "void",
    "volatile",
    "while",
    "_Alignas",
    "_Alignof",
    "_Atomic",
    "_BitInt",
    "_Bool",
    "_Complex",
    "_Decimal128",
    "_Decimal32",
    "_Decimal64",
    "_Generic",
    "_Imaginary",
    "_Noreturn",
    "_Static_assert",
    "_Thread_local",
    "asm",
    // C++ beyond C
    "and",
    "and_eq",
    "bitand",
    "bitor",
    "catch",
    "char8_t",
    "char16_t",
    "char32_t",
    "class",
    "co_await",
    "co_return",
    "co_yield",
    "compl",
    "concept",
    "consteval",
    "constinit",
    "const_cast",
    "decltype",
    "delete",
    "dynamic_cast",
    "explicit",
    "export",
    "friend",
    "mutable",
    "namespace",
    "new",
    "noexcept",
    "not",
    "not_eq",
    "operator",
    "or",
    "or_eq",
    "private",
    "protected",
    "public",
    "reinterpret_cast",
    "requires",
    "static_cast",
    "template",
    "this",
    "throw",
    "try",
    "typeid",
    "typename",
    "using",
    "virtual",
    "wchar_t",
    "xor",
    "xor_eq",
];

/// What `<stddef.h>` defines (C23), which the C source includes.
const STDDEF_NAMES: &[&str] = &[
    "size_t",
    "ptrdiff_t",
    "wchar_t",
    "max_align_t",
    "nullptr_t",
    "NULL",
    "offsetof",
    "unreachable",
];

/// Check that `name` can be the array of a C source ([`c_source`]) compiled as C or C++: a C
/// identifier that is no keyword of either language, not defined by `<stddef.h>` and not
/// reserved for the compiler. (`NAME_size`, the length beside it, is then one too.)
pub fn check_c_name(name: &str) -> Result<(), CNameError> {
    let mut chars = name.chars();
    let identifier = matches!(chars.next(), Some(c) if c.is_ascii_alphabetic() || c == '_')
        && chars.all(|c| c.is_ascii_alphanumeric() || c == '_');
    if !identifier {
        return Err(CNameError::NotIdentifier(name.to_string()));
    }
    if C_KEYWORDS.contains(&name) {
        return Err(CNameError::Keyword(name.to_string()));
    }
    if STDDEF_NAMES.contains(&name) {
        return Err(CNameError::Stddef(name.to_string()));
    }
    let b = name.as_bytes();
    if b.len() >= 2 && b[0] == b'_' && (b[1] == b'_' || b[1].is_ascii_uppercase()) {
        return Err(CNameError::Reserved(name.to_string()));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn c_names_are_identifiers_that_a_compiler_takes() {
        for ok in [
            "oblique_table",
            "t",
            "_t",
            "T1",
            "int_",
            "integer",
            "size",
            "_t_9",
        ] {
            assert_eq!(check_c_name(ok), Ok(()), "{ok}");
            assert!(c_source(&[1, 2, 3], ok, "x").is_ok(), "{ok}");
        }
        for (bad, want) in [
            ("", "not a C identifier"),
            ("9t", "not a C identifier"),
            ("a-b", "not a C identifier"),
            ("é", "not a C identifier"),
            ("a b", "not a C identifier"),
            ("int", "keyword"),
            ("_Bool", "keyword"),
            ("class", "keyword"),
            ("and", "keyword"),
            ("size_t", "<stddef.h>"),
            ("NULL", "<stddef.h>"),
            ("__t", "reserved"),
            ("_Table", "reserved"),
        ] {
            let e = check_c_name(bad).expect_err(bad);
            assert!(e.to_string().contains(want), "{bad}: {e}");
            assert!(c_source(&[1], bad, "x").is_err(), "{bad}");
        }
    }

    #[test]
    fn the_comment_of_a_c_source_stays_a_comment() {
        let s = c_source(&[1], "t", "from a*/b.h5").expect("valid name");
        let comment_end = s.find("*/").expect("comment");
        assert!(s[comment_end..].contains("#include <stddef.h>"));
        assert!(!s[..comment_end].contains("b.h5 *"), "{s}");
        assert!(s.contains("a* /b.h5"), "{s}");
    }
}
