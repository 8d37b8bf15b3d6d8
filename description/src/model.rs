//! The validated robot model: what every other part of dhgen reads.
//!
//! A [`RobotModel`] only exists after validation (see [`crate::validate`]), so code that
//! receives one may rely on its invariants: at least one link, finite numbers, physical
//! inertias, consistent dynamics (all links or none).

use crate::{Angle, Frame, Friction, Inertial, JointKind, JointValue, Ring};

/// Which Denavit-Hartenberg convention the table uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Convention {
    /// Standard (distal) DH, Spong: `A_i = Rz(θ_i) Tz(d_i) Tx(a_i) Rx(α_i)`; joint i moves
    /// about/along `z_{i-1}`.
    Standard,
    /// Modified (proximal) DH, Craig: `A_i = Rx(α_{i-1}) Tx(a_{i-1}) Rz(θ_i) Tz(d_i)`;
    /// joint i moves about/along `z_i`. Row i holds `a_{i-1}`, `α_{i-1}`.
    Modified,
    /// No DH table: each row places its joint as a URDF joint does, by a fixed
    /// [`Placement`] (an origin in the previous link frame and an axis), and link frame i is
    /// the URDF child link frame, `A_i = origin_i · Rot(axis_i, q_i)` (revolute) or
    /// `origin_i · Trans(axis_i · q_i)` (prismatic). What [`RobotModel::from_urdf_str`]
    /// builds, and the form any serial chain takes without approximation.
    Urdf,
}

/// A rigid transform given as a translation and URDF roll-pitch-yaw angles:
/// `R = Rz(yaw) Ry(pitch) Rx(roll)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pose {
    /// Translation, m.
    pub xyz: [f64; 3],
    /// `[roll, pitch, yaw]`.
    pub rpy: [Angle; 3],
}

impl Pose {
    /// The rotation matrix `Rz(yaw) Ry(pitch) Rx(roll)`, row-major, with exact entries for
    /// quarter turns.
    pub fn rotation(&self) -> [[f64; 3]; 3] {
        let (cr, sr) = self.rpy[0].cos_sin();
        let (cp, sp) = self.rpy[1].cos_sin();
        let (cy, sy) = self.rpy[2].cos_sin();
        [
            [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
            [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
            [-sp, cp * sr, cp * cr],
        ]
    }

    /// The pose as a [`Frame`] of any ring.
    pub fn frame<R: Ring>(&self) -> Frame<R> {
        let r = self.rotation();
        Frame {
            r: r.map(|row| row.map(R::from_f64)),
            p: self.xyz.map(R::from_f64),
        }
    }

    /// True for the identity pose (no translation, no rotation).
    pub fn is_identity(&self) -> bool {
        self.xyz == [0.0; 3] && self.rpy.iter().all(|a| a.quarter_turn() == Some((1, 0)))
    }
}

/// Where a joint of a [`Convention::Urdf`] row sits: URDF's joint `<origin>` and `<axis>`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    /// The joint frame at rest in the previous link frame (the base frame for the first
    /// joint).
    pub origin: Pose,
    /// The joint axis in the joint frame: a unit vector, exactly a signed coordinate axis
    /// when the description means one.
    pub axis: [f64; 3],
}

impl Placement {
    /// A rotation `A` with `A·z = axis`: the joint turns about (slides along) the z axis of
    /// the frame `origin · A`, and the link frame is that frame times `Aᵀ`. Exact (entries in
    /// {−1, 0, 1}) when the axis is a signed coordinate axis; otherwise the smallest rotation
    /// taking z to the axis.
    pub fn alignment(&self) -> [[f64; 3]; 3] {
        match self.axis {
            [0.0, 0.0, z] if z > 0.0 => [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]],
            [0.0, 0.0, _] => [[1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, -1.0]],
            [x, 0.0, 0.0] if x > 0.0 => [[0.0, 0.0, 1.0], [0.0, 1.0, 0.0], [-1.0, 0.0, 0.0]],
            [_, 0.0, 0.0] => [[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]],
            [0.0, y, 0.0] if y > 0.0 => [[1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [0.0, -1.0, 0.0]],
            [0.0, _, 0.0] => [[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]],
            [x, y, z] if z > -0.5 => {
                // Rodrigues about v = z × u (|v| = sin, u·z = cos): R = I + [v]× + [v]×²/(1 + cos).
                let k = 1.0 / (1.0 + z);
                [
                    [1.0 - x * x * k, -x * y * k, x],
                    [-x * y * k, 1.0 - y * y * k, y],
                    [-x, -y, z],
                ]
            }
            [x, y, z] => {
                // Near −z: Rx(π) · R', R' the Rodrigues rotation taking z to Rx(π)·u,
                // which is near +z.
                let k = 1.0 / (1.0 - z);
                [
                    [1.0 - x * x * k, x * y * k, x],
                    [-x * y * k, y * y * k - 1.0, y],
                    [x, -y, z],
                ]
            }
        }
    }
}

/// Roll, pitch and yaw of a rotation `Rz(yaw) Ry(pitch) Rx(roll)` (the inverse of
/// [`Pose::rotation`]), in radians: exact multiples of π/2 for rotations whose entries are in
/// {−1, 0, 1}, and never −0.
#[cfg(feature = "std")]
pub(crate) fn rpy_of(r: &[[f64; 3]; 3]) -> [f64; 3] {
    let cp = r[0][0].hypot(r[1][0]);
    let pitch = (-r[2][0]).atan2(cp);
    let rpy = if cp > 1e-12 {
        [(r[2][1]).atan2(r[2][2]), pitch, (r[1][0]).atan2(r[0][0])]
    } else {
        // Pitch ±π/2: only roll − yaw (or roll + yaw) is defined; take yaw = 0.
        let sp = -r[2][0];
        [(sp * r[0][1]).atan2(r[1][1]), pitch, 0.0]
    };
    // `+ 0.0` writes −0 (atan2 of a −0 entry) as 0.
    rpy.map(|a| a + 0.0)
}

/// Rotor inertia and gear ratio of a joint's motor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motor {
    /// Rotor inertia Jm, kg·m².
    pub inertia: f64,
    /// Gear ratio G (non-zero); the reflected inertia is `Jm·G²`.
    pub gear: f64,
}

