//! Closed-form inverse kinematics of six-joint arms whose structure decouples position and
//! orientation (section 4.3): every solution, in a fixed-size array, verified by forward
//! kinematics.
//!
//! The solver is built from the arm's structure ([`ChainRef`](crate::ChainRef)) once — by `robot!` at compile
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

mod orientation;
mod position;
mod roots;
mod structure;
mod verify;

use crate::{JointKind, NotSpherical, Rigid};
use core::f64::consts::{PI, TAU};
#[cfg(not(feature = "std"))]
use nalgebra::ComplexField as _;
use nalgebra::{Isometry3, Matrix3, SVector, Vector3};

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

impl DecoupledIk {
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
}
