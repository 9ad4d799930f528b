//! Lumped unknown disturbances (a_p of seed 001 eq. 30 and 47).
//!
//! The disturbance is a generalized acceleration added to q'' by the plant; the laws never see
//! it. Deterministic parts are evaluated at each integrator stage's time; the random part is
//! drawn once per control period from the case's counter-based stream and held.

use nalgebra::SVector;

use crate::error::{ParamError, ReadError, Validate, check};
use crate::lanes::{Gather, Real, add, mul, scale_by, zeros};
use crate::params::{FromParams, Kinds, Layout, Named, Param, ParamSource, Schema, Table, Values};
use crate::rng::{CaseStream, streams};

const VALUE: Param = Param::axes("value")
    .unit("q/s^2")
    .doc("the constant acceleration");
const AMPLITUDE: Param = Param::axes("amplitude")
    .unit("q/s^2")
    .doc("amplitude A of A sin(omega t + phase)");
const OMEGA: Param = Param::axes("omega").unit("rad/s").doc("angular frequency");
const PHASE: Param = Param::axes("phase").unit("rad").doc("phase at t = 0");
const BOUND: Param = Param::axes("bound")
    .unit("q/s^2")
    .rule("bound >= 0")
    .doc("uniform on [-bound, bound], drawn once per control period and held");
const FRACTION: Param = Param::axes("fraction")
    .unit("1")
    .rule("fraction >= 0")
    .doc("uniform on [-fraction, fraction] times the commanded acceleration, drawn per period");

/// A disturbance's table: its components, which add up.
pub const COMPONENTS: Param = Param::list("components", Layout::Family("disturbance"))
    .doc("the components, each a table of one of the component kinds");

crate::named! {
    /// The disturbance components' kinds at the Python boundary, and whether each draws
    /// random numbers.
    pub enum ComponentKind in "disturbance" {
        Constant => "constant": Schema::component(&[VALUE], false),
        Sinusoid => "sinusoid": Schema::component(&[AMPLITUDE, OMEGA, PHASE], false),
        UniformNoise => "uniform_noise": Schema::component(&[BOUND], true),
        CommandNoise => "command_noise": Schema::component(&[FRACTION], true),
    }
}

/// The disturbance components' kinds' names.
pub const COMPONENT_KINDS: &[&str] = ComponentKind::NAMES;

/// Most sinusoidal components one disturbance carries (kept fixed so the type stays `Copy`).
pub const MAX_SINUSOIDS: usize = 4;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sinusoid<const D: usize, R = f64> {
    pub amplitude: SVector<R, D>,
    /// Angular frequency, rad/s.
    pub omega: SVector<R, D>,
    pub phase: SVector<R, D>,
}

crate::gather_struct!(Sinusoid<const D: usize, R> { lanes: [amplitude, omega, phase], shared: [] });

/// `d(t) = constant + sum_j A_j sin(omega_j t + phase_j) + n_k + r_k * a_k`, with `n_k` uniform
/// on `[-bound, bound]` and `r_k` uniform on `[-relative, relative]` per axis, both drawn for
/// control period k, and `a_k` the commanded acceleration applied over that period (the applied
/// command over the inertia): seed 002's model uncertainty of up to 1 % of the command.
///
/// The deterministic part depends on time alone; a batch whose cases share it evaluates it once
/// per integrator stage for all of them (see [`crate::batch`]), with the same operations as
/// [`Disturbance::deterministic`], so the bits do not depend on which path ran.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Disturbance<const D: usize, R = f64> {
    pub constant: SVector<R, D>,
    sinusoids: [Sinusoid<D, R>; MAX_SINUSOIDS],
    /// Whether sinusoid j has the same frequency and phase on every axis (of every lane): one
    /// sine then serves all axes.
    in_phase: [bool; MAX_SINUSOIDS],
    n_sinusoids: usize,
    pub noise_bound: SVector<R, D>,
    pub relative_bound: SVector<R, D>,
    /// Whether any lane draws additive noise, and command noise.
    noisy: bool,
    command_noisy: bool,
}

impl<const D: usize> Default for Disturbance<D> {
    fn default() -> Self {
        let zero = zeros();
        Self {
            constant: zero,
            sinusoids: [Sinusoid {
                amplitude: zero,
                omega: zero,
                phase: zero,
            }; MAX_SINUSOIDS],
            in_phase: [false; MAX_SINUSOIDS],
            n_sinusoids: 0,
            noise_bound: zero,
            relative_bound: zero,
            noisy: false,
            command_noisy: false,
        }
    }
}

