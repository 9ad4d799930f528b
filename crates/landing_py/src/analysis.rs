//! Bindings of the core's theory (convergence bounds) and dispersion sampling. Scalar in,
//! scalar out: `landing.theory` broadcasts them over arrays.

use landing_core::rng::philox4x64_10;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyDict};

use landing_core::dispersion::Dispersion as CoreDispersion;
use landing_core::limits::{MAX_CASES, within_cap};
use landing_core::{ParamError, theory};

use crate::errors::{InputError, guard};
use crate::table;

/// Runs a theory formula under [`guard`], its `ParamError` as a `ParameterError`.
fn check<T>(formula: impl FnOnce() -> Result<T, ParamError>) -> PyResult<T> {
    guard(|| Ok(formula().map_err(InputError::from)?))
}

/// Seed 001 Lemma 2 (k = 1) for s' = -c1 sig^e1(s) - c2 sig^e2(s).
#[pyfunction]
pub fn fixed_time_bound(c1: f64, e1: f64, c2: f64, e2: f64) -> PyResult<f64> {
    check(|| theory::fixed_time_bound(c1, e1, c2, e2))
}

/// Seed 001 Theorem 1 (k = 1): time to reach the practical neighbourhood.
#[pyfunction]
pub fn practical_time_bound(c1: f64, e1: f64, c2: f64, e2: f64, theta: f64) -> PyResult<f64> {
    check(|| theory::practical_time_bound(c1, e1, c2, e2, theta))
}

/// Seed 001 eq. 38-39: the practical neighbourhood's radius.
#[pyfunction]
pub fn practical_radius(
    c1: f64,
    e1: f64,
    c2: f64,
    e2: f64,
    d_max: f64,
    theta: f64,
) -> PyResult<f64> {
    check(|| theory::practical_radius(c1, e1, c2, e2, d_max, theta))
}

/// Seed 001 Theorems 2 to 4 for one axis of the fixed-time MSS guidance.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn mss_bounds<'py>(
    py: Python<'py>,
    beta1: f64,
    q1: f64,
    beta2: f64,
    q2: f64,
    alpha1: f64,
    gamma1: f64,
    alpha2: f64,
    gamma2: f64,
    ap_max: f64,
    theta1: f64,
    theta2: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let b = check(|| {
        theory::mss_bounds(
            beta1, q1, beta2, q2, alpha1, gamma1, alpha2, gamma2, ap_max, theta1, theta2,
        )
    })?;
    b.named().into_py_dict(py)
}

/// Seed 001 Remark 1 (sign-consistent): (tf1, tf2) lower bounds on one axis.
#[pyfunction]
pub fn min_final_time(r0: f64, v0: f64, a_max: f64, g: f64) -> PyResult<(f64, f64)> {
    check(|| theory::min_final_time(r0, v0, a_max, g))
}

/// Shortest time to rest at 0 on one axis (time-optimal bang-bang, gravity g).
#[pyfunction]
pub fn min_time_to_rest(r0: f64, v0: f64, a_max: f64, g: f64) -> PyResult<f64> {
    check(|| theory::min_time_to_rest(r0, v0, a_max, g))
}

/// Seed 003 eq. 42 as printed, as a function of Lemma 2's constant c_v (not in the seed).
#[pyfunction]
pub fn fntsmc_ts_printed(c_v: f64, alpha_s: f64, beta_s: f64) -> PyResult<f64> {
    check(|| theory::fntsmc_ts_printed(c_v, alpha_s, beta_s))
}

/// Seed 003 eq. 47 as printed (not a bound for eq. 21's exponents; see the core).
#[pyfunction]
pub fn fntsmc_td_printed(k1: f64, p1: f64, k2: f64, p2: f64, d: f64) -> PyResult<f64> {
    check(|| theory::fntsmc_td_printed(k1, p1, k2, p2, d))
}

/// Sound fixed-time bounds of the seed-003 FNTSMC on one axis.
#[pyfunction]
#[allow(clippy::too_many_arguments)]
pub fn fntsmc_bounds<'py>(
    py: Python<'py>,
    k1: f64,
    p1: f64,
    k2: f64,
    p2: f64,
    k3: f64,
    alpha_s: f64,
    beta_s: f64,
    sigma_phi: f64,
    tol: f64,
    d_max: f64,
    theta: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let b = check(|| {
        theory::fntsmc_bounds(
            k1, p1, k2, p2, k3, alpha_s, beta_s, sigma_phi, tol, d_max, theta,
        )
    })?;
    b.named().into_py_dict(py)
}

/// A compiled dispersion (`landing.dispersions.Dispersion` holds one): independent normal or
/// uniform components, drawn by case from the counter-based generator. Also exported under its
/// former name, `DispersionHandle`.
#[pyclass(frozen, module = "landing._core")]
pub struct Dispersion {
    dispersion: CoreDispersion,
}

#[pymethods]
impl Dispersion {
    #[new]
    fn new(table: &Bound<'_, PyDict>) -> PyResult<Self> {
        guard(|| {
            let t = table::from_py("dispersion", table)?;
            let dispersion = t
                .read_one::<CoreDispersion>()
                .map_err(|e| InputError::from(e).context("dispersion"))?;
            Ok(Self { dispersion })
        })
    }

    /// Number of components.
    #[getter]
    fn dim(&self) -> PyResult<usize> {
        guard(|| Ok(self.dispersion.dim()))
    }

    /// Cases `first_case .. first_case + n`, shape (n, components).
    fn sample<'py>(
        &self,
        py: Python<'py>,
        seed: u64,
        first_case: u64,
        n: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            // `landing.dispersions.Dispersion.sample` has checked the memory it needs
            within_cap("n", n as u64, "max_cases", MAX_CASES).map_err(InputError::from)?;
            if first_case.checked_add(n as u64).is_none() {
                return Err(InputError::value(format!(
                    "first_case = {first_case} violates first_case + n < 2^64 (n = {n})"
                ))
                .into());
            }
            let dim = self.dispersion.dim();
            let d = &self.dispersion;
            let data = py.detach(|| d.sample(seed, first_case, n));
            Ok(PyArray1::from_vec(py, data).reshape([n, dim])?.into_any())
        })
    }
}

/// One Philox4x64-10 block, exposed so the tests can compare with `numpy.random.Philox`.
#[pyfunction]
fn philox4x64(counter: [u64; 4], key: [u64; 2]) -> PyResult<[u64; 4]> {
    guard(|| Ok(philox4x64_10(counter, key)))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(fixed_time_bound, m)?)?;
    m.add_function(wrap_pyfunction!(practical_time_bound, m)?)?;
    m.add_function(wrap_pyfunction!(practical_radius, m)?)?;
    m.add_function(wrap_pyfunction!(mss_bounds, m)?)?;
    m.add_function(wrap_pyfunction!(min_final_time, m)?)?;
    m.add_function(wrap_pyfunction!(min_time_to_rest, m)?)?;
    m.add_function(wrap_pyfunction!(fntsmc_ts_printed, m)?)?;
    m.add_function(wrap_pyfunction!(fntsmc_td_printed, m)?)?;
    m.add_function(wrap_pyfunction!(fntsmc_bounds, m)?)?;
    m.add_function(wrap_pyfunction!(philox4x64, m)?)?;
    m.add_class::<Dispersion>()?;
    m.add("DispersionHandle", m.getattr("Dispersion")?)?;
    Ok(())
}
