//! Cubic and quintic point-to-point profiles (section 6.5.1.1), checked against an independent
//! solve of the boundary-condition systems (equation 15 and its quintic analogue).

use crate::trajectory_support::*;
use dhgen::nalgebra::{SMatrix, SVector};
use dhgen::trajectory::{
    Cubic, FourierSeries, Interval, Lspb, MultiProfile, Profile, Quintic, Setpoint, Synchronized,
    TrajectoryError,
};
use proptest::prelude::*;

/// Coefficients `c` of `q = Σ c_k s^k` in the normalized time `s = (t - t0)/T`, solved by LU from
/// the boundary conditions: `q(0) = q0, q'(0) = v0 T, q(1) = qf, q'(1) = vf T` (equation 15 with
/// `t0 = 0, tf = 1` after scaling time).
fn cubic_by_lu(big_t: f64, q0: f64, v0: f64, qf: f64, vf: f64) -> [f64; 4] {
    #[rustfmt::skip]
    let a = SMatrix::<f64, 4, 4>::new(
        1.0, 0.0, 0.0, 0.0,
        0.0, 1.0, 0.0, 0.0,
        1.0, 1.0, 1.0, 1.0,
        0.0, 1.0, 2.0, 3.0,
    );
    let b = SVector::<f64, 4>::new(q0, v0 * big_t, qf, vf * big_t);
    let c = a
        .lu()
        .solve(&b)
        .expect("the matrix of equation 15 is invertible");
    [c[0], c[1], c[2], c[3]]
}

/// As [`cubic_by_lu`] for the quintic: rows are q, q', q'' at s = 0 and at s = 1.
fn quintic_by_lu(big_t: f64, start: Setpoint, end: Setpoint) -> [f64; 6] {
    #[rustfmt::skip]
    let a = SMatrix::<f64, 6, 6>::from_row_slice(&[
        1.0, 0.0, 0.0, 0.0, 0.0, 0.0,
        0.0, 1.0, 0.0, 0.0, 0.0, 0.0,
        0.0, 0.0, 2.0, 0.0, 0.0, 0.0,
        1.0, 1.0, 1.0, 1.0, 1.0, 1.0,
        0.0, 1.0, 2.0, 3.0, 4.0, 5.0,
        0.0, 0.0, 2.0, 6.0, 12.0, 20.0,
    ]);
    let t2 = big_t * big_t;
    let b = SVector::<f64, 6>::from_row_slice(&[
        start.q,
        start.qd * big_t,
        start.qdd * t2,
        end.q,
        end.qd * big_t,
        end.qdd * t2,
    ]);
    let c = a
        .lu()
        .solve(&b)
        .expect("the quintic boundary matrix is invertible");
    core::array::from_fn(|k| c[k])
}

/// The polynomial `Σ c_k s^k` with `s = (t - t0)/T`, and its first three time derivatives.
fn poly_eval(c: &[f64], big_t: f64, s: f64) -> [f64; 4] {
    let mut out = [0.0; 4];
    for (d, slot) in out.iter_mut().enumerate() {
        let mut sum = 0.0;
        for (k, &ck) in c.iter().enumerate().skip(d) {
            let falling: f64 = (k - d + 1..=k).map(|x| x as f64).product();
            sum += ck * falling * s.powi((k - d) as i32);
        }
        *slot = sum / big_t.powi(d as i32);
    }
    out
}

/// Bounds of |q|, |q̇|, |q̈|, |q⃛| on s in [0, 1]: sums of the absolute coefficients.
fn poly_bounds(c: &[f64], big_t: f64) -> [f64; 4] {
    core::array::from_fn(|d| {
        let sum: f64 = c
            .iter()
            .enumerate()
            .skip(d)
            .map(|(k, ck)| ck.abs() * (k - d + 1..=k).map(|x| x as f64).product::<f64>())
            .sum();
        sum / big_t.powi(d as i32)
    })
}

fn start_time() -> impl Strategy<Value = f64> {
    -100.0..100.0f64
}

