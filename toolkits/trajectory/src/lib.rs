//! Joint-space trajectory generation (section 6.5 of the reference text).
//!
//! Point-to-point profiles for one joint:
//! - [`Cubic`]: position and velocity given at both ends (equation 15 of the text);
//! - [`Quintic`]: position, velocity and acceleration given at both ends;
//! - [`Lspb`]: linear segment with parabolic blends, from the cruise velocity
//!   ([`Lspb::with_velocity`]) or the blend acceleration ([`Lspb::with_acceleration`]);
//! - minimum-time profiles, also [`Lspb`]s: bang-bang for an acceleration limit
//!   ([`Lspb::bang_bang`]) and the trapezoid for velocity and acceleration limits
//!   ([`Lspb::velocity_limited`]), with their closed-form durations
//!   ([`bang_bang_duration`], [`velocity_limited_duration`]).
//!
//! Periodic excitation for parameter identification: [`FourierSeries`], a finite Fourier series
//! about a mid position with bounds on its position, velocity and acceleration.
//!
//! Many joints: [`Synchronized`] holds one profile per joint, all sharing the same start and end
//! time (for the limit-based profiles, the slowest joint's minimum duration).
//!
//! Via points (needs the `std` feature): `CubicSpline` (continuous velocity and acceleration,
//! natural or clamped ends) and `BlendedSegments` (linear segments with parabolic blends, like
//! Robotics Toolbox's `mstraj`), from given times or from velocity and acceleration limits.
//!
//! # Time outside the trajectory
//! Every profile is defined on the closed interval `[t0, tf]`; at `t0` and `tf` it returns its own
//! boundary state (including a non-zero boundary velocity or acceleration). Outside that interval
//! the joint is **at rest at the nearest end point**: `q` is held at `q(t0)` (before) or `q(tf)`
//! (after) and `q̇ = q̈ = 0`. That triple is the derivative chain of a constant, so it is
//! kinematically consistent; for rest-to-rest profiles it is the "hold the end state" behaviour
//! of Robotics Toolbox. The price is a velocity jump at `t0` or `tf` when the profile itself starts
//! or ends moving (e.g. a cubic with `vf != 0` or a natural spline), and an acceleration jump
//! where the profile's end acceleration is non-zero (the cubic's, exactly as the text notes for
//! Figure 4). A NaN time evaluates to NaN.
//!
//! Moves with `qf < q0` are handled symmetrically everywhere: velocities and accelerations carry
//! the sign of the move, limits are magnitudes.
//!
//! All of the point-to-point code is `no_std`: it uses only `core` and `f64` arithmetic (square
//! roots through nalgebra's `ComplexField`, which is backed by `libm` without `std`), and sampling
//! into caller-provided buffers never allocates.
//!
//! [`Cubic`]: crate::Cubic
//! [`Quintic`]: crate::Quintic
//! [`Lspb`]: crate::Lspb
//! [`Lspb::with_velocity`]: crate::Lspb::with_velocity
//! [`Lspb::with_acceleration`]: crate::Lspb::with_acceleration
//! [`Lspb::bang_bang`]: crate::Lspb::bang_bang
//! [`Lspb::velocity_limited`]: crate::Lspb::velocity_limited
//! [`bang_bang_duration`]: crate::bang_bang_duration
//! [`velocity_limited_duration`]: crate::velocity_limited_duration
//! [`Synchronized`]: crate::Synchronized
//! [`FourierSeries`]: crate::FourierSeries

mod cubic;
mod fourier;
mod lspb;
mod min_time;
mod multi;
mod quintic;
#[cfg(feature = "std")]
mod via;

pub use cubic::Cubic;
pub use fourier::FourierSeries;
pub use lspb::Lspb;
pub use min_time::{bang_bang_duration, velocity_limited_duration};
pub use multi::Synchronized;
pub use quintic::Quintic;
#[cfg(feature = "std")]
pub use via::{BlendedSegments, CubicSpline, JointView, SplineEnds};

use core::fmt;

