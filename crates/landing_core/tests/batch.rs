//! Batch semantics: independence of cases, determinism across thread counts, recording.

mod common;

use common::*;
use landing_core::SimConfig;
use landing_core::batch::{Batch, PerCase, run_with_threads};
use landing_core::control::{AnyLaw, FixedTimeMss, MssVariant};
use landing_core::disturbance::Disturbance;
use landing_core::metrics::Divergence;
use landing_core::plant::MarsLander;
use landing_core::reference::Reference;
use landing_core::workloads::{mars_dispersed, mars_storm};
use nalgebra::Vector3;

fn dispersed(n: usize) -> Vec<MarsState> {
    mars_dispersed(n, 42)
}

fn noisy() -> Disturbance<3> {
    mars_storm().with_noise(Vector3::repeat(0.5))
}

fn batch(x0: Vec<MarsState>, laws: PerCase<AnyLaw<3>>) -> Batch<3, MarsLander> {
    Batch {
        plants: PerCase::shared(MarsLander {
            thrust_limit: Vector3::repeat(50_000.0),
            ..Default::default()
        }),
        laws,
        references: PerCase::shared(Reference::default()),
        disturbances: PerCase::shared(noisy()),
        x0,
    }
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let b = batch(
        dispersed(37),
        PerCase::shared(reconstructed_gains(MssVariant::Printed).into()),
    );
    let cfg = SimConfig::new(2.0, 0.001, 2, 50, 9).unwrap();
    let one = run_with_threads(&b, &cfg, Some(1)).unwrap();
    let two = run_with_threads(&b, &cfg, Some(2)).unwrap();
    let five = run_with_threads(&b, &cfg, Some(5)).unwrap();
    for other in [&two, &five] {
        assert_eq!(bits(&one.states), bits(&other.states));
        assert_eq!(bits(&one.controls), bits(&other.controls));
        assert_eq!(bits(&one.final_state), bits(&other.final_state));
        // NaN != NaN, so compare the metrics' printed forms (exact for f64 Debug)
        assert!(format!("{:?}", one.metrics) == format!("{:?}", other.metrics));
    }
}

fn bits(v: &[f64]) -> Vec<u64> {
    v.iter().map(|x| x.to_bits()).collect()
}

#[test]
fn a_case_is_the_same_alone_or_in_a_batch() {
    // per-case gains: each case of the batch equals its own single-case run
    let x0 = dispersed(6);
    let laws: Vec<_> = (0..6)
        .map(|i| FixedTimeMss {
            alpha1: Vector3::repeat(0.5 + 0.1 * i as f64),
            ..reconstructed_gains(MssVariant::Printed)
        })
        .collect();
    let cfg = SimConfig::new(1.0, 0.001, 1, 100, 3).unwrap();
    let all = run_with_threads(
        &batch(
            x0.clone(),
            PerCase::from_vec(laws.iter().map(|&l| l.into()).collect()),
        ),
        &cfg,
        Some(2),
    )
    .unwrap();
    for i in 0..6 {
        // alone, the case keeps its global index (and so its random streams)
        let alone_cfg = cfg.with_first_case(i as u64);
        let alone = run_with_threads(
            &batch(vec![x0[i]], PerCase::shared(laws[i].into())),
            &alone_cfg,
            Some(1),
        )
        .unwrap();
        assert_eq!(
            bits(&all.final_state[i * 7..(i + 1) * 7]),
            bits(&alone.final_state)
        );
        let nr = all.n_records();
        assert_eq!(
            bits(&all.states[i * nr * 7..(i + 1) * nr * 7]),
            bits(&alone.states)
        );
    }
    // and the gains did make a difference
    assert_ne!(bits(&all.final_state[0..7]), bits(&all.final_state[7..14]));
}

