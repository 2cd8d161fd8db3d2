//! C ABI of the `cdylib` (`liboblique.so`, SONAME `liboblique.so.0`, set by `build.rs`) and
//! the `staticlib` (`liboblique.a`). The header `include/oblique_lookup.h` is generated from
//! this file by cbindgen (`cbindgen.toml`); `tests/c_abi.rs` regenerates it and fails when the
//! committed one differs (`UPDATE_HEADER=1` rewrites it), then compiles `examples/query.c` with
//! the system C compiler and runs it. `scripts/install-capi.sh PREFIX` installs the libraries,
//! the header and `lib/pkgconfig/oblique.pc`; `tests/install.rs` checks the installed tree.
//!
//! Every function returns an integer status (`OBLIQUE_OK` = 0 or an `OBLIQUE_ERR_*` code);
//! `oblique_last_error()` gives the message of the last failure on the calling thread. Results
//! are written through out-pointers, only on success. Nothing panics across the boundary. A
//! table handle is immutable and may be shared by threads (queries only read it; the doc of
//! `OBLIQUE_ABI_VERSION`, at the top of the header, says which calls are thread-safe). SI units
//! and conventions of `rebound`: the normal points from sphere 1 into the other body; spins are
//! vectors (right-handed, rad/s).

use std::cell::RefCell;
use std::ffi::{c_char, c_int, CStr, CString};
use std::panic::{catch_unwind, AssertUnwindSafe};

use oblique_lookup::columns::{Column, PointColumns};
use oblique_lookup::impact::{Contact, Stiffness};
use oblique_lookup::rebound::{Body, Elastic, Incident3, Motion3, Pair, Rebound3};
use oblique_lookup::OutOfDomain;
use oblique_lookup::{Curve, LookupError, Prepared, Table};

/// Version of the ABI this header declares, also returned by `oblique_abi_version()`. It
/// changes with every incompatible change of a declaration below, and so does the number in the
/// shared library's SONAME (`liboblique.so.0` for ABI version 1). A program can check at
/// start-up that the library it loaded matches the header it was compiled with:
/// `oblique_abi_version() == OBLIQUE_ABI_VERSION`. `oblique_version()` gives the library's
/// release as a string such as `"0.1.0"`.
///
/// Language: this header is C99 and later, or C++11 and later (under C++ the functions are
/// `extern "C"`). It is not C89/C90: it uses `//` comments and `<stdint.h>`.
///
/// Units: SI throughout: masses in kg, lengths in m, velocities in m/s, angular velocities in
/// rad/s (vectors, right-handed), moduli in Pa, impulses in N s, energies in J, angles in rad.
/// `γ`, `α`, `P`, `e_t`, `κ`, `ν` and the friction coefficient `μ` are dimensionless.
///
/// Threads: an `ObliqueTable` is immutable once `oblique_table_open` returns; any number of
/// threads may use one handle at the same time, without locking, in `oblique_table_domain`,
/// `oblique_p`, `oblique_p_e`, `oblique_p_batch`, `oblique_curve_new`, `oblique_rebound_wall`,
/// `oblique_rebound_spheres`, `oblique_rebound_wall_e`, `oblique_rebound_spheres_e`,
/// `oblique_prepare_table` and `oblique_rebound_prepared`. Likewise an `ObliqueCurve`
/// (`oblique_curve_p`) and an `ObliquePrepared` (`oblique_rebound_prepared`) are immutable and
/// may be shared. `oblique_table_open` and `oblique_prepare` may be called by several threads
/// at once (the library serialises its calls into HDF5), and so may `oblique_prepare_e`. Only the functions that free a handle
/// (`oblique_table_close`, `oblique_curve_free`, `oblique_prepared_free`) need it to be used by
/// no other thread, during and after the call. `oblique_last_error()` reports the last failure
/// of the calling thread only. `oblique_version()` and `oblique_abi_version()` may be called at
/// any time from any thread.
pub const OBLIQUE_ABI_VERSION: c_int = 1;

/// Success.
pub const OBLIQUE_OK: c_int = 0;
/// A required pointer argument is NULL.
pub const OBLIQUE_ERR_NULL: c_int = 1;
/// The table file cannot be read (missing, not HDF5, truncated).
pub const OBLIQUE_ERR_IO: c_int = 2;
/// The file is not a valid table of a schema this library reads.
pub const OBLIQUE_ERR_TABLE: c_int = 3;
/// A query argument is outside its allowed range (the message names it and the range).
pub const OBLIQUE_ERR_QUERY: c_int = 4;
/// An internal error (a bug): please report it with the message.
pub const OBLIQUE_ERR_INTERNAL: c_int = 5;

/// An opened table (opaque). Create with `oblique_table_open`, free with `oblique_table_close`.
/// Immutable: one handle may be used by any number of threads at once, without locking, in
/// every function but `oblique_table_close` (see `OBLIQUE_ABI_VERSION`).
pub struct ObliqueTable(Table);

