//! Many joints synchronized to one duration (issue 6, item 2).

use crate::trajectory_support::*;
use dhgen::trajectory::{
    Cubic, Location, Lspb, MultiProfile, Profile, Quintic, Setpoint, Synchronized, TrajectoryError,
    bang_bang_duration, velocity_limited_duration,
};
use proptest::prelude::*;

const N: usize = 6;

fn start_time() -> impl Strategy<Value = f64> + Clone {
    -100.0..100.0f64
}

fn duration() -> impl Strategy<Value = f64> + Clone {
    (-3.0..2.0f64).prop_map(|e| 10f64.powf(e))
}

/// A move of either sign from 1e-3 to 1e3, or none.
fn displacement() -> impl Strategy<Value = f64> + Clone {
    prop_oneof![
        6 => ((-3.0..3.0f64), any::<bool>()).prop_map(|(e, neg)| if neg { -10f64.powf(e) } else { 10f64.powf(e) }),
        1 => Just(0.0),
    ]
}

fn limit() -> impl Strategy<Value = f64> + Clone {
    (-2.0..3.0f64).prop_map(|e| 10f64.powf(e))
}

fn joints<S: Strategy + Clone>(s: S) -> impl Strategy<Value = [S::Value; N]> {
    prop::array::uniform6(s)
}