#[test]
fn chunks_of_a_campaign_reproduce_it() {
    let x0 = dispersed(10);
    let cfg = SimConfig::new(0.5, 0.001, 1, 0, 5).unwrap();
    let whole = run_with_threads(
        &batch(
            x0.clone(),
            PerCase::shared(reconstructed_gains(MssVariant::Printed).into()),
        ),
        &cfg,
        None,
    )
    .unwrap();
    let mut pieces = Vec::new();
    for (start, end) in [(0, 3), (3, 4), (4, 10)] {
        let part = batch(
            x0[start..end].to_vec(),
            PerCase::shared(reconstructed_gains(MssVariant::Printed).into()),
        );
        pieces.extend(
            run_with_threads(&part, &cfg.with_first_case(start as u64), Some(1))
                .unwrap()
                .final_state,
        );
    }
    assert_eq!(bits(&whole.final_state), bits(&pieces));
    // and the noise matters: numbering the pieces from 0 changes them
    let wrong = run_with_threads(
        &batch(
            x0[3..4].to_vec(),
            PerCase::shared(reconstructed_gains(MssVariant::Printed).into()),
        ),
        &cfg,
        None,
    )
    .unwrap();
    assert_ne!(bits(&wrong.final_state), bits(&whole.final_state[21..28]));
}

#[test]
fn a_diverging_case_is_flagged_and_spoils_nothing() {
    // Case 2 starts 1e200 m away with an unlimited engine: the command overflows to infinity
    // within a few steps. The others have the 50 kN limit.
    let mut x0 = dispersed(4);
    x0[2] = mars_state([1e200, 0.0, 1500.0], [0.0, 0.0, 0.0], 1905.0);
    let mut b = batch(
        x0.clone(),
        PerCase::shared(reconstructed_gains(MssVariant::Printed).into()),
    );
    let limited = *b.plants.get(0);
    let mut plants = vec![limited; 4];
    plants[2] = MarsLander::default();
    b.plants = PerCase::from_vec(plants);
    let cfg = SimConfig::new(1.0, 0.01, 1, 10, 0).unwrap();
    let out = run_with_threads(&b, &cfg, Some(2)).unwrap();
    let flags: Vec<bool> = out.metrics.iter().map(|m| m.diverged.is_some()).collect();
    assert_eq!(flags, [false, false, true, false]);
    // 1e200 m away, the law's powers of the error overflow in its first command
    let stop = out.metrics[2].diverged.unwrap();
    assert_eq!(stop.reason, Divergence::NonFiniteCommand);
    assert_eq!(stop.time, 0.0);
    assert!(out.final_state[14..21].iter().all(|v| v.is_nan()));
    assert!(out.metrics[2].final_error.iter().all(|v| v.is_nan()));
    // the healthy cases equal a batch without the bad one
    let mut clean = x0.clone();
    clean[2] = x0[0];
    let ref_out = run_with_threads(
        &batch(
            clean,
            PerCase::shared(reconstructed_gains(MssVariant::Printed).into()),
        ),
        &cfg,
        Some(1),
    )
    .unwrap();
    for i in [0usize, 1, 3] {
        assert_eq!(
            bits(&out.final_state[i * 7..(i + 1) * 7]),
            bits(&ref_out.final_state[i * 7..(i + 1) * 7])
        );
        assert!(
            out.final_state[i * 7..(i + 1) * 7]
                .iter()
                .all(|v| v.is_finite())
        );
    }
}

#[test]
fn recording_keeps_every_kth_instant_and_the_last() {
    let b = batch(
        dispersed(2),
        PerCase::shared(reconstructed_gains(MssVariant::Printed).into()),
    );
    let cfg = SimConfig::new(1.0, 0.1, 1, 3, 0).unwrap();
    assert_eq!(
        cfg.record_times(),
        vec![0.0, 0.30000000000000004, 0.6000000000000001, 0.9, 1.0]
    );
    let out = run_with_threads(&b, &cfg, None).unwrap();
    assert_eq!(out.n_records(), 5);
    // first record is x0, last equals the final state
    assert_eq!(&out.states[0..7], b.x0[0].as_slice());
    let nr = out.n_records();
    assert_eq!(&out.states[(nr - 1) * 7..nr * 7], &out.final_state[0..7]);
    // record_every = 0 keeps the final states and metrics only
    let cfg0 = SimConfig::new(1.0, 0.1, 1, 0, 0).unwrap();
    let out0 = run_with_threads(&b, &cfg0, None).unwrap();
    assert!(out0.states.is_empty() && out0.times.is_empty());
    assert_eq!(bits(&out0.final_state), bits(&out.final_state));
}