/// Durations from 1 ms to 100 s, log-uniform.
fn duration() -> impl Strategy<Value = f64> {
    (-3.0..2.0f64).prop_map(|e| 10f64.powf(e))
}

fn position() -> impl Strategy<Value = f64> {
    prop_oneof![4 => -100.0..100.0f64, 1 => Just(0.0), 1 => -1e-3..1e-3f64]
}

/// A velocity or acceleration as a multiple of (100 / T^order).
fn rate() -> impl Strategy<Value = f64> {
    prop_oneof![3 => -2.0..2.0f64, 1 => Just(0.0)]
}

/// Checks a polynomial profile against its LU coefficients: boundary values, interior values,
/// derivative consistency, holding outside.
fn check_polynomial<P: Profile>(
    p: &P,
    c: &[f64],
    t0: f64,
    big_t: f64,
    start: Setpoint,
    end: Setpoint,
) {
    let bounds = poly_bounds(c, big_t);
    let scales = Scales {
        q: bounds[0],
        qd: bounds[1],
        qdd: bounds[2],
    };
    let at_end = poly_eval(c, big_t, 1.0);
    let at_start = poly_eval(c, big_t, 0.0);
    // Boundary conditions: the prescribed ones, and the unprescribed accelerations of the cubic
    // as the independent solve gives them.
    assert_state(
        "state at t0",
        p.eval(t0),
        Setpoint::new(start.q, start.qd, at_start[2]),
        scales,
    );
    assert_state(
        "state at tf",
        p.eval(p.end_time()),
        Setpoint::new(end.q, end.qd, at_end[2]),
        scales,
    );
    assert_close("prescribed qdd at t0", at_start[2], start.qdd, scales.qdd);
    assert_close("prescribed qdd at tf", at_end[2], end.qdd, scales.qdd);
    for t in interior_times(t0, p.end_time(), 9) {
        let s = (t - t0) / big_t;
        let want = poly_eval(c, big_t, s);
        let got = p.eval(t);
        assert_state(
            &format!("interior t = {t}"),
            got,
            Setpoint::new(want[0], want[1], want[2]),
            scales,
        );
    }
    let derivative_bounds = Bounds {
        qd: bounds[1],
        qdd: bounds[2],
        jerk: Some(bounds[3]),
    };
    let h = 1e-4 * big_t;
    for t in interior_times(t0 + h, p.end_time() - h, 7) {
        assert_derivatives_at(p, t, h, derivative_bounds, scales);
    }
    assert_held_outside(p, start.q, end.q);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    #[test]
    fn cubic_matches_equation_15(t0 in start_time(), big_t in duration(), q0 in position(), qf in position(),
                                 v0 in rate(), vf in rate()) {
        let (v0, vf) = (v0 * 100.0 / big_t, vf * 100.0 / big_t);
        let tf = t0 + big_t;
        let big_t = tf - t0;
        let p = Cubic::new(t0, tf, q0, v0, qf, vf).unwrap();
        prop_assert_eq!(p.duration(), big_t);
        let c = cubic_by_lu(big_t, q0, v0, qf, vf);
        // The cubic cannot prescribe accelerations: pass the solved ones through.
        let [_, _, a0, _] = poly_eval(&c, big_t, 0.0);
        let [_, _, af, _] = poly_eval(&c, big_t, 1.0);
        check_polynomial(&p, &c, t0, big_t, Setpoint::new(q0, v0, a0), Setpoint::new(qf, vf, af));
        // The monomial coefficients in τ = t - t0 are c_k / T^k.
        let scale = poly_bounds(&c, big_t)[0];
        for (k, (&a, &ck)) in p.coefficients().iter().zip(&c).enumerate() {
            assert_close(&format!("a{k} T^{k}"), a * big_t.powi(k as i32), ck, scale);
        }
    }

    #[test]
    fn quintic_matches_its_boundary_system(t0 in start_time(), big_t in duration(), q0 in position(), qf in position(),
                                           v0 in rate(), vf in rate(), a0 in rate(), af in rate()) {
        let (v0, vf) = (v0 * 100.0 / big_t, vf * 100.0 / big_t);
        let (a0, af) = (a0 * 100.0 / (big_t * big_t), af * 100.0 / (big_t * big_t));
        let tf = t0 + big_t;
        let big_t = tf - t0;
        let (start, end) = (Setpoint::new(q0, v0, a0), Setpoint::new(qf, vf, af));
        let p = Quintic::new(t0, tf, start, end).unwrap();
        let c = quintic_by_lu(big_t, start, end);
        check_polynomial(&p, &c, t0, big_t, start, end);
        let scale = poly_bounds(&c, big_t)[0];
        for (k, (&a, &ck)) in p.coefficients().iter().zip(&c).enumerate() {
            assert_close(&format!("a{k} T^{k}"), a * big_t.powi(k as i32), ck, scale);
        }
    }

    /// Rest to rest, both profiles are continuous in position and velocity across t0 and tf
    /// (holding outside), the quintic in acceleration too; peak values match the closed forms.
    #[test]
    fn rest_to_rest_is_continuous_across_the_ends(t0 in start_time(), big_t in duration(), q0 in position(), qf in position()) {
        let tf = t0 + big_t;
        let big_t = tf - t0;
        let dq = qf - q0;
        let scale_q = q0.abs().max(qf.abs());
        let eps = 1e-9 * big_t;

        let cubic = Cubic::rest_to_rest(t0, tf, q0, qf).unwrap();
        let scales = Scales { q: scale_q, qd: 1.5 * dq.abs() / big_t, qdd: 6.0 * dq.abs() / (big_t * big_t) };
        let bounds = Bounds { qd: scales.qd, qdd: scales.qdd, jerk: None };
        for t in [t0, tf] {
            assert_continuous_at(&cubic, t, eps, bounds, scales);
        }
        // Peak velocity 1.5 Δ/T at the midpoint; acceleration ±6 Δ/T² at the ends.
        let t_mid = t0 + 0.5 * big_t;
        let mid = cubic.eval(t_mid);
        assert_close("cubic peak velocity", mid.qd, 1.5 * dq / big_t, scales.qd);
        // t_mid is only the midpoint up to the rounding of t0 + T/2: use its actual s.
        let s = (t_mid - t0) / big_t;
        assert_close("cubic midpoint", mid.q, q0 + dq * s * s * (3.0 - 2.0 * s), scale_q);
        assert_close("cubic qdd(t0)", cubic.eval(t0).qdd, 6.0 * dq / (big_t * big_t), scales.qdd);
        assert_close("cubic qdd(tf)", cubic.eval(tf).qdd, -6.0 * dq / (big_t * big_t), scales.qdd);

        let quintic = Quintic::rest_to_rest(t0, tf, q0, qf).unwrap();
        let peak_a = 10.0 / 3f64.sqrt() * dq.abs() / (big_t * big_t);
        let scales = Scales { q: scale_q, qd: 1.875 * dq.abs() / big_t, qdd: peak_a };
        let bounds = Bounds { qd: scales.qd, qdd: peak_a, jerk: Some(60.0 * dq.abs() / big_t.powi(3)) };
        for t in [t0, tf] {
            assert_continuous_at(&quintic, t, eps, bounds, scales);
        }
        let mid = quintic.eval(t0 + 0.5 * big_t);
        assert_close("quintic peak velocity", mid.qd, 1.875 * dq / big_t, scales.qd);
        // Peak acceleration 10/√3 Δ/T² at s = 1/2 - √3/6.
        let s_peak = 0.5 - 3f64.sqrt() / 6.0;
        assert_close("quintic peak acceleration", quintic.eval(t0 + s_peak * big_t).qdd, peak_a * dq.signum(), scales.qdd);
    }

    /// A negative move is the mirror image of the positive one.
    #[test]
    fn negative_moves_mirror_positive_ones(t0 in start_time(), big_t in duration(), q0 in position(), qf in position(),
                                           v0 in rate(), vf in rate()) {
        let (v0, vf) = (v0 * 100.0 / big_t, vf * 100.0 / big_t);
        let tf = t0 + big_t;
        let p = Cubic::new(t0, tf, q0, v0, qf, vf).unwrap();
        let m = Cubic::new(t0, tf, -q0, -v0, -qf, -vf).unwrap();
        let pq = Quintic::rest_to_rest(t0, tf, q0, qf).unwrap();
        let mq = Quintic::rest_to_rest(t0, tf, -q0, -qf).unwrap();
        for t in interior_times(t0 - big_t, tf + big_t, 11) {
            let (a, b) = (p.eval(t), m.eval(t));
            prop_assert_eq!((a.q, a.qd, a.qdd), (-b.q, -b.qd, -b.qdd));
            let (a, b) = (pq.eval(t), mq.eval(t));
            prop_assert_eq!((a.q, a.qd, a.qdd), (-b.q, -b.qd, -b.qdd));
        }
    }
}

