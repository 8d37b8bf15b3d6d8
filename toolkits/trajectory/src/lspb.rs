//! Linear segment with parabolic blends (section 6.5.1.2, with the erratum for the third segment).

use super::{
    Interval, Location, Profile, Setpoint, TrajectoryError, abs, displacement, finite, positive,
    sqrt,
};

/// Rest-to-rest LSPB ("trapezoidal velocity") profile: constant acceleration `α` for the blend
/// time `tb`, constant velocity `V`, constant deceleration `-α` for the last `tb`.
///
/// With `τ = t - t0` and `T = tf - t0` (the text takes `t0 = 0`):
/// - `q = q0 + α τ²/2` for `0 ≤ τ ≤ tb`,
/// - `q = (q0 + qf - V T)/2 + V τ` for `tb < τ < T - tb`,
/// - `q = qf - α (T - τ)²/2` for `T - tb ≤ τ ≤ T` (the text's third segment with the erratum:
///   `qf - α T²/2 + α T τ - α τ²/2`).
///
/// `V` and `α` carry the sign of the move `qf - q0`. Position and velocity are continuous; the
/// acceleration jumps at `t0`, `t0 + tb`, `tf - tb` and `tf`. When `tb = T/2` the linear segment
/// vanishes and the profile is bang-bang. A zero move is the constant profile (`V = α = tb = 0`).
///
/// Also built by the minimum-time constructors [`Lspb::bang_bang`] and
/// [`Lspb::velocity_limited`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lspb {
    interval: Interval,
    q0: f64,
    qf: f64,
    /// Signed cruise velocity `V`.
    velocity: f64,
    /// Signed blend acceleration `α`.
    acceleration: f64,
    /// Blend time `tb`, in `[0, T/2]`.
    blend_time: f64,
}

/// How far, relative to it, a bound computed from the duration `T = tf − t0` here may lie
/// from the same bound a caller computed with its own duration `T'` (with `tf = t0 + T'`
/// rounded): `T` and `T'` differ by the rounding of `tf`, up to half an ulp of `|tf|`, which
/// is large against `T` when the move starts late (`t0 = 1e4` s, `T = 0.5` s: 4e-12), plus a
/// few roundings of the bound's own arithmetic.
fn duration_rounding(interval: Interval) -> f64 {
    let Interval { t0, tf, duration } = interval;
    8.0 * f64::EPSILON * (1.0 + (abs(t0) + abs(tf)) / duration)
}

impl Lspb {
    /// The LSPB from rest at `q0` (time `t0`) to rest at `qf` (time `tf`) with cruise velocity `v`.
    ///
    /// `v` must lie in `((qf - q0)/T, 2 (qf - q0)/T]` for a positive move and in
    /// `[2 (qf - q0)/T, (qf - q0)/T)` for a negative one (`T = tf - t0`), else the blends cannot fit;
    /// for a zero move only `v = 0` is accepted (a `v` within the rounding of `tf - t0` of the
    /// bang-bang end `2 (qf - q0)/T` is taken as it). The blend time is
    /// `tb = (q0 - qf + V T)/V` and the acceleration `α = V/tb`.
    pub fn with_velocity(
        t0: f64,
        tf: f64,
        q0: f64,
        qf: f64,
        v: f64,
    ) -> Result<Self, TrajectoryError> {
        let interval = Interval::new(t0, tf)?;
        let duration = interval.duration();
        let dq = displacement(q0, qf)?;
        finite("V", v)?;
        let average = dq / duration;
        let max = 2.0 * average;
        // The bang-bang end 2Δ/T as the caller computes it, with its own duration, lies
        // within `duration_rounding` of the one here, and is taken as that.
        let near_max = abs(v - max) <= duration_rounding(interval) * abs(max);
        let v = if near_max { max } else { v };
        // Written so that it is the same test for either sign of the move.
        let inside = if dq > 0.0 {
            v > average && v <= max
        } else if dq < 0.0 {
            v < average && v >= max
        } else {
            v == 0.0
        };
        if !inside {
            return Err(TrajectoryError::LspbVelocityOutOfRange {
                v,
                exclusive_bound: average,
                inclusive_bound: max,
                at: Location::NONE,
            });
        }
        if dq == 0.0 {
            return Ok(Self::stationary(interval, q0));
        }
        // tb = (V T - Δ)/V; rounding may push it a hair past T/2 at V = 2Δ/T.
        let blend_time = ((v * duration - dq) / v).min(0.5 * duration);
        let acceleration = v / blend_time;
        if !(blend_time > 0.0 && acceleration.is_finite()) {
            // V lies within rounding of the excluded bound (qf - q0)/T.
            return Err(out_of_float_range(blend_time));
        }
        Ok(Self {
            interval,
            q0,
            qf,
            velocity: v,
            acceleration,
            blend_time,
        })
    }

    /// The LSPB from rest at `q0` (time `t0`) to rest at `qf` (time `tf`) whose blends use the
    /// acceleration magnitude `alpha`.
    ///
    /// `alpha` must be at least `4 |qf - q0| / T²` (the bang-bang acceleration for this
    /// duration; computed by the caller from its own duration, within the rounding of
    /// `tf - t0`, it is taken as that bound); the blend time is then
    /// `tb = T/2 - sqrt(α² T² - 4 α |qf - q0|) / (2 α)`.
    pub fn with_acceleration(
        t0: f64,
        tf: f64,
        q0: f64,
        qf: f64,
        alpha: f64,
    ) -> Result<Self, TrajectoryError> {
        Self::with_acceleration_over(Interval::new(t0, tf)?, q0, qf, alpha)
    }

