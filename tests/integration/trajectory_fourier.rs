//! The finite Fourier series (`FourierSeries`): q̇ and q̈ are the derivatives of q, it repeats
//! every period, its bounds hold at every time and are reached, it starts where its formula
//! says and rests there outside its interval, and bad input is refused, naming what and where.

use super::trajectory_support::{Bounds, Scales, assert_derivatives_at, assert_held_outside};
use dhgen::trajectory::{
    FourierSeries, Location, MultiProfile, Profile, Setpoint, Synchronized, TrajectoryError,
};
use proptest::prelude::*;
use std::f64::consts::TAU;

/// Harmonics in the property tests.
const L: usize = 3;

fn series() -> impl Strategy<Value = FourierSeries<L>> {
    (
        -100.0..100.0f64,
        0.05..100.0f64,
        1u32..6,
        -3.0..3.0f64,
        prop::array::uniform3(-2.0..2.0f64),
        prop::array::uniform3(-2.0..2.0f64),
    )
        .prop_map(|(t0, period, cycles, q0, a, b)| {
            FourierSeries::new(t0, period, cycles, q0, a, b).expect("valid input")
        })
}

/// Σ_l (l ω)² |(a_l, b_l)|: a bound on the jerk.
fn jerk_bound<const N: usize>(f: &FourierSeries<N>) -> f64 {
    let (a, b) = f.coefficients();
    let omega = TAU / f.period();
    (0..N)
        .map(|l| ((l + 1) as f64 * omega).powi(2) * a[l].hypot(b[l]))
        .sum()
}

/// The start state by the formula: q0 − Σ b_l / (l ω), Σ a_l, Σ l ω b_l.
fn start_by_formula<const N: usize>(f: &FourierSeries<N>) -> Setpoint {
    let (a, b) = f.coefficients();
    let omega = TAU / f.period();
    let mut s = Setpoint::rest(f.center());
    for l in 0..N {
        let rate = (l + 1) as f64 * omega;
        s.q -= b[l] / rate;
        s.qd += a[l];
        s.qdd += rate * b[l];
    }
    s
}

/// Errors allowed in a state evaluated at time `t`: rounding of the sums, and of `t` itself
/// times the rates.
fn tolerance<const N: usize>(f: &FourierSeries<N>, t: f64) -> Setpoint {
    let bound = f.bounds();
    let time = 4.0 * f64::EPSILON * (t.abs() + f.period());
    Setpoint::new(
        1e-13 * (f.center().abs() + bound.q) + time * bound.qd,
        1e-13 * bound.qd + time * bound.qdd,
        1e-13 * bound.qdd + time * jerk_bound(f),
    )
}

