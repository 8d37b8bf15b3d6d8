//! Quintic polynomial: position, velocity and acceleration given at both ends (section 6.5.1.1).

use super::{
    Interval, Profile, Setpoint, TrajectoryError, abs, displacement, finite, polynomial_in_range,
};

/// The quintic `q(t)` matching position, velocity and acceleration at `t0` and `tf`.
///
/// Position, velocity and acceleration are continuous, and with the default rest-to-rest ends
/// (zero velocity and acceleration) the acceleration does not jump at `t0` or `tf` either.
///
/// It is evaluated in quintic Hermite form in the normalized time `s = (t - t0)/(tf - t0)`, which
/// reproduces all six boundary values exactly at `s = 0` and `s = 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quintic {
    interval: Interval,
    start: Setpoint,
    end: Setpoint,
    /// `(qf - q0) / (tf - t0)`, the average velocity.
    slope: f64,
}

impl Quintic {
    /// The quintic from `start` at `t0` to `end` at `tf`; needs `tf > t0` and finite inputs.
    ///
    /// As for [`Cubic::new`](super::Cubic::new), finite inputs can still describe a quintic
    /// `f64` cannot hold (an acceleration of 1e300 for 1e200 s): with `T = tf - t0`, the
    /// position scale `|q0| + |qf| + T (|v0| + |vf| + T (|a0| + |af|))`, the velocity scale
    /// `|qf - q0|/T + |v0| + |vf| + T (|a0| + |af|)` and the acceleration scale (the velocity
    /// scale over `T`) bound `|q|`, `|q̇|` and `|q̈|` over `[t0, tf]` up to a factor 6; where one
    /// of them comes within a factor 64 of `f64::MAX`, or a coefficient of
    /// [`coefficients`](Self::coefficients) overflows, the constructor returns
    /// [`TrajectoryError::OutOfFloatRange`] naming it. A quintic it returns evaluates to finite
    /// values at every finite time.
    pub fn new(t0: f64, tf: f64, start: Setpoint, end: Setpoint) -> Result<Self, TrajectoryError> {
        let interval = Interval::new(t0, tf)?;
        let duration = interval.duration();
        let dq = displacement(start.q, end.q)?;
        finite("v0", start.qd)?;
        finite("a0", start.qdd)?;
        finite("vf", end.qd)?;
        finite("af", end.qdd)?;
        let quintic = Self {
            interval,
            start,
            end,
            slope: dq / duration,
        };
        let speeds = abs(start.qd) + abs(end.qd);
        let accelerations = abs(start.qdd) + abs(end.qdd);
        let rates = abs(quintic.slope) + speeds;
        polynomial_in_range(
            [
                (
                    "quintic position scale |q0| + |qf| + T (|v0| + |vf| + T (|a0| + |af|))",
                    abs(start.q) + abs(end.q) + duration * (speeds + duration * accelerations),
                ),
                (
                    "quintic velocity scale |qf - q0|/T + |v0| + |vf| + T (|a0| + |af|)",
                    rates + duration * accelerations,
                ),
                (
                    "quintic acceleration scale (|qf - q0|/T + |v0| + |vf|)/T + |a0| + |af|",
                    rates / duration + accelerations,
                ),
            ],
            &quintic.coefficients(),
        )?;
        Ok(quintic)
    }

    /// The quintic from rest at `q0` to rest at `qf` (what Robotics Toolbox's `jtraj` does by default).
    pub fn rest_to_rest(t0: f64, tf: f64, q0: f64, qf: f64) -> Result<Self, TrajectoryError> {
        Self::new(t0, tf, Setpoint::rest(q0), Setpoint::rest(qf))
    }