impl Motor {
    /// The armature: the rotor inertia reflected through the gearbox, `Jm·G²`, which the
    /// motor adds to `D(q)_ii` (Pinocchio's and MuJoCo's name for it).
    pub fn armature(&self) -> f64 {
        self.inertia * self.gear * self.gear
    }
}

/// The collision shape of a link, for path planning: a capsule (the points within
/// `radius` of a segment) around the link's DH segment.
///
/// The segment of row i joins the origins of frames i−1 and i (frame 0 is the base frame),
/// that is the translation of `A_i`, in both conventions:
/// - standard DH: from joint i's axis (origin of frame i−1) to the far end of link i, built
///   from `d_i` along `z_{i−1}` and `a_i` along `x_i`; it is rigid with link i;
/// - modified DH: from the origin of frame i−1 to the origin of frame i on joint i's axis,
///   built from `a_{i−1}` along `x_{i−1}` and `d_i` along `z_i`; a revolute joint i does not
///   move it, so it is rigid with link i−1 (the body between joints i−1 and i), and nothing
///   past frame n (the flange or the tool) is covered.
///
/// A zero-length segment (a = d = 0) makes the capsule a sphere about the frame origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Collision {
    /// Capsule radius, m (finite, > 0).
    pub radius: f64,
}

/// One row of the DH table together with its link's properties.
#[derive(Clone, Debug, PartialEq)]
pub struct Link {
    /// Revolute or prismatic.
    pub joint: JointKind,
    /// Link length a (for modified DH: `a_{i-1}`), m.
    pub a: f64,
    /// Link twist α (for modified DH: `α_{i-1}`).
    pub alpha: Angle,
    /// Link offset d; for a prismatic joint the constant added to q.
    pub d: f64,
    /// Joint angle offset θ; for a revolute joint the constant added to q.
    pub theta: Angle,
    /// Joint limits `[lower, upper]` (rad or m).
    pub limits: Option<[f64; 2]>,
    /// Mass properties; `None` for a kinematics-only robot.
    pub inertial: Option<Inertial>,
    /// Motor rotor inertia and gear ratio.
    pub motor: Option<Motor>,
    /// Joint friction.
    pub friction: Option<Friction>,
    /// Collision capsule around the row's DH segment; `None`: not checked for collisions.
    pub collision: Option<Collision>,
    /// The joint's placement in a [`Convention::Urdf`] row (whose `a`, `alpha`, `d` and
    /// `theta` are then zero); `None` in a DH row.
    pub placement: Option<Placement>,
}

