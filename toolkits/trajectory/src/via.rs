//! Trajectories through via points (section 6.5.2): a cubic spline with continuous velocity and
//! acceleration, and linear segments with parabolic blends (Robotics Toolbox's `mstraj`).
//!
//! Both store their knots on the heap, so they need the `std` feature.

use super::{
    Interval, Location, MultiProfile, Profile, Setpoint, TrajectoryError, abs, finite, positive,
    sqrt,
};

/// Checks the via points and returns the number of joints: at least two points, all finite and
/// of one common, non-zero length.
fn check_points<R: AsRef<[f64]>>(points: &[R]) -> Result<usize, TrajectoryError> {
    if points.len() < 2 {
        return Err(TrajectoryError::TooFewPoints {
            found: points.len(),
        });
    }
    let dof = points[0].as_ref().len();
    if dof == 0 {
        return Err(TrajectoryError::NoJoints);
    }
    for (i, point) in points.iter().enumerate() {
        let point = point.as_ref();
        if point.len() != dof {
            return Err(TrajectoryError::LengthMismatch {
                name: "via point",
                expected: dof,
                found: point.len(),
                at: Location {
                    joint: None,
                    point: Some(i),
                },
            });
        }
        for (j, &q) in point.iter().enumerate() {
            if !q.is_finite() {
                return Err(TrajectoryError::NonFinite {
                    name: "q",
                    value: q,
                    at: Location::point(i, j),
                });
            }
        }
    }
    Ok(dof)
}

/// Checks that there is one finite time per point and that the times increase strictly.
fn check_times(times: &[f64], points: usize) -> Result<(), TrajectoryError> {
    if times.len() != points {
        return Err(TrajectoryError::LengthMismatch {
            name: "times",
            expected: points,
            found: times.len(),
            at: Location::NONE,
        });
    }
    for (i, &t) in times.iter().enumerate() {
        if !t.is_finite() {
            return Err(TrajectoryError::NonFinite {
                name: "time",
                value: t,
                at: Location {
                    joint: None,
                    point: Some(i),
                },
            });
        }
        if i > 0 {
            let previous = times[i - 1];
            if t <= previous {
                return Err(TrajectoryError::NonIncreasingTimes {
                    index: i,
                    previous,
                    value: t,
                });
            }
            finite("time step", t - previous)?;
        }
    }
    Ok(())
}

/// Checks a per-joint slice of positive limits (`name` is `"vmax"` or `"amax"`).
fn check_limits(name: &'static str, limits: &[f64], dof: usize) -> Result<(), TrajectoryError> {
    if limits.len() != dof {
        return Err(TrajectoryError::LengthMismatch {
            name,
            expected: dof,
            found: limits.len(),
            at: Location::NONE,
        });
    }
    for (j, &limit) in limits.iter().enumerate() {
        positive(name, limit).map_err(|e| e.at_joint(j))?;
    }
    Ok(())
}

/// Index of the segment `[times[k], times[k + 1]]` that contains `t` (clamped to the first and
/// last segment).
fn segment_index(times: &[f64], t: f64) -> usize {
    let after = times.partition_point(|&knot| knot <= t);
    after.saturating_sub(1).min(times.len() - 2)
}

/// The positive real roots of `a x² + b x + c` (`a > 0`), computed without cancellation.
fn positive_roots(a: f64, b: f64, c: f64) -> [Option<f64>; 2] {
    let disc = b * b - 4.0 * a * c;
    if disc.is_nan() || disc < 0.0 {
        return [None, None];
    }
    let q = -0.5 * (b + if b >= 0.0 { sqrt(disc) } else { -sqrt(disc) });
    let first = q / a;
    let second = if q != 0.0 { c / q } else { 0.0 };
    [first, second].map(|x| (x > 0.0 && x.is_finite()).then_some(x))
}

