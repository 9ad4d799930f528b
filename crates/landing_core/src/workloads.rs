//! The benchmark workloads W1-W6 (BENCHMARKS.md), shared by the criterion benches, the profiling
//! example and the tests, so that all of them measure and check the same thing.

use nalgebra::{SVector, Vector3};

use crate::batch::{Batch, PerCase};
use crate::control::{
    FixedTimeMss, FixedTimeNtsmc, FuzzyFastTerminalSmc, FuzzyVariableRate, IntegralSurface,
    MssVariant, TerminalSurface,
};
use crate::disturbance::{Disturbance, Sinusoid};
use crate::gravity::{Harmonic2, TwoPointMass};
use crate::math::Switch;
use crate::plant::tether::TetheredFlexible8;
use crate::plant::{MarsLander, SmallBody};
use crate::reference::Reference;
use crate::rng::{CaseStream, streams};

/// Seed 001 Table I initial state `[r, v, m]`.
pub const MARS_NOMINAL: [f64; 7] = [-2000.0, 1000.0, 1500.0, 100.0, -15.0, -75.0, 1905.0];

/// Seed 001 Table II standard deviations.
pub const MARS_TABLE2_SD: [f64; 7] = [100.0, 100.0, 100.0, 10.0, 10.0, 10.0, 20.0];

/// The fixed-time gains reconstructed from seed 001's printed bounds (docs/parameters.md)
/// (T1 = 74.5780 s, T2 = 30.8217 s).
pub fn reconstructed_fixed_time_gains(variant: MssVariant) -> FixedTimeMss<3> {
    FixedTimeMss {
        beta1: Vector3::repeat(0.8),
        beta2: Vector3::repeat(0.4),
        q1: Vector3::repeat(0.95),
        q2: Vector3::repeat(1.05),
        alpha1: Vector3::repeat(0.9),
        alpha2: Vector3::repeat(0.5),
        gamma1: Vector3::repeat(0.9),
        gamma2: Vector3::repeat(1.1),
        variant,
        s1_floor: 1e-3,
    }
}

/// `cases` Table II-dispersed initial states, case i drawn from the dispersion stream of
/// (seed, i).
pub fn mars_dispersed(cases: usize, seed: u64) -> Vec<SVector<f64, 7>> {
    (0..cases)
        .map(|i| {
            let mut z = [0.0; 8];
            CaseStream::new(seed, streams::DISPERSION, i as u64).fill_normals(0, &mut z);
            SVector::<f64, 7>::from_fn(|j, _| MARS_NOMINAL[j] + MARS_TABLE2_SD[j] * z[j])
        })
        .collect()
}

/// The seed-001 dust storm, a_p = 20 sin t on every axis (eq. 47).
pub fn mars_storm() -> Disturbance<3> {
    Disturbance::none()
        .with_sinusoid(Sinusoid {
            amplitude: Vector3::repeat(20.0),
            omega: Vector3::repeat(1.0),
            phase: Vector3::zeros(),
        })
        .expect("one sinusoid fits")
}

/// W1/W2: fixed-time guidance with the reconstructed gains on `cases` dispersed cases, drag, 50 kN per
/// axis, the dust storm.
pub fn mars_w1(cases: usize, seed: u64) -> Batch<3, MarsLander> {
    Batch {
        plants: PerCase::shared(MarsLander {
            thrust_limit: Vector3::repeat(50_000.0),
            ..Default::default()
        }),
        laws: PerCase::shared(reconstructed_fixed_time_gains(MssVariant::Printed).into()),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(mars_storm()),
        x0: mars_dispersed(cases, seed),
    }
}

/// W3: seed-000 fuzzy FTSMC (the preset's gains, sign switching) on 433 Eros as two mass
/// points, tracking the Table 1 cubic from `cases` starts dispersed by 10 m (1 sigma) around
/// the reference.
pub fn eros_w3(cases: usize, seed: u64) -> Batch<3, SmallBody<TwoPointMass>> {
    let p0 = Vector3::new(3200.0, 1300.0, 9000.0);
    let v0 = Vector3::new(-1.2, 0.2, -1.0);
    let reference = Reference::cubic_from_boundary(
        p0,
        v0,
        Vector3::new(2837.0, 928.1, 5708.0),
        Vector3::zeros(),
        8000.0,
    )
    .expect("a valid cubic");
    let x0 = (0..cases)
        .map(|i| {
            let mut z = [0.0; 4];
            CaseStream::new(seed, streams::DISPERSION, i as u64).fill_normals(0, &mut z);
            SVector::<f64, 6>::from([
                p0[0] + 10.0 * z[0],
                p0[1] + 10.0 * z[1],
                p0[2] + 10.0 * z[2],
                v0[0],
                v0[1],
                v0[2],
            ])
        })
        .collect();
    let law = FuzzyFastTerminalSmc {
        surface: TerminalSurface {
            alpha: Vector3::repeat(1.0),
            beta: Vector3::repeat(0.4),
            p: Vector3::repeat(1.0),
            q: Vector3::repeat(5.0),
            e_floor: 1e-3,
        },
        k: Vector3::repeat(2.5),
        switch: Switch::Sign,
        n: 10.0,
        m: 10.0,
    };
    Batch {
        plants: PerCase::shared(SmallBody::new(TwoPointMass::eros(), 3.3118e-4)),
        laws: PerCase::shared(law.into()),
        references: PerCase::shared(reference),
        disturbances: PerCase::shared(Disturbance::none()),
        x0,
    }
}

