//! Closed-form inverse kinematics by kinematic decoupling (section 4.3) for six-joint arms
//! whose last three axes meet in one point (a spherical wrist).
//!
//! # The chain
//! The solver works on the robot's kinematic structure ([`ChainRef`], the same numbers its
//! kinematics are computed from): `T(q) = P0 Z1(q1) P1 Z2(q2) ⋯ Z6(q6) P6`, with constant
//! rigid transforms `P_i` and joint motions `Z_i = Rz(q_i)` (revolute) or `Tz(q_i)`
//! (prismatic), each joint's offset folded into the transform before it so that q are the
//! joint values as the user gives them. [`DecoupledIk::from_chain`] takes the structure,
//! [`DecoupledIk::from_arm`] the one an [`Arm`] carries (a generated module's `Robot` or the
//! runtime [`Robot`](crate::Robot)), [`DecoupledIk::from_model`] the one of a description.
//!
//! # Decoupling
//! With axes 4, 5, 6 through one point c, the wrist joints do not move c, so c is fixed in
//! the tool frame (`c_t`) and in the frame of joint 4 (`c_3`): the wrist centre
//! `T c_t = P0 Z1 P1 Z2 P2 Z3 P3 c_3` depends on q1..q3 only (inverse position), and then
//! `R_3ᵀ R = Rz(q4) Q4 Rz(q5) Q5 Rz(q6) Q6` gives q4..q6 as ZYZ Euler angles (inverse
//! orientation, section 4.3.4). The wrist must have perpendicular consecutive axes (every
//! spherical wrist of the catalogue does): writing `Q4`, `Q5` as `Rz Rx(90°) Rz` turns the
//! product into `Rz(φ) Ry(θ) Rz(ψ) Rx(180°)`.
//!
//! # Inverse position: the arm geometries solved
//! Joint 1 must be revolute. With `p` the wrist centre in the frame of joint 1:
//! - **Axes 1 and 2 intersect, joint 2 revolute** (Pieper): `|p|` (after moving the origin
//!   to the intersection) depends on q3 only, giving q3 (two elbow solutions, or two roots of
//!   a quadratic for a prismatic joint 3); the height along axis 1 then gives q2 (two), and
//!   the azimuth q1 (one). The PUMA 560 (elbow arm with shoulder and forearm offsets) and the
//!   Stanford arm (prismatic joint 3) are of this kind: up to 4 arm solutions.
//! - **Axes 2 and 3 parallel, joint 3 revolute** (the elbow arm of section 4.3.3, also with
//!   an offset a1 between axes 1 and 2): the offset of the wrist centre along axis 2 is
//!   constant, giving q1 (left/right arm, two), then the planar two-link problem q3 (elbow
//!   up/down, two) and q2. Up to 4 arm solutions.
//! - **Revolute, prismatic, prismatic** (the cylindrical arm of section 4.2): the height gives
//!   one prismatic joint linearly, the radius the other from a quadratic (two), the azimuth
//!   q1. Up to 2 arm solutions.
//!
//! Each arm solution gives two wrist solutions (θ5 and −θ5: the wrist flip), so at most 8.
//! Every candidate is checked by forward kinematics and dropped unless it reproduces the pose
//! to [`VERIFY_TOLERANCE`].
//!
//! # Singular poses: the documented choices
//! - Wrist singularity (θ5 = 0 or π in the Euler angles of the wrist: axes 4 and 6 aligned):
//!   only q4 + q6 (or q4 − q6) is determined; the solver sets **q4 = 0** and gives q6 the
//!   whole rotation. Both wrist branches then coincide and are returned once.
//! - Shoulder singularity (wrist centre on axis 1): q1 is free; the solver sets **q1 = 0**.
//! - Wrist centre on axis 2 (Pieper case): q2 is free; the solver sets **q2 = 0**.
//!
//! # Returned angles
//! Revolute joint values are wrapped into (−π, π], then shifted by ±2π into the joint's
//! limits where that makes them fit. Solutions outside the limits are returned too (the
//! complete solution set); [`DecoupledIk::solve_within_limits`] keeps only those inside.

