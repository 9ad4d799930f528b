//! Parameter tables: a Python dict read once into Rust values, then read by the core's
//! [`FromParams`](landing_core::params::FromParams) implementations one case at a time.
//!
//! Every numeric parameter may be shared or given per case:
//! - a scalar parameter takes `()` or `(N,)`;
//! - a per-axis parameter takes `()`, `(D,)` per axis, `(N, D)` per case and axis, `(N, 1)`
//!   or `(N,)` per case (the same on every axis). A 1-D array whose length is D is read per
//!   axis, even when N = D; give `(N, 1)` to sweep per case then.
//!
//! A key the model never reads is refused (a misspelt gain is an error, not a default).

use std::collections::HashSet;
use std::sync::Arc;

use nalgebra::SVector;
use numpy::{PyReadonlyArrayDyn, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};

use landing_core::PerCase;
use landing_core::fuzzy::Mamdani;
use landing_core::params::{Named, ParamSource};

use crate::errors::InputError;

/// Numbers read from Python, in C order.
#[derive(Clone, Debug)]
pub struct Array {
    pub data: Vec<f64>,
    pub shape: Vec<usize>,
}

#[derive(Clone, Debug)]
pub enum Value {
    Absent,
    Flag(bool),
    Text(String),
    Numbers(Array),
    Table(Table),
    List(Vec<Table>),
    /// A compiled fuzzy system (a `FuzzySystem` handle).
    Fuzzy(Arc<Mamdani>),
}

/// A parameter table, owned by Rust.
#[derive(Clone, Debug)]
pub struct Table {
    entries: Vec<(String, Value)>,
}

fn shape_str(shape: &[usize]) -> String {
    match shape {
        [a] => format!("({a},)"),
        _ => format!(
            "({})",
            shape
                .iter()
                .map(|s| s.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

impl Table {
    /// Reads a Python dict: numbers (arrays of float64), flags, names, nested dicts and lists of
    /// dicts.
    pub fn from_py(dict: &Bound<'_, PyDict>) -> Result<Self, InputError> {
        let mut entries = Vec::with_capacity(dict.len());
        for (k, v) in dict.iter() {
            let key: String = k
                .extract()
                .map_err(|_| InputError::type_("table keys must be strings"))?;
            let value = Self::value(&key, &v)?;
            entries.push((key, value));
        }
        Ok(Self { entries })
    }

    fn value(key: &str, v: &Bound<'_, PyAny>) -> Result<Value, InputError> {
        if v.is_none() {
            return Ok(Value::Absent);
        }
        if let Ok(b) = v.extract::<bool>()
            && v.is_instance_of::<pyo3::types::PyBool>()
        {
            return Ok(Value::Flag(b));
        }
        if let Ok(s) = v.cast::<PyString>() {
            return Ok(Value::Text(s.to_string()));
        }
        if let Ok(d) = v.cast::<PyDict>() {
            return Ok(Value::Table(Self::from_py(d)?));
        }
        if let Ok(f) = v.cast::<crate::fuzzy::FuzzySystem>() {
            return Ok(Value::Fuzzy(f.get().system.clone()));
        }
        if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
            let mut items = Vec::new();
            for item in v.try_iter()? {
                let item = item?;
                let d = item
                    .cast::<PyDict>()
                    .map_err(|_| InputError::type_(format!("{key} must be a list of tables")))?;
                items.push(Self::from_py(d)?);
            }
            return Ok(Value::List(items));
        }
        let arr: PyReadonlyArrayDyn<'_, f64> = v.extract().map_err(|_| {
            InputError::type_(format!(
                "{key} must be a real number or an array of real numbers"
            ))
        })?;
        let shape = arr.shape().to_vec();
        if shape.contains(&0) {
            // every reader picks at least one value (the first case, axis or node count)
            return Err(InputError::value(format!(
                "{key} has shape {}; it takes at least one value",
                shape_str(&shape)
            )));
        }
        let data: Vec<f64> = arr.as_array().iter().copied().collect();
        if let Some((i, x)) = data.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            let at = if data.len() > 1 {
                format!(" (entry {i})")
            } else {
                String::new()
            };
            return Err(InputError::value(format!(
                "{key} = {x} violates finite values{at}"
            )));
        }
        Ok(Value::Numbers(Array { data, shape }))
    }

    /// A table with one entry, a list of tables.
    pub fn with_list(key: &str, items: Vec<Table>) -> Self {
        Self {
            entries: vec![(key.to_string(), Value::List(items))],
        }
    }

    /// The entry `key`, if present.
    pub fn entry(&self, key: &str) -> Option<&Value> {
        self.entries.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }

    fn get(&self, key: &str) -> &Value {
        self.entries
            .iter()
            .find(|(k, _)| k == key)
            .map_or(&Value::Absent, |(_, v)| v)
    }

    /// The `kind` entry, if any.
    pub fn kind(&self) -> Option<&str> {
        match self.get("kind") {
            Value::Text(s) => Some(s),
            _ => None,
        }
    }

    /// The lengths of the trailing axes of the numeric entries (to guess a law's axis count).
    pub fn trailing_lengths(&self) -> Vec<usize> {
        self.entries
            .iter()
            .filter_map(|(_, v)| match v {
                Value::Numbers(a) => a.shape.last().copied(),
                _ => None,
            })
            .collect()
    }
}