/// A pair of bodies with its contact, checked once (opaque): create with `oblique_prepare`
/// (`oblique_prepare_e`, or `oblique_prepare_table` for one table: faster with an `e_n` axis),
/// use with `oblique_rebound_prepared` for many impacts, free with `oblique_prepared_free`.
pub struct ObliquePrepared(Prepared);

/// `P(α)` of a table at one fixed `γ` (opaque; independent of the table once made): create with
/// `oblique_curve_new`, query with `oblique_curve_p`, free with `oblique_curve_free`.
pub struct ObliqueCurve(Curve);

/// Mass, radius and inertia factor of a sphere.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ObliqueBody {
    /// Mass `m` (kg), > 0.
    pub mass: f64,
    /// Radius `R` (m), > 0.
    pub radius: f64,
    /// Inertia factor `κ` in `I = κ m R²` (0.4 for a solid sphere), > 0.
    pub kappa: f64,
}

/// Elastic constants of an isotropic material.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ObliqueMaterial {
    /// Young's modulus `E` (Pa), > 0; `INFINITY` for a rigid body.
    pub youngs_modulus: f64,
    /// Poisson's ratio `ν`, in (−1, 0.5].
    pub poisson_ratio: f64,
}

/// Contact properties.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct ObliqueContact {
    /// The material group `γ` (`γ² = (m*/m_t) G*/E*`) if > 0; `0` to compute it from the two
    /// materials below.
    pub gamma: f64,
    /// Material of sphere 1 (used when `gamma == 0`).
    pub sphere_material: ObliqueMaterial,
    /// Material of the wall or of sphere 2 (used when `gamma == 0`).
    pub other_material: ObliqueMaterial,
    /// Coulomb friction coefficient `μ ≥ 0` (`INFINITY` for no slip).
    pub friction: f64,
    /// 0: a `γ` outside the table's domain is an error; 1: answer at the nearest `γ` of the table
    /// (any other value is refused with `OBLIQUE_ERR_QUERY`).
    pub clamp: c_int,
}

/// Velocity (m/s) and angular velocity (rad/s) of a body, as 3-vectors.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct ObliqueMotion {
    /// Velocity of the centre `v` (m/s).
    pub velocity: [f64; 3],
    /// Angular velocity `ω` (rad/s).
    pub spin: [f64; 3],
}

/// The outcome of one impact.
#[repr(C)]
#[derive(Debug, Clone, Copy, Default)]
pub struct ObliqueRebound {
    /// Sphere 1 after the impact.
    pub sphere: ObliqueMotion,
    /// Sphere 2 after the impact (all zero for a wall).
    pub other: ObliqueMotion,
    /// Plane of impact: `t`, direction of the incident slip of the contact point.
    pub tangent: [f64; 3],
    /// Plane of impact: `b = n × t`.
    pub binormal: [f64; 3],
    /// Plane of impact: the unit normal `n`.
    pub normal: [f64; 3],
    /// `γ` used (dimensionless).
    pub gamma: f64,
    /// `α = (2/7)(m*/m_t) μ v_z0/|u0|` (`INFINITY` when `u0 = 0`).
    pub alpha: f64,
    /// `P(γ, α)` (NaN when `u0 = 0`).
    pub p: f64,
    /// `|u0|`, incident slip speed of the contact point (m/s).
    pub slip_before: f64,
    /// `P |u0|`, slip velocity after along `t` (m/s).
    pub slip_after: f64,
    /// Friction impulse on body 2 along `+t` (N s).
    pub tangential_impulse: f64,
    /// Normal impulse `(1 + e_n) m* v_z0` on body 2 along `+n` (N s): `2 m* v_z0` elastic.
    pub normal_impulse: f64,
    /// `e_t = (w_after · w_before)/|w_before|²`, `w` the tangential relative centre velocity.
    pub e_t: f64,
    /// `atan2(|w_before|, v_z0)` (rad).
    pub incidence_angle: f64,
    /// `atan2(|w_after|, e_n v_z0)` (rad).
    pub rebound_angle_centre: f64,
    /// `atan2(P |u0|, e_n v_z0)` (rad), negative when the slip reversed.
    pub rebound_angle_contact: f64,
    /// Kinetic energy lost, `(m_t/2) u0² (1 − P²) + (m*/2) v_z0² (1 − e_n²)` (J): to friction,
    /// and to normal damping at `e_n < 1` (the `_e` functions).
    pub energy_lost: f64,
}

/// The crate's version, NUL-terminated, for `oblique_version`.
const VERSION: &CStr =
    match CStr::from_bytes_with_nul(concat!(env!("CARGO_PKG_VERSION"), "\0").as_bytes()) {
        Ok(v) => v,
        Err(_) => panic!("the crate version contains a NUL byte"),
    };

// The handles are shared by threads, as the header promises: they must stay `Send + Sync`.
const _: fn() = || {
    fn shared<T: Send + Sync>() {}
    shared::<ObliqueTable>();
    shared::<ObliqueCurve>();
    shared::<ObliquePrepared>();
};

thread_local! {
    static LAST_ERROR: RefCell<CString> = RefCell::new(CString::default());
}

