//! Cases that leave their model are stopped and flagged with the time and the reason; the
//! others of the batch are unaffected, and no statistic is non-finite without the flag.

use landing_core::SimConfig;
use landing_core::batch::{Batch, PerCase, run_with_threads};
use landing_core::control::{AnyLaw, OpenLoop, PdSlidingMode};
use landing_core::disturbance::Disturbance;
use landing_core::gravity::PointMass;
use landing_core::integrator::IntegratorKind;
use landing_core::math::Switch;
use landing_core::metrics::{Divergence, MAX_COMMAND, MAX_STATE};
use landing_core::plant::{MarsLander, SmallBody};
use landing_core::reference::Reference;
use nalgebra::{SVector, Vector3};

fn open_loop(a: [f64; 3]) -> AnyLaw<3> {
    OpenLoop {
        acceleration: Vector3::from(a),
    }
    .into()
}

fn mars(x0: Vec<SVector<f64, 7>>, laws: Vec<AnyLaw<3>>) -> Batch<3, MarsLander> {
    mars_with(x0, laws, 225.0)
}

fn mars_with(x0: Vec<SVector<f64, 7>>, laws: Vec<AnyLaw<3>>, isp: f64) -> Batch<3, MarsLander> {
    Batch {
        plants: PerCase::shared(MarsLander {
            drag: false,
            isp,
            ..Default::default()
        }),
        laws: PerCase::from_vec(laws),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(Disturbance::none()),
        x0,
    }
}

fn hover() -> SVector<f64, 7> {
    SVector::from([0.0, 0.0, 1500.0, 0.0, 0.0, 0.0, 1905.0])
}

#[test]
fn leaving_the_range_of_the_mars_model_is_out_of_domain() {
    // 1e5 m/s^2 up from 1500 m: r_z = 1500 + 5e4 t^2 passes 1e8 m at t = 44.7 s (an
    // engine of absurd specific impulse, so that the force held over a period does not burn
    // the mass first)
    let b = mars_with(
        vec![hover(), hover()],
        vec![open_loop([0.0, 0.0, 1e5]), open_loop([0.0, 0.0, 3.7114])],
        1e9,
    );
    let cfg = SimConfig::new(60.0, 0.1, 1, 0, 0).unwrap();
    let out = run_with_threads(&b, &cfg, Some(1)).unwrap();
    let stop = out.metrics[0].diverged.expect("case 0 leaves the range");
    assert_eq!(stop.reason, Divergence::OutOfDomain);
    let t_cross = ((1e8 - 1500.0) / 5e4f64).sqrt();
    assert!(
        stop.time > t_cross - 0.1 && stop.time <= t_cross + 0.1 + 1e-9,
        "stopped at {} s, the range is left at {t_cross} s",
        stop.time
    );
    assert!(out.final_state[..7].iter().all(|v| v.is_nan()));
    // the hovering case is untouched: gravity cancelled, it stays where it started
    assert!(out.metrics[1].diverged.is_none());
    assert!((out.final_state[9] - 1500.0).abs() < 1e-6);
}

#[test]
fn burning_the_mass_to_zero_is_out_of_domain() {
    // The force m0 |a| is held over the period and m' = -|F| / (Isp g0): one step of 0.1 s at
    // |a| = 1e5 m/s^2 takes m to m0 (1 - 1e4 / 2206.6) < 0
    let b = mars(vec![hover()], vec![open_loop([1e5, 0.0, 0.0])]);
    let cfg = SimConfig::new(1.0, 0.1, 1, 0, 0)
        .unwrap()
        .with_integrator(IntegratorKind::Euler);
    let out = run_with_threads(&b, &cfg, Some(1)).unwrap();
    let stop = out.metrics[0].diverged.unwrap();
    assert_eq!(stop.reason, Divergence::OutOfDomain);
    assert_eq!(stop.time, 0.1);
    assert!(out.metrics[0].fuel_used.is_nan());
}

#[test]
fn a_command_beyond_the_limit_is_out_of_range() {
    let b = mars(
        vec![hover(); 3],
        vec![
            open_loop([0.0, 2.0 * MAX_COMMAND, 0.0]),
            open_loop([0.0, 0.0, 3.7114]),
            open_loop([0.0, 0.0, 3.7114]),
        ],
    );
    let cfg = SimConfig::new(1.0, 0.1, 1, 0, 0).unwrap();
    let out = run_with_threads(&b, &cfg, Some(1)).unwrap();
    let stop = out.metrics[0].diverged.unwrap();
    assert_eq!(
        (stop.reason, stop.time),
        (Divergence::CommandOutOfRange, 0.0)
    );
    assert!(out.metrics[1].diverged.is_none() && out.metrics[2].diverged.is_none());
    // statistics of a stopped case stay finite
    assert!(out.metrics[0].accumulations_finite());
}