/// The smallest blend time `tacc > 0` such that, with segment `k` lasting `max(cruise[k], tacc)`,
/// every blend changes every joint's velocity by at most `amax[j] · tacc`; `None` if nothing moves.
///
/// `moves` holds `cruise.len()` rows of per-joint displacements. The condition is not monotone in
/// `tacc` (stretching one segment can enlarge a velocity change), so instead of iterating it is
/// solved piecewise: between consecutive cruise durations every segment velocity is either
/// constant or `Δq / tacc`, so each blend's velocity change is `α + β / tacc` and its constraint
/// `|α tacc + β| ≤ amax tacc²` switches only at roots of two quadratics. The smallest feasible
/// `tacc` is therefore a piece's left end or one of those roots: the candidates are checked in
/// increasing order.
fn minimal_blend_time(cruise: &[f64], moves: &[f64], amax: &[f64]) -> Option<f64> {
    let (m, dof) = (cruise.len(), amax.len());
    // Velocity of segment k (1..=m; 0 and m + 1 are the rests before and after) at blend time tacc.
    let velocity = |k: usize, j: usize, tacc: f64| {
        if k == 0 || k > m {
            return 0.0;
        }
        let d = cruise[k - 1].max(tacc);
        if d > 0.0 {
            moves[(k - 1) * dof + j] / d
        } else {
            0.0
        }
    };
    // Relative slack so that a root, where one constraint holds with equality, is accepted.
    let feasible = |tacc: f64| {
        (0..=m).all(|k| {
            (0..dof).all(|j| {
                abs(velocity(k + 1, j, tacc) - velocity(k, j, tacc))
                    <= amax[j] * tacc * (1.0 + 1e-12)
            })
        })
    };
    let mut breaks: Vec<f64> = cruise.iter().copied().filter(|&c| c > 0.0).collect();
    breaks.sort_by(f64::total_cmp);
    breaks.dedup();
    let mut lower = 0.0;
    for piece in 0..=breaks.len() {
        let upper = breaks.get(piece).copied().unwrap_or(f64::INFINITY);
        // Segment k's velocity on this piece: (constant part, coefficient of 1/tacc).
        let parts = |k: usize, j: usize| {
            if k == 0 || k > m {
                (0.0, 0.0)
            } else if cruise[k - 1] >= upper {
                (moves[(k - 1) * dof + j] / cruise[k - 1], 0.0)
            } else {
                (0.0, moves[(k - 1) * dof + j])
            }
        };
        let mut candidates: Vec<f64> = Vec::new();
        if lower > 0.0 {
            candidates.push(lower);
        }
        for k in 0..=m {
            for (j, &a) in amax.iter().enumerate() {
                let ((c1, i1), (c0, i0)) = (parts(k + 1, j), parts(k, j));
                let (alpha, beta) = (c1 - c0, i1 - i0);
                for root in positive_roots(a, -alpha, -beta)
                    .into_iter()
                    .chain(positive_roots(a, alpha, beta))
                {
                    candidates.extend(root.filter(|&r| r >= lower && r < upper));
                }
            }
        }
        candidates.sort_by(f64::total_cmp);
        if let Some(tacc) = candidates.into_iter().find(|&t| feasible(t)) {
            return Some(tacc);
        }
        lower = upper;
    }
    None
}

/// A borrowed view of one joint of a multi-joint via-point trajectory, usable as a [`Profile`].
#[derive(Clone, Copy, Debug)]
pub struct JointView<'a, M> {
    path: &'a M,
    joint: usize,
}

impl<M> JointView<'_, M> {
    /// The joint index this view shows.
    pub fn joint(&self) -> usize {
        self.joint
    }
}

/// End conditions of a [`CubicSpline`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SplineEnds<'a> {
    /// Zero acceleration at both ends (the end velocities are whatever results).
    Natural,
    /// Zero velocity at both ends (clamped, starting and stopping at rest).
    AtRest,
    /// The given per-joint velocities at the start and the end (clamped).
    Clamped {
        /// Velocity of each joint at the first via time.
        start: &'a [f64],
        /// Velocity of each joint at the last via time.
        end: &'a [f64],
    },
}