#[test]
fn horizon_must_be_whole_periods() {
    assert!(SimConfig::new(1.0, 0.3, 1, 1, 0).is_err());
    assert!(SimConfig::new(8000.0, 0.01, 1, 1, 0).is_ok());
    assert_eq!(
        SimConfig::new(8000.0, 0.01, 1, 1, 0).unwrap().steps,
        800_000
    );
    assert_eq!(
        SimConfig::new(-1.0, 0.1, 1, 1, 0).unwrap_err().param,
        "t_final"
    );
    assert_eq!(SimConfig::new(1.0, 0.0, 1, 1, 0).unwrap_err().param, "dt");
    assert_eq!(
        SimConfig::new(1.0, 0.1, 0, 1, 0).unwrap_err().param,
        "substeps"
    );
}

/// Final states and metrics of a batch as bits (NaN-safe).
fn fingerprint<const D: usize>(out: &landing_core::BatchOutput<D>) -> (Vec<u64>, Vec<u64>, String) {
    (
        bits(&out.final_state),
        bits(&out.states),
        format!("{:?}", out.metrics),
    )
}

#[test]
fn every_level_gives_the_same_bits() {
    use landing_core::batch::{RunOptions, run};
    use landing_core::workloads::{eros_w3, eros_w5, tether_w6};
    use landing_core::{Level, SimConfig};
    let levels = Level::supported();
    let at = |level: Level| RunOptions {
        threads: Some(2),
        level: Some(level),
        cancel: None,
        recording: None,
    };
    // W1-like with noise, per-case gains and recording; W3; W5 (fuzzy, command noise); W6
    let mut x0 = dispersed(21);
    x0[3][3] = 1e200; // drag overflows: the case diverges (a masked lane among live ones)
    let laws: Vec<AnyLaw<3>> = (0..21)
        .map(|i| {
            FixedTimeMss {
                alpha1: Vector3::repeat(0.5 + 0.05 * i as f64),
                ..reconstructed_gains(MssVariant::Printed)
            }
            .into()
        })
        .collect();
    let mars = batch(x0, PerCase::from_vec(laws));
    let cfg = SimConfig::new(0.5, 0.001, 2, 37, 7).unwrap();
    let w3 = eros_w3(19, 3);
    let cfg3 = SimConfig::new(2.0, 0.01, 1, 10, 0).unwrap();
    let w5 = eros_w5(19, 3);
    let cfg5 = SimConfig::new(20.0, 0.1, 1, 10, 11).unwrap();
    let w6 = tether_w6(9, 3);
    let cfg6 = SimConfig::new(0.5, 0.01, 6, 5, 0).unwrap();
    let reference = (
        fingerprint(&run(&mars, &cfg, &at(Level::Baseline)).unwrap()),
        fingerprint(&run(&w3, &cfg3, &at(Level::Baseline)).unwrap()),
        fingerprint(&run(&w5, &cfg5, &at(Level::Baseline)).unwrap()),
        fingerprint(&run(&w6, &cfg6, &at(Level::Baseline)).unwrap()),
    );
    assert!(
        run(&mars, &cfg, &at(Level::Baseline)).unwrap().metrics[3]
            .diverged
            .is_some(),
        "the case with an absurd speed diverges"
    );
    for &level in &levels[1..] {
        let out = run(&mars, &cfg, &at(level)).unwrap();
        assert_eq!(out.level, level);
        assert_eq!(fingerprint(&out), reference.0, "W1 at {level:?}");
        assert_eq!(
            fingerprint(&run(&w3, &cfg3, &at(level)).unwrap()),
            reference.1,
            "W3 at {level:?}"
        );
        assert_eq!(
            fingerprint(&run(&w5, &cfg5, &at(level)).unwrap()),
            reference.2,
            "W5 at {level:?}"
        );
        assert_eq!(
            fingerprint(&run(&w6, &cfg6, &at(level)).unwrap()),
            reference.3,
            "W6 at {level:?}"
        );
    }
    eprintln!("compared levels {levels:?}");
}