use crate::rigid::Rigid;
use crate::rotation::{EulerZyz, wrap_angle};
use crate::{Arm, ArmAllocator};
use dhgen_model::{ChainRef, JointKind, NotSpherical};

use nalgebra::{DefaultAllocator, Isometry3, Matrix3, Rotation3, SVector, Vector3};
// Without `std`, f64 has no `sin_cos`, `atan2`, `hypot`...: nalgebra's traits supply them
// (through libm). With `std` the inherent methods win and the imports go unused.
#[cfg(not(feature = "std"))]
use nalgebra::{ComplexField as _, RealField as _};

/// A returned solution reproduces the pose to this: position error in metres and orientation
/// error in radians, each.
pub const VERIFY_TOLERANCE: f64 = 1e-9;

/// `f · Z(q)`: the frame right-multiplied by the joint motion.
fn joint(f: &Rigid, prismatic: bool, q: f64) -> Rigid {
    let mut out = *f;
    let kind = if prismatic {
        JointKind::Prismatic
    } else {
        JointKind::Revolute
    };
    out.apply_joint(kind, q);
    out
}

/// Position error and rotation angle between two frames; the angle from
/// `‖Ra − Rb‖_F = 2√2 sin(θ/2)`, accurate for small angles.
fn frame_error(a: &Rigid, b: &Rigid) -> (f64, f64) {
    let chord = (a.r - b.r).norm() / (2.0 * core::f64::consts::SQRT_2);
    ((a.p - b.p).norm(), 2.0 * chord.min(1.0).asin())
}

fn rz(q: f64) -> Matrix3<f64> {
    let (s, c) = q.sin_cos();
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// `Rz(a) Rx(b) Rz(c)` of a rotation, with `b ∈ [0, π]`: `(a, b, c)`; `None` when b is 0 or π
/// (the rotation keeps z: the two axes it relates are parallel).
fn zxz(m: &Matrix3<f64>) -> Option<(f64, f64, f64)> {
    let sb = m[(0, 2)].hypot(m[(1, 2)]);
    if sb < 1e-9 {
        return None;
    }
    Some((
        m[(0, 2)].atan2(-m[(1, 2)]),
        sb.atan2(m[(2, 2)]),
        m[(2, 0)].atan2(m[(2, 1)]),
    ))
}

/// The solutions of `a cos x + b sin x = c` (0, 1 or 2). A right-hand side outside the range
/// by no more than rounding is clamped to the boundary (one double root).
fn solve_trig(a: f64, b: f64, c: f64) -> ([f64; 2], usize) {
    let rho = a.hypot(b);
    let base = b.atan2(a);
    let ratio = c / rho;
    if !ratio.is_finite() || ratio.abs() > 1.0 + 1e-12 {
        return ([0.0; 2], 0);
    }
    let ratio = ratio.clamp(-1.0, 1.0);
    // acos through atan2 keeps full accuracy away from the boundary.
    let gamma = (1.0 - ratio * ratio).max(0.0).sqrt().atan2(ratio);
    if gamma == 0.0 {
        ([base, 0.0], 1)
    } else {
        ([base + gamma, base - gamma], 2)
    }
}

/// The real roots of `x² + 2 b x + c = 0` (a discriminant below zero by no more than rounding
/// is clamped to zero).
fn solve_monic_quadratic(b: f64, c: f64, scale: f64) -> ([f64; 2], usize) {
    let disc = b * b - c;
    if !disc.is_finite() || disc < -1e-12 * scale * scale {
        return ([0.0; 2], 0);
    }
    let root = disc.max(0.0).sqrt();
    if root == 0.0 {
        ([-b, 0.0], 1)
    } else {
        ([-b + root, -b - root], 2)
    }
}

/// Why an arm has no closed-form solution here.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StructureError {
    /// Kinematic decoupling needs exactly six joints.
    #[error("closed-form IK needs 6 joints with a spherical wrist; this arm has {dof}")]
    NotSixJoints {
        /// The arm's number of joints.
        dof: usize,
    },
    /// The last three axes are not a spherical wrist (see
    /// [`ChainRef::spherical_wrist`](dhgen_model::ChainRef::spherical_wrist)).
    #[error("no spherical wrist: {0}")]
    NoSphericalWrist(NotSpherical),
    /// Two consecutive wrist axes are not perpendicular (twist ≠ ±90°), so the wrist is not
    /// a ZYZ Euler wrist.
    #[error(
        "wrist axes {axis} and {} are at {angle} rad, not perpendicular (ZYZ wrists only)",
        axis + 1
    )]
    WristNotPerpendicular {
        /// The first of the two axes, 1-based (4 or 5).
        axis: usize,
        /// The angle between them, rad.
        angle: f64,
    },
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