/// A piecewise cubic through every via point at its time, with continuous position, velocity
/// and acceleration for every joint (the interpolating cubic spline).
///
/// Per segment `[t_k, t_{k+1}]` of length `h`, with `a = (t_{k+1} - t)/h`, `b = 1 - a` and the knot
/// accelerations `M_k`:
/// `q = a y_k + b y_{k+1} + ((a³ - a) M_k + (b³ - b) M_{k+1}) h²/6`; the `M_k` solve the tridiagonal
/// system that makes the velocity continuous, closed by the [`SplineEnds`].
#[derive(Clone, Debug, PartialEq)]
pub struct CubicSpline {
    dof: usize,
    times: Vec<f64>,
    /// Row-major `points × dof` positions.
    values: Vec<f64>,
    /// Row-major `points × dof` knot accelerations `M`.
    accelerations: Vec<f64>,
}

impl CubicSpline {
    /// The spline reaching `points[i]` (one position per joint) at `times[i]`.
    ///
    /// Needs at least two points, strictly increasing finite times, finite positions and, for
    /// [`SplineEnds::Clamped`], one finite velocity per joint at each end.
    pub fn new<R: AsRef<[f64]>>(
        times: &[f64],
        points: &[R],
        ends: SplineEnds<'_>,
    ) -> Result<Self, TrajectoryError> {
        let dof = check_points(points)?;
        let n = points.len();
        check_times(times, n)?;
        if let SplineEnds::Clamped { start, end } = ends {
            for (name, velocities) in [("start velocities", start), ("end velocities", end)] {
                if velocities.len() != dof {
                    return Err(TrajectoryError::LengthMismatch {
                        name,
                        expected: dof,
                        found: velocities.len(),
                        at: Location::NONE,
                    });
                }
                for (j, &v) in velocities.iter().enumerate() {
                    finite(name, v).map_err(|e| e.at_joint(j))?;
                }
            }
        }
        let clamped = !matches!(ends, SplineEnds::Natural);
        let values: Vec<f64> = points
            .iter()
            .flat_map(|p| p.as_ref().iter().copied())
            .collect();
        let steps: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
        // Finite points and times can still be too far apart, or too close in time, for the
        // segment's average velocity to be representable.
        for k in 1..n {
            for j in 0..dof {
                let v = (values[k * dof + j] - values[(k - 1) * dof + j]) / steps[k - 1];
                if !v.is_finite() {
                    return Err(TrajectoryError::OutOfFloatRange {
                        name: "segment velocity",
                        value: v,
                        at: Location::point(k, j),
                    });
                }
            }
        }

        // Tridiagonal matrix (sub, diag, sup), shared by all joints; the right-hand side is per joint.
        let mut sub = vec![0.0; n];
        let mut diag = vec![0.0; n];
        let mut sup = vec![0.0; n];
        if clamped {
            diag[0] = steps[0] / 3.0;
            sup[0] = steps[0] / 6.0;
            sub[n - 1] = steps[n - 2] / 6.0;
            diag[n - 1] = steps[n - 2] / 3.0;
        } else {
            diag[0] = 1.0;
            diag[n - 1] = 1.0;
        }
        for i in 1..n - 1 {
            sub[i] = steps[i - 1] / 6.0;
            diag[i] = (steps[i - 1] + steps[i]) / 3.0;
            sup[i] = steps[i] / 6.0;
        }
        // Thomas algorithm; the matrix is strictly diagonally dominant, so no pivoting is needed.
        let mut sup_reduced = vec![0.0; n];
        let mut pivot = vec![0.0; n];
        pivot[0] = diag[0];
        sup_reduced[0] = sup[0] / pivot[0];
        for i in 1..n {
            pivot[i] = diag[i] - sub[i] * sup_reduced[i - 1];
            sup_reduced[i] = sup[i] / pivot[i];
        }

        let mut accelerations = vec![0.0; n * dof];
        let mut rhs = vec![0.0; n];
        for j in 0..dof {
            let y = |i: usize| values[i * dof + j];
            let slope = |k: usize| (y(k + 1) - y(k)) / steps[k];
            for (i, r) in rhs.iter_mut().enumerate().take(n - 1).skip(1) {
                *r = slope(i) - slope(i - 1);
            }
            (rhs[0], rhs[n - 1]) = match ends {
                SplineEnds::Natural => (0.0, 0.0),
                SplineEnds::AtRest => (slope(0), -slope(n - 2)),
                SplineEnds::Clamped { start, end } => (slope(0) - start[j], end[j] - slope(n - 2)),
            };
            rhs[0] /= pivot[0];
            for i in 1..n {
                rhs[i] = (rhs[i] - sub[i] * rhs[i - 1]) / pivot[i];
            }
            for i in (0..n - 1).rev() {
                rhs[i] -= sup_reduced[i] * rhs[i + 1];
            }
            for (i, &m) in rhs.iter().enumerate() {
                accelerations[i * dof + j] =
                    finite("spline knot acceleration", m).map_err(|e| e.at_joint(j))?;
            }
        }
        Ok(Self {
            dof,
            times: times.to_vec(),
            values,
            accelerations,
        })
    }

