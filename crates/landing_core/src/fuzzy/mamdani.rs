//! A Mamdani fuzzy inference system: min for AND and for implication, max for aggregation,
//! centroid defuzzification of the aggregated membership sampled on the output universe and
//! interpolated linearly between samples (the scikit-fuzzy conventions, which the Python tests
//! compare with).
//!
//! Evaluated over [`Real`] lanes, one system for a block of cases. Only the output sets some
//! lane fires are aggregated, and only over the grid points where one of them is positive:
//! elsewhere the aggregated membership is zero and adds nothing to the centroid's sums.

use super::Membership;
use crate::error::{ParamError, ReadError, require};
use crate::lanes::{Mask, Real};
use crate::limits::MAX_FUZZY_RESOLUTION;
use crate::params::schema::{Declared, Layout, Param, Schema};

/// A variable's universe, low end.
pub const LO: Param = Param::scalar("lo")
    .unit("units of the variable")
    .doc("low end of the universe");
/// Its high end.
pub const HI: Param = Param::scalar("hi")
    .unit("units of the variable")
    .rule("universe hi > lo")
    .doc("high end of the universe");
/// Its fuzzy sets.
pub const SETS: Param = Param::list("sets", Layout::Family("fuzzy"))
    .rule("at least one fuzzy set")
    .doc("the fuzzy sets, each a pair (shape, corners)");
/// A linguistic variable's table.
pub const VARIABLE: &[Param] = &[LO, HI, SETS];
/// The set indices of one rule.
pub const RULE: Param = Param::components("values")
    .unit("1")
    .rule("antecedent sets that exist")
    .doc("the set index of each input, then the output's");
pub const INPUTS: Param = Param::list("inputs", Layout::Fixed(VARIABLE))
    .rule("1 to 4 inputs")
    .doc("the input variables");
pub const OUTPUT: Param = Param::nested("output", Layout::Fixed(VARIABLE))
    .rule("at most 16 output sets")
    .doc("the output variable");
pub const RULES: Param = Param::list("rules", Layout::Fixed(&[RULE]))
    .rule("at least one rule")
    .doc("IF input_0 is a_0 AND ... THEN output is c, each a list of set indices (a_0, ..., c)");
pub const RESOLUTION: Param = Param::scalar("resolution")
    .unit("1")
    .rule("2 <= resolution <= max_fuzzy_resolution (100000)")
    .doc("points sampling the output universe for the centroid, ends included");

/// Most sets one output variable may have (the aggregation keeps one activation per set on
/// the stack, so evaluation never allocates).
pub const MAX_OUTPUT_SETS: usize = 16;
/// Most inputs a system may have.
pub const MAX_INPUTS: usize = 4;
/// Most sets one input variable may have (their memberships are kept on the stack).
pub const MAX_INPUT_SETS: usize = 16;

impl Mamdani {
    /// The crisp outputs for rows of `columns` inputs each (row-major), refusing rows of
    /// another width than [`Mamdani::n_inputs`] and non-finite inputs by their position.
    pub fn evaluate_rows(&self, rows: &[f64], columns: usize) -> Result<Vec<f64>, ReadError> {
        let n = self.n_inputs();
        if columns != n {
            return Err(ReadError::value(format!(
                "inputs has {columns} columns; the system takes {n}"
            )));
        }
        if let Some((k, v)) = rows.iter().enumerate().find(|(_, v)| !v.is_finite()) {
            return Err(ReadError::value(format!(
                "inputs[{}, {}] = {v} violates finite values",
                k / n,
                k % n
            )));
        }
        Ok(rows
            .chunks_exact(n)
            .map(|r| self.evaluate::<f64>(r))
            .collect())
    }
}

/// A linguistic variable on the universe [lo, hi].
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    pub lo: f64,
    pub hi: f64,
    pub sets: Vec<Membership>,
}

impl Variable {
    pub fn validate(&self, name: &'static str) -> Result<(), ParamError> {
        require(self.hi > self.lo, name, self.hi, HI.rule)?;
        require(!self.sets.is_empty(), name, 0.0, SETS.rule)?;
        for (i, s) in self.sets.iter().enumerate() {
            s.validate().map_err(|e| e.on_axis(i))?;
        }
        Ok(())
    }
}

/// IF input_0 is set a_0 AND input_1 is set a_1 ... THEN output is set c.
#[derive(Clone, Debug, PartialEq)]
pub struct Rule {
    /// Set index per input.
    pub antecedent: Vec<usize>,
    pub consequent: usize,
}

impl Declared for Mamdani {
    const SCHEMA: Schema = Schema::new(&[INPUTS, OUTPUT, RULES, RESOLUTION]);
}

#[derive(Clone, Debug, PartialEq)]
pub struct Mamdani {
    inputs: Vec<Variable>,
    output: Variable,
    rules: Vec<Rule>,
    /// The sampled output universe.
    grid: Vec<f64>,
    /// Output set memberships on the grid, set-major.
    table: Vec<f64>,
    /// Per output set, the first and last grid index where its membership is positive
    /// (first > last when it is nowhere positive on the grid).
    support: Vec<(usize, usize)>,
}