fn set_error(message: &str) {
    let c = CString::new(message.replace('\0', " ")).unwrap_or_default();
    LAST_ERROR.with(|e| *e.borrow_mut() = c);
}

fn code_of(e: &LookupError) -> c_int {
    match e {
        LookupError::Io { .. } => OBLIQUE_ERR_IO,
        LookupError::Invalid { .. } => OBLIQUE_ERR_TABLE,
        LookupError::Query { .. }
        | LookupError::Batch { .. }
        | LookupError::Length { .. }
        | LookupError::Point { .. }
        | LookupError::Axis { .. } => OBLIQUE_ERR_QUERY,
    }
}

/// Run `f` with panics caught; record the message of a failure.
fn guard(f: impl FnOnce() -> Result<(), (c_int, String)>) -> c_int {
    match catch_unwind(AssertUnwindSafe(f)) {
        Ok(Ok(())) => OBLIQUE_OK,
        Ok(Err((code, message))) => {
            set_error(&message);
            code
        }
        Err(_) => {
            set_error("internal error (panic) in oblique-lookup");
            OBLIQUE_ERR_INTERNAL
        }
    }
}

fn lookup(e: LookupError) -> (c_int, String) {
    (code_of(&e), e.to_string())
}

fn null(name: &str) -> (c_int, String) {
    (OBLIQUE_ERR_NULL, format!("argument '{name}' is NULL"))
}

/// `*p` or an `OBLIQUE_ERR_NULL` error naming it.
///
/// # Safety
/// `p` is NULL or valid for reads of `T`.
unsafe fn read<T: Copy>(p: *const T, name: &str) -> Result<T, (c_int, String)> {
    if p.is_null() {
        Err(null(name))
    } else {
        Ok(*p)
    }
}

/// The library's release (the version of the crate oblique-lookup-capi): a static
/// NUL-terminated string such as `"0.1.0"`; do not free it. Thread-safe.
#[no_mangle]
pub extern "C" fn oblique_version() -> *const c_char {
    VERSION.as_ptr()
}

/// The ABI version of the library, to compare with `OBLIQUE_ABI_VERSION` of the header the
/// caller was compiled with. Thread-safe.
#[no_mangle]
pub extern "C" fn oblique_abi_version() -> c_int {
    OBLIQUE_ABI_VERSION
}

/// Message of the last failed call on the calling thread (UTF-8, NUL-terminated; empty if none).
/// Valid until the next failing call on this thread; do not free it.
#[no_mangle]
pub extern "C" fn oblique_last_error() -> *const c_char {
    LAST_ERROR.with(|e| e.borrow().as_ptr())
}

/// Open, validate and load a table file (HDF5, schema v2 or v3) into memory. On success `*table` is a
/// handle to free with `oblique_table_close`; no file access happens after this call.
///
/// # Safety
/// `path` is NULL or a NUL-terminated string; `table` is NULL or valid for writes.
#[no_mangle]
pub unsafe extern "C" fn oblique_table_open(
    path: *const c_char,
    table: *mut *mut ObliqueTable,
) -> c_int {
    guard(|| {
        if path.is_null() {
            return Err(null("path"));
        }
        if table.is_null() {
            return Err(null("table"));
        }
        let path = CStr::from_ptr(path).to_str().map_err(|_| {
            (
                OBLIQUE_ERR_IO,
                "argument 'path' is not valid UTF-8".to_string(),
            )
        })?;
        let t = Table::open(path).map_err(lookup)?;
        *table = Box::into_raw(Box::new(ObliqueTable(t)));
        Ok(())
    })
}

/// Free a table handle (NULL is ignored).
///
/// # Safety
/// `table` is NULL or a handle from `oblique_table_open` not closed before, used by no other
/// thread during and after the call.
#[no_mangle]
pub unsafe extern "C" fn oblique_table_close(table: *mut ObliqueTable) {
    if !table.is_null() {
        drop(Box::from_raw(table));
    }
}

/// The table's domain: `γ ∈ [*gamma_min, *gamma_max]`, `α ≤ *alpha_max` (`INFINITY` when the
/// no-slip limit is included). Any out-pointer may be NULL.
///
/// # Safety
/// `table` is NULL or a live handle; the out-pointers are NULL or valid for writes.
#[no_mangle]
pub unsafe extern "C" fn oblique_table_domain(
    table: *const ObliqueTable,
    gamma_min: *mut f64,
    gamma_max: *mut f64,
    alpha_max: *mut f64,
) -> c_int {
    guard(|| {
        let t = table.as_ref().ok_or_else(|| null("table"))?;
        let s = &t.0.surface();
        for (p, v) in [
            (gamma_min, s.gamma_min()),
            (gamma_max, s.gamma_max()),
            (alpha_max, s.alpha_max()),
        ] {
            if !p.is_null() {
                *p = v;
            }
        }
        Ok(())
    })
}