    /// The via times.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// The acceleration of every joint at via point `i` (`None` if out of range).
    pub fn knot_accelerations(&self, i: usize) -> Option<&[f64]> {
        self.accelerations.get(i * self.dof..(i + 1) * self.dof)
    }

    /// Joint `joint` as a single-joint [`Profile`] (`None` if `joint >= dof`).
    pub fn joint(&self, joint: usize) -> Option<JointView<'_, Self>> {
        (joint < self.dof).then_some(JointView { path: self, joint })
    }

    /// The state of one joint (`joint < dof`) at time `t`.
    fn joint_setpoint(&self, t: f64, joint: usize) -> Setpoint {
        let dof = self.dof;
        let last = self.times.len() - 1;
        if t < self.times[0] {
            return Setpoint::rest(self.values[joint]);
        }
        if t > self.times[last] {
            return Setpoint::rest(self.values[last * dof + joint]);
        }
        let k = segment_index(&self.times, t);
        let h = self.times[k + 1] - self.times[k];
        let a = (self.times[k + 1] - t) / h;
        let b = (t - self.times[k]) / h;
        let (y0, y1) = (
            self.values[k * dof + joint],
            self.values[(k + 1) * dof + joint],
        );
        let (m0, m1) = (
            self.accelerations[k * dof + joint],
            self.accelerations[(k + 1) * dof + joint],
        );
        Setpoint {
            q: a * y0 + b * y1 + ((a * a * a - a) * m0 + (b * b * b - b) * m1) * h * h / 6.0,
            qd: (y1 - y0) / h + ((1.0 - 3.0 * a * a) * m0 + (3.0 * b * b - 1.0) * m1) * h / 6.0,
            qdd: a * m0 + b * m1,
        }
    }
}

/// Linear segments between via points joined by parabolic blends, like Robotics Toolbox's
/// `mstraj` (which blends with quintics instead).
///
/// The trajectory starts at rest at the first point at `t0` and stops at rest at the last point
/// at `tf`. In between, all joints move on straight lines (constant velocity) that would pass
/// through the via points at their corner times `τ_k`; around every corner a blend of duration
/// `tacc` (centred on `τ_k`) changes the velocity at constant acceleration from one segment's to
/// the next's. The first blend starts from rest at `t0` and the last one ends at rest at `tf`, so
/// the end corners are virtual: `τ_0 = t0 + tacc/2` and `τ_m = tf - tacc/2`. The interior via
/// points are therefore approached, not passed through: at `τ_k` the path is
/// `(v_{k+1} - v_k) tacc/8` away from via point `k` (the corner it cuts). With two points it is
/// exactly the [`Lspb`](super::Lspb) with blend time `tacc`.
///
/// Position and velocity are continuous; the acceleration is piecewise constant.
#[derive(Clone, Debug, PartialEq)]
pub struct BlendedSegments {
    dof: usize,
    /// The via times: `t0`, the interior corner times, `tf`.
    times: Vec<f64>,
    /// The corner times `τ_k` (the end ones shifted inwards by `tacc/2`).
    corners: Vec<f64>,
    blend_time: f64,
    /// Row-major `points × dof` via positions.
    values: Vec<f64>,
    /// Row-major `(points + 1) × dof` segment velocities; rows 0 and `points` are the rest
    /// "segments" before the start and after the end.
    velocities: Vec<f64>,
}

