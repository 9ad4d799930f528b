//! Parameter tables: the values a user gave, owned by Rust (the bindings convert a Python dict
//! into a [`Table`] once), and the [`Reader`] that the models' [`FromParams`] read one case at a
//! time.
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

use super::{FromParams, Kinds, Named, Param, ParamSource, Shape};
use crate::batch::PerCase;
use crate::error::ReadError;
use crate::fuzzy::Mamdani;

/// Numbers, in C order.
#[derive(Clone, Debug, PartialEq)]
pub struct Array {
    pub data: Vec<f64>,
    pub shape: Vec<usize>,
}

impl Array {
    /// The numbers of the entry `key`: at least one (every reader picks at least one value:
    /// the first case, axis or node count), each finite.
    pub fn new(key: &str, data: Vec<f64>, shape: Vec<usize>) -> Result<Self, ReadError> {
        if shape.contains(&0) {
            return Err(ReadError::value(format!(
                "{key} has shape {}; it takes at least one value",
                shape_str(&shape)
            )));
        }
        if let Some((i, x)) = data.iter().enumerate().find(|(_, x)| !x.is_finite()) {
            let at = if data.len() > 1 {
                format!(" (entry {i})")
            } else {
                String::new()
            };
            return Err(ReadError::value(format!(
                "{key} = {x} violates finite values{at}"
            )));
        }
        Ok(Self { data, shape })
    }
}

#[derive(Clone, Debug)]
pub enum Value {
    Absent,
    Flag(bool),
    Text(String),
    Numbers(Array),
    Table(Table),
    List(Vec<Table>),
    /// A compiled fuzzy system.
    Fuzzy(Arc<Mamdani>),
}

/// A parameter table: named values, in the order given.
#[derive(Clone, Debug, Default)]
pub struct Table {
    entries: Vec<(String, Value)>,
}