/// Position, velocity and acceleration of one joint at one instant.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Setpoint {
    /// Position `q`.
    pub q: f64,
    /// Velocity `q̇`.
    pub qd: f64,
    /// Acceleration `q̈`.
    pub qdd: f64,
}

impl Setpoint {
    /// A state with the given position, velocity and acceleration.
    pub const fn new(q: f64, qd: f64, qdd: f64) -> Self {
        Self { q, qd, qdd }
    }

    /// All NaN: the state at a NaN time.
    pub(crate) const NAN: Setpoint = Setpoint::new(f64::NAN, f64::NAN, f64::NAN);

    /// At rest at `q`: zero velocity and acceleration.
    pub const fn rest(q: f64) -> Self {
        Self {
            q,
            qd: 0.0,
            qdd: 0.0,
        }
    }
}

impl From<Setpoint> for (f64, f64, f64) {
    fn from(s: Setpoint) -> Self {
        (s.q, s.qd, s.qdd)
    }
}

/// The time interval `[t0, tf]` a trajectory runs over, with its duration.
///
/// The three are stored as the trajectory computed them: the duration is `tf − t0`, or, for a
/// trajectory timed by its duration (a joint synchronized to another's, a minimum-time move, a
/// whole number of periods), that duration exactly with `tf = t0 + duration` rounded. Every
/// profile answers [`start_time`](Profile::start_time), [`duration`](Profile::duration) and
/// [`end_time`](Profile::end_time) from its interval.
///
/// ```
/// use dhgen::trajectory::{Interval, Profile, Quintic};
///
/// let span = Interval::new(1.0, 3.5)?;
/// assert_eq!((span.start(), span.end(), span.duration()), (1.0, 3.5, 2.5));
/// let move_ = Quintic::rest_to_rest(1.0, 3.5, 0.0, 1.0)?;
/// assert_eq!(move_.interval(), span);
/// assert!(Interval::new(2.0, 2.0).is_err());
/// # Ok::<(), dhgen::trajectory::TrajectoryError>(())
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Interval {
    t0: f64,
    tf: f64,
    duration: f64,
}

impl Interval {
    /// `[t0, tf]`; needs finite times with `tf > t0` a finite distance apart.
    ///
    /// # Errors
    /// [`TrajectoryError::NonFinite`] naming `t0`, `tf` or `tf - t0`;
    /// [`TrajectoryError::EmptyTimeInterval`] for `tf <= t0`.
    pub fn new(t0: f64, tf: f64) -> Result<Self, TrajectoryError> {
        finite("t0", t0)?;
        finite("tf", tf)?;
        if tf <= t0 {
            return Err(TrajectoryError::EmptyTimeInterval { t0, tf });
        }
        // Two huge finite times can still be infinitely far apart.
        let duration = finite("tf - t0", tf - t0)?;
        Ok(Self { t0, tf, duration })
    }

    /// The interval of the given `duration` (finite, non-negative: zero for a minimum-time
    /// profile of a zero move) ending at `tf`, which the caller has checked is `t0 + duration`
    /// rounded, or `tf − t0` exactly.
    pub(crate) const fn timed(t0: f64, tf: f64, duration: f64) -> Self {
        Self { t0, tf, duration }
    }

    /// The start time `t0`.
    pub const fn start(&self) -> f64 {
        self.t0
    }

    /// The end time `tf`.
    pub const fn end(&self) -> f64 {
        self.tf
    }

    /// The duration (zero only for a minimum-time profile of a zero move).
    pub const fn duration(&self) -> f64 {
        self.duration
    }
}

/// A trajectory of one joint: `q(t)`, `q̇(t)`, `q̈(t)` on `[start_time, end_time]`.
///
/// Outside that interval the joint is at rest at the nearest end (see the
/// [module documentation](self)).
pub trait Profile {
    /// The time interval the profile runs over.
    fn interval(&self) -> Interval;
    /// The start time `t0`.
    fn start_time(&self) -> f64 {
        self.interval().start()
    }
    /// The duration `tf - t0` (zero only for a minimum-time profile of a zero move).
    fn duration(&self) -> f64 {
        self.interval().duration()
    }
    /// The end time `tf`.
    fn end_time(&self) -> f64 {
        self.interval().end()
    }
    /// Position, velocity and acceleration at time `t`.
    fn eval(&self, t: f64) -> Setpoint;
}