impl BlendedSegments {
    /// Linear segments through `points` with blends of duration `blend_time` (`tacc`), where
    /// `times[0]` is the start time, `times[m]` the end time and `times[k]` (`0 < k < m`) the
    /// corner time of via point `k` (when the two straight lines meeting there pass through it).
    ///
    /// The blends must not overlap: a segment `k` needs `times[k] - times[k-1] ≥ tacc`, plus
    /// `tacc/2` for each of its ends that is the first or last point.
    pub fn from_times<R: AsRef<[f64]>>(
        times: &[f64],
        points: &[R],
        blend_time: f64,
    ) -> Result<Self, TrajectoryError> {
        let dof = check_points(points)?;
        check_times(times, points.len())?;
        positive("tacc", blend_time)?;
        let m = points.len() - 1;
        for k in 1..=m {
            let available = times[k] - times[k - 1];
            let ends = [k == 1, k == m].iter().filter(|&&end| end).count() as f64;
            let needed = blend_time * (1.0 + 0.5 * ends);
            // Times computed as t[k-1] + needed may come out a rounding error short.
            let rounding = 4.0 * f64::EPSILON * (needed + abs(times[k]));
            if available < needed - rounding {
                return Err(TrajectoryError::BlendsOverlap {
                    segment: k,
                    available,
                    needed,
                });
            }
        }
        let half = 0.5 * blend_time;
        let mut corners = times.to_vec();
        corners[0] += half;
        corners[m] -= half;
        let spans = corners.windows(2).map(|c| c[1] - c[0]).collect();
        Self::build(dof, times.to_vec(), corners, spans, blend_time, points)
    }

    /// Linear segments through `points` starting at `t0`, timed by per-joint velocity limits
    /// `vmax` and acceleration limits `amax` (all positive).
    ///
    /// Every segment lasts as long as its slowest joint needs at `vmax` (so all joints move on a
    /// straight line and arrive together), but at least `tacc`; `tacc` is the smallest blend time
    /// for which every blend keeps every joint within `amax` (found exactly, see
    /// `minimal_blend_time`). For a path that never moves, `tacc = max_j vmax_j / amax_j`.
    pub fn from_limits<R: AsRef<[f64]>>(
        t0: f64,
        points: &[R],
        vmax: &[f64],
        amax: &[f64],
    ) -> Result<Self, TrajectoryError> {
        finite("t0", t0)?;
        let dof = check_points(points)?;
        check_limits("vmax", vmax, dof)?;
        check_limits("amax", amax, dof)?;
        let m = points.len() - 1;
        // Row k - 1 holds segment k's displacement.
        let moves: Vec<f64> = (1..=m)
            .flat_map(|k| (0..dof).map(move |j| points[k].as_ref()[j] - points[k - 1].as_ref()[j]))
            .collect();
        for &d in &moves {
            finite("via point difference", d)?;
        }
        // Duration of each segment at full speed of its slowest joint.
        let cruise: Vec<f64> = (0..m)
            .map(|k| {
                (0..dof)
                    .map(|j| abs(moves[k * dof + j]) / vmax[j])
                    .fold(0.0, f64::max)
            })
            .collect();
        for &d in &cruise {
            finite("segment duration", d)?;
        }
        let tacc = minimal_blend_time(&cruise, &moves, amax)
            .unwrap_or_else(|| (0..dof).map(|j| vmax[j] / amax[j]).fold(0.0, f64::max));
        finite("tacc", tacc)?;
        let half = 0.5 * tacc;
        // The segments' durations themselves set their velocities: differences of the corner
        // times hold them only to the rounding of those times, which a late start makes large
        // against a short segment (at t0 = 3e6 s, 5e-10 s: accelerations 1.7e-8 over amax).
        let spans: Vec<f64> = cruise.iter().map(|c| c.max(tacc)).collect();
        let mut corners = Vec::with_capacity(m + 1);
        corners.push(t0 + half);
        for k in 1..=m {
            corners.push(corners[k - 1] + spans[k - 1]);
        }
        let mut times = corners.clone();
        times[0] = t0;
        times[m] = corners[m] + half;
        finite("tf", times[m])?;
        Self::build(dof, times, corners, spans, tacc, points)
    }

