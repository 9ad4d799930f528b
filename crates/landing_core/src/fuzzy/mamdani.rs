//! A Mamdani fuzzy inference system: min for AND and for implication, max for aggregation,
//! centroid defuzzification of the aggregated membership sampled on the output universe and
//! interpolated linearly between samples (the scikit-fuzzy conventions, which the Python tests
//! compare with).

use super::Membership;
use crate::error::{ParamError, require};

/// Most sets one output variable may have (the aggregation keeps one activation per set on
/// the stack, so evaluation never allocates).
pub const MAX_OUTPUT_SETS: usize = 16;
/// Most inputs a system may have.
pub const MAX_INPUTS: usize = 4;

/// A linguistic variable on the universe [lo, hi].
#[derive(Clone, Debug, PartialEq)]
pub struct Variable {
    pub lo: f64,
    pub hi: f64,
    pub sets: Vec<Membership>,
}

impl Variable {
    pub fn validate(&self, name: &'static str) -> Result<(), ParamError> {
        require(self.hi > self.lo, name, self.hi, "universe hi > lo")?;
        require(!self.sets.is_empty(), name, 0.0, "at least one fuzzy set")?;
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

#[derive(Clone, Debug, PartialEq)]
pub struct Mamdani {
    inputs: Vec<Variable>,
    output: Variable,
    rules: Vec<Rule>,
    /// The sampled output universe.
    grid: Vec<f64>,
    /// Output set memberships on the grid, set-major.
    table: Vec<f64>,
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
            "inputs",
            inputs.len() as f64,
            "1 to 4 inputs",
        )?;
        for v in &inputs {
            v.validate("inputs")?;
        }
        output.validate("output")?;
        require(
            output.sets.len() <= MAX_OUTPUT_SETS,
            "output",
            output.sets.len() as f64,
            "at most 16 output sets",
        )?;
        require(
            resolution >= 2,
            "resolution",
            resolution as f64,
            "resolution >= 2",
        )?;
        require(!rules.is_empty(), "rules", 0.0, "at least one rule")?;
        for (k, r) in rules.iter().enumerate() {
            require(
                r.antecedent.len() == inputs.len(),
                "rules",
                k as f64,
                "one antecedent set per input in every rule",
            )?;
            for (i, &a) in r.antecedent.iter().enumerate() {
                require(
                    a < inputs[i].sets.len(),
                    "rules",
                    k as f64,
                    "antecedent sets that exist",
                )?;
            }
            require(
                r.consequent < output.sets.len(),
                "rules",
                k as f64,
                "consequent sets that exist",
            )?;
        }
        let step = (output.hi - output.lo) / (resolution - 1) as f64;
        let grid: Vec<f64> = (0..resolution)
            .map(|j| output.lo + step * j as f64)
            .collect();
        let table = output
            .sets
            .iter()
            .flat_map(|s| grid.iter().map(|&y| s.eval(y)))
            .collect();
        Ok(Self {
            inputs,
            output,
            rules,
            grid,
            table,
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

    /// The crisp output for `x` (one value per input; values outside an input's universe are
    /// clipped to it). 0 when no rule fires.
    pub fn evaluate(&self, x: &[f64]) -> f64 {
        let mut fire = [0.0f64; MAX_OUTPUT_SETS];
        let mut clipped = [0.0f64; MAX_INPUTS];
        for (i, v) in self.inputs.iter().enumerate() {
            clipped[i] = x[i].clamp(v.lo, v.hi);
        }
        for r in &self.rules {
            let mut w: f64 = 1.0;
            for (i, &a) in r.antecedent.iter().enumerate() {
                w = w.min(self.inputs[i].sets[a].eval(clipped[i]));
            }
            fire[r.consequent] = fire[r.consequent].max(w);
        }
        let n = self.grid.len();
        let fire = &fire[..self.output.sets.len()];
        let aggregated = |j: usize| -> f64 {
            let mut mu: f64 = 0.0;
            for (k, &f) in fire.iter().enumerate() {
                if f > 0.0 {
                    mu = mu.max(f.min(self.table[k * n + j]));
                }
            }
            mu
        };
        // centroid of the piecewise-linear interpolant: each grid interval is a trapezoid with
        // area h (m0 + m1) / 2 and first moment h (x0 (2 m0 + m1) + x1 (m0 + 2 m1)) / 6
        let (mut moment, mut area) = (0.0, 0.0);
        let mut m0 = aggregated(0);
        for j in 1..n {
            let m1 = aggregated(j);
            if m0 > 0.0 || m1 > 0.0 {
                let (x0, x1) = (self.grid[j - 1], self.grid[j]);
                let h = x1 - x0;
                area += 0.5 * h * (m0 + m1);
                moment += h * (x0 * (2.0 * m0 + m1) + x1 * (m0 + 2.0 * m1)) / 6.0;
            }
            m0 = m1;
        }
        if area > 0.0 { moment / area } else { 0.0 }
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