#[test]
fn a_case_does_not_depend_on_its_lane_or_its_block_mates() {
    use landing_core::batch::{RunOptions, run};
    use landing_core::{Level, SimConfig};
    // 5 cases numbered 40..45; then the same cases behind k other cases (so that they sit at
    // other lanes of other blocks, beside other cases), with the same global indices
    let x0 = dispersed(60);
    let laws = |range: std::ops::Range<usize>| -> PerCase<AnyLaw<3>> {
        PerCase::from_vec(
            range
                .map(|i| {
                    FixedTimeMss {
                        beta1: Vector3::repeat(0.7 + 0.01 * i as f64),
                        ..reconstructed_gains(MssVariant::Printed)
                    }
                    .into()
                })
                .collect(),
        )
    };
    let cfg = SimConfig::new(0.3, 0.001, 1, 50, 17).unwrap();
    for level in Level::supported() {
        let options = RunOptions {
            threads: Some(1),
            level: Some(level),
            cancel: None,
            recording: None,
        };
        let alone = run(
            &batch(x0[40..45].to_vec(), laws(40..45)),
            &cfg.with_first_case(40),
            &options,
        )
        .unwrap();
        for k in [1usize, 3, 7, 13, 21, 35] {
            let shifted = run(
                &batch(x0[40 - k..45].to_vec(), laws(40 - k..45)),
                &cfg.with_first_case((40 - k) as u64),
                &options,
            )
            .unwrap();
            let nr = alone.n_records();
            assert_eq!(
                bits(&shifted.final_state[k * 7..]),
                bits(&alone.final_state),
                "{level:?}, {k} cases before"
            );
            assert_eq!(bits(&shifted.states[k * nr * 7..]), bits(&alone.states));
            assert_eq!(
                format!("{:?}", &shifted.metrics[k..]),
                format!("{:?}", alone.metrics)
            );
        }
        // and one case alone in a padded block
        for (i, x) in x0.iter().enumerate().take(45).skip(40) {
            let one = run(
                &batch(vec![*x], laws(i..i + 1)),
                &cfg.with_first_case(i as u64),
                &options,
            )
            .unwrap();
            assert_eq!(
                bits(&one.final_state),
                bits(&alone.final_state[(i - 40) * 7..(i - 39) * 7])
            );
        }
    }
}

#[test]
fn a_lent_recording_holds_the_bits_the_batch_records_in_its_own() {
    use landing_core::batch::{BatchError, RunOptions, run};
    let mut x0 = dispersed(21);
    x0[3][3] = 1e200; // a diverging case: NaN from its divergence on
    let b = batch(
        x0,
        PerCase::shared(reconstructed_gains(MssVariant::Printed).into()),
    );
    let cfg = SimConfig::new(0.5, 0.001, 2, 37, 7).unwrap();
    let own = run_with_threads(&b, &cfg, Some(2)).unwrap();
    let (nr, nx, nd) = (own.n_records(), own.state_dim, own.diagnostic_dim);
    assert!(
        own.states.iter().any(|x| x.is_nan()),
        "the diverged case records NaN"
    );
    for threads in [1, 2] {
        let mut lent = LentBuffers::new(21, nr, [nx, 3, nd]);
        let out = run(&b, &cfg, &lent.options(threads)).unwrap();
        // the caller holds the recording; the batch hands back the rest
        assert!(out.states.is_empty() && out.controls.is_empty() && out.diagnostics.is_empty());
        assert_eq!(out.n_records(), nr);
        assert_eq!(bits(&lent.states), bits(&own.states));
        assert_eq!(bits(&lent.controls), bits(&own.controls));
        assert_eq!(bits(&lent.diagnostics), bits(&own.diagnostics));
        assert_eq!(bits(&out.final_state), bits(&own.final_state));
        assert_eq!(format!("{:?}", out.metrics), format!("{:?}", own.metrics));
    }
    // a shape other than the batch's is refused before anything runs or is written
    let mut wrong = LentBuffers::new(21, nr, [nx, 3, nd + 1]);
    let options: RunOptions<'_> = wrong.options(2);
    match run(&b, &cfg, &options) {
        Err(BatchError::Lent {
            what,
            shape,
            expected,
        }) => {
            assert_eq!(what, "diagnostics");
            assert_eq!((shape, expected), ([21, nr, nd + 1], [21, nr, nd]));
        }
        other => panic!("expected a refused lent shape, got {other:?}"),
    }
    assert!(wrong.states.iter().all(|&x| x == 7.25));
}