/// What a table's cases turned out to be: how many (1 when everything is shared) and which key
/// made them per case.
#[derive(Clone, Debug, Default)]
pub struct Cases {
    pub count: usize,
    pub key: Option<String>,
}

/// Reads a [`Table`] at one case; the core's models read their keys through it.
pub struct Reader<'t> {
    root: &'t Table,
    table: &'t Table,
    /// The case being read.
    case: usize,
    /// Number of cases, once known (from the batch, or from the first per-case entry).
    cases: Option<usize>,
    per_case_key: Option<String>,
    /// Keys read, per table (by address).
    used: HashSet<(usize, String)>,
}

impl<'t> Reader<'t> {
    pub fn new(table: &'t Table, case: usize, cases: Option<usize>) -> Self {
        Self {
            root: table,
            table,
            case,
            cases,
            per_case_key: None,
            used: HashSet::new(),
        }
    }

    fn mark(&mut self, key: &str) {
        self.used
            .insert((self.table as *const Table as usize, key.to_string()));
    }

    fn raw(&mut self, key: &str) -> &'t Value {
        self.mark(key);
        self.table.get(key)
    }

    fn numbers(&mut self, key: &str) -> Result<Option<&'t Array>, InputError> {
        match self.raw(key) {
            Value::Absent => Ok(None),
            Value::Numbers(a) => Ok(Some(a)),
            _ => Err(InputError::type_(format!(
                "{key} must be a real number or an array of real numbers"
            ))),
        }
    }

    fn required(key: &str) -> InputError {
        InputError::type_(format!("missing parameter {key}"))
    }

    /// Registers a per-case length for `key`.
    fn claim(&mut self, key: &str, len: usize) -> Result<(), InputError> {
        match self.cases {
            Some(n) if n != len => Err(InputError::value(format!(
                "{key} has {len} values per case but the batch has {n} cases"
            ))),
            _ => {
                self.cases = Some(len);
                if self.per_case_key.is_none() {
                    self.per_case_key = Some(key.to_string());
                }
                Ok(())
            }
        }
    }

    /// What the cases turned out to be after a read.
    pub fn cases(&self) -> Cases {
        match &self.per_case_key {
            Some(k) => Cases {
                count: self.cases.unwrap_or(1),
                key: Some(k.clone()),
            },
            None => Cases {
                count: 1,
                key: None,
            },
        }
    }

    /// Refuses the keys of every table reached that no model read.
    pub fn check_unknown(&self) -> Result<(), InputError> {
        fn walk(t: &Table, used: &HashSet<(usize, String)>) -> Result<(), InputError> {
            let addr = t as *const Table as usize;
            for (k, v) in &t.entries {
                if k == "kind" {
                    continue;
                }
                if !used.contains(&(addr, k.clone())) {
                    return Err(InputError::type_(format!("unknown parameter {k:?}")));
                }
                match v {
                    Value::Table(sub) => walk(sub, used)?,
                    Value::List(items) => {
                        for sub in items {
                            walk(sub, used)?;
                        }
                    }
                    _ => {}
                }
            }
            Ok(())
        }
        walk(self.root, &self.used)
    }

    fn with_table<T>(
        &mut self,
        table: &'t Table,
        read: impl FnOnce(&mut Self) -> Result<T, InputError>,
    ) -> Result<T, InputError> {
        let outer = self.table;
        self.table = table;
        let r = read(self);
        self.table = outer;
        r
    }

    fn pick_scalar(&mut self, key: &str, a: &Array) -> Result<f64, InputError> {
        match a.shape.as_slice() {
            [] | [1] => Ok(a.data[0]),
            [len] => {
                self.claim(key, *len)?;
                Ok(a.data[self.case])
            }
            s => Err(InputError::value(format!(
                "{key} has shape {}; it takes a scalar or one value per case, shape (N,)",
                shape_str(s)
            ))),
        }
    }

    fn pick_axes<const D: usize>(
        &mut self,
        key: &str,
        a: &Array,
    ) -> Result<SVector<f64, D>, InputError> {
        let i = self.case;
        let row = |r: usize| SVector::<f64, D>::from_column_slice(&a.data[r * D..(r + 1) * D]);
        match a.shape.as_slice() {
            [] | [1] => Ok(SVector::repeat(a.data[0])),
            [d] if *d == D => Ok(row(0)),
            [len] => {
                self.claim(key, *len)?;
                Ok(SVector::repeat(a.data[i]))
            }
            [1, d] if *d == D => Ok(row(0)),
            [len, 1] => {
                self.claim(key, *len)?;
                Ok(SVector::repeat(a.data[i]))
            }
            [len, d] if *d == D => {
                self.claim(key, *len)?;
                Ok(row(i))
            }
            s => Err(InputError::value(format!(
                "{key} has shape {}; it takes a scalar, one value per axis ({D},), or per case (N,), (N, 1), (N, {D})",
                shape_str(s)
            ))),
        }
    }
}

