//! LSPB (section 6.5.1.2): from the cruise velocity and from the blend acceleration.

use crate::trajectory_support::*;
use dhgen::trajectory::{Location, Lspb, Profile, Setpoint, TrajectoryError};
use proptest::prelude::*;

fn start_time() -> impl Strategy<Value = f64> {
    -100.0..100.0f64
}

fn duration() -> impl Strategy<Value = f64> {
    (-3.0..2.0f64).prop_map(|e| 10f64.powf(e))
}

fn position() -> impl Strategy<Value = f64> {
    prop_oneof![4 => -100.0..100.0f64, 1 => -1e-3..1e-3f64]
}

/// The text's LSPB at local time `tau` (third segment as corrected by the errata, factored as
/// `qf - α (T - τ)²/2`).
fn text_lspb(tau: f64, big_t: f64, q0: f64, qf: f64, v: f64, alpha: f64, tb: f64) -> Setpoint {
    if tau <= tb {
        Setpoint::new(q0 + 0.5 * alpha * tau * tau, alpha * tau, alpha)
    } else if tau <= big_t - tb {
        Setpoint::new(0.5 * (q0 + qf - v * big_t) + v * tau, v, 0.0)
    } else {
        let left = big_t - tau;
        Setpoint::new(qf - 0.5 * alpha * left * left, alpha * left, -alpha)
    }
}

/// The expected cruise velocity, blend acceleration (both signed as the move) and blend time.
#[derive(Clone, Copy, Debug)]
struct Blend {
    v: f64,
    alpha: f64,
    tb: f64,
}

