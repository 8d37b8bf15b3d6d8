//! Cubic polynomial: position and velocity given at both ends (section 6.5.1.1, equation 15).

use super::{
    Interval, Profile, Setpoint, TrajectoryError, abs, displacement, finite, polynomial_in_range,
};

/// The cubic `q(t)` with `q(t0) = q0`, `q̇(t0) = v0`, `q(tf) = qf`, `q̇(tf) = vf`.
///
/// Position and velocity are continuous; the acceleration is linear in time and generally jumps
/// at `t0` and `tf` (the text's motivation for the [`Quintic`](super::Quintic)).
///
/// It is evaluated in cubic Hermite form in the normalized time `s = (t - t0)/(tf - t0)`, which is
/// the unique solution of equation 15 and reproduces the four boundary values exactly at
/// `s = 0` and `s = 1` (no cancellation between large monomial coefficients).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cubic {
    interval: Interval,
    q0: f64,
    qf: f64,
    v0: f64,
    vf: f64,
    /// `(qf - q0) / (tf - t0)`, the average velocity.
    slope: f64,
}

impl Cubic {
    /// The cubic through `(t0, q0, v0)` and `(tf, qf, vf)`; needs `tf > t0` and finite inputs.
    ///
    /// Finite inputs can still describe a cubic `f64` cannot hold (a move of 1e308 in 0.5 s, a
    /// velocity of 1e300 for 1e10 s, a duration of 5e-324 s): with `T = tf - t0`, the position
    /// scale `|q0| + |qf| + T (|v0| + |vf|)`, the velocity scale `|qf - q0|/T + |v0| + |vf|` and
    /// the acceleration scale (the velocity scale over `T`) bound `|q|`, `|q̇|` and `|q̈|` over
    /// `[t0, tf]` up to a factor 6; where one of them comes within a factor 64 of `f64::MAX`,
    /// or a coefficient of [`coefficients`](Self::coefficients) overflows, the constructor
    /// returns [`TrajectoryError::OutOfFloatRange`] naming it. A cubic it returns evaluates to
    /// finite values at every finite time.
    pub fn new(
        t0: f64,
        tf: f64,
        q0: f64,
        v0: f64,
        qf: f64,
        vf: f64,
    ) -> Result<Self, TrajectoryError> {
        let interval = Interval::new(t0, tf)?;
        let duration = interval.duration();
        let dq = displacement(q0, qf)?;
        finite("v0", v0)?;
        finite("vf", vf)?;
        let cubic = Self {
            interval,
            q0,
            qf,
            v0,
            vf,
            slope: dq / duration,
        };
        let rates = abs(cubic.slope) + abs(v0) + abs(vf);
        polynomial_in_range(
            [
                (
                    "cubic position scale |q0| + |qf| + T (|v0| + |vf|)",
                    abs(q0) + abs(qf) + duration * (abs(v0) + abs(vf)),
                ),
                ("cubic velocity scale |qf - q0|/T + |v0| + |vf|", rates),
                (
                    "cubic acceleration scale (|qf - q0|/T + |v0| + |vf|)/T",
                    rates / duration,
                ),
            ],
            &cubic.coefficients(),
        )?;
        Ok(cubic)
    }

    /// The cubic from rest at `q0` to rest at `qf` (Figure 4 of the text).
    pub fn rest_to_rest(t0: f64, tf: f64, q0: f64, qf: f64) -> Result<Self, TrajectoryError> {
        Self::new(t0, tf, q0, 0.0, qf, 0.0)
    }

    /// The monomial coefficients `[a0, a1, a2, a3]` of `q = a0 + a1 τ + a2 τ² + a3 τ³` in the local
    /// time `τ = t - t0` (equation 15 with `t0 = 0`).
    ///
    /// Formed from the average velocity `(qf - q0)/T` and divided by `T` one power at a time,
    /// so that no power of `T` overflows or underflows on the way: `a2 = (3 (qf - q0)/T -
    /// 2 v0 - vf)/T`, `a3 = (v0 + vf - 2 (qf - q0)/T)/T²`.
    pub fn coefficients(&self) -> [f64; 4] {
        let (t, slope, v0, vf) = (self.interval.duration(), self.slope, self.v0, self.vf);
        [
            self.q0,
            v0,
            (3.0 * slope - (2.0 * v0 + vf)) / t,
            (v0 + vf - 2.0 * slope) / t / t,
        ]
    }
}

impl Profile for Cubic {
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
        let s = (t - t0) / duration;
        let r = 1.0 - s;
        let big_t = duration;
        // Hermite basis: h01 carries qf, h00 = 1 - h01 carries q0, h10/h11 carry T v0 / T vf.
        let h01 = s * s * (3.0 - 2.0 * s);
        let h00 = 1.0 - h01;
        let h10 = s * r * r;
        let h11 = -s * s * r;
        let q = self.q0 * h00 + self.qf * h01 + big_t * (self.v0 * h10 + self.vf * h11);
        let qd = 6.0 * s * r * self.slope
            + self.v0 * r * (1.0 - 3.0 * s)
            + self.vf * s * (3.0 * s - 2.0);
        let qdd =
            ((6.0 - 12.0 * s) * self.slope + self.v0 * (6.0 * s - 4.0) + self.vf * (6.0 * s - 2.0))
                / big_t;
        Setpoint { q, qd, qdd }
    }
}
