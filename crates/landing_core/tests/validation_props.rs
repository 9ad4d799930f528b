//! Property tests of the core's parameter validation: for generated parameter values
//! (ordinary, boundary, negative, zero, NaN and infinite), `validate()` never panics and
//! accepts exactly the documented ranges (docs/parameters.md and the law's paper), checked
//! against the rules written out again here, independently of the code under test.

use landing_core::control::{FixedTimeMss, MssVariant, SuperTwisting, SuperTwistingVariant};
use landing_core::error::Validate;
use landing_core::fuzzy::{Mamdani, Rule, Variable, even_triangles};
use landing_core::gravity::Uniform;
use landing_core::limits::{LIMITS, MAX_FUZZY_RESOLUTION};
use landing_core::plant::MarsLander;
use nalgebra::{SVector, Vector3};
use proptest::prelude::*;

/// Values that hit every side of the rules: around 0 and 1, negative, huge, NaN and Inf.
fn value() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => -3.0..3.0f64,
        1 => prop::sample::select(vec![
            0.0,
            -0.0,
            1.0,
            0.5,
            2.0,
            -1.0,
            f64::MIN_POSITIVE,
            1.0 - f64::EPSILON,
            1.0 + f64::EPSILON,
            1e300,
            -1e300,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ]),
    ]
}

fn axes3() -> impl Strategy<Value = [f64; 3]> {
    [value(), value(), value()]
}

/// A parameter's name, its values and its documented rule.
type Check<'a> = (&'static str, &'a [f64], fn(f64) -> bool);

