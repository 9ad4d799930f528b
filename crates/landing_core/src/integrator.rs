//! Fixed-step integrators.
//!
//! An integrator advances `x' = f(t, x)` by one step `h`; the rollout calls it `substeps` times
//! per control period with the command held. The derivative is asked for at a [`Stage`] of the
//! step (its start, middle or end) rather than at a bare time, so that the caller can look up
//! what depends on time alone (the deterministic disturbance) once per stage for a whole batch.
//!
//! The integrator is chosen at run time: the `match` per step is perfectly predicted and costs
//! nothing measurable, where a type parameter would double the compiled rollouts.

use crate::lanes::Real;
use crate::state::State;

/// Where in a step `[t, t + h]` the derivative is evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stage {
    /// `t`
    Start,
    /// `t + h/2`
    Middle,
    /// `t + h`
    End,
}

impl Stage {
    /// The stage's position in [`IntegratorKind::stages`] (a step's stages are a prefix of
    /// start, middle, end).
    #[inline(always)]
    pub fn index(self) -> usize {
        match self {
            Stage::Start => 0,
            Stage::Middle => 1,
            Stage::End => 2,
        }
    }

    /// The stage's time in the step `[t, t + h]`.
    #[inline(always)]
    pub fn time(self, t: f64, h: f64) -> f64 {
        match self {
            Stage::Start => t,
            Stage::Middle => t + 0.5 * h,
            Stage::End => t + h,
        }
    }
}

/// `x'` at a stage of the current step: what an integrator steps. A trait with an
/// `#[inline(always)]` method rather than a closure, so that the whole derivative is inlined
/// into the kernel (a closure call left out of line would be compiled at the baseline level).
pub trait StageDerivative<R: Real, S: State<R>> {
    fn at(&self, stage: Stage, x: &S) -> S;

    /// [`at`](Self::at) written into `k`. A derivative of a large state overrides it to write
    /// in place: returned by value, a state of kilobytes was copied out of the plant's
    /// derivative at every stage (BENCHMARKS.md, W6).
    #[inline(always)]
    fn at_into(&self, stage: Stage, x: &S, k: &mut S) {
        *k = self.at(stage, x);
    }
}

impl<R: Real, S: State<R>, F: Fn(Stage, &S) -> S> StageDerivative<R, S> for F {
    #[inline(always)]
    fn at(&self, stage: Stage, x: &S) -> S {
        self(stage, x)
    }
}

crate::named! {
    /// The integrators, by name at the Python boundary.
    pub enum IntegratorKind {
        /// Classic four-stage Runge-Kutta.
        Rk4 => "rk4",
        /// Forward Euler.
        Euler => "euler",
    }
}

impl IntegratorKind {
    /// Convergence order (global error ~ h^ORDER), for documentation and tests.
    pub fn order(self) -> u32 {
        match self {
            Self::Rk4 => 4,
            Self::Euler => 1,
        }
    }

