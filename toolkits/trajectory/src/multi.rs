//! Many joints moving together: one profile per joint over one common time interval.

use super::{
    Cubic, FourierSeries, Interval, Location, Lspb, MultiProfile, Profile, Quintic, Setpoint,
    TrajectoryError, bang_bang_duration, finite, velocity_limited_duration,
};

/// One profile per joint (`N` joints), all starting and ending at the same times.
///
/// For profiles whose duration is given (cubic, quintic, LSPB) every joint simply gets the same
/// `[t0, tf]`. For the minimum-time profiles the common duration is the slowest joint's minimum
/// duration, and the faster joints are slowed down to it (see [`Synchronized::bang_bang`] and
/// [`Synchronized::velocity_limited`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Synchronized<P, const N: usize> {
    joints: [P; N],
}

/// Builds `[P; N]` from a fallible per-joint constructor, returning the first joint's error
/// (attributed to that joint).
fn try_joints<P, const N: usize>(
    mut build: impl FnMut(usize) -> Result<P, TrajectoryError>,
) -> Result<[P; N], TrajectoryError> {
    let mut first_error = None;
    let slots: [Option<P>; N] = core::array::from_fn(|j| {
        if first_error.is_some() {
            return None;
        }
        match build(j) {
            Ok(profile) => Some(profile),
            Err(error) => {
                first_error = Some(error.at_joint(j));
                None
            }
        }
    });
    if let Some(error) = first_error {
        return Err(error);
    }
    // from_fn visited every joint and none failed, so every slot is filled.
    Ok(slots.map(|slot| slot.expect("every joint was built")))
}

/// The slowest joint's duration (`durations` never empty: `N > 0` is checked by callers).
fn slowest(durations: &[f64]) -> f64 {
    durations.iter().copied().fold(0.0, f64::max)
}

impl<P: Profile, const N: usize> Synchronized<P, N> {
    /// Groups per-joint profiles that already share one start and one end time.
    pub fn new(joints: [P; N]) -> Result<Self, TrajectoryError> {
        let first = joints.first().ok_or(TrajectoryError::NoJoints)?;
        let (expected_t0, expected_tf) = (first.start_time(), first.end_time());
        for (joint, profile) in joints.iter().enumerate() {
            let (t0, tf) = (profile.start_time(), profile.end_time());
            if t0 != expected_t0 || tf != expected_tf {
                return Err(TrajectoryError::MismatchedTimes {
                    joint,
                    t0,
                    tf,
                    expected_t0,
                    expected_tf,
                });
            }
        }
        Ok(Self { joints })
    }

    /// The per-joint profiles.
    pub fn joints(&self) -> &[P; N] {
        &self.joints
    }

    /// Every joint's state at time `t`.
    pub fn eval(&self, t: f64) -> [Setpoint; N] {
        core::array::from_fn(|j| self.joints[j].eval(t))
    }
}

impl<P: Profile, const N: usize> MultiProfile for Synchronized<P, N> {
    fn dof(&self) -> usize {
        N
    }

    fn interval(&self) -> Interval {
        self.joints
            .first()
            .map_or(Interval::default(), Profile::interval)
    }

    fn eval_into(&self, t: f64, out: &mut [Setpoint]) -> Result<(), TrajectoryError> {
        if out.len() != N {
            return Err(TrajectoryError::LengthMismatch {
                name: "out",
                expected: N,
                found: out.len(),
                at: Location::NONE,
            });
        }
        for (state, profile) in out.iter_mut().zip(&self.joints) {
            *state = profile.eval(t);
        }
        Ok(())
    }
}

impl<const N: usize> Synchronized<Cubic, N> {
    /// One [`Cubic`] per joint on `[t0, tf]`, from `(q0[j], v0[j])` to `(qf[j], vf[j])`.
    pub fn cubic(
        t0: f64,
        tf: f64,
        q0: &[f64; N],
        v0: &[f64; N],
        qf: &[f64; N],
        vf: &[f64; N],
    ) -> Result<Self, TrajectoryError> {
        let joints = try_joints(|j| Cubic::new(t0, tf, q0[j], v0[j], qf[j], vf[j]))?;
        Self::new(joints)
    }
}

impl<const N: usize, const L: usize> Synchronized<FourierSeries<L>, N> {
    /// One [`FourierSeries`] per joint, `cycles` periods of `period` from `t0`: joint `j`
    /// about `q0[j]` with coefficients `a[j]` and `b[j]`.
    pub fn fourier(
        t0: f64,
        period: f64,
        cycles: u32,
        q0: &[f64; N],
        a: &[[f64; L]; N],
        b: &[[f64; L]; N],
    ) -> Result<Self, TrajectoryError> {
        let joints = try_joints(|j| FourierSeries::new(t0, period, cycles, q0[j], a[j], b[j]))?;
        Self::new(joints)
    }
}

impl<const N: usize> Synchronized<Quintic, N> {
    /// One [`Quintic`] per joint on `[t0, tf]`, from `start[j]` to `end[j]`.
    pub fn quintic(
        t0: f64,
        tf: f64,
        start: &[Setpoint; N],
        end: &[Setpoint; N],
    ) -> Result<Self, TrajectoryError> {
        let joints = try_joints(|j| Quintic::new(t0, tf, start[j], end[j]))?;
        Self::new(joints)
    }

