//! Closed-form inverse kinematics of six-joint arms whose structure decouples position and
//! orientation (section 4.3): every solution, in a fixed-size array, verified by forward
//! kinematics.
//!
//! The solver is built from the arm's structure ([`ChainRef`]) once — by `robot!` at compile
//! time, whose modules carry it as the constant `IK` — and solving allocates nothing.
//!
//! # The chain
//! `T(q) = P0 Z1(q1) P1 ⋯ Z6(q6) P6` (see [`crate::chain`]), each joint's offset folded into
//! the transform before it, so that q are the joint values as the user gives them.
//!
//! # Arms with a spherical wrist (Pieper's condition)
//! When axes 4, 5, 6 meet in a point c, the wrist joints do not move c: the wrist centre
//! `T c_tool` depends on q1, q2, q3 only.
//!
//! **Inverse position.** With joint 1 revolute, `p` (the wrist centre in the frame joint 1
//! turns) is `Rz(q1) g(q2, q3)`, so `|p|² = |g|²` and `p_z = g_z` do not depend on q1. Sliding
//! the origin along axis 1 to the foot of the common normal of axes 1 and 2 makes them two
//! equations in the projections `X`, `Y` of joint 3's contribution on two perpendicular
//! directions (`a = ` the distance of axes 1 and 2, `b = ` the sine of their angle):
//! `L1(q3) = 2a X`, `L2(q3) = b Y`, `X² + Y² = ρ²(q3)`. Hence, at any twist angles:
//! - axes 1 and 2 intersect (`a = 0`, PUMA 560, Stanford arm): `L1(q3) = 0`, two roots;
//!   then q2 from the second equation (two);
//! - axes 1 and 2 parallel (`b = 0`): `L2(q3) = 0`, two roots; then q2 from the first;
//! - otherwise (an offset between skew axes, e.g. an elbow arm with a shoulder offset):
//!   `(L1/2a)² + (L2/b)² = ρ²`, a trigonometric polynomial of degree 2 in q3 (a quartic; for a
//!   prismatic joint 3 a quartic in its displacement), solved for all its real roots (complex
//!   Aberth–Ehrlich iteration, then Newton polishing on the real equation); q2 then follows
//!   uniquely from `(X, Y)`.
//!
//! q1 is the azimuth that turns `g` onto `p`. Revolute–prismatic–prismatic arms (the
//! cylindrical arm of section 4.2) are solved from the height and the radius. Up to 4 arm
//! solutions. Those of a skew shoulder are refined by a few steps of Newton's method on the
//! wrist centre's position: one that nearly intersects (axes 1 and 2 tens of micrometres
//! apart, as CAD rounds a zero) divides by its offset squared, which the closed form's
//! rounding does not survive (a reachable pose had found no solution within the tolerance
//! below).
//!
//! **Inverse orientation.** With `M = R_3ᵀ R P6ᵀ = Rz(q4) A4 Rz(q5) A5 Rz(q6)`, the direction
//! of axis 6 gives `e_z · M e_z = (A4ᵀ e_z) · Rz(q5) (A5 e_z)`: two q5 (Paden–Kahan's second
//! subproblem, at any wrist twist angles), then q4 and q6 each from one rotation about a
//! known axis. Each arm solution gives two wrist solutions (the wrist flip): at most 8.
//!
//! # Arms with three consecutive parallel axes (UR type)
//! When axes 2, 3, 4 are parallel (direction n) and axes 5 and 6 meet in a point X (the
//! Universal Robots arms), every point's component along n is unchanged by q2, q3, q4. X is
//! fixed in the tool and in the link before joint 5, so its n-component gives q1 (two);
//! the n-component of axis 6's direction gives q5 (two); the tool's orientation then gives q6
//! and `q2 + q3 + q4`; and the position of X, a planar two-link problem, q3 (two) and q2.
//! At most 8.
//!
//! # Degenerate structures: refused
//! A structure that loses a direction at every configuration has, for a reachable pose, a
//! continuum of solutions (or none), which no finite list holds: [`DecoupledIk::from_chain`]
//! refuses it, saying why. Joints 1–3 that cannot move the wrist centre in three independent
//! directions (axes 2 and 3 coaxial, axes 1–3 parallel, the centre on their axes: checked by
//! the rank of their Jacobian of the centre at a few configurations); wrist axes 5 and 6
//! parallel (as 4 and 5 are); two of the UR type's parallel axes 2–4 coinciding, or axis 5
//! parallel to them.
//!
//! # Singular poses: the documented choices
//! - Wrist singularity (axes 4 and 6 aligned): only `q4 ± q6` is determined; the solver sets
//!   **q4 = 0** and gives q6 the whole rotation. For the UR type, when axis 6 is parallel to
//!   axes 2–4, only `ψ = q2 + q3 + q4` and q6 together are; the solver sets **q6 = 0**, or,
//!   where the planar arm cannot then reach (the point where axes 5 and 6 meet is off axis 4,
//!   so ψ moves its target), the value nearest 0 at which it can.
//! - Shoulder singularity (wrist centre on axis 1; for the UR type, that point on axis 1):
//!   q1 is free for the position; the solver sets **q1 = 0**, or, where the wrist cannot then
//!   turn the tool into place (oblique wrist axes reach only some orientations), the value
//!   nearest 0 at which it can.
//! - Wrist centre on axis 2: q2 is free; likewise **q2 = 0** or the value nearest 0 that the
//!   wrist completes.
//!
//! # Near-degenerate equations
//! At a singular pose the subproblems meet double roots: `a cos x + b sin x = c` with `|c|`
//! at `√(a² + b²)` (the wrist's q5, the elbow stretched or folded), a polynomial's pair of
//! roots (a skew shoulder's quartic at the workspace boundary). Rounding splits a double root
//! into two a `√ε ≈ 1.5e-8` apart, or into a complex pair, and neither reproduces the pose
//! to the tolerance below. Each root finder takes a root within rounding of a double one
//! (known from the size of the terms its coefficients came from) as that double root as well
//! as the pair beside it, and a candidate that misses the pose by more than the arithmetic
//! does is polished by Gauss–Newton steps on the pose before it is verified: no solution is
//! lost to rounding. Candidates closer than 1e-7 in every joint are one solution.
//!
//! Every candidate is checked by forward kinematics and dropped unless it reproduces the pose
//! to [`VERIFY_TOLERANCE`]. Revolute joint values are wrapped into (−π, π], then shifted by
//! ±2π into the joint's limits where that makes them fit; solutions outside the limits are
//! returned too (the complete set), [`DecoupledIk::solve_within_limits`] keeps those inside.

use crate::{ChainRef, JointKind, NotSpherical, Rigid};
use core::f64::consts::{PI, TAU};
use nalgebra::{Complex, Isometry3, Matrix3, Matrix6, SVector, Vector2, Vector3, Vector6};
#[cfg(not(feature = "std"))]
use nalgebra::{ComplexField as _, RealField as _};

/// A returned solution reproduces the pose to this: position error in metres and orientation
/// error in radians, each.
pub const VERIFY_TOLERANCE: f64 = 1e-9;

/// A candidate reproducing the pose to this (m, relative to the arm's length scale, and rad)
/// is as exact as the arithmetic makes it and is not polished; one missing it by more, by
/// rounding the closed forms could not avoid, is (`DecoupledIk::polished`).
const POLISHED: f64 = 1e-14;

/// Two solutions closer than this in every joint (rad, or m) are one: a double root leaves a
/// joint uncertain to about √ε ≈ 1.5e-8 (times its conditioning), and two genuine solutions
/// this close are one to any controller.
const SAME_SOLUTION: f64 = 1e-7;

/// The arm geometry [`DecoupledIk`] solves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArmKind {
    /// Spherical wrist; revolute joints 1 and 2 with intersecting axes (Pieper's case), joint
    /// 3 revolute or prismatic. PUMA 560, Stanford arm.
    IntersectingShoulder,
    /// Spherical wrist; revolute joints 1 and 2 with parallel axes.
    ParallelShoulder,
    /// Spherical wrist; revolute joints 1 and 2 with skew axes (an offset between them), at
    /// any angle: the quartic case.
    OffsetShoulder,
    /// Spherical wrist; revolute joint 1 and two prismatic joints (the cylindrical arm).
    Cylindrical,
    /// Axes 2, 3, 4 parallel and axes 5, 6 meeting (Universal Robots).
    ThreeParallel,
}