impl ParamSource for Reader<'_> {
    type Error = InputError;

    fn scalar(&mut self, key: &'static str) -> Result<f64, InputError> {
        self.opt_scalar(key)?.ok_or_else(|| Self::required(key))
    }

    fn opt_scalar(&mut self, key: &'static str) -> Result<Option<f64>, InputError> {
        match self.numbers(key)? {
            None => Ok(None),
            Some(a) => self.pick_scalar(key, a).map(Some),
        }
    }

    fn axes<const D: usize>(&mut self, key: &'static str) -> Result<SVector<f64, D>, InputError> {
        self.opt_axes(key)?.ok_or_else(|| Self::required(key))
    }

    fn opt_axes<const D: usize>(
        &mut self,
        key: &'static str,
    ) -> Result<Option<SVector<f64, D>>, InputError> {
        match self.numbers(key)? {
            None => Ok(None),
            Some(a) => self.pick_axes(key, a).map(Some),
        }
    }

    fn choice<T: Named>(&mut self, key: &'static str) -> Result<T, InputError> {
        let names = T::NAMES;
        match self.raw(key) {
            Value::Absent => Err(Self::required(key)),
            Value::Text(s) => T::from_name(s)
                .ok_or_else(|| InputError::value(format!("{key} = {s:?} is not one of {names:?}"))),
            _ => Err(InputError::type_(format!(
                "{key} must be a string, one of {names:?}"
            ))),
        }
    }

    fn flag(&mut self, key: &'static str) -> Result<bool, InputError> {
        match self.raw(key) {
            Value::Absent => Err(Self::required(key)),
            Value::Flag(b) => Ok(*b),
            _ => Err(InputError::type_(format!("{key} must be True or False"))),
        }
    }

    fn count(
        &mut self,
        key: &'static str,
        allowed: &'static [usize],
        rule: &'static str,
    ) -> Result<usize, InputError> {
        let a = self.numbers(key)?.ok_or_else(|| Self::required(key))?;
        let first = a.data[0];
        if a.data.iter().any(|&v| v != first) {
            return Err(InputError::value(format!(
                "{key} must be the same for every case (it fixes the model's size)"
            )));
        }
        let n = first as usize;
        if first.fract() != 0.0 || first < 0.0 || !allowed.contains(&n) {
            return Err(InputError::value(format!(
                "{key} = {first} violates {rule}"
            )));
        }
        Ok(n)
    }

    fn kind<T: Named>(&mut self) -> Result<T, InputError> {
        self.mark("kind");
        let known = T::NAMES;
        match self.table.get("kind") {
            Value::Text(s) => T::from_name(s)
                .ok_or_else(|| InputError::value(format!("unknown kind {s:?}; known: {known:?}"))),
            _ => Err(InputError::type_("the table has no 'kind'")),
        }
    }

    fn nested<T>(
        &mut self,
        key: &'static str,
        read: impl FnOnce(&mut Self) -> Result<T, InputError>,
    ) -> Result<T, InputError> {
        match self.raw(key) {
            Value::Table(t) => self.with_table(t, read).map_err(|e| e.context(key)),
            Value::Absent => Err(Self::required(key)),
            _ => Err(InputError::type_(format!("{key} must be a table"))),
        }
    }

    fn list_len(&mut self, key: &'static str) -> Result<usize, InputError> {
        match self.raw(key) {
            Value::Absent => Ok(0),
            Value::List(items) => Ok(items.len()),
            _ => Err(InputError::type_(format!("{key} must be a list of tables"))),
        }
    }

    fn list_item<T>(
        &mut self,
        key: &'static str,
        index: usize,
        read: impl FnOnce(&mut Self) -> Result<T, InputError>,
    ) -> Result<T, InputError> {
        match self.raw(key) {
            Value::List(items) => self.with_table(&items[index], read),
            _ => Err(InputError::type_(format!("{key} must be a list of tables"))),
        }
    }

    fn fuzzy_system(&mut self, key: &'static str) -> Result<Arc<Mamdani>, InputError> {
        match self.raw(key) {
            Value::Fuzzy(m) => Ok(m.clone()),
            Value::Absent => Err(Self::required(key)),
            _ => Err(InputError::type_(format!(
                "{key} must be a landing.fuzzy.Mamdani system"
            ))),
        }
    }

    fn skip(&mut self, key: &'static str) {
        self.mark(key);
    }
}

impl Table {
    /// Reads every case with `read` (case 0 first, which finds how many cases the table
    /// holds), refusing unknown keys. `cases`: the batch's size, when known.
    pub fn read_cases<T>(
        &self,
        cases: Option<usize>,
        read: impl Fn(&mut Reader<'_>) -> Result<T, InputError>,
    ) -> Result<(PerCase<T>, Cases), InputError> {
        let at_case = |e: InputError, i: usize| match e {
            InputError::Value(m) => InputError::Value(format!("{m} (case {i})")),
            other => other,
        };
        let mut r = Reader::new(self, 0, cases);
        let first = match read(&mut r) {
            Ok(v) => v,
            Err(e) if r.per_case_key.is_some() => return Err(at_case(e, 0)),
            Err(e) => return Err(e),
        };
        r.check_unknown()?;
        let found = r.cases();
        let mut items = Vec::with_capacity(found.count);
        items.push(first);
        for i in 1..found.count {
            let mut r = Reader::new(self, i, Some(found.count));
            items.push(read(&mut r).map_err(|e| at_case(e, i))?);
        }
        Ok((PerCase::from_vec(items), found))
    }
}
