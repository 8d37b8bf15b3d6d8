//! The generic runtime robot: a validated [`RobotModel`] plus the constants every call
//! needs, computed once at construction (Pinocchio's split between the constant model and
//! the per-call work, which lives in [`crate::kinematics`] and [`crate::dynamics`]).

use crate::Error;
pub(crate) use crate::rigid::Rigid;
use dhgen_model::{Convention, JointKind, JointValue, Link, RobotModel};
use nalgebra::{Matrix3, Vector3};
use std::path::Path;

/// The constants of one moving body (link i with the joint that moves it).
///
/// Each body carries a *joint frame* in which its joint is a pure `Rz(q)` or `Tz(q)` about
/// or along the frame's z axis: for modified DH that is link frame i itself; for standard DH
/// it is link frame i−1 turned by the joint (same origin and z axis), and link frame i is
/// fixed in it. Both follow from [`Link::transform`]: standard DH gives
/// `A_i(q) = J(q) · A_i(0)` and modified DH `A_i(q) = A_i(0) · J(q)`, with
/// `J = Rz` (revolute) or `Tz` (prismatic), because `Rz` and `Tz` commute.
#[derive(Clone, Debug)]
pub(crate) struct Body {
    /// Revolute or prismatic.
    pub joint: JointKind,
    /// The joint frame at q = 0 in the previous body's joint frame (in the world frame for
    /// the first body, so the base pose is folded in).
    pub parent_to_joint: Rigid,
    /// Link frame i in the joint frame; `None` for the identity (modified DH).
    pub link_in_joint: Option<Rigid>,
    /// Mass, kg (0 for a kinematics-only robot).
    pub mass: f64,
    /// Centre of mass in the joint frame.
    pub com: Vector3<f64>,
    /// Inertia about the centre of mass, joint-frame axes.
    pub inertia: Matrix3<f64>,
    /// Reflected motor inertia `Jm·G²`, added to `D_ii`.
    pub armature: f64,
    /// Viscous friction coefficient.
    pub viscous: f64,
    /// Coulomb friction.
    pub coulomb: f64,
}

/// A serial robot arm built at run time from a description, with its kinematics and rigid
/// body dynamics.
///
/// # Frames and units
/// Every pose, axis and vector this type takes or returns is expressed in the *world
/// frame*: the frame in which the description's `base` pose is given (the same frame as DH
/// frame 0 when there is no `base`). The description's `gravity` is taken in that frame too,
/// as in Robotics Toolbox and Pinocchio: rotating the base turns the robot, not gravity.
/// Units are SI; joint values are radians (revolute) or metres (prismatic), and include no
/// offset: the description's `theta` (revolute) or `d` (prismatic) is added internally.
///
/// # Panics
/// Every method taking joint vectors (`q`, `qd`, `qdd`, `tau`) panics when a slice does not
/// have exactly [`dof`](Robot::dof) entries, naming the argument and both lengths, e.g.
/// ``dhgen::Robot::fk: `q` has length 5, expected 6 (one entry per joint)``.
/// The dynamics methods also panic for a kinematics-only description (no mass
/// properties); check [`has_dynamics`](Robot::has_dynamics) first.
///
/// ```
/// let robot = dhgen::Robot::from_toml_str(r#"
///     name = "planar"
///     convention = "standard"
///     gravity = [0, -9.81, 0]
///     [[links]]
///     joint = "revolute"
///     a = 1.0
///     alpha = 0
///     d = 0
///     theta = 0
///     mass = 2.0
///     com = [-0.5, 0, 0]
///     inertia = { yy = 0.1, zz = 0.1 }
/// "#).unwrap();
/// let pose = robot.fk(&[std::f64::consts::FRAC_PI_2]);
/// assert!((pose.translation.vector.y - 1.0).abs() < 1e-12);
/// // Holding the arm horizontal takes m·g·l/2.
/// let g = robot.gravity(&[0.0]);
/// assert!((g[0] - 2.0 * 9.81 * 0.5).abs() < 1e-12);
/// ```
#[derive(Clone, Debug)]
pub struct Robot {
    pub(crate) model: RobotModel,
    pub(crate) bodies: Vec<Body>,
    /// The tool frame in the last body's joint frame.
    pub(crate) tool: Rigid,
    /// Gravitational acceleration in the world frame.
    pub(crate) gravity: Vector3<f64>,
    pub(crate) has_dynamics: bool,
}