impl<const D: usize, R: Real> Gather<R> for Disturbance<D, R> {
    type Case = Disturbance<D>;

    fn gather<'a>(case: &dyn Fn(usize) -> &'a Self::Case) -> Self {
        let lanes = 0..R::LANES;
        let n = case(0).n_sinusoids;
        let mut in_phase = [false; MAX_SINUSOIDS];
        for (j, p) in in_phase.iter_mut().enumerate().take(n) {
            *p = lanes.clone().all(|i| case(i).in_phase[j]);
        }
        Self {
            constant: Gather::gather(&|i| &case(i).constant),
            sinusoids: Gather::gather(&|i| &case(i).sinusoids),
            in_phase,
            n_sinusoids: n,
            noise_bound: Gather::gather(&|i| &case(i).noise_bound),
            relative_bound: Gather::gather(&|i| &case(i).relative_bound),
            noisy: lanes.clone().any(|i| case(i).noisy),
            command_noisy: lanes.clone().any(|i| case(i).command_noisy),
        }
    }

    fn same_shape(a: &Self::Case, b: &Self::Case) -> bool {
        a.n_sinusoids == b.n_sinusoids
    }
}

impl<const D: usize> Disturbance<D> {
    pub fn none() -> Self {
        Self::default()
    }

    pub fn with_constant(mut self, value: SVector<f64, D>) -> Self {
        self.constant += value;
        self
    }

    pub fn with_noise(mut self, bound: SVector<f64, D>) -> Self {
        self.noise_bound += bound;
        self.noisy = self.noise_bound.iter().any(|&b| b > 0.0);
        self
    }

    /// Adds a random disturbance of up to `fraction` of the commanded acceleration per axis.
    pub fn with_command_noise(mut self, fraction: SVector<f64, D>) -> Self {
        self.relative_bound += fraction;
        self.command_noisy = self.relative_bound.iter().any(|&b| b > 0.0);
        self
    }

    /// Adds a sinusoid; fails past [`MAX_SINUSOIDS`] components.
    pub fn with_sinusoid(mut self, s: Sinusoid<D>) -> Result<Self, ParamError> {
        if self.n_sinusoids == MAX_SINUSOIDS {
            return Err(ParamError::new(
                "disturbance",
                (MAX_SINUSOIDS + 1) as f64,
                "at most 4 sinusoidal components",
            ));
        }
        self.sinusoids[self.n_sinusoids] = s;
        self.in_phase[self.n_sinusoids] =
            (1..D).all(|i| s.omega[i] == s.omega[0] && s.phase[i] == s.phase[0]);
        self.n_sinusoids += 1;
        Ok(self)
    }

    /// Both disturbances acting together (their components add up); fails past
    /// [`MAX_SINUSOIDS`] sinusoids.
    pub fn add(&self, other: &Self) -> Result<Self, ParamError> {
        let mut d = self
            .with_constant(other.constant)
            .with_noise(other.noise_bound)
            .with_command_noise(other.relative_bound);
        for s in other.sinusoids() {
            d = d.with_sinusoid(*s)?;
        }
        Ok(d)
    }

    pub fn sinusoids(&self) -> &[Sinusoid<D>] {
        &self.sinusoids[..self.n_sinusoids]
    }

    pub fn has_noise(&self) -> bool {
        self.noisy
    }

    pub fn has_command_noise(&self) -> bool {
        self.command_noisy
    }

    /// Whether the deterministic part varies in time (has sinusoids).
    pub fn is_time_varying(&self) -> bool {
        self.n_sinusoids > 0
    }

    /// Bound on |d_i(t)| per axis (used by the theory's practical fixed-time neighbourhoods),
    /// leaving out the part proportional to the command, whose bound depends on the law.
    pub fn bound(&self) -> SVector<f64, D> {
        let mut b = self.constant.abs() + self.noise_bound;
        for s in self.sinusoids() {
            b += s.amplitude.abs();
        }
        b
    }
}

impl<const D: usize, R: Real> Disturbance<D, R> {
    /// Whether any lane draws random numbers each control period.
    #[inline(always)]
    pub fn is_random(&self) -> bool {
        self.noisy || self.command_noisy
    }