/// The kind of arm (the geometry of joints 1–3) that [`DecoupledIk`] recognised; see the
/// module documentation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArmKind {
    /// Revolute joints 1 and 2 with intersecting axes (Pieper's case); joint 3 revolute or
    /// prismatic. PUMA 560, Stanford arm.
    IntersectingShoulder,
    /// Revolute joints 1-3 with axes 2 and 3 parallel (the elbow arm of section 4.3.3).
    ParallelElbow,
    /// Revolute joint 1 and two prismatic joints (the cylindrical arm).
    Cylindrical,
}

/// Constants of the inverse position problem, per geometry. `p` below is the wrist centre in
/// the frame of joint 1.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Position {
    /// `p − shift e_z = Rz(q1) R1 Rz(q2) g(q3)`, `g(q3) = P2 Z3(q3) w` (P2 with the shift
    /// along axis 2 folded in).
    Intersecting {
        shift: f64,
        r1: Matrix3<f64>,
        /// `R1ᵀ e_z`: axis 1 in the frame of joint 2.
        n: Vector3<f64>,
        p2: Rigid,
        /// `R2ᵀ t2`: P2's translation in the frame of joint 3.
        m: Vector3<f64>,
    },
    /// `p = Rz(q1) (R1 Rz(q2) g(q3) + t1)`, axes 2 ∥ 3.
    Parallel {
        p1: Rigid,
        p2: Rigid,
        /// Axis 2 in the frame of joint 1.
        a2: Vector3<f64>,
        /// Constant offset of the wrist centre along axis 2.
        offset: f64,
        m: Vector3<f64>,
    },
    /// `p = Rz(q1) (f0 + q_lead u + q_other v)` with the lead joint moving along axis 1.
    Cylindrical {
        f0: Vector3<f64>,
        u: Vector3<f64>,
        v: Vector3<f64>,
        /// True when joint 2 is the lead (solved from the height), false for joint 3.
        lead_is_2: bool,
    },
}

/// Closed-form inverse kinematics of a six-joint arm with a spherical wrist, built once
/// from the robot (precomputed constants, fixed size, `Copy`); [`solve`](Self::solve)
/// allocates nothing. See the module documentation for the method, the geometries and the
/// choices at singular poses.
///
/// ```
/// use dhgen::ik::DecoupledIk;
/// dhgen::robot!(mod puma = "robots/puma560.toml");
///
/// let ik = DecoupledIk::from_arm(&puma::Robot).unwrap();
/// let q = [0.3, -0.4, 0.2, 0.5, -0.7, 1.1];
/// let pose = puma::fk(&q);
/// let solutions = ik.solve(&pose);
/// assert_eq!(solutions.len(), 8);
/// assert!(solutions.iter().any(|s| (s - dhgen::nalgebra::SVector::from(q)).norm() < 1e-9));
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DecoupledIk {
    chain: [Rigid; 7],
    prismatic: [bool; 6],
    limits: [Option<[f64; 2]>; 6],
    /// Inverse of `P0`.
    p0_inv: Rigid,
    /// The wrist centre in the tool frame.
    centre_tool: Vector3<f64>,
    /// The wrist centre in the frame in which joint 3 moves: `P3 c_3`.
    w: Vector3<f64>,
    position: Position,
    arm: ArmKind,
    /// `Rz(a) Rx(90°) Rz(b)` of `Q4` and `Q5`.
    wrist4: (f64, f64),
    wrist5: (f64, f64),
    /// Length scale of the arm (sum of the constant offsets), for relative thresholds.
    scale: f64,
}