impl Mamdani {
    /// `resolution` points sample the output universe, ends included.
    pub fn new(
        inputs: Vec<Variable>,
        output: Variable,
        rules: Vec<Rule>,
        resolution: usize,
    ) -> Result<Self, ParamError> {
        require(
            !inputs.is_empty() && inputs.len() <= MAX_INPUTS,
            INPUTS.name,
            inputs.len() as f64,
            INPUTS.rule,
        )?;
        for v in &inputs {
            v.validate(INPUTS.name)?;
            require(
                v.sets.len() <= MAX_INPUT_SETS,
                INPUTS.name,
                v.sets.len() as f64,
                "at most 16 sets per input",
            )?;
        }
        output.validate(OUTPUT.name)?;
        require(
            output.sets.len() <= MAX_OUTPUT_SETS,
            OUTPUT.name,
            output.sets.len() as f64,
            OUTPUT.rule,
        )?;
        require(
            (2..=MAX_FUZZY_RESOLUTION).contains(&(resolution as u64)),
            RESOLUTION.name,
            resolution as f64,
            RESOLUTION.rule,
        )?;
        require(!rules.is_empty(), RULES.name, 0.0, RULES.rule)?;
        for (k, r) in rules.iter().enumerate() {
            require(
                r.antecedent.len() == inputs.len(),
                RULES.name,
                k as f64,
                "one antecedent set per input in every rule",
            )?;
            for (i, &a) in r.antecedent.iter().enumerate() {
                require(a < inputs[i].sets.len(), RULES.name, k as f64, RULE.rule)?;
            }
            require(
                r.consequent < output.sets.len(),
                RULES.name,
                k as f64,
                "consequent sets that exist",
            )?;
        }
        let step = (output.hi - output.lo) / (resolution - 1) as f64;
        let grid: Vec<f64> = (0..resolution)
            .map(|j| output.lo + step * j as f64)
            .collect();
        let table: Vec<f64> = output
            .sets
            .iter()
            .flat_map(|s| grid.iter().map(|&y| s.eval(y)))
            .collect();
        let support = table
            .chunks(resolution)
            .map(|row| {
                let first = row.iter().position(|&m| m > 0.0);
                let last = row.iter().rposition(|&m| m > 0.0);
                match (first, last) {
                    (Some(a), Some(b)) => (a, b),
                    _ => (resolution, 0),
                }
            })
            .collect();
        Ok(Self {
            inputs,
            output,
            rules,
            grid,
            table,
            support,
        })
    }

    pub fn n_inputs(&self) -> usize {
        self.inputs.len()
    }

    pub fn inputs(&self) -> &[Variable] {
        &self.inputs
    }

    pub fn output(&self) -> &Variable {
        &self.output
    }

    pub fn rules(&self) -> &[Rule] {
        &self.rules
    }

    /// Number of points sampling the output universe.
    pub fn resolution(&self) -> usize {
        self.grid.len()
    }

    /// The aggregated membership at grid point `j`: the largest of the fired output sets
    /// clipped at their firing strengths.
    #[inline(always)]
    fn aggregated<R: Real>(&self, fire: &[R; MAX_OUTPUT_SETS], active: &[usize], j: usize) -> R {
        let n = self.grid.len();
        let mut m = R::zero();
        for &k in active {
            m = m.max(fire[k].min(R::splat(self.table[k * n + j])));
        }
        m
    }

    /// The crisp output for `x` (one value per input; values outside an input's universe are
    /// clipped to it), lane by lane. 0 where no rule fires.
    ///
    /// The centroid of the piecewise-linear interpolant of the aggregated membership m_j on the
    /// grid x_j = lo + j h, j = 0..n-1, is, summing the trapezoids' areas and first moments in
    /// closed form,
    /// `lo + h (S1 - (n - 1) m_(n-1) / 2 + (m_0 - m_(n-1)) / 6) / (S0 - (m_0 + m_(n-1)) / 2)`
    /// with `S0 = sum m_j`, `S1 = sum j m_j`: two sums per grid point.
    #[inline(always)]
    pub fn evaluate<R: Real>(&self, x: &[R]) -> R {
        let zero = R::zero();
        // memberships of every input set, each evaluated once
        let mut mu = [[zero; MAX_INPUT_SETS]; MAX_INPUTS];
        for (i, v) in self.inputs.iter().enumerate() {
            let xi = x[i].clamp(R::splat(v.lo), R::splat(v.hi));
            for (a, set) in v.sets.iter().enumerate() {
                mu[i][a] = set.eval_lanes(xi);
            }
        }
        let mut fire = [zero; MAX_OUTPUT_SETS];
        for r in &self.rules {
            let mut w = R::one();
            for (i, &a) in r.antecedent.iter().enumerate() {
                w = w.min(mu[i][a]);
            }
            fire[r.consequent] = fire[r.consequent].max(w);
        }
        // the output sets fired in some lane, and the grid points where one is positive
        let n = self.grid.len();
        let mut active = [0usize; MAX_OUTPUT_SETS];
        let mut n_active = 0;
        let (mut first, mut last) = (n, 0);
        for (k, f) in fire.iter().enumerate().take(self.output.sets.len()) {
            if f.simd_gt(zero).any() {
                active[n_active] = k;
                n_active += 1;
                first = first.min(self.support[k].0);
                last = last.max(self.support[k].1);
            }
        }
        if first > last {
            return zero;
        }
        let active = &active[..n_active];
        let (mut s0, mut s1) = (zero, zero);
        for j in first..=last {
            let m = self.aggregated(&fire, active, j);
            s0 += m;
            s1 += m * (j as f64);
        }
        let m0 = if first == 0 {
            self.aggregated(&fire, active, 0)
        } else {
            zero
        };
        let mn = if last == n - 1 {
            self.aggregated(&fire, active, n - 1)
        } else {
            zero
        };
        let h = (self.output.hi - self.output.lo) / (n - 1) as f64;
        let area = s0 - (m0 + mn) * 0.5;
        let moment = s1 - mn * (0.5 * (n - 1) as f64) + (m0 - mn) / 6.0;
        let centroid = R::splat(self.output.lo) + moment * h / area;
        R::select(area.simd_gt(zero), centroid, zero)
    }
}