/// Everything an LSPB on `[t0, tf]` from `q0` to `qf` must satisfy, given its expected blend.
fn check_lspb(p: &Lspb, (t0, tf): (f64, f64), (q0, qf): (f64, f64), blend: Blend) {
    let Blend { v, alpha, tb } = blend;
    let big_t = tf - t0;
    let scales = Scales {
        q: q0.abs().max(qf.abs()).max(v.abs() * big_t),
        qd: v.abs(),
        qdd: alpha.abs(),
    };
    // Closed forms of the blend.
    assert_close("blend time", p.blend_time(), tb, big_t);
    assert_close("cruise velocity", p.velocity(), v, scales.qd);
    assert_close("blend acceleration", p.acceleration(), alpha, scales.qdd);
    assert!(
        p.blend_time() >= 0.0 && p.blend_time() <= 0.5 * big_t,
        "tb = {} outside [0, T/2]",
        p.blend_time()
    );
    // Boundary conditions: at rest at both ends, accelerating into the move at t0 and out at tf.
    assert_state("t0", p.eval(t0), Setpoint::new(q0, 0.0, alpha), scales);
    assert_state("tf", p.eval(tf), Setpoint::new(qf, 0.0, -alpha), scales);
    assert_held_outside(p, q0, qf);
    // The piecewise formula of the text, and the symmetry it was derived from.
    let bounds = Bounds {
        qd: v.abs(),
        qdd: alpha.abs(),
        jerk: None,
    };
    let time_rounding = |t: f64| 64.0 * f64::EPSILON * t.abs() * v.abs();
    let switches = [t0 + tb, tf - tb];
    for t in interior_times(t0, tf, 10) {
        let got = p.eval(t);
        let want = text_lspb(t - t0, big_t, q0, qf, v, alpha, tb);
        assert_close(&format!("q({t})"), got.q, want.q, scales.q);
        assert_close(&format!("qd({t})"), got.qd, want.qd, scales.qd);
        if switches.iter().all(|s| (t - s).abs() > 1e-9 * big_t) {
            assert_eq!(got.qdd, want.qdd, "qdd({t})");
        }
        let mirror = p.eval(tf - (t - t0));
        let tol = BOUNDARY_TOL * scales.q + time_rounding(t) + time_rounding(tf);
        assert!(
            (got.q + mirror.q - (q0 + qf)).abs() <= tol,
            "q is not point-symmetric about the midpoint at {t}"
        );
        assert_within_limits(p, t, v.abs(), alpha.abs());
    }
    // Position and velocity continuous at the switches; derivatives consistent everywhere.
    let eps = 1e-9 * big_t;
    for s in switches {
        assert_continuous_at(p, s, eps, bounds, scales);
        assert_within_limits(p, s, v.abs(), alpha.abs());
    }
    let h = 1e-4 * big_t;
    for t in interior_times(t0 + h, tf - h, 8) {
        assert_derivatives_at(p, t, h, bounds, scales);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    /// V anywhere in ((qf - q0)/T, 2 (qf - q0)/T], including the bang-bang end; any sign of move.
    #[test]
    fn lspb_from_velocity(t0 in start_time(), big_t in duration(), q0 in position(), qf in position(),
                          fraction in prop_oneof![1 => Just(1.0), 4 => (-6.0..0.0f64).prop_map(|e| 10f64.powf(e))]) {
        let tf = t0 + big_t;
        let big_t = tf - t0;
        let v = (qf - q0) / big_t * (1.0 + fraction);
        let p = Lspb::with_velocity(t0, tf, q0, qf, v).unwrap();
        // The text's closed forms: tb = (q0 - qf + V T)/V, α = V/tb.
        let tb = ((q0 - qf + v * big_t) / v).min(0.5 * big_t);
        prop_assert_eq!(p.velocity(), v);
        check_lspb(&p, (t0, tf), (q0, qf), Blend { v, alpha: v / tb, tb });
        prop_assert_eq!(p.duration(), big_t);
    }

    /// α from the bang-bang minimum 4|Δ|/T² up to a million times that.
    #[test]
    fn lspb_from_acceleration(t0 in start_time(), big_t in duration(), q0 in position(), qf in position(),
                              factor in prop_oneof![1 => Just(1.0), 4 => (0.0..6.0f64).prop_map(|e| 10f64.powf(e))]) {
        let tf = t0 + big_t;
        let big_t = tf - t0;
        let dq = qf - q0;
        let alpha = 4.0 * dq.abs() / (big_t * big_t) * factor;
        let p = Lspb::with_acceleration(t0, tf, q0, qf, alpha).unwrap();
        // The defining equation: the distance covered, α tb (T - tb), is |Δ|.
        let tb = p.blend_time();
        assert_close("α tb (T - tb)", alpha * tb * (big_t - tb), dq.abs(), dq.abs());
        // The text's closed form tb = T/2 - sqrt(α² T² - 4 α |Δ|)/(2α), where it is well
        // conditioned: not near bang-bang (where tb has an infinite derivative in α) and not for
        // blends so short that the subtraction cancels.
        let disc = alpha * alpha * big_t * big_t - 4.0 * alpha * dq.abs();
        let text_tb = 0.5 * big_t - disc.max(0.0).sqrt() / (2.0 * alpha);
        if factor >= 1.01 && text_tb > 1e-3 * big_t {
            assert_close("blend time (closed form)", tb, text_tb, big_t);
        }
        let v = dq.signum() * alpha * tb;
        check_lspb(&p, (t0, tf), (q0, qf), Blend { v, alpha: dq.signum() * alpha, tb });
    }

    /// Negative moves are exact mirror images of positive ones.
    #[test]
    fn lspb_negative_moves_mirror(t0 in start_time(), big_t in duration(), q0 in position(), qf in position(),
                                  fraction in 1e-6..=1.0f64, factor in 1.0..1e6f64) {
        let tf = t0 + big_t;
        let v = (qf - q0) / (tf - t0) * (1.0 + fraction);
        let alpha = 4.0 * (qf - q0).abs() / ((tf - t0) * (tf - t0)) * factor;
        let pairs = [
            (Lspb::with_velocity(t0, tf, q0, qf, v).unwrap(), Lspb::with_velocity(t0, tf, -q0, -qf, -v).unwrap()),
            (Lspb::with_acceleration(t0, tf, q0, qf, alpha).unwrap(), Lspb::with_acceleration(t0, tf, -q0, -qf, alpha).unwrap()),
        ];
        for (p, m) in pairs {
            for t in interior_times(t0 - big_t, tf + big_t, 12) {
                let (a, b) = (p.eval(t), m.eval(t));
                prop_assert_eq!((a.q, a.qd, a.qdd), (-b.q, -b.qd, -b.qdd));
            }
        }
    }
}

/// The erratum's third segment, `qf - α tf²/2 + α tf t - α t²/2`, is what the profile follows.
#[test]
fn third_segment_follows_the_erratum() {
    let (q0, qf, tf, v) = (10.0, 40.0, 2.0, 20.0);
    let p = Lspb::with_velocity(0.0, tf, q0, qf, v).unwrap();
    let tb = (q0 - qf + v * tf) / v; // 0.5
    let alpha = v / tb; // 40
    assert_eq!((p.blend_time(), p.acceleration()), (tb, alpha));
    for t in [1.5, 1.6, 1.75, 1.9, 2.0] {
        let want = qf - alpha * tf * tf / 2.0 + alpha * tf * t - alpha * t * t / 2.0;
        assert!(
            (p.eval(t).q - want).abs() < 1e-12,
            "q({t}) = {} but the erratum gives {want}",
            p.eval(t).q
        );
    }
}

#[test]
fn zero_moves_stand_still() {
    let p = Lspb::with_velocity(1.0, 3.0, 5.0, 5.0, 0.0).unwrap();
    let a = Lspb::with_acceleration(1.0, 3.0, 5.0, 5.0, 2.0).unwrap();
    for t in [0.0, 1.0, 1.5, 2.0, 3.0, 4.0] {
        assert_eq!(p.eval(t), Setpoint::rest(5.0));
        assert_eq!(a.eval(t), Setpoint::rest(5.0));
    }
}

#[test]
fn velocity_outside_the_interval_is_rejected() {
    // Positive move of 1 in 1 s: V must lie in (1, 2].
    for v in [0.5, 1.0, 2.0 + 1e-12, 3.0, -1.5] {
        let e = Lspb::with_velocity(0.0, 1.0, 0.0, 1.0, v).unwrap_err();
        assert_eq!(
            e,
            TrajectoryError::LspbVelocityOutOfRange {
                v,
                exclusive_bound: 1.0,
                inclusive_bound: 2.0,
                at: Location::NONE
            }
        );
        assert_eq!(
            e.to_string(),
            format!(
                "LSPB cruise velocity V = {v} is outside the allowed interval (1, 2] = ((qf - q0)/T, 2(qf - q0)/T]"
            )
        );
    }
    assert!(
        Lspb::with_velocity(0.0, 1.0, 0.0, 1.0, 2.0).is_ok(),
        "2 (qf - q0)/T is allowed (bang-bang)"
    );
    // Negative move of -2 in 2 s: V must lie in [-2, -1).
    for v in [-1.0, -0.5, -2.5, 1.5] {
        let e = Lspb::with_velocity(0.0, 2.0, 1.0, -1.0, v).unwrap_err();
        assert!(
            matches!(e, TrajectoryError::LspbVelocityOutOfRange { exclusive_bound, inclusive_bound, .. }
                if exclusive_bound == -1.0 && inclusive_bound == -2.0),
            "{e:?}"
        );
        assert!(
            e.to_string()
                .contains("[-2, -1) = [2(qf - q0)/T, (qf - q0)/T) of this negative move"),
            "{e}"
        );
    }
    assert!(Lspb::with_velocity(0.0, 2.0, 1.0, -1.0, -2.0).is_ok());
    assert!(Lspb::with_velocity(0.0, 2.0, 1.0, -1.0, -1.5).is_ok());
    // Zero move: only V = 0.
    let e = Lspb::with_velocity(0.0, 1.0, 3.0, 3.0, 0.1).unwrap_err();
    assert_eq!(
        e.to_string(),
        "LSPB cruise velocity V = 0.1 must be 0 for a zero move (qf = q0)"
    );
}

#[test]
fn acceleration_too_small_is_rejected() {
    // 4 |Δ| / T² = 4 * 2 / 4 = 2.
    let e = Lspb::with_acceleration(0.0, 2.0, 1.0, -1.0, 1.5).unwrap_err();
    assert_eq!(
        e,
        TrajectoryError::LspbAccelerationTooSmall {
            alpha: 1.5,
            min: 2.0,
            at: Location::NONE
        }
    );
    assert_eq!(
        e.to_string(),
        "LSPB blend acceleration 1.5 is too small to finish the move in time: it must be at least 4|qf - q0|/T^2 = 2"
    );
    let p = Lspb::with_acceleration(0.0, 2.0, 1.0, -1.0, 2.0).unwrap();
    assert_eq!(
        (p.blend_time(), p.velocity()),
        (1.0, -2.0),
        "the minimum is bang-bang"
    );
}

#[test]
fn non_positive_acceleration_is_rejected() {
    for alpha in [0.0, -1.0] {
        let e = Lspb::with_acceleration(0.0, 1.0, 0.0, 1.0, alpha).unwrap_err();
        assert_eq!(
            e,
            TrajectoryError::NonPositiveLimit {
                name: "alpha",
                value: alpha,
                at: Location::NONE
            }
        );
        assert_eq!(e.to_string(), format!("alpha = {alpha} must be positive"));
    }
}

#[test]
fn tf_not_after_t0_is_rejected() {
    assert_eq!(
        Lspb::with_velocity(2.0, 2.0, 0.0, 1.0, 1.0).unwrap_err(),
        TrajectoryError::EmptyTimeInterval { t0: 2.0, tf: 2.0 }
    );
    assert_eq!(
        Lspb::with_acceleration(2.0, 1.0, 0.0, 1.0, 10.0).unwrap_err(),
        TrajectoryError::EmptyTimeInterval { t0: 2.0, tf: 1.0 }
    );
}

#[test]
fn non_finite_inputs_are_named() {
    let nan = f64::NAN;
    let cases = [
        ("t0", Lspb::with_velocity(nan, 1.0, 0.0, 1.0, 1.5)),
        ("tf", Lspb::with_velocity(0.0, nan, 0.0, 1.0, 1.5)),
        ("q0", Lspb::with_velocity(0.0, 1.0, nan, 1.0, 1.5)),
        ("qf", Lspb::with_velocity(0.0, 1.0, 0.0, f64::INFINITY, 1.5)),
        ("V", Lspb::with_velocity(0.0, 1.0, 0.0, 1.0, nan)),
        (
            "alpha",
            Lspb::with_acceleration(0.0, 1.0, 0.0, 1.0, f64::INFINITY),
        ),
        (
            "q0",
            Lspb::with_acceleration(0.0, 1.0, f64::NEG_INFINITY, 1.0, 5.0),
        ),
    ];
    for (name, result) in cases {
        let e = result.unwrap_err();
        assert!(
            matches!(e, TrajectoryError::NonFinite { name: got, .. } if got == name),
            "{name}: {e:?}"
        );
        assert!(e.to_string().contains("is not finite"), "{e}");
    }
}

#[test]
fn blends_below_float_resolution_are_rejected() {
    // V one ulp above (qf - q0)/T = 1/3: V T - Δ rounds to 0, so tb would be 0 and α infinite.
    let average = 1.0f64 / 3.0;
    let v = f64::from_bits(average.to_bits() + 1);
    assert!(
        v > average && v * 3.0 - 1.0 <= 0.0,
        "the case must round tb to zero"
    );
    let e = Lspb::with_velocity(0.0, 3.0, 0.0, 1.0, v).unwrap_err();
    assert!(
        matches!(
            e,
            TrajectoryError::OutOfFloatRange {
                name: "LSPB blend time tb",
                ..
            }
        ),
        "{e:?}"
    );
    assert!(
        e.to_string().contains("cannot be represented in f64"),
        "{e}"
    );
    // α so large that α T² overflows: the blends would be shorter than f64 resolves.
    let e = Lspb::with_acceleration(0.0, 2.0, 0.0, 1e-300, 1e308).unwrap_err();
    assert!(
        matches!(e, TrajectoryError::OutOfFloatRange { .. }),
        "{e:?}"
    );
    // Large but representable: still a valid profile that ends at rest at qf.
    let p = Lspb::with_acceleration(0.0, 2.0, 0.0, 1.0, 1e300).unwrap();
    assert!(p.blend_time() > 0.0 && p.acceleration().is_finite());
    assert_eq!(p.eval(2.0), Setpoint::new(1.0, 0.0, -1e300));
}

/// The bang-bang ends, V = 2Δ/T and α = 4|Δ|/T², computed by the caller from its own duration
/// T, are accepted at any start time, and give a valid LSPB between the same points. With `tf = t0 + T` the
/// duration here, `tf − t0`, differs from T by the rounding of `tf` (4e-12 of T for
/// `t0 = 1e4` s, `T = 0.5` s): α had been refused as too small for 16 % of such calls.
#[test]
fn bang_bang_ends_computed_by_the_caller_are_accepted_at_any_start() {
    let mut refused_before = 0;
    for t0 in [
        0.0,
        -3.7,
        1e3,
        12_345.678,
        19_216.294_467_242_7,
        82_597.583_854_816_72,
        1e6,
    ] {
        for big_t in [1e-3, 0.562_533_940_163_127_9, 20.513_546_583_031_03, 39.4] {
            for (q0, qf) in [
                (-1_574.039_643_061_203_8, -1_921.171_826_866_983),
                (9.284_153_992_952_483e-7, 1.007_399_156_133_687_4e-6),
                (0.0, 1.0),
                (3.294_885_825_966_184_3e-3, 1.991_026_852_178_582e-3),
            ] {
                let tf = t0 + big_t;
                let dq: f64 = qf - q0;
                let alpha = 4.0 * dq.abs() / (big_t * big_t);
                let here = tf - t0;
                if alpha < 4.0 * dq.abs() / (here * here) * (1.0 - 8.0 * f64::EPSILON) {
                    refused_before += 1;
                }
                let from_alpha = Lspb::with_acceleration(t0, tf, q0, qf, alpha)
                    .unwrap_or_else(|e| panic!("t0 {t0}, T {big_t}, {q0} -> {qf}: {e}"));
                let from_v = Lspb::with_velocity(t0, tf, q0, qf, 2.0 * dq / big_t)
                    .unwrap_or_else(|e| panic!("t0 {t0}, T {big_t}, {q0} -> {qf}: {e}"));
                for p in [from_alpha, from_v] {
                    // A valid LSPB: its blends cover the move, from q0 to qf.
                    let tb = p.blend_time();
                    let a = p.acceleration().abs();
                    assert_close("α tb (T - tb)", a * tb * (here - tb), dq.abs(), dq.abs());
                    assert_close("q(tf)", p.eval(tf).q, qf, dq.abs());
                    assert_close("q(t0)", p.eval(t0).q, q0, dq.abs());
                }
            }
        }
    }
    assert!(
        refused_before > 0,
        "the cases include ones the old rule refused"
    );
}