/// Why an arm has no closed-form solution here.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StructureError {
    /// Kinematic decoupling needs exactly six joints.
    #[error("closed-form IK needs 6 joints; this arm has {dof}")]
    NotSixJoints {
        /// The arm's number of joints.
        dof: usize,
    },
    /// Neither a spherical wrist (why not given) nor three parallel axes 2, 3, 4 followed by
    /// intersecting axes 5 and 6.
    #[error(
        "no spherical wrist ({0}), and not axes 2, 3, 4 parallel with axes 5, 6 meeting: \
         no decoupling to solve in closed form"
    )]
    NoDecoupling(NotSpherical),
    /// The first three joints are not a geometry solved in closed form here (see the module
    /// documentation); `joints` spells their kinds, e.g. `"RPR"`.
    #[error(
        "arm joints 1-3 ({}{}{}) have no closed form here: {reason}",
        joints[0] as char,
        joints[1] as char,
        joints[2] as char
    )]
    UnsupportedArm {
        /// Joint kinds of joints 1..3, `R` or `P`.
        joints: [u8; 3],
        /// What is missing.
        reason: &'static str,
    },
}

/// The constants of a spherical-wrist arm's inverse position problem.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shoulder {
    /// Joints 1 and 2 revolute; the origin slid along axis 1 by `shift` to the foot of the
    /// common normal of axes 1 and 2, where `t1` is axis 2's point.
    Revolute {
        /// How far the origin slid along axis 1.
        shift: f64,
        /// Origin of joint 2's frame, slid.
        t1: Vector3<f64>,
        /// `r1ᵀ t1`: the common normal, in joint 2's frame.
        u: Vector3<f64>,
        /// `r1ᵀ e_z`: axis 1, in joint 2's frame.
        n: Vector3<f64>,
    },
    /// Joint 1 revolute, joints 2 and 3 prismatic: `p = Rz(q1) (f0 + q2 u + q3 v)`, the lead
    /// joint moving along axis 1.
    Cylindrical {
        /// The wrist centre at `q2 = q3 = 0`.
        f0: Vector3<f64>,
        /// Joint 2's direction.
        u: Vector3<f64>,
        /// Joint 3's direction.
        v: Vector3<f64>,
        /// Whether joint 2 is the lead (solved from the height).
        lead_is_2: bool,
    },
}

/// How a [`DecoupledIk`] decouples its arm.
#[doc(hidden)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Method {
    /// A spherical wrist.
    Spherical {
        /// The wrist centre in the tool frame.
        centre_tool: Vector3<f64>,
        /// The wrist centre in the frame joint 3 moves (`P3 c`).
        w: Vector3<f64>,
        /// The inverse position problem.
        shoulder: Shoulder,
    },
    /// Axes 2, 3, 4 parallel, axes 5 and 6 meeting at X.
    ThreeParallel {
        /// The common direction of axes 2–4 in the frame after joint 1.
        n: Vector3<f64>,
        /// X in the tool frame.
        x_tool: Vector3<f64>,
        /// X in the frame after joint 4.
        x4: Vector3<f64>,
        /// X's (constant) component along `n`, in the frame after joint 1.
        kappa: f64,
        /// `±1`: the orientation of axis 4 against axis 2.
        sigma: f64,
        /// Signs of axes 3 and 4 against axis 2.
        sigma3: f64,
        /// `σ3 σ4`.
        sigma34: f64,
        /// The rotation of the frame after joint 4 at `q2 = q3 = q4 = 0`, in joint 2's frame.
        k0: Matrix3<f64>,
    },
}

/// Closed-form inverse kinematics of a six-joint arm (see the module documentation), built
/// once from its structure; [`solve`](Self::solve) allocates nothing.
///
/// The fields are its precomputed constants, public so that `robot!` can emit the solver as
/// a constant; build it with [`DecoupledIk::from_chain`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DecoupledIk {
    #[doc(hidden)]
    pub chain: [Rigid; 7],
    #[doc(hidden)]
    pub prismatic: [bool; 6],
    #[doc(hidden)]
    pub limits: [Option<[f64; 2]>; 6],
    /// Length scale of the arm (1 m plus its constant offsets), for relative thresholds.
    #[doc(hidden)]
    pub scale: f64,
    #[doc(hidden)]
    pub kind: ArmKind,
    #[doc(hidden)]
    pub method: Method,
}

/// At most 8 joint vectors of a six-joint arm, in a fixed-size array (no allocation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solutions {
    q: [SVector<f64, 6>; 8],
    len: usize,
}

/// `x` wrapped into (−π, π].
fn wrap_angle(x: f64) -> f64 {
    let mut y = x - TAU * (x / TAU).round();
    if y <= -PI {
        y += TAU;
    } else if y > PI {
        y -= TAU;
    }
    y
}

impl Solutions {
    /// Most solutions a six-joint arm has here.
    pub const CAPACITY: usize = 8;

    const EMPTY: Solutions = Solutions {
        q: [SVector::<f64, 6>::new(0.0, 0.0, 0.0, 0.0, 0.0, 0.0); 8],
        len: 0,
    };

    /// Number of solutions.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when there is none (the pose is unreachable).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The solutions as a slice.
    pub fn as_slice(&self) -> &[SVector<f64, 6>] {
        &self.q[..self.len]
    }

    /// Iterates over the solutions.
    pub fn iter(&self) -> core::slice::Iter<'_, SVector<f64, 6>> {
        self.as_slice().iter()
    }

    /// The solution nearest to `q` (Euclidean distance with revolute differences wrapped
    /// into (−π, π]), e.g. the current configuration, for continuity along a path.
    pub fn nearest(&self, q: &SVector<f64, 6>, prismatic: &[bool; 6]) -> Option<SVector<f64, 6>> {
        let dist = |s: &SVector<f64, 6>| {
            (0..6)
                .map(|j| {
                    let d = s[j] - q[j];
                    let d = if prismatic[j] { d } else { wrap_angle(d) };
                    d * d
                })
                .sum::<f64>()
        };
        self.iter()
            .min_by(|a, b| dist(a).total_cmp(&dist(b)))
            .copied()
    }

    /// Keeps the solutions for which `keep` is true.
    pub fn retain(&mut self, mut keep: impl FnMut(&SVector<f64, 6>) -> bool) {
        let mut n = 0;
        for i in 0..self.len {
            if keep(&self.q[i]) {
                self.q[n] = self.q[i];
                n += 1;
            }
        }
        self.len = n;
    }

    fn push(&mut self, q: SVector<f64, 6>) {
        if self.len < Self::CAPACITY {
            self.q[self.len] = q;
            self.len += 1;
        }
    }
}

impl core::ops::Index<usize> for Solutions {
    type Output = SVector<f64, 6>;
    fn index(&self, i: usize) -> &SVector<f64, 6> {
        &self.as_slice()[i]
    }
}

impl<'a> IntoIterator for &'a Solutions {
    type Item = &'a SVector<f64, 6>;
    type IntoIter = core::slice::Iter<'a, SVector<f64, 6>>;
    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

/// Up to `N` real values found by a subproblem, in a fixed array.
#[derive(Clone, Copy, Debug)]
struct Roots<const N: usize> {
    x: [f64; N],
    len: usize,
    /// The equation does not depend on the unknown: every value solves it, and the one value
    /// held, 0, stands for them (a joint the pose leaves free).
    free: bool,
}

impl<const N: usize> Roots<N> {
    const NONE: Self = Roots {
        x: [0.0; N],
        len: 0,
        free: false,
    };

    /// Every value: 0 stands for them.
    const FREE: Self = Roots {
        x: [0.0; N],
        len: 1,
        free: true,
    };

    fn one(x: f64) -> Self {
        let mut r = Self::NONE;
        r.push(x);
        r
    }

    fn push(&mut self, x: f64) {
        if self.len < N {
            self.x[self.len] = x;
            self.len += 1;
        }
    }

