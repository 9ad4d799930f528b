//! Python callables as the core's external law and plant (`landing_core::external`): the
//! arrays handed to them at every call, and the checks of what they return.

use numpy::{PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use landing_core::external::{ExternalLaw, ExternalPlant, Inputs, StateLayout};

use crate::errors::invalid;

/// What the binding keeps for a Python callee between calls: the (N, width) arrays handed to
/// it, reused (fresh ones fault their pages in at every call; one the callee kept is replaced);
/// and, between a driver's two `on_thread` calls, the interpreter's record of the pool thread
/// calling it, with the GIL released (each `Python::attach` made and dropped one: 10 us).
#[derive(Default)]
pub struct Handed {
    slots: Vec<Option<Py<PyArray2<f64>>>>,
    thread: Option<(pyo3::ffi::PyGILState_STATE, usize)>,
}

impl Handed {
    // SAFETY (both): the C API's pattern for a foreign thread, register it and release the GIL,
    // then restore and release on the same thread (the drivers make both calls there)
    fn on_thread(&mut self, entering: bool) {
        if entering {
            let gil = unsafe { pyo3::ffi::PyGILState_Ensure() };
            self.thread = Some((gil, unsafe { pyo3::ffi::PyEval_SaveThread() } as usize));
        } else if let Some((gil, saved)) = self.thread.take() {
            unsafe { pyo3::ffi::PyEval_RestoreThread(saved as *mut pyo3::ffi::PyThreadState) };
            unsafe { pyo3::ffi::PyGILState_Release(gil) };
        }
    }

    /// Slot `slot`'s array, holding `values` (`n x width`, row-major).
    fn array<'py>(
        &mut self,
        py: Python<'py>,
        slot: usize,
        values: &[f64],
        n: usize,
    ) -> Bound<'py, PyAny> {
        let width = values.len() / n;
        if self.slots.len() <= slot {
            self.slots.resize_with(slot + 1, || None);
        }
        let held = &mut self.slots[slot];
        // SAFETY: a plain reference count read of a live object, with the GIL held
        let ours = |a: &Py<PyArray2<f64>>| unsafe { pyo3::ffi::Py_REFCNT(a.as_ptr()) } == 1;
        if !held
            .as_ref()
            .is_some_and(|a| ours(a) && a.bind(py).shape() == [n, width])
        {
            *held = Some(PyArray2::zeros(py, [n, width], false).unbind());
        }
        let a = held.as_ref().expect("set above").bind(py);
        // SAFETY: a C-contiguous (n, width) float64 array that only this slot holds (its count
        // is one, or it was just made), so no Python code sees the write; numpy's read-only
        // flag, which the Python layer sets, guards Python's writes, not this one
        unsafe { std::ptr::copy_nonoverlapping(values.as_ptr(), a.data(), values.len()) };
        a.clone().into_any()
    }

    /// Calls `f(*head, *arrays)`, the arrays in slots `first ..` (each `n` rows).
    fn call<'py>(
        &mut self,
        f: &Bound<'py, PyAny>,
        head: Vec<Bound<'py, PyAny>>,
        arrays: &[&[f64]],
        first: usize,
        n: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = f.py();
        let mut items = head;
        for (j, a) in arrays.iter().enumerate() {
            items.push(self.array(py, first + j, a, n));
        }
        f.call1(PyTuple::new(py, items)?)
    }
}

/// Copies a C-contiguous (n, width) array that `who` returned into `into`, or an error naming
/// it: a wrong shape would be read out of bounds.
fn copy_rows(who: &str, a: &PyReadonlyArray2<'_, f64>, n: usize, into: &mut [f64]) -> PyResult<()> {
    let width = into.len() / n;
    if a.shape() != [n, width] {
        invalid!(
            "{who} returned an array of shape {:?}; expected ({n}, {width})",
            a.shape()
        );
    }
    into.copy_from_slice(a.as_slice()?);
    Ok(())
}

