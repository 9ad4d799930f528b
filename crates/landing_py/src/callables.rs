//! Python callables as the core's external law and plant (`landing_core::external`): the
//! arrays handed to them at every call, and the checks of what they return.

use numpy::{PyArray2, PyArrayMethods, PyReadonlyArray2, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyTuple;

use landing_core::external::{ExternalLaw, ExternalPlant, Inputs, Staging, StateLayout};

use crate::errors::invalid;

/// Frees one 8 MB block from the C heap, once per process, before the first run of a Python
/// callee. glibc's `malloc` serves blocks above its mmap threshold with fresh mappings and
/// returns a heap's top to the system when more than its trim threshold is free there; both
/// start low (128 and 256 kB) and rise only when a mapped block is freed, to its size and
/// twice that (mallopt(3), "dynamic mmap threshold"). Until then a Python law's numpy
/// temporaries (about 100 kB each for 4096 cases of three axes) had their pages returned and
/// faulted in again at every call: a process's first run of the fixed-time MSS law in numpy,
/// 10^4 Mars cases, took 2.8 times as long as its next on one thread (BENCHMARKS.md). Freeing
/// this block raises the thresholds as any large array freed would (to 8 and 16 MB), at once.
/// Where `MALLOC_TRIM_THRESHOLD_` or `MALLOC_MMAP_THRESHOLD_` is set (Dask sets the first, to
/// 64 kB, for its workers), glibc keeps the values given and this changes nothing; other C
/// libraries do not adjust thresholds this way, and there it is one allocation.
fn raise_malloc_thresholds() {
    use std::alloc::{GlobalAlloc, Layout, System};
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        let layout = Layout::from_size_align(8 << 20, 16).expect("a valid layout");
        // SAFETY: a non-zero size; the block is freed with the layout it was allocated with
        // (`System` is the C library's malloc and free, which numpy's arrays use too)
        unsafe {
            let block = std::hint::black_box(System.alloc(layout));
            if !block.is_null() {
                System.dealloc(block, layout);
            }
        }
    });
}

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
            raise_malloc_thresholds();
            let gil = unsafe { pyo3::ffi::PyGILState_Ensure() };
            self.thread = Some((gil, unsafe { pyo3::ffi::PyEval_SaveThread() } as usize));
        } else if let Some((gil, saved)) = self.thread.take() {
            unsafe { pyo3::ffi::PyEval_RestoreThread(saved as *mut pyo3::ffi::PyThreadState) };
            unsafe { pyo3::ffi::PyGILState_Release(gil) };
        }
    }

    /// Slot `slot`'s array, of shape (n, width), read-only to Python, only this slot's: kept,
    /// or new when the callee kept the one before (its count is more than one: the new one is a
    /// copy, so that memory lent to a driver still holds the last call's inputs, [`Staging`]) or
    /// the shape changed (zeros).
    fn slot<'py>(
        &mut self,
        py: Python<'py>,
        slot: usize,
        n: usize,
        width: usize,
    ) -> Bound<'py, PyArray2<f64>> {
        if self.slots.len() <= slot {
            self.slots.resize_with(slot + 1, || None);
        }
        let held = &mut self.slots[slot];
        // SAFETY: a plain reference count read of a live object, with the GIL held
        let ours = |a: &Py<PyArray2<f64>>| unsafe { pyo3::ffi::Py_REFCNT(a.as_ptr()) } == 1;
        let fresh = match held.as_ref() {
            Some(a) if a.bind(py).shape() == [n, width] => (!ours(a)).then(|| {
                let kept = a.bind(py);
                let copy = PyArray2::<f64>::zeros(py, [n, width], false);
                // SAFETY: both C-contiguous (n, width) float64 arrays (the slot's arrays are
                // made here); the new one is not yet seen by any Python code
                unsafe { std::ptr::copy_nonoverlapping(kept.data(), copy.data(), n * width) };
                copy
            }),
            _ => Some(PyArray2::zeros(py, [n, width], false)),
        };
        if let Some(a) = fresh {
            // read-only for Python, once here rather than by the Python layer at every call
            // (seven `setflags` took 1.2 of a call's 3.5 us of overhead): the core writes
            // through the data pointer, which the flag does not guard
            // SAFETY: a live array made just above, that no Python code has seen yet
            unsafe { (*a.as_array_ptr()).flags &= !numpy::npyffi::NPY_ARRAY_WRITEABLE };
            *held = Some(a.unbind());
        }
        held.as_ref().expect("set above").bind(py).clone()
    }

    /// Slot `slot`'s array, holding `values` (`n x width`, row-major).
    fn array<'py>(
        &mut self,
        py: Python<'py>,
        slot: usize,
        values: &[f64],
        n: usize,
    ) -> Bound<'py, PyAny> {
        let a = self.slot(py, slot, n, values.len() / n);
        // SAFETY: a C-contiguous (n, width) float64 array that only this slot holds (its count
        // is one, or it was just made), so no Python code sees the write; numpy's read-only
        // flag (`slot`) guards Python's writes, not this one
        unsafe { std::ptr::copy_nonoverlapping(values.as_ptr(), a.data(), values.len()) };
        a.into_any()
    }

    /// Lends slots `first ..` (each `n x width`) as a driver's [`Staging`]: until the next call
    /// that hands them over, only the slots hold them. They hold what the last call handed over.
    fn lend(&mut self, py: Python<'_>, first: usize, n: usize, width: usize) -> Staging {
        let fields = std::array::from_fn(|j| self.slot(py, first + j, n, width).data());
        // SAFETY: each array holds n x width float64 values and only its slot holds it (`slot`);
        // nothing here touches the slots again before `call` hands them over
        unsafe { Staging::new(fields, n * width) }
    }

    /// Calls `f(*head, *arrays)`, the arrays in slots `first ..` (each `n` rows): `Ok` the
    /// values copied into them, `Err((count, width))` the `count` arrays as the driver staged
    /// them (`lend`).
    fn call<'py>(
        &mut self,
        f: &Bound<'py, PyAny>,
        head: Vec<Bound<'py, PyAny>>,
        arrays: Result<&[&[f64]], (usize, usize)>,
        first: usize,
        n: usize,
    ) -> PyResult<Bound<'py, PyAny>> {
        let py = f.py();
        let mut items = head;
        match arrays {
            Ok(arrays) => {
                for (j, a) in arrays.iter().enumerate() {
                    items.push(self.array(py, first + j, a, n));
                }
            }
            // staged: the lent arrays, as `lend` left them
            Err((count, width)) => {
                for j in 0..count {
                    items.push(self.slot(py, first + j, n, width).into_any());
                }
            }
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

/// A Python callable as the core's [`ExternalLaw`]: `step(t, k, first, track, e, de, position,
/// velocity, acceleration, drift, inertia)`, the arrays (m, D) float64 for the m cases from row
/// `first` on (at most `per_call`; `track`: [`Inputs::track`]), returns `(command, diagnostics)`, C-contiguous float64 (m, D)
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

    fn staging(&mut self, track: usize, cases: usize) -> Option<Staging> {
        Some(Python::attach(|py| {
            self.handed.lend(py, 7 * track, cases, D)
        }))
    }

    fn command(&mut self, i: &Inputs<D>, u: &mut [f64], diagnostics: &mut [f64]) -> PyResult<()> {
        Python::attach(|py| {
            let head = (i.t, i.k, i.first, i.track)
                .into_pyobject(py)?
                .into_iter()
                .collect();
            let (m, fields) = (i.cases(), i.fields());
            // each track's arrays in slots of its own: the two slices' sizes may differ
            let slots = i.track * fields.len();
            let arrays = if i.staged {
                Err((fields.len(), D))
            } else {
                Ok(&fields[..])
            };
            let out = self
                .handed
                .call(self.step.bind(py), head, arrays, slots, m)?;
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
            let r = self
                .handed
                .call(f.bind(py), head, Ok(args), 2 * i, self.n)?;
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
