//! `oblique._native`: the Rust side of the Python package `oblique`.
//!
//! Flat functions over contiguous one-dimensional float64 arrays; the Python layer
//! (`python/oblique/__init__.py`) converts, broadcasts and reshapes, and gives the public API
//! its names and documentation. A column here is the data of one argument: length 1 (the same
//! value for every row) or the number of rows (`3 ×` that for a vector), read as an
//! `oblique_lookup::columns::Column`; the batches, their row loops and the layout of a
//! rebound's row are those of `oblique_lookup::columns`. Every loop over rows runs with the GIL
//! released, in parallel on rayon's pool for large inputs, and stops at the first invalid row;
//! the error names the row by its index in the broadcast shape.
//!
//! `build_table` ([`build`]) builds a table from a config, as `sweep run` does.
//!
//! Symbols and units are those of `physics.md` and `oblique_physics::rebound` (SI).

use numpy::{PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadwriteArray1};
use pyo3::create_exception;
use pyo3::exceptions::{PyOSError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;

use oblique_lookup::columns::{
    self, BodyColumns, Column, ColumnError, ElasticColumns, Motions, PairColumns, PlaneColumns,
    PointColumns, ReboundColumns, SpaceColumns, StiffnessColumns,
};
use oblique_lookup::rebound::{Elastic, Incident, State};
use oblique_lookup::{LookupError, OutOfDomain, Stiffness};
use oblique_physics::regimes::{self, Regime};
use oblique_solver::thornton;
use oblique_solver::units::{Groups, PhysicalImpact};
use oblique_solver::{Accuracy, BodiesLaw, Law, Method, PhysicsError, Request, PARAMETER_KEYS};

mod build;

create_exception!(
    oblique,
    TableError,
    PyOSError,
    "A file that is not a readable, valid P table (damaged, truncated, not a table, a newer \
     schema). The message names the file and the problem."
);

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

/// `row(i, row i of out)` for every row of `width` values, GIL released, in parallel for many
/// rows (`columns::fill_rows_par`); the error of the lowest failing row.
fn fill_rows<E: Send>(
    py: Python<'_>,
    out: &mut [f64],
    width: usize,
    row: impl Fn(usize, &mut [f64]) -> Result<(), E> + Sync + Send,
) -> Result<(), (usize, E)> {
    py.detach(|| columns::fill_rows_par(out, width, row))
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
    row: impl Fn(usize, &mut [f64]) -> Result<(), E> + Sync + Send,
    error: impl FnOnce(usize, E) -> PyErr,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    new_array(py, rows, width, |o| {
        fill_rows(py, o, width, row).map_err(|(i, e)| error(i, e))
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

/// The argument `name` as a column of one number per row (or one for every row).
fn column<'a>(name: &'static str, a: &'a PyReadonlyArray1<'_, f64>) -> PyResult<Column<'a>> {
    Ok(Column::scalar(name, slice(name, a)?))
}

/// The argument `name` as a column of 3-vectors.
fn vector<'a>(name: &'static str, a: &'a PyReadonlyArray1<'_, f64>) -> PyResult<Column<'a>> {
    Ok(Column::vector(name, slice(name, a)?))
}

/// Columns that do not broadcast, as a `ValueError` naming one and both lengths.
fn column_error(e: ColumnError) -> PyErr {
    PyValueError::new_err(e.to_string())
}

