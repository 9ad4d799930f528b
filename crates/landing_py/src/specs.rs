//! From the Python layer's parameter tables to typed core values, dispatched once per batch.
//!
//! A table is a dict with a `kind` and the parameters of that kind (see `python/landing`).
//! Laws and references are generic in the number of axes D, fixed by the plant.

use nalgebra::{SVector, Vector3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::PerCase;
use std::sync::Arc;

use landing_core::control::{
    ControlLaw, FastTerminalSmc, FixedTimeMss, FixedTimeNtsmc, FuzzyFastTerminalSmc,
    FuzzyVariableRate, IntegralExponentialReaching, IntegralSurface, MssVariant, Ntsmc, OpenLoop,
    PdSlidingMode, SuperTwisting, SuperTwistingVariant, TerminalSurface,
};
use landing_core::disturbance::{Disturbance, MAX_SINUSOIDS, Sinusoid};
use landing_core::gravity::{Harmonic2, PointMass, TwoPointMass, Uniform};
use landing_core::math::Switch;
use landing_core::plant::tether::{
    TetherBody, TetheredFlexible, TetheredFlexible2, TetheredFlexible4, TetheredFlexible8,
    TetheredFlexible16, TetheredSimplified, orbital_rate,
};
use landing_core::plant::{DoubleIntegrator, MarsLander, SmallBody};
use landing_core::reference::Reference;

use crate::errors::{InputError, param_error};
use crate::fuzzy_spec::parse_mamdani;
use crate::gravity_spec::{GravitySpec, parse_gravity_into};
use crate::params::{Params, pick};

pub fn kind_of(dict: &Bound<'_, PyDict>, what: &str) -> Result<String, InputError> {
    dict.get_item("kind")?
        .and_then(|k| k.extract::<String>().ok())
        .ok_or_else(|| InputError::Type(format!("{what} table has no 'kind'")))
}

pub enum PlantSpec {
    Mars(PerCase<MarsLander>),
    DoubleIntegrator(PerCase<DoubleIntegrator>),
    SmallBodyPointMass(PerCase<SmallBody<PointMass>>),
    SmallBodyTwoPointMass(PerCase<SmallBody<TwoPointMass>>),
    SmallBodyHarmonic2(PerCase<SmallBody<Harmonic2>>),
    TetherSimplified(PerCase<TetheredSimplified>),
    TetherFlexible2(PerCase<TetheredFlexible2>),
    TetherFlexible4(PerCase<TetheredFlexible4>),
    TetherFlexible8(PerCase<TetheredFlexible8>),
    TetherFlexible16(PerCase<TetheredFlexible16>),
}

/// The node counts of the flexible tether that the bindings dispatch on (each one is its own
/// fixed-size state type): enough for the refinement study to show convergence, few enough to
/// keep the number of monomorphised rollouts small.
pub const TETHER_NODES: [usize; 4] = [2, 4, 8, 16];

/// Runs `$body` with `$plants` bound to the typed plants of a `PlantSpec` and `$d` to their
/// number of axes (a const usable as a generic argument): the dispatch on the plant.
macro_rules! with_plants {
    ($spec:expr, $plants:ident, $d:ident => $body:expr) => {
        match $spec {
            PlantSpec::Mars($plants) => {
                const $d: usize = 3;
                $body
            }
            PlantSpec::DoubleIntegrator($plants) => {
                const $d: usize = 3;
                $body
            }
            PlantSpec::SmallBodyPointMass($plants) => {
                const $d: usize = 3;
                $body
            }
            PlantSpec::SmallBodyTwoPointMass($plants) => {
                const $d: usize = 3;
                $body
            }
            PlantSpec::SmallBodyHarmonic2($plants) => {
                const $d: usize = 3;
                $body
            }
            PlantSpec::TetherSimplified($plants) => {
                const $d: usize = 2;
                $body
            }
            PlantSpec::TetherFlexible2($plants) => {
                const $d: usize = 2;
                $body
            }
            PlantSpec::TetherFlexible4($plants) => {
                const $d: usize = 2;
                $body
            }
            PlantSpec::TetherFlexible8($plants) => {
                const $d: usize = 2;
                $body
            }
            PlantSpec::TetherFlexible16($plants) => {
                const $d: usize = 2;
                $body
            }
        }
    };
}
pub(crate) use with_plants;

impl PlantSpec {
    pub const KINDS: [&'static str; 4] = [
        "mars_lander",
        "double_integrator",
        "small_body",
        "tethered_satellite",
    ];

    pub fn axes(&self) -> usize {
        match self {
            Self::Mars(_)
            | Self::DoubleIntegrator(_)
            | Self::SmallBodyPointMass(_)
            | Self::SmallBodyTwoPointMass(_)
            | Self::SmallBodyHarmonic2(_) => 3,
            Self::TetherSimplified(_)
            | Self::TetherFlexible2(_)
            | Self::TetherFlexible4(_)
            | Self::TetherFlexible8(_)
            | Self::TetherFlexible16(_) => 2,
        }
    }
}

/// One small-body plant per case from the plant's own parameters and the gravity fields.
fn small_bodies<G: landing_core::gravity::GravityField>(
    p: &Params<'_>,
    fields: Vec<G>,
    omega: &[f64],
    limit: &Option<Vec<Vector3<f64>>>,
) -> Result<PerCase<SmallBody<G>>, InputError> {
    p.build(
        |i| SmallBody {
            gravity: fields[if fields.len() == 1 { 0 } else { i }],
            omega: pick(omega, i),
            acceleration_limit: limit
                .as_ref()
                .map_or(Vector3::repeat(f64::INFINITY), |l| pick(l, i)),
        },
        landing_core::plant::Plant::validate,
    )
}

/// The tethered satellite's table: `fidelity` ("simplified" or "flexible"), the shared body
/// (seed Table 1, the orbit, the actuator limits) and, for the flexible model, the tether.
fn parse_tether(p: &mut Params<'_>) -> Result<PlantSpec, InputError> {
    let fidelity = p.choice("fidelity", &["simplified", "flexible"])?;
    let main_mass = p.scalar("main_mass")?;
    let sub_mass = p.scalar("sub_mass")?;
    let length = p.scalar("tether_length")?;
    let side = p.scalar("side")?;
    let altitude = p.scalar("orbit_altitude")?;
    let rates = altitude
        .iter()
        .map(|&h| orbital_rate(h).map_err(|e| param_error(&e, None)))
        .collect::<Result<Vec<f64>, _>>()?;
    let thrust = p.opt_scalar("thrust_limit")?;
    let torque = p.opt_scalar("torque_limit")?;
    let body = |i: usize| {
        let thrust_limit = thrust.as_ref().map_or(f64::INFINITY, |t| pick(t, i));
        let side = pick(&side, i);
        TetherBody {
            main_mass: pick(&main_mass, i),
            sub_mass: pick(&sub_mass, i),
            length: pick(&length, i),
            side,
            orbital_rate: pick(&rates, i),
            thrust_limit,
            // SPEC 3.3: the thrust times the lever arm a/2 unless set
            torque_limit: torque
                .as_ref()
                .map_or(0.5 * side * thrust_limit, |t| pick(t, i)),
        }
    };
    if fidelity == "simplified" {
        let plants = p.build(
            |i| TetheredSimplified { body: body(i) },
            |t: &TetheredSimplified| landing_core::plant::Plant::validate(t),
        )?;
        return Ok(PlantSpec::TetherSimplified(plants));
    }
    let nodes = p.shared_count("nodes", &TETHER_NODES, "nodes in {2, 4, 8, 16}")?;
    let density = p.scalar("tether_density")?;
    let stiffness = p.scalar("axial_stiffness")?;
    let damping = p.scalar("axial_damping")?;
    fn flexible<const N: usize, const S: usize>(
        p: &Params<'_>,
        body: &dyn Fn(usize) -> TetherBody,
        tether: [&[f64]; 3],
    ) -> Result<PerCase<TetheredFlexible<N, S>>, InputError> {
        p.build(
            |i| TetheredFlexible {
                body: body(i),
                density: pick(tether[0], i),
                axial_stiffness: pick(tether[1], i),
                axial_damping: pick(tether[2], i),
            },
            |t: &TetheredFlexible<N, S>| landing_core::plant::Plant::validate(t),
        )
    }
    let tether = [density.as_slice(), stiffness.as_slice(), damping.as_slice()];
    Ok(match nodes {
        2 => PlantSpec::TetherFlexible2(flexible(p, &body, tether)?),
        4 => PlantSpec::TetherFlexible4(flexible(p, &body, tether)?),
        8 => PlantSpec::TetherFlexible8(flexible(p, &body, tether)?),
        _ => PlantSpec::TetherFlexible16(flexible(p, &body, tether)?),
    })
}

pub fn parse_plant(kind: &str, p: &mut Params<'_>) -> Result<PlantSpec, InputError> {
    match kind {
        "mars_lander" => {
            let isp = p.scalar("isp")?;
            let area = p.axes::<3>("area")?;
            let gravity = p.scalar("gravity")?;
            let g0 = p.scalar("g0")?;
            let drag = p.flag("drag")?;
            let kd = p.scalar("drag_coefficient")?;
            let hd = p.scalar("density_decay")?;
            let limit = p.opt_axes::<3>("thrust_limit")?;
            let plants = p.build(
                |i| MarsLander {
                    isp: pick(&isp, i),
                    area: pick(&area, i),
                    gravity: Uniform {
                        g0: pick(&gravity, i),
                    },
                    g0: pick(&g0, i),
                    drag,
                    drag_coefficient: pick(&kd, i),
                    density_decay: pick(&hd, i),
                    thrust_limit: limit
                        .as_ref()
                        .map_or(Vector3::repeat(f64::INFINITY), |l| pick(l, i)),
                },
                |m: &MarsLander| landing_core::plant::Plant::validate(m),
            )?;
            Ok(PlantSpec::Mars(plants))
        }
        "double_integrator" => {
            let limit = p.opt_axes::<3>("acceleration_limit")?;
            let plants = p.build(
                |i| DoubleIntegrator {
                    acceleration_limit: limit
                        .as_ref()
                        .map_or(Vector3::repeat(f64::INFINITY), |l| pick(l, i)),
                },
                |d: &DoubleIntegrator| landing_core::plant::Plant::validate(d),
            )?;
            Ok(PlantSpec::DoubleIntegrator(plants))
        }
        "small_body" => {
            let omega = p.scalar("omega")?;
            let limit = p.opt_axes::<3>("acceleration_limit")?;
            let gravity = p.table("gravity", "a landing.gravity field")?;
            Ok(match parse_gravity_into(gravity, p)? {
                GravitySpec::PointMass(f) => {
                    PlantSpec::SmallBodyPointMass(small_bodies(p, f, &omega, &limit)?)
                }
                GravitySpec::TwoPointMass(f) => {
                    PlantSpec::SmallBodyTwoPointMass(small_bodies(p, f, &omega, &limit)?)
                }
                GravitySpec::Harmonic2(f) => {
                    PlantSpec::SmallBodyHarmonic2(small_bodies(p, f, &omega, &limit)?)
                }
            })
        }
        "tethered_satellite" => parse_tether(p),
        other => Err(InputError::Value(format!(
            "unknown plant kind {other:?}; known: {:?}",
            PlantSpec::KINDS
        ))),
    }
}

pub enum LawSpec<const D: usize> {
    FixedTimeMss(PerCase<FixedTimeMss<D>>),
    SuperTwisting(PerCase<SuperTwisting<D>>),
    OpenLoop(PerCase<OpenLoop<D>>),
    PdSlidingMode(PerCase<PdSlidingMode<D>>),
    FastTerminalSmc(PerCase<FastTerminalSmc<D>>),
    FuzzyFastTerminalSmc(PerCase<FuzzyFastTerminalSmc<D>>),
    IntegralExponentialReaching(PerCase<IntegralExponentialReaching<D>>),
    FuzzyVariableRate(PerCase<FuzzyVariableRate<D>>),
    Ntsmc(PerCase<Ntsmc<D>>),
    FixedTimeNtsmc(PerCase<FixedTimeNtsmc<D>>),
}

pub const LAW_KINDS: [&str; 10] = [
    "fixed_time_mss",
    "super_twisting",
    "open_loop",
    "pd_sliding_mode",
    "fast_terminal_smc",
    "fuzzy_fast_terminal_smc",
    "integral_exponential_reaching",
    "fuzzy_variable_rate",
    "ntsmc",
    "fixed_time_ntsmc",
];

/// Names and widths of a law's diagnostic signals, in recording order.
fn layout<const D: usize, L: ControlLaw<D>>() -> Vec<(&'static str, usize)> {
    L::DIAGNOSTICS
        .iter()
        .map(|n| (*n, D))
        .chain(L::SCALAR_DIAGNOSTICS.iter().map(|n| (*n, 1)))
        .collect()
}

impl<const D: usize> LawSpec<D> {
    pub fn diagnostic_layout(&self) -> Vec<(&'static str, usize)> {
        match self {
            Self::FixedTimeMss(_) => layout::<D, FixedTimeMss<D>>(),
            Self::SuperTwisting(_) => layout::<D, SuperTwisting<D>>(),
            Self::OpenLoop(_) => layout::<D, OpenLoop<D>>(),
            Self::PdSlidingMode(_) => layout::<D, PdSlidingMode<D>>(),
            Self::FastTerminalSmc(_) => layout::<D, FastTerminalSmc<D>>(),
            Self::FuzzyFastTerminalSmc(_) => layout::<D, FuzzyFastTerminalSmc<D>>(),
            Self::IntegralExponentialReaching(_) => layout::<D, IntegralExponentialReaching<D>>(),
            Self::FuzzyVariableRate(_) => layout::<D, FuzzyVariableRate<D>>(),
            Self::Ntsmc(_) => layout::<D, Ntsmc<D>>(),
            Self::FixedTimeNtsmc(_) => layout::<D, FixedTimeNtsmc<D>>(),
        }
    }
}

const SWITCHES: [&str; 3] = ["sign", "sat", "tanh"];

/// The switching function of a sliding-mode law: `switch` and its `boundary_layer`.
fn switch(p: &mut Params<'_>) -> Result<Switch, InputError> {
    let kind = p.choice("switch", &SWITCHES)?;
    let phi = p.scalar("boundary_layer")?;
    if phi.len() != 1 {
        return Err(InputError::Shape(
            "boundary_layer is shared by all cases".into(),
        ));
    }
    Ok(match kind.as_str() {
        "sign" => Switch::Sign,
        "sat" => Switch::Sat(phi[0]),
        _ => Switch::Tanh(phi[0]),
    })
}

/// The fast terminal surface parameters (alpha, beta, p, q, e_floor), per case.
fn terminal_surfaces<const D: usize>(
    p: &mut Params<'_>,
) -> Result<impl Fn(usize) -> TerminalSurface<D> + use<D>, InputError> {
    let alpha = p.axes::<D>("alpha")?;
    let beta = p.axes::<D>("beta")?;
    let pp = p.axes::<D>("p")?;
    let q = p.axes::<D>("q")?;
    let floor = p.scalar("e_floor")?;
    Ok(move |i| TerminalSurface {
        alpha: pick(&alpha, i),
        beta: pick(&beta, i),
        p: pick(&pp, i),
        q: pick(&q, i),
        e_floor: pick(&floor, i),
    })
}

/// The integral surface parameters (c1, c2, k), per case.
fn integral_surfaces<const D: usize>(
    p: &mut Params<'_>,
) -> Result<impl Fn(usize) -> IntegralSurface<D> + use<D>, InputError> {
    let c1 = p.axes::<D>("c1")?;
    let c2 = p.axes::<D>("c2")?;
    let k = p.axes::<D>("k")?;
    Ok(move |i| IntegralSurface {
        c1: pick(&c1, i),
        c2: pick(&c2, i),
        k: pick(&k, i),
    })
}

pub fn parse_law<const D: usize>(kind: &str, p: &mut Params<'_>) -> Result<LawSpec<D>, InputError> {
    match kind {
        "fixed_time_mss" => {
            let names = [
                "beta1", "beta2", "q1", "q2", "alpha1", "alpha2", "gamma1", "gamma2",
            ];
            let mut g: Vec<Vec<SVector<f64, D>>> = Vec::with_capacity(8);
            for name in names {
                g.push(p.axes::<D>(name)?);
            }
            let variant = MssVariant::from_name(&p.choice("variant", &MssVariant::NAMES)?)
                .expect("checked by choice");
            let floor = p.scalar("s1_floor")?;
            let laws = p.build(
                |i| FixedTimeMss {
                    beta1: pick(&g[0], i),
                    beta2: pick(&g[1], i),
                    q1: pick(&g[2], i),
                    q2: pick(&g[3], i),
                    alpha1: pick(&g[4], i),
                    alpha2: pick(&g[5], i),
                    gamma1: pick(&g[6], i),
                    gamma2: pick(&g[7], i),
                    variant,
                    s1_floor: pick(&floor, i),
                },
                ControlLaw::validate,
            )?;
            Ok(LawSpec::FixedTimeMss(laws))
        }
        "super_twisting" => {
            let b1 = p.axes::<D>("b1")?;
            let b2 = p.axes::<D>("b2")?;
            let c = p.axes::<D>("c")?;
            let variant = SuperTwistingVariant::from_name(
                &p.choice("variant", &SuperTwistingVariant::NAMES)?,
            )
            .expect("checked by choice");
            let floor = p.scalar("s_floor")?;
            let laws = p.build(
                |i| SuperTwisting {
                    b1: pick(&b1, i),
                    b2: pick(&b2, i),
                    c: pick(&c, i),
                    variant,
                    s_floor: pick(&floor, i),
                },
                ControlLaw::validate,
            )?;
            Ok(LawSpec::SuperTwisting(laws))
        }
        "open_loop" => {
            let a = p.axes::<D>("acceleration")?;
            let laws = p.build(
                |i| OpenLoop {
                    acceleration: pick(&a, i),
                },
                ControlLaw::validate,
            )?;
            Ok(LawSpec::OpenLoop(laws))
        }
        "pd_sliding_mode" => {
            let lambda = p.axes::<D>("lambda")?;
            let k = p.axes::<D>("k")?;
            let sw = switch(p)?;
            let laws = p.build(
                |i| PdSlidingMode {
                    lambda: pick(&lambda, i),
                    k: pick(&k, i),
                    switch: sw,
                },
                ControlLaw::validate,
            )?;
            Ok(LawSpec::PdSlidingMode(laws))
        }
        "fast_terminal_smc" => {
            let surface = terminal_surfaces::<D>(p)?;
            let k = p.axes::<D>("k")?;
            let sw = switch(p)?;
            let laws = p.build(
                |i| FastTerminalSmc {
                    surface: surface(i),
                    k: pick(&k, i),
                    switch: sw,
                },
                ControlLaw::validate,
            )?;
            Ok(LawSpec::FastTerminalSmc(laws))
        }
        "fuzzy_fast_terminal_smc" => {
            let surface = terminal_surfaces::<D>(p)?;
            let k = p.axes::<D>("k")?;
            let sw = switch(p)?;
            let n = p.scalar("n")?;
            let m = p.scalar("m")?;
            let laws = p.build(
                |i| FuzzyFastTerminalSmc {
                    surface: surface(i),
                    k: pick(&k, i),
                    switch: sw,
                    n: pick(&n, i),
                    m: pick(&m, i),
                },
                ControlLaw::validate,
            )?;
            Ok(LawSpec::FuzzyFastTerminalSmc(laws))
        }
        "integral_exponential_reaching" => {
            let surface = integral_surfaces::<D>(p)?;
            let eps = p.axes::<D>("epsilon")?;
            let sw = switch(p)?;
            let laws = p.build(
                |i| IntegralExponentialReaching {
                    surface: surface(i),
                    epsilon: pick(&eps, i),
                    switch: sw,
                },
                ControlLaw::validate,
            )?;
            Ok(LawSpec::IntegralExponentialReaching(laws))
        }
        "fuzzy_variable_rate" => {
            let surface = integral_surfaces::<D>(p)?;
            let ke = p.axes::<D>("ke")?;
            let kec = p.axes::<D>("kec")?;
            let ku = p.axes::<D>("ku")?;
            let system = p.table("system", "a landing.fuzzy.Mamdani system")?;
            let system = Arc::new(parse_mamdani(&system).map_err(|e| e.context("system"))?);
            let laws = p.build(
                |i| FuzzyVariableRate {
                    surface: surface(i),
                    ke: pick(&ke, i),
                    kec: pick(&kec, i),
                    ku: pick(&ku, i),
                    system: Arc::clone(&system),
                },
                ControlLaw::validate,
            )?;
            Ok(LawSpec::FuzzyVariableRate(laws))
        }
        "ntsmc" => {
            let alpha = p.axes::<D>("alpha")?;
            let beta = p.axes::<D>("beta")?;
            let gamma = p.axes::<D>("gamma")?;
            let k = p.axes::<D>("k")?;
            let laws = p.build(
                |i| Ntsmc {
                    alpha: pick(&alpha, i),
                    beta: pick(&beta, i),
                    gamma: pick(&gamma, i),
                    k: pick(&k, i),
                },
                ControlLaw::validate,
            )?;
            Ok(LawSpec::Ntsmc(laws))
        }
        "fixed_time_ntsmc" => {
            let names = [
                "k1",
                "k2",
                "k3",
                "eps_max",
                "p1",
                "p2",
                "alpha_s",
                "beta_s",
                "sigma_phi",
                "gamma",
                "rbf_scale_e1",
                "rbf_scale_e2",
                "rbf_width",
            ];
            let mut g: Vec<Vec<SVector<f64, D>>> = Vec::with_capacity(names.len());
            for name in names {
                g.push(p.axes::<D>(name)?);
            }
            let nodes =
                p.shared_count("rbf_nodes", &[1, 2, 3, 4, 5, 6, 7], "rbf_nodes in 1..=7")?;
            let laws = p.build(
                |i| FixedTimeNtsmc {
                    k1: pick(&g[0], i),
                    k2: pick(&g[1], i),
                    k3: pick(&g[2], i),
                    eps_max: pick(&g[3], i),
                    p1: pick(&g[4], i),
                    p2: pick(&g[5], i),
                    alpha_s: pick(&g[6], i),
                    beta_s: pick(&g[7], i),
                    sigma_phi: pick(&g[8], i),
                    gamma: pick(&g[9], i),
                    rbf_nodes: nodes,
                    rbf_scale_e1: pick(&g[10], i),
                    rbf_scale_e2: pick(&g[11], i),
                    rbf_width: pick(&g[12], i),
                },
                ControlLaw::validate,
            )?;
            Ok(LawSpec::FixedTimeNtsmc(laws))
        }
        other => Err(InputError::Value(format!(
            "unknown controller kind {other:?}; known: {LAW_KINDS:?}"
        ))),
    }
}

pub fn parse_reference<const D: usize>(
    kind: &str,
    p: &mut Params<'_>,
) -> Result<PerCase<Reference<D>>, InputError> {
    match kind {
        "constant" => {
            let pos = p.axes::<D>("position")?;
            let vel = p
                .opt_axes::<D>("velocity")?
                .unwrap_or_else(|| vec![SVector::zeros()]);
            p.build(
                |i| Reference::Constant {
                    position: pick(&pos, i),
                    velocity: pick(&vel, i),
                },
                Reference::validate,
            )
        }
        "cubic" => {
            let c: Vec<Vec<SVector<f64, D>>> = (0..4)
                .map(|j| p.axes::<D>(&format!("c{j}")))
                .collect::<Result<_, _>>()?;
            let t_end = p.scalar("t_end")?;
            p.build(
                |i| Reference::Cubic {
                    coefficients: [
                        pick(&c[0], i),
                        pick(&c[1], i),
                        pick(&c[2], i),
                        pick(&c[3], i),
                    ],
                    t_end: pick(&t_end, i),
                },
                Reference::validate,
            )
        }
        other => Err(InputError::Value(format!(
            "unknown reference kind {other:?}; known: [\"constant\", \"cubic\"]"
        ))),
    }
}

/// A disturbance table is `{"components": [...]}`, each component a table with a `kind`:
/// `constant` (value), `sinusoid` (amplitude, omega, phase) or `uniform_noise` (bound).
/// Components add up.
pub fn parse_disturbance<const D: usize>(
    p: &mut Params<'_>,
) -> Result<PerCase<Disturbance<D>>, InputError> {
    enum Part<const D: usize> {
        Constant(Vec<SVector<f64, D>>),
        Sinusoid(
            Vec<SVector<f64, D>>,
            Vec<SVector<f64, D>>,
            Vec<SVector<f64, D>>,
        ),
        Noise(Vec<SVector<f64, D>>),
        CommandNoise(Vec<SVector<f64, D>>),
    }
    let mut parts = Vec::new();
    let mut n_sinusoids = 0;
    for table in p.list_of_dicts("components")? {
        let kind = kind_of(&table, "disturbance component")?;
        let mut c = p.child(table);
        let part = match kind.as_str() {
            "constant" => Part::Constant(c.axes::<D>("value")?),
            "sinusoid" => {
                n_sinusoids += 1;
                Part::Sinusoid(
                    c.axes::<D>("amplitude")?,
                    c.axes::<D>("omega")?,
                    c.axes::<D>("phase")?,
                )
            }
            "uniform_noise" => Part::Noise(c.axes::<D>("bound")?),
            "command_noise" => Part::CommandNoise(c.axes::<D>("fraction")?),
            other => {
                return Err(InputError::Value(format!(
                    "unknown disturbance kind {other:?}; known: [\"constant\", \"sinusoid\", \"uniform_noise\", \"command_noise\"]"
                )));
            }
        };
        p.merge(&c)?;
        parts.push(part);
    }
    if n_sinusoids > MAX_SINUSOIDS {
        return Err(InputError::Value(format!(
            "{n_sinusoids} sinusoids given; at most {MAX_SINUSOIDS} are supported"
        )));
    }
    p.build(
        |i| {
            let mut d = Disturbance::none();
            for part in &parts {
                d = match part {
                    Part::Constant(v) => d.with_constant(pick(v, i)),
                    Part::Noise(b) => d.with_noise(pick(b, i)),
                    Part::CommandNoise(f) => d.with_command_noise(pick(f, i)),
                    Part::Sinusoid(a, w, ph) => d
                        .with_sinusoid(Sinusoid {
                            amplitude: pick(a, i),
                            omega: pick(w, i),
                            phase: pick(ph, i),
                        })
                        .expect("the number of sinusoids is checked above"),
                };
            }
            d
        },
        Disturbance::validate,
    )
}