/// At most 8 joint vectors of a six-joint arm, in a fixed-size array (no allocation).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Solutions {
    q: [SVector<f64, 6>; 8],
    len: usize,
}

impl Solutions {
    /// Most solutions a six-joint arm with a spherical wrist has.
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
            .min_by(|a, b| {
                dist(a)
                    .partial_cmp(&dist(b))
                    .unwrap_or(core::cmp::Ordering::Equal)
            })
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

/// Up to 4 solutions of the inverse position problem.
struct ArmSolutions {
    q: [[f64; 3]; 4],
    len: usize,
}

impl ArmSolutions {
    fn push(&mut self, q: [f64; 3]) {
        if self.len < 4 {
            self.q[self.len] = q;
            self.len += 1;
        }
    }
}

impl DecoupledIk {
    /// Builds the solver from a validated description (joint offsets, base and tool
    /// included).
    #[cfg(feature = "std")]
    pub fn from_model(model: &dhgen_model::RobotModel) -> Result<DecoupledIk, StructureError> {
        Self::from_chain(model.chain().view())
    }

    /// Builds the solver for any arm, generated or runtime, from the structure it carries
    /// ([`Arm::chain`]). Allocation-free.
    pub fn from_arm<A: Arm>(arm: &A) -> Result<DecoupledIk, StructureError>
    where
        DefaultAllocator: ArmAllocator<A::Dof>,
    {
        Self::from_chain(arm.chain())
    }

    /// Builds the solver from a kinematic structure.
    pub fn from_chain(chain: ChainRef<'_>) -> Result<DecoupledIk, StructureError> {
        let dof = chain.dof();
        if dof != 6 {
            return Err(StructureError::NotSixJoints { dof });
        }
        let wrist = chain
            .spherical_wrist()
            .map_err(StructureError::NoSphericalWrist)?;
        // T(q) = P0 Z1(q1 + o1) P1 ⋯: fold each offset into the transform before its joint,
        // `P_{k} Z_{k+1}(o)`, so that the solver's joint values are the user's.
        let chain_frames: [Rigid; 7] = core::array::from_fn(|k| {
            let p = &chain.placements[k];
            if k < 6 {
                let z = chain.bodies[k].motion(0.0);
                Rigid::from_frame(&p.compose(&z))
            } else {
                Rigid::from_frame(p)
            }
        });
        let prismatic = core::array::from_fn(|i| chain.bodies[i].joint == JointKind::Prismatic);
        let limits = core::array::from_fn(|i| chain.bodies[i].limits);
        Self::from_frames(chain_frames, prismatic, limits, Vector3::from(wrist.centre))
    }

