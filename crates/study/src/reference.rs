//! Exact references for the single-impact tests DEM codes verify their contact models against:
//! Chung & Ooi (2011) tests 1–8, MFIX's DEM05 (Kharaz, Gorham & Salman 2001), Thornton's
//! normalised diagrams, and seed 000's Fig. 5.
//!
//! Each test ([`spec`]) is computed ([`eval`]) by the universal mapping and `P(γ, α)` (a
//! dimensionless simulation of each point, or a table), or by direct two-body simulation in SI
//! units; the quantities each suite reports ([`columns`]) come with their error bounds, and the
//! closed forms ([`checks`]) are computed beside them. [`output`] writes the CSVs and figures.
//! Nothing here prints; `sweep reference` is the front end.

pub mod checks;
pub mod columns;
pub mod eval;
pub mod measured;
pub mod output;
pub mod spec;

use std::time::Instant;

use thiserror::Error;

pub use checks::Check;
pub use eval::{Method, NormalOutcome, ObliqueResult};
pub use spec::{Suite, Test};

/// Errors of computing or writing a reference.
#[derive(Debug, Error)]
pub enum ReferenceError {
    /// An impact could not be simulated.
    #[error(transparent)]
    Physics(#[from] oblique_solver::PhysicsError),
    /// An input of the rebound algebra is out of range.
    #[error(transparent)]
    Input(#[from] oblique_lookup::rebound::InvalidInput),
    /// A table lookup failed.
    #[error(transparent)]
    Lookup(#[from] oblique_lookup::LookupError),
    /// A figure could not be drawn.
    #[error(transparent)]
    Plot(#[from] oblique_plot::PlotError),
    /// A file could not be written.
    #[error("{path}: {message}")]
    Io {
        /// File path.
        path: String,
        /// What went wrong.
        message: String,
    },
}

impl ReferenceError {
    /// Whether a different argument would avoid it (a tolerance the solver refuses, a table
    /// that does not cover a test, an output format).
    pub fn user_can_fix(&self) -> bool {
        match self {
            ReferenceError::Physics(e) => e.user_can_fix(),
            ReferenceError::Input(_) => false,
            ReferenceError::Lookup(e) => e.user_can_fix(),
            ReferenceError::Plot(e) => e.user_can_fix(),
            ReferenceError::Io { .. } => false,
        }
    }
}

/// A computed test.
#[derive(Debug, Clone, PartialEq)]
pub enum TestResult {
    /// A normal test and its outcomes per setup.
    Normal(spec::NormalTest, Vec<NormalOutcome>),
    /// An oblique test and its outcomes.
    Oblique(spec::ObliqueTest, ObliqueResult),
}

/// A computed suite.
#[derive(Debug, Clone, PartialEq)]
pub struct SuiteResult {
    /// The suite.
    pub suite: Suite,
    /// Its tests, in order.
    pub tests: Vec<TestResult>,
    /// The closed-form checks.
    pub checks: Vec<Check>,
    /// Per test with measured data (by file stem), the measured points against the model.
    pub measured: Vec<(&'static str, Vec<output::MeasuredRow>)>,
    /// How `P` was computed, in words.
    pub method: String,
    /// Wall time (s).
    pub elapsed_s: f64,
}

impl SuiteResult {
    /// Number of impacts computed (cases of every setup of every test).
    pub fn cases(&self) -> usize {
        self.tests
            .iter()
            .map(|t| match t {
                TestResult::Normal(_, o) => o.len(),
                TestResult::Oblique(_, r) => r.setups.iter().map(|(_, o)| o.len()).sum(),
            })
            .sum()
    }
}

/// Compute a suite.
pub fn run(suite: Suite, method: &Method) -> Result<SuiteResult, ReferenceError> {
    let start = Instant::now();
    let mut tests = Vec::new();
    let mut checks = Vec::new();
    let mut setups = Vec::new();
    let mut measured = Vec::new();
    for test in suite.tests() {
        match test {
            Test::Normal(t) => {
                let outs = eval::normal(&t, method)?;
                checks.extend(checks::hertz(t.id, &outs));
                tests.push(TestResult::Normal(t, outs));
            }
            Test::Oblique(t) => {
                let res = eval::oblique(&t, method)?;
                checks.extend(checks::gross_slip(t.id, &res, method)?);
                checks.extend(checks::rolling(t.id, &res));
                checks.extend(checks::plastic_restitution(t.id, &res));
                setups.extend(res.setups.iter().map(|(s, _)| *s));
                if let Some(m) = t.measured {
                    measured.push((t.id, output::measured_rows(&t, m, method)?));
                }
                tests.push(TestResult::Oblique(t, res));
            }
        }
    }
    checks.extend(checks::no_slip(suite.name(), &setups, method)?);
    Ok(SuiteResult {
        suite,
        tests,
        checks,
        measured,
        method: method.describe(),
        elapsed_s: start.elapsed().as_secs_f64(),
    })
}
