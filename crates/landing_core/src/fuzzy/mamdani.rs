//! A Mamdani fuzzy inference system: min for AND and for implication, max for aggregation,
//! centroid defuzzification of the aggregated membership sampled on the output universe and
//! interpolated linearly between samples (the scikit-fuzzy conventions, which the Python tests
//! compare with).
//!
//! Evaluated over [`Real`] lanes, one system for a block of cases. The aggregated membership
//! is made at each grid point from the output sets positive there (a table made once per
//! system), and only over the grid points where a set some lane fires is positive: elsewhere
//! it is zero and adds nothing to the centroid's sums.

use super::Membership;
use crate::error::{ParamError, ReadError, require};
use crate::lanes::slots::Slots;
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
    /// Per grid point, the output sets positive there and their memberships, in set order and
    /// in pairs: `points[j]` the first two, and `more[more_at[j]..more_at[j + 1]]` any further
    /// ones (none in an even partition, where at most two sets are positive at a point). A pair
    /// short of a set is completed by set 0 at membership 0, whose clipped membership, 0, the
    /// max with the other leaves as it is (the strengths are not negative).
    points: Vec<GridPoint>,
    more_at: Vec<usize>,
    more: Vec<GridPoint>,
}

/// Two output sets and their memberships at a grid point, and the point's index as a double
/// (the weight of its membership in the centroid's first moment). The loop reads each of
/// these constants as a broadcast from memory, which with AVX-512 is a load alone; converted
/// from the index, or loaded and then broadcast from a register, each took an operation of
/// the two vector ports the loop's arithmetic fills (in this layout W5 was 4 to 6 % faster
/// than with each membership in a tuple beside its set's index, which LLVM loaded as a scalar
/// and broadcast from a register; see BENCHMARKS.md).
#[derive(Clone, Copy, Debug, PartialEq)]
struct GridPoint {
    membership: [f64; 2],
    set: [usize; 2],
    index: f64,
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
        let (mut points, mut more_at, mut more) = (Vec::new(), vec![0], Vec::new());
        for j in 0..resolution {
            let positive: Vec<(usize, f64)> = (0..output.sets.len())
                .map(|k| (k, table[k * resolution + j]))
                .filter(|&(_, t)| t > 0.0)
                .collect();
            let mut pairs = positive.chunks(2).map(|p| {
                let (a, b) = (p[0], *p.get(1).unwrap_or(&(0, 0.0)));
                GridPoint {
                    membership: [a.1, b.1],
                    set: [a.0, b.0],
                    index: j as f64,
                }
            });
            let empty = GridPoint {
                membership: [0.0; 2],
                set: [0; 2],
                index: j as f64,
            };
            points.push(pairs.next().unwrap_or(empty));
            more.extend(pairs);
            more_at.push(more.len());
        }
        Ok(Self {
            inputs,
            output,
            rules,
            grid,
            table,
            support,
            points,
            more_at,
            more,
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
    fn aggregated<R: Real>(&self, fire: &[R], active: &[usize], j: usize) -> R {
        let n = self.grid.len();
        let mut m = R::zero();
        for &k in active {
            m = m.max(fire[k].min(R::splat(self.table[k * n + j])));
        }
        m
    }

    /// The sums `S0 = sum m_j` and `S1 = sum j m_j` of [`evaluate`](Self::evaluate)'s
    /// centroid for each of `A` points, over the grid points `first..=last`; `MORE` when some
    /// grid point has more than two positive output sets.
    ///
    /// The aggregated membership point by point, from the sets positive there only: a set's
    /// membership is 0 elsewhere, which min and max with the non-negative strengths leave out,
    /// and a set no lane fires has strength 0 in each lane (whose inputs are numbers: a NaN
    /// input gives a lane no defined strength), its clipped membership too, so each point gets
    /// the value `aggregated` gives it (min and max are exact in any order) for a fraction of
    /// the work (two sets at a point of an even partition, however many fire in the block).
    /// The point's membership is made in registers and summed at once, in grid order; a point
    /// adds exact zeros outside its own span, which leave its sums as they were. (A zero's
    /// sign, which the max of zeros may change, changes no sum.) Each point's work is the
    /// same, two sets, with no inner loop and no bounds check: W5 5 % faster than a loop over
    /// each point's one or two sets (BENCHMARKS.md).
    #[inline(always)]
    fn centroid_sums<R: Real, const A: usize, const MORE: bool>(
        &self,
        fire: &[&[R]; A],
        first: usize,
        last: usize,
    ) -> ([R; A], [R; A]) {
        let zero = R::zero();
        let (mut s0, mut s1) = ([zero; A], [zero; A]);
        if first > last {
            return (s0, s1);
        }
        let sets = self.output.sets.len();
        for f in fire {
            assert!(f.len() == sets, "a strength per output set");
        }
        // the point's membership: the larger of its two sets' clipped at their strengths
        let pair = |p: &GridPoint, f: &[R]| {
            debug_assert!(p.set[0] < sets && p.set[1] < sets);
            // SAFETY: every set index in `points` and `more` is below the number of output
            // sets (`new`), which is `f.len()` (asserted above)
            let (f0, f1) = unsafe { (f.get_unchecked(p.set[0]), f.get_unchecked(p.set[1])) };
            f0.min(R::splat(p.membership[0]))
                .max(f1.min(R::splat(p.membership[1])))
        };
        for (j, p) in (first..=last).zip(&self.points[first..=last]) {
            let mut m = [zero; A];
            for a in 0..A {
                m[a] = pair(p, fire[a]);
            }
            if MORE {
                for p in &self.more[self.more_at[j]..self.more_at[j + 1]] {
                    for a in 0..A {
                        m[a] = m[a].max(pair(p, fire[a]));
                    }
                }
            }
            let index = R::splat(p.index);
            for a in 0..A {
                s0[a] += m[a];
                s1[a] += m[a] * index;
            }
        }
        (s0, s1)
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
        let mut point = [R::zero(); MAX_INPUTS];
        for (i, p) in point.iter_mut().enumerate().take(self.inputs.len()) {
            *p = x[i];
        }
        self.evaluate_each(&[point])[0]
    }

    /// [`evaluate`](Self::evaluate) at `A` points at once (a law's axes; each point's inputs
    /// first, the rest of its row unread: `I` is at least [`Mamdani::n_inputs`], which the
    /// laws check when they are validated), each giving the bits it gives alone. Each point's
    /// two centroid sums are chains of dependent additions over the grid, in grid order; run
    /// in one loop, the points' chains advance side by side where one after another each
    /// would wait on its own.
    #[inline(always)]
    pub fn evaluate_each<R: Real, const A: usize, const I: usize>(
        &self,
        x: &[[R; I]; A],
    ) -> [R; A] {
        let zero = R::zero();
        let n = self.grid.len();
        // (loops, not `std::array::from_fn`: its closures are not inlined into a kernel
        // compiled for an instruction set, whose intrinsics then become calls)
        let mut slots = [Slots::<R, MAX_OUTPUT_SETS>::EMPTY; A];
        let mut fire: [&[R]; A] = [&[]; A];
        for ((f, slots), x) in fire.iter_mut().zip(&mut slots).zip(x) {
            *f = self.strengths(x, slots);
        }
        // per point, the output sets fired in some lane, and the grid points where one of
        // them is positive
        let mut active = [[0usize; MAX_OUTPUT_SETS]; A];
        let mut n_active = [0usize; A];
        let mut span = [(n, 0usize); A];
        for a in 0..A {
            for (k, f) in fire[a].iter().enumerate() {
                if f.simd_gt(zero).any() {
                    active[a][n_active[a]] = k;
                    n_active[a] += 1;
                    span[a].0 = span[a].0.min(self.support[k].0);
                    span[a].1 = span[a].1.max(self.support[k].1);
                }
            }
        }
        let first = span.iter().map(|s| s.0).min().unwrap_or(n);
        let last = span.iter().map(|s| s.1).max().unwrap_or(0);
        let (s0, s1) = if self.more.is_empty() {
            self.centroid_sums::<R, A, false>(&fire, first, last)
        } else {
            self.centroid_sums::<R, A, true>(&fire, first, last)
        };
        let h = (self.output.hi - self.output.lo) / (n - 1) as f64;
        let mut out = [zero; A];
        for (a, out) in out.iter_mut().enumerate() {
            let (first, last) = span[a];
            if first > last {
                continue;
            }
            let active = &active[a][..n_active[a]];
            let m0 = if first == 0 {
                self.aggregated(fire[a], active, 0)
            } else {
                zero
            };
            let mn = if last == n - 1 {
                self.aggregated(fire[a], active, n - 1)
            } else {
                zero
            };
            let area = s0[a] - (m0 + mn) * 0.5;
            let moment = s1[a] - mn * (0.5 * (n - 1) as f64) + (m0 - mn) / 6.0;
            let centroid = R::splat(self.output.lo) + moment * h / area;
            *out = R::select(area.simd_gt(zero), centroid, zero);
        }
        out
    }

    /// Each output set's firing strength at `x`, written in `slots`: the largest over its
    /// rules of the smallest membership of the rule's antecedents (every input set's
    /// membership evaluated once).
    #[inline(always)]
    fn strengths<'s, R: Real>(&self, x: &[R], slots: &'s mut Slots<R, MAX_OUTPUT_SETS>) -> &'s [R] {
        debug_assert!(x.len() >= self.inputs.len(), "one value per input");
        let mut memberships = [Slots::<R, MAX_INPUT_SETS>::EMPTY; MAX_INPUTS];
        let mut mu: [&[R]; MAX_INPUTS] = [&[]; MAX_INPUTS];
        for (((v, mu), slots), &x) in self.inputs.iter().zip(&mut mu).zip(&mut memberships).zip(x) {
            let xi = x.clamp(R::splat(v.lo), R::splat(v.hi));
            let mut row = slots.start();
            for set in &v.sets {
                row.push(set.eval_lanes(xi));
            }
            *mu = row.done();
        }
        let mut fire = slots.start();
        for _ in &self.output.sets {
            fire.push(R::zero());
        }
        let fire = fire.done();
        for r in &self.rules {
            let mut w = R::one();
            for (i, &a) in r.antecedent.iter().enumerate() {
                w = w.min(mu[i][a]);
            }
            fire[r.consequent] = fire[r.consequent].max(w);
        }
        fire
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
    use crate::fuzzy::Membership;

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

    /// The centroid as the definition reads, written apart from `evaluate`: every rule, every
    /// output set and every grid point, in grid order.
    fn naive(m: &Mamdani, x: &[f64]) -> f64 {
        let n = m.resolution();
        let mut fire = vec![0.0f64; m.output.sets.len()];
        for r in &m.rules {
            let w = r.antecedent.iter().enumerate().fold(1.0f64, |w, (i, &a)| {
                let v = &m.inputs[i];
                w.min(v.sets[a].eval(x[i].clamp(v.lo, v.hi)))
            });
            fire[r.consequent] = fire[r.consequent].max(w);
        }
        let mu: Vec<f64> = (0..n)
            .map(|j| {
                let y = m.grid[j];
                m.output
                    .sets
                    .iter()
                    .zip(&fire)
                    .fold(0.0f64, |acc, (s, &f)| acc.max(f.min(s.eval(y))))
            })
            .collect();
        let (s0, s1) = mu
            .iter()
            .enumerate()
            .fold((0.0, 0.0), |(s0, s1), (j, &v)| (s0 + v, s1 + v * j as f64));
        let (m0, mn) = (mu[0], mu[n - 1]);
        let h = (m.output.hi - m.output.lo) / (n - 1) as f64;
        let area = s0 - (m0 + mn) * 0.5;
        let moment = s1 - mn * (0.5 * (n - 1) as f64) + (m0 - mn) / 6.0;
        if area > 0.0 {
            m.output.lo + moment * h / area
        } else {
            0.0
        }
    }

    /// Systems with trapezoids, shoulders, sets narrower than the grid's step and uneven
    /// overlaps, at resolutions from 2 to 1000.
    fn odd_systems() -> Vec<Mamdani> {
        let s_in = Variable {
            lo: -5.0,
            hi: 5.0,
            sets: vec![
                Membership::Trapezoid(-5.0, -5.0, -3.0, 0.3),
                Membership::Triangle(-2.0, 0.1, 2.5),
                Membership::Trapezoid(-0.5, 2.0, 5.0, 5.0),
            ],
        };
        let d_in = Variable {
            lo: -5.0,
            hi: 5.0,
            sets: vec![
                Membership::Triangle(-5.0, -5.0, 1.0),
                Membership::Triangle(-1.0, 5.0, 5.0),
            ],
        };
        let out = Variable {
            lo: -4.0,
            hi: 4.0,
            sets: vec![
                Membership::Trapezoid(-4.0, -4.0, -1.0, 3.9),
                Membership::Triangle(-3.3, -1.0, 0.7),
                Membership::Triangle(-0.01, 0.0, 0.013),
                Membership::Trapezoid(0.5, 1.5, 2.2, 4.0),
                Membership::Triangle(3.0, 4.0, 4.0),
                // with sets 0, 3 and 4, four sets positive at a point (two pairs there)
                Membership::Triangle(-4.0, 0.0, 4.0),
            ],
        };
        let rules = [
            (0, 0, 0),
            (0, 1, 1),
            (1, 0, 2),
            (1, 1, 3),
            (2, 0, 4),
            (2, 1, 0),
            (2, 1, 5),
        ]
        .map(|(a, b, c)| Rule {
            antecedent: vec![a, b],
            consequent: c,
        })
        .to_vec();
        [2, 3, 31, 32, 33, 401, 1000]
            .into_iter()
            .map(|res| {
                Mamdani::new(
                    vec![s_in.clone(), d_in.clone()],
                    out.clone(),
                    rules.clone(),
                    res,
                )
                .unwrap()
            })
            .chain([2, 7, 401, 2001].map(variable_rate_system))
            .collect()
    }

    /// A system at every cap (4 inputs of 16 sets, 16 output sets, a rule for each output set
    /// and input set): its memberships and strengths fill the evaluation's slots.
    #[test]
    fn a_system_at_every_cap_has_the_bits_of_the_definition() {
        use crate::lanes::Lanes;
        let input = Variable {
            lo: -5.0,
            hi: 5.0,
            sets: even_triangles(-5.0, 5.0, MAX_INPUT_SETS),
        };
        let output = Variable {
            lo: -4.0,
            hi: 4.0,
            sets: even_triangles(-4.0, 4.0, MAX_OUTPUT_SETS),
        };
        // every input set and every output set in some rule; a rule fires where the inputs are
        // near one another, as they are below
        let rules = (0..MAX_INPUT_SETS)
            .map(|k| Rule {
                antecedent: vec![k; MAX_INPUTS],
                consequent: (7 * k + 3) % MAX_OUTPUT_SETS,
            })
            .collect();
        let m = Mamdani::new(vec![input; MAX_INPUTS], output, rules, 301).unwrap();
        let value = |i: usize| -5.5 + 11.0 * ((i * 37) % 101) as f64 / 100.0;
        let mut fired = 0;
        for start in 0..60 {
            let point = |p: usize| {
                let mut row = [Lanes::<8>([0.0; 8]); MAX_INPUTS];
                for (i, v) in row.iter_mut().enumerate() {
                    *v = Lanes(std::array::from_fn(|l| {
                        value(start + 13 * p + 3 * l) + 0.1 * i as f64
                    }));
                }
                row
            };
            let got = m.evaluate_each(&[point(0), point(1)]);
            for (p, got) in got.iter().enumerate() {
                let row = point(p);
                for l in 0..8 {
                    let x: Vec<f64> = row.iter().map(|v| v.0[l]).collect();
                    let want = naive(&m, &x);
                    fired += usize::from(want != 0.0);
                    assert_eq!(got.0[l].to_bits(), want.to_bits(), "point {p}, lane {l}");
                    assert_eq!(m.evaluate(&x).to_bits(), want.to_bits(), "{x:?}");
                }
            }
        }
        assert!(fired > 200, "too few inputs fire a rule: {fired}");
    }

    #[test]
    fn the_centroid_has_the_bits_of_the_definition_at_every_point_and_lane() {
        use crate::lanes::Lanes;
        // a deterministic spread of inputs: inside, on the corners, outside the universe
        let xs: Vec<f64> = (0..97)
            .map(|i| -6.5 + 13.0 * ((i * 37) % 97) as f64 / 96.0)
            .collect();
        let mut fired = 0;
        for m in odd_systems() {
            for (i, &a) in xs.iter().enumerate() {
                let b = xs[(i * 11 + 5) % xs.len()];
                let want = naive(&m, &[a, b]);
                fired += usize::from(want != 0.0);
                assert_eq!(m.evaluate(&[a, b]).to_bits(), want.to_bits(), "({a}, {b})");
            }
            // three points of eight lanes each at once, every lane the bits of the definition
            for start in (0..xs.len() - 24).step_by(7) {
                let point = |p: usize| {
                    let mut row = [Lanes::<8>([0.0; 8]); MAX_INPUTS];
                    row[0] = Lanes(std::array::from_fn(|l| xs[start + 8 * p + l]));
                    row[1] = Lanes(std::array::from_fn(|l| {
                        xs[(start + 8 * p + l) * 5 % xs.len()]
                    }));
                    row
                };
                let got = m.evaluate_each(&[point(0), point(1), point(2)]);
                for (p, got) in got.iter().enumerate() {
                    let row = point(p);
                    for l in 0..8 {
                        let want = naive(&m, &[row[0].0[l], row[1].0[l]]);
                        assert_eq!(got.0[l].to_bits(), want.to_bits(), "point {p}, lane {l}");
                    }
                }
            }
        }
        assert!(fired > 500, "too few inputs fire a rule: {fired}");
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
