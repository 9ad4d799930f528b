//! `RunRequest::compile`: the one place run options from outside Rust are checked.

use landing_core::batch::RunRequest;
use landing_core::event::Event;
use landing_core::integrator::IntegratorKind;
use landing_core::{Level, Tolerance};

fn request() -> RunRequest<'static> {
    RunRequest {
        t_final: 2.0,
        dt: 0.01,
        integrator: "euler",
        substeps: 3,
        record_every: 10,
        seed: u64::MAX,
        first_case: 7,
        settle_tolerance: 0.5,
        settle_relative: false,
        chatter_cutoff: Some(4.0),
        threads: Some(2),
        kernel: Some("baseline"),
        stop_at: Some("touchdown"),
    }
}

#[test]
fn a_valid_request_keeps_every_option() {
    let (cfg, options) = request().compile().unwrap();
    assert_eq!(cfg.steps, 200);
    assert_eq!((cfg.substeps, cfg.record_every), (3, 10));
    // the seed passes through exactly (2^64 - 1 is not a float)
    assert_eq!((cfg.seed, cfg.first_case), (u64::MAX, 7));
    assert_eq!(cfg.integrator, IntegratorKind::Euler);
    assert_eq!(cfg.settle, Tolerance::Absolute(0.5));
    assert_eq!(cfg.chatter_cutoff, 4.0);
    assert_eq!(options.threads, Some(2));
    assert_eq!(options.level, Some(Level::Baseline));
    assert!(options.cancel.is_none());
    assert_eq!(cfg.stop_at, Some(Event::Touchdown));
}

/// One option set to a bad value.
type Change = fn(&mut RunRequest<'static>);

#[test]
fn each_bad_option_is_named_with_its_rule() {
    let cases: [(Change, &str); 10] = [
        (
            |r| r.integrator = "rk45",
            r#"integrator = "rk45" is not one of ["rk4", "euler"]"#,
        ),
        (|r| r.substeps = 0, "substeps = 0 violates substeps >= 1"),
        (
            |r| r.substeps = 10_001,
            "substeps = 10001 violates substeps <= max_substeps (10000)",
        ),
        (
            |r| r.record_every = -1,
            "record_every = -1 violates record_every >= 0",
        ),
        (|r| r.threads = Some(0), "threads = 0 violates threads >= 1"),
        (
            |r| r.threads = Some(1025),
            "threads = 1025 violates threads <= max_threads (1024)",
        ),
        (|r| r.kernel = Some("sse9"), "kernel: "),
        (
            |r| r.t_final = 2.005,
            "t_final = 2.005 violates t_final an integer multiple of dt",
        ),
        (
            |r| r.chatter_cutoff = Some(50.0),
            "chatter_cutoff = 50 violates 0 < chatter_cutoff",
        ),
        (
            |r| r.stop_at = Some("landing"),
            r#"stop_at = "landing" is not one of ["touchdown"] or None"#,
        ),
    ];
    for (change, message) in cases {
        let mut r = request();
        change(&mut r);
        let e = r.compile().unwrap_err().to_string();
        assert!(
            e.starts_with(message),
            "{e:?} does not start with {message:?}"
        );
    }
    let mut r = request();
    r.settle_tolerance = -1.0;
    let e = r.compile().unwrap_err().to_string();
    assert!(e.starts_with("settle_tolerance = -1 violates"), "{e}");
}
