//! `oblique._native`: the Rust side of the Python package `oblique`.
//!
//! Flat functions over contiguous one-dimensional float64 arrays; the Python layer
//! (`python/oblique/__init__.py`) converts, broadcasts and reshapes, and gives the public API
//! its names and documentation. A column here is the data of one argument: length 1 (the same
//! value for every row) or the number of rows (`3 ×` that for a vector). Every loop over rows
//! runs with the GIL released, in parallel on rayon's pool for large inputs, and stops at the
//! first invalid row; the error names the row by its index in the broadcast shape.
//!
//! `build_table` ([`build`]) builds a table from a config, as `sweep run` does.
//!
//! Symbols and units are those of `physics.md` and `oblique_physics::rebound` (SI).

use numpy::{PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadwriteArray1, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;

use oblique_lookup::rebound::{
    Body, Elastic, Incident, Incident3, Motion3, Pair, Rebound, Rebound3, State,
};
use oblique_lookup::{Answer, Contact, LookupError, OutOfDomain, Prepared, Stiffness};
use oblique_physics::regimes::{self, Regime};
use oblique_solver::units::{Groups, PhysicalImpact};
use oblique_solver::{Accuracy, Law, Method, PhysicsError, Request, PARAMETER_KEYS};

mod build;

create_exception!(
    oblique,
    TableError,
    PyOSError,
    "A file that is not a readable, valid P table (damaged, truncated, not a table, a newer \
     schema). The message names the file and the problem."
);

/// Rows per parallel task; below two chunks the loop runs on the calling thread.
const CHUNK: usize = 4096;

fn outside(clamp: bool) -> OutOfDomain {
    if clamp {
        OutOfDomain::Clamp
    } else {
        OutOfDomain::Error
    }
}

/// `index` (row-major, 0-based) in `shape`, as Python prints a tuple index.
fn unravel(mut index: usize, shape: &[usize]) -> String {
    let mut parts = vec![0; shape.len()];
    for (p, &n) in parts.iter_mut().zip(shape).rev() {
        if n > 0 {
            *p = index % n;
            index /= n;
        }
    }
    match parts.len() {
        0 => "()".into(),
        1 => format!("({},)", parts[0]),
        _ => format!(
            "({})",
            parts
                .iter()
                .map(|p| p.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// A lookup error as a Python exception: the file's problems as [`TableError`], a query's as
/// `ValueError`; a batch's failing row is named by its index in `shape`.
fn lookup_error(e: LookupError, shape: &[usize]) -> PyErr {
    match e {
        LookupError::Io { .. } | LookupError::Invalid { .. } => TableError::new_err(e.to_string()),
        LookupError::Batch { index, source } => row_error(index, shape, &source.to_string()),
        other => PyValueError::new_err(other.to_string()),
    }
}

/// `message`, naming the failing row by its index in `shape` (nothing for a scalar call).
fn at_index(message: String, index: usize, shape: &[usize]) -> String {
    if shape.is_empty() {
        message
    } else {
        format!("{message} (at index {})", unravel(index, shape))
    }
}

fn row_error(index: usize, shape: &[usize], message: &str) -> PyErr {
    PyValueError::new_err(at_index(message.to_string(), index, shape))
}

/// A solver error as a Python exception (a tolerance not reached is a `RuntimeError`, bad input
/// a `ValueError`), naming the failing row by its index in `shape`.
fn physics_error(e: PhysicsError, index: usize, shape: &[usize]) -> PyErr {
    let text = at_index(e.to_string(), index, shape);
    match e {
        PhysicsError::ToleranceUnreachable { .. } => PyRuntimeError::new_err(text),
        _ => PyValueError::new_err(text),
    }
}

/// One argument's data: one value for every row, or one per row (`width` values each).
#[derive(Clone, Copy)]
struct Col<'a> {
    data: &'a [f64],
    width: usize,
}

impl<'a> Col<'a> {
    fn new(
        name: &str,
        a: &'a PyReadonlyArray1<'_, f64>,
        width: usize,
        rows: usize,
    ) -> PyResult<Col<'a>> {
        let data = a.as_slice().map_err(|_| {
            PyValueError::new_err(format!("{name}: expected a contiguous float64 array"))
        })?;
        if data.len() != width && data.len() != width * rows {
            return Err(PyValueError::new_err(format!(
                "{name}: {} values, expected {width} or {}",
                data.len(),
                width * rows
            )));
        }
        Ok(Col { data, width })
    }

    /// Whether every row has the same value.
    fn shared(&self) -> bool {
        self.data.len() == self.width
    }

    #[inline]
    fn at(&self, row: usize) -> f64 {
        if self.shared() {
            self.data[0]
        } else {
            self.data[row]
        }
    }

    #[inline]
    fn vec(&self, row: usize) -> [f64; 3] {
        let k = if self.shared() { 0 } else { 3 * row };
        [self.data[k], self.data[k + 1], self.data[k + 2]]
    }
}

/// Fill `out` (rows of `width` values) by `row(i, that_row)` for every row, `chunk` rows per
/// parallel task (on the calling thread below two tasks), GIL released; the error of the lowest
/// failing row.
fn fill_rows<E: Send>(
    py: Python<'_>,
    out: &mut [f64],
    width: usize,
    chunk: usize,
    row: impl Fn(usize, &mut [f64]) -> Result<(), E> + Sync + Send,
) -> Result<(), (usize, E)> {
    let rows = out.len() / width.max(1);
    py.detach(|| {
        let run = |(k, block): (usize, &mut [f64])| -> Result<(), (usize, E)> {
            for (j, r) in block.chunks_mut(width).enumerate() {
                let i = k * chunk + j;
                row(i, r).map_err(|e| (i, e))?;
            }
            Ok(())
        };
        if rows < 2 * chunk {
            out.chunks_mut(chunk * width).enumerate().try_for_each(run)
        } else {
            let errors: Vec<(usize, E)> = out
                .par_chunks_mut(chunk * width)
                .enumerate()
                .filter_map(|x| run(x).err())
                .collect();
            match errors.into_iter().min_by_key(|(i, _)| *i) {
                None => Ok(()),
                Some(e) => Err(e),
            }
        }
    })
}

/// [`new_rows`] for rows that each cost milliseconds or more (simulations): the rows run in
/// waves of a few per worker thread, and between waves the interpreter's signal handlers run,
/// so that Ctrl-C raises `KeyboardInterrupt` within one wave (about a second at most) instead
/// of after the whole array. A row's error stops the array at the lowest failing row of its
/// wave.
fn new_rows_interruptible<'py, E: Send>(
    py: Python<'py>,
    rows: usize,
    width: usize,
    row: impl Fn(usize, &mut [f64]) -> Result<(), E> + Sync + Send,
    error: impl FnOnce(usize, E) -> PyErr,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    new_array(py, rows, width, |o| {
        let wave = 4 * rayon::current_num_threads().max(1);
        for (w, block) in o.chunks_mut(wave * width.max(1)).enumerate() {
            let first = w * wave;
            let failed = py.detach(|| {
                block
                    .par_chunks_mut(width.max(1))
                    .enumerate()
                    .filter_map(|(j, r)| row(first + j, r).err().map(|e| (first + j, e)))
                    .min_by_key(|(i, _)| *i)
            });
            if let Some((i, e)) = failed {
                return Err(error(i, e));
            }
            py.check_signals()?;
        }
        Ok(())
    })
}

/// A new zeroed `(rows, width)` array, filled in place by `fill`.
fn new_array<'py>(
    py: Python<'py>,
    rows: usize,
    width: usize,
    fill: impl FnOnce(&mut [f64]) -> PyResult<()>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let out = PyArray2::<f64>::zeros(py, [rows, width], false);
    {
        let mut rw = out.readwrite();
        let o = rw
            .as_slice_mut()
            .map_err(|_| PyRuntimeError::new_err("output array is not contiguous"))?;
        fill(o)?;
    }
    Ok(out)
}

/// A new `(rows, width)` array filled by [`fill_rows`]; the lowest failing row's error as
/// `error(row, e)`.
fn new_rows<'py, E: Send>(
    py: Python<'py>,
    rows: usize,
    width: usize,
    chunk: usize,
    row: impl Fn(usize, &mut [f64]) -> Result<(), E> + Sync + Send,
    error: impl FnOnce(usize, E) -> PyErr,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    new_array(py, rows, width, |o| {
        fill_rows(py, o, width, chunk, row).map_err(|(i, e)| error(i, e))
    })
}