/// `A_i(0)`: the link transform with the joint at zero (offsets applied).
fn transform_at_zero(link: &Link, convention: Convention) -> Rigid {
    let zero = match link.joint {
        JointKind::Revolute => JointValue::Revolute { cos: 1.0, sin: 0.0 },
        JointKind::Prismatic => JointValue::Prismatic(0.0),
    };
    Rigid::from_frame(&link.transform(convention, zero))
}

impl Robot {
    /// Builds a robot from a validated model, precomputing the per-link constants.
    pub fn from_model(model: RobotModel) -> Robot {
        let convention = model.convention;
        let base = model
            .base_pose()
            .map_or(Rigid::IDENTITY, |p| Rigid::from_frame(&p.frame()));
        let tool = model
            .tool_pose()
            .map_or(Rigid::IDENTITY, |p| Rigid::from_frame(&p.frame()));
        let at_zero: Vec<Rigid> = model
            .links
            .iter()
            .map(|l| transform_at_zero(l, convention))
            .collect();
        let bodies: Vec<Body> = model
            .links
            .iter()
            .enumerate()
            .map(|(i, link)| {
                let (parent_to_joint, link_in_joint) = match convention {
                    Convention::Standard => {
                        let previous = if i == 0 { base } else { at_zero[i - 1] };
                        (previous, Some(at_zero[i]))
                    }
                    Convention::Modified => {
                        let joint = if i == 0 {
                            base.compose(&at_zero[0])
                        } else {
                            at_zero[i]
                        };
                        (joint, None)
                    }
                };
                let to_joint = link_in_joint.unwrap_or(Rigid::IDENTITY);
                let (mass, com, inertia) = match &link.inertial {
                    Some(inertial) => {
                        let c = Vector3::from(inertial.com);
                        let i = Matrix3::from_fn(|r, k| inertial.inertia[r][k]);
                        (
                            inertial.mass,
                            to_joint.r * c + to_joint.p,
                            to_joint.r * i * to_joint.r.transpose(),
                        )
                    }
                    None => (0.0, Vector3::zeros(), Matrix3::zeros()),
                };
                Body {
                    joint: link.joint,
                    parent_to_joint,
                    link_in_joint,
                    mass,
                    com,
                    inertia,
                    armature: link.motor.map_or(0.0, |m| m.reflected_inertia()),
                    viscous: link.friction.map_or(0.0, |f| f.viscous),
                    coulomb: link.friction.map_or(0.0, |f| f.coulomb),
                }
            })
            .collect();
        let last = bodies
            .last()
            .expect("a validated model has at least one link");
        let tool = last.link_in_joint.unwrap_or(Rigid::IDENTITY).compose(&tool);
        Robot {
            gravity: Vector3::from(model.gravity),
            has_dynamics: model.has_dynamics(),
            tool,
            bodies,
            model,
        }
    }

    /// Parses and validates a TOML description (see the description format); errors name
    /// the source as `<string>`, the link and the field.
    pub fn from_toml_str(text: &str) -> Result<Robot, Error> {
        Ok(Robot::from_model(RobotModel::from_toml_str(text)?))
    }

    /// Reads, parses and validates a TOML description file; errors name the file, the link
    /// and the field.
    pub fn from_toml_file(path: impl AsRef<Path>) -> Result<Robot, Error> {
        Ok(Robot::from_model(RobotModel::from_toml_file(path)?))
    }

    /// The validated model this robot was built from.
    pub fn model(&self) -> &RobotModel {
        &self.model
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.bodies.len()
    }

    /// True when the description gives mass properties, so the dynamics methods may be
    /// called.
    pub fn has_dynamics(&self) -> bool {
        self.has_dynamics
    }

    /// Panics unless `v` has one entry per joint.
    #[inline]
    #[track_caller]
    pub(crate) fn check_len(&self, method: &str, arg: &str, v: &[f64]) {
        let n = self.bodies.len();
        if v.len() != n {
            panic!(
                "dhgen::Robot::{method}: `{arg}` has length {}, expected {n} (one entry per joint)",
                v.len()
            );
        }
    }

    /// Panics for a kinematics-only robot.
    #[inline]
    #[track_caller]
    pub(crate) fn check_dynamics(&self, method: &str) {
        if !self.has_dynamics {
            panic!(
                "dhgen::Robot::{method}: robot `{}` has no mass properties (a kinematics-only \
                 description); check Robot::has_dynamics() before calling dynamics methods",
                self.model.name
            );
        }
    }
}
