//! Sampling into caller buffers (no allocation) and into Vecs (issue 6, item 4).

use crate::support::allocations_during;
use dhgen::trajectory::{
    BlendedSegments, CubicSpline, Location, Lspb, MAX_SAMPLES, Profile, Quintic, Setpoint,
    SplineEnds, Synchronized, TrajectoryError, sample, sample_into, sample_multi,
    sample_multi_into, sample_times_into, uniform_time,
};

#[test]
fn the_counter_sees_allocations() {
    assert!(allocations_during(|| drop(std::hint::black_box(vec![1u8; 16]))) >= 1);
}

#[test]
fn sampling_into_buffers_does_not_allocate() {
    let quintic = Quintic::rest_to_rest(0.0, 2.0, 1.0, -1.0).unwrap();
    let lspb = Lspb::velocity_limited(0.5, 0.0, 3.0, 1.0, 2.0).unwrap();
    let sync = Synchronized::bang_bang(0.0, &[0.0, 1.0, 2.0], &[1.0, -1.0, 2.0], &[1.0, 2.0, 3.0])
        .unwrap();
    let points = [[0.0, 1.0], [1.0, 0.0], [3.0, 2.0], [2.0, 2.0]];
    let spline = CubicSpline::new(&[0.0, 1.0, 2.5, 3.0], &points, SplineEnds::AtRest).unwrap();
    let blends = BlendedSegments::from_limits(0.0, &points, &[1.0, 2.0], &[4.0, 4.0]).unwrap();
    let mut one = [Setpoint::default(); 50];
    let mut rows = [Setpoint::default(); 50 * 3];
    let mut rows2 = [Setpoint::default(); 25 * 2];
    let times = [0.0, 0.1, 1.7, 3.0];
    let mut at_times = [Setpoint::default(); 4];
    let count = allocations_during(|| {
        sample_into(&quintic, &mut one).unwrap();
        sample_into(&lspb, &mut one).unwrap();
        sample_into(&spline.joint(1).unwrap(), &mut one).unwrap();
        sample_into(&blends.joint(0).unwrap(), &mut one).unwrap();
        sample_times_into(&quintic, &times, &mut at_times).unwrap();
        sample_multi_into(&sync, &mut rows).unwrap();
        sample_multi_into(&spline, &mut rows2).unwrap();
        sample_multi_into(&blends, &mut rows2).unwrap();
        // Errors do not allocate either.
        assert!(sample_into(&quintic, &mut one[..1]).is_err());
        assert!(sample_multi_into(&sync, &mut rows[..4]).is_err());
    });
    assert_eq!(count, 0, "sampling into caller buffers allocated");
    // The last buffer holds the blended path: starts and ends at rest at its end points.
    assert_eq!(rows2[0], Setpoint::new(0.0, 0.0, rows2[0].qdd));
    assert_eq!(
        (rows2[48].q, rows2[48].qd, rows2[49].q, rows2[49].qd),
        (2.0, 0.0, 2.0, 0.0)
    );
}

#[test]
fn uniform_samples_span_the_interval_exactly() {
    let p = Quintic::rest_to_rest(0.1, 0.7, 0.0, 1.0).unwrap();
    let s = sample(&p, 7).unwrap();
    assert_eq!(s.times.len(), 7);
    assert_eq!((s.times[0], s.times[6]), (0.1, 0.7));
    for w in s.times.windows(2) {
        assert!(w[1] > w[0]);
    }
    for (t, state) in s.times.iter().zip(&s.setpoints) {
        assert_eq!(*state, p.eval(*t));
    }
    assert_eq!(s.setpoints[6], Setpoint::rest(1.0));
    let mut buffer = [Setpoint::default(); 7];
    sample_into(&p, &mut buffer).unwrap();
    assert_eq!(&buffer[..], &s.setpoints[..]);
    assert_eq!(uniform_time(0.1, 0.7, 7, 3), 0.1 + 0.6 * 0.5);
}

#[test]
fn multi_samples_are_row_major() {
    let sync = Synchronized::quintic_rest_to_rest(0.0, 1.0, &[0.0, 10.0], &[1.0, -10.0]).unwrap();
    let s = sample_multi(&sync, 5).unwrap();
    assert_eq!((s.dof, s.times.len(), s.setpoints.len()), (2, 5, 10));
    for (i, &t) in s.times.iter().enumerate() {
        assert_eq!(s.get(i, 0), Some(sync.joints()[0].eval(t)));
        assert_eq!(s.get(i, 1), Some(sync.joints()[1].eval(t)));
    }
    assert_eq!(s.get(5, 0), None);
    assert_eq!(s.get(0, 2), None);
    let joint1: Vec<(f64, Setpoint)> = s.joint(1).collect();
    assert_eq!(joint1.len(), 5);
    assert_eq!(joint1[4], (1.0, Setpoint::rest(-10.0)));
    assert_eq!(s.joint(2).count(), 0);
}