fn slice_mut<'a>(name: &str, a: &'a mut PyReadwriteArray1<'_, f64>) -> PyResult<&'a mut [f64]> {
    a.as_slice_mut()
        .map_err(|_| PyValueError::new_err(format!("{name}: expected a contiguous float64 array")))
}

fn slice<'a>(name: &str, a: &'a PyReadonlyArray1<'_, f64>) -> PyResult<&'a [f64]> {
    a.as_slice()
        .map_err(|_| PyValueError::new_err(format!("{name}: expected a contiguous float64 array")))
}

fn same_length(name: &str, len: usize, expected: usize) -> PyResult<()> {
    if len == expected {
        Ok(())
    } else {
        Err(PyValueError::new_err(format!(
            "{name}: length {len}, expected {expected}"
        )))
    }
}

/// A loaded table (`oblique_lookup::Table`): immutable, shared by threads.
#[pyclass(frozen, module = "oblique._native", name = "Table")]
struct PyTable {
    inner: oblique_lookup::Table,
    path: String,
}

#[pymethods]
impl PyTable {
    /// Open, validate and load a table file (HDF5, written by `sweep run`).
    #[new]
    fn new(py: Python<'_>, path: std::path::PathBuf) -> PyResult<Self> {
        let inner = py
            .detach(|| oblique_lookup::Table::open(&path))
            .map_err(|e| lookup_error(e, &[]))?;
        Ok(PyTable {
            inner,
            path: path.display().to_string(),
        })
    }

    /// The table built into the module (`EMBEDDED_TABLE`: tables/isotropic.h5).
    #[staticmethod]
    fn embedded(py: Python<'_>) -> PyResult<Self> {
        let inner = py
            .detach(oblique_lookup::Table::embedded)
            .map_err(|e| lookup_error(e, &[]))?;
        Ok(PyTable {
            inner,
            path: oblique_lookup::embedded_name(),
        })
    }

    /// `P(γ, α)` of one point.
    fn p(&self, gamma: f64, alpha: f64, clamp: bool) -> PyResult<f64> {
        self.inner
            .p_with(gamma, alpha, outside(clamp))
            .map_err(|e| lookup_error(e, &[]))
    }