/// `clamp` as the functions take it: 0 or 1; any other value is refused (`OBLIQUE_ERR_QUERY`
/// naming it), not read as "clamp".
fn outside(clamp: c_int) -> Result<OutOfDomain, (c_int, String)> {
    match clamp {
        0 => Ok(OutOfDomain::Error),
        1 => Ok(OutOfDomain::Clamp),
        _ => Err((
            OBLIQUE_ERR_QUERY,
            format!(
                "invalid clamp = {clamp}: must be 0 (refuse a point outside the table's \
                 domain) or 1 (answer at the nearest point of the domain)"
            ),
        )),
    }
}

/// `*p = P(γ, α)` (dimensionless). `alpha` may be `INFINITY` (no slip). `clamp` = 0: a point
/// outside the table's domain is an error; 1: it is answered at the nearest point of the domain
/// (in every function: any other value is refused with `OBLIQUE_ERR_QUERY` naming `clamp`).
///
/// # Safety
/// `table` is NULL or a live handle; `p` is NULL or valid for writes.
#[no_mangle]
pub unsafe extern "C" fn oblique_p(
    table: *const ObliqueTable,
    gamma: f64,
    alpha: f64,
    clamp: c_int,
    p: *mut f64,
) -> c_int {
    // `Table::p_e_with` at e_n = 1 is `Table::p_with`, on every path.
    point(table, gamma, alpha, 1.0, clamp, p)
}

/// `*p = P(γ, α, e_n)` (dimensionless) at normal restitution `e_n`: `oblique_p` for a table
/// with an `e_n` axis (built with `domain.e_n_min`/`e_n_max`). An elastic table answers
/// `e_n = 1` only, a table with the axis `e_n` inside its range (`oblique_table_restitution`);
/// otherwise `OBLIQUE_ERR_QUERY` naming `e_n` (never clamped, whatever `clamp`). The table of
/// one pair (`P(α, e_n)` at a single γ: `oblique_table_domain` gives it as both ends) takes a
/// `gamma` within 1e-9 (relative) of its own as its own; above the full-slip line it refuses any
/// other (`OBLIQUE_ERR_QUERY` naming `gamma` and the pair's γ) or, with `clamp` = 1, answers at
/// its own.
///
/// # Safety
/// `table` is NULL or a live handle; `p` is NULL or valid for writes.
#[no_mangle]
pub unsafe extern "C" fn oblique_p_e(
    table: *const ObliqueTable,
    gamma: f64,
    alpha: f64,
    e_n: f64,
    clamp: c_int,
    p: *mut f64,
) -> c_int {
    point(table, gamma, alpha, e_n, clamp, p)
}

/// Shared part of `oblique_p` and `oblique_p_e`.
///
/// # Safety
/// As for `oblique_p_e`.
unsafe fn point(
    table: *const ObliqueTable,
    gamma: f64,
    alpha: f64,
    e_n: f64,
    clamp: c_int,
    p: *mut f64,
) -> c_int {
    guard(|| {
        let t = table.as_ref().ok_or_else(|| null("table"))?;
        if p.is_null() {
            return Err(null("p"));
        }
        *p =
            t.0.p_e_with(gamma, alpha, e_n, outside(clamp)?)
                .map_err(lookup)?;
        Ok(())
    })
}

/// `*p = P(point)` (dimensionless) at a point of `n` values, one per axis of the table in
/// order (`oblique_table_axes`: `gamma`, `alpha`, then the table's extra axes, such as `e_n`):
/// `oblique_p` for `{γ, α}` of an elastic table, `oblique_p_e` for `{γ, α, e_n}` of a table
/// with an `e_n` axis, with the same bits. Another `n` is `OBLIQUE_ERR_QUERY` naming the
/// table's axes; `clamp` as for `oblique_p` (an extra axis is never clamped).
///
/// # Safety
/// `table` is NULL or a live handle; `point` is NULL or valid for `n` reads; `p` is NULL or
/// valid for writes.
#[no_mangle]
pub unsafe extern "C" fn oblique_p_at(
    table: *const ObliqueTable,
    point: *const f64,
    n: usize,
    clamp: c_int,
    p: *mut f64,
) -> c_int {
    guard(|| {
        let t = table.as_ref().ok_or_else(|| null("table"))?;
        if point.is_null() {
            return Err(null("point"));
        }
        if p.is_null() {
            return Err(null("p"));
        }
        // More values than any table has axes are refused before they are read.
        let axes = 2 + oblique_lookup::EXTRA_AXES.len();
        let values = std::slice::from_raw_parts(point, n.min(axes));
        *p = match n <= axes {
            true => t.0.p_at_with(values, outside(clamp)?),
            false => Err(t.0.point_error(n)),
        }
        .map_err(lookup)?;
        Ok(())
    })
}

/// The names of every axis a table may have, NUL-terminated, built once: `gamma`, `alpha`, then
/// the extra axes in their order.
fn axis_names() -> &'static [CString] {
    static NAMES: std::sync::OnceLock<Vec<CString>> = std::sync::OnceLock::new();
    NAMES.get_or_init(|| {
        ["gamma", "alpha"]
            .into_iter()
            .chain(oblique_lookup::EXTRA_AXES.iter().map(|a| a.name))
            .map(|n| CString::new(n).unwrap_or_default())
            .collect()
    })
}