/// A trajectory of several joints sharing one time interval.
pub trait MultiProfile {
    /// Number of joints.
    fn dof(&self) -> usize;
    /// The common time interval.
    fn interval(&self) -> Interval;
    /// The common start time `t0`.
    fn start_time(&self) -> f64 {
        self.interval().start()
    }
    /// The common duration `tf - t0`.
    fn duration(&self) -> f64 {
        self.interval().duration()
    }
    /// The common end time `tf`.
    fn end_time(&self) -> f64 {
        self.interval().end()
    }
    /// Writes the state of every joint at time `t` into `out` (`out.len()` must equal
    /// [`dof`](MultiProfile::dof)).
    fn eval_into(&self, t: f64, out: &mut [Setpoint]) -> Result<(), TrajectoryError>;
}

/// Where in a multi-joint or via-point input a problem was found (indices are 0-based).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Location {
    /// The joint index, if the problem belongs to one joint.
    pub joint: Option<usize>,
    /// The via-point index, if the problem belongs to one via point.
    pub point: Option<usize>,
}

impl Location {
    /// No particular joint or point (a single-joint profile).
    pub const NONE: Self = Self {
        joint: None,
        point: None,
    };

    /// The given joint.
    pub const fn joint(joint: usize) -> Self {
        Self {
            joint: Some(joint),
            point: None,
        }
    }

    /// The given joint of the given via point.
    pub const fn point(point: usize, joint: usize) -> Self {
        Self {
            joint: Some(joint),
            point: Some(point),
        }
    }
}

impl fmt::Display for Location {
    /// Empty for [`Location::NONE`], else `" (via point 3, joint 1)"`-style text to append.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.point, self.joint) {
            (None, None) => Ok(()),
            (Some(p), Some(j)) => write!(f, " (via point {p}, joint {j})"),
            (Some(p), None) => write!(f, " (via point {p})"),
            (None, Some(j)) => write!(f, " (joint {j})"),
        }
    }
}