    /// One rest-to-rest [`Quintic`] per joint on `[t0, tf]` (Robotics Toolbox's `jtraj`).
    pub fn quintic_rest_to_rest(
        t0: f64,
        tf: f64,
        q0: &[f64; N],
        qf: &[f64; N],
    ) -> Result<Self, TrajectoryError> {
        let joints = try_joints(|j| Quintic::rest_to_rest(t0, tf, q0[j], qf[j]))?;
        Self::new(joints)
    }
}

impl<const N: usize> Synchronized<Lspb, N> {
    /// One [`Lspb::with_velocity`] per joint on `[t0, tf]` with cruise velocity `v[j]`.
    pub fn lspb_velocity(
        t0: f64,
        tf: f64,
        q0: &[f64; N],
        qf: &[f64; N],
        v: &[f64; N],
    ) -> Result<Self, TrajectoryError> {
        let joints = try_joints(|j| Lspb::with_velocity(t0, tf, q0[j], qf[j], v[j]))?;
        Self::new(joints)
    }

    /// One [`Lspb::with_acceleration`] per joint on `[t0, tf]` with blend acceleration `alpha[j]`.
    pub fn lspb_acceleration(
        t0: f64,
        tf: f64,
        q0: &[f64; N],
        qf: &[f64; N],
        alpha: &[f64; N],
    ) -> Result<Self, TrajectoryError> {
        let joints = try_joints(|j| Lspb::with_acceleration(t0, tf, q0[j], qf[j], alpha[j]))?;
        Self::new(joints)
    }

    /// Bang-bang for every joint, synchronized to the slowest joint's minimum duration
    /// `T = max_j 2 sqrt(|qf[j] - q0[j]| / amax[j])`.
    ///
    /// Every joint switches at `T/2` and uses the acceleration `4 |qf[j] - q0[j]| / T² ≤ amax[j]`
    /// (the slowest joint uses exactly `amax`), so all joints follow the same normalized time
    /// law: the motion is a straight line in joint space.
    pub fn bang_bang(
        t0: f64,
        q0: &[f64; N],
        qf: &[f64; N],
        amax: &[f64; N],
    ) -> Result<Self, TrajectoryError> {
        finite("t0", t0)?;
        let durations: [f64; N] = try_joints(|j| bang_bang_duration(q0[j], qf[j], amax[j]))?;
        if N == 0 {
            return Err(TrajectoryError::NoJoints);
        }
        let duration = slowest(&durations);
        let interval = Interval::timed(t0, finite("t0 + duration", t0 + duration)?, duration);
        let joints = try_joints(|j| {
            if durations[j] == duration {
                // The slowest joint keeps its own profile: exactly amax, no re-rounding.
                Lspb::bang_bang(t0, q0[j], qf[j], amax[j])
            } else if q0[j] == qf[j] {
                Ok(Lspb::stationary(interval, q0[j]))
            } else {
                Ok(Lspb::from_blend_time(
                    interval,
                    q0[j],
                    qf[j],
                    0.5 * duration,
                ))
            }
        })?;
        Self::new(joints)
    }

    /// The velocity-limited minimum-time profile for every joint, synchronized to the slowest
    /// joint's minimum duration `T = max_j velocity_limited_duration(q0[j], qf[j], vmax[j], amax[j])`.
    ///
    /// The slowest joint runs its own minimum-time profile; every other joint runs the LSPB of
    /// duration `T` whose blends use its full `amax[j]` (`Lspb::with_acceleration`), which lowers its
    /// cruise velocity below its own minimum-time peak, so both of its limits hold: to
    /// rounding, which the blend time's square root can raise to a few 1e-9 of `vmax[j]` where
    /// a joint's move lies at the boundary of the two regimes (`amax·|Δ| ≈ vmax²`) and its own
    /// minimum duration within rounding of `T` (4 of 400,000 profiles built to hit that case).
    pub fn velocity_limited(
        t0: f64,
        q0: &[f64; N],
        qf: &[f64; N],
        vmax: &[f64; N],
        amax: &[f64; N],
    ) -> Result<Self, TrajectoryError> {
        finite("t0", t0)?;
        let durations: [f64; N] =
            try_joints(|j| velocity_limited_duration(q0[j], qf[j], vmax[j], amax[j]))?;
        if N == 0 {
            return Err(TrajectoryError::NoJoints);
        }
        let duration = slowest(&durations);
        let interval = Interval::timed(t0, finite("t0 + duration", t0 + duration)?, duration);
        let joints = try_joints(|j| {
            if durations[j] == duration {
                Lspb::velocity_limited(t0, q0[j], qf[j], vmax[j], amax[j])
            } else if q0[j] == qf[j] {
                Ok(Lspb::stationary(interval, q0[j]))
            } else {
                // Over the slowest joint's duration T itself, ending at its end time t0 + T
                // (end − t0 is T only to the rounding of the end, which the square root of
                // the blend time can amplify past a limit where a joint's move is nearly the
                // slowest one's).
                Lspb::with_acceleration_over(interval, q0[j], qf[j], amax[j])
            }
        })?;
        Self::new(joints)
    }
}