/// The axes of a table's point (`oblique_p_at`): `*n` is their number (2 for an elastic table,
/// 3 with an `e_n` axis); for `i < *n`, `names[i]` (when `names` is not NULL and `i < cap`) is
/// the name of axis `i`, a static NUL-terminated string (`gamma`, `alpha`, `e_n`; do not free
/// it), and `lo[i]`, `hi[i]` (each when not NULL and `i < cap`) its range: `γ` over the
/// domain, `α` over `[0, alpha_max]`, an extra axis over the table's range. Call with `cap` = 0
/// to learn `*n`.
///
/// # Safety
/// `table` is NULL or a live handle; `n` is NULL or valid for writes; `names`, `lo`, `hi` are
/// each NULL or valid for `cap` writes.
#[no_mangle]
pub unsafe extern "C" fn oblique_table_axes(
    table: *const ObliqueTable,
    n: *mut usize,
    names: *mut *const c_char,
    lo: *mut f64,
    hi: *mut f64,
    cap: usize,
) -> c_int {
    guard(|| {
        let t = table.as_ref().ok_or_else(|| null("table"))?;
        if n.is_null() {
            return Err(null("n"));
        }
        let s = t.0.surface();
        let axes = t.0.axes();
        *n = axes.len();
        for (i, name) in axes.iter().enumerate().take(cap) {
            let range = match i {
                0 => (s.gamma_min(), s.gamma_max()),
                1 => (0.0, s.alpha_max()),
                _ => t.0.axis_range(name).unwrap_or((f64::NAN, f64::NAN)),
            };
            if !names.is_null() {
                let c = axis_names()
                    .iter()
                    .find(|c| c.to_bytes() == name.as_bytes());
                *names.add(i) = c.map_or(std::ptr::null(), |c| c.as_ptr());
            }
            if !lo.is_null() {
                *lo.add(i) = range.0;
            }
            if !hi.is_null() {
                *hi.add(i) = range.1;
            }
        }
        Ok(())
    })
}

/// The `e_n` range of a table: `[e_n_min, e_n_max]` for a table with an `e_n` axis, `[1, 1]`
/// for an elastic table. Any out-pointer may be NULL.
///
/// # Safety
/// `table` is NULL or a live handle; the out-pointers are NULL or valid for writes.
#[no_mangle]
pub unsafe extern "C" fn oblique_table_restitution(
    table: *const ObliqueTable,
    e_n_min: *mut f64,
    e_n_max: *mut f64,
) -> c_int {
    guard(|| {
        let t = table.as_ref().ok_or_else(|| null("table"))?;
        let (lo, hi) = t.0.restitution().unwrap_or((1.0, 1.0));
        if let Some(x) = e_n_min.as_mut() {
            *x = lo;
        }
        if let Some(x) = e_n_max.as_mut() {
            *x = hi;
        }
        Ok(())
    })
}

/// `p[i] = P(gamma[i], alpha[i])` for `i < n`, on the calling thread. On an invalid query the
/// message names its index and `p` is filled only before it.
///
/// # Safety
/// `table` is NULL or a live handle; `gamma`, `alpha` are NULL or valid for `n` reads, `p` for
/// `n` writes (not overlapping the inputs).
#[no_mangle]
pub unsafe extern "C" fn oblique_p_batch(
    table: *const ObliqueTable,
    gamma: *const f64,
    alpha: *const f64,
    n: usize,
    clamp: c_int,
    p: *mut f64,
) -> c_int {
    guard(|| {
        let t = table.as_ref().ok_or_else(|| null("table"))?;
        for (ptr, name) in [(gamma, "gamma"), (alpha, "alpha"), (p as *const f64, "p")] {
            if ptr.is_null() {
                return Err(null(name));
            }
        }
        let outside = outside(clamp)?;
        let g = std::slice::from_raw_parts(gamma, n);
        let a = std::slice::from_raw_parts(alpha, n);
        let out = std::slice::from_raw_parts_mut(p, n);
        let points =
            PointColumns::new(Column::scalar("gamma", g), Column::scalar("alpha", a), None)
                .map_err(|e| (OBLIQUE_ERR_QUERY, e.to_string()))?;
        t.0.p_columns(&points, out, outside).map_err(lookup)
    })
}

/// Precompute `P(α)` at one fixed `γ` from a table (for many queries of one pair of materials:
/// the same values as `oblique_p` to about 1e-15, in fewer operations). `clamp` = 0: `γ` outside
/// the table's domain is an error, and so will be `α > alpha_max` in `oblique_curve_p`; 1: both
/// are clamped into the domain. On success `*curve` is a handle to free with
/// `oblique_curve_free`; it does not refer to the table, which may be closed.
///
/// # Safety
/// `table` is NULL or a live handle; `curve` is NULL or valid for writes.
#[no_mangle]
pub unsafe extern "C" fn oblique_curve_new(
    table: *const ObliqueTable,
    gamma: f64,
    clamp: c_int,
    curve: *mut *mut ObliqueCurve,
) -> c_int {
    guard(|| {
        let t = table.as_ref().ok_or_else(|| null("table"))?;
        if curve.is_null() {
            return Err(null("curve"));
        }
        let c = t.0.curve(gamma, outside(clamp)?).map_err(lookup)?;
        *curve = Box::into_raw(Box::new(ObliqueCurve(c)));
        Ok(())
    })
}