/// Why a trajectory could not be built or sampled.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
pub enum TrajectoryError {
    /// The final time is not after the start time.
    #[error("final time tf = {tf} must be greater than start time t0 = {t0}")]
    EmptyTimeInterval {
        /// Start time.
        t0: f64,
        /// Final time.
        tf: f64,
    },
    /// An input (or a difference of inputs, e.g. `qf - q0`) is NaN or infinite.
    #[error("{name} = {value} is not finite{at}")]
    NonFinite {
        /// The quantity's name, e.g. `"q0"`, `"vmax"`, `"qf - q0"`.
        name: &'static str,
        /// Its value.
        value: f64,
        /// Which joint or via point.
        at: Location,
    },
    /// A coefficient of a [`FourierSeries`] is NaN or infinite.
    #[error("Fourier coefficient {coefficient}_{harmonic} = {value} is not finite{at}")]
    NonFiniteCoefficient {
        /// `"a"` or `"b"`.
        coefficient: &'static str,
        /// The harmonic, from 1.
        harmonic: usize,
        /// Its value.
        value: f64,
        /// Which joint.
        at: Location,
    },
    /// The LSPB cruise velocity `V` lies outside `((qf - q0)/T, 2 (qf - q0)/T]` for a positive
    /// move, `[2 (qf - q0)/T, (qf - q0)/T)` for a negative move, or is not 0 for a zero move.
    #[error("{}", LspbVelocityMessage { v: *v, exclusive_bound: *exclusive_bound, inclusive_bound: *inclusive_bound, at })]
    LspbVelocityOutOfRange {
        /// The requested cruise velocity.
        v: f64,
        /// `(qf - q0)/T`: the average velocity, excluded (the blends would take no time).
        exclusive_bound: f64,
        /// `2 (qf - q0)/T`: included (the blends meet in the middle: bang-bang).
        inclusive_bound: f64,
        /// Which joint.
        at: Location,
    },
    /// The LSPB blend acceleration cannot cover the move in the given time.
    #[error(
        "LSPB blend acceleration {alpha} is too small to finish the move in time: \
         it must be at least 4|qf - q0|/T^2 = {min}{at}"
    )]
    LspbAccelerationTooSmall {
        /// The requested blend acceleration (magnitude).
        alpha: f64,
        /// The smallest feasible one, `4 |qf - q0| / T²`.
        min: f64,
        /// Which joint.
        at: Location,
    },
    /// Valid inputs so extreme that a derived quantity cannot be represented in `f64`, e.g. an
    /// LSPB cruise velocity within rounding of `(qf - q0)/T`, whose blend time rounds to zero,
    /// or a cubic or quintic whose position, velocity or acceleration scale (which bounds the
    /// profile's values over `[t0, tf]`) comes within a factor 64 of `f64::MAX`, or whose
    /// monomial coefficients overflow (see [`Cubic::new`]).
    #[error(
        "{name} = {value} cannot be represented in f64: the inputs are too extreme \
         relative to each other{at}"
    )]
    OutOfFloatRange {
        /// The derived quantity, e.g. `"LSPB blend time tb"`.
        name: &'static str,
        /// Its computed value.
        value: f64,
        /// Which joint.
        at: Location,
    },
    /// A limit or blend time that must be positive is zero or negative.
    #[error("{name} = {value} must be positive{at}")]
    NonPositiveLimit {
        /// The limit's name, e.g. `"amax"`.
        name: &'static str,
        /// Its value.
        value: f64,
        /// Which joint.
        at: Location,
    },
    /// Via times do not increase strictly.
    #[error(
        "via times must increase strictly, but times[{index}] = {value} is not greater \
         than times[{}] = {previous}",
        index - 1
    )]
    NonIncreasingTimes {
        /// Index of the first time that is not greater than its predecessor.
        index: usize,
        /// `times[index - 1]`.
        previous: f64,
        /// `times[index]`.
        value: f64,
    },
    /// A via-point trajectory needs at least two points.
    #[error("a via-point trajectory needs at least two points, got {found}")]
    TooFewPoints {
        /// How many were given.
        found: usize,
    },
    /// A slice has the wrong length.
    #[error("{name} has length {found}, expected {expected}{at}")]
    LengthMismatch {
        /// Which slice, e.g. `"times"`, `"out"`, `"vmax"`.
        name: &'static str,
        /// The required length.
        expected: usize,
        /// The given length.
        found: usize,
        /// Which via point, if the slice is one point's coordinates.
        at: Location,
    },
    /// A trajectory needs at least one joint.
    #[error("a trajectory needs at least one joint, got none")]
    NoJoints,
    /// Uniform sampling needs at least two samples (to include both `t0` and `tf`).
    #[error("uniform sampling needs at least two samples (t0 and tf), got {found}")]
    TooFewSamples {
        /// How many were requested.
        found: usize,
    },
    /// Uniform sampling into vectors ([`sample`], [`sample_multi`]) was asked for more than
    /// [`MAX_SAMPLES`] setpoints (`samples · dof`, also when that product overflows `usize`),
    /// or for fewer that the allocator could not provide.
    #[error(
        "{samples} samples of {dof} joint(s) cannot be allocated: sampling into vectors \
         allocates at most {max} setpoints (samples times joints), memory permitting; \
         sample a longer trajectory in pieces into buffers of your own (sample_into, \
         sample_multi_into)"
    )]
    TooManySamples {
        /// How many samples were requested.
        samples: usize,
        /// The number of joints each sample holds.
        dof: usize,
        /// [`MAX_SAMPLES`].
        max: usize,
    },
    /// Parabolic blends of the given duration do not fit into a segment between via points.
    #[error(
        "segment {segment} (via point {} to {segment}) lasts {available}, but its parabolic \
         blends need {needed}: use a shorter blend time or more time for the segment",
        segment - 1
    )]
    BlendsOverlap {
        /// The segment index `k` (from via point `k - 1` to via point `k`).
        segment: usize,
        /// The segment's duration `t[k] - t[k-1]`.
        available: f64,
        /// The duration the blends need: `tacc`, plus `tacc/2` if the segment starts at the first
        /// point, plus `tacc/2` if it ends at the last point (the end blends start or stop at rest
        /// inside the trajectory).
        needed: f64,
    },
    /// Profiles passed to [`Synchronized::new`] do not share the first joint's time interval.
    #[error(
        "joint {joint} runs on [{t0}, {tf}] but joint 0 on [{expected_t0}, {expected_tf}]: \
         synchronized joints must share one time interval"
    )]
    MismatchedTimes {
        /// The first joint whose interval differs.
        joint: usize,
        /// Its start time.
        t0: f64,
        /// Its end time.
        tf: f64,
        /// Joint 0's start time.
        expected_t0: f64,
        /// Joint 0's end time.
        expected_tf: f64,
    },
}

