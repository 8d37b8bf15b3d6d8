//! `dhgen::simulate`: the Runge–Kutta step is of fourth order (halving the step divides the
//! error after a fixed time by about 16), conserves the energy of a frictionless arm moving
//! freely, agrees between generated and runtime arms, and reports a singular `D(q)` and a
//! state that is not finite.

use crate::catalogue::{panda, weightless_wrist};
use crate::support::runtime;
use dhgen::ArmDynamics;
use dhgen::nalgebra::{DVector, SVector};
use dhgen::simulate::{rk4_step, rk4_step_with};

type V7 = SVector<f64, 7>;

/// The Panda's state after `time` seconds of free motion (τ = 0) from `(q0, q̇0)` in steps of
/// `dt`.
fn free_motion(dt: f64, time: f64) -> (V7, V7) {
    let mut q = V7::from([0.1, -0.5, 0.3, -2.0, 0.2, 1.4, 0.6]);
    let mut qd = V7::from([0.5, -0.4, 0.8, 0.3, -0.6, 0.9, -1.0]);
    for _ in 0..(time / dt).round() as usize {
        (q, qd) = rk4_step(&panda::Robot, &q, &qd, &V7::zeros(), dt).unwrap();
    }
    (q, qd)
}

#[test]
fn halving_the_step_divides_the_error_by_sixteen() {
    let (q_ref, qd_ref) = free_motion(0.02 / 64.0, 0.4);
    let error = |dt| {
        let (q, qd) = free_motion(dt, 0.4);
        (q - q_ref).norm() + (qd - qd_ref).norm()
    };
    let (coarse, fine) = (error(0.02), error(0.01));
    let ratio = coarse / fine;
    eprintln!("error at dt = 20 ms {coarse:.2e}, 10 ms {fine:.2e}: ratio {ratio:.1}");
    assert!(
        fine < 1e-3 && (12.0..20.0).contains(&ratio),
        "{coarse:e} {fine:e}"
    );
}

#[test]
fn a_frictionless_arm_moving_freely_keeps_its_energy() {
    for name in ["puma560", "stanford", "panda"] {
        let robot = runtime(name);
        let n = robot.dof();
        let mut q = DVector::from_fn(n, |i, _| 0.3 * (i as f64 + 1.0).sin());
        let mut qd = DVector::from_fn(n, |i, _| (i as f64 * 1.7).cos());
        let energy = |q: &DVector<f64>, qd: &DVector<f64>| {
            ArmDynamics::kinetic_energy(&robot, q, qd) + ArmDynamics::potential_energy(&robot, q)
        };
        let e0 = energy(&q, &qd);
        let mut drift = 0.0f64;
        for _ in 0..500 {
            (q, qd) = rk4_step(&robot, &q, &qd, &DVector::zeros(n), 1e-3).unwrap();
            drift = drift.max((energy(&q, &qd) - e0).abs());
        }
        let scale = e0.abs().max(ArmDynamics::kinetic_energy(&robot, &q, &qd));
        eprintln!("{name}: energy {e0:.3} J, drift over 0.5 s {drift:.1e} J");
        assert!(
            qd.norm() > 0.1 && drift < 1e-8 * scale,
            "{name}: {drift:e} of {scale}"
        );
    }
}

#[test]
fn generated_and_runtime_arms_step_alike() {
    let robot = runtime("panda");
    let (q, qd) = (
        V7::from([0.1, -0.5, 0.3, -2.0, 0.2, 1.4, 0.6]),
        V7::from([0.5, -0.4, 0.8, 0.3, -0.6, 0.9, -1.0]),
    );
    let tau = V7::from([3.0, -20.0, 1.0, 10.0, -0.5, 0.7, 0.1]);
    let (qg, qdg) = rk4_step(&panda::Robot, &q, &qd, &tau, 1e-3).unwrap();
    let dynamic = |v: &V7| DVector::from_column_slice(v.as_slice());
    let (qr, qdr) = rk4_step(&robot, &dynamic(&q), &dynamic(&qd), &dynamic(&tau), 1e-3).unwrap();
    assert!((dynamic(&qg) - qr).amax() < 1e-14 && (dynamic(&qdg) - qdr).amax() < 1e-11);
}

#[test]
fn a_singular_inertia_matrix_or_an_overflow_stops_the_step() {
    // The weightless wrist's D(q) is singular everywhere.
    let (q, qd) = (SVector::from([0.3, 0.2]), SVector::<f64, 2>::zeros());
    assert_eq!(
        rk4_step(&weightless_wrist::Robot, &q, &qd, &SVector::zeros(), 1e-3),
        None
    );
    // A plant whose acceleration fails at the third stage.
    let mut calls = 0;
    let failing = |_: &SVector<f64, 2>, qd: &SVector<f64, 2>| {
        calls += 1;
        (calls < 3).then_some(*qd)
    };
    assert_eq!(rk4_step_with(failing, &q, &qd, 1e-3), None);
    assert_eq!(calls, 3);
    // A step too long for f64, and a step of NaN seconds: no state rather than a non-finite one.
    let (q, qd) = (
        V7::from([0.1, -0.5, 0.3, -2.0, 0.2, 1.4, 0.6]),
        V7::repeat(1.0),
    );
    for dt in [1e300, f64::NAN] {
        assert_eq!(
            rk4_step(&panda::Robot, &q, &qd, &V7::zeros(), dt),
            None,
            "dt = {dt}"
        );
    }
    // Finite accelerations at every stage whose sum overflows.
    let huge = |_: &V7, _: &V7| Some(V7::repeat(1e308));
    assert_eq!(rk4_step_with(huge, &q, &qd, 10.0), None);
}