    /// `out[i] = P(gamma[i], alpha[i])`; `shape` names a failing index.
    fn p_into(
        &self,
        py: Python<'_>,
        gamma: PyReadonlyArray1<'_, f64>,
        alpha: PyReadonlyArray1<'_, f64>,
        mut out: PyReadwriteArray1<'_, f64>,
        clamp: bool,
        shape: Vec<usize>,
    ) -> PyResult<()> {
        let (g, a) = (slice("gamma", &gamma)?, slice("alpha", &alpha)?);
        let o = slice_mut("out", &mut out)?;
        same_length("alpha", a.len(), g.len())?;
        same_length("out", o.len(), g.len())?;
        let t = &self.inner;
        let r = py.detach(|| {
            if g.len() < 2 * CHUNK {
                t.p_batch(g, a, o, outside(clamp))
            } else {
                t.p_batch_par(g, a, o, outside(clamp))
            }
        });
        r.map_err(|e| lookup_error(e, &shape))
    }

    /// `P(γ, α, e_n)` of one point.
    fn p_e(&self, gamma: f64, alpha: f64, e_n: f64, clamp: bool) -> PyResult<f64> {
        self.inner
            .p_e_with(gamma, alpha, e_n, outside(clamp))
            .map_err(|e| lookup_error(e, &[]))
    }

    /// `out[i] = P(gamma[i], alpha[i], e_n[i])`; `shape` names a failing index.
    #[allow(clippy::too_many_arguments)]
    fn p_e_into(
        &self,
        py: Python<'_>,
        gamma: PyReadonlyArray1<'_, f64>,
        alpha: PyReadonlyArray1<'_, f64>,
        e_n: PyReadonlyArray1<'_, f64>,
        mut out: PyReadwriteArray1<'_, f64>,
        clamp: bool,
        shape: Vec<usize>,
    ) -> PyResult<()> {
        let (g, a, e) = (
            slice("gamma", &gamma)?,
            slice("alpha", &alpha)?,
            slice("e_n", &e_n)?,
        );
        let o = slice_mut("out", &mut out)?;
        same_length("alpha", a.len(), g.len())?;
        same_length("e_n", e.len(), g.len())?;
        same_length("out", o.len(), g.len())?;
        let t = &self.inner;
        let r = py.detach(|| {
            if g.len() < 2 * CHUNK {
                t.p_e_batch(g, a, e, o, outside(clamp))
            } else {
                t.p_e_batch_par(g, a, e, o, outside(clamp))
            }
        });
        r.map_err(|e| lookup_error(e, &shape))
    }

    /// A per-γ curve.
    fn curve(&self, py: Python<'_>, gamma: f64, clamp: bool) -> PyResult<PyCurve> {
        let t = &self.inner;
        let inner = py
            .detach(|| t.curve(gamma, outside(clamp)))
            .map_err(|e| lookup_error(e, &[]))?;
        Ok(PyCurve { inner })
    }

    /// Domain, bound and provenance as a dict.
    fn info<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let t = &self.inner;
        let s = t.surface();
        let p = t.provenance();
        let d = PyDict::new(py);
        d.set_item("path", &self.path)?;
        d.set_item("gamma_min", s.gamma_min())?;
        d.set_item("gamma_max", s.gamma_max())?;
        d.set_item("alpha_max", s.alpha_max())?;
        // The single γ of the table of one pair (axes alpha, e_n; gamma_min = gamma_max), None
        // for a table over a range of γ; and the table's axes, in order.
        d.set_item("pair_gamma", s.pair_gamma())?;
        let axes: Vec<&str> = s.axes().iter().map(|a| a.name.name()).collect();
        d.set_item("axes", axes)?;
        // The e_n range ([1, 1] for an elastic table) and the law of the node values.
        let (e_lo, e_hi) = s.restitution().unwrap_or((1.0, 1.0));
        d.set_item("e_n_min", e_lo)?;
        d.set_item("e_n_max", e_hi)?;
        d.set_item(
            "law",
            if s.restitution().is_some() {
                p.law.as_str()
            } else {
                "elastic"
            },
        )?;
        d.set_item("error_bound", t.error_bound())?;
        d.set_item("schema_version", p.schema_version)?;
        d.set_item("engine_version", &p.engine_version)?;
        d.set_item("git_commit", &p.git_commit)?;
        d.set_item("created", &p.created)?;
        d.set_item("wall_time_s", p.wall_time_s)?;
        d.set_item("node_tol", p.node_tol)?;
        d.set_item("check_tol", p.check_tol)?;
        d.set_item("target_error", p.target_error)?;
        d.set_item("solver", &p.solver)?;
        d.set_item("config", &p.config)?;
        d.set_item("checks", t.checks().len())?;
        let worst = t
            .checks()
            .iter()
            .map(|c| c.interpolation_error)
            .fold(0.0, f64::max);
        d.set_item("checks_max_error", worst)?;
        Ok(d)
    }
}

/// `P(α)` at one fixed `γ` (`oblique_lookup::Curve`).
#[pyclass(frozen, module = "oblique._native", name = "Curve")]
struct PyCurve {
    inner: oblique_lookup::Curve,
}

#[pymethods]
impl PyCurve {
    /// `γ` the curve answers (after clamping).
    #[getter]
    fn gamma(&self) -> f64 {
        self.inner.gamma()
    }

    /// `γ` asked for.
    #[getter]
    fn requested_gamma(&self) -> f64 {
        self.inner.requested_gamma()
    }

    /// Bytes held.
    #[getter]
    fn nbytes(&self) -> usize {
        self.inner.bytes()
    }

    fn p(&self, alpha: f64) -> PyResult<f64> {
        self.inner.p(alpha).map_err(|e| lookup_error(e, &[]))
    }