    /// Stores the path (inputs already checked), after making sure that its velocities and
    /// accelerations are representable: absurdly short blends or segments (e.g. a 1e-300 s
    /// blend) are rejected rather than producing inf or NaN. `spans[k - 1]` is the time from
    /// corner `k - 1` to corner `k`, which sets segment `k`'s velocity.
    fn build<R: AsRef<[f64]>>(
        dof: usize,
        times: Vec<f64>,
        corners: Vec<f64>,
        spans: Vec<f64>,
        blend_time: f64,
        points: &[R],
    ) -> Result<Self, TrajectoryError> {
        let n = points.len();
        let values: Vec<f64> = points
            .iter()
            .flat_map(|p| p.as_ref().iter().copied())
            .collect();
        let mut velocities = vec![0.0; (n + 1) * dof];
        for (k, &span) in (1..n).zip(&spans) {
            for j in 0..dof {
                let v = (values[k * dof + j] - values[(k - 1) * dof + j]) / span;
                let change = (v - velocities[(k - 1) * dof + j]) / blend_time;
                if !(v.is_finite() && change.is_finite()) {
                    return Err(TrajectoryError::OutOfFloatRange {
                        name: "segment velocity",
                        value: v,
                        at: Location::point(k, j),
                    });
                }
                velocities[k * dof + j] = v;
            }
        }
        for j in 0..dof {
            let stop = velocities[(n - 1) * dof + j] / blend_time;
            if !stop.is_finite() {
                return Err(TrajectoryError::OutOfFloatRange {
                    name: "final blend acceleration",
                    value: stop,
                    at: Location::point(n - 1, j),
                });
            }
        }
        Ok(Self {
            dof,
            times,
            corners,
            blend_time,
            values,
            velocities,
        })
    }

    /// The via times: start time, interior corner times, end time.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// The blend duration `tacc`.
    pub fn blend_time(&self) -> f64 {
        self.blend_time
    }

    /// The constant velocity of every joint on segment `k` (from via point `k - 1` to `k`,
    /// `1 ≤ k ≤ m`); `None` otherwise.
    pub fn segment_velocity(&self, k: usize) -> Option<&[f64]> {
        if k == 0 || k >= self.times.len() {
            return None;
        }
        self.velocities.get(k * self.dof..(k + 1) * self.dof)
    }

