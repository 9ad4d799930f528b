//! A Python dict read once into the core's parameter [`Table`], which the core's models then
//! read (`landing_core::params`).
//!
//! Numbers are float64 arrays (or Python numbers and lists of them); flags, names, nested
//! dicts and lists of dicts keep their meaning; a compiled `FuzzySystem` stays a handle. In a
//! list, an item that is not a dict is shorthand for a table: a `(kind, values)` pair for
//! `{"kind": kind, "values": values}` (a fuzzy set), anything else for `{"values": item}` (a
//! fuzzy rule).

use numpy::{PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use landing_core::params::{Array, Table, Value};

use crate::errors::InputError;

/// The table of `dict`, its errors prefixed with `owner`.
pub fn from_py(owner: &str, dict: &Bound<'_, PyDict>) -> Result<Table, InputError> {
    read_dict(dict).map_err(|e| e.context(owner))
}

fn read_dict(dict: &Bound<'_, PyDict>) -> Result<Table, InputError> {
    let mut entries = Vec::with_capacity(dict.len());
    for (k, v) in dict.iter() {
        let key: String = k
            .extract()
            .map_err(|_| InputError::type_("table keys must be strings"))?;
        let value = value(&key, &v)?;
        entries.push((key, value));
    }
    Ok(Table::new(entries))
}

fn is_number(v: &Bound<'_, PyAny>) -> bool {
    (v.is_instance_of::<PyFloat>() || v.is_instance_of::<PyInt>()) && !v.is_instance_of::<PyBool>()
}

fn value(key: &str, v: &Bound<'_, PyAny>) -> Result<Value, InputError> {
    if v.is_none() {
        return Ok(Value::Absent);
    }
    if let Ok(b) = v.cast::<PyBool>() {
        return Ok(Value::Flag(b.is_true()));
    }
    if let Ok(s) = v.cast::<PyString>() {
        return Ok(Value::Text(s.to_string()));
    }
    if let Ok(d) = v.cast::<PyDict>() {
        return Ok(Value::Table(read_dict(d)?));
    }
    if let Ok(f) = v.cast::<crate::fuzzy::FuzzySystem>() {
        return Ok(Value::Fuzzy(f.get().system.clone()));
    }
    if is_number(v) {
        return numbers(key, vec![v.extract()?], vec![]);
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items: Vec<Bound<'_, PyAny>> = v.try_iter()?.collect::<PyResult<_>>()?;
        if !items.is_empty() && items.iter().all(is_number) {
            let data = items.iter().map(|x| x.extract()).collect::<PyResult<_>>()?;
            return numbers(key, data, vec![items.len()]);
        }
        return items
            .iter()
            .map(|item| list_item(key, item))
            .collect::<Result<_, _>>()
            .map(Value::List);
    }
    let arr: PyReadonlyArrayDyn<'_, f64> = v.extract().map_err(|_| {
        InputError::type_(format!(
            "{key} must be a real number or an array of real numbers"
        ))
    })?;
    numbers(
        key,
        arr.as_array().iter().copied().collect(),
        arr.shape().to_vec(),
    )
}

/// A list's item as a table (see the module's shorthands).
fn list_item(key: &str, item: &Bound<'_, PyAny>) -> Result<Table, InputError> {
    if let Ok(d) = item.cast::<PyDict>() {
        return read_dict(d);
    }
    let pair = item
        .cast::<PyTuple>()
        .ok()
        .filter(|t| t.len() == 2 && t.get_item(0).is_ok_and(|k| k.is_instance_of::<PyString>()));
    let mut entries = Vec::with_capacity(2);
    let values = match pair {
        Some(t) => {
            entries.push(("kind".to_string(), value(key, &t.get_item(0)?)?));
            t.get_item(1)?
        }
        None => item.clone(),
    };
    entries.push(("values".to_string(), value(key, &values)?));
    Ok(Table::new(entries))
}

fn numbers(key: &str, data: Vec<f64>, shape: Vec<usize>) -> Result<Value, InputError> {
    Ok(Value::Numbers(Array::new(key, data, shape)?))
}
