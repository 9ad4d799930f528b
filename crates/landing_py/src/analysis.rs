//! Bindings of the core's theory (convergence bounds) and dispersion sampling. Scalar in,
//! scalar out: `landing.theory` broadcasts them over arrays.

use landing_core::rng::{philox4x64_10, streams};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{IntoPyDict, PyDict};

use landing_core::dispersion::{Dispersion as CoreDispersion, parameter_stream};
use landing_core::theory;

use crate::errors::{InputError, guard};
use crate::table;

/// A formula's result as Python sees it: a number, a pair, or a bound's named terms (a dict).
trait Answer {
    fn answer(self, py: Python<'_>) -> PyResult<Bound<'_, PyAny>>;
}

/// Numbers and pairs as they are; a bound as the dict of its named terms.
macro_rules! answers {
    ($($number:ty),* ; $($bound:ty),*) => {
        $(impl Answer for $number {
            fn answer(self, py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
                Ok(self.into_pyobject(py)?.into_any())
            }
        })*
        $(impl Answer for $bound {
            fn answer(self, py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
                Ok(self.named().into_py_dict(py)?.into_any())
            }
        })*
    };
}

answers!(f64, (f64, f64); theory::MssBounds, theory::FntsmcBounds);

/// Each formula of `landing_core::theory` listed once: a function of the same name and
/// arguments (all float), its `ParamError` as a `ParameterError`, and its registration.
macro_rules! formulas {
    ($($(#[$doc:meta])* $name:ident($($arg:ident),*);)*) => {
        $(
            $(#[$doc])*
            #[pyfunction]
            #[allow(clippy::too_many_arguments)]
            fn $name(py: Python<'_>, $($arg: f64),*) -> PyResult<Bound<'_, PyAny>> {
                guard(|| theory::$name($($arg),*).map_err(InputError::from)?.answer(py))
            }
        )*

        fn register_formulas(m: &Bound<'_, PyModule>) -> PyResult<()> {
            $(m.add_function(wrap_pyfunction!($name, m)?)?;)*
            Ok(())
        }
    };
}

formulas! {
    /// Seed 001 Lemma 2 (k = 1) for s' = -c1 sig^e1(s) - c2 sig^e2(s).
    fixed_time_bound(c1, e1, c2, e2);
    /// Seed 001 Theorem 1 (k = 1): time to reach the practical neighbourhood.
    practical_time_bound(c1, e1, c2, e2, theta);
    /// Seed 001 eq. 38-39: the practical neighbourhood's radius.
    practical_radius(c1, e1, c2, e2, d_max, theta);
    /// Seed 001 Theorems 2 to 4 for one axis of the fixed-time MSS guidance.
    mss_bounds(beta1, q1, beta2, q2, alpha1, gamma1, alpha2, gamma2, ap_max, theta1, theta2);
    /// Seed 001 Remark 1 (sign-consistent): (tf1, tf2) lower bounds on one axis.
    min_final_time(r0, v0, a_max, g);
    /// Shortest time to rest at 0 on one axis (time-optimal bang-bang, gravity g).
    min_time_to_rest(r0, v0, a_max, g);
    /// Seed 000 eq. 7 (eq. 5 at alpha = 0): time to reach e = 0 on the (fast) terminal surface.
    terminal_reaching_time(e0, alpha, beta, p, q);
    /// Seed 000 eq. 7 (eq. 5 at alpha = 0) as printed: p and q swapped, negative for p < q.
    terminal_reaching_time_printed(e0, alpha, beta, p, q);
    /// Seed 003 eq. 42 as printed, as a function of Lemma 2's constant c_v (not in the seed).
    fntsmc_ts_printed(c_v, alpha_s, beta_s);
    /// Seed 003 eq. 47 as printed (not a bound for eq. 21's exponents; see the core).
    fntsmc_td_printed(k1, p1, k2, p2, d);
    /// Sound fixed-time bounds of the seed-003 FNTSMC on one axis.
    fntsmc_bounds(k1, p1, k2, p2, k3, alpha_s, beta_s, sigma_phi, tol, d_max, theta);
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

    /// Cases `first_case .. first_case + n`, shape (n, components): of the initial states'
    /// stream, or of the stream of the parameter named `key`.
    #[pyo3(signature = (seed, first_case, n, key=None))]
    fn sample<'py>(
        &self,
        py: Python<'py>,
        seed: u64,
        first_case: u64,
        n: usize,
        key: Option<&str>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guard(|| {
            // `landing.dispersions.Dispersion.sample` has checked the memory it needs
            let d = &self.dispersion;
            let stream = key.map_or(streams::DISPERSION, parameter_stream);
            let data = py.detach(|| d.sample_checked(seed, stream, first_case, n));
            let data = data.map_err(InputError::from)?;
            Ok(PyArray1::from_vec(py, data)
                .reshape([n, d.dim()])?
                .into_any())
        })
    }
}

/// One Philox4x64-10 block, exposed so the tests can compare with `numpy.random.Philox`.
#[pyfunction]
fn philox4x64(counter: [u64; 4], key: [u64; 2]) -> PyResult<[u64; 4]> {
    guard(|| Ok(philox4x64_10(counter, key)))
}

pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    register_formulas(m)?;
    m.add_function(wrap_pyfunction!(philox4x64, m)?)?;
    m.add_class::<Dispersion>()?;
    m.add("DispersionHandle", m.getattr("Dispersion")?)?;
    Ok(())
}