/// The synchronized profile reproduces its per-joint profiles exactly, through both `eval` and
/// `eval_into`, and all joints share its time interval.
fn check_same_as_joints<P: Profile + PartialEq + core::fmt::Debug>(
    sync: &Synchronized<P, N>,
    singles: &[P; N],
) {
    assert_eq!(sync.joints(), singles);
    let (t0, tf) = (sync.start_time(), sync.end_time());
    for p in singles {
        assert_eq!((p.start_time(), p.end_time()), (t0, tf));
    }
    let mut out = [Setpoint::default(); N];
    let span = tf - t0;
    for t in interior_times(t0 - 0.1 * span, tf + 0.1 * span, 13).chain([t0, tf]) {
        sync.eval_into(t, &mut out).unwrap();
        let each: [Setpoint; N] = core::array::from_fn(|j| singles[j].eval(t));
        assert_eq!(out, each);
        assert_eq!(sync.eval(t), each);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    /// Cubic, quintic and both LSPB forms: one given interval for all joints.
    #[test]
    fn given_duration_profiles_share_the_interval(t0 in start_time(), big_t in duration(),
                                                  q0 in joints(-100.0..100.0f64), dq in joints(displacement()),
                                                  rates in joints(-2.0..2.0f64), fractions in joints(1e-6..=1.0f64)) {
        let tf = t0 + big_t;
        let big_t = tf - t0;
        let qf: [f64; N] = core::array::from_fn(|j| q0[j] + dq[j]);
        let v: [f64; N] = core::array::from_fn(|j| rates[j] * 100.0 / big_t);
        let zero = [0.0; N];

        let sync = Synchronized::cubic(t0, tf, &q0, &v, &qf, &zero).unwrap();
        let singles = core::array::from_fn(|j| Cubic::new(t0, tf, q0[j], v[j], qf[j], 0.0).unwrap());
        check_same_as_joints(&sync, &singles);

        let start: [Setpoint; N] = core::array::from_fn(|j| Setpoint::new(q0[j], v[j], rates[j]));
        let end: [Setpoint; N] = core::array::from_fn(|j| Setpoint::rest(qf[j]));
        let sync = Synchronized::quintic(t0, tf, &start, &end).unwrap();
        let singles = core::array::from_fn(|j| Quintic::new(t0, tf, start[j], end[j]).unwrap());
        check_same_as_joints(&sync, &singles);
        let sync = Synchronized::quintic_rest_to_rest(t0, tf, &q0, &qf).unwrap();
        let singles = core::array::from_fn(|j| Quintic::rest_to_rest(t0, tf, q0[j], qf[j]).unwrap());
        check_same_as_joints(&sync, &singles);

        let cruise: [f64; N] = core::array::from_fn(|j| (qf[j] - q0[j]) / big_t * (1.0 + fractions[j]));
        let sync = Synchronized::lspb_velocity(t0, tf, &q0, &qf, &cruise).unwrap();
        let singles = core::array::from_fn(|j| Lspb::with_velocity(t0, tf, q0[j], qf[j], cruise[j]).unwrap());
        check_same_as_joints(&sync, &singles);

        let alpha: [f64; N] = core::array::from_fn(|j| 4.0 * (qf[j] - q0[j]).abs() / (big_t * big_t) / fractions[j] + 1e-3);
        let sync = Synchronized::lspb_acceleration(t0, tf, &q0, &qf, &alpha).unwrap();
        let singles = core::array::from_fn(|j| Lspb::with_acceleration(t0, tf, q0[j], qf[j], alpha[j]).unwrap());
        check_same_as_joints(&sync, &singles);
    }

    /// Bang-bang: the slowest joint sets the duration, every joint switches at T/2 within its
    /// acceleration limit, and the motion is a straight line in joint space.
    #[test]
    fn bang_bang_synchronizes_to_the_slowest_joint(t0 in start_time(), q0 in joints(-100.0..100.0f64),
                                                   dq in joints(displacement()), amax in joints(limit())) {
        let qf: [f64; N] = core::array::from_fn(|j| q0[j] + dq[j]);
        let sync = Synchronized::bang_bang(t0, &q0, &qf, &amax).unwrap();
        // Closed form: T = max_j 2 sqrt(|Δ_j| / amax_j).
        let own: [f64; N] = core::array::from_fn(|j| 2.0 * ((qf[j] - q0[j]).abs() / amax[j]).sqrt());
        let big_t = own.iter().copied().fold(0.0, f64::max);
        assert_close("common duration", sync.duration(), big_t, big_t);
        if big_t == 0.0 {
            prop_assert_eq!(sync.eval(t0), core::array::from_fn(|j| Setpoint::rest(q0[j])));
            return Ok(());
        }
        let (tf, big_t) = (sync.end_time(), sync.duration());
        let slowest = (0..N).max_by(|&a, &b| own[a].total_cmp(&own[b])).unwrap();
        // The normalized bang-bang law s(τ) every joint must follow: 2 (τ/T)² up to T/2, then
        // 1 - 2 ((T - τ)/T)².
        let law = |t: f64| {
            let (since, to_go) = ((t - t0) / big_t, (tf - t) / big_t);
            if since <= 0.5 { 2.0 * since * since } else { 1.0 - 2.0 * to_go * to_go }
        };
        for (j, p) in sync.joints().iter().enumerate() {
            prop_assert_eq!((p.start_time(), p.end_time()), (t0, tf));
            let d = qf[j] - q0[j];
            let peak = 2.0 * d.abs() / big_t;
            let acc = 4.0 * d.abs() / (big_t * big_t);
            let scales = Scales { q: q0[j].abs().max(qf[j].abs()), qd: peak, qdd: acc };
            let sign = d.signum();
            assert_state("t0", p.eval(t0), Setpoint::new(q0[j], 0.0, sign * acc), scales);
            assert_state("tf", p.eval(tf), Setpoint::new(qf[j], 0.0, -sign * acc), scales);
            // A joint that does not move stands still (no blends at all).
            let switch = if d == 0.0 { 0.0 } else { 0.5 * big_t };
            assert_close("switching time", p.blend_time(), switch, big_t);
            if j == slowest {
                assert_close("slowest joint uses amax", p.acceleration().abs(), amax[j], amax[j]);
            }
            let bounds = Bounds { qd: peak, qdd: acc, jerk: None };
            assert_continuous_at(p, t0 + 0.5 * big_t, 1e-9 * big_t, bounds, scales);
            for t in interior_times(t0, tf, 10) {
                assert_within_limits(p, t, f64::INFINITY, amax[j]);
                if d != 0.0 {
                    // Straight line: every joint's normalized progress follows the same law
                    // (measured to the position scale and to the rounding of t).
                    let s = (p.eval(t).q - q0[j]) / d;
                    let tol = BOUNDARY_TOL * (scales.q / d.abs() + 1.0) + 64.0 * f64::EPSILON * t.abs() * 2.0 / big_t;
                    prop_assert!((s - law(t)).abs() <= tol, "joint {} at {}: progress {} vs {}", j, t, s, law(t));
                }
            }
        }
    }

    /// Velocity-limited: the slowest joint runs its own minimum-time profile; every joint ends
    /// together and stays within both of its limits.
    #[test]
    fn velocity_limited_synchronizes_to_the_slowest_joint(t0 in start_time(), q0 in joints(-100.0..100.0f64),
                                                          dq in joints(displacement()), vmax in joints(limit()),
                                                          amax in joints(limit())) {
        let qf: [f64; N] = core::array::from_fn(|j| q0[j] + dq[j]);
        let sync = Synchronized::velocity_limited(t0, &q0, &qf, &vmax, &amax).unwrap();
        let own: [f64; N] = core::array::from_fn(|j| {
            let d = (qf[j] - q0[j]).abs();
            if amax[j] * d <= vmax[j] * vmax[j] { 2.0 * (d / amax[j]).sqrt() } else { d / vmax[j] + vmax[j] / amax[j] }
        });
        let big_t = own.iter().copied().fold(0.0, f64::max);
        assert_close("common duration", sync.duration(), big_t, big_t);
        if big_t == 0.0 {
            return Ok(());
        }
        let (tf, big_t) = (sync.end_time(), sync.duration());
        for (j, p) in sync.joints().iter().enumerate() {
            prop_assert_eq!((p.start_time(), p.end_time()), (t0, tf));
            let d = qf[j] - q0[j];
            if own[j] == big_t {
                prop_assert_eq!(p, &Lspb::velocity_limited(t0, q0[j], qf[j], vmax[j], amax[j]).unwrap());
            }
            let scales = Scales { q: q0[j].abs().max(qf[j].abs()), qd: vmax[j], qdd: amax[j] };
            assert_state("t0", p.eval(t0), Setpoint::new(q0[j], 0.0, p.acceleration()), scales);
            assert_state("tf", p.eval(tf), Setpoint::new(qf[j], 0.0, -p.acceleration()), scales);
            if d != 0.0 {
                // Blends at full acceleration; the cruise covers the rest of the move.
                assert_close("blend acceleration", p.acceleration().abs(), amax[j], amax[j]);
                assert_close("distance V (T - tb)", p.velocity() * (big_t - p.blend_time()), d, d.abs());
            }
            let bounds = Bounds { qd: vmax[j], qdd: amax[j], jerk: None };
            for s in [t0 + p.blend_time(), tf - p.blend_time()] {
                assert_continuous_at(p, s, 1e-9 * big_t, bounds, scales);
                assert_within_limits(p, s, vmax[j], amax[j]);
            }
            for t in interior_times(t0, tf, 10) {
                assert_within_limits(p, t, vmax[j], amax[j]);
            }
        }
    }
}

#[test]
fn closed_form_durations_are_the_per_joint_maximum() {
    let q0 = [0.0; 3];
    let qf = [8.0, -2.0, 0.0];
    let sync = Synchronized::bang_bang(0.0, &q0, &qf, &[2.0, 8.0, 1.0]).unwrap();
    assert_eq!(sync.duration(), 4.0); // joint 0: 2 sqrt(8/2); joint 1: 1
    assert_eq!(bang_bang_duration(0.0, 8.0, 2.0).unwrap(), 4.0);
    let sync =
        Synchronized::velocity_limited(0.0, &q0, &qf, &[2.0, 1.0, 1.0], &[2.0, 8.0, 1.0]).unwrap();
    assert_eq!(sync.duration(), 5.0); // joint 0: 8/2 + 2/2; joint 1: 2/1 + 1/8
    assert_eq!(
        velocity_limited_duration(0.0, -2.0, 1.0, 8.0).unwrap(),
        2.125
    );
    assert_eq!(
        sync.eval(5.0),
        [
            Setpoint::new(8.0, 0.0, -2.0),
            Setpoint::new(-2.0, 0.0, 8.0),
            Setpoint::rest(0.0)
        ]
    );
}

#[test]
fn errors_name_the_joint() {
    let q0 = [0.0; 3];
    let qf = [1.0, 2.0, 3.0];
    let e = Synchronized::bang_bang(0.0, &q0, &qf, &[1.0, 1.0, -1.0]).unwrap_err();
    assert_eq!(
        e,
        TrajectoryError::NonPositiveLimit {
            name: "amax",
            value: -1.0,
            at: Location::joint(2)
        }
    );
    assert_eq!(e.to_string(), "amax = -1 must be positive (joint 2)");
    let e = Synchronized::velocity_limited(0.0, &q0, &qf, &[1.0, 0.0, 1.0], &[1.0; 3]).unwrap_err();
    assert_eq!(
        e,
        TrajectoryError::NonPositiveLimit {
            name: "vmax",
            value: 0.0,
            at: Location::joint(1)
        }
    );
    let e = Synchronized::lspb_velocity(0.0, 1.0, &q0, &qf, &[1.5, 5.0, 4.5]).unwrap_err();
    assert!(
        matches!(e, TrajectoryError::LspbVelocityOutOfRange { at, .. } if at == Location::joint(1)),
        "{e:?}"
    );
    assert!(e.to_string().ends_with("(joint 1)"), "{e}");
    let e = Synchronized::lspb_acceleration(0.0, 1.0, &q0, &qf, &[4.0, 8.0, 1.0]).unwrap_err();
    assert!(
        matches!(e, TrajectoryError::LspbAccelerationTooSmall { at, .. } if at == Location::joint(2)),
        "{e:?}"
    );
    let e = Synchronized::quintic_rest_to_rest(0.0, 1.0, &q0, &[1.0, f64::NAN, 0.0]).unwrap_err();
    assert_eq!(e.to_string(), "qf = NaN is not finite (joint 1)");
    let e = Synchronized::cubic(1.0, 1.0, &q0, &q0, &qf, &q0).unwrap_err();
    assert_eq!(e, TrajectoryError::EmptyTimeInterval { t0: 1.0, tf: 1.0 });
}

#[test]
fn joints_on_different_intervals_are_rejected() {
    let a = Cubic::rest_to_rest(0.0, 1.0, 0.0, 1.0).unwrap();
    let b = Cubic::rest_to_rest(0.0, 2.0, 0.0, 1.0).unwrap();
    let e = Synchronized::new([a, a, b]).unwrap_err();
    assert_eq!(
        e,
        TrajectoryError::MismatchedTimes {
            joint: 2,
            t0: 0.0,
            tf: 2.0,
            expected_t0: 0.0,
            expected_tf: 1.0
        }
    );
    assert_eq!(
        e.to_string(),
        "joint 2 runs on [0, 2] but joint 0 on [0, 1]: synchronized joints must share one time interval"
    );
    assert!(Synchronized::new([a, a]).is_ok());
}

#[test]
fn no_joints_is_rejected() {
    let none: [Cubic; 0] = [];
    assert_eq!(
        Synchronized::new(none).unwrap_err(),
        TrajectoryError::NoJoints
    );
    let e = Synchronized::<Lspb, 0>::bang_bang(0.0, &[], &[], &[]).unwrap_err();
    assert_eq!(
        e.to_string(),
        "a trajectory needs at least one joint, got none"
    );
}

#[test]
fn eval_into_checks_the_buffer_length() {
    let sync = Synchronized::quintic_rest_to_rest(0.0, 1.0, &[0.0; 2], &[1.0; 2]).unwrap();
    let mut out = [Setpoint::default(); 3];
    let e = sync.eval_into(0.5, &mut out).unwrap_err();
    assert_eq!(
        e,
        TrajectoryError::LengthMismatch {
            name: "out",
            expected: 2,
            found: 3,
            at: Location::NONE
        }
    );
    assert_eq!(e.to_string(), "out has length 3, expected 2");
}

/// A joint whose move is nearly the slowest joint's, at the boundary of the two regimes
/// (amax·|Δ| ≈ vmax², where the blend time has an infinite derivative), starting late: it
/// follows the slowest joint's duration itself, not `end − t0` (which is that duration only to
/// the rounding of the end time). Built from `end − t0` it had exceeded vmax by 1.9e-7 of it
/// (and, before the bang-bang bound allowed for that rounding, had been refused).
#[test]
fn a_joint_nearly_the_slowest_keeps_its_limits_when_starting_late() {
    let q0 = [
        0.835_073_358_107_350_1,
        0.903_782_761_416_425_7,
        0.156_428_751_233_391_5,
    ];
    let qf = [
        0.521_761_883_075_312_3,
        0.590_471_286_384_388_1,
        -6.349_236_870_898_389e-4,
    ];
    let (vmax, amax) = (1.199_027_104_930_081_6, 4.588_617_565_256_723);
    for t0 in [0.0, 1e3, 1e5, 3e6] {
        let p = Synchronized::velocity_limited(t0, &q0, &qf, &[vmax; 3], &[amax; 3])
            .unwrap_or_else(|e| panic!("t0 {t0}: {e}"));
        let (a, b) = (p.start_time(), p.end_time());
        for i in 0..=2000 {
            let t = a + (b - a) * f64::from(i) / 2000.0;
            for (j, s) in p.eval(t).iter().enumerate() {
                assert!(
                    s.qd.abs() <= vmax * (1.0 + 1e-12),
                    "t0 {t0}, joint {j}: q̇ {} at {t}",
                    s.qd
                );
                assert!(
                    s.qdd.abs() <= amax * (1.0 + 1e-12),
                    "t0 {t0}, joint {j}: q̈ {}",
                    s.qdd
                );
            }
        }
        for (j, s) in p.eval(b).iter().enumerate() {
            assert_close("q(tf)", s.q, qf[j], 1.0);
        }
    }
}
