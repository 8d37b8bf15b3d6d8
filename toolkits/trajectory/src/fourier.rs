//! Finite Fourier series: the periodic exciting trajectories of parameter identification.

use super::{
    Interval, Location, Profile, Setpoint, TrajectoryError, abs, finite, polynomial_in_range,
    positive,
};

/// One joint's finite Fourier series of `L` harmonics of `ω = 2π / period` about `q0`, run for
/// `cycles` periods from `t0`: the exciting trajectory of inertial parameter identification
/// (Swevers, Ganseman, Bilgin Tükel, De Schutter and Van Brussel, 1997). With `τ = t − t0`,
///
/// ```text
/// q(t) = q0 + Σ_{l=1..L} ( a_l sin(l ω τ) − b_l cos(l ω τ) ) / (l ω)
/// q̇(t) =      Σ_{l=1..L}   a_l cos(l ω τ) + b_l sin(l ω τ)
/// q̈(t) =      Σ_{l=1..L} ( b_l cos(l ω τ) − a_l sin(l ω τ) ) l ω
/// ```
///
/// (`a[l − 1]` and `b[l − 1]` are harmonic `l`'s coefficients, in velocity units). It repeats
/// every period, so a recording of whole periods can be averaged period by period, and its
/// torques hold the harmonics of `ω` only; [`bounds`](Self::bounds) bound `|q − q0|`, `|q̇|`
/// and `|q̈|` at every time, what one checks against the joint's limits.
///
/// It starts (and, being periodic, ends) at `q0 − Σ b_l / (l ω)` with velocity `Σ a_l` and
/// acceleration `Σ l ω b_l`: at rest where `Σ a_l = 0` and `Σ l b_l = 0`. Outside
/// `[t0, t0 + cycles · period]` the joint is at rest at that position, as for every profile
/// (see the [module documentation](super)), so a series that does not start at rest jumps in
/// velocity or acceleration at its ends.
///
/// ```
/// use dhgen::trajectory::{FourierSeries, Profile};
///
/// // Two harmonics of a 10 s period, from rest: Σ a_l = 0 and Σ l b_l = 0.
/// let f = FourierSeries::new(0.0, 10.0, 3, 0.2, [0.3, -0.3], [0.2, -0.1]).unwrap();
/// assert_eq!(f.duration(), 30.0);
/// let start = f.eval(0.0);
/// assert!(start.qd.abs() < 1e-15 && start.qdd.abs() < 1e-15);
/// // Periodic, and within its bounds.
/// let (a, b) = (f.eval(3.7), f.eval(13.7));
/// assert!((a.q - b.q).abs() < 1e-12 && (a.qdd - b.qdd).abs() < 1e-12);
/// let bound = f.bounds();
/// assert!((a.q - 0.2).abs() <= bound.q && a.qd.abs() <= bound.qd && a.qdd.abs() <= bound.qdd);
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FourierSeries<const L: usize> {
    /// `cycles · period` from `t0`, ending at `t0 + duration` rounded (the interval's test
    /// uses that end).
    interval: Interval,
    period: f64,
    /// `2π / period`.
    omega: f64,
    q0: f64,
    a: [f64; L],
    b: [f64; L],
}

