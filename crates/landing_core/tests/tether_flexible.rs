//! The flexible tethered satellite against conservation laws and closed forms (issue 5, item 2).
//!
//! The tests integrate the plant directly (RK4 at a fixed step) and choose parameters that make
//! each property sharp: a fast orbit (n = 0.02 rad/s) keeps the runs short, which changes no
//! closed form (they hold for any n).

use landing_core::integrator::IntegratorKind;
use landing_core::plant::Plant;
use landing_core::plant::tether::{TetherBody, TetheredFlexible};
use nalgebra::{SVector, Vector2};

const FAST_ORBIT: f64 = 0.02;

fn body(n: f64, side: f64) -> TetherBody {
    TetherBody {
        orbital_rate: n,
        side,
        thrust_limit: f64::INFINITY,
        torque_limit: f64::INFINITY,
        ..Default::default()
    }
}

/// Integrates from `x0` for `t_end` at step `h` under the held command `u`, calling `see` at
/// every step.
fn integrate<const N: usize, const S: usize>(
    plant: &TetheredFlexible<N, S>,
    x0: SVector<f64, S>,
    u: Vector2<f64>,
    t_end: f64,
    h: f64,
    mut see: impl FnMut(f64, &SVector<f64, S>),
) -> SVector<f64, S> {
    let d = Vector2::zeros();
    let steps = (t_end / h).round() as usize;
    let mut x = x0;
    see(0.0, &x);
    for k in 0..steps {
        let t = k as f64 * h;
        let f = |s: landing_core::integrator::Stage, x: &SVector<f64, S>| {
            plant.derivative(s.time(t, h), x, &u, &d)
        };
        x = IntegratorKind::Rk4.step(&f, &x, h);
        see((k + 1) as f64 * h, &x);
    }
    x
}

/// Largest |C(t) - C(0)| of the Jacobi integral over a run, and the smallest tension seen.
fn jacobi_drift(h: f64, damping: f64) -> (f64, f64, f64) {
    // a soft tether, so that a lively motion keeps every segment taut (slack would make the
    // force only C1 and cost RK4 its order)
    let plant = TetheredFlexible::<4, 22> {
        body: body(FAST_ORBIT, 1.0),
        density: 0.01,
        axial_stiffness: 50.0,
        axial_damping: damping,
    };
    let mut x0 = plant.state_at(0.1, 0.3, 0.002, 0.05).unwrap();
    // bend the tether: push the middle node sideways
    x0[6 + 4 + 1] += 0.5;
    let c0 = plant.jacobi(&x0);
    let mut drift = 0.0f64;
    let mut min_tension = f64::INFINITY;
    integrate(&plant, x0, Vector2::zeros(), 200.0, h, |_, x| {
        drift = drift.max((plant.jacobi(x) - c0).abs());
        for j in 0..=4 {
            min_tension = min_tension.min(plant.tension(x, j));
        }
    });
    (drift, c0.abs(), min_tension)
}

#[test]
fn the_jacobi_integral_is_conserved_to_integrator_accuracy() {
    let (coarse, scale, taut) = jacobi_drift(0.02, 0.0);
    let (fine, _, _) = jacobi_drift(0.01, 0.0);
    assert!(
        taut > 0.0,
        "the premise: the tether stays taut (min tension {taut})"
    );
    assert!(fine < 1e-8 * scale, "drift {fine} against |C| = {scale}");
    // halving the step divides the drift by about 2^4: it is RK4's error, not the model's
    let order = (coarse / fine).log2();
    assert!(order > 3.5, "observed order {order} ({coarse} -> {fine})");
    // the check can fail: material damping dissipates, and the same measure sees it
    let (damped, _, _) = jacobi_drift(0.01, 0.5);
    assert!(damped > 1e3 * fine, "damped drift {damped}");
}

