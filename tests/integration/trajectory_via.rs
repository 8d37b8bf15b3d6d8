//! Via-point trajectories (section 6.5.2): the cubic spline and linear segments with parabolic
//! blends (`mstraj`-like), from given times and from limits.

use crate::support::max_abs;
use crate::trajectory_support::*;
use dhgen::trajectory::{
    BlendedSegments, CubicSpline, Location, Lspb, MultiProfile, Profile, Setpoint, SplineEnds,
    TrajectoryError,
};
use proptest::prelude::*;

/// Via times (start in [-10, 10], steps in [0.05, 2]) and points (`dof` in 1..=3, 2..=7 points).
fn via_points() -> impl Strategy<Value = (Vec<f64>, Vec<Vec<f64>>)> {
    (1usize..=3, 2usize..=7)
        .prop_flat_map(|(dof, n)| {
            (
                -10.0..10.0f64,
                prop::collection::vec(0.05..2.0f64, n - 1),
                prop::collection::vec(prop::collection::vec(-100.0..100.0f64, dof), n),
            )
        })
        .prop_map(|(t0, steps, points)| {
            let mut times = vec![t0];
            for h in steps {
                times.push(times[times.len() - 1] + h);
            }
            (times, points)
        })
}

/// Checks the spline through `points` at `times` for one joint.
fn check_spline_joint(
    spline: &CubicSpline,
    times: &[f64],
    points: &[Vec<f64>],
    j: usize,
    ends: SplineEnds<'_>,
) {
    let p = spline.joint(j).unwrap();
    let n = times.len();
    let y: Vec<f64> = points.iter().map(|pt| pt[j]).collect();
    let m: Vec<f64> = (0..n)
        .map(|i| spline.knot_accelerations(i).unwrap()[j])
        .collect();
    let steps: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
    let (h_min, h_max) = (
        steps.iter().copied().fold(f64::INFINITY, f64::min),
        steps.iter().copied().fold(0.0, f64::max),
    );
    let m_max = max_abs(m.iter().copied());
    let slope_max = max_abs((0..n - 1).map(|k| (y[k + 1] - y[k]) / steps[k]));
    let end_v = match ends {
        SplineEnds::Clamped { start, end } => start[j].abs().max(end[j].abs()),
        _ => 0.0,
    };
    let scales = Scales {
        q: max_abs(y.iter().copied()) + m_max * h_max * h_max,
        qd: slope_max + m_max * h_max + end_v,
        qdd: m_max + (slope_max + end_v) / h_min,
    };
    // Bounds of the true derivatives: |q̇| from the segment formula, |q̈| ≤ max |M| (linear
    // between knots), |q⃛| ≤ max |M_{k+1} - M_k| / h_k.
    let jerk = (0..n - 1)
        .map(|k| (m[k + 1] - m[k]).abs() / steps[k])
        .fold(0.0, f64::max);
    let bounds = Bounds {
        qd: slope_max + 2.0 * m_max * h_max / 3.0,
        qdd: m_max,
        jerk: Some(jerk),
    };

    // Interpolation: every via point is reached at its time.
    for i in 0..n {
        assert_close(
            &format!("q at via point {i}"),
            p.eval(times[i]).q,
            y[i],
            scales.q,
        );
    }
    // End conditions.
    let (first, last) = (p.eval(times[0]), p.eval(times[n - 1]));
    match ends {
        SplineEnds::Natural => {
            assert_close("natural start q̈", first.qdd, 0.0, scales.qdd);
            assert_close("natural end q̈", last.qdd, 0.0, scales.qdd);
        }
        SplineEnds::AtRest => {
            assert_close("start q̇", first.qd, 0.0, scales.qd);
            assert_close("end q̇", last.qd, 0.0, scales.qd);
        }
        SplineEnds::Clamped { start, end } => {
            assert_close("start q̇", first.qd, start[j], scales.qd);
            assert_close("end q̇", last.qd, end[j], scales.qd);
        }
    }
    // Position, velocity and acceleration continuous across every interior knot.
    let eps = 1e-9 * h_min;
    for &t in &times[1..n - 1] {
        assert_continuous_at(&p, t, eps, bounds, scales);
    }
    // q̇ and q̈ are the derivatives of q and q̇ everywhere.
    let h = 1e-4 * h_min;
    for t in interior_times(times[0] + h, times[n - 1] - h, 4 * n) {
        assert_derivatives_at(&p, t, h, bounds, scales);
    }
    assert_held_outside(&p, y[0], y[n - 1]);
}