/// Figure 4 of the text: q0 = 10°, qf = -20° on [0, 1] gives q = 10 - 90 t² + 60 t³.
#[test]
fn figure_4_cubic() {
    let p = Cubic::rest_to_rest(0.0, 1.0, 10.0, -20.0).unwrap();
    for i in 0..=20 {
        let t = i as f64 / 20.0;
        let want = Setpoint::new(
            10.0 - 90.0 * t * t + 60.0 * t * t * t,
            -180.0 * t + 180.0 * t * t,
            -180.0 + 360.0 * t,
        );
        assert_state(
            &format!("t = {t}"),
            p.eval(t),
            want,
            Scales {
                q: 20.0,
                qd: 45.0,
                qdd: 180.0,
            },
        );
    }
    assert_eq!(p.coefficients(), [10.0, 0.0, -90.0, 60.0]);
}

#[test]
fn tf_not_after_t0_is_rejected() {
    for (t0, tf) in [(1.0, 1.0), (2.0, 1.0)] {
        let e = Cubic::rest_to_rest(t0, tf, 0.0, 1.0).unwrap_err();
        assert_eq!(e, TrajectoryError::EmptyTimeInterval { t0, tf });
        assert_eq!(
            e.to_string(),
            format!("final time tf = {tf} must be greater than start time t0 = {t0}")
        );
        assert_eq!(Quintic::rest_to_rest(t0, tf, 0.0, 1.0).unwrap_err(), e);
    }
}