    fn from_frames(
        chain: [Rigid; 7],
        prismatic: [bool; 6],
        limits: [Option<[f64; 2]>; 6],
        centre: Vector3<f64>,
    ) -> Result<DecoupledIk, StructureError> {
        let scale = 1.0 + chain.iter().map(|f| f.p.norm()).sum::<f64>();
        let tol = 1e-9 * scale;
        // Wrist axes in the frame of joint 4 (q4 = q5 = 0).
        let f5 = chain[4];
        let f6 = chain[4].compose(&chain[5]);
        let (d4, d5, d6) = (Vector3::z(), f5.r.column(2).into_owned(), f6.r.column(2));
        for (axis, a, b) in [(4, d4, d5), (5, d5, d6.into_owned())] {
            let cos = a.dot(&b);
            if cos.abs() > 1e-9 {
                return Err(StructureError::WristNotPerpendicular {
                    axis,
                    angle: cos.clamp(-1.0, 1.0).acos(),
                });
            }
        }
        // The tool in the frame of joint 4 at q4 = q5 = q6 = 0.
        let wrist_to_tool = chain[4].compose(&chain[5]).compose(&chain[6]);
        let centre_tool = wrist_to_tool.inverse().point(&centre);
        let w = chain[3].point(&centre);
        let (a4, _, b4) = zxz(&chain[4].r).ok_or(StructureError::WristNotPerpendicular {
            axis: 4,
            angle: 0.0,
        })?;
        let (a5, _, b5) = zxz(&chain[5].r).ok_or(StructureError::WristNotPerpendicular {
            axis: 5,
            angle: 0.0,
        })?;

        let kinds = [
            if prismatic[0] { b'P' } else { b'R' },
            if prismatic[1] { b'P' } else { b'R' },
            if prismatic[2] { b'P' } else { b'R' },
        ];
        let unsupported = |reason| StructureError::UnsupportedArm {
            joints: kinds,
            reason,
        };
        if prismatic[0] {
            return Err(unsupported("joint 1 must be revolute"));
        }
        let (p1, p2) = (chain[1], chain[2]);
        let (position, geometry) = if !prismatic[1] {
            let a2 = p1.r.column(2).into_owned();
            if a2.xy().norm() < 1e-9 {
                return Err(unsupported("axes 1 and 2 are parallel"));
            }
            // Slide the origin along axis 1 to axis 2's height: then axes 1 and 2 intersect
            // iff what is left of t1 lies along axis 2.
            let rest = Vector3::new(p1.p.x, p1.p.y, 0.0);
            let along = rest.dot(&a2);
            let parallel_23 = (p2.r[(2, 2)].abs() - 1.0).abs() < 1e-12;
            if (rest - a2 * along).norm() <= tol {
                let p2 = Rigid {
                    r: p2.r,
                    p: p2.p + Vector3::z() * along,
                };
                let m = p2.r.transpose() * p2.p;
                if !prismatic[2] && (m.xy().norm() < tol || w.xy().norm() < tol) {
                    return Err(unsupported(
                        "the wrist centre's distance from the shoulder does not depend on joint 3",
                    ));
                }
                (
                    Position::Intersecting {
                        shift: p1.p.z,
                        r1: p1.r,
                        n: p1.r.transpose() * Vector3::z(),
                        p2,
                        m,
                    },
                    ArmKind::IntersectingShoulder,
                )
            } else if !prismatic[2] && parallel_23 {
                let m = p2.r.transpose() * p2.p;
                if m.xy().norm() < tol || w.xy().norm() < tol {
                    return Err(unsupported(
                        "the wrist centre's distance from axis 2 does not depend on joint 3",
                    ));
                }
                let sigma = p2.r[(2, 2)].signum();
                (
                    Position::Parallel {
                        p1,
                        p2,
                        a2,
                        offset: a2.dot(&p1.p) + p2.p.z + sigma * w.z,
                        m,
                    },
                    ArmKind::ParallelElbow,
                )
            } else {
                return Err(unsupported(
                    "needs axes 1 and 2 intersecting, or joints 2 and 3 revolute with parallel axes",
                ));
            }
        } else if prismatic[2] {
            let u = p1.r.column(2).into_owned();
            let v = p1.r * p2.r.column(2);
            let f0 = p1.p + p1.r * (p2.p + p2.r * w);
            let lead_is_2 = u.z.abs() >= v.z.abs();
            let (lead, other) = if lead_is_2 { (u, v) } else { (v, u) };
            if lead.z.abs() < 1e-9 {
                return Err(unsupported("neither prismatic joint moves along axis 1"));
            }
            if (other.xy() - lead.xy() * (other.z / lead.z)).norm() < 1e-9 {
                return Err(unsupported(
                    "the prismatic joints do not change the distance from axis 1",
                ));
            }
            (
                Position::Cylindrical {
                    f0,
                    u,
                    v,
                    lead_is_2,
                },
                ArmKind::Cylindrical,
            )
        } else {
            return Err(unsupported(
                "a prismatic joint 2 needs a prismatic joint 3 (cylindrical arm)",
            ));
        };
        Ok(DecoupledIk {
            chain,
            prismatic,
            limits,
            p0_inv: chain[0].inverse(),
            centre_tool,
            w,
            position,
            arm: geometry,
            wrist4: (a4, b4),
            wrist5: (a5, b5),
            scale,
        })
    }