#[test]
fn a_slack_tether_carries_no_compression() {
    let plant = TetheredFlexible::<4, 22>::default();
    let n = plant.body.orbital_rate;
    let mut x = plant.state_at(0.0, 0.0, 0.0, 0.0).unwrap();
    // pull the sub-satellite halfway in and crowd the nodes: every segment shorter than rest
    for i in [0usize, 1, 3, 4] {
        x[i] *= 0.5;
    }
    for k in 0..4 {
        let i = 6 + 4 * k;
        x[i] *= 0.4;
        x[i + 1] *= 0.4;
    }
    for j in 0..=4 {
        assert_eq!(plant.tension(&x, j), 0.0, "segment {j}");
    }
    // so every point moves in the bare Hill-frame field
    let dx = plant.derivative(0.0, &x, &Vector2::zeros(), &Vector2::zeros());
    let field = |px: f64, vx: f64, vy: f64| (2.0 * n * vy + 3.0 * n * n * px, -2.0 * n * vx);
    for k in 0..4 {
        let i = 6 + 4 * k;
        let (ax, ay) = field(x[i], x[i + 2], x[i + 3]);
        assert_eq!((dx[i + 2], dx[i + 3]), (ax, ay), "node {k}");
    }
    let (ax, ay) = field(x[0], x[3], x[4]);
    assert_eq!((dx[3], dx[4], dx[5]), (ax, ay, 0.0));

    // stretched but shortening fast: the damper would push, the tether does not
    let mut y = plant.state_at(0.0, 0.0, 0.0, 0.0).unwrap();
    let k = 6 + 4 * 3; // the last node, below the main satellite (x < 0)
    y[k + 2] = -10.0; // rushing down towards the sub-satellite
    let stretch = plant.tension(&plant.state_at(0.0, 0.0, 0.0, 0.0).unwrap(), 4);
    assert!(
        stretch > 0.0,
        "at rest the last segment is taut ({stretch} N)"
    );
    assert_eq!(plant.tension(&y, 4), 0.0);
    // and a run that goes slack: the sub-satellite thrown up towards the main satellite; every
    // tension stays >= 0 along it
    let mut x0 = plant.state_at(0.0, 0.0, 0.0, 0.0).unwrap();
    assert!(x0[0] < 0.0);
    x0[3] = 0.02;
    let mut slack_seen = false;
    integrate(
        &plant,
        x0,
        Vector2::zeros(),
        20.0,
        plant.max_step(),
        |_, x| {
            for j in 0..=4 {
                let t = plant.tension(x, j);
                assert!(t >= 0.0);
                slack_seen |= t == 0.0;
            }
        },
    );
    assert!(slack_seen, "the run went slack somewhere");
}

/// Zero crossings of phi, linearly interpolated.
fn crossings<const N: usize, const S: usize>(
    plant: &TetheredFlexible<N, S>,
    x0: SVector<f64, S>,
    t_end: f64,
    h: f64,
) -> Vec<f64> {
    let mut out = Vec::new();
    let mut last: Option<(f64, f64)> = None;
    integrate(plant, x0, Vector2::zeros(), t_end, h, |t, x| {
        let phi = plant.coordinates(x).0[0];
        if let Some((t0, p0)) = last
            && (p0 > 0.0 && phi <= 0.0 || p0 < 0.0 && phi >= 0.0)
        {
            out.push(t0 + (t - t0) * p0 / (p0 - phi));
        }
        last = Some((t, phi));
    });
    out
}