/// `count` triangles evenly spaced over [lo, hi], the outer two as shoulders (peaks at the
/// ends): the usual partition of a quantised universe.
pub fn even_triangles(lo: f64, hi: f64, count: usize) -> Vec<Membership> {
    let step = (hi - lo) / (count - 1) as f64;
    (0..count)
        .map(|i| {
            let b = lo + step * i as f64;
            Membership::Triangle((b - step).max(lo), b, (b + step).min(hi))
        })
        .collect()
}

/// [`variable_rate_system`] at a resolution a caller names: refused below 2 or past the cap.
pub fn checked_variable_rate_system(resolution: usize) -> Result<Mamdani, ReadError> {
    if resolution < 2 {
        return Err(ReadError::value(format!(
            "resolution = {resolution} violates resolution >= 2"
        )));
    }
    let cap = crate::limits::MAX_FUZZY_RESOLUTION;
    crate::limits::within_cap("resolution", resolution as u64, "max_fuzzy_resolution", cap)?;
    Ok(variable_rate_system(resolution))
}

/// The seed-002 variable-rate system (sec. 2.3, Table 1): inputs s and s' with NB NS ZR PS PB
/// on [-5, 5], output eps with NB NM NS ZR PS PM PB on [-4, 4], even triangles, the 5x5 rules.
pub fn variable_rate_system(resolution: usize) -> Mamdani {
    // rows: s in NB..PB; columns: s' in NB..PB; entries index NB NM NS ZR PS PM PB = 0..6
    const TABLE: [[usize; 5]; 5] = [
        [0, 1, 1, 4, 3],
        [1, 2, 2, 3, 5],
        [2, 2, 3, 4, 4],
        [5, 3, 4, 5, 5],
        [3, 5, 5, 5, 6],
    ];
    let input = Variable {
        lo: -5.0,
        hi: 5.0,
        sets: even_triangles(-5.0, 5.0, 5),
    };
    let output = Variable {
        lo: -4.0,
        hi: 4.0,
        sets: even_triangles(-4.0, 4.0, 7),
    };
    let rules = (0..5)
        .flat_map(|i| {
            (0..5).map(move |j| Rule {
                antecedent: vec![i, j],
                consequent: TABLE[i][j],
            })
        })
        .collect();
    Mamdani::new(vec![input.clone(), input], output, rules, resolution)
        .expect("the seed system is valid")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_single_rule_returns_its_set_centroid() {
        let out = Variable {
            lo: -4.0,
            hi: 4.0,
            sets: even_triangles(-4.0, 4.0, 7),
        };
        let inp = Variable {
            lo: -5.0,
            hi: 5.0,
            sets: even_triangles(-5.0, 5.0, 5),
        };
        // only ZR -> PM fires (fully at 0): the centroid of the PM triangle is its peak 8/3
        let m = Mamdani::new(
            vec![inp],
            out,
            vec![Rule {
                antecedent: vec![2],
                consequent: 5,
            }],
            8001,
        )
        .unwrap();
        // (the sampled universe puts the feet off the grid: 1e-6 of sampling error)
        assert!((m.evaluate(&[0.0]) - 8.0 / 3.0).abs() < 1e-6);
        // clipped at half height the trapezoid is still symmetric about the peak
        assert!((m.evaluate(&[1.25]) - 8.0 / 3.0).abs() < 1e-6);
        // nothing fires
        assert_eq!(m.evaluate(&[5.0]), 0.0);
    }

    #[test]
    fn the_seed_system_is_odd_at_the_centre_and_follows_the_table() {
        let m = variable_rate_system(801);
        assert!(m.evaluate(&[0.0, 0.0]).abs() < 1e-12);
        // (NB, NB) -> NB: the left shoulder's centroid, negative and large
        assert!(m.evaluate(&[-5.0, -5.0]) < -3.0);
        assert!(m.evaluate(&[5.0, 5.0]) > 3.0);
        // (NB, PB) -> ZR
        assert!(m.evaluate(&[-5.0, 5.0]).abs() < 1e-9);
    }
}