/// `Interval::new` refuses what every timed profile refuses, naming the same thing, and every
/// profile reports the interval it was built on: `[t0, tf]` with `tf − t0`, or, timed by its
/// duration, that duration with the end `t0 + duration` rounded.
#[test]
fn intervals_are_checked_and_reported() {
    for (t0, tf) in [(1.0, 1.0), (2.0, 1.0)] {
        let e = Interval::new(t0, tf).unwrap_err();
        assert_eq!(e, TrajectoryError::EmptyTimeInterval { t0, tf });
        assert_eq!(Cubic::rest_to_rest(t0, tf, 0.0, 1.0).unwrap_err(), e);
    }
    for (name, t0, tf) in [
        ("t0", f64::NAN, 1.0),
        ("tf", 0.0, f64::INFINITY),
        ("tf - t0", -1e308, 1e308),
    ] {
        let e = Interval::new(t0, tf).unwrap_err();
        assert!(
            matches!(e, TrajectoryError::NonFinite { name: n, .. } if n == name),
            "{name}: {e:?}"
        );
        let quintic = Quintic::rest_to_rest(t0, tf, 0.0, 1.0).unwrap_err();
        assert_eq!(quintic.to_string(), e.to_string());
    }

    let (t0, tf) = (0.1, 0.7);
    let span = Interval::new(t0, tf).unwrap();
    assert_eq!(
        (span.start(), span.end(), span.duration()),
        (t0, tf, tf - t0)
    );
    let check = |what: &str, p: &dyn Profile, expected: Interval| {
        assert_eq!(p.interval(), expected, "{what}");
        let times = (p.start_time(), p.duration(), p.end_time());
        assert_eq!(
            times,
            (expected.start(), expected.duration(), expected.end()),
            "{what}"
        );
    };
    check(
        "cubic",
        &Cubic::rest_to_rest(t0, tf, 0.0, 1.0).unwrap(),
        span,
    );
    check(
        "quintic",
        &Quintic::rest_to_rest(t0, tf, 0.0, 1.0).unwrap(),
        span,
    );
    check(
        "lspb",
        &Lspb::with_velocity(t0, tf, 0.0, 1.0, 2.0).unwrap(),
        span,
    );
    // Timed by their durations: 3 periods of 0.1 s end at 0.1 + 0.30000000000000004, and a
    // bang-bang move of 2 sqrt(1/3) s at 0.1 plus that, each rounded.
    let periods = 3.0 * 0.1;
    let series = FourierSeries::new(t0, 0.1, 3, 0.0, [0.1], [0.0]).unwrap();
    assert_eq!(series.duration(), periods);
    assert_eq!(series.end_time(), t0 + periods);
    let fastest = Lspb::bang_bang(t0, 0.0, 1.0, 3.0).unwrap();
    let bang = 2.0 * (1.0f64 / 3.0).sqrt();
    assert_eq!((fastest.duration(), fastest.end_time()), (bang, t0 + bang));
    let joints = Synchronized::bang_bang(t0, &[0.0, 0.0], &[1.0, 0.5], &[3.0, 3.0]).unwrap();
    assert_eq!(MultiProfile::interval(&joints), fastest.interval());
    for joint in joints.joints() {
        check("synchronized joint", joint, fastest.interval());
    }
}