#[track_caller]
fn assert_states_close(what: &str, got: Setpoint, want: Setpoint, tol: Setpoint) {
    assert!(
        (got.q - want.q).abs() <= tol.q
            && (got.qd - want.qd).abs() <= tol.qd
            && (got.qdd - want.qdd).abs() <= tol.qdd,
        "{what}: {got:?} against {want:?} (tolerance {tol:?})"
    );
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2_000))]

    #[test]
    fn fourier_velocity_and_acceleration_are_the_derivatives(f in series(), s in 0.0..1.0f64) {
        let bound = f.bounds();
        let bounds = Bounds { qd: bound.qd, qdd: bound.qdd, jerk: Some(jerk_bound(&f)) };
        let scales = Scales { q: f.center().abs() + bound.q, qd: bound.qd, qdd: bound.qdd };
        let h = 1e-4 * f.period();
        let t = f.start_time() + h + s * (f.duration() - 2.0 * h);
        assert_derivatives_at(&f, t, h, bounds, scales);
    }

    #[test]
    fn fourier_repeats_every_period(f in series(), s in 0.0..1.0f64) {
        prop_assume!(f.duration() > f.period());
        let t = f.start_time() + s * (f.duration() - f.period());
        let (here, later) = (f.eval(t), f.eval(t + f.period()));
        assert_states_close("one period later", later, here, tolerance(&f, t + f.period()));
    }

    #[test]
    fn fourier_stays_within_its_bounds(f in series()) {
        let bound = f.bounds();
        let tol = tolerance(&f, f.end_time());
        for i in 0..=500 {
            let t = f.start_time() + f.duration() * (i as f64 / 500.0);
            let s = f.eval(t);
            prop_assert!((s.q - f.center()).abs() <= bound.q + tol.q, "q({}) = {}", t, s.q);
            prop_assert!(s.qd.abs() <= bound.qd + tol.qd, "q̇({}) = {}", t, s.qd);
            prop_assert!(s.qdd.abs() <= bound.qdd + tol.qdd, "q̈({}) = {}", t, s.qdd);
        }
    }

    #[test]
    fn fourier_starts_and_ends_where_its_formula_says(f in series()) {
        let start = start_by_formula(&f);
        assert_states_close("at t0", f.eval(f.start_time()), start, tolerance(&f, f.start_time()));
        assert_states_close("at tf", f.eval(f.end_time()), start, tolerance(&f, f.end_time()));
        // Outside, at rest at the (common) end position, exactly as evaluated at t0.
        let q = f.eval(f.start_time()).q;
        assert_held_outside(&f, q, q);
    }
}

/// With every `b_l = 0` and `a_l ≥ 0` the harmonics' velocities peak together at `t0`: the
/// bound is reached there; with every `a_l = 0` and `b_l ≥ 0` the accelerations do, and a
/// quarter period later a single harmonic's position does.
#[test]
fn fourier_bounds_are_reached() {
    let f = FourierSeries::new(1.0, 4.0, 2, 0.5, [0.3, 0.2, 0.1], [0.0; 3]).unwrap();
    let (start, bound) = (f.eval(1.0), f.bounds());
    assert!((start.qd - bound.qd).abs() <= 1e-15, "{start:?} {bound:?}");
    let f = FourierSeries::new(1.0, 4.0, 2, 0.5, [0.0; 3], [0.3, 0.2, 0.1]).unwrap();
    let (start, bound) = (f.eval(1.0), f.bounds());
    assert!(
        (start.qdd - bound.qdd).abs() <= 1e-14,
        "{start:?} {bound:?}"
    );
    let f = FourierSeries::new(0.0, 4.0, 1, 0.5, [0.3], [0.0]).unwrap();
    let peak = f.eval(1.0);
    assert!((peak.q - 0.5 - f.bounds().q).abs() <= 1e-15, "{peak:?}");
    // The amplitudes: 0.3 / (2π/4) in position, 0.3 · 2π/4 in acceleration.
    assert!((f.bounds().q - 0.3 * 4.0 / TAU).abs() <= 1e-16);
    assert!((f.bounds().qdd - 0.3 * TAU / 4.0).abs() <= 1e-15);
}

/// Coefficients with Σ a_l = 0 and Σ l b_l = 0 start (and end) at rest, so the recording can
/// begin from a robot standing still.
#[test]
fn fourier_with_balanced_coefficients_starts_at_rest() {
    let f = FourierSeries::new(0.0, 10.0, 3, -0.4, [0.3, -0.1, -0.2], [0.2, 0.2, -0.2]).unwrap();
    for t in [0.0, 10.0, 30.0] {
        let s = f.eval(t);
        assert!(s.qd.abs() < 1e-15 && s.qdd.abs() < 1e-15, "at {t}: {s:?}");
    }
}

/// Many periods: evaluated within one period, the phase loses no accuracy (against the same
/// time one period in, to rounding of the time itself).
#[test]
fn fourier_keeps_its_accuracy_over_many_cycles() {
    let f = FourierSeries::new(0.0, 0.1, 1_000_000, 0.0, [1.0, 0.5], [0.25, -0.5]).unwrap();
    let (early, late) = (f.eval(0.0123), f.eval(99_999.012_3));
    let time = 2.0 * f64::EPSILON * 99_999.012_3;
    assert!((early.q - late.q).abs() <= time * f.bounds().qd + 1e-15);
    assert!((early.qd - late.qd).abs() <= time * f.bounds().qdd + 1e-14);
}