/// Independent expectations for a blended path from given times: corner times and velocities.
/// `spans`: the segments' durations where they are known in closed form (from limits); else
/// the differences of corner times (from times). The differences of absolute times carry
/// their rounding, up to ulp(t) over a short segment late in a long path.
fn expected_blends(
    times: &[f64],
    points: &[Vec<f64>],
    tacc: f64,
    j: usize,
    spans: Option<&[f64]>,
) -> (Vec<f64>, Vec<f64>) {
    let m = times.len() - 1;
    let mut corners = times.to_vec();
    corners[0] += tacc / 2.0;
    corners[m] -= tacc / 2.0;
    let mut v = vec![0.0; m + 2];
    for k in 1..=m {
        let span = spans.map_or(corners[k] - corners[k - 1], |s| s[k - 1]);
        v[k] = (points[k][j] - points[k - 1][j]) / span;
    }
    (corners, v)
}

/// Checks one joint of a blended path: rest at the ends, corner cutting, lines, blends,
/// continuity and derivative consistency. Returns the largest |q̇| and |q̈| seen.
fn check_blend_joint(path: &BlendedSegments, points: &[Vec<f64>], j: usize, spans: Option<&[f64]>) {
    let p = path.joint(j).unwrap();
    let times = path.times();
    let m = times.len() - 1;
    let tacc = path.blend_time();
    let half = tacc / 2.0;
    let (corners, v) = expected_blends(times, points, tacc, j, spans);
    let v_max = max_abs(v.iter().copied());
    let a_max = (0..=m)
        .map(|k| (v[k + 1] - v[k]).abs() / tacc)
        .fold(0.0, f64::max);
    let t_max = max_abs(times.iter().copied());
    let scales = Scales {
        q: max_abs(points.iter().map(|pt| pt[j])) + v_max * t_max,
        qd: v_max,
        qdd: a_max,
    };
    for (k, &v_k) in v.iter().enumerate().take(m + 1).skip(1) {
        assert_close(
            &format!("segment {k} velocity"),
            path.segment_velocity(k).unwrap()[j],
            v_k,
            v_max,
        );
    }
    // At rest at the first and last point, accelerating into / out of the first / last segment.
    assert_state(
        "t0",
        p.eval(times[0]),
        Setpoint::new(points[0][j], 0.0, v[1] / tacc),
        scales,
    );
    assert_state(
        "tf",
        p.eval(times[m]),
        Setpoint::new(points[m][j], 0.0, -v[m] / tacc),
        scales,
    );
    assert_held_outside(&p, points[0][j], points[m][j]);
    for k in 0..=m {
        let a_k = (v[k + 1] - v[k]) / tacc;
        // Interior corners are cut by (v_{k+1} - v_k) tacc / 8.
        if k > 0 && k < m {
            let got = p.eval(corners[k]);
            assert_close(
                &format!("corner {k} position"),
                got.q,
                points[k][j] + a_k * tacc * tacc / 8.0,
                scales.q,
            );
            assert_close(
                &format!("corner {k} velocity"),
                got.qd,
                0.5 * (v[k] + v[k + 1]),
                scales.qd,
            );
        }
        // Constant acceleration inside each blend.
        for t in [corners[k] - half / 2.0, corners[k] + half / 2.0] {
            assert_close(
                &format!("blend {k} acceleration"),
                p.eval(t).qdd,
                a_k,
                scales.qdd,
            );
        }
        // Continuous position and velocity where blends start and end, and at corners.
        let bounds = Bounds {
            qd: v_max,
            qdd: a_max,
            jerk: None,
        };
        let eps = 1e-9 * tacc;
        for t in [corners[k] - half, corners[k], corners[k] + half] {
            if t > times[0] && t < times[m] {
                assert_continuous_at(&p, t, eps, bounds, scales);
            }
        }
    }
    // Straight lines with the segment velocity between the blends.
    for k in 1..=m {
        let (from, to) = (corners[k - 1] + half, corners[k] - half);
        if to - from > 1e-6 * tacc {
            let t = 0.5 * (from + to);
            let got = p.eval(t);
            assert_close(
                &format!("line {k} position"),
                got.q,
                points[k][j] + v[k] * (t - corners[k]),
                scales.q,
            );
            assert_eq!(
                (got.qd, got.qdd),
                (path.segment_velocity(k).unwrap()[j], 0.0),
                "line {k}"
            );
        }
    }
    let bounds = Bounds {
        qd: v_max,
        qdd: a_max,
        jerk: None,
    };
    let h = 1e-4 * tacc;
    for t in interior_times(times[0] + h, times[m] - h, 6 * m) {
        assert_derivatives_at(&p, t, h, bounds, scales);
        let s = p.eval(t);
        assert!(
            s.qd.abs() <= v_max * (1.0 + LIMIT_SLACK),
            "|q̇| above the fastest segment at {t}"
        );
        assert!(
            s.qdd.abs() <= a_max * (1.0 + LIMIT_SLACK),
            "|q̈| above the largest blend at {t}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(10_000))]

    #[test]
    fn spline_interpolates_with_continuous_acceleration((times, points) in via_points(), kind in 0u8..3,
                                                        v in prop::collection::vec(-50.0..50.0f64, 6)) {
        let dof = points[0].len();
        let ends = match kind {
            0 => SplineEnds::Natural,
            1 => SplineEnds::AtRest,
            _ => SplineEnds::Clamped { start: &v[..dof], end: &v[3..3 + dof] },
        };
        let spline = CubicSpline::new(&times, &points, ends).unwrap();
        prop_assert_eq!(spline.dof(), dof);
        prop_assert_eq!((spline.start_time(), spline.end_time()), (times[0], times[times.len() - 1]));
        for j in 0..dof {
            check_spline_joint(&spline, &times, &points, j, ends);
        }
    }

    /// A cubic is its own clamped spline: through knots sampled from a cubic polynomial, with the
    /// polynomial's end velocities, the spline is that polynomial.
    #[test]
    fn spline_reproduces_a_cubic((times, _) in via_points(), c in prop::collection::vec(-10.0..10.0f64, 4)) {
        let (t0, tf) = (times[0], times[times.len() - 1]);
        let x = |t: f64| (t - t0) / (tf - t0);
        let poly = |t: f64| c[0] + x(t) * (c[1] + x(t) * (c[2] + x(t) * c[3]));
        let dpoly = |t: f64| (c[1] + x(t) * (2.0 * c[2] + x(t) * 3.0 * c[3])) / (tf - t0);
        let ddpoly = |t: f64| (2.0 * c[2] + 6.0 * c[3] * x(t)) / ((tf - t0) * (tf - t0));
        let points: Vec<[f64; 1]> = times.iter().map(|&t| [poly(t)]).collect();
        let spline = CubicSpline::new(&times, &points, SplineEnds::Clamped { start: &[dpoly(t0)], end: &[dpoly(tf)] }).unwrap();
        let p = spline.joint(0).unwrap();
        let scale: f64 = c.iter().map(|x| x.abs()).sum();
        let span = tf - t0;
        for t in interior_times(t0, tf, 17).chain(times.iter().copied()) {
            let got = p.eval(t);
            assert_close("q", got.q, poly(t), scale);
            assert_close("q̇", got.qd, dpoly(t), scale / span * 1e2);
            assert_close("q̈", got.qdd, ddpoly(t), scale / (span * span) * 1e3);
        }
    }

    #[test]
    fn blends_from_times((times, points) in via_points(), tacc in 0.05..1.0f64,
                         extra in prop::collection::vec(prop_oneof![1 => Just(0.0), 3 => 0.0..2.0f64], 6)) {
        // Re-time the segments so that the blends fit (sometimes exactly).
        let m = points.len() - 1;
        let mut times = times;
        for k in 1..=m {
            let ends = [k == 1, k == m].iter().filter(|&&e| e).count() as f64;
            let needed = tacc * (1.0 + 0.5 * ends);
            times[k] = times[k - 1] + needed * (1.0 + extra[k - 1]);
        }
        let path = BlendedSegments::from_times(&times, &points, tacc).unwrap();
        prop_assert_eq!(path.times(), &times[..]);
        prop_assert_eq!(path.blend_time(), tacc);
        for j in 0..points[0].len() {
            check_blend_joint(&path, &points, j, None);
        }
    }

    /// With two points, linear segments with parabolic blends are the LSPB with tb = tacc.
    #[test]
    fn two_point_blend_is_lspb(t0 in -10.0..10.0f64, big_t in 0.1..10.0f64, q0 in -100.0..100.0f64,
                               qf in -100.0..100.0f64, fraction in 1e-3..=0.5f64) {
        let tf = t0 + big_t;
        let big_t = tf - t0;
        let tacc = fraction * big_t;
        let path = BlendedSegments::from_times(&[t0, tf], &[[q0], [qf]], tacc).unwrap();
        let v = (qf - q0) / (big_t - tacc);
        let lspb = Lspb::with_velocity(t0, tf, q0, qf, v).unwrap();
        assert_close("tb", lspb.blend_time(), tacc, big_t);
        let p = path.joint(0).unwrap();
        let scales = Scales { q: q0.abs().max(qf.abs()) + v.abs() * tf.abs(), qd: v.abs(), qdd: v.abs() / tacc };
        for t in interior_times(t0 - 1.0, tf + 1.0, 23).chain([t0, tf]) {
            let (a, b) = (p.eval(t), lspb.eval(t));
            assert_close("q", a.q, b.q, scales.q);
            assert_close("q̇", a.qd, b.qd, scales.qd);
            if (t - t0 - tacc).abs() > 1e-9 * big_t && (tf - t - tacc).abs() > 1e-9 * big_t {
                assert_close("q̈", a.qdd, b.qdd, scales.qdd);
            }
        }
    }

    /// From limits: every joint within its vmax and amax, segments timed by their slowest joint.
    #[test]
    fn blends_from_limits((_, points) in via_points(), t0 in -10.0..10.0f64,
                          vmax in prop::collection::vec((-1.0..2.0f64).prop_map(|e| 10f64.powf(e)), 3),
                          amax in prop::collection::vec((-1.0..3.0f64).prop_map(|e| 10f64.powf(e)), 3),
                          repeat in any::<bool>()) {
        let dof = points[0].len();
        let mut points = points;
        if repeat {
            // A repeated via point: a segment where nothing moves.
            let p = points[0].clone();
            points.insert(1, p);
        }
        let (vmax, amax) = (&vmax[..dof], &amax[..dof]);
        let path = BlendedSegments::from_limits(t0, &points, vmax, amax).unwrap();
        let times = path.times();
        let m = times.len() - 1;
        let tacc = path.blend_time();
        prop_assert_eq!(times[0], t0);
        prop_assert!(tacc > 0.0);
        // Closed form of each segment's duration: its slowest joint at vmax, at least tacc.
        // Measured as a difference of corner times, it carries their rounding (relative to
        // the times, not to the duration: a short segment after long ones).
        let mut corners = times.to_vec();
        corners[0] += tacc / 2.0;
        corners[m] -= tacc / 2.0;
        let mut spans = Vec::new();
        for k in 1..=m {
            let cruise = (0..dof).map(|j| (points[k][j] - points[k - 1][j]).abs() / vmax[j]).fold(0.0, f64::max);
            let want = cruise.max(tacc);
            let times_scale = corners[k].abs().max(corners[k - 1].abs());
            assert_close(&format!("segment {k} duration"), corners[k] - corners[k - 1], want, want + times_scale);
            spans.push(want);
        }
        // tacc is the smallest blend time whose blends all stay within amax: at tacc some blend
        // uses its joint's full amax, and every sampled shorter blend time overloads some joint.
        let worst = |tacc: f64| {
            let velocity = |k: usize, j: usize| {
                if k == 0 || k > m {
                    return 0.0;
                }
                let cruise = (0..dof).map(|i| (points[k][i] - points[k - 1][i]).abs() / vmax[i]).fold(0.0, f64::max);
                let d = cruise.max(tacc);
                if d > 0.0 { (points[k][j] - points[k - 1][j]) / d } else { 0.0 }
            };
            (0..=m)
                .flat_map(|k| (0..dof).map(move |j| (k, j)))
                .map(|(k, j)| (velocity(k + 1, j) - velocity(k, j)).abs() / (amax[j] * tacc))
                .fold(0.0, f64::max)
        };
        let moves = points.windows(2).any(|w| w[0] != w[1]);
        if moves {
            let at_tacc = worst(tacc);
            prop_assert!((at_tacc - 1.0).abs() <= 1e-9, "at tacc = {} the largest blend uses {} of amax", tacc, at_tacc);
            for fraction in [0.25, 0.5, 0.75, 0.9, 0.99, 0.999] {
                let shorter = worst(fraction * tacc);
                prop_assert!(shorter > 1.0, "tacc * {} = {} would also do ({} of amax)", fraction, fraction * tacc, shorter);
            }
        }
        for j in 0..dof {
            check_blend_joint(&path, &points, j, Some(&spans));
            let p = path.joint(j).unwrap();
            let half = tacc / 2.0;
            let probes = corners.iter().flat_map(|&c| [c - half, c - half / 2.0, c, c + half / 2.0, c + half]);
            for t in interior_times(times[0], times[m], 8 * m).chain(probes) {
                assert_within_limits(&p, t, vmax[j], amax[j]);
            }
        }
    }
}

#[test]
fn fewer_than_two_points_are_rejected() {
    let none: [[f64; 2]; 0] = [];
    let one = [[1.0, 2.0]];
    for (points, found) in [(&none[..], 0), (&one[..], 1)] {
        let times = vec![0.0; found];
        let e = CubicSpline::new(&times, points, SplineEnds::Natural).unwrap_err();
        assert_eq!(e, TrajectoryError::TooFewPoints { found });
        assert_eq!(
            e.to_string(),
            format!("a via-point trajectory needs at least two points, got {found}")
        );
        assert_eq!(
            BlendedSegments::from_times(&times, points, 0.1).unwrap_err(),
            e
        );
        assert_eq!(
            BlendedSegments::from_limits(0.0, points, &[1.0; 2], &[1.0; 2]).unwrap_err(),
            e
        );
    }
}

#[test]
fn non_increasing_via_times_are_rejected() {
    let points = [[0.0], [1.0], [2.0], [3.0]];
    for (times, previous, value) in [
        ([0.0, 1.0, 1.0, 2.0], 1.0, 1.0),
        ([0.0, 1.0, 0.5, 2.0], 1.0, 0.5),
    ] {
        let e = CubicSpline::new(&times, &points, SplineEnds::AtRest).unwrap_err();
        assert_eq!(
            e,
            TrajectoryError::NonIncreasingTimes {
                index: 2,
                previous,
                value
            }
        );
        assert_eq!(
            e.to_string(),
            format!(
                "via times must increase strictly, but times[2] = {value} is not greater than times[1] = {previous}"
            )
        );
        assert_eq!(
            BlendedSegments::from_times(&times, &points, 0.1).unwrap_err(),
            e
        );
    }
}

#[test]
fn non_finite_via_inputs_are_named() {
    let e = CubicSpline::new(
        &[0.0, 1.0, 2.0],
        &[[0.0, 1.0], [1.0, f64::NAN], [2.0, 2.0]],
        SplineEnds::Natural,
    )
    .unwrap_err();
    assert!(
        matches!(e, TrajectoryError::NonFinite { name: "q", value, at } if value.is_nan() && at == Location::point(1, 1)),
        "{e:?}"
    );
    assert_eq!(
        e.to_string(),
        "q = NaN is not finite (via point 1, joint 1)"
    );
    let e = BlendedSegments::from_times(&[0.0, f64::INFINITY], &[[0.0], [1.0]], 0.1).unwrap_err();
    assert_eq!(e.to_string(), "time = inf is not finite (via point 1)");
    let e = CubicSpline::new(
        &[0.0, 1.0],
        &[[0.0, 0.0], [1.0, 1.0]],
        SplineEnds::Clamped {
            start: &[0.0, 0.0],
            end: &[f64::NAN, 0.0],
        },
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "end velocities = NaN is not finite (joint 0)"
    );
    let e = BlendedSegments::from_limits(
        0.0,
        &[[0.0, 0.0], [1.0, 1.0]],
        &[1.0, f64::NAN],
        &[1.0, 1.0],
    )
    .unwrap_err();
    assert_eq!(e.to_string(), "vmax = NaN is not finite (joint 1)");
    let e = BlendedSegments::from_limits(f64::NAN, &[[0.0], [1.0]], &[1.0], &[1.0]).unwrap_err();
    assert!(
        matches!(e, TrajectoryError::NonFinite { name: "t0", .. }),
        "{e:?}"
    );
}

#[test]
fn non_positive_limits_are_rejected() {
    let points = [[0.0, 0.0], [1.0, 1.0]];
    let e = BlendedSegments::from_times(&[0.0, 1.0], &points, 0.0).unwrap_err();
    assert_eq!(
        e,
        TrajectoryError::NonPositiveLimit {
            name: "tacc",
            value: 0.0,
            at: Location::NONE
        }
    );
    assert_eq!(e.to_string(), "tacc = 0 must be positive");
    let e = BlendedSegments::from_limits(0.0, &points, &[1.0, -1.0], &[1.0, 1.0]).unwrap_err();
    assert_eq!(
        e,
        TrajectoryError::NonPositiveLimit {
            name: "vmax",
            value: -1.0,
            at: Location::joint(1)
        }
    );
    let e = BlendedSegments::from_limits(0.0, &points, &[1.0, 1.0], &[0.0, 1.0]).unwrap_err();
    assert_eq!(e.to_string(), "amax = 0 must be positive (joint 0)");
}

#[test]
fn overlapping_blends_are_rejected() {
    // Three points: segment 1 needs 1.5 tacc, segment 2 needs 1.5 tacc; with four, the middle 1 tacc.
    let e = BlendedSegments::from_times(&[0.0, 1.4, 3.0], &[[0.0], [1.0], [0.0]], 1.0).unwrap_err();
    assert_eq!(
        e,
        TrajectoryError::BlendsOverlap {
            segment: 1,
            available: 1.4,
            needed: 1.5
        }
    );
    assert_eq!(
        e.to_string(),
        "segment 1 (via point 0 to 1) lasts 1.4, but its parabolic blends need 1.5: \
         use a shorter blend time or more time for the segment"
    );
    let e = BlendedSegments::from_times(&[0.0, 1.5, 2.4, 4.0], &[[0.0], [1.0], [0.0], [1.0]], 1.0)
        .unwrap_err();
    assert!(
        matches!(e, TrajectoryError::BlendsOverlap { segment: 2, needed, .. } if needed == 1.0),
        "{e:?}"
    );
    // Two points: the LSPB condition T >= 2 tacc.
    let e = BlendedSegments::from_times(&[0.0, 1.9], &[[0.0], [1.0]], 1.0).unwrap_err();
    assert!(
        matches!(e, TrajectoryError::BlendsOverlap { segment: 1, needed, .. } if needed == 2.0),
        "{e:?}"
    );
    assert!(BlendedSegments::from_times(&[0.0, 2.0], &[[0.0], [1.0]], 1.0).is_ok());
}

#[test]
fn mismatched_lengths_are_rejected() {
    let e = CubicSpline::new(&[0.0, 1.0, 2.0], &[[0.0], [1.0]], SplineEnds::Natural).unwrap_err();
    assert_eq!(e.to_string(), "times has length 3, expected 2");
    let ragged: [&[f64]; 3] = [&[0.0, 1.0], &[1.0, 2.0], &[2.0]];
    let e = CubicSpline::new(&[0.0, 1.0, 2.0], &ragged, SplineEnds::Natural).unwrap_err();
    assert_eq!(
        e.to_string(),
        "via point has length 1, expected 2 (via point 2)"
    );
    let e = CubicSpline::new(
        &[0.0, 1.0],
        &[[0.0, 0.0], [1.0, 1.0]],
        SplineEnds::Clamped {
            start: &[0.0],
            end: &[0.0, 0.0],
        },
    )
    .unwrap_err();
    assert_eq!(e.to_string(), "start velocities has length 1, expected 2");
    let e = BlendedSegments::from_limits(0.0, &[[0.0, 0.0], [1.0, 1.0]], &[1.0], &[1.0, 1.0])
        .unwrap_err();
    assert_eq!(e.to_string(), "vmax has length 1, expected 2");
    let empty: [&[f64]; 2] = [&[], &[]];
    assert_eq!(
        CubicSpline::new(&[0.0, 1.0], &empty, SplineEnds::Natural).unwrap_err(),
        TrajectoryError::NoJoints
    );
    let spline =
        CubicSpline::new(&[0.0, 1.0], &[[0.0, 0.0], [1.0, 1.0]], SplineEnds::Natural).unwrap();
    let mut out = [Setpoint::default(); 1];
    assert!(matches!(
        spline.eval_into(0.5, &mut out),
        Err(TrajectoryError::LengthMismatch {
            name: "out",
            expected: 2,
            found: 1,
            ..
        })
    ));
    assert!(spline.joint(2).is_none());
}

#[test]
fn stationary_path_from_limits() {
    let path = BlendedSegments::from_limits(1.0, &[[2.0], [2.0], [2.0]], &[1.0], &[4.0]).unwrap();
    assert_eq!(path.blend_time(), 0.25);
    for t in interior_times(0.0, path.end_time() + 1.0, 9) {
        assert_eq!(path.joint(0).unwrap().eval(t), Setpoint::rest(2.0));
    }
}

#[test]
fn blends_beyond_float_range_are_rejected() {
    // A 2e-300 s move of 1: the segment velocity (1e300) is finite, its blend acceleration is not.
    let e = BlendedSegments::from_times(&[0.0, 2e-300], &[[0.0], [1.0]], 1e-300).unwrap_err();
    assert!(
        matches!(e, TrajectoryError::OutOfFloatRange { name: "segment velocity", at, .. } if at == Location::point(1, 0)),
        "{e:?}"
    );
    assert!(
        e.to_string().contains("cannot be represented in f64"),
        "{e}"
    );
}

/// From limits, starting late: the segments' velocities come from their durations, not from
/// differences of the corner times (which hold a 5e-10 s rounding at t0 = 3e6 s, large against
/// millimetre segments of a few milliseconds), so every joint stays within its limits to
/// rounding at any start time. From the corner times, the blends had exceeded amax by 1.7e-8
/// of it in a sweep of 30,000 such paths.
#[test]
fn blends_from_limits_keep_the_limits_when_starting_late() {
    let points = [
        [0.0, 0.0, 0.0],
        [1e-3, 2e-3, 5e-4],
        [5e-4, 3e-3, 1e-3],
        [2e-3, 1e-3, 0.0],
        [2.5e-3, 1.5e-3, 7e-4],
    ];
    let (vmax, amax) = ([0.53, 0.71, 0.37], [1.13, 2.29, 0.71]);
    let mut worst: f64 = 0.0;
    for t0 in [0.0, -42.0, 1e3, 1e5, 3e6, 1e8] {
        let path = BlendedSegments::from_limits(t0, &points, &vmax, &amax).unwrap();
        let (a, b) = (path.start_time(), path.end_time());
        let mut out = vec![Setpoint::rest(0.0); 3];
        for i in 0..=20_000 {
            let t = a + (b - a) * f64::from(i) / 20_000.0;
            path.eval_into(t, &mut out).unwrap();
            for (j, s) in out.iter().enumerate() {
                worst = worst.max(s.qd.abs() / vmax[j]).max(s.qdd.abs() / amax[j]);
            }
        }
        assert!(
            worst <= 1.0 + 1e-12,
            "t0 {t0}: a limit exceeded by {:e} of it",
            worst - 1.0
        );
    }
}