    /// The distinct stages a step evaluates, in order.
    pub fn stages(self) -> &'static [Stage] {
        match self {
            Self::Rk4 => &[Stage::Start, Stage::Middle, Stage::End],
            Self::Euler => &[Stage::Start],
        }
    }

    /// The method's Butcher tableau, in the form its step uses.
    fn tableau(self) -> &'static Tableau {
        match self {
            Self::Rk4 => &RK4,
            Self::Euler => &EULER,
        }
    }

    /// One step of length `h` from `x` into `next`, with `f(stage, y)` the derivative at that
    /// stage. `scratch` may hold anything on entry: a large state's stage point and stage
    /// derivative are written there (see below).
    ///
    /// Both methods run through one loop over their tableau's stages, so the derivative (the
    /// bulk of the code) is inlined once, whatever the method: the choice of method is a
    /// number of stages and a few coefficients read at run time, not a second copy. The
    /// stage point and the weighted sum are updated in place (see [`State`]). A caller that
    /// computes the derivatives elsewhere (a plant written in Python, one call per stage for
    /// every case) runs the same step stage by stage: [`Self::accumulate`] for each stage, then
    /// [`Self::combine`].
    ///
    /// A state that fits the vector registers (a lander's block) keeps its stage point and
    /// derivative in locals, copies of `x` the compiler leaves in registers. A larger one
    /// (the flexible tether's 38 components, 2.4 kB a block) would pay a `memcpy` for each
    /// of those copies and one more for the first stage's `sum = k`: it uses the caller's
    /// `scratch` instead, and its first stage of weight 1 (both methods') is evaluated
    /// straight into the sum. The same operations either way, so the same bits. Measured
    /// (BENCHMARKS.md): the large path makes W6 7 % faster, and W1 (896 bytes a block) 20 %
    /// slower, its stage values sent through memory.
    #[inline(always)]
    pub fn step_into<R: Real, S: State<R>>(
        self,
        f: &impl StageDerivative<R, S>,
        x: &S,
        h: f64,
        next: &mut S,
        scratch: &mut [S; 2],
    ) {
        // `next` holds the weighted sum of the stage derivatives until the last line
        let tab = self.tableau();
        if const { std::mem::size_of::<S>() <= IN_REGISTERS } {
            let mut y = *x;
            let mut k = *x;
            for i in 0..tab.stages {
                f.at_into(self.stage(i), if i == 0 { x } else { &y }, &mut k);
                self.accumulate(i, x, &k, h, next, &mut y);
            }
        } else {
            let [y, k] = scratch;
            for i in 0..tab.stages {
                if i == 0 && tab.weight[0] == 1.0 {
                    // `sum = 1 k0` is `k0`, bit for bit (as `accumulate` makes it)
                    f.at_into(self.stage(0), x, next);
                    if tab.stages > 1 {
                        y.set_add_scaled(x, next, R::splat(tab.next[0] * h));
                    }
                } else {
                    f.at_into(self.stage(i), if i == 0 { x } else { y }, k);
                    self.accumulate(i, x, k, h, next, y);
                }
            }
        }
        self.combine(x, h, next);
    }

    /// Number of derivative evaluations per step (RK4: 4, two of them at the middle).
    pub fn evaluations(self) -> usize {
        self.tableau().stages
    }

    /// Where evaluation `i` of a step lies.
    #[inline(always)]
    pub fn stage(self, i: usize) -> Stage {
        self.tableau().at[i]
    }

    /// Adds evaluation `i`'s derivative `k` (at `x` for the first, at `y` for the others) to
    /// the weighted sum `sum` and, unless it is the last, moves `y` to the next evaluation's
    /// point.
    #[inline(always)]
    pub fn accumulate<R: Real, S: State<R>>(
        self,
        i: usize,
        x: &S,
        k: &S,
        h: f64,
        sum: &mut S,
        y: &mut S,
    ) {
        let tab = self.tableau();
        // a weight of 1 multiplies nothing: `k * 1` is `k`, bit for bit
        let w = tab.weight[i];
        match (i == 0, w == 1.0) {
            (true, true) => *sum = *k,
            (true, false) => sum.set_scaled(k, R::splat(w)),
            (false, true) => sum.add_assign_state(k),
            (false, false) => sum.add_scaled_assign(k, R::splat(w)),
        }
        if i + 1 < tab.stages {
            y.set_add_scaled(x, k, R::splat(tab.next[i] * h));
        }
    }

    /// The step's end: the weighted sum `sum` becomes the new state, `x + sum h / divisor`.
    #[inline(always)]
    pub fn combine<R: Real, S: State<R>>(self, x: &S, h: f64, sum: &mut S) {
        let c = R::splat(h / self.tableau().divisor);
        for i in 0..S::DIM {
            // x + sum c, written over the sum
            let v = sum.component(i).mul_add(c, x.component(i));
            sum.set_component(i, v);
        }
    }

    /// One step of length `h` from `x`: [`Self::step_into`] returning the new state.
    #[inline(always)]
    pub fn step<R: Real, S: State<R>>(self, f: &impl StageDerivative<R, S>, x: &S, h: f64) -> S {
        let mut next = *x;
        self.step_into(f, x, h, &mut next, &mut [*x; 2]);
        next
    }
}

/// The largest state (in bytes, a block's) that [`IntegratorKind::step_into`] keeps in locals:
/// half of AVX-512's 32 registers, so that the step's other values fit beside it.
const IN_REGISTERS: usize = 16 * 64;

/// An explicit Runge-Kutta method whose stage i evaluates at `x + next[i-1] h k_(i-1)` (a
/// diagonal tableau, as Euler's and the classic RK4's are) and whose step is
/// `x + (h / divisor) sum_i weight_i k_i`.
struct Tableau {
    stages: usize,
    at: [Stage; 4],
    next: [f64; 4],
    weight: [f64; 4],
    divisor: f64,
}

const RK4: Tableau = Tableau {
    stages: 4,
    at: [Stage::Start, Stage::Middle, Stage::Middle, Stage::End],
    next: [0.5, 0.5, 1.0, 0.0],
    weight: [1.0, 2.0, 2.0, 1.0],
    divisor: 6.0,
};