    fn p_into(
        &self,
        py: Python<'_>,
        alpha: PyReadonlyArray1<'_, f64>,
        mut out: PyReadwriteArray1<'_, f64>,
        shape: Vec<usize>,
    ) -> PyResult<()> {
        let a = slice("alpha", &alpha)?;
        let o = slice_mut("out", &mut out)?;
        same_length("out", o.len(), a.len())?;
        let c = &self.inner;
        fill_rows(py, o, 1, CHUNK, |i, r| {
            r[0] = c.p(a[i])?;
            Ok::<(), LookupError>(())
        })
        .map_err(|(i, e)| row_error(i, &shape, &e.to_string()))
    }
}

/// `γ`, `α` as checked by the solver and the table alike (`γ` finite > 0, `α ≥ 0`).
fn check_groups(gamma: f64, alpha: f64) -> Result<(), PhysicsError> {
    oblique_solver::impact::check_gamma(gamma)?;
    oblique_solver::impact::check_alpha(alpha)?;
    Ok(())
}

/// Regime codes at normal restitution `e_n` (Kelvin–Voigt law; `1`: elastic): 0 full slip
/// (up to `α_c1(γ, e_n)` for `γ > 1`), 1 partial slip, 2 stick.
#[pyfunction]
fn regime_into(
    py: Python<'_>,
    gamma: PyReadonlyArray1<'_, f64>,
    alpha: PyReadonlyArray1<'_, f64>,
    e_n: PyReadonlyArray1<'_, f64>,
    mut out: PyReadwriteArray1<'_, f64>,
    shape: Vec<usize>,
) -> PyResult<()> {
    let n = out.len();
    let (g, a, e) = (
        Col::new("gamma", &gamma, 1, n)?,
        Col::new("alpha", &alpha, 1, n)?,
        Col::new("e_n", &e_n, 1, n)?,
    );
    let o = slice_mut("out", &mut out)?;
    fill_rows(py, o, 1, CHUNK, |i, r| {
        let (gi, ai) = (g.at(i), a.at(i));
        check_groups(gi, ai)?;
        let ei = oblique_solver::law::check_restitution(e.at(i))?;
        r[0] = match Regime::of_dissipative(gi, ai, ei) {
            Regime::FullSlip => 0.0,
            Regime::PartialSlip => 1.0,
            Regime::Stick => 2.0,
        };
        Ok::<(), PhysicsError>(())
    })
    .map_err(|(i, e)| row_error(i, &shape, &e.to_string()))
}

/// `α_c1(γ, e_n)`, `α_c2(γ)` into the two columns of `out` (rows of 2).
#[pyfunction]
fn critical_into(
    py: Python<'_>,
    gamma: PyReadonlyArray1<'_, f64>,
    e_n: PyReadonlyArray1<'_, f64>,
    mut out: PyReadwriteArray1<'_, f64>,
    shape: Vec<usize>,
) -> PyResult<()> {
    let n = out.len() / 2;
    let g = Col::new("gamma", &gamma, 1, n)?;
    let e = Col::new("e_n", &e_n, 1, n)?;
    let o = slice_mut("out", &mut out)?;
    fill_rows(py, o, 2, CHUNK, |i, r| {
        let gi = oblique_solver::impact::check_gamma(g.at(i))?;
        let ei = oblique_solver::law::check_restitution(e.at(i))?;
        r[0] = regimes::alpha_c1_dissipative(gi, ei);
        r[1] = regimes::alpha_c2(gi);
        Ok::<(), PhysicsError>(())
    })
    .map_err(|(i, e)| row_error(i, &shape, &e.to_string()))
}

/// Centre-of-mass `e_t = 1 − (κ/(1 + κ))(1 − P)` of a sphere hitting a wall without spin.
#[pyfunction]
fn e_t_into(
    py: Python<'_>,
    p: PyReadonlyArray1<'_, f64>,
    kappa: PyReadonlyArray1<'_, f64>,
    mut out: PyReadwriteArray1<'_, f64>,
    shape: Vec<usize>,
) -> PyResult<()> {
    let n = out.len();
    let (p, k) = (Col::new("p", &p, 1, n)?, Col::new("kappa", &kappa, 1, n)?);
    let o = slice_mut("out", &mut out)?;
    fill_rows(py, o, 1, CHUNK, |i, r| {
        r[0] = regimes::centre_restitution(p.at(i), k.at(i))?;
        Ok::<(), oblique_physics::InvalidInput>(())
    })
    .map_err(|(i, e)| row_error(i, &shape, &e.to_string()))
}