impl<const L: usize> FourierSeries<L> {
    /// The series about `q0` with coefficients `a` and `b` (harmonic `l` at index `l − 1`),
    /// running `cycles` periods from `t0`.
    ///
    /// # Errors
    /// [`TrajectoryError::NonFinite`] for a non-finite `t0`, `q0` or `period`, or an end time
    /// `t0 + cycles · period` beyond `f64`; [`TrajectoryError::NonFiniteCoefficient`] naming
    /// the coefficient; [`TrajectoryError::NonPositiveLimit`] for a period or a number of cycles
    /// that is not positive; [`TrajectoryError::OutOfFloatRange`] where a bound (see
    /// [`bounds`](Self::bounds)), or `|q0|` plus the position bound, comes within a factor 64
    /// of `f64::MAX`.
    pub fn new(
        t0: f64,
        period: f64,
        cycles: u32,
        q0: f64,
        a: [f64; L],
        b: [f64; L],
    ) -> Result<Self, TrajectoryError> {
        finite("t0", t0)?;
        finite("q0", q0)?;
        positive("period", period)?;
        positive("cycles", f64::from(cycles))?;
        for (coefficient, values) in [("a", &a), ("b", &b)] {
            if let Some((l, &value)) = values.iter().enumerate().find(|(_, x)| !x.is_finite()) {
                return Err(TrajectoryError::NonFiniteCoefficient {
                    coefficient,
                    harmonic: l + 1,
                    value,
                    at: Location::NONE,
                });
            }
        }
        let duration = finite("cycles · period", f64::from(cycles) * period)?;
        let tf = finite("tf = t0 + cycles · period", t0 + duration)?;
        let series = Self {
            interval: Interval::timed(t0, tf, duration),
            period,
            omega: core::f64::consts::TAU / period,
            q0,
            a,
            b,
        };
        let bounds = series.bounds();
        polynomial_in_range(
            [
                (
                    "Fourier series position scale |q0| + Σ |(a_l, b_l)| / (l ω)",
                    abs(q0) + bounds.q,
                ),
                ("Fourier series velocity bound Σ |(a_l, b_l)|", bounds.qd),
                (
                    "Fourier series acceleration bound Σ l ω |(a_l, b_l)|",
                    bounds.qdd,
                ),
            ],
            &[],
        )?;
        Ok(series)
    }

    /// Bounds on `|q − q0|`, `|q̇|` and `|q̈|` at every time (as a [`Setpoint`]): harmonic `l`
    /// is a sinusoid of amplitude `c_l / (l ω)` in position, `c_l` in velocity and `l ω c_l`
    /// in acceleration, `c_l = √(a_l² + b_l²)`, and the bounds are their sums, reached where
    /// the harmonics peak together (a velocity with every `b_l = 0` and `a_l ≥ 0` reaches its
    /// bound at `t0`).
    pub fn bounds(&self) -> Setpoint {
        let mut bound = Setpoint::default();
        for (l, (&a, &b)) in self.a.iter().zip(&self.b).enumerate() {
            let c = libm::hypot(a, b);
            let rate = (l + 1) as f64 * self.omega;
            bound.q += c / rate;
            bound.qd += c;
            bound.qdd += c * rate;
        }
        bound
    }

    /// The period, `2π / ω`.
    pub fn period(&self) -> f64 {
        self.period
    }

    /// The position the series oscillates about.
    pub fn center(&self) -> f64 {
        self.q0
    }

    /// The coefficients `(a, b)`, harmonic `l` at index `l − 1`.
    pub fn coefficients(&self) -> (&[f64; L], &[f64; L]) {
        (&self.a, &self.b)
    }

    /// The state at `τ` seconds into a period (`0 ≤ τ < period`).
    fn at_phase(&self, tau: f64) -> Setpoint {
        let mut s = Setpoint::rest(self.q0);
        for (l, (&a, &b)) in self.a.iter().zip(&self.b).enumerate() {
            let rate = (l + 1) as f64 * self.omega;
            let (sin, cos) = libm::sincos(rate * tau);
            s.q += (a * sin - b * cos) / rate;
            s.qd += a * cos + b * sin;
            s.qdd += (b * cos - a * sin) * rate;
        }
        s
    }
}

impl<const L: usize> Profile for FourierSeries<L> {
    fn interval(&self) -> Interval {
        self.interval
    }

    fn eval(&self, t: f64) -> Setpoint {
        if t.is_nan() {
            return Setpoint::NAN;
        }
        let Interval { t0, tf, .. } = self.interval;
        if t < t0 || t > tf {
            return Setpoint::rest(self.at_phase(0.0).q);
        }
        // Into one period, so that the sines' arguments stay small over many cycles; the end
        // time is the start of a period.
        let tau = t - t0;
        let phase = tau - self.period * libm::floor(tau / self.period);
        self.at_phase(if phase < self.period { phase } else { 0.0 })
    }
}