/// `Ok` when every column has one row or `rows`.
fn check_rows<'a>(cols: impl IntoIterator<Item = Column<'a>>, rows: usize) -> PyResult<()> {
    columns::check_rows(cols, rows).map_err(column_error)
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
        out: PyReadwriteArray1<'_, f64>,
        clamp: bool,
        shape: Vec<usize>,
    ) -> PyResult<()> {
        let points = PointColumns::new(column("gamma", &gamma)?, column("alpha", &alpha)?, None);
        self.p_columns(py, points, out, clamp, &shape)
    }

    /// The names of the axes of a point of this table: `gamma`, `alpha`, then its extra axes.
    fn axes(&self) -> Vec<&'static str> {
        self.inner.axes()
    }

    /// `P` at `γ`, `α` and the extra axes `names` at `values` (an axis not named at its
    /// fixed value).
    fn p_axes(
        &self,
        gamma: f64,
        alpha: f64,
        names: Vec<String>,
        values: Vec<f64>,
        clamp: bool,
    ) -> PyResult<f64> {
        let extra: Vec<(&str, f64)> = names.iter().map(String::as_str).zip(values).collect();
        self.inner
            .p_axes_with(gamma, alpha, &extra, outside(clamp))
            .map_err(|e| lookup_error(e, &[]))
    }

    /// `out[i] = P(gamma[i], alpha[i], columns[k][i] for the axes names[k])`; `shape` names a
    /// failing index.
    #[allow(clippy::too_many_arguments)]
    fn p_axes_into(
        &self,
        py: Python<'_>,
        gamma: PyReadonlyArray1<'_, f64>,
        alpha: PyReadonlyArray1<'_, f64>,
        names: Vec<String>,
        columns: Vec<PyReadonlyArray1<'_, f64>>,
        out: PyReadwriteArray1<'_, f64>,
        clamp: bool,
        shape: Vec<usize>,
    ) -> PyResult<()> {
        let (g, a) = (column("gamma", &gamma)?, column("alpha", &alpha)?);
        let extra = names
            .iter()
            .zip(&columns)
            .map(|(n, c)| match oblique_lookup::ExtraAxis::named(n) {
                Some(axis) => column(axis.name, c),
                None => Err(lookup_error(oblique_lookup::axis_error(n), &[])),
            })
            .collect::<PyResult<Vec<_>>>()?;
        let points = PointColumns::with_axes(g, a, &extra);
        self.p_columns(py, points, out, clamp, &shape)
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
        // The range of every extra axis (its fixed value at both ends where the table has no
        // such axis: e_n in [1, 1] for an elastic table) and the law of the node values.
        for a in oblique_lookup::EXTRA_AXES {
            let (lo, hi) = t.axis_range(a.name).unwrap_or((a.fixed, a.fixed));
            d.set_item(a.attr_min, lo)?;
            d.set_item(a.attr_max, hi)?;
        }
        d.set_item(
            "law",
            if s.restitution().is_some() {
                p.law.as_str()
            } else {
                "elastic"
            },
        )?;
        // How the e_n axis maps to its coordinate ("e_n" linear, "(1-e_n)^(1/4)"), None for an
        // elastic table.
        d.set_item(
            "e_n_coordinate",
            s.restitution().map(|_| s.e_n_map().name()),
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

impl PyTable {
    /// `P` of every row of `points` into `out` (`Table::p_columns_par`), GIL released.
    fn p_columns(
        &self,
        py: Python<'_>,
        points: Result<PointColumns<'_>, ColumnError>,
        mut out: PyReadwriteArray1<'_, f64>,
        clamp: bool,
        shape: &[usize],
    ) -> PyResult<()> {
        let points = points.map_err(column_error)?;
        let o = slice_mut("out", &mut out)?;
        let t = &self.inner;
        py.detach(|| t.p_columns_par(&points, o, outside(clamp)))
            .map_err(|e| lookup_error(e, shape))
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
        let a = column("alpha", &alpha)?;
        let o = slice_mut("out", &mut out)?;
        check_rows([a], o.len())?;
        let c = &self.inner;
        fill_rows(py, o, 1, |i, r| {
            r[0] = c.p(a.at(i))?;
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
    let (g, a, e) = (
        column("gamma", &gamma)?,
        column("alpha", &alpha)?,
        column("e_n", &e_n)?,
    );
    let o = slice_mut("out", &mut out)?;
    check_rows([g, a, e], o.len())?;
    fill_rows(py, o, 1, |i, r| {
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
    let (g, e) = (column("gamma", &gamma)?, column("e_n", &e_n)?);
    let o = slice_mut("out", &mut out)?;
    check_rows([g, e], o.len() / 2)?;
    fill_rows(py, o, 2, |i, r| {
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
    let (p, k) = (column("p", &p)?, column("kappa", &kappa)?);
    let o = slice_mut("out", &mut out)?;
    check_rows([p, k], o.len())?;
    fill_rows(py, o, 1, |i, r| {
        r[0] = regimes::centre_restitution(p.at(i), k.at(i))?;
        Ok::<(), oblique_physics::InvalidInput>(())
    })
    .map_err(|(i, e)| row_error(i, &shape, &e.to_string()))
}

/// The body and contact columns (`oblique_lookup::columns::PairColumns`): `sphere` and `other`
/// (empty for a wall) the `mass`, `radius`, `kappa` of each body, `γ` given (`gamma`) or from
/// `materials` (E and ν of both bodies), `e_n` the normal restitution (`None`: 1 for every
/// row).
fn pair_columns<'a>(
    sphere: &'a [PyReadonlyArray1<'_, f64>],
    other: &'a [PyReadonlyArray1<'_, f64>],
    gamma: &'a Option<PyReadonlyArray1<'_, f64>>,
    materials: &'a [PyReadonlyArray1<'_, f64>],
    friction: &'a PyReadonlyArray1<'_, f64>,
    e_n: Option<&'a PyReadonlyArray1<'_, f64>>,
    clamp: bool,
) -> PyResult<PairColumns<'a>> {
    let body = |names: [&'static str; 3], v: &'a [PyReadonlyArray1<'_, f64>]| match v {
        [m, r, k] => Ok(BodyColumns {
            mass: column(names[0], m)?,
            radius: column(names[1], r)?,
            kappa: column(names[2], k)?,
        }),
        _ => Err(PyValueError::new_err(format!(
            "{}: expected mass, radius, kappa",
            names[0]
        ))),
    };
    let stiffness = match (gamma, materials) {
        (Some(g), _) => StiffnessColumns::Gamma(column("gamma", g)?),
        (None, [e1, n1, e2, n2]) => StiffnessColumns::Materials(
            ElasticColumns {
                youngs_modulus: column("youngs_modulus", e1)?,
                poisson_ratio: column("poisson_ratio", n1)?,
            },
            ElasticColumns {
                youngs_modulus: column("other youngs_modulus", e2)?,
                poisson_ratio: column("other poisson_ratio", n2)?,
            },
        ),
        (None, _) => {
            return Err(PyValueError::new_err(
                "materials: expected E and nu of both bodies",
            ))
        }
    };
    Ok(PairColumns {
        sphere: body(["mass", "radius", "kappa"], sphere)?,
        other: if other.is_empty() {
            None
        } else {
            Some(body(["other mass", "other radius", "other kappa"], other)?)
        },
        stiffness,
        friction: column("friction", friction)?,
        restitution: match e_n {
            Some(e) => column("e_n", e)?,
            None => Column::scalar("e_n", &[1.0]),
        },
        outside: outside(clamp),
    })
}

/// The 2-D incident states: `(v_x, v_z, ω)` of sphere 1, then of sphere 2.
fn plane_columns<'a>(motion: &'a [PyReadonlyArray1<'_, f64>]) -> PyResult<PlaneColumns<'a>> {
    let [v_x, v_z, omega, ov_x, ov_z, oomega] = motion else {
        return Err(PyValueError::new_err("motion: expected six columns"));
    };
    Ok(PlaneColumns {
        v_x: column("v_x", v_x)?,
        v_z: column("v_z", v_z)?,
        omega: column("omega", omega)?,
        other_v_x: column("other_v_x", ov_x)?,
        other_v_z: column("other_v_z", ov_z)?,
        other_omega: column("other_omega", oomega)?,
    })
}

/// The rebounds of `rows` impacts (`Table::rebound_columns_par`, GIL released): an array of
/// `(rows, len(M::COLUMNS))`; `shape` names a failing row.
fn rebounds<'py, M: Motions>(
    py: Python<'py>,
    table: &PyTable,
    rows: usize,
    shape: &[usize],
    pairs: PairColumns<'_>,
    motions: M,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let batch = ReboundColumns::new(pairs, motions).map_err(column_error)?;
    let t = &table.inner;
    new_array(py, rows, M::COLUMNS.len(), |o| {
        py.detach(|| t.rebound_columns_par(&batch, o))
            .map_err(|e| lookup_error(e, shape))
    })
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
    let pairs = pair_columns(
        &sphere,
        &other,
        &gamma,
        &materials,
        &friction,
        Some(&e_n),
        clamp,
    )?;
    let motions = SpaceColumns {
        velocity: vector("velocity", &velocity)?,
        spin: vector("spin", &spin)?,
        other_velocity: vector("other_velocity", &other_velocity)?,
        other_spin: vector("other_spin", &other_spin)?,
        normal: vector("normal", &normal)?,
    };
    rebounds(py, table, rows, &shape, pairs, motions)
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
    let pairs = pair_columns(
        &sphere,
        &other,
        &gamma,
        &materials,
        &friction,
        Some(&e_n),
        clamp,
    )?;
    rebounds(py, table, rows, &shape, pairs, plane_columns(&motion)?)
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
fn physical(pairs: &PairColumns<'_>, incident: Incident, i: usize) -> PhysicalImpact {
    let contact = pairs.contact(i);
    let materials = match contact.stiffness {
        Stiffness::Materials(a, b) => [a, b],
        // `physical_*` callers always pass materials.
        Stiffness::Gamma(_) => [Elastic::RIGID; 2],
    };
    PhysicalImpact {
        pair: pairs.pair(i),
        materials,
        incident,
        friction: contact.friction,
        law: Default::default(),
    }
}

/// The bodies, materials and incident states of `rows` 2-D impacts in physical units, each
/// column of one row or `rows`.
fn physical_columns<'a>(
    rows: usize,
    motion: &'a [PyReadonlyArray1<'_, f64>],
    sphere: &'a [PyReadonlyArray1<'_, f64>],
    other: &'a [PyReadonlyArray1<'_, f64>],
    materials: &'a [PyReadonlyArray1<'_, f64>],
    friction: &'a PyReadonlyArray1<'_, f64>,
) -> PyResult<(PairColumns<'a>, PlaneColumns<'a>)> {
    let pairs = pair_columns(sphere, other, &None, materials, friction, None, false)?;
    let states = plane_columns(motion)?;
    check_rows(pairs.columns().into_iter().chain(states.columns()), rows)?;
    Ok((pairs, states))
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
    let (pairs, states) = physical_columns(rows, &motion, &sphere, &other, &materials, &friction)?;
    new_rows(
        py,
        rows,
        GROUPS.len(),
        |i, r| {
            r.copy_from_slice(&groups_row(
                &physical(&pairs, states.incident(i), i).groups()?,
            ));
            Ok::<(), PhysicsError>(())
        },
        |i, e| physics_error(e, i, &shape),
    )
}

/// Columns of an impact row before the law's parameters.
const IMPACT_HEAD: [&str; 6] = [
    "p",
    "error_estimate",
    "closed_form",
    "springs",
    "steps",
    "e_n",
];

/// Columns of an impact row: [`IMPACT_HEAD`], then the law's parameters ([`PARAMETER_KEYS`]:
/// `tau`, `yield_pressure`), so that a law added to the solver adds its column here.
const IMPACT: [&str; IMPACT_HEAD.len() + PARAMETER_KEYS.len()] = {
    let mut all = [""; IMPACT_HEAD.len() + PARAMETER_KEYS.len()];
    let mut i = 0;
    while i < IMPACT_HEAD.len() {
        all[i] = IMPACT_HEAD[i];
        i += 1;
    }
    while i < all.len() {
        all[i] = PARAMETER_KEYS[i - IMPACT_HEAD.len()];
        i += 1;
    }
    all
};

/// `P(γ, α, e_n)` simulated to `tol` (or in closed form) for every row, with the law `law`
/// (`None`: elastic at e_n = 1, Kelvin–Voigt below); returns `(rows, len(IMPACT))`.
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
        column("gamma", &gamma)?,
        column("alpha", &alpha)?,
        column("e_n", &e_n)?,
    );
    check_rows([g, a, e], rows)?;
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
            let head: [f64; IMPACT_HEAD.len()] = [
                s.p,
                s.error_estimate,
                f64::from(u8::from(s.method == Method::ClosedForm)),
                s.resolution.springs as f64,
                s.resolution.steps as f64,
                s.e_n,
            ];
            // The law's parameters (`tau`, `yield_pressure`) last, through the law.
            let (front, back) = r.split_at_mut(head.len());
            front.copy_from_slice(&head);
            back.copy_from_slice(&s.law.values());
            Ok::<(), PhysicsError>(())
        },
        |i, e| physics_error(e, i, &shape),
    )
}