#[test]
fn fourier_refuses_bad_input_naming_it() {
    let nan = f64::NAN;
    assert!(matches!(
        FourierSeries::new(0.0, 1.0, 1, 0.0, [1.0, 2.0], [0.0, nan]).unwrap_err(),
        TrajectoryError::NonFiniteCoefficient {
            coefficient: "b",
            harmonic: 2,
            value,
            at: Location::NONE
        } if value.is_nan()
    ));
    let refused = |period: f64, cycles: u32| {
        FourierSeries::new(0.0, period, cycles, 0.0, [1.0], [0.0]).unwrap_err()
    };
    assert!(matches!(
        refused(0.0, 1),
        TrajectoryError::NonPositiveLimit { name: "period", .. }
    ));
    assert!(matches!(
        refused(-1.0, 1),
        TrajectoryError::NonPositiveLimit { name: "period", .. }
    ));
    assert!(matches!(
        refused(1.0, 0),
        TrajectoryError::NonPositiveLimit { name: "cycles", .. }
    ));
    assert!(matches!(
        refused(f64::INFINITY, 1),
        TrajectoryError::NonFinite { name: "period", .. }
    ));
    assert!(matches!(
        refused(1e308, 10),
        TrajectoryError::NonFinite {
            name: "cycles · period",
            ..
        }
    ));
    assert!(matches!(
        FourierSeries::new(1e308, 1e308, 1, 0.0, [1.0], [0.0]).unwrap_err(),
        TrajectoryError::NonFinite {
            name: "tf = t0 + cycles · period",
            ..
        }
    ));
    // Finite coefficients whose acceleration bound is beyond f64.
    assert!(matches!(
        FourierSeries::new(0.0, 1e-10, 1, 0.0, [1e300], [0.0]).unwrap_err(),
        TrajectoryError::OutOfFloatRange { .. }
    ));
    // A NaN time is NaN; what was accepted is finite everywhere.
    let f = FourierSeries::new(0.0, 1.0, 2, 0.0, [1.0], [1.0]).unwrap();
    assert!(f.eval(f64::NAN).q.is_nan());
    // Synchronized joints: the error names the joint.
    let error = Synchronized::<FourierSeries<1>, 2>::fourier(
        0.0,
        1.0,
        1,
        &[0.0, 0.0],
        &[[1.0], [f64::INFINITY]],
        &[[0.0], [0.0]],
    )
    .unwrap_err();
    assert_eq!(
        error,
        TrajectoryError::NonFiniteCoefficient {
            coefficient: "a",
            harmonic: 1,
            value: f64::INFINITY,
            at: Location::joint(1)
        }
    );
    assert_eq!(
        error.to_string(),
        "Fourier coefficient a_1 = inf is not finite (joint 1)"
    );
}

/// Several joints share one interval and evaluate as each joint's own series.
#[test]
fn fourier_synchronized_joints_are_their_series() {
    let (q0, a, b) = (
        [0.1, -0.2],
        [[0.3, -0.3], [0.5, 0.1]],
        [[0.0, 0.2], [-0.1, 0.4]],
    );
    let joints = Synchronized::<FourierSeries<2>, 2>::fourier(2.0, 8.0, 2, &q0, &a, &b).unwrap();
    assert_eq!((joints.start_time(), joints.end_time()), (2.0, 18.0));
    let mut out = [Setpoint::default(); 2];
    joints.eval_into(7.5, &mut out).unwrap();
    for j in 0..2 {
        let alone = FourierSeries::new(2.0, 8.0, 2, q0[j], a[j], b[j]).unwrap();
        assert_eq!(out[j], alone.eval(7.5));
    }
}