    /// The random draws for control period `period`, lane i from the streams of its case
    /// (`rng[i]`), with `command` the commanded acceleration applied over the period.
    #[inline(always)]
    pub fn draw(
        &self,
        rng: &[NoiseStreams],
        period: u64,
        command: &SVector<R, D>,
    ) -> SVector<R, D> {
        let mut held = zeros();
        if self.noisy {
            let u = lane_uniforms::<D, R>(rng, period, |s| &s.additive);
            held = add(&held, &mul(&self.noise_bound, &u));
        }
        if self.command_noisy {
            let u = lane_uniforms::<D, R>(rng, period, |s| &s.relative);
            held = add(&held, &mul(&mul(&self.relative_bound, &u), command));
        }
        held
    }

    /// The deterministic part at time `t`.
    #[inline(always)]
    pub fn deterministic(&self, t: f64) -> SVector<R, D> {
        let mut d = self.constant;
        for j in 0..self.n_sinusoids {
            let s = &self.sinusoids[j];
            if self.in_phase[j] {
                d = add(
                    &d,
                    &scale_by(&s.amplitude, (s.omega[0] * t + s.phase[0]).sin()),
                );
            } else {
                for i in 0..D {
                    d[i] += s.amplitude[i] * (s.omega[i] * t + s.phase[i]).sin();
                }
            }
        }
        d
    }
}

impl<const D: usize> Validate for Disturbance<D> {
    fn validate(&self) -> Result<(), ParamError> {
        for i in 0..D {
            let on_axis = |e: ParamError| e.on_axis(i);
            // a sum of constants is named for the component, as the user gave it
            crate::error::require(true, "constant", self.constant[i], "").map_err(on_axis)?;
            check(&BOUND, self.noise_bound[i], |b| b >= 0.0).map_err(on_axis)?;
            check(&FRACTION, self.relative_bound[i], |f| f >= 0.0).map_err(on_axis)?;
            for s in self.sinusoids() {
                check(&AMPLITUDE, s.amplitude[i], |_| true).map_err(on_axis)?;
                check(&OMEGA, s.omega[i], |_| true).map_err(on_axis)?;
                check(&PHASE, s.phase[i], |_| true).map_err(on_axis)?;
            }
        }
        Ok(())
    }
}

/// Uniforms on [-1, 1) per axis for a control period, lane by lane from each case's stream:
/// ceil(D / 4) Philox blocks per period, so axes never share a word.
#[inline]
fn lane_uniforms<const D: usize, R: Real>(
    rng: &[NoiseStreams],
    period: u64,
    stream: impl Fn(&NoiseStreams) -> &CaseStream,
) -> SVector<R, D> {
    let blocks = D.div_ceil(4) as u64;
    let mut u: SVector<R, D> = zeros();
    let mut one = [0.0f64; D];
    for (i, s) in rng.iter().enumerate().take(R::LANES) {
        stream(s).fill_uniforms(period * blocks, &mut one);
        for k in 0..D {
            u[k].set_lane(i, one[k] * 2.0 - 1.0);
        }
    }
    u
}

/// The random streams a case's disturbance draws from.
#[derive(Clone, Copy, Debug)]
pub struct NoiseStreams {
    additive: CaseStream,
    relative: CaseStream,
}

/// The streams of case `case` under `seed`.
pub fn disturbance_stream(seed: u64, case: u64) -> NoiseStreams {
    NoiseStreams {
        additive: CaseStream::new(seed, streams::DISTURBANCE, case),
        relative: CaseStream::new(seed, streams::COMMAND_NOISE, case),
    }
}

/// The disturbances, read and validated for each axis count ([`crate::params::ByAxes`]).
pub struct Disturbances;

impl crate::params::ReadFor for Disturbances {
    type At<const D: usize> = Disturbance<D>;
    fn read<const D: usize>(
        p: &mut crate::params::Reader<'_>,
    ) -> Result<Disturbance<D>, ReadError> {
        crate::params::read_valid(p)
    }
}