/// The bodies' law of `simulate`: Kelvin–Voigt of relaxation time `τ` (s; elastic at 0), or
/// Thornton's of limiting pressure `p_y` (Pa), or elastic where neither is given; not both
/// (each is checked by its law).
fn bodies_law(relaxation_time: Option<f64>, yield_pressure: Option<f64>) -> PyResult<BodiesLaw> {
    match (relaxation_time, yield_pressure) {
        (None, None) => Ok(BodiesLaw::default()),
        (Some(tau), None) => Ok(BodiesLaw::of_relaxation_time(tau)),
        (Some(_), Some(_)) => Err(PyValueError::new_err(
            "relaxation_time and yield_pressure: give one or the other (Kelvin–Voigt bodies \
             or Thornton's elastic–plastic bodies), not both",
        )),
        (None, Some(p)) => Ok(BodiesLaw::Thornton(thornton::BodiesParameters {
            yield_pressure: p,
        })),
    }
}

/// One impact in physical units, simulated to `tol` (2-D, in its plane), with the bodies' law
/// of [`bodies_law`]. Returns a dict.
#[pyfunction]
#[pyo3(signature = (motion, sphere, other, materials, friction, tol, relaxation_time, yield_pressure))]
#[allow(clippy::too_many_arguments)]
fn simulate<'py>(
    py: Python<'py>,
    motion: Vec<PyReadonlyArray1<'_, f64>>,
    sphere: Vec<PyReadonlyArray1<'_, f64>>,
    other: Vec<PyReadonlyArray1<'_, f64>>,
    materials: Vec<PyReadonlyArray1<'_, f64>>,
    friction: PyReadonlyArray1<'_, f64>,
    tol: f64,
    relaxation_time: Option<f64>,
    yield_pressure: Option<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let law = bodies_law(relaxation_time, yield_pressure)?;
    let (pairs, states) = physical_columns(1, &motion, &sphere, &other, &materials, &friction)?;
    let imp = physical(&pairs, states.incident(0), 0).with_law(law);
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
    d.set_item("law", out.law.name())?;
    for (key, value) in PARAMETER_KEYS.into_iter().zip(out.law.values()) {
        d.set_item(key, value)?;
    }
    d.set_item("springs", out.resolution.springs)?;
    d.set_item("steps", out.resolution.steps)?;
    d.set_item("groups", groups_row(&out.groups))?;
    Ok(d)
}