#[test]
fn non_finite_inputs_are_named() {
    let nan = f64::NAN;
    let cases: [(&str, Result<Cubic, TrajectoryError>); 6] = [
        ("t0", Cubic::new(nan, 1.0, 0.0, 0.0, 1.0, 0.0)),
        ("tf", Cubic::new(0.0, f64::INFINITY, 0.0, 0.0, 1.0, 0.0)),
        ("q0", Cubic::new(0.0, 1.0, nan, 0.0, 1.0, 0.0)),
        ("v0", Cubic::new(0.0, 1.0, 0.0, nan, 1.0, 0.0)),
        ("qf", Cubic::new(0.0, 1.0, 0.0, 0.0, f64::NEG_INFINITY, 0.0)),
        ("vf", Cubic::new(0.0, 1.0, 0.0, 0.0, 1.0, nan)),
    ];
    for (name, result) in cases {
        match result {
            Err(TrajectoryError::NonFinite { name: got, .. }) => assert_eq!(got, name),
            other => panic!("{name}: expected NonFinite, got {other:?}"),
        }
    }
    let ok = Setpoint::rest(0.0);
    let bad = |qd, qdd| Setpoint::new(1.0, qd, qdd);
    for (name, start, end) in [
        ("v0", Setpoint::new(0.0, nan, 0.0), Setpoint::rest(1.0)),
        ("a0", Setpoint::new(0.0, 0.0, nan), Setpoint::rest(1.0)),
        ("vf", ok, bad(nan, 0.0)),
        ("af", ok, bad(0.0, f64::INFINITY)),
    ] {
        let e = Quintic::new(0.0, 1.0, start, end).unwrap_err();
        assert!(
            matches!(e, TrajectoryError::NonFinite { name: got, .. } if got == name),
            "{name}: {e:?}"
        );
        assert!(e.to_string().starts_with(&format!("{name} = ")), "{e}");
    }
    // Finite inputs whose difference overflows.
    let e = Cubic::rest_to_rest(-1e308, 1e308, 0.0, 1.0).unwrap_err();
    assert!(
        matches!(
            e,
            TrajectoryError::NonFinite {
                name: "tf - t0",
                ..
            }
        ),
        "{e:?}"
    );
    let e = Quintic::rest_to_rest(0.0, 1.0, -1e308, 1e308).unwrap_err();
    assert!(
        matches!(
            e,
            TrajectoryError::NonFinite {
                name: "qf - q0",
                ..
            }
        ),
        "{e:?}"
    );
}