const EULER: Tableau = Tableau {
    stages: 1,
    at: [Stage::Start; 4],
    next: [0.0; 4],
    weight: [1.0, 0.0, 0.0, 0.0],
    divisor: 1.0,
};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::Lanes;
    use nalgebra::{SVector, Vector1, Vector2};

    /// Global error at t = 5 of the harmonic oscillator x'' = -x, x(0) = 1, x'(0) = 0, whose
    /// solution is (cos t, -sin t).
    fn oscillator_error(integ: IntegratorKind, h: f64) -> f64 {
        let f = |_s: Stage, x: &Vector2<f64>| Vector2::new(x[1], -x[0]);
        let n = (5.0 / h).round() as usize;
        let mut x = Vector2::new(1.0, 0.0);
        for _ in 0..n {
            x = integ.step(&f, &x, h);
        }
        let t = n as f64 * h;
        (x - Vector2::new(t.cos(), -t.sin())).norm()
    }

    /// Global error at t = 2 of the time-dependent x' = x cos t, x(0) = 1 (x = e^{sin t}):
    /// checks that stage times are the right ones.
    fn time_dependent_error(integ: IntegratorKind, h: f64) -> f64 {
        let n = (2.0 / h).round() as usize;
        let mut x = Vector1::new(1.0);
        for k in 0..n {
            let t = k as f64 * h;
            let f = |s: Stage, x: &Vector1<f64>| *x * s.time(t, h).cos();
            x = integ.step(&f, &x, h);
        }
        (x[0] - (n as f64 * h).sin().exp()).abs()
    }

    fn observed_order(e_coarse: f64, e_fine: f64) -> f64 {
        (e_coarse / e_fine).log2()
    }

    #[test]
    fn rk4_is_fourth_order() {
        for err in [oscillator_error, time_dependent_error] {
            let e = [0.1, 0.05, 0.025].map(|h| err(IntegratorKind::Rk4, h));
            for w in e.windows(2) {
                let p = observed_order(w[0], w[1]);
                assert!((p - 4.0).abs() < 0.15, "observed order {p}, errors {e:?}");
            }
        }
    }

    #[test]
    fn euler_is_first_order() {
        for err in [oscillator_error, time_dependent_error] {
            let e = [0.004, 0.002, 0.001].map(|h| err(IntegratorKind::Euler, h));
            for w in e.windows(2) {
                let p = observed_order(w[0], w[1]);
                assert!((p - 1.0).abs() < 0.05, "observed order {p}, errors {e:?}");
            }
        }
    }

    /// A state too large for the registers (40 components of 4 lanes, 1280 bytes) steps by
    /// the other path of `step_into` (the caller's scratch, the first stage into the sum):
    /// each of its 20 pairs must come out bit for bit as the same pair stepped alone (2
    /// components, the path of the small states), whatever the scratch held (NaN here).
    #[test]
    fn a_large_state_steps_as_its_parts_alone() {
        type Big = SVector<Lanes<4>, 40>;
        type Pair = SVector<Lanes<4>, 2>;
        assert!(std::mem::size_of::<Big>() > IN_REGISTERS);
        assert!(std::mem::size_of::<Pair>() <= IN_REGISTERS);
        let (h, t0) = (0.01, 0.3);
        // x'' = -x^2 + cos t per pair, each pair with its own start
        let stage_big = |s: Stage, x: &Big| {
            let mut k = *x;
            for p in 0..20 {
                k[2 * p] = x[2 * p + 1];
                k[2 * p + 1] = -x[2 * p] * x[2 * p] + Lanes::splat(s.time(t0, h).cos());
            }
            k
        };
        let stage_pair =
            |s: Stage, x: &Pair| Pair::new(x[1], -x[0] * x[0] + Lanes::splat(s.time(t0, h).cos()));
        let start = |p: usize, i: usize| (p as f64 - 9.5) * 0.1 + i as f64 * 0.01;
        for integ in [IntegratorKind::Rk4, IntegratorKind::Euler] {
            let mut big = Big::from_fn(|c, _| Lanes(std::array::from_fn(|i| start(c / 2, i))));
            let mut pairs: Vec<Pair> = (0..20)
                .map(|p| Pair::new(Lanes(std::array::from_fn(|i| start(p, i))), Lanes([0.5; 4])))
                .collect();
            for p in 0..20 {
                big[2 * p + 1] = Lanes([0.5; 4]);
            }
            for _ in 0..50 {
                let mut next = big;
                let mut scratch = [Big::repeat(Lanes::splat(f64::NAN)); 2];
                integ.step_into(&stage_big, &big, h, &mut next, &mut scratch);
                big = next;
                for x in pairs.iter_mut() {
                    *x = integ.step(&stage_pair, x, h);
                }
            }
            for (p, x) in pairs.iter().enumerate() {
                for c in 0..2 {
                    for i in 0..4 {
                        assert_eq!(
                            big[2 * p + c].0[i].to_bits(),
                            x[c].0[i].to_bits(),
                            "{integ:?}, pair {p}, component {c}, lane {i}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn lanes_step_each_case_as_alone() {
        let x0 = [1.0, 0.3, -2.0, 7.0];
        let f1 = |_s: Stage, x: &SVector<f64, 2>| SVector::<f64, 2>::new(x[1], -x[0] * x[0]);
        let f4 =
            |_s: Stage, x: &SVector<Lanes<4>, 2>| SVector::<Lanes<4>, 2>::new(x[1], -x[0] * x[0]);
        let mut xl = SVector::<Lanes<4>, 2>::new(Lanes(x0), Lanes([0.0; 4]));
        let mut xs = x0.map(|v| SVector::<f64, 2>::new(v, 0.0));
        for _ in 0..100 {
            xl = IntegratorKind::Rk4.step(&f4, &xl, 0.01);
            for x in xs.iter_mut() {
                *x = IntegratorKind::Rk4.step(&f1, x, 0.01);
            }
        }
        for (i, x) in xs.iter().enumerate() {
            assert_eq!(xl[0].0[i].to_bits(), x[0].to_bits());
            assert_eq!(xl[1].0[i].to_bits(), x[1].to_bits());
        }
    }
}