/// `*p = P(γ, α)` at the curve's `γ` (dimensionless); `alpha` may be `INFINITY` (no slip).
///
/// # Safety
/// `curve` is NULL or a live handle; `p` is NULL or valid for writes.
#[no_mangle]
pub unsafe extern "C" fn oblique_curve_p(
    curve: *const ObliqueCurve,
    alpha: f64,
    p: *mut f64,
) -> c_int {
    guard(|| {
        let c = curve.as_ref().ok_or_else(|| null("curve"))?;
        if p.is_null() {
            return Err(null("p"));
        }
        *p = c.0.p(alpha).map_err(lookup)?;
        Ok(())
    })
}

/// Free a curve handle (NULL is ignored).
///
/// # Safety
/// `curve` is NULL or a handle from `oblique_curve_new` not freed before, used by no other
/// thread during and after the call.
#[no_mangle]
pub unsafe extern "C" fn oblique_curve_free(curve: *mut ObliqueCurve) {
    if !curve.is_null() {
        drop(Box::from_raw(curve));
    }
}

/// The contact of `c` at normal restitution `e_n` (1: the functions without `_e`).
fn contact(c: &ObliqueContact, e_n: f64) -> Result<Contact, (c_int, String)> {
    let elastic = |m: &ObliqueMaterial| Elastic {
        youngs_modulus: m.youngs_modulus,
        poisson_ratio: m.poisson_ratio,
    };
    Ok(Contact {
        stiffness: if c.gamma == 0.0 {
            Stiffness::Materials(elastic(&c.sphere_material), elastic(&c.other_material))
        } else {
            Stiffness::Gamma(c.gamma)
        },
        friction: c.friction,
        outside: outside(c.clamp)?,
        restitution: e_n,
    })
}

fn body(b: &ObliqueBody) -> Body {
    Body {
        mass: b.mass,
        radius: b.radius,
        kappa: b.kappa,
    }
}

fn motion(m: &ObliqueMotion) -> Motion3 {
    Motion3 {
        velocity: m.velocity,
        spin: m.spin,
    }
}

fn c_motion(m: &Motion3) -> ObliqueMotion {
    ObliqueMotion {
        velocity: m.velocity,
        spin: m.spin,
    }
}

fn c_rebound(gamma: f64, alpha: f64, r: &Rebound3) -> ObliqueRebound {
    ObliqueRebound {
        sphere: c_motion(&r.sphere),
        other: r.other.as_ref().map(c_motion).unwrap_or_default(),
        tangent: r.frame.tangent,
        binormal: r.frame.binormal,
        normal: r.frame.normal,
        gamma,
        alpha,
        p: r.p,
        slip_before: r.slip_before,
        slip_after: r.slip_after,
        tangential_impulse: r.tangential_impulse,
        normal_impulse: r.normal_impulse,
        e_t: r.e_t,
        incidence_angle: r.incidence_angle(),
        rebound_angle_centre: r.rebound_angle_centre(),
        rebound_angle_contact: r.rebound_angle_contact(),
        energy_lost: r.energy_lost,
    }
}

/// Shared part of the two rebound functions.
///
/// # Safety
/// As for `oblique_rebound_spheres`.
#[allow(clippy::too_many_arguments)]
unsafe fn rebound(
    table: *const ObliqueTable,
    sphere: *const ObliqueBody,
    other: Option<*const ObliqueBody>,
    contact_: *const ObliqueContact,
    motion1: *const ObliqueMotion,
    motion2: Option<*const ObliqueMotion>,
    normal: *const f64,
    e_n: f64,
    out: *mut ObliqueRebound,
) -> c_int {
    guard(|| {
        let t = table.as_ref().ok_or_else(|| null("table"))?;
        let pair = Pair {
            sphere: body(&read(sphere, "sphere")?),
            other: match other {
                Some(o) => Some(body(&read(o, "other")?)),
                None => None,
            },
        };
        let c = contact(&read(contact_, "contact")?, e_n)?;
        if normal.is_null() {
            return Err(null("normal"));
        }
        if out.is_null() {
            return Err(null("out"));
        }
        let n = [*normal, *normal.add(1), *normal.add(2)];
        let s = Incident3 {
            sphere: motion(&read(motion1, "motion")?),
            other: match motion2 {
                Some(m) => motion(&read(m, "other_motion")?),
                None => Motion3::default(),
            },
            normal: n,
        };
        let a = t.0.rebound_3d(&pair, &c, &s).map_err(lookup)?;
        *out = c_rebound(a.gamma, a.alpha, &a.rebound);
        Ok(())
    })
}