#[test]
fn small_in_plane_libration_has_the_dumbbell_frequency() {
    // the rigid-dumbbell limit: a light, stiff tether and a small sub-satellite
    let plant = TetheredFlexible::<2, 14> {
        body: body(FAST_ORBIT, 0.02),
        density: 1e-4,
        axial_stiffness: 1e4,
        axial_damping: 1.0,
    };
    let x0 = plant.state_at(0.01, 0.01, 0.0, 0.0).unwrap();
    let period = std::f64::consts::TAU / (3f64.sqrt() * FAST_ORBIT);
    let zc = crossings(&plant, x0, 2.2 * period, 4e-3);
    assert!(zc.len() >= 4, "{zc:?}");
    // three half periods between the first and the fourth crossing
    let measured = (zc[3] - zc[0]) / 1.5;
    let rel = measured / period - 1.0;
    // the elastic tether shifts it by O(n^2 L m_s / EA) = 4e-5 here
    assert!(
        rel.abs() < 2e-4,
        "period {measured} s against sqrt(3) n: {period} s ({rel:+.2e})"
    );
    // not a trivially long window: a wrong frequency (e.g. the 2 n of a free point mass's
    // epicycle) would miss by 13 %
    assert!((std::f64::consts::TAU / (2.0 * FAST_ORBIT) / period - 1.0).abs() > 0.1);
}

/// Sub-satellite position after a lateral thrust, for N nodes (a heavy tether, so its
/// transverse waves matter to the end body).
fn pushed<const N: usize, const S: usize>() -> Vector2<f64> {
    let plant = TetheredFlexible::<N, S> {
        body: body(FAST_ORBIT, 1.0),
        density: 0.05,
        axial_stiffness: 1e3,
        axial_damping: 1.0,
    };
    let x0 = plant.state_at(0.0, 0.0, 0.0, 0.0).unwrap();
    let x = integrate(&plant, x0, Vector2::new(0.2, 0.0), 30.0, 5e-3, |_, _| {});
    Vector2::new(x[0], x[1])
}

#[test]
fn refining_the_tether_converges() {
    let reference = pushed::<32, 134>();
    let e = [
        (pushed::<2, 14>() - reference).norm(),
        (pushed::<4, 22>() - reference).norm(),
        (pushed::<8, 38>() - reference).norm(),
        (pushed::<16, 70>() - reference).norm(),
    ];
    // second order in h = L0 / (N + 1) would divide the error by about 4 per doubling (a bit
    // less here, since N = 32 is itself only a reference)
    for w in e.windows(2) {
        assert!(
            w[1] < 0.45 * w[0],
            "errors against N = 32 do not shrink: {e:?}"
        );
    }
    // and the differences are not round-off: the coarsest model is visibly off
    assert!(e[0] > 1e-3, "{e:?}");
}

/// The derivative the rollout asks for, written into its stage buffer, sets every component
/// whatever the buffer held (it is not cleared first): the same bits as the derivative made
/// fresh, into a buffer of NaNs and into one holding another state's derivative. An odd node
/// count takes the path of the last, unpaired segment.
#[test]
fn the_derivative_written_in_place_sets_every_component() {
    fn check<const N: usize, const S: usize>() {
        let plant = TetheredFlexible::<N, S> {
            body: body(FAST_ORBIT, 1.0),
            density: 0.01,
            axial_stiffness: 50.0,
            axial_damping: 0.3,
        };
        let mut x = plant.state_at(0.1, 0.3, 0.002, 0.05).unwrap();
        // bend and shake the chain so that every component of x' is nonzero
        for (i, v) in x.iter_mut().enumerate().skip(6) {
            *v += 1e-3 * ((i * 7 % 11) as f64 - 5.0);
        }
        let (u, d) = (Vector2::new(0.02, -0.01), Vector2::new(1e-4, 2e-4));
        let fresh = plant.derivative(0.0, &x, &u, &d);
        let other = plant.derivative(0.0, &(x * 1.01), &u, &d);
        for start in [SVector::<f64, S>::from_element(f64::NAN), other] {
            let mut dx = start;
            plant.derivative_into(0.0, &x, &u, &d, &Vector2::zeros(), &mut dx);
            for i in 0..S {
                assert_eq!(
                    dx[i].to_bits(),
                    fresh[i].to_bits(),
                    "N = {N}, component {i}"
                );
            }
        }
    }
    check::<4, 22>();
    check::<5, 26>();
}