impl TrajectoryError {
    /// The same error attributed to `joint` (for errors that can belong to one joint and do not
    /// name one yet); other errors are returned unchanged.
    pub fn at_joint(self, joint: usize) -> Self {
        let place = |at: Location| {
            if at.joint.is_none() {
                Location {
                    joint: Some(joint),
                    ..at
                }
            } else {
                at
            }
        };
        match self {
            Self::NonFinite { name, value, at } => Self::NonFinite {
                name,
                value,
                at: place(at),
            },
            Self::NonFiniteCoefficient {
                coefficient,
                harmonic,
                value,
                at,
            } => Self::NonFiniteCoefficient {
                coefficient,
                harmonic,
                value,
                at: place(at),
            },
            Self::LspbVelocityOutOfRange {
                v,
                exclusive_bound,
                inclusive_bound,
                at,
            } => Self::LspbVelocityOutOfRange {
                v,
                exclusive_bound,
                inclusive_bound,
                at: place(at),
            },
            Self::LspbAccelerationTooSmall { alpha, min, at } => Self::LspbAccelerationTooSmall {
                alpha,
                min,
                at: place(at),
            },
            Self::NonPositiveLimit { name, value, at } => Self::NonPositiveLimit {
                name,
                value,
                at: place(at),
            },
            Self::OutOfFloatRange { name, value, at } => Self::OutOfFloatRange {
                name,
                value,
                at: place(at),
            },
            other => other,
        }
    }
}

/// The message of [`TrajectoryError::LspbVelocityOutOfRange`]: the allowed interval depends
/// on the direction of the move.
struct LspbVelocityMessage<'a> {
    v: f64,
    exclusive_bound: f64,
    inclusive_bound: f64,
    at: &'a Location,
}

impl fmt::Display for LspbVelocityMessage<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let LspbVelocityMessage {
            v,
            exclusive_bound,
            inclusive_bound,
            at,
        } = self;
        if *exclusive_bound > 0.0 {
            write!(
                f,
                "LSPB cruise velocity V = {v} is outside the allowed interval \
                 ({exclusive_bound}, {inclusive_bound}] = ((qf - q0)/T, 2(qf - q0)/T]{at}"
            )
        } else if *exclusive_bound < 0.0 {
            write!(
                f,
                "LSPB cruise velocity V = {v} is outside the allowed interval \
                 [{inclusive_bound}, {exclusive_bound}) = [2(qf - q0)/T, (qf - q0)/T) \
                 of this negative move{at}"
            )
        } else {
            write!(
                f,
                "LSPB cruise velocity V = {v} must be 0 for a zero move (qf = q0){at}"
            )
        }
    }
}

/// `Ok(x)` if `x` is finite, else the [`TrajectoryError::NonFinite`] naming it.
pub(crate) fn finite(name: &'static str, value: f64) -> Result<f64, TrajectoryError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(TrajectoryError::NonFinite {
            name,
            value,
            at: Location::NONE,
        })
    }
}

/// `Ok(x)` if `x` is finite and positive, else the error naming it.
pub(crate) fn positive(name: &'static str, value: f64) -> Result<f64, TrajectoryError> {
    finite(name, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(TrajectoryError::NonPositiveLimit {
            name,
            value,
            at: Location::NONE,
        })
    }
}