/// Every value a profile returns on `[t0, tf]` (and its coefficients) is finite.
fn assert_finite_everywhere<P: Profile>(what: &str, p: &P, coefficients: &[f64]) {
    assert!(
        coefficients.iter().all(|c| c.is_finite()),
        "{what}: coefficients {coefficients:?}"
    );
    let (t0, tf) = (p.start_time(), p.end_time());
    for i in 0..=64 {
        let t = dhgen::trajectory::uniform_time(t0, tf, 65, i);
        let s = p.eval(t);
        assert!(
            s.q.is_finite() && s.qd.is_finite() && s.qdd.is_finite(),
            "{what}: at t = {t:e} (t0 = {t0:e}, tf = {tf:e}) {s:?}"
        );
    }
}

fn out_of_float_range<P: core::fmt::Debug>(
    what: &str,
    r: Result<P, TrajectoryError>,
) -> &'static str {
    match r {
        Err(TrajectoryError::OutOfFloatRange { name, .. }) => name,
        other => panic!("{what}: expected OutOfFloatRange, got {other:?}"),
    }
}

/// Finite input whose profile `f64` cannot hold (derived velocities, accelerations or
/// coefficients beyond it) is `OutOfFloatRange` naming the quantity, never a profile whose
/// samples are NaN or infinite.
#[test]
fn finite_input_beyond_f64_is_out_of_float_range() {
    let cases = [
        // A move of 1e308 in 0.5 s: the average velocity 2e308 overflows.
        (
            "cubic dq 1e308 in 0.5 s",
            Cubic::rest_to_rest(0.0, 0.5, 0.0, 1e308),
            "velocity",
        ),
        // A duration of one subnormal.
        (
            "cubic T = 5e-324",
            Cubic::rest_to_rest(0.0, 5e-324, 0.0, 1.0),
            "velocity",
        ),
        (
            "cubic dq 1e10 in 1e-300 s",
            Cubic::rest_to_rest(0.0, 1e-300, 0.0, 1e10),
            "velocity",
        ),
        // v0 = 1e300 for 1e10 s: q reaches infinity at late t.
        (
            "cubic v0 T = 1e310",
            Cubic::new(0.0, 1e10, 0.0, 1e300, 0.0, 0.0),
            "position",
        ),
        (
            "cubic q 1.5e308, v0 1e308",
            Cubic::new(0.0, 1.0, 1.5e308, 1e308, 1.5e308, 0.0),
            "position",
        ),
        // A move of 1e-10 in 1e-160 s: velocity 1e150, acceleration 6e310.
        (
            "cubic dq 1e-10 in 1e-160 s",
            Cubic::rest_to_rest(0.0, 1e-160, 0.0, 1e-10),
            "acceleration",
        ),
        // Finite peak acceleration 6e300, but the jerk -1.2e451 is not.
        (
            "cubic T = 1e-150",
            Cubic::rest_to_rest(0.0, 1e-150, 0.0, 1.0),
            "coefficient a3",
        ),
    ];
    for (what, r, quantity) in cases {
        let name = out_of_float_range(what, r);
        assert!(name.contains(quantity), "{what}: {name}");
    }
    let rest = Setpoint::rest;
    let cases = [
        (
            "quintic dq 1e308 in 0.5 s",
            Quintic::rest_to_rest(0.0, 0.5, 0.0, 1e308),
            "velocity",
        ),
        (
            "quintic dq 1e10 in 1e-300 s",
            Quintic::rest_to_rest(0.0, 1e-300, 0.0, 1e10),
            "velocity",
        ),
        // a0 = 1e300 for 1e200 s.
        (
            "quintic a0 T² = 1e700",
            Quintic::new(0.0, 1e200, Setpoint::new(0.0, 0.0, 1e300), rest(1.0)),
            "position",
        ),
        (
            "quintic a0 1e308",
            Quintic::new(0.0, 1.0, Setpoint::new(0.0, 0.0, 1e308), rest(1.0)),
            "position",
        ),
        (
            "quintic dq 1e-10 in 1e-160 s",
            Quintic::rest_to_rest(0.0, 1e-160, 0.0, 1e-10),
            "acceleration",
        ),
        // Peak acceleration 5.8e200 and a3 = 1e301, but a4 = -1.5e401.
        (
            "quintic T = 1e-100",
            Quintic::rest_to_rest(0.0, 1e-100, 0.0, 1.0),
            "coefficient a4",
        ),
    ];
    for (what, r, quantity) in cases {
        let name = out_of_float_range(what, r);
        assert!(name.contains(quantity), "{what}: {name}");
    }
    let e = Cubic::rest_to_rest(0.0, 0.5, 0.0, 1e308).unwrap_err();
    assert_eq!(
        e.to_string(),
        "cubic velocity scale |qf - q0|/T + |v0| + |vf| = inf cannot be represented in f64: \
         the inputs are too extreme relative to each other"
    );
    // Synchronized profiles name the joint.
    let e = Synchronized::quintic_rest_to_rest(0.0, 0.5, &[0.0, 0.0], &[1.0, 1e308]).unwrap_err();
    assert!(
        matches!(e, TrajectoryError::OutOfFloatRange { at, .. } if at.joint == Some(1)),
        "{e:?}"
    );

    // Extreme but representable profiles are accepted and finite everywhere: a move of 1 rad
    // over 1e200 s (T² overflows, which the quintic's evaluation must not form), a move of
    // 1e290 over 1 ms, a huge start time.
    for (t0, big_t, q0, qf) in [
        (0.0, 1e200, 0.0, 1.0),
        (0.0, 1e300, -1.0, 1.0),
        (0.0, 1e-3, 0.0, 1e290),
        (1e300, 1e290, 1.0, 2.0),
        (0.0, 1e-100, 0.0, 1e-300),
    ] {
        let what = format!("rest to rest over {big_t:e} s from {q0} to {qf}");
        let c = Cubic::rest_to_rest(t0, t0 + big_t, q0, qf).unwrap();
        assert_finite_everywhere(&format!("cubic {what}"), &c, &c.coefficients());
        let p = Quintic::rest_to_rest(t0, t0 + big_t, q0, qf).unwrap();
        assert_finite_everywhere(&format!("quintic {what}"), &p, &p.coefficients());
    }
}

