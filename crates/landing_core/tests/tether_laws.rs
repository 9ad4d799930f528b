//! Laws 8 and 9 (seed 003): the piecewise zeta, the RBF adaptation against a hand computation,
//! and closed-loop behaviour on the tethered satellite (issue 5, item 3).

use landing_core::SimConfig;
use landing_core::batch::{Batch, BatchOutput, PerCase, RunOptions, run};
use landing_core::control::rbf::{MAX_NODES, centre};
use landing_core::control::{
    AnyLaw, ControlLaw, FixedTimeNtsmc, LawInput, Ntsmc, zeta, zeta_slope,
};
use landing_core::disturbance::Disturbance;
use landing_core::error::Validate;
use landing_core::plant::PlantModel;
use landing_core::plant::tether::TetheredSimplified;
use landing_core::reference::{RefPoint, Reference};
use nalgebra::{SMatrix, Vector2};

/// Table 2 with alpha_s and beta_s in the text's roles, and a small network.
fn fntsmc(gamma: f64) -> FixedTimeNtsmc<2> {
    FixedTimeNtsmc {
        k1: Vector2::new(0.08, 0.6),
        k2: Vector2::new(0.08, 0.5),
        k3: Vector2::new(0.09, 0.8),
        eps_max: Vector2::repeat(1e-4),
        p1: Vector2::repeat(1.1),
        p2: Vector2::new(0.99, 0.6),
        alpha_s: Vector2::new(0.89, 0.7),
        beta_s: Vector2::new(1.1, 1.8),
        sigma_phi: Vector2::new(0.01, 0.001),
        gamma: Vector2::repeat(gamma),
        rbf_nodes: 3,
        rbf_scale_e1: Vector2::new(0.02, 0.02),
        rbf_scale_e2: Vector2::new(2e-3, 0.03),
        rbf_width: Vector2::repeat(1.0),
    }
}

fn ntsmc() -> Ntsmc<2> {
    Ntsmc {
        alpha: Vector2::repeat(1.0),
        beta: Vector2::new(0.05, 0.3),
        gamma: Vector2::new(1.07, 1.1),
        k: Vector2::repeat(0.001),
    }
}

fn input(e: [f64; 2], de: [f64; 2], dt: f64) -> LawInput<2> {
    let zero = Vector2::zeros();
    LawInput {
        t: 0.0,
        dt,
        e: Vector2::from(e),
        de: Vector2::from(de),
        reference: RefPoint {
            position: zero,
            velocity: zero,
            acceleration: zero,
        },
        drift: zero,
        inertia: TetheredSimplified::default().body.inertia(),
    }
}

#[test]
fn zeta_value_and_slope_are_continuous_at_sigma() {
    for (p, sigma) in [
        (1.1f64, 0.01f64),
        (0.99, 0.01),
        (0.6, 0.001),
        (1.8, 0.3),
        (0.2, 2.0),
    ] {
        for side in [1.0, -1.0] {
            let at = side * sigma;
            let (inside, outside) = (at * (1.0 - 1e-12), at * (1.0 + 1e-12));
            // value: both branches meet sig^p(sigma)
            let target = side * sigma.powf(p);
            for e in [inside, outside] {
                assert!(
                    (zeta(e, p, sigma) - target).abs() < 1e-9 * sigma.powf(p),
                    "p {p}: {e}"
                );
            }
            // slope: one-sided finite differences on each branch agree with p sigma^(p-1)
            let slope = p * sigma.powf(p - 1.0);
            let h = 1e-6 * sigma;
            let left = (zeta(at, p, sigma) - zeta(at - h * side, p, sigma)) / h * side;
            let right = (zeta(at + h * side, p, sigma) - zeta(at, p, sigma)) / h * side;
            for fd in [left, right] {
                assert!(
                    (fd - slope).abs() < 1e-4 * slope,
                    "p {p} sigma {sigma}: {fd} vs {slope}"
                );
            }
            assert!((zeta_slope(inside, p, sigma) - slope).abs() < 1e-8 * slope);
            assert!((zeta_slope(outside, p, sigma) - slope).abs() < 1e-8 * slope);
        }
        // the analytic slope is the derivative of the value everywhere (both branches)
        for e in [0.0, 0.3 * sigma, -0.8 * sigma, 1.7 * sigma, -5.0 * sigma] {
            let h = 1e-7 * sigma;
            let fd = (zeta(e + h, p, sigma) - zeta(e - h, p, sigma)) / (2.0 * h);
            assert!(
                (fd - zeta_slope(e, p, sigma)).abs()
                    < 1e-5 * zeta_slope(e, p, sigma).abs().max(1e-9)
            );
        }
        // zeta is odd and increasing: it orders like its argument
        assert_eq!(zeta(0.0, p, sigma), 0.0);
        assert!(zeta(-0.5 * sigma, p, sigma) == -zeta(0.5 * sigma, p, sigma));
        assert!(zeta_slope(0.0, p, sigma) > 0.0 && zeta_slope(sigma, p, sigma) > 0.0);
    }
}

