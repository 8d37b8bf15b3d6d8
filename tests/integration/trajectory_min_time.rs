//! Minimum-time profiles (section 6.5.1.3): bang-bang and the velocity-limited trapezoid.

use crate::trajectory_support::*;
use dhgen::trajectory::{
    Location, Lspb, Profile, Setpoint, TrajectoryError, bang_bang_duration,
    velocity_limited_duration,
};
use proptest::prelude::*;

fn start_time() -> impl Strategy<Value = f64> {
    -100.0..100.0f64
}

/// A move of either sign from 1e-3 to 1e3, or none.
fn displacement() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => ((-3.0..3.0f64), any::<bool>()).prop_map(|(e, neg)| if neg { -10f64.powf(e) } else { 10f64.powf(e) }),
        1 => Just(0.0),
    ]
}

/// A limit from 1e-2 to 1e3.
fn limit() -> impl Strategy<Value = f64> {
    (-2.0..3.0f64).prop_map(|e| 10f64.powf(e))
}

/// Checks a rest-to-rest profile that must use exactly the acceleration `amax` in its blends and
/// reach the peak velocity `peak`.
fn check_min_time(p: &Lspb, t0: f64, q0: f64, qf: f64, peak: f64, amax: f64) {
    let dq = qf - q0;
    let (tf, big_t) = (p.end_time(), p.duration());
    let scales = Scales {
        q: q0.abs().max(qf.abs()),
        qd: peak,
        qdd: amax,
    };
    let sign = dq.signum();
    assert_state(
        "t0",
        p.eval(t0),
        Setpoint::new(q0, 0.0, sign * amax),
        scales,
    );
    assert_state(
        "tf",
        p.eval(tf),
        Setpoint::new(qf, 0.0, -sign * amax),
        scales,
    );
    assert_held_outside(p, q0, qf);
    // At the (rounded) midpoint time: the velocity there is the peak, or a hair below it if the
    // rounding of t0 + T/2 lands on a blend.
    let t_mid = t0 + 0.5 * big_t;
    let (since, to_go) = (t_mid - t0, tf - t_mid);
    let want = peak.min(amax * since.min(to_go));
    assert_close("peak velocity", p.eval(t_mid).qd.abs(), want, peak);
    assert_close("blend time", p.blend_time(), peak / amax, big_t);
    let bounds = Bounds {
        qd: peak,
        qdd: amax,
        jerk: None,
    };
    let eps = 1e-9 * big_t;
    for s in [t0 + p.blend_time(), tf - p.blend_time()] {
        assert_continuous_at(p, s, eps, bounds, scales);
        assert_within_limits(p, s, peak, amax);
    }
    for t in interior_times(t0, tf, 10) {
        assert_within_limits(p, t, peak, amax);
    }
    let h = 1e-4 * big_t;
    for t in interior_times(t0 + h, tf - h, 8) {
        assert_derivatives_at(p, t, h, bounds, scales);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    #[test]
    fn bang_bang_is_minimum_time(t0 in start_time(), q0 in -100.0..100.0f64, dq in displacement(), amax in limit()) {
        let qf = q0 + dq;
        let dq = qf - q0;
        let p = Lspb::bang_bang(t0, q0, qf, amax).unwrap();
        // Closed form: tf = 2 ts with ts = sqrt(|qf - q0| / α).
        let ts = (dq.abs() / amax).sqrt();
        assert_close("duration", p.duration(), 2.0 * ts, 2.0 * ts);
        prop_assert_eq!(p.duration(), bang_bang_duration(q0, qf, amax).unwrap());
        if dq == 0.0 {
            prop_assert_eq!(p.duration(), 0.0);
            prop_assert_eq!(p.eval(t0), Setpoint::rest(q0));
            return Ok(());
        }
        check_min_time(&p, t0, q0, qf, amax * ts, amax);
        assert_close("switching time", p.blend_time(), 0.5 * p.duration(), p.duration());
        // Minimal: no LSPB with |q̈| ≤ amax makes the move in a slightly shorter time.
        let faster = Lspb::with_acceleration(t0, t0 + p.duration() * (1.0 - 1e-6), q0, qf, amax);
        let too_small = matches!(faster, Err(TrajectoryError::LspbAccelerationTooSmall { .. }));
        prop_assert!(too_small, "a faster move was possible: {:?}", faster);
    }

    #[test]
    fn velocity_limited_is_minimum_time(t0 in start_time(), q0 in -100.0..100.0f64, dq in displacement(),
                                        vmax in limit(), amax in limit()) {
        let qf = q0 + dq;
        let dq = qf - q0;
        let p = Lspb::velocity_limited(t0, q0, qf, vmax, amax).unwrap();
        prop_assert_eq!(p.duration(), velocity_limited_duration(q0, qf, vmax, amax).unwrap());
        if dq == 0.0 {
            prop_assert_eq!(p.duration(), 0.0);
            return Ok(());
        }
        let unconstrained_peak = (amax * dq.abs()).sqrt();
        let (want, peak) = if unconstrained_peak <= vmax {
            (2.0 * (dq.abs() / amax).sqrt(), unconstrained_peak)
        } else {
            // Trapezoid: T = |Δ|/vmax + vmax/amax, written over a common denominator here.
            ((dq.abs() * amax + vmax * vmax) / (vmax * amax), vmax)
        };
        assert_close("duration", p.duration(), want, want);
        check_min_time(&p, t0, q0, qf, peak, amax);
        assert_within_limits(&p, t0 + 0.5 * p.duration(), vmax, amax);
        // Minimal: a slightly shorter LSPB at full acceleration needs more than vmax (or cannot
        // be done at all).
        let faster = Lspb::with_acceleration(t0, t0 + p.duration() * (1.0 - 1e-6), q0, qf, amax);
        match faster {
            Ok(f) => prop_assert!(f.velocity().abs() > vmax, "a faster move within the limits: {:?}", f),
            Err(e) => prop_assert!(matches!(e, TrajectoryError::LspbAccelerationTooSmall { .. }), "{:?}", e),
        }
    }

    #[test]
    fn minimum_time_negative_moves_mirror(t0 in start_time(), q0 in -100.0..100.0f64, dq in displacement(),
                                          vmax in limit(), amax in limit()) {
        let qf = q0 + dq;
        let pairs = [
            (Lspb::bang_bang(t0, q0, qf, amax).unwrap(), Lspb::bang_bang(t0, -q0, -qf, amax).unwrap()),
            (
                Lspb::velocity_limited(t0, q0, qf, vmax, amax).unwrap(),
                Lspb::velocity_limited(t0, -q0, -qf, vmax, amax).unwrap(),
            ),
        ];
        for (p, m) in pairs {
            prop_assert_eq!(p.duration(), m.duration());
            for t in interior_times(t0 - 1.0, p.end_time() + 1.0, 12) {
                let (a, b) = (p.eval(t), m.eval(t));
                prop_assert_eq!((a.q, a.qd, a.qdd), (-b.q, -b.qd, -b.qdd));
            }
        }
    }
}

#[test]
fn textbook_numbers() {
    // ts = sqrt((qf - q0)/α) = sqrt(8/2) = 2, tf = 4.
    let p = Lspb::bang_bang(0.0, 0.0, 8.0, 2.0).unwrap();
    assert_eq!(
        (p.duration(), p.blend_time(), p.velocity()),
        (4.0, 2.0, 4.0)
    );
    assert_eq!(p.eval(2.0), Setpoint::new(4.0, 4.0, 2.0));
    // vmax = 2 < 4: trapezoid, tb = 1, T = 8/2 + 2/2 = 5.
    let p = Lspb::velocity_limited(0.0, 0.0, 8.0, 2.0, 2.0).unwrap();
    assert_eq!(
        (p.duration(), p.blend_time(), p.velocity()),
        (5.0, 1.0, 2.0)
    );
    assert_eq!(p.eval(2.5), Setpoint::new(4.0, 2.0, 0.0));
}

#[test]
fn non_positive_limits_are_rejected() {
    for bad in [0.0, -2.0] {
        let e = Lspb::bang_bang(0.0, 0.0, 1.0, bad).unwrap_err();
        assert_eq!(
            e,
            TrajectoryError::NonPositiveLimit {
                name: "amax",
                value: bad,
                at: Location::NONE
            }
        );
        assert_eq!(e.to_string(), format!("amax = {bad} must be positive"));
        let e = Lspb::velocity_limited(0.0, 0.0, 1.0, bad, 1.0).unwrap_err();
        assert_eq!(
            e,
            TrajectoryError::NonPositiveLimit {
                name: "vmax",
                value: bad,
                at: Location::NONE
            }
        );
        let e = Lspb::velocity_limited(0.0, 0.0, 1.0, 1.0, bad).unwrap_err();
        assert_eq!(
            e,
            TrajectoryError::NonPositiveLimit {
                name: "amax",
                value: bad,
                at: Location::NONE
            }
        );
        assert!(bang_bang_duration(0.0, 1.0, bad).is_err());
        assert!(velocity_limited_duration(0.0, 1.0, bad, 1.0).is_err());
    }
}

#[test]
fn non_finite_inputs_are_named() {
    let nan = f64::NAN;
    let cases = [
        ("t0", Lspb::bang_bang(nan, 0.0, 1.0, 1.0)),
        ("q0", Lspb::bang_bang(0.0, nan, 1.0, 1.0)),
        (
            "qf",
            Lspb::velocity_limited(0.0, 0.0, f64::INFINITY, 1.0, 1.0),
        ),
        ("amax", Lspb::bang_bang(0.0, 0.0, 1.0, f64::INFINITY)),
        ("vmax", Lspb::velocity_limited(0.0, 0.0, 1.0, nan, 1.0)),
        // Finite inputs whose minimum time overflows.
        ("duration", Lspb::bang_bang(0.0, 0.0, 1e300, 1e-300)),
        (
            "t0 + duration",
            Lspb::velocity_limited(f64::MAX, 0.0, 1e301, 1.0, 1e-300),
        ),
    ];
    for (name, result) in cases {
        let e = result.unwrap_err();
        assert!(
            matches!(e, TrajectoryError::NonFinite { name: got, .. } if got == name),
            "{name}: {e:?}"
        );
        assert!(e.to_string().starts_with(&format!("{name} = ")), "{e}");
    }
}