/// Extreme magnitudes: exponents of T, positions, velocities and accelerations anywhere in
/// f64's range.
fn magnitude() -> impl Strategy<Value = f64> {
    (-320.0..308.0f64, any::<bool>()).prop_map(|(e, negative)| {
        let x = 10f64.powf(e);
        if negative { -x } else { x }
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    /// Whatever finite input a constructor accepts evaluates to finite values on [t0, tf],
    /// with finite coefficients; what it refuses is OutOfFloatRange.
    #[test]
    fn accepted_polynomials_are_finite_everywhere(t0 in prop_oneof![Just(0.0), magnitude()],
                                                  big_t in magnitude(), q0 in magnitude(), qf in magnitude(),
                                                  v0 in magnitude(), vf in magnitude(),
                                                  a0 in magnitude(), af in magnitude()) {
        let tf = t0 + big_t.abs();
        if tf.is_finite() && tf > t0 && (qf - q0).is_finite() {
            match Cubic::new(t0, tf, q0, v0, qf, vf) {
                Ok(c) => assert_finite_everywhere("cubic", &c, &c.coefficients()),
                Err(e) => prop_assert!(matches!(e, TrajectoryError::OutOfFloatRange { .. }), "{e:?}"),
            }
            match Quintic::new(t0, tf, Setpoint::new(q0, v0, a0), Setpoint::new(qf, vf, af)) {
                Ok(p) => assert_finite_everywhere("quintic", &p, &p.coefficients()),
                Err(e) => prop_assert!(matches!(e, TrajectoryError::OutOfFloatRange { .. }), "{e:?}"),
            }
            match Quintic::rest_to_rest(t0, tf, q0, qf) {
                Ok(p) => assert_finite_everywhere("quintic rest to rest", &p, &p.coefficients()),
                Err(e) => prop_assert!(matches!(e, TrajectoryError::OutOfFloatRange { .. }), "{e:?}"),
            }
        }
    }
}