#[test]
fn one_period_of_adaptation_is_gamma_n_phi() {
    let law = fntsmc(250.0);
    let dt = 0.01;
    let inp = input([0.015, -0.004], [-1e-3, 0.02], dt);
    let mut w = law.start(&inp);
    law.advance(&mut w, &inp);
    let m = inp.inertia;
    for i in 0..2 {
        // by hand, from the seed's formulas
        let (e1, e2) = (inp.e[i], inp.de[i]);
        let sigma = law.sigma_phi[i];
        let z = |p: f64| {
            if e1.abs() > sigma {
                e1.signum() * e1.abs().powf(p)
            } else {
                (2.0 - p) * sigma.powf(p - 1.0) * e1
                    + (p - 1.0) * sigma.powf(p - 2.0) * e1 * e1.abs()
            }
        };
        let s = e2 + law.k1[i] * z(law.p1[i]) + law.k2[i] * z(law.p2[i]);
        let sg = |x: f64, a: f64| x.signum() * x.abs().powf(a);
        let big_n = law.k3[i]
            * (sg(s, 2.0 * law.alpha_s[i] - 1.0) + sg(s, 2.0 * law.beta_s[i] - 1.0))
            / m[i];
        let zn = [e1 / law.rbf_scale_e1[i], e2 / law.rbf_scale_e2[i]];
        let b = law.rbf_width[i];
        for a in 0..3 {
            for c in 0..3 {
                let d2 = (zn[0] - centre(a, 3)).powi(2) + (zn[1] - centre(c, 3)).powi(2);
                let phi = (-d2 / (b * b)).exp();
                let expect = dt * law.gamma[i] * big_n * phi;
                let got = w[(a * 3 + c, i)];
                assert!(
                    (got - expect).abs() <= 1e-12 * expect.abs(),
                    "axis {i} node ({a}, {c}): {got} vs {expect}"
                );
                assert!(got != 0.0);
            }
        }
        for j in 9..MAX_NODES {
            assert_eq!(w[(j, i)], 0.0);
        }
    }
    // and the command then subtracts the network's estimate, in actuator units
    let with = law.command(&w, &inp);
    let without = law.command(&SMatrix::zeros(), &inp);
    let est = law.estimate(&w, &inp);
    for i in 0..2 {
        // to the round-off of the command it is subtracted from
        let diff = (without[i] - with[i]) * m[i];
        assert!(est[i] != 0.0 && (diff - est[i]).abs() < 1e-14 * (without[i] * m[i]).abs());
    }
}

/// The rollout's one call per period (the surfaces and the basis computed once) gives what the
/// command and then the weights' update give, bit for bit, period after period; with one axis
/// adapting and the other not, and through s = 0.
#[test]
fn command_and_advance_is_the_command_then_the_update() {
    let mut law = fntsmc(250.0);
    law.gamma[1] = 0.0;
    let dt = 0.01;
    let mut apart = law.start(&input([0.0; 2], [0.0; 2], dt));
    let mut together = apart;
    for k in 0..40 {
        let t = k as f64;
        // e swings through zero on both axes; at k = 20 the first surface is exactly 0
        let e = if k == 20 {
            [0.0, 0.0]
        } else {
            [0.02 * (0.37 * t).sin(), -0.01 * (0.23 * t).cos()]
        };
        let de = if k == 20 {
            [0.0, 0.0]
        } else {
            [1e-3 * (0.51 * t).cos(), 0.02 * (0.17 * t).sin()]
        };
        let inp = input(e, de, dt);
        let a = law.command(&apart, &inp);
        law.advance(&mut apart, &inp);
        let b = law.command_and_advance(&mut together, &inp);
        for i in 0..2 {
            assert_eq!(
                a[i].to_bits(),
                b[i].to_bits(),
                "period {k}, axis {i}: {} vs {}",
                a[i],
                b[i]
            );
        }
        for (x, y) in apart.iter().zip(together.iter()) {
            assert_eq!(x.to_bits(), y.to_bits(), "period {k}: weights {x} vs {y}");
        }
    }
    assert!(
        apart.column(0).iter().any(|w| *w != 0.0),
        "the first axis adapted"
    );
    assert!(
        apart.column(1).iter().all(|w| *w == 0.0),
        "the second did not"
    );
}