/// What sets `γ` for every row: given, or the elastic constants of both bodies.
enum Stiff<'a> {
    Gamma(Col<'a>),
    Materials([Col<'a>; 4]),
}

impl Stiff<'_> {
    fn at(&self, i: usize) -> Stiffness {
        match self {
            Stiff::Gamma(g) => Stiffness::Gamma(g.at(i)),
            Stiff::Materials([e1, n1, e2, n2]) => Stiffness::Materials(
                Elastic {
                    youngs_modulus: e1.at(i),
                    poisson_ratio: n1.at(i),
                },
                Elastic {
                    youngs_modulus: e2.at(i),
                    poisson_ratio: n2.at(i),
                },
            ),
        }
    }

    fn shared(&self) -> bool {
        match self {
            Stiff::Gamma(g) => g.shared(),
            Stiff::Materials(c) => c.iter().all(Col::shared),
        }
    }
}

/// Bodies (`mass`, `radius`, `kappa` of sphere 1, then of sphere 2 unless a wall) and contact.
struct Setup<'a> {
    sphere: [Col<'a>; 3],
    other: Option<[Col<'a>; 3]>,
    stiffness: Stiff<'a>,
    friction: Col<'a>,
    /// Normal restitution `e_n` (1 for the callers that take none).
    restitution: Col<'a>,
    clamp: bool,
}

impl Setup<'_> {
    fn pair(&self, i: usize) -> Pair {
        let body = |c: &[Col; 3]| Body {
            mass: c[0].at(i),
            radius: c[1].at(i),
            kappa: c[2].at(i),
        };
        Pair {
            sphere: body(&self.sphere),
            other: self.other.as_ref().map(body),
        }
    }

    fn contact(&self, i: usize) -> Contact {
        Contact {
            stiffness: self.stiffness.at(i),
            friction: self.friction.at(i),
            outside: outside(self.clamp),
            restitution: self.restitution.at(i),
        }
    }

    /// `Ok` when `table` answers the `e_n` of row `i` (exactly 1 for an elastic table, inside
    /// its range for one with an `e_n` axis): checked for every row, also where the contact
    /// point does not slip and the table is not consulted.
    fn check_restitution(
        &self,
        table: &oblique_lookup::Table,
        i: usize,
    ) -> Result<(), LookupError> {
        table.surface().check_e_n(self.restitution.at(i))
    }

    fn shared(&self) -> bool {
        self.sphere.iter().all(Col::shared)
            && self.other.iter().flatten().all(Col::shared)
            && self.stiffness.shared()
            && self.friction.shared()
            && self.restitution.shared()
    }
}

/// Reads the body and contact columns (see `Setup`); `rows` is the number of rows, `e_n` the
/// normal restitution (`None`: 1 for every row).
#[allow(clippy::too_many_arguments)]
fn setup<'a>(
    rows: usize,
    sphere: &'a [PyReadonlyArray1<'_, f64>],
    other: &'a [PyReadonlyArray1<'_, f64>],
    gamma: &'a Option<PyReadonlyArray1<'_, f64>>,
    materials: &'a [PyReadonlyArray1<'_, f64>],
    friction: &'a PyReadonlyArray1<'_, f64>,
    e_n: Option<&'a PyReadonlyArray1<'_, f64>>,
    clamp: bool,
) -> PyResult<Setup<'a>> {
    let three = |name: &str, v: &'a [PyReadonlyArray1<'_, f64>]| -> PyResult<[Col<'a>; 3]> {
        if v.len() != 3 {
            return Err(PyValueError::new_err(format!(
                "{name}: expected mass, radius, kappa"
            )));
        }
        Ok([
            Col::new("mass", &v[0], 1, rows)?,
            Col::new("radius", &v[1], 1, rows)?,
            Col::new("kappa", &v[2], 1, rows)?,
        ])
    };
    let stiffness = match gamma {
        Some(g) => Stiff::Gamma(Col::new("gamma", g, 1, rows)?),
        None => {
            if materials.len() != 4 {
                return Err(PyValueError::new_err(
                    "materials: expected E and nu of both bodies",
                ));
            }
            Stiff::Materials([
                Col::new("youngs_modulus", &materials[0], 1, rows)?,
                Col::new("poisson_ratio", &materials[1], 1, rows)?,
                Col::new("other youngs_modulus", &materials[2], 1, rows)?,
                Col::new("other poisson_ratio", &materials[3], 1, rows)?,
            ])
        }
    };
    Ok(Setup {
        sphere: three("sphere", sphere)?,
        other: if other.is_empty() {
            None
        } else {
            Some(three("other", other)?)
        },
        stiffness,
        friction: Col::new("friction", friction, 1, rows)?,
        restitution: match e_n {
            Some(e) => Col::new("e_n", e, 1, rows)?,
            None => Col {
                data: &[1.0],
                width: 1,
            },
        },
        clamp,
    })
}

/// Columns of a 3-D rebound row.
const REBOUND3: [&str; 31] = [
    "velocity_x",
    "velocity_y",
    "velocity_z",
    "spin_x",
    "spin_y",
    "spin_z",
    "other_velocity_x",
    "other_velocity_y",
    "other_velocity_z",
    "other_spin_x",
    "other_spin_y",
    "other_spin_z",
    "gamma",
    "alpha",
    "p",
    "e_t",
    "slip_before",
    "slip_after",
    "tangential_impulse",
    "normal_impulse",
    "e_n",
    "approach_speed",
    "centre_speed_before",
    "centre_speed_after",
    "energy_lost",
    "tangent_x",
    "tangent_y",
    "tangent_z",
    "incidence_angle",
    "rebound_angle_centre",
    "rebound_angle_contact",
];

fn write3(a: &Answer<Rebound3>, r: &mut [f64]) {
    let b = &a.rebound;
    r[0..3].copy_from_slice(&b.sphere.velocity);
    r[3..6].copy_from_slice(&b.sphere.spin);
    let o = b.other.unwrap_or(Motion3 {
        velocity: [f64::NAN; 3],
        spin: [f64::NAN; 3],
    });
    r[6..9].copy_from_slice(&o.velocity);
    r[9..12].copy_from_slice(&o.spin);
    r[12..25].copy_from_slice(&[
        a.gamma,
        a.alpha,
        b.p,
        b.e_t,
        b.slip_before,
        b.slip_after,
        b.tangential_impulse,
        b.normal_impulse,
        b.e_n,
        b.approach_speed,
        b.centre_speed_before,
        b.centre_speed_after,
        b.energy_lost,
    ]);
    r[25..28].copy_from_slice(&b.frame.tangent);
    r[28] = b.incidence_angle();
    r[29] = b.rebound_angle_centre();
    r[30] = b.rebound_angle_contact();
}