    fn as_slice(&self) -> &[f64] {
        &self.x[..self.len]
    }
}

/// How well the coefficients of a trigonometric equation are known, relative to the size of
/// the terms they were computed from: 64 ulp. They come from the target pose and the arm's
/// constants through one or two products of rotations (a few ulp each), the pose itself from
/// forward kinematics of six joints (tens of ulp at most).
const EQUATION_ROUNDING: f64 = 64.0 * f64::EPSILON;

/// How far (relative) a right-hand side may lie beyond the range of `a cos x + b sin x` and
/// still be taken as touching it: a pose out of reach by a hair (a description or target
/// rounded to twelve digits) gets the double root, which verification then judges.
const BEYOND_RANGE: f64 = 1e-12;

/// The solutions of `a cos x + b sin x = c`, whose coefficients were computed from terms of
/// magnitude up to `size`, each to [`EQUATION_ROUNDING`].
///
/// With `ρ = √(a² + b²)` and `φ = atan2(b, a)` the roots are `φ ± acos(c/ρ)`. Coefficients
/// known to `η = EQUATION_ROUNDING · size` make `c/ρ` known to about `η/ρ`; near ±1 its two
/// roots `φ ± γ` (`γ ≈ √(2(1 − |c/ρ|))`) are then not told apart from the double root: with
/// `|c/ρ|` within `η/ρ` of 1 the double root (`φ`, or `φ + π`) is returned as well as the two
/// roots (a pose at a singularity has the double root, one beside it the two; the caller
/// verifies each). With `ρ` itself below `η` the equation does not depend on `x`: every `x`
/// solves it when `c` is below `η` too, and `x = 0` is returned to stand for them (a joint the
/// pose leaves free), else none.
fn solve_trig(a: f64, b: f64, c: f64, size: f64) -> Roots<3> {
    let rho = a.hypot(b);
    let noise = EQUATION_ROUNDING * size;
    if !(rho.is_finite() && c.is_finite()) {
        return Roots::NONE;
    }
    if rho <= noise {
        return if c.abs() <= noise {
            Roots::FREE
        } else {
            Roots::NONE
        };
    }
    let base = b.atan2(a);
    let ratio = c / rho;
    let band = noise / rho;
    if ratio.abs() > 1.0 + band.max(BEYOND_RANGE) {
        return Roots::NONE;
    }
    let mut out = Roots::NONE;
    if ratio.abs() >= 1.0 - band {
        out.push(if ratio > 0.0 { base } else { base + PI });
    }
    if ratio.abs() < 1.0 {
        // acos through atan2 keeps full accuracy away from the boundary.
        let gamma = (1.0 - ratio * ratio).sqrt().atan2(ratio);
        out.push(base + gamma);
        out.push(base - gamma);
    }
    out
}

/// `f(x) = c0 + a cos x + b sin x`, from its values at 0, π/2 and π: `(a, b, c0)`.
fn trig_coefficients(f: impl Fn(f64, f64) -> f64) -> (f64, f64, f64) {
    let (f0, f90, f180) = (f(1.0, 0.0), f(0.0, 1.0), f(-1.0, 0.0));
    let c0 = 0.5 * (f0 + f180);
    (0.5 * (f0 - f180), f90 - c0, c0)
}

/// The angles where the affine trigonometric function `f(cos x, sin x)`, made of terms of
/// magnitude up to `size`, vanishes (see [`solve_trig`]).
fn trig_roots(f: impl Fn(f64, f64) -> f64, size: f64) -> Roots<3> {
    let (a, b, c0) = trig_coefficients(f);
    solve_trig(a, b, -c0, size)
}

/// The real roots of the polynomial `Σ c[k] x^k` (degree at most 4, leading coefficients
/// that vanish relative to the others dropped), by Aberth–Ehrlich iteration on the complex
/// roots, those with a negligible imaginary part polished by Newton's method on the real
/// polynomial.
fn real_polynomial_roots(c: [f64; 5], size: f64) -> Roots<6> {
    let scale = c.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if scale == 0.0 || !scale.is_finite() {
        return Roots::NONE;
    }
    let mut degree = 4;
    while degree > 0 && c[degree].abs() <= 1e-13 * scale {
        degree -= 1;
    }
    // The value and its first two derivatives, by Horner's scheme.
    let eval = |x: f64| -> (f64, f64, f64) {
        let (mut v, mut d, mut dd) = (0.0, 0.0, 0.0);
        for k in (0..=degree).rev() {
            dd = dd * x + 2.0 * d;
            d = d * x + v;
            v = v * x + c[k];
        }
        (v, d, dd)
    };
    // The coefficients' own rounding (`size`) and that of the terms at x.
    let noise = |x: f64| {
        let terms = (0..=degree).fold(0.0, |sum, k| sum + (c[k] * x.powi(k as i32)).abs());
        EQUATION_ROUNDING * (size + terms)
    };
    let mut out = Roots::NONE;
    let coefficients: [Complex<f64>; 5] = core::array::from_fn(|k| Complex::new(c[k], 0.0));
    for z in complex_roots(&coefficients, degree).as_slice() {
        // Each complex root's real part, polished on the real polynomial, is a real root if
        // the polynomial vanishes there (a pair a rounding off the axis gives its double root).
        let near_axis = z.im.abs() <= 1e-6 * (1.0 + z.re.abs());
        let small = |x: f64| 1e-16 * (1.0 + x.abs());
        let near = real_roots_near(z.re, near_axis, eval, noise(z.re), small);
        for x in near.into_iter().flatten() {
            if !out
                .as_slice()
                .iter()
                .any(|y| (y - x).abs() <= 1e-9 * (1.0 + x.abs()))
            {
                out.push(x);
            }
        }
    }
    out
}

/// The angles where a trigonometric polynomial of degree 2,
/// `f = a0 + a1 cos x + b1 sin x + a2 cos 2x + b2 sin 2x` (given as a function), vanishes:
/// the roots on the unit circle of `z² f(z)`, `z = e^{ix}`, polished by Newton's method on
/// `f` itself.
fn trig2_roots(f: impl Fn(f64) -> f64, size: f64) -> Roots<6> {
    // The coefficients from five samples (exact for degree 2).
    let samples: [f64; 5] = core::array::from_fn(|k| f(TAU * k as f64 / 5.0));
    let coefficient = |harmonic: f64, sine: bool| -> f64 {
        samples
            .iter()
            .enumerate()
            .map(|(k, v)| {
                let x = harmonic * TAU * k as f64 / 5.0;
                v * if sine { x.sin() } else { x.cos() }
            })
            .sum::<f64>()
            * 0.4
    };
    let a0 = samples.iter().sum::<f64>() / 5.0;
    let (a1, b1) = (coefficient(1.0, false), coefficient(1.0, true));
    let (a2, b2) = (coefficient(2.0, false), coefficient(2.0, true));
    let scale = [a0, a1, b1, a2, b2]
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    let mut out = Roots::NONE;
    if scale == 0.0 || !scale.is_finite() {
        return out;
    }
    if a2.hypot(b2) <= 1e-13 * scale {
        for x in solve_trig(a1, b1, -a0, size).as_slice() {
            out.push(*x);
        }
        return out;
    }
    // z² f(z) = ((a2 − i b2) z⁴ + (a1 − i b1) z³ + 2 a0 z² + (a1 + i b1) z + (a2 + i b2)) / 2.
    let p = [
        Complex::new(a2, b2),
        Complex::new(a1, b1),
        Complex::new(2.0 * a0, 0.0),
        Complex::new(a1, -b1),
        Complex::new(a2, -b2),
    ];
    let value = |x: f64| -> (f64, f64, f64) {
        let (c1, s1) = (x.cos(), x.sin());
        let (c2, s2) = ((2.0 * x).cos(), (2.0 * x).sin());
        (
            a0 + a1 * c1 + b1 * s1 + a2 * c2 + b2 * s2,
            -a1 * s1 + b1 * c1 - 2.0 * a2 * s2 + 2.0 * b2 * c2,
            -a1 * c1 - b1 * s1 - 4.0 * a2 * c2 - 4.0 * b2 * s2,
        )
    };
    let noise = EQUATION_ROUNDING * size;
    for z in complex_roots(&p, 4).as_slice() {
        // Each root's angle, polished on f, is a real root if f vanishes there (a pair of
        // roots a rounding off the unit circle gives its double root).
        let near_circle = (modulus(*z) - 1.0).abs() <= 1e-3;
        let near = real_roots_near(z.im.atan2(z.re), near_circle, value, noise, |_| 1e-16);
        for x in near.into_iter().flatten() {
            let x = wrap_angle(x);
            if !out
                .as_slice()
                .iter()
                .any(|y| wrap_angle(y - x).abs() <= 1e-9)
            {
                out.push(x);
            }
        }
    }
    out
}

/// Real roots of `f` (which gives its value and first two derivatives) from the estimate
/// `x`, known to `noise`: `x` polished by [`newton`], and, where `x` or the polished root is a
/// near-double root — the parabola through it has its extremum within `noise` of zero, so
/// that the pair of roots beside the extremum cannot be told from a double root — the
/// extremum (Newton's method on `f′`, a simple root there) if `f` vanishes there to `noise`:
/// a double root accurate to rounding rather than to √ε. Both are candidates (the noise is a
/// bound: a pair that is told apart is kept as well). The polished root is kept if `x` came
/// from a root `near_axis` of the real line (or of the unit circle) or if `f` vanishes there
/// to `noise` (a complex pair a rounding off the axis); the extremum if `f` vanishes there.
fn real_roots_near(
    x: f64,
    near_axis: bool,
    f: impl Fn(f64) -> (f64, f64, f64),
    noise: f64,
    small: impl Fn(f64) -> f64,
) -> [Option<f64>; 2] {
    let double_root = |x: f64| {
        let (v, d, dd) = f(x);
        if dd != 0.0 && (v - d * d / (2.0 * dd)).abs() <= noise {
            Some(newton(x, |x| (f(x).1, f(x).2), &small))
        } else {
            None
        }
    };
    // Near a double root Newton's first step on f leaps away (f′ nearly vanishes there), so
    // the estimate is tried as one before polishing too.
    let extremum = double_root(x);
    let root = newton(x, |x| (f(x).0, f(x).1), &small);
    let extremum = extremum.or_else(|| double_root(root));
    let vanishes = |x: &f64| x.is_finite() && f(*x).0.abs() <= noise;
    [
        Some(root).filter(|x| x.is_finite() && (near_axis || vanishes(x))),
        extremum.filter(vanishes),
    ]
}

/// A root of `f` polished by Newton's method from `x` (`f` gives the value and the
/// derivative), at most 50 steps, until a step is below `small(x)`.
fn newton(mut x: f64, f: impl Fn(f64) -> (f64, f64), small: impl Fn(f64) -> f64) -> f64 {
    for _ in 0..50 {
        let (v, d) = f(x);
        if d == 0.0 {
            break;
        }
        let step = v / d;
        x -= step;
        if step.abs() <= small(x) {
            break;
        }
    }
    x
}

/// `|z|`.
fn modulus(z: Complex<f64>) -> f64 {
    z.re.hypot(z.im)
}

/// The roots of `Σ c[k] z^k` (degree `degree ≤ 4`), by Aberth–Ehrlich iteration.
fn complex_roots(c: &[Complex<f64>; 5], degree: usize) -> Roots4C {
    let mut out = Roots4C {
        z: [Complex::new(0.0, 0.0); 4],
        len: 0,
    };
    if degree == 0 {
        return out;
    }
    let lead = c[degree];
    // Monic coefficients.
    let a: [Complex<f64>; 5] = core::array::from_fn(|k| {
        if k <= degree {
            c[k] / lead
        } else {
            Complex::new(0.0, 0.0)
        }
    });
    let eval = |z: Complex<f64>| -> (Complex<f64>, Complex<f64>) {
        let (mut v, mut d) = (Complex::new(0.0, 0.0), Complex::new(0.0, 0.0));
        for k in (0..=degree).rev() {
            d = d * z + v;
            v = v * z + a[k];
        }
        (v, d)
    };
    // Starting points on a circle of the roots' size (Cauchy's bound), off the axes.
    let radius = 1.0 + (0..degree).fold(0.0_f64, |m, k| m.max(modulus(a[k])));
    let radius = radius.min(1e6);
    let mut z: [Complex<f64>; 4] = core::array::from_fn(|k| {
        let angle = TAU * k as f64 / degree as f64 + 0.4;
        Complex::new(angle.cos(), angle.sin()) * (0.5 * radius)
    });
    for _ in 0..200 {
        let mut moved = 0.0_f64;
        for i in 0..degree {
            let (v, d) = eval(z[i]);
            if modulus(v) == 0.0 {
                continue;
            }
            let ratio = v / d;
            let mut sum = Complex::new(0.0, 0.0);
            for j in 0..degree {
                if j != i {
                    let diff = z[i] - z[j];
                    if modulus(diff) > 0.0 {
                        sum += Complex::new(1.0, 0.0) / diff;
                    }
                }
            }
            let step = ratio / (Complex::new(1.0, 0.0) - ratio * sum);
            if step.re.is_finite() && step.im.is_finite() {
                z[i] -= step;
                moved = moved.max(modulus(step) / (1.0 + modulus(z[i])));
            }
        }
        if moved < 1e-15 {
            break;
        }
    }
    for zi in &z[..degree] {
        out.z[out.len] = *zi;
        out.len += 1;
    }
    out
}

/// Up to four complex roots.
struct Roots4C {
    z: [Complex<f64>; 4],
    len: usize,
}

impl Roots4C {
    fn as_slice(&self) -> &[Complex<f64>] {
        &self.z[..self.len]
    }
}

/// Newton-type refinement: `attempt(q)` gives the error at `q` and the next iterate (none when
/// the step cannot be taken); an iterate is accepted while the error falls (a NaN is no fall),
/// at most 8 times, stopping once the error is at most `done`.
fn refine<Q: Copy>(mut q: Q, done: f64, attempt: impl Fn(&Q) -> (f64, Option<Q>)) -> Q {
    let (mut error, mut next) = attempt(&q);
    for _ in 0..8 {
        if error <= done {
            break;
        }
        let Some(candidate) = next else {
            break;
        };
        let (e, n) = attempt(&candidate);
        if e.partial_cmp(&error) != Some(core::cmp::Ordering::Less) {
            break;
        }
        (q, error, next) = (candidate, e, n);
    }
    q
}

/// `[Δp; Δθ]` taking `a` to `b`: the difference of origins and the rotation vector of
/// `R_b R_aᵀ`, both in the outer frame (the angle from `atan2(|v|, (tr R − 1)/2)`, `v` the
/// axial vector of its skew part, accurate at small angles).
fn pose_difference(a: &Rigid, b: &Rigid) -> Vector6<f64> {
    let r = b.r * a.r.transpose();
    let v = 0.5
        * Vector3::new(
            r[(2, 1)] - r[(1, 2)],
            r[(0, 2)] - r[(2, 0)],
            r[(1, 0)] - r[(0, 1)],
        );
    let sin = v.norm();
    let angle = sin.atan2(0.5 * (r.trace() - 1.0));
    let w = if sin > 0.0 { v * (angle / sin) } else { v };
    let dp = b.p - a.p;
    Vector6::new(dp.x, dp.y, dp.z, w.x, w.y, w.z)
}

/// Position error and rotation angle between two frames; the angle from
/// `‖Ra − Rb‖_F = 2√2 sin(θ/2)`, accurate for small angles.
fn frame_error(a: &Rigid, b: &Rigid) -> (f64, f64) {
    let chord = (a.r - b.r).norm() / (2.0 * core::f64::consts::SQRT_2);
    ((a.p - b.p).norm(), 2.0 * chord.min(1.0).asin())
}

/// Whether two axes whose directions have the cosine `cos` are parallel or anti-parallel: the
/// cosine within 1e-12 of ±1.
fn parallel(cos: f64) -> bool {
    (cos.abs() - 1.0).abs() <= 1e-12
}

fn rz(q: f64) -> Matrix3<f64> {
    let (s, c) = q.sin_cos();
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// The angle of the rotation about z that a rotation matrix is (its xy block).
fn z_angle(m: &Matrix3<f64>) -> f64 {
    m[(1, 0)].atan2(m[(0, 0)])
}

/// The angle turning the xy part of `from` onto that of `to` about z, and whether it is free.
/// With `to` on the axis (relative to `tiny`) every angle does: 0 stands for them (`from`,
/// made of roots that a singular pose leaves accurate only to √ε, may miss the axis by more;
/// polishing on the pose settles it); `None` when `from` is on the axis and `to` is not.
fn azimuth(to: &Vector3<f64>, from: &Vector3<f64>, tiny: f64) -> Option<(f64, bool)> {
    let (a, b) = (to.xy().norm(), from.xy().norm());
    if a < tiny {
        Some((0.0, true))
    } else if b < tiny {
        None
    } else {
        Some((to.y.atan2(to.x) - from.y.atan2(from.x), false))
    }
}

/// The value nearest 0 of a joint the position leaves free at which `g` (affine in the
/// joint's cosine and sine, made of terms of magnitude `size`) lies in `[lo, hi]`, where the
/// rest of the arm can then complete the pose: 0 when it does there, else the nearest value
/// where `g` reaches `lo` or `hi` (the completing joint then at a double root); 0 when none.
fn nearest_within(g: impl Fn(f64, f64) -> f64, lo: f64, hi: f64, size: f64) -> f64 {
    if (lo..=hi).contains(&g(1.0, 0.0)) {
        return 0.0;
    }
    let (a, b, c0) = trig_coefficients(g);
    let mut nearest: Option<f64> = None;
    for bound in [lo, hi] {
        for &x in solve_trig(a, b, bound - c0, size).as_slice() {
            let x = wrap_angle(x);
            if nearest.is_none_or(|y| x.abs() < y.abs()) {
                nearest = Some(x);
            }
        }
    }
    nearest.unwrap_or(0.0)
}

fn kinds(prismatic: &[bool; 6]) -> [u8; 3] {
    core::array::from_fn(|i| if prismatic[i] { b'P' } else { b'R' })
}

impl DecoupledIk {
    /// Builds the solver from a validated description.
    #[cfg(feature = "std")]
    pub fn from_model(model: impl Into<crate::JointChain>) -> Result<DecoupledIk, StructureError> {
        Self::from_chain(model.into().view())
    }

    /// Builds the solver from a kinematic structure (an arm's: `Arm::chain`, a generated
    /// module's `CHAIN`).
    pub fn from_chain(chain: ChainRef<'_>) -> Result<DecoupledIk, StructureError> {
        let dof = chain.dof();
        if dof != 6 {
            return Err(StructureError::NotSixJoints { dof });
        }
        // T(q) = P0 Z1(q1 + o1) P1 ⋯: fold each offset into the transform before its joint,
        // `P_k Z_{k+1}(o)`, so that the solver's joint values are the user's.
        let frames: [Rigid; 7] = core::array::from_fn(|k| {
            let p = &chain.placements[k];
            if k < 6 {
                Rigid::from_frame(&p.compose(&chain.bodies[k].motion(0.0)))
            } else {
                Rigid::from_frame(p)
            }
        });
        let prismatic = core::array::from_fn(|i| chain.bodies[i].joint == JointKind::Prismatic);
        let limits = core::array::from_fn(|i| chain.bodies[i].limits);
        let scale = 1.0 + frames.iter().map(|f| f.p.norm()).sum::<f64>();
        let base = DecoupledIk {
            chain: frames,
            prismatic,
            limits,
            scale,
            kind: ArmKind::IntersectingShoulder,
            method: Method::Spherical {
                centre_tool: Vector3::zeros(),
                w: Vector3::zeros(),
                shoulder: Shoulder::Cylindrical {
                    f0: Vector3::zeros(),
                    u: Vector3::zeros(),
                    v: Vector3::zeros(),
                    lead_is_2: true,
                },
            },
        };
        match chain.spherical_wrist() {
            Ok(wrist) => base.spherical(Vector3::from(wrist.centre)),
            Err(why) => match base.three_parallel() {
                Some(ik) => match ik.three_parallel_degenerate() {
                    Some(reason) => Err(ik.unsupported(reason)),
                    None => Ok(ik),
                },
                None => Err(StructureError::NoDecoupling(why)),
            },
        }
    }

    fn unsupported(&self, reason: &'static str) -> StructureError {
        StructureError::UnsupportedArm {
            joints: kinds(&self.prismatic),
            reason,
        }
    }

    /// The solver of a spherical-wrist arm with wrist centre `centre` in joint frame 4.
    fn spherical(mut self, centre: Vector3<f64>) -> Result<DecoupledIk, StructureError> {
        let c = &self.chain;
        let tol = 1e-9 * self.scale;
        // The tool in the frame of joint 4 at q4 = q5 = q6 = 0.
        let wrist_to_tool = c[4].compose(&c[5]).compose(&c[6]);
        let centre_tool = wrist_to_tool.inverse().point(&centre);
        let w = c[3].point(&centre);
        if self.prismatic[0] {
            return Err(self.unsupported("joint 1 must be revolute"));
        }
        if !self.places_the_wrist_centre(&w) {
            return Err(self.unsupported(
                "they cannot move the wrist centre in three independent directions (two of \
                 their axes coincide, all three are parallel, or the centre lies on their axes): \
                 the arm is redundant or degenerate, with a continuum of solutions or none",
            ));
        }
        let (p1, p2) = (c[1], c[2]);
        let (shoulder, kind) = if !self.prismatic[1] {
            // Axis 2 in the frame joint 1 turns: through p1.p along n2. Slide the origin to
            // the foot of the common normal of axes 1 and 2.
            let n2 = p1.r.column(2).into_owned();
            let sin = n2.xy().norm();
            let shift = if sin > 1e-12 {
                // The common normal meets axis 1 where p1.p + t n2 is closest to it.
                let t = -(p1.p.xy().dot(&n2.xy())) / (sin * sin);
                p1.p.z + t * n2.z
            } else {
                0.0
            };
            let t1 = p1.p - Vector3::z() * shift;
            let u = p1.r.transpose() * t1;
            let n = p1.r.transpose() * Vector3::z();
            let (a, b) = (u.xy().norm(), n.xy().norm());
            // Joint 3 must move the wrist centre's distance from axis 2 (or along it).
            let moves = if self.prismatic[2] {
                (p2.r.column(2).into_owned()).norm() > 0.0
            } else {
                w.xy().norm() > tol
            };
            if !moves {
                return Err(
                    self.unsupported("joint 3 does not move the wrist centre (it lies on axis 3)")
                );
            }
            let kind = match (a > tol, b > 1e-12) {
                (false, true) => ArmKind::IntersectingShoulder,
                (true, false) => ArmKind::ParallelShoulder,
                (true, true) => ArmKind::OffsetShoulder,
                (false, false) => return Err(self.unsupported("axes 1 and 2 coincide")),
            };
            (Shoulder::Revolute { shift, t1, u, n }, kind)
        } else if self.prismatic[2] {
            let u = p1.r.column(2).into_owned();
            let v = p1.r * p2.r.column(2);
            let f0 = p1.p + p1.r * (p2.p + p2.r * w);
            let lead_is_2 = u.z.abs() >= v.z.abs();
            let (lead, other) = if lead_is_2 { (u, v) } else { (v, u) };
            if lead.z.abs() < 1e-9 {
                return Err(self.unsupported("neither prismatic joint moves along axis 1"));
            }
            if (other.xy() - lead.xy() * (other.z / lead.z)).norm() < 1e-9 {
                return Err(
                    self.unsupported("the prismatic joints do not change the distance from axis 1")
                );
            }
            (
                Shoulder::Cylindrical {
                    f0,
                    u,
                    v,
                    lead_is_2,
                },
                ArmKind::Cylindrical,
            )
        } else {
            return Err(
                self.unsupported("a prismatic joint 2 needs a prismatic joint 3 (cylindrical arm)")
            );
        };
        self.kind = kind;
        self.method = Method::Spherical {
            centre_tool,
            w,
            shoulder,
        };
        Ok(self)
    }

    /// Whether joints 1–3 move the wrist centre (`w` in the frame joint 3 moves) in three
    /// independent directions: the determinant of their 3×3 Jacobian of its position, each
    /// column made a unit vector (a column shorter than a billionth of the arm's length scale
    /// counts as none), is not zero at every one of a few fixed configurations. A structure
    /// that fails (axes 2 and 3 coaxial, axes 1–3 parallel, the centre on every axis) loses a
    /// direction everywhere, and its pose has a continuum of solutions or none: no closed form
    /// here.
    fn places_the_wrist_centre(&self, w: &Vector3<f64>) -> bool {
        const SAMPLES: [[f64; 3]; 4] = [
            [0.7, -1.1, 0.4],
            [-2.3, 0.5, 1.9],
            [1.3, 2.1, -0.8],
            [-0.4, -2.7, 2.6],
        ];
        SAMPLES.iter().any(|q| {
            let (_, jacobian) = self.wrist_centre(w, q);
            let columns: [Vector3<f64>; 3] = core::array::from_fn(|i| {
                let c = jacobian.column(i).into_owned();
                let norm = c.norm();
                if norm > 1e-9 * self.scale {
                    c / norm
                } else {
                    Vector3::zeros()
                }
            });
            Matrix3::from_columns(&columns).determinant().abs() > 1e-9
        })
    }

    /// The wrist centre (`w` in the frame joint 3 moves) at `(q1, q2, q3)`, in the frame joint
    /// 1 turns, and its Jacobian over the three joints.
    fn wrist_centre(&self, w: &Vector3<f64>, q: &[f64; 3]) -> (Vector3<f64>, Matrix3<f64>) {
        let mut f = Rigid::IDENTITY;
        let mut axes = [(Vector3::zeros(), Vector3::zeros()); 3];
        for i in 0..3 {
            if i > 0 {
                f = f.compose(&self.chain[i]);
            }
            axes[i] = (f.r.column(2).into_owned(), f.p);
            f.apply_joint(self.joint(i), q[i]);
        }
        let centre = f.point(w);
        let columns: [Vector3<f64>; 3] = core::array::from_fn(|i| {
            let (z, o) = axes[i];
            if self.prismatic[i] {
                z
            } else {
                z.cross(&(centre - o))
            }
        });
        (centre, Matrix3::from_columns(&columns))
    }

    /// `q` refined by Gauss–Newton steps on the whole pose ([`refine`]; the pseudo-inverse of
    /// the arm's Jacobian, singular values below 1e-12 of the largest dropped, so that a
    /// singular configuration moves least along the directions the pose leaves free). A
    /// singular pose leaves a double root's joint accurate to √ε only, and the rest of the
    /// candidate inherits the error; two or three steps restore full precision.
    fn polished(&self, q: SVector<f64, 6>, target: &Rigid) -> SVector<f64, 6> {
        refine(q, POLISHED, |q| {
            let (frame, jacobian) = self.fk_and_jacobian(q);
            let error = pose_difference(&frame, target);
            let svd = jacobian.svd(true, true);
            let cutoff = 1e-12 * svd.singular_values.max();
            (
                error.norm(),
                svd.solve(&error, cutoff).ok().map(|step| q + step),
            )
        })
    }

    /// `q` refined by Newton's method on the wrist centre's position `p` (in the frame joint 1
    /// turns, [`refine`]): a skew shoulder's closed form divides by its offset squared, which
    /// the rounding of its inputs does not survive when the offset is small (CAD's tens of
    /// micrometres for a zero), leaving q2 far from the root; the pose's Jacobian is then too
    /// ill-conditioned for [`polished`](Self::polished), the position's is not.
    fn polished_arm(&self, w: &Vector3<f64>, p: &Vector3<f64>, q: [f64; 3]) -> [f64; 3] {
        refine(q, 1e-14 * self.scale, |q| {
            let (centre, jacobian) = self.wrist_centre(w, q);
            let error = centre - p;
            let next = jacobian
                .lu()
                .solve(&error)
                .map(|step| core::array::from_fn(|i| q[i] - step[i]));
            (error.norm(), next)
        })
    }

    /// Why an arm with axes 2, 3, 4 parallel loses a direction at every configuration, if it
    /// does: joints 2–4 are a planar arm of two links, the distances between axes 2 and 3 and
    /// between axes 3 and 4 (in the frames joints 2 and 3 move), and a link of length zero
    /// (two coaxial joints) leaves a continuum of solutions or none; so does axis 5 parallel
    /// to them (four parallel axes: the tool turns about two directions only).
    fn three_parallel_degenerate(&self) -> Option<&'static str> {
        let c = &self.chain;
        if c[2].p.xy().norm().min(c[3].p.xy().norm()) <= 1e-9 * self.scale {
            Some(
                "axes 2, 3, 4 are parallel but two of them coincide: the planar arm they make \
                 has a link of length zero (a continuum of solutions or none)",
            )
        } else if parallel((c[4].r * Vector3::z()).z) {
            Some(
                "axes 2, 3, 4 and 5 are parallel: the tool turns about two directions only (a \
                 continuum of solutions or none)",
            )
        } else {
            None
        }
    }

    /// The solver of an arm with axes 2, 3, 4 parallel and axes 5, 6 meeting, if it is one.
    fn three_parallel(mut self) -> Option<DecoupledIk> {
        if self.prismatic.iter().any(|p| *p) {
            return None;
        }
        let c = self.chain;
        let z = Vector3::z();
        // Axes 3 and 4 parallel to axis 2 (up to sign), in their predecessors' frames.
        let s3 = (c[2].r * z).z;
        let s4 = (c[3].r * z).z;
        if !(parallel(s3) && parallel(s4)) {
            return None;
        }
        let n = c[1].r * z;
        // Axis 1 must not be parallel to them, or q1 would not change X's n-component.
        if n.xy().norm() < 1e-9 {
            return None;
        }
        // X: where axes 5 and 6 meet, in the frame after joint 4 (axis 5 is its z axis
        // through c[4].p, axis 6 is c[4]·c[5]'s).
        let f6 = c[4].compose(&c[5]);
        let (o5, d5) = (c[4].p, c[4].r * z);
        let (o6, d6) = (f6.p, f6.r * z);
        let w0 = o5 - o6;
        let k = d5.dot(&d6);
        let denom = 1.0 - k * k;
        if denom < 1e-12 {
            return None;
        }
        let (d, e) = (d5.dot(&w0), d6.dot(&w0));
        let x5 = o5 + d5 * ((k * e - d) / denom);
        let x6 = o6 + d6 * ((e - k * d) / denom);
        if (x5 - x6).norm() > 1e-9 * self.scale {
            return None;
        }
        let x4 = x5;
        let x_tool = f6.compose(&c[6]).inverse().point(&x4);
        // The frame after joint 4 at q2 = q3 = q4 = 0, in the frame after joint 1.
        let b0 = c[1].compose(&c[2]).compose(&c[3]);
        let kappa = n.dot(&b0.point(&x4));
        let sigma = (b0.r.transpose() * n).z;
        self.kind = ArmKind::ThreeParallel;
        self.method = Method::ThreeParallel {
            n,
            x_tool,
            x4,
            kappa,
            sigma,
            sigma3: s3.signum(),
            sigma34: (s3 * s4).signum(),
            k0: c[1].r.transpose() * b0.r,
        };
        Some(self)
    }

    /// The arm geometry recognised.
    pub fn arm_kind(&self) -> ArmKind {
        self.kind
    }

    /// The wrist centre (the point where axes 4, 5, 6 meet) in the tool frame, for arms with
    /// a spherical wrist.
    pub fn wrist_centre_in_tool(&self) -> Option<Vector3<f64>> {
        match self.method {
            Method::Spherical { centre_tool, .. } => Some(centre_tool),
            Method::ThreeParallel { .. } => None,
        }
    }

    /// Which joints are prismatic.
    pub fn prismatic(&self) -> [bool; 6] {
        self.prismatic
    }

    fn joint(&self, i: usize) -> JointKind {
        if self.prismatic[i] {
            JointKind::Prismatic
        } else {
            JointKind::Revolute
        }
    }

    /// Forward kinematics of the chain the solver works with (the same pose as the arm's).
    pub fn fk(&self, q: &SVector<f64, 6>) -> Isometry3<f64> {
        self.fk_frame(q).to_isometry()
    }

    fn fk_frame(&self, q: &SVector<f64, 6>) -> Rigid {
        self.walk(q, |_, _| {})
    }

    /// `T(q)`, calling `at_joint(i, frame)` with the frame joint `i` moves (its z axis the
    /// joint's, in the world) on the way.
    fn walk(&self, q: &SVector<f64, 6>, mut at_joint: impl FnMut(usize, &Rigid)) -> Rigid {
        let mut f = self.chain[0];
        for i in 0..6 {
            at_joint(i, &f);
            f = f.moved(self.joint(i), q[i]).compose(&self.chain[i + 1]);
        }
        f
    }

    /// `T(q)` and the geometric Jacobian of the tool's origin, world axes, rows `[v; ω]`.
    fn fk_and_jacobian(&self, q: &SVector<f64, 6>) -> (Rigid, Matrix6<f64>) {
        let mut axes = [(Vector3::zeros(), Vector3::zeros()); 6];
        let tool = self.walk(q, |i, f| axes[i] = (f.r.column(2).into_owned(), f.p));
        let mut jacobian = Matrix6::zeros();
        for (i, (z, o)) in axes.iter().enumerate() {
            let (v, w) = if self.prismatic[i] {
                (*z, Vector3::zeros())
            } else {
                (z.cross(&(tool.p - o)), *z)
            };
            jacobian.fixed_view_mut::<3, 1>(0, i).copy_from(&v);
            jacobian.fixed_view_mut::<3, 1>(3, i).copy_from(&w);
        }
        (tool, jacobian)
    }

    /// The frame after joint 3 (`P0 Z1 P1 Z2 P2 Z3`), in the world.
    fn arm_frame(&self, arm: &[f64; 3]) -> Rigid {
        let mut g = self.chain[0];
        for (i, &qi) in arm.iter().enumerate() {
            g = g.moved(self.joint(i), qi);
            if i < 2 {
                g = g.compose(&self.chain[i + 1]);
            }
        }
        g
    }

    /// Every joint vector that puts the tool at `pose` (at most 8), each checked by forward
    /// kinematics to [`VERIFY_TOLERANCE`]. Empty when the pose is out of reach or not finite.
    pub fn solve(&self, pose: &Isometry3<f64>) -> Solutions {
        let mut out = Solutions::EMPTY;
        let target = Rigid::from_isometry(pose);
        if !(target.r.iter().all(|x| x.is_finite()) && target.p.iter().all(|x| x.is_finite())) {
            return out;
        }
        match self.method {
            Method::Spherical {
                centre_tool,
                w,
                shoulder,
            } => {
                let p = self.chain[0].inverse().point(&target.point(&centre_tool));
                let arm = self.solve_position(&shoulder, &w, &p);
                for a in arm.as_slice() {
                    self.solve_wrist(a, &target, &mut out);
                }
            }
            Method::ThreeParallel { .. } => self.solve_three_parallel(&target, &mut out),
        }
        out
    }

    /// The solutions of [`solve`](Self::solve) that respect every joint limit.
    pub fn solve_within_limits(&self, pose: &Isometry3<f64>) -> Solutions {
        let mut s = self.solve(pose);
        s.retain(|q| {
            (0..6).all(|j| {
                self.limits[j].is_none_or(|[lo, hi]| q[j] >= lo - 1e-12 && q[j] <= hi + 1e-12)
            })
        });
        s
    }

    /// Up to 4 `(q1, q2, q3)` putting the wrist centre at `p` (in the frame joint 1 turns).
    fn solve_position(
        &self,
        shoulder: &Shoulder,
        w: &Vector3<f64>,
        p: &Vector3<f64>,
    ) -> ArmSolutions {
        let mut out = ArmSolutions::NONE;
        let mut push = |q: [f64; 3], free: [bool; 3]| out.push(q, free);
        let tiny = 1e-12 * self.scale;
        let (length, area) = (self.scale, self.scale * self.scale);
        match *shoulder {
            Shoulder::Revolute { shift, t1, u, n } => {
                let joint3 = self.joint(2);
                let p2 = self.chain[2];
                // h(q3): the wrist centre in the frame joint 2 turns.
                let h = |q3: f64| p2.moved(joint3, q3).point(w);
                let ps = p - Vector3::z() * shift;
                let (a, b) = (u.xy().norm(), n.xy().norm());
                // E1: L1 = 2 u·Rz(q2) h − 2 u_z h_z ... written as the q2-free part:
                let l1 = |h: &Vector3<f64>| {
                    ps.norm_squared() - h.norm_squared() - t1.norm_squared() - 2.0 * u.z * h.z
                };
                let l2 = |h: &Vector3<f64>| ps.z - t1.z - n.z * h.z;
                // Given q3, q2 from `k · Rz(q2) h = rhs` for a direction k in the xy plane, of
                // terms of magnitude `size`; with the wrist centre on axis 2 the equation does
                // not depend on q2, which is free (0) where it holds.
                let q2_from = |k: &Vector2<f64>, h: &Vector3<f64>, rhs: f64, size: f64| {
                    let (hx, hy) = (h.x, h.y);
                    solve_trig(k.x * hx + k.y * hy, k.y * hx - k.x * hy, rhs, size)
                };
                let q3s = match self.kind {
                    ArmKind::IntersectingShoulder => self.joint3_roots(&|q3| l1(&h(q3)), area),
                    ArmKind::ParallelShoulder => self.joint3_roots(&|q3| l2(&h(q3)), length),
                    _ => {
                        let residual = |q3: f64| {
                            let hv = h(q3);
                            let x = l1(&hv) / (2.0 * a);
                            let y = l2(&hv) / b;
                            x * x + y * y - hv.xy().norm_squared()
                        };
                        // Terms of the size of X², Y² and |h|².
                        let size = (area / a).powi(2) + (length / b).powi(2) + area;
                        if self.prismatic[2] {
                            quartic_in_displacement(&residual, size)
                        } else {
                            trig2_roots(residual, size)
                        }
                    }
                };
                for &q3 in q3s.as_slice() {
                    let hv = h(q3);
                    let q2s = match self.kind {
                        ArmKind::IntersectingShoulder => q2_from(&n.xy(), &hv, l2(&hv), length),
                        ArmKind::ParallelShoulder => q2_from(&u.xy(), &hv, 0.5 * l1(&hv), area),
                        _ => {
                            // Rz(q2) h_xy = X û + Y n̂ (û ⟂ n̂ in the plane).
                            let (x, y) = (l1(&hv) / (2.0 * a), l2(&hv) / b);
                            let target = u.xy() * (x / a) + n.xy() * (y / b);
                            if hv.xy().norm() < tiny {
                                Roots::<3>::FREE
                            } else {
                                Roots::one(target.y.atan2(target.x) - hv.y.atan2(hv.x))
                            }
                        }
                    };
                    for &q2 in q2s.as_slice() {
                        let g = self.chain[1].moved(JointKind::Revolute, q2).point(&hv);
                        if let Some((q1, free1)) = azimuth(p, &g, tiny) {
                            let q = [q1, q2, q3];
                            // q2 and q3 went through X/a and Y/b: refined where a or b (the
                            // shoulder's offset, the sine of its angle) is small.
                            let q = match self.kind {
                                ArmKind::OffsetShoulder => self.polished_arm(w, p, q),
                                _ => q,
                            };
                            push(q, [free1, q2s.free, false]);
                        }
                    }
                }
            }
            Shoulder::Cylindrical {
                f0,
                u,
                v,
                lead_is_2,
            } => {
                let (lead, other) = if lead_is_2 { (u, v) } else { (v, u) };
                // Height: q_lead = (p_z − f0_z − q_other other_z) / lead_z; radius: quadratic.
                let base = f0 + lead * ((p.z - f0.z) / lead.z);
                let dir = other - lead * (other.z / lead.z);
                let (a, b) = (base.xy(), dir.xy());
                let bb = b.norm_squared();
                let roots = real_polynomial_roots(
                    [
                        a.norm_squared() - p.xy().norm_squared(),
                        2.0 * a.dot(&b),
                        bb,
                        0.0,
                        0.0,
                    ],
                    area,
                );
                for &q_other in roots.as_slice() {
                    let q_lead = (p.z - f0.z - q_other * other.z) / lead.z;
                    let (q2, q3) = if lead_is_2 {
                        (q_lead, q_other)
                    } else {
                        (q_other, q_lead)
                    };
                    let f = f0 + u * q2 + v * q3;
                    if let Some((q1, free1)) = azimuth(p, &f, tiny) {
                        push([q1, q2, q3], [free1, false, false]);
                    }
                }
            }
        }
        out
    }

    /// The values of joint 3 where `f` (affine in its cosine and sine, or quadratic in its
    /// displacement; of terms of magnitude `size`) vanishes.
    fn joint3_roots(&self, f: &dyn Fn(f64) -> f64, size: f64) -> Roots<6> {
        let mut out = Roots::NONE;
        if self.prismatic[2] {
            // f is quadratic in the displacement: from three samples.
            let (f0, f1, fm) = (f(0.0), f(1.0), f(-1.0));
            let c2 = 0.5 * (f1 + fm) - f0;
            let c1 = 0.5 * (f1 - fm);
            for x in real_polynomial_roots([f0, c1, c2, 0.0, 0.0], size).as_slice() {
                out.push(*x);
            }
        } else {
            for x in trig_roots(|c, s| f(s.atan2(c)), size).as_slice() {
                out.push(*x);
            }
        }
        out
    }

    /// Appends the wrist solutions of one arm solution.
    ///
    /// A joint the position leaves free (q1 with the wrist centre on axis 1, q2 on axis 2) turns
    /// the frame the wrist starts from: it takes the value nearest 0 at which the wrist can
    /// point axis 6 as the pose asks (any value for a wrist whose axes are at right angles).
    fn solve_wrist(&self, arm: &ArmSolution, target: &Rigid, out: &mut Solutions) {
        let (a4, a5, a6) = (self.chain[4].r, self.chain[5].r, self.chain[6].r);
        let a = a5.column(2).into_owned();
        let k4 = a4.transpose() * Vector3::z();
        let alpha = k4.x * a.x + k4.y * a.y;
        let beta = k4.y * a.x - k4.x * a.y;
        // M = Rz(q4) A4 Rz(q5) A5 Rz(q6), and the q5 equation's right-hand side.
        let m_of = |q: &[f64; 3]| {
            self.arm_frame(q).compose(&self.chain[3]).r.transpose() * target.r * a6.transpose()
        };
        let rhs = |m: &Matrix3<f64>| m[(2, 2)] - k4.z * a.z;
        let mut q = arm.q;
        for j in (0..2).filter(|&j| arm.free[j]) {
            let rho = alpha.hypot(beta);
            q[j] = nearest_within(
                |c, s| {
                    let mut at = q;
                    at[j] = s.atan2(c);
                    rhs(&m_of(&at))
                },
                -rho,
                rho,
                1.0,
            );
        }
        let arm = q;
        let m = m_of(&arm);
        let b = m.column(2).into_owned();
        for &q5 in solve_trig(alpha, beta, rhs(&m), 1.0).as_slice() {
            let v = a4 * rz(q5) * a;
            // Rz(q4) v = b; at the wrist singularity (axis 6 along axis 4) q4 = 0.
            let q4 = if b.xy().norm() < 1e-9 || v.xy().norm() < 1e-9 {
                0.0
            } else {
                b.y.atan2(b.x) - v.y.atan2(v.x)
            };
            let q6 = z_angle(&((rz(q4) * a4 * rz(q5) * a5).transpose() * m));
            self.push_verified([arm[0], arm[1], arm[2], q4, q5, q6], target, out);
        }
    }

    fn solve_three_parallel(&self, target: &Rigid, out: &mut Solutions) {
        let Method::ThreeParallel {
            n,
            x_tool,
            x4,
            kappa,
            sigma,
            sigma3,
            sigma34,
            k0,
        } = self.method
        else {
            return;
        };
        let c = &self.chain;
        let tiny = 1e-12 * self.scale;
        let area = self.scale * self.scale;
        let z = Vector3::z();
        let x_root = c[0].inverse().point(&target.point(&x_tool));
        // q1: (Rz(q1) n) · X = κ.
        let alpha = n.x * x_root.x + n.y * x_root.y;
        let beta = n.x * x_root.y - n.y * x_root.x;
        let axis6 = c[0].r.transpose() * target.r * c[6].r.transpose() * z;
        let (t1, t2, t3) = (c[1].p, c[2].p, c[3].p);
        // q5: σ e_z · A4 Rz(q5) v6 = n · axis 6 (both in the frame after joint 1).
        let v6 = c[5].r * z;
        let k4 = c[4].r.transpose() * z;
        let a5 = k4.x * v6.x + k4.y * v6.y;
        let b5 = k4.y * v6.x - k4.x * v6.y;
        let q5_rhs = |q1: f64| sigma * n.dot(&(rz(q1).transpose() * axis6)) - k4.z * v6.z;
        let q1s = solve_trig(alpha, beta, kappa - n.z * x_root.z, self.scale);
        for &q1 in q1s.as_slice() {
            // X on axis 1 leaves q1 free: the value nearest 0 at which q5 can align axis 6.
            let q1 = if q1s.free {
                let rho = a5.hypot(b5);
                nearest_within(|cc, ss| q5_rhs(ss.atan2(cc)), -rho, rho, 1.0)
            } else {
                q1
            };
            let r0 = rz(q1);
            let x1 = r0.transpose() * x_root;
            for &q5 in solve_trig(a5, b5, q5_rhs(q1), 1.0).as_slice() {
                // R1ᵀ M = Rz(ψ) G Rz(q6) with G = K0 A4 Rz(q5) A5.
                let m = c[1].r.transpose()
                    * r0.transpose()
                    * c[0].r.transpose()
                    * target.r
                    * c[6].r.transpose();
                let g = k0 * c[4].r * rz(q5) * c[5].r;
                let (g0, g1) = (g[(2, 0)], g[(2, 1)]);
                let (m0, m1) = (m[(2, 0)], m[(2, 1)]);
                let psi_of = |q6: f64| z_angle(&(m * rz(q6).transpose() * g.transpose()));
                // X's position fixes the origin of the frame after joint 4: V = Rz(q2) s(q3).
                let v_of = |q6: f64| c[1].r.transpose() * (x1 - t1) - rz(psi_of(q6)) * k0 * x4;
                let s = |q3: f64| t2 + c[2].r * rz(q3) * t3;
                let q3_roots = |v: &Vector3<f64>| {
                    trig_roots(
                        |cc, ss| s(ss.atan2(cc)).xy().norm_squared() - v.xy().norm_squared(),
                        area,
                    )
                };
                let q6 = if g0.hypot(g1) >= 1e-9 {
                    (g1 * m0 - g0 * m1).atan2(g0 * m0 + g1 * m1)
                } else {
                    // Axis 6 along axes 2–4: only ψ + q6 is fixed, but X off axis 4 makes ψ
                    // move the planar arm's target V: q6 is the value nearest 0 at which |V|
                    // lies within the planar arm's reach |s(q3)|.
                    let (a, b, c0) =
                        trig_coefficients(|cc, ss| s(ss.atan2(cc)).xy().norm_squared());
                    let rho = a.hypot(b);
                    nearest_within(
                        |cc, ss| v_of(ss.atan2(cc)).xy().norm_squared(),
                        c0 - rho,
                        c0 + rho,
                        area,
                    )
                };
                let psi = psi_of(q6);
                let v = v_of(q6);
                let q3s = q3_roots(&v);
                for &q3 in q3s.as_slice() {
                    // (A free q2 is any: q4 takes up ψ.)
                    let Some((q2, _)) = azimuth(&v, &s(q3), tiny) else {
                        continue;
                    };
                    let q4 = sigma34 * (psi - q2 - sigma3 * q3);
                    self.push_verified([q1, q2, q3, q4, q5, q6], target, out);
                }
            }
        }
    }

    /// Appends the candidate `q` if it reproduces `target` to [`VERIFY_TOLERANCE`] and is not
    /// already there; a candidate missing the pose by more than the arithmetic does
    /// ([`POLISHED`]) is [`polished`](Self::polished) first.
    fn push_verified(&self, q: [f64; 6], target: &Rigid, out: &mut Solutions) {
        let known = |q: &SVector<f64, 6>| {
            out.iter()
                .any(|s| (0..6).all(|j| self.joint_distance(j, s[j], q[j]) < SAME_SOLUTION))
        };
        let mut q = self.normalise(SVector::from(q));
        if known(&q) {
            return;
        }
        let (mut dp, mut dr) = frame_error(&self.fk_frame(&q), target);
        if dp > POLISHED * self.scale || dr > POLISHED {
            q = self.normalise(self.polished(q, target));
            if known(&q) {
                return;
            }
            (dp, dr) = frame_error(&self.fk_frame(&q), target);
        }
        if dp <= VERIFY_TOLERANCE && dr <= VERIFY_TOLERANCE {
            out.push(q);
        }
    }

    fn joint_distance(&self, j: usize, a: f64, b: f64) -> f64 {
        if self.prismatic[j] {
            (a - b).abs()
        } else {
            wrap_angle(a - b).abs()
        }
    }

    /// Wraps revolute values into (−π, π], then by ±2π into the limits where that fits.
    fn normalise(&self, mut q: SVector<f64, 6>) -> SVector<f64, 6> {
        for j in 0..6 {
            if self.prismatic[j] {
                continue;
            }
            let mut x = wrap_angle(q[j]);
            if let Some([lo, hi]) = self.limits[j] {
                if x < lo && x + TAU <= hi {
                    x += TAU;
                } else if x > hi && x - TAU >= lo {
                    x -= TAU;
                }
            }
            q[j] = x;
        }
        q
    }
}

/// Candidate solutions `(q1, q2, q3)` of the inverse position problem: at most 4, and more at
/// a singular pose, where a near-double root is also tried as the double root
/// ([`solve_trig`], [`real_roots_near`]): up to 6 values of q3 times 3 of q2.
struct ArmSolutions {
    q: [ArmSolution; ArmSolutions::CAPACITY],
    len: usize,
}

/// `(q1, q2, q3)`, and which of them the wrist centre's position leaves free (on axis 1 or 2;
/// set to 0 until the wrist chooses them).
#[derive(Clone, Copy, Debug)]
struct ArmSolution {
    q: [f64; 3],
    free: [bool; 3],
}

impl ArmSolutions {
    const CAPACITY: usize = 18;