/// A validated serial robot: the one model type of dhgen.
#[cfg(feature = "std")]
#[derive(Clone, Debug, PartialEq)]
pub struct RobotModel {
    /// Identifier; also the default module name.
    pub name: String,
    /// Free text.
    pub description: Option<String>,
    /// DH convention of the table.
    pub convention: Convention,
    /// Gravitational acceleration in the base frame, m/s².
    pub gravity: [f64; 3],
    /// Base frame pose in the world frame.
    pub base: Option<Pose>,
    /// Tool frame pose in the last link frame.
    pub tool: Option<Pose>,
    /// The DH table, base to tip.
    pub links: Vec<Link>,
}

#[cfg(feature = "std")]
impl RobotModel {
    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.links.len()
    }

    /// True when every link has mass properties (validation guarantees all or none).
    pub fn has_dynamics(&self) -> bool {
        self.links.iter().all(|l| l.inertial.is_some())
    }

    /// The base pose, if it is not the identity.
    pub fn base_pose(&self) -> Option<&Pose> {
        self.base.as_ref().filter(|p| !p.is_identity())
    }

    /// The tool pose, if it is not the identity.
    pub fn tool_pose(&self) -> Option<&Pose> {
        self.tool.as_ref().filter(|p| !p.is_identity())
    }
}

impl Link {
    /// The link transform `A_i(q_i)` in the given convention: the one definition of the DH
    /// conventions in dhgen, used by the runtime path and by the symbolic engine alike.
    ///
    /// The joint offsets are applied here: `θ_i = q + theta` (revolute) or `d_i = q + d`
    /// (prismatic). Exact quarter-turn constants stay exact. A [`Convention::Urdf`] row is
    /// `origin · A · Z(q) · Aᵀ` with `A` its [alignment](Placement::alignment).
    pub fn transform<R: Ring>(&self, convention: Convention, q: JointValue<R>) -> Frame<R> {
        let k = R::from_f64;
        if let (Convention::Urdf, Some(p)) = (convention, &self.placement) {
            let a = Frame {
                r: p.alignment(),
                p: [0.0; 3],
            };
            return p
                .origin
                .frame::<f64>()
                .compose(&a)
                .to_ring::<R>()
                .compose(&q.motion())
                .compose(&a.inverse().to_ring());
        }
        let (ct0, st0) = self.theta.cos_sin();
        let (ct, st, d) = match q {
            JointValue::Revolute { cos, sin } => {
                // cos(q + θ0), sin(q + θ0) by the addition formulas; exact when θ0 = 0.
                if (ct0, st0) == (1.0, 0.0) {
                    (cos, sin, k(self.d))
                } else {
                    (
                        cos.clone() * k(ct0) - sin.clone() * k(st0),
                        sin * k(ct0) + cos * k(st0),
                        k(self.d),
                    )
                }
            }
            JointValue::Prismatic(q) => (k(ct0), k(st0), q + k(self.d)),
        };
        self.dh_transform(convention, ct, st, d)
    }

    /// The DH formula itself, given the full joint angle's cosine and sine and the full
    /// offset `d` (offsets already applied): `A_i` for the given convention. A
    /// [`Convention::Urdf`] row's DH fields are zero, and its formula is read as the modified
    /// one: the joint motion `Rz(θ) Tz(d)` alone.
    pub fn dh_transform<R: Ring>(&self, convention: Convention, ct: R, st: R, d: R) -> Frame<R> {
        let k = R::from_f64;
        let (ca, sa) = self.alpha.cos_sin();
        let z = k(0.0);
        match convention {
            Convention::Standard => Frame {
                r: [
                    [ct.clone(), -(st.clone() * k(ca)), st.clone() * k(sa)],
                    [st.clone(), ct.clone() * k(ca), -(ct.clone() * k(sa))],
                    [z, k(sa), k(ca)],
                ],
                p: [ct * k(self.a), st * k(self.a), d],
            },
            Convention::Modified | Convention::Urdf => Frame {
                r: [
                    [ct.clone(), -st.clone(), z],
                    [st.clone() * k(ca), ct.clone() * k(ca), k(-sa)],
                    [st * k(sa), ct * k(sa), k(ca)],
                ],
                p: [k(self.a), -(d.clone() * k(sa)), d * k(ca)],
            },
        }
    }
}

impl Convention {
    /// The index of the frame whose z axis and origin carry joint i (0-based `i`, frames
    /// numbered 0 = base .. n): `i` for standard DH (`z_{i-1}` in 1-based terms), `i + 1`
    /// for modified DH and for URDF rows (whose link frame carries the joint's origin; its z
    /// axis is the joint axis only when the axis is z).
    pub fn joint_frame(self, i: usize) -> usize {
        match self {
            Convention::Standard => i,
            Convention::Modified | Convention::Urdf => i + 1,
        }
    }
}