/// 3-D rebounds of `rows` impacts; returns `(rows, len(REBOUND3))`.
#[pyfunction]
#[pyo3(signature = (table, rows, shape, velocity, spin, other_velocity, other_spin, normal, sphere, other, gamma, materials, friction, e_n, clamp))]
#[allow(clippy::too_many_arguments)]
fn rebound_3d<'py>(
    py: Python<'py>,
    table: &PyTable,
    rows: usize,
    shape: Vec<usize>,
    velocity: PyReadonlyArray1<'_, f64>,
    spin: PyReadonlyArray1<'_, f64>,
    other_velocity: PyReadonlyArray1<'_, f64>,
    other_spin: PyReadonlyArray1<'_, f64>,
    normal: PyReadonlyArray1<'_, f64>,
    sphere: Vec<PyReadonlyArray1<'_, f64>>,
    other: Vec<PyReadonlyArray1<'_, f64>>,
    gamma: Option<PyReadonlyArray1<'_, f64>>,
    materials: Vec<PyReadonlyArray1<'_, f64>>,
    friction: PyReadonlyArray1<'_, f64>,
    e_n: PyReadonlyArray1<'_, f64>,
    clamp: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let s = setup(
        rows,
        &sphere,
        &other,
        &gamma,
        &materials,
        &friction,
        Some(&e_n),
        clamp,
    )?;
    let v1 = Col::new("velocity", &velocity, 3, rows)?;
    let w1 = Col::new("spin", &spin, 3, rows)?;
    let v2 = Col::new("other_velocity", &other_velocity, 3, rows)?;
    let w2 = Col::new("other_spin", &other_spin, 3, rows)?;
    let n = Col::new("normal", &normal, 3, rows)?;
    let incident = |i: usize| Incident3 {
        sphere: Motion3 {
            velocity: v1.vec(i),
            spin: w1.vec(i),
        },
        other: Motion3 {
            velocity: v2.vec(i),
            spin: w2.vec(i),
        },
        normal: n.vec(i),
    };
    let t = &table.inner;
    // One e_n for every row: check it once (no index), else row by row.
    let each_e_n = !s.restitution.shared();
    if !each_e_n {
        s.check_restitution(t, 0)
            .map_err(|e| lookup_error(e, &[]))?;
    }
    // One pair and contact for every row: check them once. For many rows, prepare the pair for
    // this table (with an e_n axis: its P(α) at the pair's (γ, e_n) computed once, 2-9 µs,
    // then about 15 ns less per row; the same bits).
    let prepared = if s.shared() {
        let (pair, contact) = (s.pair(0), s.contact(0));
        let k = if rows >= PREPARE_FOR_TABLE_ROWS {
            // A pair that this table does not prepare for (the table of one pair at another
            // γ) goes the way of fewer rows: its rows are answered or refused one by one, so
            // the answer does not depend on the number of rows.
            t.prepare(&pair, &contact)
                .or_else(|_| Prepared::new(&pair, &contact))
        } else {
            Prepared::new(&pair, &contact)
        };
        Some(k.map_err(|e| lookup_error(e, &[]))?)
    } else {
        None
    };
    new_rows(
        py,
        rows,
        REBOUND3.len(),
        CHUNK,
        |i, r| {
            if each_e_n {
                s.check_restitution(t, i)?;
            }
            let answer = match &prepared {
                Some(k) => t.rebound_3d_prepared(k, &incident(i))?,
                None => t.rebound_3d(&s.pair(i), &s.contact(i), &incident(i))?,
            };
            write3(&answer, r);
            Ok::<(), LookupError>(())
        },
        |i, e| row_error(i, &shape, &e.to_string()),
    )
}

/// Rows of one pair from which `rebound_3d` prepares the pair for the table (`Table::prepare`):
/// below, its 2-9 µs would cost more than the 15 ns per row it saves.
const PREPARE_FOR_TABLE_ROWS: usize = 1024;

/// Columns of a 2-D rebound row.
const REBOUND2: [&str; 19] = [
    "v_x",
    "v_z",
    "omega",
    "other_v_x",
    "other_v_z",
    "other_omega",
    "gamma",
    "alpha",
    "p",
    "e_t",
    "slip_before",
    "slip_after",
    "tangential_impulse",
    "normal_impulse",
    "e_n",
    "incidence_angle",
    "rebound_angle_centre",
    "rebound_angle_contact",
    "energy_lost",
];

fn write2(a: &Answer<Rebound>, r: &mut [f64]) {
    let b = &a.rebound;
    let o = b.other.unwrap_or(State {
        v_x: f64::NAN,
        v_z: f64::NAN,
        omega: f64::NAN,
    });
    r.copy_from_slice(&[
        b.sphere.v_x,
        b.sphere.v_z,
        b.sphere.omega,
        o.v_x,
        o.v_z,
        o.omega,
        a.gamma,
        a.alpha,
        b.p,
        b.e_t,
        b.slip_before,
        b.slip_after,
        b.tangential_impulse,
        b.normal_impulse,
        b.e_n,
        b.incidence_angle,
        b.rebound_angle_centre,
        b.rebound_angle_contact,
        b.energy_lost,
    ]);
}

