//! Quintic polynomial: position, velocity and acceleration given at both ends (section 6.5.1.1).

use super::{Profile, Setpoint, TrajectoryError, displacement, finite, interval};

/// The quintic `q(t)` matching position, velocity and acceleration at `t0` and `tf`.
///
/// Position, velocity and acceleration are continuous, and with the default rest-to-rest ends
/// (zero velocity and acceleration) the acceleration does not jump at `t0` or `tf` either.
///
/// It is evaluated in quintic Hermite form in the normalized time `s = (t - t0)/(tf - t0)`, which
/// reproduces all six boundary values exactly at `s = 0` and `s = 1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quintic {
    t0: f64,
    tf: f64,
    duration: f64,
    start: Setpoint,
    end: Setpoint,
    /// `(qf - q0) / (tf - t0)`, the average velocity.
    slope: f64,
}

impl Quintic {
    /// The quintic from `start` at `t0` to `end` at `tf`; needs `tf > t0` and finite inputs.
    pub fn new(t0: f64, tf: f64, start: Setpoint, end: Setpoint) -> Result<Self, TrajectoryError> {
        let duration = interval(t0, tf)?;
        let dq = displacement(start.q, end.q)?;
        finite("v0", start.qd)?;
        finite("a0", start.qdd)?;
        finite("vf", end.qd)?;
        finite("af", end.qdd)?;
        Ok(Self {
            t0,
            tf,
            duration,
            start,
            end,
            slope: dq / duration,
        })
    }

    /// The quintic from rest at `q0` to rest at `qf` (what Robotics Toolbox's `jtraj` does by default).
    pub fn rest_to_rest(t0: f64, tf: f64, q0: f64, qf: f64) -> Result<Self, TrajectoryError> {
        Self::new(t0, tf, Setpoint::rest(q0), Setpoint::rest(qf))
    }

    /// The monomial coefficients `[a0, ..., a5]` of `q = Σ a_k τ^k` in the local time `τ = t - t0`.
    pub fn coefficients(&self) -> [f64; 6] {
        let t = self.duration;
        let (q0, v0, a0) = (self.start.q, self.start.qd, self.start.qdd);
        let (v1, a1) = (self.end.qd, self.end.qdd);
        let dq = self.end.q - q0;
        let (t2, t3) = (t * t, t * t * t);
        [
            q0,
            v0,
            a0 / 2.0,
            (20.0 * dq - (12.0 * v0 + 8.0 * v1) * t - (3.0 * a0 - a1) * t2) / (2.0 * t3),
            (-30.0 * dq + (16.0 * v0 + 14.0 * v1) * t + (3.0 * a0 - 2.0 * a1) * t2)
                / (2.0 * t3 * t),
            (12.0 * dq - 6.0 * (v0 + v1) * t - (a0 - a1) * t2) / (2.0 * t3 * t2),
        ]
    }
}

impl Profile for Quintic {
    fn start_time(&self) -> f64 {
        self.t0
    }

    fn duration(&self) -> f64 {
        self.duration
    }

    fn end_time(&self) -> f64 {
        self.tf
    }

    fn eval(&self, t: f64) -> Setpoint {
        if t < self.t0 {
            return Setpoint::rest(self.start.q);
        }
        if t > self.tf {
            return Setpoint::rest(self.end.q);
        }
        let big_t = self.duration;
        let s = (t - self.t0) / big_t;
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
        let q = self.start.q * h0
            + self.end.q * h5
            + big_t * (v0 * h1 + v1 * h4)
            + big_t * big_t * (a0 * h2 + a1 * h3);
        let qd = self.slope * d5 + v0 * d1 + v1 * d4 + big_t * (a0 * d2 + a1 * d3);
        let qdd = (self.slope * dd5 + v0 * dd1 + v1 * dd4) / big_t + a0 * dd2 + a1 * dd3;
        Setpoint { q, qd, qdd }
    }
}