    const NONE: ArmSolutions = ArmSolutions {
        q: [ArmSolution {
            q: [0.0; 3],
            free: [false; 3],
        }; ArmSolutions::CAPACITY],
        len: 0,
    };

    fn push(&mut self, q: [f64; 3], free: [bool; 3]) {
        if self.len < Self::CAPACITY {
            self.q[self.len] = ArmSolution { q, free };
            self.len += 1;
        }
    }

    fn as_slice(&self) -> &[ArmSolution] {
        &self.q[..self.len]
    }
}

/// The real roots of `f`, a polynomial of degree at most 4 in a prismatic joint's
/// displacement, from five samples.
fn quartic_in_displacement(f: &dyn Fn(f64) -> f64, size: f64) -> Roots<6> {
    // Newton's divided differences at −2..2, expanded to monomial coefficients.
    let xs = [-2.0, -1.0, 0.0, 1.0, 2.0];
    let mut dd: [f64; 5] = core::array::from_fn(|i| f(xs[i]));
    for level in 1..5 {
        for i in (level..5).rev() {
            dd[i] = (dd[i] - dd[i - 1]) / (xs[i] - xs[i - level]);
        }
    }
    // p(x) = dd0 + dd1 (x − x0) + dd2 (x − x0)(x − x1) + …, by Horner on the nested form.
    let mut c = [0.0; 5];
    c[0] = dd[4];
    for (degree, k) in (0..4).rev().enumerate() {
        // c ← c · (x − xs[k]) + dd[k]; c has degree `degree` before.
        let mut next = [0.0; 5];
        for d in 0..=degree {
            next[d + 1] += c[d];
            next[d] -= c[d] * xs[k];
        }
        next[0] += dd[k];
        c = next;
    }
    real_polynomial_roots(c, size)
}