impl<const D: usize> FromParams for Disturbance<D> {
    /// A list `components` of tables, each with a `kind`: `constant` (value), `sinusoid`
    /// (amplitude, omega, phase), `uniform_noise` (bound) or `command_noise` (fraction); they
    /// add up.
    fn from_params<S: ParamSource>(p: &mut S) -> Result<Self, ReadError> {
        let mut d = Disturbance::none();
        for j in 0..p.list_len(&COMPONENTS)? {
            d = p.list_item(&COMPONENTS, j, |c| {
                Ok(match c.kind::<ComponentKind>()? {
                    ComponentKind::Constant => d.with_constant(c.axes(&VALUE)?),
                    ComponentKind::Sinusoid => d.with_sinusoid(Sinusoid {
                        amplitude: c.axes(&AMPLITUDE)?,
                        omega: c.axes(&OMEGA)?,
                        phase: c.axes(&PHASE)?,
                    })?,
                    ComponentKind::UniformNoise => d.with_noise(c.axes(&BOUND)?),
                    ComponentKind::CommandNoise => d.with_command_noise(c.axes(&FRACTION)?),
                })
            })?;
        }
        Ok(d)
    }
}

/// The components of a disturbance's table (`{"components": [...]}`), `owner` naming it in the
/// error when it has none.
pub fn components_of(table: &Table, owner: &str) -> Result<Vec<Table>, ReadError> {
    let list = table.list(COMPONENTS.name).ok_or_else(|| {
        ReadError::type_(format!(
            "{owner}: a disturbance table has a list 'components'"
        ))
    });
    list.map(<[Table]>::to_vec)
}

/// The numeric parameter `name` of the one component of `components` that declares it, as
/// read for `axes` axes.
pub fn component_values(
    components: &[Table],
    name: &str,
    axes: usize,
) -> Result<Values, ReadError> {
    let declares = |c: &&Table| {
        c.kind()
            .and_then(ComponentKind::from_name)
            .is_some_and(|k| k.schema().param(name).is_some())
    };
    let mut found = components.iter().filter(declares);
    match (found.next(), found.next()) {
        (Some(c), None) => c.values::<ComponentKind>(name, axes),
        (None, _) => Err(ReadError::value(format!(
            "unknown parameter {name:?}; the components are {:?}",
            components
                .iter()
                .filter_map(Table::kind)
                .collect::<Vec<_>>()
        ))),
        (Some(_), Some(_)) => Err(ReadError::value(format!(
            "{name} is a parameter of several components; ask one component"
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;

    #[test]
    fn deterministic_parts_add_up() {
        let d = Disturbance::<3>::none()
            .with_constant(Vector3::new(1.0, 0.0, -1.0))
            .with_sinusoid(Sinusoid {
                amplitude: Vector3::repeat(20.0),
                omega: Vector3::repeat(1.0),
                phase: Vector3::new(0.0, 0.5, 0.0),
            })
            .unwrap();
        let v = d.deterministic(0.3);
        assert!((v[0] - (1.0 + 20.0 * 0.3f64.sin())).abs() < 1e-14);
        assert!((v[1] - 20.0 * 0.8f64.sin()).abs() < 1e-14);
        assert_eq!(d.bound(), Vector3::new(21.0, 20.0, 21.0));
    }

    #[test]
    fn noise_is_bounded_held_and_reproducible() {
        let d = Disturbance::<3>::none().with_noise(Vector3::new(0.5, 1.0, 0.0));
        let s = [disturbance_stream(11, 4)];
        let mut max = Vector3::<f64>::zeros();
        for k in 0..5000 {
            let n = d.draw(&s, k, &Vector3::zeros());
            max = max.sup(&n.abs());
            assert_eq!(n, d.draw(&s, k, &Vector3::zeros()));
        }
        assert!(max[0] <= 0.5 && max[0] > 0.49);
        assert!(max[1] <= 1.0 && max[1] > 0.98);
        assert_eq!(max[2], 0.0);
    }

    #[test]
    fn command_noise_scales_with_the_command() {
        let d = Disturbance::<3>::none().with_command_noise(Vector3::repeat(0.01));
        let s = [disturbance_stream(3, 1)];
        let a = Vector3::new(2.0, -0.5, 0.0);
        let mut seen: f64 = 0.0;
        for k in 0..2000 {
            let n = d.draw(&s, k, &a);
            assert!(n[0].abs() <= 0.02 && n[1].abs() <= 0.005 && n[2] == 0.0);
            // the same draw scales linearly with the command
            assert!((d.draw(&s, k, &(a * 3.0)) - n * 3.0).norm() < 1e-15);
            seen = seen.max(n[0].abs());
        }
        assert!(seen > 0.0195);
    }
}