/// The 2-D incident states: `(v_x, v_z, ω)` of sphere 1, then of sphere 2.
fn states<'a>(
    rows: usize,
    motion: &'a [PyReadonlyArray1<'_, f64>],
) -> PyResult<impl Fn(usize) -> Incident + Sync + 'a> {
    const NAMES: [&str; 6] = [
        "v_x",
        "v_z",
        "omega",
        "other_v_x",
        "other_v_z",
        "other_omega",
    ];
    if motion.len() != 6 {
        return Err(PyValueError::new_err("motion: expected six columns"));
    }
    let c: Vec<Col<'a>> = NAMES
        .iter()
        .zip(motion)
        .map(|(name, a)| Col::new(name, a, 1, rows))
        .collect::<PyResult<_>>()?;
    Ok(move |i: usize| Incident {
        sphere: State {
            v_x: c[0].at(i),
            v_z: c[1].at(i),
            omega: c[2].at(i),
        },
        other: State {
            v_x: c[3].at(i),
            v_z: c[4].at(i),
            omega: c[5].at(i),
        },
    })
}

/// 2-D rebounds (in the plane of impact) of `rows` impacts; returns `(rows, len(REBOUND2))`.
#[pyfunction]
#[pyo3(signature = (table, rows, shape, motion, sphere, other, gamma, materials, friction, e_n, clamp))]
#[allow(clippy::too_many_arguments)]
fn rebound_2d<'py>(
    py: Python<'py>,
    table: &PyTable,
    rows: usize,
    shape: Vec<usize>,
    motion: Vec<PyReadonlyArray1<'_, f64>>,
    sphere: Vec<PyReadonlyArray1<'_, f64>>,
    other: Vec<PyReadonlyArray1<'_, f64>>,
    gamma: Option<PyReadonlyArray1<'_, f64>>,
    materials: Vec<PyReadonlyArray1<'_, f64>>,
    friction: PyReadonlyArray1<'_, f64>,
    e_n: PyReadonlyArray1<'_, f64>,
    clamp: bool,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let s = setup(
        rows,
        &sphere,
        &other,
        &gamma,
        &materials,
        &friction,
        Some(&e_n),
        clamp,
    )?;
    let incident = states(rows, &motion)?;
    let t = &table.inner;
    // One e_n for every row: check it once (no index), else row by row.
    let each_e_n = !s.restitution.shared();
    if !each_e_n {
        s.check_restitution(t, 0)
            .map_err(|e| lookup_error(e, &[]))?;
    }
    new_rows(
        py,
        rows,
        REBOUND2.len(),
        CHUNK,
        |i, r| {
            if each_e_n {
                s.check_restitution(t, i)?;
            }
            write2(&t.rebound(&s.pair(i), &s.contact(i), &incident(i))?, r);
            Ok::<(), LookupError>(())
        },
        |i, e| row_error(i, &shape, &e.to_string()),
    )
}

/// Columns of a groups row.
const GROUPS: [&str; 9] = [
    "gamma",
    "alpha",
    "e_star",
    "g_star",
    "normal_mass",
    "tangential_mass",
    "radius",
    "approach_speed",
    "slip_velocity",
];

/// A row of [`GROUPS`].
fn groups_row(g: &Groups) -> [f64; 9] {
    [
        g.gamma,
        g.alpha,
        g.e_star,
        g.g_star,
        g.normal_mass,
        g.tangential_mass,
        g.radius,
        g.approach_speed,
        g.slip_velocity,
    ]
}

/// The impact in physical units of row `i`.
fn physical(s: &Setup<'_>, incident: &Incident, i: usize) -> PhysicalImpact {
    let materials = match s.stiffness.at(i) {
        Stiffness::Materials(a, b) => [a, b],
        // `physical_*` callers always pass materials.
        Stiffness::Gamma(_) => [Elastic::RIGID; 2],
    };
    PhysicalImpact {
        pair: s.pair(i),
        materials,
        incident: *incident,
        friction: s.friction.at(i),
        law: Default::default(),
    }
}

/// `γ`, `α` and the effective quantities of `rows` 2-D impacts; returns `(rows, len(GROUPS))`.
#[pyfunction]
#[pyo3(signature = (rows, shape, motion, sphere, other, materials, friction))]
#[allow(clippy::too_many_arguments)]
fn groups<'py>(
    py: Python<'py>,
    rows: usize,
    shape: Vec<usize>,
    motion: Vec<PyReadonlyArray1<'_, f64>>,
    sphere: Vec<PyReadonlyArray1<'_, f64>>,
    other: Vec<PyReadonlyArray1<'_, f64>>,
    materials: Vec<PyReadonlyArray1<'_, f64>>,
    friction: PyReadonlyArray1<'_, f64>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let s = setup(
        rows, &sphere, &other, &None, &materials, &friction, None, false,
    )?;
    let incident = states(rows, &motion)?;
    new_rows(
        py,
        rows,
        GROUPS.len(),
        CHUNK,
        |i, r| {
            r.copy_from_slice(&groups_row(&physical(&s, &incident(i), i).groups()?));
            Ok::<(), PhysicsError>(())
        },
        |i, e| physics_error(e, i, &shape),
    )
}

/// Columns of an impact row: the law's parameters ([`PARAMETER_KEYS`]) last.
const IMPACT: [&str; 7] = [
    "p",
    "error_estimate",
    "closed_form",
    "springs",
    "steps",
    "e_n",
    "tau",
];