/// One entry of the catalogue for Python: name, E (Pa), ν, density (kg/m³, `None` for the
/// rigid body), source, yield stress `Y` (Pa, `None` without one), limiting pressure
/// `p_y = 1.60 Y` (Pa) and the yield stress's source.
type MaterialRow = (
    &'static str,
    f64,
    f64,
    Option<f64>,
    &'static str,
    Option<f64>,
    Option<f64>,
    &'static str,
);

/// The material catalogue (`oblique_physics::materials`) as rows `(name, E (Pa), nu, density
/// (kg/m³) or None, source)`, in catalogue order.
fn material_rows() -> Vec<MaterialRow> {
    oblique_physics::materials::CATALOGUE
        .iter()
        .map(|m| {
            (
                m.name,
                m.youngs_modulus,
                m.poisson_ratio,
                Some(m.density).filter(|d| d.is_finite()),
                m.source,
                m.yield_stress,
                m.limiting_pressure(),
                m.yield_source,
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
    m.add("REBOUND3", columns::REBOUND_3D_COLUMNS.to_vec())?;
    // The axes a table may have beyond gamma and alpha, and the value of each where a table
    // lacks it.
    let extra: Vec<(&str, f64)> = oblique_lookup::EXTRA_AXES
        .iter()
        .map(|a| (a.name, a.fixed))
        .collect();
    m.add("EXTRA_AXES", extra)?;
    m.add("REBOUND2", columns::REBOUND_COLUMNS.to_vec())?;
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
