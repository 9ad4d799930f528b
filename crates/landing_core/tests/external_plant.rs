//! A plant computed outside the core ([`run_external_plant`]: one call per integrator stage
//! for every case) against the same plant built in. The Mars lander written as an external
//! plant with the core's own model, case by case, must give the built-in plant's bits: the
//! blocks, the integrator's stages and the metrics are the same code, driven in another order.

mod common;

use common::*;
use landing_core::batch::{Batch, BatchOutput, PerCase, RunOptions, run};
use landing_core::control::{
    AnyLaw, FixedTimeMss, MssVariant, SuperTwisting, SuperTwistingVariant,
};
use landing_core::disturbance::Disturbance;
use landing_core::external::{
    ExternalError, ExternalPlant, Laws, MAX_EXTERNAL_STATE, StateLayout, run_external_plant,
};
use landing_core::integrator::IntegratorKind;
use landing_core::plant::{MarsLander, Plant};
use landing_core::reference::Reference;
use landing_core::workloads::{mars_dispersed, mars_storm};
use landing_core::{Level, SimConfig};
use nalgebra::Vector3;

/// The core's Mars lander, case by case, as an external plant; `calls` counts the derivative's
/// calls; `fail_at` makes the derivative fail at that time.
struct CaseByCase {
    plant: MarsLander,
    layout: StateLayout<3>,
    calls: usize,
    fail_at: Option<f64>,
}

impl CaseByCase {
    fn new() -> Self {
        Self {
            plant: plant(),
            layout: StateLayout::new(7, &[0, 1, 2], &[3, 4, 5], Some(6), Some(2)).unwrap(),
            calls: 0,
            fail_at: None,
        }
    }
}

fn state(x: &[f64], i: usize) -> MarsState {
    MarsState::from_column_slice(&x[7 * i..7 * i + 7])
}

fn axes(v: &[f64], i: usize) -> Vector3<f64> {
    Vector3::from_column_slice(&v[3 * i..3 * i + 3])
}

impl ExternalPlant<3> for CaseByCase {
    type Error = String;

    fn layout(&self) -> &StateLayout<3> {
        &self.layout
    }

    fn hooks(&self) -> [bool; 3] {
        [true; 3]
    }

    fn derivative(&mut self, t: f64, x: &[f64], u: &[f64], xdot: &mut [f64]) -> Result<(), String> {
        if self.fail_at == Some(t) {
            return Err(format!("failed at t = {t}"));
        }
        self.calls += 1;
        for i in 0..x.len() / 7 {
            let k = self
                .plant
                .derivative(t, &state(x, i), &axes(u, i), &Vector3::zeros());
            xdot[7 * i..7 * i + 7].copy_from_slice(k.as_slice());
        }
        Ok(())
    }

    fn model(&mut self, t: f64, x: &[f64], model: &mut [f64]) -> Result<(), String> {
        for i in 0..x.len() / 7 {
            let s = state(x, i);
            model[6 * i..6 * i + 3]
                .copy_from_slice(self.plant.modelled_acceleration(t, &s).as_slice());
            model[6 * i + 3..6 * i + 6].copy_from_slice(self.plant.inertia(&s).as_slice());
        }
        Ok(())
    }

    fn actuate(&mut self, _t: f64, x: &[f64], a: &[f64], u: &mut [f64]) -> Result<(), String> {
        for i in 0..x.len() / 7 {
            let applied = self.plant.actuate(&state(x, i), &axes(a, i));
            u[3 * i..3 * i + 3].copy_from_slice(applied.as_slice());
        }
        Ok(())
    }

    fn in_domain(&mut self, _t: f64, x: &[f64], inside: &mut [f64]) -> Result<(), String> {
        for (i, v) in inside.iter_mut().enumerate() {
            *v = f64::from(u8::from(self.plant.in_domain(&state(x, i))));
        }
        Ok(())
    }
}

fn plant() -> MarsLander {
    MarsLander {
        thrust_limit: Vector3::repeat(50_000.0),
        ..Default::default()
    }
}

fn fingerprint(out: &BatchOutput<3>) -> (Vec<u64>, Vec<u64>, Vec<u64>, Vec<u64>, String) {
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    (
        bits(&out.final_state),
        bits(&out.states),
        bits(&out.controls),
        bits(&out.diagnostics),
        format!("{:?}", out.metrics),
    )
}

/// 21 dispersed cases, one with an absurd speed (it leaves the domain), one 2 m above the
/// ground falling at 30 m/s (a touchdown), per-case gains.
fn cases(law: impl Fn(usize) -> AnyLaw<3>) -> (Vec<AnyLaw<3>>, Vec<MarsState>) {
    let mut x0 = mars_dispersed(21, 42);
    x0[3][3] = 1e200;
    x0[5] = mars_state([10.0, 0.0, 2.0], [0.0, 0.0, -30.0], 1900.0);
    ((0..21).map(law).collect(), x0)
}

fn mss(i: usize) -> AnyLaw<3> {
    FixedTimeMss {
        alpha1: Vector3::repeat(0.5 + 0.05 * i as f64),
        ..reconstructed_gains(MssVariant::Printed)
    }
    .into()
}

fn twisting(i: usize) -> AnyLaw<3> {
    SuperTwisting {
        b1: Vector3::repeat(2.0 + 0.1 * i as f64),
        b2: Vector3::repeat(1.0),
        c: Vector3::repeat(0.4),
        variant: SuperTwistingVariant::Standard,
        s_floor: 1e-6,
    }
    .into()
}