/// A sphere hitting a fixed wall: `normal` (3 doubles, any non-zero length) points from the
/// sphere into the wall. Writes the state after the impact and the impact's quantities to `*out`.
///
/// # Safety
/// `table` is NULL or a live handle; the other pointers are NULL or valid (`normal` for 3
/// reads, `out` for a write).
#[no_mangle]
pub unsafe extern "C" fn oblique_rebound_wall(
    table: *const ObliqueTable,
    sphere: *const ObliqueBody,
    contact: *const ObliqueContact,
    motion: *const ObliqueMotion,
    normal: *const f64,
    out: *mut ObliqueRebound,
) -> c_int {
    rebound(table, sphere, None, contact, motion, None, normal, 1.0, out)
}

/// Two spheres: `normal` (3 doubles, any non-zero length) points from sphere 1's centre towards
/// sphere 2's. Writes both states after the impact and the impact's quantities to `*out`.
///
/// # Safety
/// `table` is NULL or a live handle; the other pointers are NULL or valid (`normal` for 3
/// reads, `out` for a write).
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn oblique_rebound_spheres(
    table: *const ObliqueTable,
    sphere: *const ObliqueBody,
    other: *const ObliqueBody,
    contact: *const ObliqueContact,
    motion: *const ObliqueMotion,
    other_motion: *const ObliqueMotion,
    normal: *const f64,
    out: *mut ObliqueRebound,
) -> c_int {
    rebound(
        table,
        sphere,
        Some(other),
        contact,
        motion,
        Some(other_motion),
        normal,
        1.0,
        out,
    )
}

/// `oblique_rebound_wall` at normal restitution `e_n` in [0, 1]: the sphere leaves the wall at
/// `e_n` times its approach speed, `P` is `P(γ, α, e_n)` of the table (`oblique_p_e`: `e_n`
/// must lie in the table's range, `oblique_table_restitution`; an elastic table answers
/// `e_n = 1` only), and the normal impulse and the energy lost follow (`ObliqueRebound`). An
/// `e_n` outside [0, 1] or outside the table's range: `OBLIQUE_ERR_QUERY`, also for a pure
/// normal impact (`u0 = 0`), whose `P` is not needed (as every binding refuses it).
/// `e_n = 1`: the answer of `oblique_rebound_wall`, bit for bit.
///
/// # Safety
/// As for `oblique_rebound_wall`.
#[no_mangle]
pub unsafe extern "C" fn oblique_rebound_wall_e(
    table: *const ObliqueTable,
    sphere: *const ObliqueBody,
    contact: *const ObliqueContact,
    e_n: f64,
    motion: *const ObliqueMotion,
    normal: *const f64,
    out: *mut ObliqueRebound,
) -> c_int {
    rebound(table, sphere, None, contact, motion, None, normal, e_n, out)
}

/// `oblique_rebound_spheres` at normal restitution `e_n` in [0, 1]: the spheres separate at
/// `e_n` times their approach speed (see `oblique_rebound_wall_e`). `e_n = 1`: the answer of
/// `oblique_rebound_spheres`, bit for bit.
///
/// # Safety
/// As for `oblique_rebound_spheres`.
#[no_mangle]
#[allow(clippy::too_many_arguments)]
pub unsafe extern "C" fn oblique_rebound_spheres_e(
    table: *const ObliqueTable,
    sphere: *const ObliqueBody,
    other: *const ObliqueBody,
    contact: *const ObliqueContact,
    e_n: f64,
    motion: *const ObliqueMotion,
    other_motion: *const ObliqueMotion,
    normal: *const f64,
    out: *mut ObliqueRebound,
) -> c_int {
    rebound(
        table,
        sphere,
        Some(other),
        contact,
        motion,
        Some(other_motion),
        normal,
        e_n,
        out,
    )
}

/// Check a pair of bodies (`other` NULL: a fixed wall) and its contact once, and precompute what
/// every rebound of the pair needs (`γ`, the reduced masses). On success `*prepared` is a handle
/// for `oblique_rebound_prepared`, to free with `oblique_prepared_free`. It does not depend on a
/// table.
///
/// # Safety
/// `sphere`, `contact` are NULL or valid for reads, `other` is NULL or valid for reads,
/// `prepared` is NULL or valid for writes.
#[no_mangle]
pub unsafe extern "C" fn oblique_prepare(
    sphere: *const ObliqueBody,
    other: *const ObliqueBody,
    contact: *const ObliqueContact,
    prepared: *mut *mut ObliquePrepared,
) -> c_int {
    prepare(sphere, other, contact, 1.0, prepared)
}

/// `oblique_prepare` at normal restitution `e_n` in [0, 1] (else `OBLIQUE_ERR_QUERY`): the
/// handle's rebounds (`oblique_rebound_prepared`) are those of `oblique_rebound_wall_e` /
/// `oblique_rebound_spheres_e`, and need a table that answers `e_n` (`oblique_p_e`). `e_n = 1`:
/// the handle of `oblique_prepare`.
///
/// # Safety
/// As for `oblique_prepare`.
#[no_mangle]
pub unsafe extern "C" fn oblique_prepare_e(
    sphere: *const ObliqueBody,
    other: *const ObliqueBody,
    contact: *const ObliqueContact,
    e_n: f64,
    prepared: *mut *mut ObliquePrepared,
) -> c_int {
    prepare(sphere, other, contact, e_n, prepared)
}