    /// Joint `joint` as a single-joint [`Profile`] (`None` if `joint >= dof`).
    pub fn joint(&self, joint: usize) -> Option<JointView<'_, Self>> {
        (joint < self.dof).then_some(JointView { path: self, joint })
    }

    /// The state of one joint (`joint < dof`) at time `t`.
    fn joint_setpoint(&self, t: f64, joint: usize) -> Setpoint {
        let dof = self.dof;
        let m = self.corners.len() - 1;
        let point = |k: usize| self.values[k * dof + joint];
        let velocity = |k: usize| self.velocities[k * dof + joint];
        if t < self.times[0] {
            return Setpoint::rest(point(0));
        }
        if t > self.times[m] {
            return Setpoint::rest(point(m));
        }
        if t.is_nan() {
            // Else it would land in the first blend with a finite velocity.
            return Setpoint::NAN;
        }
        let half = 0.5 * self.blend_time;
        // The first blend that has not ended at t (the last one at t = tf).
        let k = self
            .corners
            .partition_point(|&corner| corner + half <= t)
            .min(m);
        let corner = self.corners[k];
        let s = t - corner;
        if k == 0 || s >= -half {
            // Blend around corner k from velocity v_k to v_{k+1}; anchored on the side of t so
            // that the end points (at rest) are reproduced exactly.
            let acceleration = (velocity(k + 1) - velocity(k)) / self.blend_time;
            if s <= 0.0 {
                // The first blend is measured from t0 itself, so that q̇(t0) = 0 exactly.
                let since = if k == 0 {
                    t - self.times[0]
                } else {
                    (s + half).max(0.0)
                };
                Setpoint {
                    q: point(k) + velocity(k) * s + 0.5 * acceleration * since * since,
                    qd: velocity(k) + acceleration * since,
                    qdd: acceleration,
                }
            } else {
                // The last blend is measured to tf itself, so that q̇(tf) = 0 exactly.
                let until = if k == m {
                    self.times[m] - t
                } else {
                    (half - s).max(0.0)
                };
                Setpoint {
                    q: point(k) + velocity(k + 1) * s + 0.5 * acceleration * until * until,
                    qd: velocity(k + 1) - acceleration * until,
                    qdd: acceleration,
                }
            }
        } else {
            // Linear segment k, through via point k at its corner time.
            Setpoint {
                q: point(k) + velocity(k) * s,
                qd: velocity(k),
                qdd: 0.0,
            }
        }
    }
}

/// What the via-point paths share: their knot times, their joints, and one joint's state at
/// a time. The multi-joint and single-joint profile interfaces follow from it, once.
trait ViaPath {
    fn joints(&self) -> usize;
    fn knot_times(&self) -> &[f64];
    fn eval_joint(&self, t: f64, joint: usize) -> Setpoint;
}

impl ViaPath for CubicSpline {
    fn joints(&self) -> usize {
        self.dof
    }
    fn knot_times(&self) -> &[f64] {
        &self.times
    }
    fn eval_joint(&self, t: f64, joint: usize) -> Setpoint {
        self.joint_setpoint(t, joint)
    }
}

impl ViaPath for BlendedSegments {
    fn joints(&self) -> usize {
        self.dof
    }
    fn knot_times(&self) -> &[f64] {
        &self.times
    }
    fn eval_joint(&self, t: f64, joint: usize) -> Setpoint {
        self.joint_setpoint(t, joint)
    }
}

impl<P: ViaPath> MultiProfile for P {
    fn dof(&self) -> usize {
        self.joints()
    }

    fn interval(&self) -> Interval {
        let times = self.knot_times();
        let (t0, tf) = (times[0], times[times.len() - 1]);
        Interval::timed(t0, tf, tf - t0)
    }

    fn eval_into(&self, t: f64, out: &mut [Setpoint]) -> Result<(), TrajectoryError> {
        if out.len() != self.joints() {
            return Err(TrajectoryError::LengthMismatch {
                name: "out",
                expected: self.joints(),
                found: out.len(),
                at: Location::NONE,
            });
        }
        for (joint, state) in out.iter_mut().enumerate() {
            *state = self.eval_joint(t, joint);
        }
        Ok(())
    }
}

impl<P: ViaPath> Profile for JointView<'_, P> {
    fn interval(&self) -> Interval {
        MultiProfile::interval(self.path)
    }

    fn eval(&self, t: f64) -> Setpoint {
        self.path.eval_joint(t, self.joint)
    }
}