#[test]
fn the_command_is_eq_22() {
    let law = fntsmc(0.0);
    // one axis outside sigma, one inside
    let inp = input([0.0175, 0.0004], [-2e-3, 0.01], 0.01);
    let a = law.command(&law.start(&inp), &inp);
    let m = inp.inertia;
    // axis 0: |e1| > sigma
    let (e1, e2): (f64, f64) = (0.0175, -2e-3);
    let s = e2 + 0.08 * e1.powf(1.1) + 0.08 * e1.powf(0.99);
    let rate = (0.08 * 1.1 * e1.powf(0.1) + 0.08 * 0.99 * e1.powf(-0.01)) * e2;
    let expect = -(rate + 0.09 * (s.abs().powf(0.89) + s.abs().powf(1.1)) * s.signum())
        - 1e-4 * s.signum() / m[0];
    assert!((a[0] - expect).abs() < 1e-15, "{} {}", a[0], expect);
    // axis 1: |e1| < sigma = 0.001: the quadratic branch
    let (e1, e2, sg): (f64, f64, f64) = (0.0004, 0.01, 0.001);
    let l = |p: f64| (2.0 - p) * sg.powf(p - 1.0);
    let mm = |p: f64| (p - 1.0) * sg.powf(p - 2.0);
    let s = e2 + 0.6 * (l(1.1) * e1 + mm(1.1) * e1 * e1) + 0.5 * (l(0.6) * e1 + mm(0.6) * e1 * e1);
    let rate = (0.6 * (l(1.1) + 2.0 * mm(1.1) * e1) + 0.5 * (l(0.6) + 2.0 * mm(0.6) * e1)) * e2;
    let expect = -(rate + 0.8 * (s.abs().powf(0.7) + s.abs().powf(1.8)) * s.signum())
        - 1e-4 * s.signum() / m[1];
    assert!((a[1] - expect).abs() < 1e-14, "{} {}", a[1], expect);
}

#[test]
fn the_law_is_symmetric_in_its_two_reaching_exponents() {
    // Table 2 prints alpha_s and beta_s swapped; swapping them back changes no bit
    let law = fntsmc(250.0);
    let swapped = FixedTimeNtsmc {
        alpha_s: law.beta_s,
        beta_s: law.alpha_s,
        ..law
    };
    let inp = input([0.015, -0.004], [-1e-3, 0.02], 0.01);
    let (mut w1, mut w2) = (law.start(&inp), swapped.start(&inp));
    law.advance(&mut w1, &inp);
    swapped.advance(&mut w2, &inp);
    assert_eq!(w1, w2);
    assert_eq!(law.command(&w1, &inp), swapped.command(&w2, &inp));
    // (the swapped one is refused by the validation, which follows the text's ranges)
    assert!(swapped.validate().is_err());
}

#[test]
fn validation_follows_the_seeds_ranges() {
    let bad = |f: &dyn Fn(&mut FixedTimeNtsmc<2>)| {
        let mut l = fntsmc(1.0);
        f(&mut l);
        l.validate().unwrap_err()
    };
    assert_eq!(bad(&|l| l.p1[0] = 0.9).rule, "p1 > 1");
    assert_eq!(bad(&|l| l.p2[1] = 1.0).rule, "0 < p2 < 1");
    assert_eq!(bad(&|l| l.alpha_s[0] = 1.1).rule, "1/2 < alpha_s < 1");
    assert_eq!(bad(&|l| l.alpha_s[0] = 0.5).rule, "1/2 < alpha_s < 1");
    assert_eq!(bad(&|l| l.beta_s[1] = 0.89).rule, "beta_s > 1");
    assert_eq!(bad(&|l| l.sigma_phi[0] = 0.0).param, "sigma_phi");
    assert_eq!(bad(&|l| l.rbf_nodes = 8).rule, "rbf_nodes in 1..=7");
    assert_eq!(bad(&|l| l.gamma[0] = -1.0).param, "gamma");
    assert!(fntsmc(1.0).validate().is_ok());
}

fn run_on_simplified(law: impl Into<AnyLaw<2>>, t_final: f64) -> BatchOutput<2> {
    let plant = TetheredSimplified::default();
    let deg = std::f64::consts::PI / 180.0;
    let batch = Batch {
        plants: PerCase::shared(plant),
        laws: PerCase::shared(law.into()),
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(Disturbance::none()),
        x0: vec![nalgebra::Vector4::new(deg, deg, 0.0, 0.0)],
    };
    let cfg = SimConfig::new(t_final, 0.01, 1, 1, 0).unwrap();
    run(&batch, &cfg, &RunOptions::default()).unwrap()
}

#[test]
fn both_laws_bring_the_simplified_plant_to_rest() {
    let deg = std::f64::consts::PI / 180.0;
    for out in [
        run_on_simplified(fntsmc(0.0), 150.0),
        run_on_simplified(ntsmc(), 150.0),
    ] {
        let m = &out.metrics[0];
        assert!(m.diverged.is_none());
        // from 1 degree to within 1 % of it, and at rest
        assert!(
            m.final_error.abs().max() < 0.01 * deg,
            "{:?}",
            m.final_error
        );
        assert!(
            m.final_rate_error.abs().max() < 1e-4,
            "{:?}",
            m.final_rate_error
        );
        // the thrust saturates at the seed's 0.1 N and the torque at 0.05 N m
        assert!(m.peak_command_axis[0] <= 0.1 && m.peak_command_axis[1] <= 0.05);
    }
    // the sliding variables are recorded, and s of the FNTSMC is eq. 20 at t = 0
    let out = run_on_simplified(fntsmc(0.0), 1.0);
    let s0 = out.diagnostics[0];
    assert!((s0 - (0.08 * deg.powf(1.1) + 0.08 * deg.powf(0.99))).abs() < 1e-15);
    let plant = TetheredSimplified::default();
    assert_eq!(<TetheredSimplified as PlantModel<2>>::STATE_NAMES[0], "phi");
    assert!(plant.validate().is_ok());
}