/// Checks `q0` and `qf` and returns the move `qf - q0`.
pub(crate) fn displacement(q0: f64, qf: f64) -> Result<f64, TrajectoryError> {
    finite("q0", q0)?;
    finite("qf", qf)?;
    finite("qf - q0", qf - q0)
}

/// How far below `f64::MAX` the scales of a polynomial profile must stay. [`Cubic`] and
/// [`Quintic`] evaluate their Hermite form in `s = (t - t0)/T ∈ [0, 1]`: q, q̇ and q̈, and every
/// partial sum and product on the way, are sums of the terms of the matching scale (see
/// [`polynomial_in_range`]) times basis polynomials of magnitude at most 6 on `[0, 1]`, and
/// the monomial coefficients are formed from them with factors up to 33 before they are
/// divided by powers of `T` (which overflows only where the coefficient itself does). Within
/// this factor of `f64::MAX`, nothing overflows on the way.
const POLYNOMIAL_HEADROOM: f64 = 64.0;

/// The names of the monomial coefficients, for [`TrajectoryError::OutOfFloatRange`].
const COEFFICIENT_NAMES: [&str; 6] = [
    "polynomial coefficient a0",
    "polynomial coefficient a1",
    "polynomial coefficient a2",
    "polynomial coefficient a3",
    "polynomial coefficient a4",
    "polynomial coefficient a5",
];