/// A shape as numpy prints it: `(3,)`, `(2, 3)`.
pub fn shape_str(shape: &[usize]) -> String {
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
    pub fn new(entries: Vec<(String, Value)>) -> Self {
        Self { entries }
    }

    /// A table with one entry, a list of tables.
    pub fn with_list(key: &str, items: Vec<Table>) -> Self {
        Self::new(vec![(key.to_string(), Value::List(items))])
    }

    /// The entry `key`, if present.
    pub fn entry(&self, key: &str) -> Option<&Value> {
        self.entries.iter().find(|(k, _)| k == key).map(|(_, v)| v)
    }

    fn get(&self, key: &str) -> &Value {
        self.entry(key).unwrap_or(&Value::Absent)
    }

    /// The `kind` entry, if any.
    pub fn kind(&self) -> Option<&str> {
        match self.get("kind") {
            Value::Text(s) => Some(s),
            _ => None,
        }
    }

    /// The list of tables `key` (a disturbance's components), if it is one.
    pub fn list(&self, key: &str) -> Option<&[Table]> {
        match self.get(key) {
            Value::List(items) => Some(items),
            _ => None,
        }
    }

    /// Whether the table looks meant for two axes: some per-axis array has length 2 and none
    /// length 3 (read for three axes, its error would then call it one value per case).
    pub fn meant_for_two_axes(&self) -> bool {
        let lengths: Vec<usize> = self
            .entries
            .iter()
            .filter_map(|(_, v)| match v {
                Value::Numbers(a) => a.shape.last().copied(),
                _ => None,
            })
            .collect();
        lengths.contains(&2) && !lengths.contains(&3)
    }

    /// Reads every case with `read` (case 0 first, which finds how many cases the table
    /// holds), refusing unknown keys. `cases`: the batch's size, when known.
    pub fn read_cases<T>(
        &self,
        cases: Option<usize>,
        read: impl Fn(&mut Reader<'_>) -> Result<T, ReadError>,
    ) -> Result<(PerCase<T>, Cases), ReadError> {
        let at_case = |e: ReadError, i: usize| match e {
            ReadError::Value(m) => ReadError::Value(format!("{m} (case {i})")),
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

    /// Reads a model shared by every case (a dispersion, a fuzzy system), refusing unknown keys.
    pub fn read_one<T: FromParams>(&self) -> Result<T, ReadError> {
        let mut r = Reader::new(self, 0, None);
        let v = T::from_params(&mut r)?;
        r.check_unknown()?;
        Ok(v)
    }

    /// The numeric parameter `name` of a table of kind `K`, as a model with `axes` axes reads
    /// it (scalars and per-axis values broadcast, per case or shared).
    pub fn values<K: Kinds>(&self, name: &str, axes: usize) -> Result<Values, ReadError> {
        let kind = self
            .kind()
            .and_then(K::from_name)
            .ok_or_else(|| ReadError::type_("the table has no known 'kind'"))?;
        let param = kind
            .schema()
            .param(name)
            .ok_or_else(|| unknown(name, kind.schema()))?;
        if !param.shape.is_numeric() {
            return Err(unknown(name, kind.schema()));
        }
        self.values_of(param, axes)
    }

    /// [`Table::values`] of a declared parameter.
    pub fn values_of(&self, param: &Param, axes: usize) -> Result<Values, ReadError> {
        let per_axis = param.shape == Shape::PerAxis;
        let width = if per_axis { axes } else { 1 };
        let a = match self.get(param.name) {
            Value::Numbers(a) => a,
            Value::Absent => {
                return Err(ReadError::value(format!(
                    "{} is not given (None)",
                    param.name
                )));
            }
            _ => return Err(not_numbers(param.name)),
        };
        let read = |r: &mut Reader<'_>, out: &mut Vec<f64>| -> Result<(), ReadError> {
            if per_axis {
                r.pick_axes(param.name, a, axes, out)
            } else {
                out.push(r.pick_scalar(param.name, a)?);
                Ok(())
            }
        };
        let mut data = Vec::new();
        let mut r = Reader::new(self, 0, None);
        read(&mut r, &mut data)?;
        let cases = r.cases().count;
        for i in 1..cases {
            read(&mut Reader::new(self, i, Some(cases)), &mut data)?;
        }
        Ok(Values {
            data,
            cases,
            width,
            per_axis,
        })
    }
}

/// A numeric parameter as the models read it: `cases` rows (1 when shared) of `width` values
/// (the axes of a per-axis parameter, 1 for a scalar), row-major.
#[derive(Clone, Debug, PartialEq)]
pub struct Values {
    pub data: Vec<f64>,
    pub cases: usize,
    pub width: usize,
    pub per_axis: bool,
}

fn unknown(name: &str, schema: super::Schema) -> ReadError {
    let numeric: Vec<&str> = schema
        .params
        .iter()
        .filter(|p| p.shape.is_numeric())
        .map(|p| p.name)
        .collect();
    ReadError::value(format!(
        "unknown parameter {name:?}; the numeric parameters are {numeric:?}"
    ))
}

fn not_numbers(key: &str) -> ReadError {
    ReadError::type_(format!(
        "{key} must be a real number or an array of real numbers"
    ))
}

fn required(key: &str) -> ReadError {
    ReadError::type_(format!("missing parameter {key}"))
}

/// What a table's cases turned out to be: how many (1 when everything is shared) and which key
/// made them per case.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Cases {
    pub count: usize,
    pub key: Option<String>,
}

impl Cases {
    /// Checks that the table suits a batch of `n` cases.
    pub fn check(&self, owner: &str, n: usize) -> Result<(), ReadError> {
        match &self.key {
            Some(key) if self.count != n => Err(ReadError::value(format!(
                "{owner}: {key} has {} values per case but the batch has {n} cases",
                self.count
            ))),
            _ => Ok(()),
        }
    }
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

    fn numbers(&mut self, key: &str) -> Result<Option<&'t Array>, ReadError> {
        match self.raw(key) {
            Value::Absent => Ok(None),
            Value::Numbers(a) => Ok(Some(a)),
            _ => Err(not_numbers(key)),
        }
    }

    /// Registers a per-case length for `key`.
    fn claim(&mut self, key: &str, len: usize) -> Result<(), ReadError> {
        match self.cases {
            Some(n) if n != len => Err(ReadError::value(format!(
                "{key} has {len} values per case but the batch has {n} cases{}",
                self.set_by()
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

    /// Which parameter set the case count, for an error about it: a mismatch may be the
    /// other parameter's mistake (a per-axis parameter of a three-axis plant given to a
    /// two-axis law reads as three cases), so the message names both.
    fn set_by(&self) -> String {
        match &self.per_case_key {
            Some(k) => format!("; {k} gave {} per case", self.cases.unwrap_or(1)),
            None => String::new(),
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
    pub fn check_unknown(&self) -> Result<(), ReadError> {
        fn walk(t: &Table, used: &HashSet<(usize, String)>) -> Result<(), ReadError> {
            let addr = t as *const Table as usize;
            for (k, v) in &t.entries {
                if k == "kind" {
                    continue;
                }
                if !used.contains(&(addr, k.clone())) {
                    return Err(ReadError::type_(format!("unknown parameter {k:?}")));
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
        read: impl FnOnce(&mut Self) -> Result<T, ReadError>,
    ) -> Result<T, ReadError> {
        let outer = self.table;
        self.table = table;
        let r = read(self);
        self.table = outer;
        r
    }

    fn pick_scalar(&mut self, key: &str, a: &Array) -> Result<f64, ReadError> {
        match a.shape.as_slice() {
            [] | [1] => Ok(a.data[0]),
            [len] => {
                self.claim(key, *len)?;
                Ok(a.data[self.case])
            }
            s => Err(ReadError::value(format!(
                "{key} has shape {}; it takes a scalar or one value per case, shape (N,)",
                shape_str(s)
            ))),
        }
    }

    /// This case's `d` values of a per-axis parameter, appended to `out`.
    fn pick_axes(
        &mut self,
        key: &str,
        a: &Array,
        d: usize,
        out: &mut Vec<f64>,
    ) -> Result<(), ReadError> {
        let i = self.case;
        let row = |r: usize| &a.data[r * d..(r + 1) * d];
        match a.shape.as_slice() {
            [] | [1] => out.extend(std::iter::repeat_n(a.data[0], d)),
            [n] if *n == d => out.extend_from_slice(row(0)),
            [len] => {
                // neither per axis nor per case: say both counts (a law's per-axis defaults
                // sized for another plant read as per case otherwise)
                if let Some(n) = self.cases.filter(|n| n != len) {
                    return Err(ReadError::value(format!(
                        "{key} has {len} values: one per axis takes {d} (the plant's axes), one per case {n} (the batch's cases){}",
                        self.set_by()
                    )));
                }
                self.claim(key, *len)?;
                out.extend(std::iter::repeat_n(a.data[i], d));
            }
            [1, n] if *n == d => out.extend_from_slice(row(0)),
            [len, 1] => {
                self.claim(key, *len)?;
                out.extend(std::iter::repeat_n(a.data[i], d));
            }
            [len, n] if *n == d => {
                self.claim(key, *len)?;
                out.extend_from_slice(row(i));
            }
            s => {
                return Err(ReadError::value(format!(
                    "{key} has shape {}; it takes a scalar, one value per axis ({d},), or per case (N,), (N, 1), (N, {d})",
                    shape_str(s)
                )));
            }
        }
        Ok(())
    }
}

impl ParamSource for Reader<'_> {
    fn scalar(&mut self, p: &Param) -> Result<f64, ReadError> {
        self.opt_scalar(p)?.ok_or_else(|| required(p.name))
    }

    fn opt_scalar(&mut self, p: &Param) -> Result<Option<f64>, ReadError> {
        match self.numbers(p.name)? {
            None => Ok(None),
            Some(a) => self.pick_scalar(p.name, a).map(Some),
        }
    }

    fn axes<const D: usize>(&mut self, p: &Param) -> Result<SVector<f64, D>, ReadError> {
        self.opt_axes(p)?.ok_or_else(|| required(p.name))
    }

    fn opt_axes<const D: usize>(
        &mut self,
        p: &Param,
    ) -> Result<Option<SVector<f64, D>>, ReadError> {
        match self.numbers(p.name)? {
            None => Ok(None),
            Some(a) => {
                let mut v = Vec::with_capacity(D);
                self.pick_axes(p.name, a, D, &mut v)?;
                Ok(Some(SVector::from_column_slice(&v)))
            }
        }
    }

    fn components(&mut self, p: &Param) -> Result<Vec<f64>, ReadError> {
        let key = p.name;
        match self.raw(key) {
            Value::Numbers(a) if a.shape.len() <= 1 => Ok(a.data.clone()),
            Value::Numbers(a) => Err(ReadError::value(format!(
                "{key} has shape {:?}; it takes a scalar or one value per component",
                a.shape
            ))),
            _ => Err(required(key)),
        }
    }

    fn case_components(&mut self, p: &Param) -> Result<Vec<f64>, ReadError> {
        let key = p.name;
        match self.raw(key) {
            Value::Numbers(a) if a.shape.len() <= 1 => Ok(a.data.clone()),
            Value::Numbers(a) if a.shape.len() == 2 => {
                let [len, width] = [a.shape[0], a.shape[1]];
                self.claim(key, len)?;
                let i = self.case;
                Ok(a.data[i * width..(i + 1) * width].to_vec())
            }
            Value::Numbers(a) => Err(ReadError::value(format!(
                "{key} has shape {}; it takes a scalar, one value per component (K,), or per case (N, 1), (N, K)",
                shape_str(&a.shape)
            ))),
            _ => Err(required(key)),
        }
    }

    fn choice<T: Named>(&mut self, p: &Param) -> Result<T, ReadError> {
        let (key, names) = (p.name, T::NAMES);
        match self.raw(key) {
            Value::Absent => Err(required(key)),
            Value::Text(s) => T::from_name(s)
                .ok_or_else(|| ReadError::value(format!("{key} = {s:?} is not one of {names:?}"))),
            _ => Err(ReadError::type_(format!(
                "{key} must be a string, one of {names:?}"
            ))),
        }
    }

    fn flag(&mut self, p: &Param) -> Result<bool, ReadError> {
        match self.raw(p.name) {
            Value::Absent => Err(required(p.name)),
            Value::Flag(b) => Ok(*b),
            _ => Err(ReadError::type_(format!(
                "{} must be True or False",
                p.name
            ))),
        }
    }

    fn count(&mut self, p: &Param) -> Result<usize, ReadError> {
        let key = p.name;
        let allowed = match p.shape {
            Shape::Count(allowed) => allowed,
            _ => &[],
        };
        let a = self.numbers(key)?.ok_or_else(|| required(key))?;
        let first = a.data[0];
        if a.data.iter().any(|&v| v != first) {
            return Err(ReadError::value(format!(
                "{key} must be the same for every case (it fixes the model's size)"
            )));
        }
        let n = first as usize;
        if first.fract() != 0.0 || first < 0.0 || !allowed.contains(&n) {
            return Err(ReadError::value(format!(
                "{key} = {first} violates {}",
                p.rule
            )));
        }
        Ok(n)
    }

    fn kind<T: Kinds>(&mut self) -> Result<T, ReadError> {
        self.mark("kind");
        let known = T::NAMES;
        match self.table.get("kind") {
            Value::Text(s) => T::from_name(s)
                .ok_or_else(|| ReadError::value(format!("unknown kind {s:?}; known: {known:?}"))),
            _ => Err(ReadError::type_("the table has no 'kind'")),
        }
    }

    fn nested<T>(
        &mut self,
        p: &Param,
        read: impl FnOnce(&mut Self) -> Result<T, ReadError>,
    ) -> Result<T, ReadError> {
        let key = p.name;
        match self.raw(key) {
            Value::Table(t) => self.with_table(t, read).map_err(|e| e.context(key)),
            Value::Absent => Err(required(key)),
            _ => Err(ReadError::type_(format!("{key} must be a table"))),
        }
    }

    fn opt_nested<T>(
        &mut self,
        p: &Param,
        read: impl FnOnce(&mut Self) -> Result<T, ReadError>,
    ) -> Result<Option<T>, ReadError> {
        match self.raw(p.name) {
            Value::Absent => Ok(None),
            _ => self.nested(p, read).map(Some),
        }
    }

    fn list_len(&mut self, p: &Param) -> Result<usize, ReadError> {
        match self.raw(p.name) {
            Value::Absent => Ok(0),
            Value::List(items) => Ok(items.len()),
            _ => Err(ReadError::type_(format!(
                "{} must be a list of tables",
                p.name
            ))),
        }
    }

    fn list_item<T>(
        &mut self,
        p: &Param,
        index: usize,
        read: impl FnOnce(&mut Self) -> Result<T, ReadError>,
    ) -> Result<T, ReadError> {
        match self.raw(p.name) {
            Value::List(items) if index < items.len() => self.with_table(&items[index], read),
            _ => Err(ReadError::type_(format!(
                "{} must be a list of tables",
                p.name
            ))),
        }
    }

    fn fuzzy_system(&mut self, p: &Param) -> Result<Arc<Mamdani>, ReadError> {
        match self.raw(p.name) {
            Value::Fuzzy(m) => Ok(m.clone()),
            Value::Absent => Err(required(p.name)),
            _ => Err(ReadError::type_(format!(
                "{} must be a landing.fuzzy.Mamdani system",
                p.name
            ))),
        }
    }

    fn skip(&mut self, p: &Param) {
        self.mark(p.name);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::control::{AnyLaw, LawKind};

    fn numbers(data: &[f64], shape: &[usize]) -> Value {
        Value::Numbers(Array {
            data: data.to_vec(),
            shape: shape.to_vec(),
        })
    }

    fn open_loop(acceleration: Value) -> Table {
        Table::new(vec![
            ("kind".into(), Value::Text("open_loop".into())),
            ("acceleration".into(), acceleration),
        ])
    }

    #[test]
    fn a_per_axis_parameter_is_shared_per_axis_or_per_case() {
        let per_axis = |v: Value, axes| open_loop(v).values::<LawKind>("acceleration", axes);
        let shared = per_axis(numbers(&[2.0], &[]), 3).unwrap();
        assert_eq!((shared.data, shared.cases), (vec![2.0; 3], 1));
        let axes = per_axis(numbers(&[1.0, 2.0, 3.0], &[3]), 3).unwrap();
        assert_eq!((axes.data, axes.cases), (vec![1.0, 2.0, 3.0], 1));
        // the same 1-D array of length 3 is one value per case for two axes
        let cases = per_axis(numbers(&[1.0, 2.0, 3.0], &[3]), 2).unwrap();
        assert_eq!(cases.data, [1.0, 1.0, 2.0, 2.0, 3.0, 3.0]);
        assert_eq!(cases.cases, 3);
        let grid = per_axis(numbers(&[1.0, 2.0, 3.0, 4.0], &[2, 2]), 2).unwrap();
        assert_eq!((grid.data, grid.cases), (vec![1.0, 2.0, 3.0, 4.0], 2));
        let err = per_axis(numbers(&[1.0; 8], &[2, 4]), 3).unwrap_err();
        assert_eq!(
            err.message(),
            "acceleration has shape (2, 4); it takes a scalar, one value per axis (3,), or per case (N,), (N, 1), (N, 3)"
        );
    }

    #[test]
    fn a_table_reads_each_case_and_refuses_unknown_keys() {
        let t = open_loop(numbers(&[1.0, 2.0], &[2, 1]));
        let (laws, cases) = t.read_cases(None, |p| AnyLaw::<3>::from_params(p)).unwrap();
        assert_eq!((laws.len(), cases.count), (2, 2));
        assert_eq!(cases.key.as_deref(), Some("acceleration"));
        assert!(cases.check("law", 2).is_ok());
        assert_eq!(
            cases.check("law", 3).unwrap_err().message(),
            "law: acceleration has 2 values per case but the batch has 3 cases"
        );
        let mut extra = open_loop(numbers(&[1.0], &[]));
        extra
            .entries
            .push(("acceleraton".into(), numbers(&[1.0], &[])));
        let err = extra
            .read_cases(None, |p| AnyLaw::<3>::from_params(p))
            .unwrap_err();
        assert_eq!(err, ReadError::type_("unknown parameter \"acceleraton\""));
    }
}