/// W5: seed-002 fuzzy variable-rate law (the preset's gains, the seed's 5x5 Mamdani system
/// sampled at 401 points) on 433 Eros with C20/C22 harmonics, tracking the seed-002 cubic from
/// `cases` starts dispersed by 10 m (1 sigma) about the documented 50 m offset, under a model
/// uncertainty of up to 1 % of the command.
pub fn eros_w5(cases: usize, seed: u64) -> Batch<3, SmallBody<Harmonic2>> {
    let p0 = Vector3::new(550.0, 500.0, 8200.0);
    let v0 = Vector3::new(-1.7, 0.7, -1.5);
    let reference = Reference::cubic_from_boundary(
        p0,
        v0,
        Vector3::new(20.0, 80.0, 2000.0),
        Vector3::zeros(),
        4000.0,
    )
    .expect("a valid cubic");
    let x0 = (0..cases)
        .map(|i| {
            let mut z = [0.0; 4];
            CaseStream::new(seed, streams::DISPERSION, i as u64).fill_normals(0, &mut z);
            SVector::<f64, 6>::from([
                p0[0] + 50.0 + 10.0 * z[0],
                p0[1] + 50.0 + 10.0 * z[1],
                p0[2] + 50.0 + 10.0 * z[2],
                v0[0],
                v0[1],
                v0[2],
            ])
        })
        .collect();
    let law = FuzzyVariableRate {
        surface: IntegralSurface {
            c1: Vector3::repeat(0.017 * 0.017),
            c2: Vector3::repeat(2.0 * 0.017),
            k: Vector3::repeat(0.1),
        },
        ke: Vector3::repeat(3.162e4),
        kec: Vector3::repeat(10.0),
        ku: Vector3::repeat(2.813e-4),
        system: std::sync::Arc::new(crate::fuzzy::variable_rate_system(401)),
    };
    Batch {
        plants: PerCase::shared(SmallBody::new(Harmonic2::seed002(), 1.65e-4)),
        laws: PerCase::shared(law.into()),
        references: PerCase::shared(reference),
        disturbances: PerCase::shared(
            Disturbance::none().with_command_noise(Vector3::repeat(0.01)),
        ),
        x0,
    }
}

/// W6: seed-003 fixed-time NTSMC with its RBF network (the preset: Table 2 gains, 5 x 5
/// centres) on the flexible tethered satellite with 8 nodes, from `cases` starts with angles
/// uniform within +-1 degree and rates within +-(2e-4, 2e-3) rad/s.
pub fn tether_w6(cases: usize, seed: u64) -> Batch<2, TetheredFlexible8> {
    use nalgebra::Vector2;
    let plant = TetheredFlexible8::default();
    let deg = std::f64::consts::PI / 180.0;
    let x0 = (0..cases)
        .map(|i| {
            let mut u = [0.0; 4];
            CaseStream::new(seed, streams::DISPERSION, i as u64).fill_uniforms(0, &mut u);
            let s = u.map(|v| 2.0 * v - 1.0);
            plant
                .state_at(s[0] * deg, s[1] * deg, s[2] * 2e-4, s[3] * 2e-3)
                .expect("a valid state")
        })
        .collect();
    let law = FixedTimeNtsmc {
        k1: Vector2::new(0.08, 0.6),
        k2: Vector2::new(0.08, 0.5),
        k3: Vector2::new(0.09, 0.8),
        eps_max: Vector2::repeat(1e-4),
        p1: Vector2::repeat(1.1),
        p2: Vector2::new(0.99, 0.6),
        alpha_s: Vector2::new(0.89, 0.7),
        beta_s: Vector2::new(1.1, 1.8),
        sigma_phi: Vector2::new(0.01, 0.001),
        gamma: Vector2::new(3700.0, 0.48),
        rbf_nodes: 5,
        rbf_scale_e1: Vector2::new(0.12 * deg, 2.0 * deg),
        rbf_scale_e2: Vector2::new(0.0045, 0.00036),
        rbf_width: Vector2::new(5.9, 1.4),
    };
    Batch {
        plants: PerCase::shared(plant),
        laws: PerCase::shared(law.into()),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(Disturbance::none()),
        x0,
    }
}