    /// The monomial coefficients `[a0, ..., a5]` of `q = Σ a_k τ^k` in the local time `τ = t - t0`.
    ///
    /// Formed from the average velocity `Δ/T = (qf - q0)/T` and divided by `T` one power at a
    /// time, so that no power of `T` overflows or underflows on the way:
    /// `a3 = ((20 Δ/T - 12 v0 - 8 vf)/T - 3 a0 + af)/(2T)`,
    /// `a4 = ((16 v0 + 14 vf - 30 Δ/T)/T + 3 a0 - 2 af)/(2T²)`,
    /// `a5 = ((12 Δ/T - 6 (v0 + vf))/T - a0 + af)/(2T³)`.
    pub fn coefficients(&self) -> [f64; 6] {
        let (t, slope) = (self.interval.duration(), self.slope);
        let (q0, v0, a0) = (self.start.q, self.start.qd, self.start.qdd);
        let (v1, a1) = (self.end.qd, self.end.qdd);
        let two_t = 2.0 * t;
        [
            q0,
            v0,
            a0 / 2.0,
            ((20.0 * slope - (12.0 * v0 + 8.0 * v1)) / t - (3.0 * a0 - a1)) / two_t,
            ((16.0 * v0 + 14.0 * v1 - 30.0 * slope) / t + (3.0 * a0 - 2.0 * a1)) / two_t / t,
            ((12.0 * slope - 6.0 * (v0 + v1)) / t - (a0 - a1)) / two_t / t / t,
        ]
    }
}

impl Profile for Quintic {
    fn interval(&self) -> Interval {
        self.interval
    }

    fn eval(&self, t: f64) -> Setpoint {
        let Interval { t0, tf, duration } = self.interval;
        if t < t0 {
            return Setpoint::rest(self.start.q);
        }
        if t > tf {
            return Setpoint::rest(self.end.q);
        }
        let big_t = duration;
        let s = (t - t0) / big_t;
        let r = 1.0 - s;
        let (s2, s3) = (s * s, s * s * s);
        let (v0, a0, v1, a1) = (self.start.qd, self.start.qdd, self.end.qd, self.end.qdd);
        // Quintic Hermite basis in s and its first two s-derivatives. h5 carries qf and
        // h0 = 1 - h5 carries q0; h1/h4 carry T v0 / T vf; h2/h3 carry T² a0 / T² af.
        let h5 = s3 * (10.0 - 15.0 * s + 6.0 * s2);
        let h0 = 1.0 - h5;
        let h1 = s * r * r * r * (1.0 + 3.0 * s);
        let h4 = -s3 * r * (4.0 - 3.0 * s);
        let h2 = 0.5 * s2 * r * r * r;
        let h3 = 0.5 * s3 * r * r;
        let d5 = 30.0 * s2 * r * r;
        let d1 = r * r * (1.0 + 2.0 * s - 15.0 * s2);
        let d4 = -s2 * (12.0 - 28.0 * s + 15.0 * s2);
        let d2 = 0.5 * s * r * r * (2.0 - 5.0 * s);
        let d3 = 0.5 * s2 * r * (3.0 - 5.0 * s);
        let dd5 = 60.0 * s * r * (1.0 - 2.0 * s);
        let dd1 = -12.0 * s * r * (3.0 - 5.0 * s);
        let dd4 = -12.0 * s * r * (2.0 - 5.0 * s);
        let dd2 = r * (1.0 - 8.0 * s + 10.0 * s2);
        let dd3 = s * (3.0 - 12.0 * s + 10.0 * s2);
        // T (v h + T (a h)), not T² (a h): T² alone overflows from T = 1.4e154 s on, and
        // would turn a rest-to-rest profile's zero accelerations into inf · 0 = NaN.
        let q = self.start.q * h0
            + self.end.q * h5
            + big_t * (v0 * h1 + v1 * h4 + big_t * (a0 * h2 + a1 * h3));
        let qd = self.slope * d5 + v0 * d1 + v1 * d4 + big_t * (a0 * d2 + a1 * d3);
        let qdd = (self.slope * dd5 + v0 * dd1 + v1 * dd4) / big_t + a0 * dd2 + a1 * dd3;
        Setpoint { q, qd, qdd }
    }
}