/// A Python callable as the core's [`ExternalLaw`]: `step(t, k, first, e, de, position,
/// velocity, acceleration, drift, inertia)`, the arrays (m, D) float64 for the m cases from row
/// `first` on (at most `per_call`), returns `(command, diagnostics)`, C-contiguous float64 (m, D)
/// and (m, width), checked by the Python layer (`landing.controllers.PythonLaw`) and again here.
pub struct PyLaw {
    pub step: Py<PyAny>,
    pub width: usize,
    pub per_call: usize,
    pub handed: Handed,
}

impl<const D: usize> ExternalLaw<D> for PyLaw {
    type Error = PyErr;

    fn diagnostic_width(&self) -> usize {
        self.width
    }

    fn cases_per_call(&self) -> usize {
        self.per_call
    }

    fn on_thread(&mut self, entering: bool) {
        self.handed.on_thread(entering);
    }

    fn command(&mut self, i: &Inputs<D>, u: &mut [f64], diagnostics: &mut [f64]) -> PyResult<()> {
        Python::attach(|py| {
            let head = (i.t, i.k, i.first).into_pyobject(py)?.into_iter().collect();
            let m = i.cases();
            let out = self
                .handed
                .call(self.step.bind(py), head, &i.fields(), 0, m)?;
            let (a, diag): (PyReadonlyArray2<'_, f64>, PyReadonlyArray2<'_, f64>) =
                out.extract()?;
            copy_rows("the Python law's step (command)", &a, m, u)?;
            copy_rows("the Python law's step (diagnostics)", &diag, m, diagnostics)
        })
    }
}

/// A plant written in Python, as the core's [`ExternalPlant`]: `landing.plants.PythonPlant`
/// hands over its hooks `(derivative, model, actuate, in_domain)`, each None but the first when
/// absent, and each called as `f(t, *arrays)` on (N, width) float64 arrays (`derivative(t, x,
/// u)`, `model(t, x)`, `actuate(t, x, a)`, `in_domain(t, x)`) to return one C-contiguous
/// float64 array (N, n_state), (N, 2 D): drifts then inertias, (N, D), (N, 1): 1 inside.
pub struct PyPlant<const D: usize> {
    pub layout: StateLayout<D>,
    pub hooks: [Option<Py<PyAny>>; 4],
    pub n: usize,
    pub handed: Handed,
}

impl<const D: usize> PyPlant<D> {
    /// Hook `i` on `args`, its result into `out` (`n x width`).
    fn call(&mut self, i: usize, t: f64, args: &[&[f64]], out: &mut [f64]) -> PyResult<()> {
        let what = ["derivative", "model", "actuate", "in_domain"][i];
        let Some(f) = &self.hooks[i] else {
            invalid!("the plant has no {what} to call");
        };
        Python::attach(|py| {
            let head = vec![t.into_pyobject(py)?.into_any()];
            // two slots per hook: its arguments after t
            let r = self.handed.call(f.bind(py), head, args, 2 * i, self.n)?;
            copy_rows(&format!("the plant's {what}"), &r.extract()?, self.n, out)
        })
    }
}

impl<const D: usize> ExternalPlant<D> for PyPlant<D> {
    type Error = PyErr;

    fn layout(&self) -> &StateLayout<D> {
        &self.layout
    }

    fn hooks(&self) -> [bool; 3] {
        [1, 2, 3].map(|i| self.hooks[i].is_some())
    }

    fn on_thread(&mut self, entering: bool) {
        self.handed.on_thread(entering);
    }

    fn derivative(&mut self, t: f64, x: &[f64], u: &[f64], xdot: &mut [f64]) -> PyResult<()> {
        self.call(0, t, &[x, u], xdot)
    }

    fn model(&mut self, t: f64, x: &[f64], model: &mut [f64]) -> PyResult<()> {
        self.call(1, t, &[x], model)
    }

    fn actuate(&mut self, t: f64, x: &[f64], a: &[f64], u: &mut [f64]) -> PyResult<()> {
        self.call(2, t, &[x, a], u)
    }

    fn in_domain(&mut self, t: f64, x: &[f64], inside: &mut [f64]) -> PyResult<()> {
        self.call(3, t, &[x], inside)
    }
}