/// `oblique_prepare_e` for rebounds through `table`: an `e_n` the table does not answer is
/// refused at once (`OBLIQUE_ERR_QUERY`). For a table with an `e_n` axis the handle also holds
/// the pair's `P(α)` at its `(γ, e_n)` through that table (a few kB, computed once, about
/// 2 µs), and `oblique_rebound_prepared` with that table answers with the same bits in fewer
/// operations. With another table the handle answers as `oblique_prepare_e`'s. The handle
/// owns what it holds: it stays valid after the table is closed.
///
/// # Safety
/// `table` is NULL or a live handle; otherwise as for `oblique_prepare`.
#[no_mangle]
pub unsafe extern "C" fn oblique_prepare_table(
    table: *const ObliqueTable,
    sphere: *const ObliqueBody,
    other: *const ObliqueBody,
    contact: *const ObliqueContact,
    e_n: f64,
    prepared: *mut *mut ObliquePrepared,
) -> c_int {
    guard(|| {
        let t = table.as_ref().ok_or_else(|| null("table"))?;
        prepare_with(sphere, other, contact, e_n, prepared, |pair, c| {
            t.0.prepare(pair, c)
        })
    })
}

/// Shared part of `oblique_prepare` and `oblique_prepare_e`.
///
/// # Safety
/// As for `oblique_prepare`.
unsafe fn prepare(
    sphere: *const ObliqueBody,
    other: *const ObliqueBody,
    contact: *const ObliqueContact,
    e_n: f64,
    prepared: *mut *mut ObliquePrepared,
) -> c_int {
    guard(|| prepare_with(sphere, other, contact, e_n, prepared, Prepared::new))
}

/// The pair and contact read and checked, then `*prepared` from `make`.
///
/// # Safety
/// As for `oblique_prepare`.
unsafe fn prepare_with(
    sphere: *const ObliqueBody,
    other: *const ObliqueBody,
    contact: *const ObliqueContact,
    e_n: f64,
    prepared: *mut *mut ObliquePrepared,
    make: impl FnOnce(&Pair, &Contact) -> Result<Prepared, LookupError>,
) -> Result<(), (c_int, String)> {
    let pair = Pair {
        sphere: body(&read(sphere, "sphere")?),
        other: other.as_ref().map(body),
    };
    let c = self::contact(&read(contact, "contact")?, e_n)?;
    if prepared.is_null() {
        return Err(null("prepared"));
    }
    let k = make(&pair, &c).map_err(lookup)?;
    *prepared = Box::into_raw(Box::new(ObliquePrepared(k)));
    Ok(())
}

/// Free a handle from `oblique_prepare` (NULL is ignored).
///
/// # Safety
/// `prepared` is NULL or a handle from `oblique_prepare` not freed before, used by no other
/// thread during and after the call.
#[no_mangle]
pub unsafe extern "C" fn oblique_prepared_free(prepared: *mut ObliquePrepared) {
    if !prepared.is_null() {
        drop(Box::from_raw(prepared));
    }
}

/// One impact of a prepared pair: `motion` of sphere 1, `other_motion` of sphere 2 (NULL: at
/// rest; for a wall it must be NULL or all zero), `normal` (3 doubles, any non-zero length) from sphere 1
/// into the other body. Writes the same `*out` as `oblique_rebound_spheres` /
/// `oblique_rebound_wall` (up to rounding), without checking the bodies and the materials again.
///
/// # Safety
/// `table` is NULL or a live handle, `prepared` NULL or a live handle from `oblique_prepare`;
/// the other pointers are NULL or valid (`normal` for 3 reads, `out` for a write).
#[no_mangle]
pub unsafe extern "C" fn oblique_rebound_prepared(
    table: *const ObliqueTable,
    prepared: *const ObliquePrepared,
    motion: *const ObliqueMotion,
    other_motion: *const ObliqueMotion,
    normal: *const f64,
    out: *mut ObliqueRebound,
) -> c_int {
    guard(|| {
        let t = table.as_ref().ok_or_else(|| null("table"))?;
        let k = prepared.as_ref().ok_or_else(|| null("prepared"))?;
        if normal.is_null() {
            return Err(null("normal"));
        }
        if out.is_null() {
            return Err(null("out"));
        }
        let s = Incident3 {
            sphere: self::motion(&read(motion, "motion")?),
            other: other_motion.as_ref().map(self::motion).unwrap_or_default(),
            normal: [*normal, *normal.add(1), *normal.add(2)],
        };
        let a = t.0.rebound_3d_prepared(&k.0, &s).map_err(lookup)?;
        *out = c_rebound(a.gamma, a.alpha, &a.rebound);
        Ok(())
    })
}
