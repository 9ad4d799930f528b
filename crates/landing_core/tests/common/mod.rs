//! Helpers shared by the integration tests.
#![allow(dead_code)]

use landing_core::SimConfig;
use landing_core::batch::{Batch, BatchOutput, PerCase, RunOptions, run};
use landing_core::control::{AnyLaw, FixedTimeMss, MssVariant};
use landing_core::disturbance::Disturbance;
use landing_core::error::Validate;
use landing_core::integrator::IntegratorKind;
use landing_core::plant::MarsLander;
use landing_core::reference::Reference;
use landing_core::workloads::{MARS_NOMINAL, reconstructed_fixed_time_gains};
use nalgebra::SVector;

pub type MarsState = SVector<f64, 7>;

pub fn mars_state(r: [f64; 3], v: [f64; 3], m: f64) -> MarsState {
    MarsState::from([r[0], r[1], r[2], v[0], v[1], v[2], m])
}

/// The seed-001 nominal initial state (Table I).
pub fn nominal() -> MarsState {
    MarsState::from(MARS_NOMINAL)
}

/// The gains reconstructed from seed 001's printed bounds (docs/parameters.md).
pub fn reconstructed_gains(variant: MssVariant) -> FixedTimeMss<3> {
    reconstructed_fixed_time_gains(variant)
}

pub fn run_one(
    plant: MarsLander,
    law: impl Into<AnyLaw<3>>,
    integrator: IntegratorKind,
    x0: MarsState,
    disturbance: Disturbance<3>,
    cfg: &SimConfig,
) -> BatchOutput<3> {
    let batch = Batch {
        plants: PerCase::shared(plant),
        laws: PerCase::shared(law.into()),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(disturbance),
        x0: vec![x0],
    };
    run(
        &batch,
        &cfg.with_integrator(integrator),
        &RunOptions::default(),
    )
    .expect("batch runs")
}

pub fn no_drag() -> MarsLander {
    MarsLander {
        drag: false,
        ..Default::default()
    }
}

pub fn final_state(out: &BatchOutput<3>, case: usize) -> MarsState {
    MarsState::from_column_slice(&out.final_state[case * 7..(case + 1) * 7])
}

pub fn check_plant_ok<P: Validate>(p: &P) {
    p.validate().expect("valid plant");
}

/// Recording buffers to lend a batch (`landing_core::batch::Lent`), filled with a value the
/// batch must overwrite everywhere, NaN included.
pub struct LentBuffers {
    pub states: Vec<f64>,
    pub controls: Vec<f64>,
    pub diagnostics: Vec<f64>,
    shapes: [[usize; 3]; 3],
}

impl LentBuffers {
    /// Buffers for `n` cases and `records` instants of `[state_dim, D, diagnostic_dim]` values.
    pub fn new(n: usize, records: usize, widths: [usize; 3]) -> Self {
        let shapes = widths.map(|w| [n, records, w]);
        let filled = |s: [usize; 3]| vec![7.25; s.iter().product()];
        Self {
            states: filled(shapes[0]),
            controls: filled(shapes[1]),
            diagnostics: filled(shapes[2]),
            shapes,
        }
    }

    /// The options of a batch on `threads` threads writing its recording into these buffers.
    pub fn options(&mut self, threads: usize) -> RunOptions<'static> {
        // SAFETY: the buffers outlive each batch a test runs with the options, one at a time,
        // and are read only after it
        let lent = unsafe {
            landing_core::batch::Lent::new(
                (self.states.as_mut_ptr(), self.shapes[0]),
                (self.controls.as_mut_ptr(), self.shapes[1]),
                (self.diagnostics.as_mut_ptr(), self.shapes[2]),
            )
        };
        RunOptions {
            threads: Some(threads),
            level: None,
            cancel: None,
            recording: Some(lent),
        }
    }
}