    /// [`with_acceleration`](Self::with_acceleration) over `interval`, whose duration may be
    /// given exactly with `tf = t0 + duration` rounded ([`Interval::timed`]): for a joint
    /// synchronized to another's duration, which `tf - t0` gives only to the rounding of `tf`.
    pub(crate) fn with_acceleration_over(
        interval: Interval,
        q0: f64,
        qf: f64,
        alpha: f64,
    ) -> Result<Self, TrajectoryError> {
        let duration = interval.duration();
        let dq = displacement(q0, qf)?;
        positive("alpha", alpha)?;
        if dq == 0.0 {
            return Ok(Self::stationary(interval, q0));
        }
        let distance = abs(dq);
        let min = 4.0 * distance / (duration * duration);
        // Accept the bang-bang acceleration computed by the caller with its own rounding (of
        // the move and of the duration), and take it as the one here.
        if alpha < min * (1.0 - duration_rounding(interval)) {
            return Err(TrajectoryError::LspbAccelerationTooSmall {
                alpha,
                min,
                at: Location::NONE,
            });
        }
        let alpha = alpha.max(min);
        let slack = (alpha * duration * duration - 4.0 * distance).max(0.0);
        // tb = T/2 - sqrt(α(αT² - 4|Δ|))/(2α), rationalized so that a large α (short blends) does
        // not lose tb to cancellation; sqrt(α) sqrt(slack) cannot overflow where α · slack could.
        let blend_time =
            (2.0 * distance / (alpha * duration + sqrt(alpha) * sqrt(slack))).min(0.5 * duration);
        if blend_time <= 0.0 {
            // α is so large, or the move so small, that the blends are shorter than f64 resolves.
            return Err(out_of_float_range(blend_time));
        }
        let sign = if dq > 0.0 { 1.0 } else { -1.0 };
        Ok(Self {
            interval,
            q0,
            qf,
            velocity: sign * alpha * blend_time,
            acceleration: sign * alpha,
            blend_time,
        })
    }

    /// The LSPB over `interval` (of positive duration) with blend time `blend_time` in
    /// `(0, duration/2]`: the shape shared by the minimum-time profiles. `dq = qf - q0` must
    /// be non-zero.
    pub(crate) fn from_blend_time(interval: Interval, q0: f64, qf: f64, blend_time: f64) -> Self {
        let velocity = (qf - q0) / (interval.duration() - blend_time);
        Self {
            interval,
            q0,
            qf,
            velocity,
            acceleration: velocity / blend_time,
            blend_time,
        }
    }

    /// The same profile with explicitly given signed velocity and acceleration (used where these
    /// are limits that must be reproduced exactly rather than recomputed with rounding).
    pub(crate) fn from_parts(
        interval: Interval,
        q0: f64,
        qf: f64,
        blend_time: f64,
        velocity: f64,
        acceleration: f64,
    ) -> Self {
        Self {
            interval,
            q0,
            qf,
            velocity,
            acceleration,
            blend_time,
        }
    }

    /// Holding `q` over `interval` (a zero move; its duration may be 0 for minimum-time
    /// profiles).
    pub(crate) fn stationary(interval: Interval, q: f64) -> Self {
        Self {
            interval,
            q0: q,
            qf: q,
            velocity: 0.0,
            acceleration: 0.0,
            blend_time: 0.0,
        }
    }

    /// The signed cruise velocity `V` (the peak velocity).
    pub fn velocity(&self) -> f64 {
        self.velocity
    }

    /// The signed blend acceleration `α` (`-α` while decelerating).
    pub fn acceleration(&self) -> f64 {
        self.acceleration
    }

    /// The blend time `tb`, in `[0, T/2]`.
    pub fn blend_time(&self) -> f64 {
        self.blend_time
    }
}

impl Profile for Lspb {
    fn interval(&self) -> Interval {
        self.interval
    }

    fn eval(&self, t: f64) -> Setpoint {
        let Interval { t0, tf, duration } = self.interval;
        if t < t0 {
            return Setpoint::rest(self.q0);
        }
        if t > tf {
            return Setpoint::rest(self.qf);
        }
        if t.is_nan() {
            // Else it would fall through to the last blend, whose acceleration is finite.
            return Setpoint::NAN;
        }
        // Time since the start and time to go, each measured from its own end so that both
        // boundary setpoints are exact even when tf = t0 + T was rounded.
        let tau = t - t0;
        let to_go = tf - t;
        let (alpha, tb) = (self.acceleration, self.blend_time);
        if tau <= tb {
            Setpoint {
                q: self.q0 + 0.5 * alpha * tau * tau,
                qd: alpha * tau,
                qdd: alpha,
            }
        } else if to_go > tb {
            let q = 0.5 * (self.q0 + self.qf - self.velocity * duration) + self.velocity * tau;
            Setpoint {
                q,
                qd: self.velocity,
                qdd: 0.0,
            }
        } else {
            Setpoint {
                q: self.qf - 0.5 * alpha * to_go * to_go,
                qd: alpha * to_go,
                qdd: -alpha,
            }
        }
    }
}

/// The error for a blend time that rounds to zero although the move is not zero.
fn out_of_float_range(blend_time: f64) -> TrajectoryError {
    TrajectoryError::OutOfFloatRange {
        name: "LSPB blend time tb",
        value: blend_time,
        at: Location::NONE,
    }
}
