//! Property: every lane kernel gives the bits of the width-1 instance of the same rollout
//! (`run_scalar`, one case at a time in `f64`), whatever the cases, their number (partial
//! blocks), their gains, the seed, the substeps, and cases that diverge beside healthy ones.

use landing_core::batch::{Batch, PerCase, RunOptions, run, run_scalar};
use landing_core::control::{AnyLaw, MssVariant};
use landing_core::plant::PlantModel;
use landing_core::workloads::{
    eros_w3, eros_w5, mars_w1, reconstructed_fixed_time_gains, tether_w6,
};
use landing_core::{BatchOutput, Level, SimConfig};
use nalgebra::Vector3;
use proptest::prelude::*;

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

fn fingerprint<const D: usize>(out: &BatchOutput<D>) -> (Vec<u64>, Vec<u64>, Vec<u64>, String) {
    (
        bits(&out.final_state),
        bits(&out.states),
        bits(&out.controls),
        // exact for f64 (shortest round-trip), and NaN prints as NaN
        format!("{:?}", out.metrics),
    )
}

/// Every level this CPU has against the scalar path.
fn check_levels<const D: usize, P: PlantModel<D>>(b: &Batch<D, P>, cfg: &SimConfig) {
    let scalar = fingerprint(&run_scalar(b, cfg, Some(2)).unwrap());
    for level in Level::supported() {
        let options = RunOptions {
            threads: Some(2),
            level: Some(level),
            cancel: None,
            recording: None,
        };
        let lanes = fingerprint(&run(b, cfg, &options).unwrap());
        assert!(lanes == scalar, "{level:?} differs from the scalar path");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, ..ProptestConfig::default() })]

    #[test]
    fn mars_lanes_are_the_scalar_path(
        seed in any::<u64>(),
        n in 1usize..45,
        alpha1 in 0.2f64..3.0,
        q1 in 0.05f64..0.95,
        exact in any::<bool>(),
        substeps in 1u32..3,
        noise in 0.0f64..2.0,
        wild in proptest::collection::vec(0.0f64..300.0, 0..4),
    ) {
        let mut b = mars_w1(n, seed);
        let variant = if exact { MssVariant::Exact } else { MssVariant::Printed };
        let laws: Vec<AnyLaw<3>> = (0..n)
            .map(|i| {
                let mut g = reconstructed_fixed_time_gains(variant);
                g.alpha1 = Vector3::repeat(alpha1 + 0.01 * i as f64);
                g.q1 = Vector3::repeat(q1);
                g.into()
            })
            .collect();
        b.laws = PerCase::from_vec(laws);
        b.disturbances = PerCase::shared(
            landing_core::workloads::mars_storm().with_noise(Vector3::repeat(noise)),
        );
        // a few cases start absurdly far away (10^e m): they diverge in some lanes of a block
        // while the others go on
        for (k, e) in wild.iter().enumerate() {
            let i = (k * 7 + 3) % n;
            b.x0[i][0] = 10f64.powf(*e);
        }
        let cfg = SimConfig::new(0.3, 0.01, substeps, 7, seed).unwrap();
        check_levels(&b, &cfg);
    }

    #[test]
    fn small_body_and_tether_lanes_are_the_scalar_path(seed in any::<u64>(), n in 1usize..20) {
        check_levels(&eros_w3(n, seed), &SimConfig::new(1.0, 0.01, 1, 9, seed).unwrap());
        check_levels(&eros_w5(n, seed), &SimConfig::new(2.0, 0.1, 2, 3, seed).unwrap());
        check_levels(&tether_w6(n.min(9), seed), &SimConfig::new(0.2, 0.01, 3, 4, seed).unwrap());
    }
}