/// The first (name, value) that breaks its rule, in the order the parameters are documented.
fn first_violation(checks: &[Check<'_>]) -> Option<(&'static str, f64)> {
    for (name, values, ok) in checks {
        for &v in *values {
            if !(v.is_finite() && ok(v)) {
                return Some((name, v));
            }
        }
    }
    None
}

/// `validate()` accepted the value (`expected` None) or refused it naming the expected
/// parameter and value.
fn check(
    got: Result<(), landing_core::ParamError>,
    expected: Option<(&str, f64)>,
) -> Result<(), TestCaseError> {
    match (got, expected) {
        (Ok(()), None) => {}
        (Err(e), Some((name, value))) => {
            prop_assert_eq!(e.param, name);
            prop_assert!(
                same_value(e.value, value),
                "{} reported {} for {}",
                name,
                e.value,
                value
            );
        }
        (got, want) => prop_assert!(
            false,
            "validate() = {:?}, expected a violation {:?}",
            got,
            want
        ),
    }
    Ok(())
}

fn same_value(a: f64, b: f64) -> bool {
    (a.is_nan() && b.is_nan()) || a == b
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    /// Seed 001 eq. 15-25: beta > 0, 0 < q1 < 1 < q2, alpha > 0, 0 < gamma1 < 1 < gamma2,
    /// s1_floor > 0, all finite.
    #[test]
    fn fixed_time_mss_accepts_exactly_its_ranges(
        beta1 in axes3(), beta2 in axes3(), q1 in axes3(), q2 in axes3(),
        alpha1 in axes3(), alpha2 in axes3(), gamma1 in axes3(), gamma2 in axes3(),
        s1_floor in value(),
    ) {
        let v = SVector::<f64, 3>::from;
        let law = FixedTimeMss::<3> {
            beta1: v(beta1), beta2: v(beta2), q1: v(q1), q2: v(q2),
            alpha1: v(alpha1), alpha2: v(alpha2), gamma1: v(gamma1), gamma2: v(gamma2),
            variant: MssVariant::Printed, s1_floor,
        };
        let positive = |x: f64| x > 0.0;
        let unit = |x: f64| x > 0.0 && x < 1.0;
        let above_one = |x: f64| x > 1.0;
        let expected = first_violation(&[
            ("beta1", &beta1, positive), ("beta2", &beta2, positive),
            ("q1", &q1, unit), ("q2", &q2, above_one),
            ("alpha1", &alpha1, positive), ("alpha2", &alpha2, positive),
            ("gamma1", &gamma1, unit), ("gamma2", &gamma2, above_one),
            ("s1_floor", &[s1_floor], positive),
        ]);
        check(law.validate(), expected)?;
    }

    /// Seed 001 eq. 46: b1, b2, c > 0 per axis, s_floor > 0, all finite.
    #[test]
    fn super_twisting_accepts_exactly_its_ranges(
        b1 in axes3(), b2 in axes3(), c in axes3(), s_floor in value(),
    ) {
        let v = SVector::<f64, 3>::from;
        let law = SuperTwisting::<3> {
            b1: v(b1), b2: v(b2), c: v(c), variant: SuperTwistingVariant::Printed, s_floor,
        };
        let positive = |x: f64| x > 0.0;
        let expected = first_violation(&[
            ("b1", &b1, positive), ("b2", &b2, positive), ("c", &c, positive),
            ("s_floor", &[s_floor], positive),
        ]);
        check(law.validate(), expected)?;
    }

    /// The Mars lander: isp, area, g0 > 0; gravity, drag_coefficient, density_decay >= 0; all
    /// finite, except the thrust limit, which may be infinite (no limit) but not NaN or <= 0.
    #[test]
    fn mars_lander_accepts_exactly_its_ranges(
        isp in value(), area in axes3(), gravity in value(), g0 in value(),
        drag_coefficient in value(), density_decay in value(),
        thrust_limit in [value(), value(), value()],
    ) {
        let plant = MarsLander {
            isp, area: Vector3::from(area), gravity: Uniform { g0: gravity }, g0, drag: true,
            drag_coefficient, density_decay, thrust_limit: Vector3::from(thrust_limit),
            ..MarsLander::default()
        };
        let positive = |x: f64| x > 0.0;
        let nonnegative = |x: f64| x >= 0.0;
        let expected = first_violation(&[
            ("isp", &[isp], positive), ("area", &area, positive),
            ("gravity", &[gravity], nonnegative), ("g0", &[g0], positive),
            ("drag_coefficient", &[drag_coefficient], nonnegative),
            ("density_decay", &[density_decay], nonnegative),
        ])
        .or_else(|| {
            thrust_limit.iter().find(|l| l.is_nan() || **l <= 0.0).map(|&l| ("thrust_limit", l))
        });
        check(plant.validate(), expected)?;
    }

    /// A fuzzy system's resolution: 2 <= resolution <= MAX_FUZZY_RESOLUTION, refused before
    /// anything of that size is allocated (a resolution of usize::MAX must not abort).
    #[test]
    fn fuzzy_resolution_accepts_exactly_its_range(
        resolution in prop_oneof![
            0usize..8,
            (MAX_FUZZY_RESOLUTION as usize - 2)..(MAX_FUZZY_RESOLUTION as usize + 3),
            (MAX_FUZZY_RESOLUTION as usize + 3)..usize::MAX,
            Just(usize::MAX),
        ],
    ) {
        let var = |lo: f64, hi: f64, n: usize| Variable { lo, hi, sets: even_triangles(lo, hi, n) };
        let rules = (0..3).map(|i| Rule { antecedent: vec![i], consequent: 2 - i }).collect();
        let system = Mamdani::new(vec![var(-1.0, 1.0, 3)], var(-2.0, 2.0, 3), rules, resolution);
        let valid = (2..=MAX_FUZZY_RESOLUTION as usize).contains(&resolution);
        match system {
            Ok(m) => {
                prop_assert!(valid, "resolution {} accepted", resolution);
                prop_assert_eq!(m.resolution(), resolution);
            }
            Err(e) => {
                prop_assert!(!valid, "resolution {} refused: {}", resolution, e);
                prop_assert_eq!(e.param, "resolution");
            }
        }
    }
}

#[test]
fn the_limits_are_listed_once_by_name() {
    let names: Vec<&str> = LIMITS.iter().map(|(n, _)| *n).collect();
    assert_eq!(
        names,
        [
            "max_cases",
            "max_steps",
            "max_substeps",
            "max_threads",
            "max_fuzzy_resolution"
        ]
    );
    assert!(LIMITS.iter().all(|(_, v)| *v >= 1024));
}