/// `P(γ, α, e_n)` simulated to `tol` (or in closed form) for every row, with the law `law`
/// (`None`: elastic at e_n = 1, Kelvin–Voigt below); returns `(rows, 7)`.
#[pyfunction]
#[pyo3(signature = (gamma, alpha, e_n, rows, shape, tol, simulate, law))]
#[allow(clippy::too_many_arguments)]
fn impact<'py>(
    py: Python<'py>,
    gamma: PyReadonlyArray1<'_, f64>,
    alpha: PyReadonlyArray1<'_, f64>,
    e_n: PyReadonlyArray1<'_, f64>,
    rows: usize,
    shape: Vec<usize>,
    tol: f64,
    simulate: bool,
    law: Option<&str>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let (g, a, e) = (
        Col::new("gamma", &gamma, 1, rows)?,
        Col::new("alpha", &alpha, 1, rows)?,
        Col::new("e_n", &e_n, 1, rows)?,
    );
    let law = law
        .map(Law::from_name)
        .transpose()
        .map_err(|err| PyValueError::new_err(format!("law: {err}")))?;
    // One simulation takes 0.05-5 ms (up to 0.1 s at tol 1e-8): parallel over single rows, in
    // waves that let Ctrl-C through.
    new_rows_interruptible(
        py,
        rows,
        IMPACT.len(),
        |i, r| {
            let req = Request::new(g.at(i), a.at(i))
                .e_n(e.at(i))
                .accuracy(Accuracy::Tolerance(tol))
                .forced(simulate);
            let req = match law {
                Some(l) => req.law(l),
                None => req,
            };
            let s = req.solve()?;
            let head = [
                s.p,
                s.error_estimate,
                f64::from(u8::from(s.method == Method::ClosedForm)),
                s.resolution.springs as f64,
                s.resolution.steps as f64,
                s.e_n,
            ];
            // The law's parameters (`tau`) last, through the law.
            let (front, back) = r.split_at_mut(head.len());
            front.copy_from_slice(&head);
            back.copy_from_slice(&s.law.values());
            Ok::<(), PhysicsError>(())
        },
        |i, e| physics_error(e, i, &shape),
    )
}

/// One impact in physical units, simulated to `tol` (2-D, in its plane). Returns a dict.
#[pyfunction]
#[pyo3(signature = (motion, sphere, other, materials, friction, tol, relaxation_time))]
#[allow(clippy::too_many_arguments)]
fn simulate<'py>(
    py: Python<'py>,
    motion: Vec<PyReadonlyArray1<'_, f64>>,
    sphere: Vec<PyReadonlyArray1<'_, f64>>,
    other: Vec<PyReadonlyArray1<'_, f64>>,
    materials: Vec<PyReadonlyArray1<'_, f64>>,
    friction: PyReadonlyArray1<'_, f64>,
    tol: f64,
    relaxation_time: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let s = setup(
        1, &sphere, &other, &None, &materials, &friction, None, false,
    )?;
    let incident = states(1, &motion)?;
    let imp = physical(&s, &incident(0), 0).with_relaxation_time(relaxation_time);
    let out = py
        .detach(|| imp.solve(tol))
        .map_err(|e| physics_error(e, 0, &[]))?;
    let d = PyDict::new(py);
    let st = |s: &State| (s.v_x, s.v_z, s.omega);
    d.set_item("sphere", st(&out.sphere))?;
    d.set_item("other", out.other.as_ref().map(st))?;
    d.set_item("p", out.p.unwrap_or(f64::NAN))?;
    d.set_item("error_estimate", out.error_estimate)?;
    d.set_item("contact_time", out.contact_time)?;
    d.set_item("peak_force", out.peak_force)?;
    d.set_item("max_indentation", out.max_indentation)?;
    d.set_item("e_n", out.e_n)?;
    for (key, value) in PARAMETER_KEYS.into_iter().zip(out.law.values()) {
        d.set_item(key, value)?;
    }
    d.set_item("springs", out.resolution.springs)?;
    d.set_item("steps", out.resolution.steps)?;
    d.set_item("groups", groups_row(&out.groups))?;
    Ok(d)
}

/// The material catalogue (`oblique_physics::materials`) as rows `(name, E (Pa), nu, density
/// (kg/m³) or None, source)`, in catalogue order.
fn material_rows() -> Vec<(&'static str, f64, f64, Option<f64>, &'static str)> {
    oblique_physics::materials::CATALOGUE
        .iter()
        .map(|m| {
            (
                m.name,
                m.youngs_modulus,
                m.poisson_ratio,
                Some(m.density).filter(|d| d.is_finite()),
                m.source,
            )
        })
        .collect()
}

/// The native module.
#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyTable>()?;
    m.add_class::<PyCurve>()?;
    m.add("TableError", m.py().get_type::<TableError>())?;
    m.add("REBOUND3", REBOUND3.to_vec())?;
    m.add("REBOUND2", REBOUND2.to_vec())?;
    m.add("GROUPS", GROUPS.to_vec())?;
    m.add("IMPACT", IMPACT.to_vec())?;
    m.add("VERSION", env!("CARGO_PKG_VERSION"))?;
    m.add("EMBEDDED_TABLE", oblique_lookup::EMBEDDED_TABLE)?;
    m.add("MATERIALS", material_rows())?;
    m.add_function(wrap_pyfunction!(regime_into, m)?)?;
    m.add_function(wrap_pyfunction!(critical_into, m)?)?;
    m.add_function(wrap_pyfunction!(e_t_into, m)?)?;
    m.add_function(wrap_pyfunction!(rebound_3d, m)?)?;
    m.add_function(wrap_pyfunction!(rebound_2d, m)?)?;
    m.add_function(wrap_pyfunction!(groups, m)?)?;
    m.add_function(wrap_pyfunction!(impact, m)?)?;
    m.add_function(wrap_pyfunction!(simulate, m)?)?;
    m.add_function(wrap_pyfunction!(build::build_table, m)?)?;
    Ok(())
}