    /// The arm geometry recognised.
    pub fn arm_kind(&self) -> ArmKind {
        self.arm
    }

    /// The wrist centre (the point where axes 4, 5, 6 meet) in the tool frame.
    pub fn wrist_centre_in_tool(&self) -> Vector3<f64> {
        self.centre_tool
    }

    /// Which joints are prismatic.
    pub fn prismatic(&self) -> [bool; 6] {
        self.prismatic
    }

    /// Forward kinematics of the chain the solver works with (the same pose as the arm's).
    pub fn fk(&self, q: &SVector<f64, 6>) -> Isometry3<f64> {
        self.fk_frame(q).to_isometry()
    }

    fn fk_frame(&self, q: &SVector<f64, 6>) -> Rigid {
        let mut f = self.chain[0];
        for i in 0..6 {
            f = joint(&f, self.prismatic[i], q[i]).compose(&self.chain[i + 1]);
        }
        f
    }

    /// Every joint vector that puts the tool at `pose` (at most 8), each checked by forward
    /// kinematics to [`VERIFY_TOLERANCE`]. Empty when the pose is out of reach or not finite.
    pub fn solve(&self, pose: &Isometry3<f64>) -> Solutions {
        let mut out = Solutions::EMPTY;
        let target = Rigid::from_isometry(pose);
        if !(target.r.iter().all(|x| x.is_finite()) && target.p.iter().all(|x| x.is_finite())) {
            return out;
        }
        let centre = self.p0_inv.point(&target.point(&self.centre_tool));
        let arm = self.solve_position(&centre);
        for a in &arm.q[..arm.len] {
            self.solve_orientation(a, &target, &mut out);
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

    fn solve_position(&self, p: &Vector3<f64>) -> ArmSolutions {
        let mut out = ArmSolutions {
            q: [[0.0; 3]; 4],
            len: 0,
        };
        let tiny = 1e-12 * self.scale;
        // q1 rotating u (in the frame after joint 1) onto p about z; free (0) on the axis.
        let azimuth = |p: &Vector3<f64>, u: &Vector3<f64>| -> Option<f64> {
            let (pr, ur) = (p.xy().norm(), u.xy().norm());
            if pr < tiny && ur < tiny {
                Some(0.0)
            } else if pr < tiny || ur < tiny {
                None
            } else {
                Some(p.y.atan2(p.x) - u.y.atan2(u.x))
            }
        };
        match self.position {
            Position::Intersecting {
                shift,
                r1,
                n,
                p2,
                m,
            } => {
                let p = p - Vector3::z() * shift;
                let w = self.w;
                let (q3s, count) = if self.prismatic[2] {
                    let wm = w + m;
                    solve_monic_quadratic(wm.z, wm.norm_squared() - p.norm_squared(), self.scale)
                } else {
                    let a = 2.0 * (m.x * w.x + m.y * w.y);
                    let b = 2.0 * (m.y * w.x - m.x * w.y);
                    let k = w.norm_squared() + p2.p.norm_squared() + 2.0 * m.z * w.z;
                    solve_trig(a, b, p.norm_squared() - k)
                };
                for &q3 in &q3s[..count] {
                    let g = joint(&p2, self.prismatic[2], q3).point(&w);
                    let a = n.x * g.x + n.y * g.y;
                    let b = n.y * g.x - n.x * g.y;
                    let c = p.z - n.z * g.z;
                    let (q2s, count2) = if a.hypot(b) < tiny {
                        // The wrist centre is on axis 2: q2 is free where the height fits.
                        if c.abs() < tiny {
                            ([0.0, 0.0], 1)
                        } else {
                            ([0.0, 0.0], 0)
                        }
                    } else {
                        solve_trig(a, b, c)
                    };
                    for &q2 in &q2s[..count2] {
                        let u = r1 * (rz(q2) * g);
                        if let Some(q1) = azimuth(&p, &u) {
                            out.push([q1, q2, q3]);
                        }
                    }
                }
            }
            Position::Parallel {
                p1,
                p2,
                a2,
                offset,
                m,
            } => {
                let a = a2.x * p.x + a2.y * p.y;
                let b = a2.x * p.y - a2.y * p.x;
                let c = offset - a2.z * p.z;
                let (q1s, count) = if a.hypot(b) < tiny {
                    if c.abs() < tiny {
                        ([0.0, 0.0], 1)
                    } else {
                        ([0.0, 0.0], 0)
                    }
                } else {
                    solve_trig(a, b, c)
                };
                let w = self.w;
                let a3 = 2.0 * (m.x * w.x + m.y * w.y);
                let b3 = 2.0 * (m.y * w.x - m.x * w.y);
                let k3 = w.norm_squared() + p2.p.norm_squared() + 2.0 * m.z * w.z;
                for &q1 in &q1s[..count] {
                    let x = p1.inverse().point(&(rz(-q1) * p));
                    let (q3s, count3) = solve_trig(a3, b3, x.norm_squared() - k3);
                    for &q3 in &q3s[..count3] {
                        let g = joint(&p2, false, q3).point(&w);
                        if let Some(q2) = azimuth(&x, &g) {
                            out.push([q1, q2, q3]);
                        }
                    }
                }
            }
            Position::Cylindrical {
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
                let (roots, count) = solve_monic_quadratic(
                    a.dot(&b) / bb,
                    (a.norm_squared() - p.xy().norm_squared()) / bb,
                    self.scale,
                );
                for &q_other in &roots[..count] {
                    let q_lead = (p.z - f0.z - q_other * other.z) / lead.z;
                    let (q2, q3) = if lead_is_2 {
                        (q_lead, q_other)
                    } else {
                        (q_other, q_lead)
                    };
                    let f = f0 + u * q2 + v * q3;
                    if let Some(q1) = azimuth(p, &f) {
                        out.push([q1, q2, q3]);
                    }
                }
            }
        }
        out
    }

    fn solve_orientation(&self, arm: &[f64; 3], target: &Rigid, out: &mut Solutions) {
        let mut g = self.chain[0];
        for (i, &qi) in arm.iter().enumerate() {
            g = joint(&g, self.prismatic[i], qi).compose(&self.chain[i + 1]);
        }
        // R_3ᵀ R Q6ᵀ = Rz(q4 + a4) Rx(90°) Rz(b4 + q5 + a5) Rx(90°) Rz(b5 + q6)
        //            = Rz(φ) Ry(θ) Rz(ψ) Rx(180°), φ = q4 + a4, θ = −(b4 + q5 + a5), ψ = −(b5 + q6).
        let flip_x = Matrix3::new(1.0, 0.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, -1.0);
        let m = g.r.transpose() * target.r * self.chain[6].r.transpose() * flip_x;
        let (a4, b4) = self.wrist4;
        let (a5, b5) = self.wrist5;
        for euler in EulerZyz::from_rotation(&Rotation3::from_matrix_unchecked(m)) {
            let (mut phi, theta, mut psi) = (euler.phi, euler.theta, euler.psi);
            if euler.is_singular() {
                // Only φ + ψ (θ = 0) or φ − ψ (θ = π) is known: choose q4 = 0.
                let new_phi = a4;
                psi += if theta.cos() > 0.0 {
                    phi - new_phi
                } else {
                    new_phi - phi
                };
                phi = new_phi;
            }
            let q = SVector::<f64, 6>::new(
                arm[0],
                arm[1],
                arm[2],
                phi - a4,
                -theta - b4 - a5,
                -psi - b5,
            );
            let q = self.normalise(q);
            if out
                .iter()
                .any(|s| (0..6).all(|j| self.joint_distance(j, s[j], q[j]) < 1e-10))
            {
                continue;
            }
            let (dp, dr) = frame_error(&self.fk_frame(&q), target);
            if dp <= VERIFY_TOLERANCE && dr <= VERIFY_TOLERANCE {
                out.push(q);
            }
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
                let two_pi = core::f64::consts::TAU;
                if x < lo && x + two_pi <= hi {
                    x += two_pi;
                } else if x > hi && x - two_pi >= lo {
                    x -= two_pi;
                }
            }
            q[j] = x;
        }
        q
    }
}
