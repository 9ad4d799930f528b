//! A Mamdani system read from its table: `{"inputs": [variable, ...], "output": variable,
//! "rules": [[set indices..., output set], ...], "resolution": n}`, each variable
//! `{"lo": .., "hi": .., "sets": [(shape, corners), ...]}` (the bindings turn a `(shape,
//! corners)` pair into the table `{"kind": shape, "values": corners}` and a rule's list into
//! `{"values": rule}`).

use super::mamdani::{HI, INPUTS, LO, OUTPUT, RESOLUTION, RULE, RULES, SETS};
use super::membership::{MembershipShape, TRAPEZOID, TRIANGLE};
use super::{Mamdani, Membership, Rule, Variable};
use crate::error::ReadError;
use crate::params::{FromParams, ParamSource};

/// A whole, non-negative number (a set index, a resolution).
fn whole(v: f64) -> Option<usize> {
    (v >= 0.0 && v.fract() == 0.0 && v <= u32::MAX as f64).then_some(v as usize)
}

/// One fuzzy set: its shape (the table's kind) and its corners.
fn membership<S: ParamSource>(p: &mut S) -> Result<Membership, ReadError> {
    let shape = p.kind::<MembershipShape>()?;
    let corners = p.components(match shape {
        MembershipShape::Triangle => &TRIANGLE,
        MembershipShape::Trapezoid => &TRAPEZOID,
    })?;
    match (shape, corners.as_slice()) {
        (MembershipShape::Triangle, &[a, b, c]) => Ok(Membership::Triangle(a, b, c)),
        (MembershipShape::Trapezoid, &[a, b, c, d]) => Ok(Membership::Trapezoid(a, b, c, d)),
        _ => Err(ReadError::value(format!(
            "a set is ('triangle', a, b, c) or ('trapezoid', a, b, c, d), got ({:?}, {corners:?})",
            shape.name()
        ))),
    }
}

impl FromParams for Variable {
    /// The universe and the sets, each set checked here too (the system checks them again) so
    /// that the error names the set.
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        let lo = p.scalar(&LO)?;
        let hi = p.scalar(&HI)?;
        let sets = (0..p.list_len(&SETS)?)
            .map(|j| p.list_item(&SETS, j, membership))
            .collect::<Result<Vec<_>, _>>()?;
        for (j, set) in sets.iter().enumerate() {
            set.validate().map_err(|e| {
                ReadError::value(format!(
                    "sets[{j}] {} = {} violates {}",
                    e.param, e.value, e.rule
                ))
            })?;
        }
        Ok(Variable { lo, hi, sets })
    }
}

impl FromParams for Mamdani {
    /// The system, validated ([`Mamdani::new`]).
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        let inputs = (0..p.list_len(&INPUTS)?)
            .map(|i| {
                p.list_item(&INPUTS, i, Variable::from_params)
                    .map_err(|e| e.context(&format!("input {i}")))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let output = p.nested(&OUTPUT, Variable::from_params)?;
        let bad_index = || ReadError::type_("rules: a rule is a list of set indices");
        let rules = (0..p.list_len(&RULES)?)
            .map(|k| {
                let sets = p.list_item(&RULES, k, |r| r.components(&RULE))?;
                let mut sets: Vec<usize> = sets
                    .into_iter()
                    .map(whole)
                    .collect::<Option<_>>()
                    .ok_or_else(bad_index)?;
                let consequent = sets.pop().unwrap_or(usize::MAX);
                Ok(Rule {
                    antecedent: sets,
                    consequent,
                })
            })
            .collect::<Result<Vec<_>, ReadError>>()?;
        let resolution = p.scalar(&RESOLUTION)?;
        let resolution = whole(resolution)
            .ok_or_else(|| ReadError::type_("resolution must be a whole number"))?;
        Ok(Mamdani::new(inputs, output, rules, resolution)?)
    }
}
