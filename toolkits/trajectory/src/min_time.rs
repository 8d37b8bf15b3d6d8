//! Minimum-time rest-to-rest profiles (section 6.5.1.3): bang-bang under an acceleration limit,
//! and its velocity-limited variant, the trapezoid.

use super::{Interval, Lspb, TrajectoryError, abs, displacement, finite, positive, sqrt};

/// The minimum duration of a rest-to-rest move from `q0` to `qf` with `|q̈| ≤ amax`:
/// `2 sqrt(|qf - q0| / amax)` (the text's `ts = sqrt((qf - q0)/α)`, twice).
pub fn bang_bang_duration(q0: f64, qf: f64, amax: f64) -> Result<f64, TrajectoryError> {
    let dq = displacement(q0, qf)?;
    positive("amax", amax)?;
    finite("duration", 2.0 * sqrt(abs(dq) / amax))
}

/// The minimum duration of a rest-to-rest move from `q0` to `qf` with `|q̇| ≤ vmax` and
/// `|q̈| ≤ amax`: the bang-bang duration while its peak velocity `sqrt(amax |qf - q0|)` stays within
/// `vmax`, else the trapezoid's `|qf - q0| / vmax + vmax / amax`.
pub fn velocity_limited_duration(
    q0: f64,
    qf: f64,
    vmax: f64,
    amax: f64,
) -> Result<f64, TrajectoryError> {
    let dq = displacement(q0, qf)?;
    positive("vmax", vmax)?;
    positive("amax", amax)?;
    let distance = abs(dq);
    let duration = if amax * distance <= vmax * vmax {
        2.0 * sqrt(distance / amax)
    } else {
        distance / vmax + vmax / amax
    };
    finite("duration", duration)
}

impl Lspb {
    /// The fastest rest-to-rest move from `q0` (at `t0`) to `qf` with `|q̈| ≤ amax`: accelerate at
    /// `amax` until the switching time `ts = sqrt(|qf - q0| / amax)`, then decelerate at `amax`
    /// (the LSPB with `tb = T/2`). Its duration is [`bang_bang_duration`]; a zero move gives a
    /// profile of duration 0.
    pub fn bang_bang(t0: f64, q0: f64, qf: f64, amax: f64) -> Result<Self, TrajectoryError> {
        finite("t0", t0)?;
        let duration = bang_bang_duration(q0, qf, amax)?;
        let interval = Interval::timed(t0, finite("t0 + duration", t0 + duration)?, duration);
        let dq = qf - q0;
        if dq == 0.0 {
            return Ok(Self::stationary(interval, q0));
        }
        let sign = if dq > 0.0 { 1.0 } else { -1.0 };
        let switch = 0.5 * duration;
        Ok(Self::from_parts(
            interval,
            q0,
            qf,
            switch,
            sign * amax * switch,
            sign * amax,
        ))
    }

    /// The fastest rest-to-rest move from `q0` (at `t0`) to `qf` with `|q̇| ≤ vmax` and
    /// `|q̈| ≤ amax`: bang-bang if its peak velocity stays within `vmax`, otherwise the trapezoid
    /// that accelerates at `amax` for `tb = vmax / amax`, cruises at `vmax` and decelerates at
    /// `amax`. Its duration is [`velocity_limited_duration`].
    pub fn velocity_limited(
        t0: f64,
        q0: f64,
        qf: f64,
        vmax: f64,
        amax: f64,
    ) -> Result<Self, TrajectoryError> {
        finite("t0", t0)?;
        let duration = velocity_limited_duration(q0, qf, vmax, amax)?;
        let interval = Interval::timed(t0, finite("t0 + duration", t0 + duration)?, duration);
        let dq = qf - q0;
        if amax * abs(dq) <= vmax * vmax {
            return Self::bang_bang(t0, q0, qf, amax);
        }
        let sign = if dq > 0.0 { 1.0 } else { -1.0 };
        Ok(Self::from_parts(
            interval,
            q0,
            qf,
            vmax / amax,
            sign * vmax,
            sign * amax,
        ))
    }
}