#[test]
fn a_singular_gravity_gives_a_non_finite_state() {
    // A probe at the centre of a point mass: the open-loop law ignores the (infinite) drift,
    // so the command is finite and the first integrator step makes the state non-finite.
    let b = Batch {
        plants: PerCase::shared(SmallBody::new(PointMass { mu: 4.463e5 }, 0.0)),
        laws: PerCase::shared(open_loop([0.0, 0.0, 0.0])),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(Disturbance::none()),
        x0: vec![
            SVector::from([0.0; 6]),
            SVector::from([2e4, 0.0, 0.0, 0.0, 0.0, 0.0]),
        ],
    };
    let cfg = SimConfig::new(1.0, 0.5, 1, 0, 0).unwrap();
    let out = run_with_threads(&b, &cfg, Some(1)).unwrap();
    let stop = out.metrics[0].diverged.unwrap();
    assert_eq!((stop.reason, stop.time), (Divergence::NonFiniteState, 0.5));
    assert!(out.metrics[1].diverged.is_none());
}

#[test]
fn a_law_cancelling_a_singular_gravity_gives_a_non_finite_command() {
    // The PD sliding mode subtracts the drift, infinite at the centre: its first command is
    // not finite.
    let law: AnyLaw<3> = PdSlidingMode {
        lambda: Vector3::repeat(0.1),
        k: Vector3::repeat(0.01),
        switch: Switch::Sign,
    }
    .into();
    let b = Batch {
        plants: PerCase::shared(SmallBody::new(PointMass { mu: 4.463e5 }, 0.0)),
        laws: PerCase::shared(law),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(Disturbance::none()),
        x0: vec![SVector::from([0.0; 6])],
    };
    let cfg = SimConfig::new(1.0, 0.5, 1, 0, 0).unwrap();
    let out = run_with_threads(&b, &cfg, Some(1)).unwrap();
    let stop = out.metrics[0].diverged.unwrap();
    assert_eq!(
        (stop.reason, stop.time),
        (Divergence::NonFiniteCommand, 0.0)
    );
}

#[test]
fn a_finite_state_beyond_the_state_limit_is_out_of_domain() {
    // A probe at rest 1e200 m out on a small body: every component finite, but |e|^2 would
    // overflow; it stops at the end of its first step. One just inside the limit runs on.
    let law: AnyLaw<3> = open_loop([0.0, 0.0, 0.0]);
    let b = Batch {
        plants: PerCase::shared(SmallBody::new(PointMass { mu: 4.463e5 }, 0.0)),
        laws: PerCase::shared(law),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(Disturbance::none()),
        x0: vec![
            SVector::from([0.0, 0.0, 1e200, 0.0, 0.0, 0.0]),
            SVector::from([0.0, 0.0, 0.5 * MAX_STATE, 0.0, 0.0, 0.0]),
        ],
    };
    let cfg = SimConfig::new(1.0, 0.5, 1, 0, 0).unwrap();
    let out = run_with_threads(&b, &cfg, Some(1)).unwrap();
    let stop = out.metrics[0]
        .diverged
        .expect("1e200 m is beyond every plant's range");
    assert_eq!((stop.reason, stop.time), (Divergence::OutOfDomain, 0.5));
    assert!(out.metrics[0].final_error.iter().all(|v| v.is_nan()));
    let inside = &out.metrics[1];
    assert!(inside.diverged.is_none());
    assert!(inside.final_error.norm().is_finite());
}

#[test]
fn a_reference_beyond_the_state_limit_flags_the_final_error() {
    // The state stays put, the reference is 1e200 m away: the error is finite per axis but
    // its norm is not, so the case is flagged rather than reporting an infinite metric.
    let far: Reference<3> = Reference::Constant {
        position: Vector3::new(1e200, 1e200, 0.0),
        velocity: Vector3::zeros(),
    };
    let b = Batch {
        plants: PerCase::shared(SmallBody::new(PointMass { mu: 0.0 }, 0.0)),
        laws: PerCase::shared(open_loop([0.0, 0.0, 0.0])),
        references: PerCase::shared(far),
        disturbances: PerCase::shared(Disturbance::none()),
        x0: vec![SVector::from([1e4, 0.0, 0.0, 0.0, 0.0, 0.0])],
    };
    let cfg = SimConfig::new(1.0, 0.5, 1, 0, 0).unwrap();
    let out = run_with_threads(&b, &cfg, Some(1)).unwrap();
    let stop = out.metrics[0].diverged.expect("|e| overflows");
    assert_eq!(stop.reason, Divergence::NonFiniteMetric);
}

#[test]
fn reason_codes_round_trip_and_name_themselves() {
    for code in 1..Divergence::NAMES.len() as u8 {
        let d = Divergence::from_code(code).unwrap();
        assert_eq!(d.code(), code);
        assert_eq!(d.name(), Divergence::NAMES[code as usize]);
    }
    assert!(Divergence::from_code(0).is_none());
    assert!(Divergence::from_code(6).is_none());
}