#[test]
fn too_few_samples_are_rejected() {
    let p = Quintic::rest_to_rest(0.0, 1.0, 0.0, 1.0).unwrap();
    for n in [0, 1] {
        let e = sample(&p, n).unwrap_err();
        assert_eq!(e, TrajectoryError::TooFewSamples { found: n });
        assert_eq!(
            e.to_string(),
            format!("uniform sampling needs at least two samples (t0 and tf), got {n}")
        );
        let mut buffer = vec![Setpoint::default(); n];
        assert_eq!(sample_into(&p, &mut buffer).unwrap_err(), e);
    }
    let sync = Synchronized::quintic_rest_to_rest(0.0, 1.0, &[0.0; 3], &[1.0; 3]).unwrap();
    assert_eq!(
        sample_multi(&sync, 1).unwrap_err(),
        TrajectoryError::TooFewSamples { found: 1 }
    );
    let mut rows = [Setpoint::default(); 3];
    assert_eq!(
        sample_multi_into(&sync, &mut rows).unwrap_err(),
        TrajectoryError::TooFewSamples { found: 1 }
    );
}

#[test]
fn buffer_lengths_are_checked() {
    let p = Quintic::rest_to_rest(0.0, 1.0, 0.0, 1.0).unwrap();
    let mut out = [Setpoint::default(); 2];
    let e = sample_times_into(&p, &[0.0, 0.5, 1.0], &mut out).unwrap_err();
    assert_eq!(
        e,
        TrajectoryError::LengthMismatch {
            name: "out",
            expected: 3,
            found: 2,
            at: Location::NONE
        }
    );
    let e = sample_times_into(&p, &[0.0, f64::NAN], &mut out).unwrap_err();
    assert!(
        matches!(e, TrajectoryError::NonFinite { name: "t", .. }),
        "{e:?}"
    );
    let sync = Synchronized::quintic_rest_to_rest(0.0, 1.0, &[0.0; 3], &[1.0; 3]).unwrap();
    let mut rows = [Setpoint::default(); 7];
    let e = sample_multi_into(&sync, &mut rows).unwrap_err();
    assert_eq!(
        e.to_string(),
        "out (whole rows of dof setpoints) has length 7, expected 9"
    );
}

#[test]
fn zero_duration_profiles_sample_their_only_state() {
    let p = Lspb::bang_bang(2.0, 1.5, 1.5, 3.0).unwrap();
    assert_eq!(
        (p.start_time(), p.end_time(), p.duration()),
        (2.0, 2.0, 0.0)
    );
    let s = sample(&p, 3).unwrap();
    assert_eq!(s.times, vec![2.0; 3]);
    assert_eq!(s.setpoints, vec![Setpoint::rest(1.5); 3]);
}

/// Requests too large to allocate are errors, not a wrapped `n · dof`, a capacity-overflow
/// panic or an aborted allocation.
#[test]
fn huge_sample_counts_are_errors() {
    let p = Quintic::rest_to_rest(0.0, 1.0, 0.0, 1.0).unwrap();
    let sync = Synchronized::quintic_rest_to_rest(0.0, 1.0, &[0.0; 2], &[1.0; 2]).unwrap();
    let too_many = |samples, dof| TrajectoryError::TooManySamples {
        samples,
        dof,
        max: MAX_SAMPLES,
    };
    assert_eq!(sample(&p, usize::MAX).unwrap_err(), too_many(usize::MAX, 1));
    assert_eq!(
        sample(&p, MAX_SAMPLES + 1).unwrap_err(),
        too_many(MAX_SAMPLES + 1, 1)
    );
    // n · dof wraps to 0 in usize.
    let n = usize::MAX / 2 + 1;
    assert_eq!(sample_multi(&sync, n).unwrap_err(), too_many(n, 2));
    // n within the limit, n · dof not.
    let n = MAX_SAMPLES / 2 + 1;
    assert_eq!(sample_multi(&sync, n).unwrap_err(), too_many(n, 2));
    let e = sample(&p, usize::MAX).unwrap_err().to_string();
    assert!(
        e.contains("at most 16777216 setpoints") && e.contains("sample_into"),
        "{e}"
    );
    // A huge row index does not wrap around to a row that exists.
    let s = sample_multi(&sync, 3).unwrap();
    assert_eq!(s.get(usize::MAX / 2 + 1, 0), None);
    assert_eq!(s.get(usize::MAX, 1), None);
    assert_eq!(s.get(2, 1), Some(Setpoint::rest(1.0)));
}
