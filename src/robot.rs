//! The generic runtime robot: a validated [`RobotModel`] plus the constants every call
//! needs, computed once at construction (Pinocchio's split between the constant model and
//! the per-call work, which lives in [`crate::kinematics`] and [`crate::dynamics`]).

use crate::{Error, Joints};
use dhgen_description::{ChainRef, JointChain, JointKind, RobotModel};
pub(crate) use dhgen_kernel::Rigid;
use nalgebra::Vector3;
use std::path::Path;

/// The constants of one joint and the link it moves, in the runtime's working form (taken
/// from the model's [`JointChain`], computed once at construction).
///
/// Each body carries its *joint frame* (see [`dhgen_description::chain`]), in which its joint is a
/// pure `Rz(q + offset)` or `Tz(q + offset)` about or along the frame's z axis.
#[derive(Clone, Debug)]
pub(crate) struct BodyConstants {
    /// Revolute or prismatic.
    pub joint: JointKind,
    /// Added to the joint value.
    pub offset: f64,
    /// The link frame in the joint frame; `None` for the identity.
    pub link: Option<Rigid>,
    /// Mass, kg (0 for a kinematics-only robot).
    pub mass: f64,
    /// Centre of mass in the joint frame.
    pub com: Vector3<f64>,
    /// Reflected motor inertia `Jm·G²`, added to `D_ii`.
    pub armature: f64,
    /// Viscous friction coefficient.
    pub viscous: f64,
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
    pub(crate) chain: JointChain,
    pub(crate) bodies: Vec<BodyConstants>,
    /// The tool frame in the last body's joint frame (`P_n`).
    pub(crate) tool: Rigid,
    /// Gravitational acceleration in the world frame.
    pub(crate) gravity: Vector3<f64>,
    pub(crate) has_dynamics: bool,
}

impl Robot {
    /// Builds a robot from a validated model, precomputing the per-link constants from its
    /// kinematic structure ([`RobotModel::chain`]).
    pub fn from_model(model: RobotModel) -> Robot {
        let chain = model.chain();
        let view = chain.view();
        let bodies = view
            .bodies
            .iter()
            .map(|b| {
                let (mass, com) = match &b.inertial {
                    Some(i) => (i.mass, Vector3::from(i.com)),
                    None => (0.0, Vector3::zeros()),
                };
                BodyConstants {
                    joint: b.joint,
                    offset: b.offset,
                    link: (!(b.link.rotation_is_identity() && b.link.p == [0.0; 3]))
                        .then(|| Rigid::from_frame(&b.link)),
                    mass,
                    com,
                    armature: b.armature,
                    viscous: b.friction.viscous,
                }
            })
            .collect();
        Robot {
            gravity: Vector3::from(view.gravity),
            has_dynamics: view.has_dynamics(),
            tool: Rigid::from_frame(&view.placements[view.dof()]),
            bodies,
            chain,
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

    /// Reads a URDF robot (see [`dhgen_description::urdf`]: the serial chain from the root link
    /// to the one end of the movable joints, fixed joints merged, quarter turns within 1e-9
    /// rad read as exact). For a named base or tip, or a wider snapping tolerance, read with
    /// [`dhgen_description::urdf::read`] and build with [`Robot::from_model`].
    ///
    /// ```
    /// let arm = dhgen::Robot::from_urdf_str(r#"
    ///   <robot name="pendulum">
    ///     <link name="base"/>
    ///     <joint name="hinge" type="continuous">
    ///       <parent link="base"/><child link="rod"/><axis xyz="0 1 0"/>
    ///     </joint>
    ///     <link name="rod">
    ///       <inertial>
    ///         <origin xyz="0 0 -0.5"/><mass value="2"/>
    ///         <inertia ixx="0.01" iyy="0.01" izz="0.001" ixy="0" iyz="0" ixz="0"/>
    ///       </inertial>
    ///     </link>
    ///   </robot>"#).unwrap();
    /// assert_eq!(arm.dof(), 1);
    /// // Held horizontal (q = 90° about y puts the rod along −x), gravity pulls with m·g·l.
    /// let g = arm.gravity(&[std::f64::consts::FRAC_PI_2]);
    /// assert!((g[0] - 2.0 * 9.81 * 0.5).abs() < 1e-12);
    /// ```
    pub fn from_urdf_str(text: &str) -> Result<Robot, Error> {
        Ok(Robot::from_model(RobotModel::from_urdf_str(text)?))
    }

    /// Reads a URDF file with the default options (see [`Robot::from_urdf_str`]); errors name
    /// the file, line and column, the link or joint, and the attribute.
    pub fn from_urdf_file(path: impl AsRef<Path>) -> Result<Robot, Error> {
        Ok(Robot::from_model(RobotModel::from_urdf_file(path)?))
    }

    /// Reads a description file of either form: URDF when the name ends in `.urdf`, the TOML
    /// description format otherwise.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Robot, Error> {
        let path = path.as_ref();
        if dhgen_description::urdf::is_urdf_path(path) {
            Robot::from_urdf_file(path)
        } else {
            Robot::from_toml_file(path)
        }
    }

    /// The validated model this robot was built from.
    pub fn model(&self) -> &RobotModel {
        &self.model
    }

    /// The robot's kinematic structure (built once from the model).
    pub fn chain(&self) -> ChainRef<'_> {
        self.chain.view()
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

    /// The values of `v`; panics unless it has one entry per joint.
    #[inline]
    #[track_caller]
    pub(crate) fn check_len<'v>(
        &self,
        method: &str,
        arg: &str,
        v: &'v (impl Joints<f64> + ?Sized),
    ) -> &'v [f64] {
        let v = v.joints();
        let n = self.bodies.len();
        if v.len() != n {
            panic!(
                "dhgen::Robot::{method}: `{arg}` has length {}, expected {n} (one entry per joint)",
                v.len()
            );
        }
        v
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
