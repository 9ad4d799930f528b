//! From the Python layer's parameter tables to typed core values, dispatched once per batch.
//!
//! A table is a dict with a `kind` and the parameters of that kind (see `python/landing`).
//! Laws and references are generic in the number of axes D, fixed by the plant.

use nalgebra::{SVector, Vector3};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use landing_core::PerCase;
use landing_core::control::{
    ControlLaw, FixedTimeMss, MssVariant, OpenLoop, SuperTwisting, SuperTwistingVariant,
};
use landing_core::disturbance::{Disturbance, MAX_SINUSOIDS, Sinusoid};
use landing_core::gravity::Uniform;
use landing_core::plant::{DoubleIntegrator, MarsLander};
use landing_core::reference::Reference;

use crate::errors::InputError;
use crate::params::{Params, pick};

pub fn kind_of(dict: &Bound<'_, PyDict>, what: &str) -> Result<String, InputError> {
    dict.get_item("kind")?
        .and_then(|k| k.extract::<String>().ok())
        .ok_or_else(|| InputError::Type(format!("{what} table has no 'kind'")))
}

pub enum PlantSpec {
    Mars(PerCase<MarsLander>),
    DoubleIntegrator(PerCase<DoubleIntegrator>),
}

impl PlantSpec {
    pub const KINDS: [&'static str; 2] = ["mars_lander", "double_integrator"];

    pub fn axes(&self) -> usize {
        match self {
            Self::Mars(_) | Self::DoubleIntegrator(_) => 3,
        }
    }
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
}

pub const LAW_KINDS: [&str; 3] = ["fixed_time_mss", "super_twisting", "open_loop"];

impl<const D: usize> LawSpec<D> {
    pub fn diagnostic_names(&self) -> &'static [&'static str] {
        match self {
            Self::FixedTimeMss(_) => <FixedTimeMss<D> as ControlLaw<D>>::DIAGNOSTICS,
            Self::SuperTwisting(_) => <SuperTwisting<D> as ControlLaw<D>>::DIAGNOSTICS,
            Self::OpenLoop(_) => <OpenLoop<D> as ControlLaw<D>>::DIAGNOSTICS,
        }
    }
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
            other => {
                return Err(InputError::Value(format!(
                    "unknown disturbance kind {other:?}; known: [\"constant\", \"sinusoid\", \"uniform_noise\"]"
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