fn options() -> RunOptions<'static> {
    RunOptions {
        threads: Some(2),
        level: None,
        cancel: None,
        recording: None,
    }
}

#[test]
fn an_external_plant_gives_the_bits_of_the_same_plant_built_in() {
    let noisy = mars_storm().with_noise(Vector3::repeat(0.5));
    for integrator in [IntegratorKind::Rk4, IntegratorKind::Euler] {
        let cfg = SimConfig::new(0.5, 0.001, 2, 37, 7)
            .unwrap()
            .with_first_case(3)
            .with_integrator(integrator);
        for (name, make) in [
            ("fixed-time MSS", mss as fn(usize) -> AnyLaw<3>),
            ("super-twisting", twisting),
        ] {
            let (laws, x0) = cases(make);
            let batch = Batch {
                plants: PerCase::shared(plant()),
                laws: PerCase::from_vec(laws.clone()),
                references: PerCase::shared(Reference::default()),
                disturbances: PerCase::shared(noisy),
                x0: x0.clone(),
            };
            let reference = run(&batch, &cfg, &options()).unwrap();
            assert!(
                reference.metrics[3].diverged.is_some(),
                "the absurd case stops"
            );
            assert!(
                reference.metrics[5].touchdown.is_some(),
                "the low case touches down"
            );
            let flat: Vec<f64> = x0.iter().flat_map(|x| x.iter().copied()).collect();
            let mut outside = CaseByCase::new();
            let laws = PerCase::from_vec(laws);
            let out = run_external_plant(
                &mut outside,
                Laws::Builtin(&laws),
                &flat,
                &PerCase::shared(Reference::default()),
                &PerCase::shared(noisy),
                &cfg,
                &options(),
            )
            .unwrap_or_else(|_| panic!("{name} runs"));
            assert_eq!(out.level, Level::Baseline);
            assert_eq!(out.state_dim, 7);
            assert_eq!(
                fingerprint(&out),
                fingerprint(&reference),
                "{name}, {integrator:?}"
            );
            // one call per stage while a case runs: the cases that run to the end make it
            // steps x substeps x evaluations
            let evaluations = cfg.steps as usize * 2 * integrator.evaluations();
            assert_eq!(outside.calls, evaluations, "{name}, {integrator:?}");
            // the recording written into buffers the caller lends: the same bits there
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            let widths = [7, 3, reference.diagnostic_dim];
            let mut lent = LentBuffers::new(x0.len(), reference.n_records(), widths);
            let out = run_external_plant(
                &mut CaseByCase::new(),
                Laws::Builtin(&laws),
                &flat,
                &PerCase::shared(Reference::default()),
                &PerCase::shared(noisy),
                &cfg,
                &lent.options(2),
            )
            .unwrap_or_else(|_| panic!("{name} runs"));
            assert!(out.states.is_empty() && out.diagnostics.is_empty());
            assert_eq!(bits(&lent.states), bits(&reference.states), "{name}");
            assert_eq!(bits(&lent.controls), bits(&reference.controls), "{name}");
            assert_eq!(
                bits(&lent.diagnostics),
                bits(&reference.diagnostics),
                "{name}"
            );
            assert_eq!(
                bits(&out.final_state),
                bits(&reference.final_state),
                "{name}"
            );
        }
    }
}

#[test]
fn the_plant_failing_stops_the_batch_with_its_error() {
    let (laws, x0) = cases(mss);
    let flat: Vec<f64> = x0.iter().flat_map(|x| x.iter().copied()).collect();
    let cfg = SimConfig::new(0.5, 0.01, 1, 1, 0).unwrap();
    let mut outside = CaseByCase::new();
    outside.fail_at = Some(0.25);
    let laws = PerCase::from_vec(laws);
    let result = run_external_plant(
        &mut outside,
        Laws::Builtin(&laws),
        &flat,
        &PerCase::shared(Reference::default()),
        &PerCase::shared(Disturbance::none()),
        &cfg,
        &options(),
    );
    match result {
        Err(ExternalError::Plant(e)) => assert_eq!(e, "failed at t = 0.25"),
        Err(_) => panic!("another error"),
        Ok(_) => panic!("the failure is not lost"),
    }
}

#[test]
fn a_layout_is_checked() {
    let ok = StateLayout::<3>::new(7, &[0, 1, 2], &[3, 4, 5], Some(6), None);
    assert!(ok.is_ok());
    let bad = [
        (
            StateLayout::<3>::new(0, &[0, 1, 2], &[3, 4, 5], None, None),
            "n_state = 0 violates",
        ),
        (
            StateLayout::<3>::new(MAX_EXTERNAL_STATE + 1, &[0, 1, 2], &[3, 4, 5], None, None),
            "n_state = 33 violates 1 <= n_state <= 32",
        ),
        (
            StateLayout::<3>::new(7, &[0, 1], &[3, 4, 5], None, None),
            "positions has 2 entries",
        ),
        (
            StateLayout::<3>::new(7, &[0, 1, 2], &[3, 4, 7], None, None),
            "index 7 violates",
        ),
        (
            StateLayout::<3>::new(7, &[0, 1, 2], &[3, 4, 5], Some(9), None),
            "mass: index 9",
        ),
        (
            StateLayout::<3>::new(7, &[0, 1, 2], &[2, 4, 5], None, None),
            "distinct",
        ),
    ];
    for (result, message) in bad {
        let e = result.unwrap_err().to_string();
        assert!(e.contains(message), "{e:?} lacks {message:?}");
    }
}