/// The range check shared by [`Cubic`], [`Quintic`] and [`FourierSeries`] (with no
/// coefficients: its scales are its bounds), whose constructors take finite input that can
/// still describe a profile `f64` cannot hold (a velocity of 1e300 for 1e10 s).
///
/// `scales` are the position, velocity and acceleration scales: with `T = tf - t0`, the sums
/// of the magnitudes of the Hermite data each derivative is formed from (position: `|q0|`,
/// `|qf|`, `T |v0|`, `T |vf|`, `T² |a0|`, `T² |af|`; velocity: `|qf - q0|/T`, `|v0|`, `|vf|`,
/// `T |a0|`, `T |af|`; acceleration: the velocity scale over `T`). Each bounds the peak of its
/// derivative over `[t0, tf]` up to a factor 6, so within [`POLYNOMIAL_HEADROOM`] of
/// `f64::MAX` every evaluation on `[t0, tf]` stays finite. The scales are a few operations:
/// the exact peaks would need the roots of the derivative. `coefficients` are the monomial
/// coefficients `a_k` of `q = Σ a_k (t - t0)^k` (what `coefficients()` returns), which must be
/// finite too: `a_k` is the k-th scaled coefficient over `T^k`, and a short enough move
/// (`T` = 1e-150 s) has a finite acceleration but a jerk beyond `f64`.
pub(crate) fn polynomial_in_range(
    scales: [(&'static str, f64); 3],
    coefficients: &[f64],
) -> Result<(), TrajectoryError> {
    // A scale that overflowed names the cause better than one within the headroom, so those
    // come first (a move of 1e308 in 0.5 s: the velocity, not the position of 1e308).
    let overflowed = scales.iter().find(|(_, value)| !value.is_finite());
    let near_max = || {
        scales
            .iter()
            .find(|(_, value)| !(value * POLYNOMIAL_HEADROOM).is_finite())
    };
    if let Some(&(name, value)) = overflowed.or_else(near_max) {
        return Err(TrajectoryError::OutOfFloatRange {
            name,
            value,
            at: Location::NONE,
        });
    }
    for (&name, &value) in COEFFICIENT_NAMES.iter().zip(coefficients) {
        if !value.is_finite() {
            return Err(TrajectoryError::OutOfFloatRange {
                name,
                value,
                at: Location::NONE,
            });
        }
    }
    Ok(())
}

/// Square root without `std` (nalgebra routes it to `libm` in `no_std` builds).
pub(crate) fn sqrt(x: f64) -> f64 {
    nalgebra::ComplexField::sqrt(x)
}

/// Absolute value without relying on `std`.
pub(crate) fn abs(x: f64) -> f64 {
    nalgebra::ComplexField::abs(x)
}

/// The `i`-th of `n >= 2` equally spaced times from `t0` to `tf`; the last one is exactly `tf`.
pub fn uniform_time(t0: f64, tf: f64, n: usize, i: usize) -> f64 {
    if n < 2 || i + 1 >= n {
        return if i == 0 { t0 } else { tf };
    }
    t0 + (tf - t0) * (i as f64 / (n - 1) as f64)
}

/// Samples `profile` at `out.len() >= 2` equally spaced times from its start to its end time
/// (both included), without allocating.
pub fn sample_into<P: Profile + ?Sized>(
    profile: &P,
    out: &mut [Setpoint],
) -> Result<(), TrajectoryError> {
    let n = out.len();
    if n < 2 {
        return Err(TrajectoryError::TooFewSamples { found: n });
    }
    let (t0, tf) = (profile.start_time(), profile.end_time());
    for (i, state) in out.iter_mut().enumerate() {
        *state = profile.eval(uniform_time(t0, tf, n, i));
    }
    Ok(())
}

/// Samples `profile` at the given (finite) times, without allocating.
pub fn sample_times_into<P: Profile + ?Sized>(
    profile: &P,
    times: &[f64],
    out: &mut [Setpoint],
) -> Result<(), TrajectoryError> {
    if out.len() != times.len() {
        return Err(TrajectoryError::LengthMismatch {
            name: "out",
            expected: times.len(),
            found: out.len(),
            at: Location::NONE,
        });
    }
    for (state, &t) in out.iter_mut().zip(times) {
        *state = profile.eval(finite("t", t)?);
    }
    Ok(())
}

/// Samples every joint of `profile` at `n` equally spaced times, where `out` holds `n` rows of
/// `dof` setpoints (row-major: `out[i * dof + j]` is joint `j` at time `i`), without allocating.
pub fn sample_multi_into<M: MultiProfile + ?Sized>(
    profile: &M,
    out: &mut [Setpoint],
) -> Result<(), TrajectoryError> {
    let dof = profile.dof();
    if dof == 0 {
        return Err(TrajectoryError::NoJoints);
    }
    if !out.len().is_multiple_of(dof) {
        return Err(TrajectoryError::LengthMismatch {
            name: "out (whole rows of dof setpoints)",
            expected: (out.len() / dof + 1) * dof,
            found: out.len(),
            at: Location::NONE,
        });
    }
    let n = out.len() / dof;
    if n < 2 {
        return Err(TrajectoryError::TooFewSamples { found: n });
    }
    let (t0, tf) = (profile.start_time(), profile.end_time());
    for (i, row) in out.chunks_exact_mut(dof).enumerate() {
        profile.eval_into(uniform_time(t0, tf, n, i), row)?;
    }
    Ok(())
}

/// Uniform samples of one joint: `setpoints[i]` at `times[i]`.
#[cfg(feature = "std")]
#[derive(Clone, Debug, PartialEq)]
pub struct Samples {
    /// The sample times, from the start to the end time.
    pub times: Vec<f64>,
    /// The state at each time.
    pub setpoints: Vec<Setpoint>,
}

/// The most setpoints [`sample`] and [`sample_multi`] allocate: 2²⁴ (16,777,216), counting
/// `n · dof` for `n` samples of `dof` joints.
///
/// With their times that is at most 512 MiB (one joint: 24 bytes per setpoint and 8 per time),
/// enough for 4.6 hours of one joint at 1 kHz or 40 minutes of a seven-joint arm, and an
/// allocation a desktop or a CI runner can make. A larger request, including one whose
/// `n · dof` overflows `usize`, is [`TrajectoryError::TooManySamples`] rather than an
/// allocation that fails (which would abort the process) or takes the machine's memory; so is
/// an allocation below the limit that fails. Sampling into buffers of your own
/// ([`sample_into`], [`sample_multi_into`]) has no limit: sample a longer trajectory in pieces.
pub const MAX_SAMPLES: usize = 1 << 24;

/// Empty vectors with room for `n` times and `n · dof` setpoints, or
/// [`TrajectoryError::TooManySamples`] if that is more than [`MAX_SAMPLES`] setpoints or the
/// allocator cannot provide it (reported, not aborted: `try_reserve_exact`).
#[cfg(feature = "std")]
fn sample_buffers(n: usize, dof: usize) -> Result<(Vec<f64>, Vec<Setpoint>), TrajectoryError> {
    let too_many = TrajectoryError::TooManySamples {
        samples: n,
        dof,
        max: MAX_SAMPLES,
    };
    let total = n
        .checked_mul(dof)
        .filter(|&total| total <= MAX_SAMPLES)
        .ok_or(too_many)?;
    let mut times = Vec::new();
    times.try_reserve_exact(n).map_err(|_| too_many)?;
    let mut setpoints = Vec::new();
    setpoints.try_reserve_exact(total).map_err(|_| too_many)?;
    Ok((times, setpoints))
}

/// Samples `profile` at `n >= 2` equally spaced times from its start to its end time.
///
/// At most [`MAX_SAMPLES`] samples: more is [`TrajectoryError::TooManySamples`].
#[cfg(feature = "std")]
pub fn sample<P: Profile + ?Sized>(profile: &P, n: usize) -> Result<Samples, TrajectoryError> {
    if n < 2 {
        return Err(TrajectoryError::TooFewSamples { found: n });
    }
    let (mut times, mut setpoints) = sample_buffers(n, 1)?;
    let (t0, tf) = (profile.start_time(), profile.end_time());
    times.extend((0..n).map(|i| uniform_time(t0, tf, n, i)));
    setpoints.extend(times.iter().map(|&t| profile.eval(t)));
    Ok(Samples { times, setpoints })
}

/// Uniform samples of several joints.
#[cfg(feature = "std")]
#[derive(Clone, Debug, PartialEq)]
pub struct MultiSamples {
    /// The sample times, from the start to the end time.
    pub times: Vec<f64>,
    /// Number of joints.
    pub dof: usize,
    /// `times.len()` rows of `dof` setpoints: `setpoints[i * dof + j]` is joint `j` at `times[i]`.
    pub setpoints: Vec<Setpoint>,
}

#[cfg(feature = "std")]
impl MultiSamples {
    /// Joint `joint` at sample `i`, or `None` if either index is out of range.
    pub fn get(&self, i: usize, joint: usize) -> Option<Setpoint> {
        if joint >= self.dof {
            return None;
        }
        // Checked: a huge `i` must not wrap around to a sample that exists.
        let k = i.checked_mul(self.dof)?.checked_add(joint)?;
        self.setpoints.get(k).copied()
    }

    /// The `(time, state)` series of one joint (empty if `joint >= dof`).
    pub fn joint(&self, joint: usize) -> impl Iterator<Item = (f64, Setpoint)> + '_ {
        let dof = self.dof;
        let setpoints = if joint < dof {
            &self.setpoints[joint..]
        } else {
            &[]
        };
        self.times
            .iter()
            .copied()
            .zip(setpoints.iter().step_by(dof.max(1)).copied())
    }
}

/// Samples every joint of `profile` at `n >= 2` equally spaced times.
///
/// At most [`MAX_SAMPLES`] setpoints (`n · dof`): more is [`TrajectoryError::TooManySamples`].
#[cfg(feature = "std")]
pub fn sample_multi<M: MultiProfile + ?Sized>(
    profile: &M,
    n: usize,
) -> Result<MultiSamples, TrajectoryError> {
    let dof = profile.dof();
    if dof == 0 {
        return Err(TrajectoryError::NoJoints);
    }
    if n < 2 {
        return Err(TrajectoryError::TooFewSamples { found: n });
    }
    let (mut times, mut setpoints) = sample_buffers(n, dof)?;
    // sample_buffers reserved n · dof setpoints, so this does not reallocate.
    setpoints.resize(n * dof, Setpoint::default());
    sample_multi_into(profile, &mut setpoints)?;
    let (t0, tf) = (profile.start_time(), profile.end_time());
    times.extend((0..n).map(|i| uniform_time(t0, tf, n, i)));
    Ok(MultiSamples {
        times,
        dof,
        setpoints,
    })
}
