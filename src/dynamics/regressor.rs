//! The inverse dynamics are linear in the inertial parameters: `τ = Y(q, q̇, q̈) π`, the joint
//! torque regressor `Y`, and the robot's own parameters `π`.
//!
//! # The parameters
//! Ten per link, in Pinocchio's order (`Inertia::toDynamicParameters`), expressed in that
//! link's frame (the frame the description gives its `com` and `inertia` in: DH frame i, or
//! the URDF link frame), about the frame's origin, as identification practice writes them:
//!
//! `m, m·cx, m·cy, m·cz, Ixx, Ixy, Iyy, Ixz, Iyz, Izz`
//!
//! with `c` the centre of mass and `I = I_c + m (|c|² 1 − c cᵀ)` the inertia tensor about the
//! link frame's origin (`Ixy` the tensor entry, `−∫xy dm`). After the 10·n link columns come the
//! joint-side terms where the description has them, joint by joint: the armature `Jm·G²` (a
//! joint with a `motor`; column `q̈_i`), then the viscous and Coulomb coefficients (a joint
//! with `friction`; columns `q̇_i` and `sign(q̇_i)`). [`Robot::parameter_names`] names every
//! column.

use super::spatial::{Force, Inertia, Motion};
use crate::Joints;
use crate::robot::{Rigid, Robot};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

/// The number of inertial parameters of one body.
pub const BODY_PARAMETERS: usize = 10;

/// The names of a body's ten parameters, in order (`m`, `mx` for `m·cx`, ..., `Izz`).
pub const BODY_PARAMETER_NAMES: [&str; BODY_PARAMETERS] = [
    "m", "mx", "my", "mz", "Ixx", "Ixy", "Iyy", "Ixz", "Iyz", "Izz",
];

/// The ten parameters of a body of mass `mass`, centre of mass `com` and inertia `i_com` about
/// it, all in one frame: `[m, m·c, I about the origin]` in the order of [`BODY_PARAMETER_NAMES`].
pub fn body_parameters(mass: f64, com: &[f64; 3], i_com: &[[f64; 3]; 3]) -> [f64; BODY_PARAMETERS] {
    let i = Inertia::from_com(
        mass,
        &Vector3::from(*com),
        &Matrix3::from_fn(|a, b| i_com[a][b]),
    );
    let (h, k) = (i.h, i.k);
    [
        i.mass,
        h.x,
        h.y,
        h.z,
        k[(0, 0)],
        k[(0, 1)],
        k[(1, 1)],
        k[(0, 2)],
        k[(1, 2)],
        k[(2, 2)],
    ]
}

/// The spatial inertia whose parameters are `p` (about the frame's origin).
pub(crate) fn inertia_of(p: &[f64; BODY_PARAMETERS]) -> Inertia {
    Inertia {
        mass: p[0],
        h: Vector3::new(p[1], p[2], p[3]),
        k: Matrix3::new(p[4], p[5], p[7], p[5], p[6], p[8], p[7], p[8], p[9]),
    }
}

/// A motion vector about the world origin seen in a frame at `pose`.
fn motion_in(pose: &Rigid, m: &Motion) -> Motion {
    let rt = pose.r.transpose();
    Motion {
        ang: rt * m.ang,
        lin: rt * (m.lin + m.ang.cross(&pose.p)),
    }
}

/// A force given in a frame at `pose`, about the world origin in world axes.
fn force_from(pose: &Rigid, f: &Force) -> Force {
    let lin = pose.r * f.lin;
    Force {
        ang: pose.r * f.ang + pose.p.cross(&lin),
        lin,
    }
}

/// Which joint-side columns the robot has: per joint, armature and friction.
pub(crate) fn joint_columns(robot: &Robot) -> Vec<(usize, JointTerm)> {
    let mut out = Vec::new();
    for (i, l) in robot.model.links.iter().enumerate() {
        if l.motor.is_some() {
            out.push((i, JointTerm::Armature));
        }
        if l.friction.is_some() {
            out.push((i, JointTerm::Viscous));
            out.push((i, JointTerm::Coulomb));
        }
    }
    out
}

/// A joint-side parameter.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum JointTerm {
    Armature,
    Viscous,
    Coulomb,
}

impl Robot {
    /// The number of parameters, `10·n` plus the joint-side ones (see the
    /// [`dhgen::parameters`](crate::parameters)).
    pub fn parameter_count(&self) -> usize {
        BODY_PARAMETERS * self.dof() + joint_columns(self).len()
    }

    /// The names of the parameters, in order: `m1, mx1, my1, mz1, Ixx1, Ixy1, Iyy1, Ixz1,
    /// Iyz1, Izz1, m2, ...`, then `Ia3` (armature of joint 3), `fv3`, `fc3` (viscous and
    /// Coulomb friction of joint 3) where the description has them.
    pub fn parameter_names(&self) -> Vec<String> {
        let mut names = Vec::with_capacity(self.parameter_count());
        for j in 1..=self.dof() {
            names.extend(BODY_PARAMETER_NAMES.iter().map(|n| format!("{n}{j}")));
        }
        for (i, term) in joint_columns(self) {
            let prefix = match term {
                JointTerm::Armature => "Ia",
                JointTerm::Viscous => "fv",
                JointTerm::Coulomb => "fc",
            };
            names.push(format!("{prefix}{}", i + 1));
        }
        names
    }

    /// The robot's own parameters `π` (see the [`dhgen::parameters`](crate::parameters) for the order and frames):
    /// `regressor(q, q̇, q̈) · parameters() = inverse_dynamics(q, q̇, q̈)`.
    ///
    /// # Panics
    /// If the robot has no mass properties.
    #[doc(alias = "toDynamicParameters")]
    pub fn parameters(&self) -> DVector<f64> {
        self.check_dynamics("parameters");
        let mut pi = Vec::with_capacity(self.parameter_count());
        for l in &self.model.links {
            let i = l.inertial.expect("checked: every link has mass properties");
            pi.extend(body_parameters(i.mass, &i.com, &i.inertia));
        }
        for (i, term) in joint_columns(self) {
            let l = &self.model.links[i];
            pi.push(match term {
                JointTerm::Armature => l.motor.map_or(0.0, |m| m.armature()),
                JointTerm::Viscous => l.friction.map_or(0.0, |f| f.viscous),
                JointTerm::Coulomb => l.friction.map_or(0.0, |f| f.coulomb),
            });
        }
        DVector::from_vec(pi)
    }

    /// The joint torque regressor `Y(q, q̇, q̈)`, `n × parameter_count()`, with
    /// `τ = Y π` for every `π` (`parameters()` gives the robot's own): what least-squares
    /// identification stacks over a trajectory. Column `10 j + k` is the torque that
    /// parameter `k` of link `j + 1` contributes per unit; O(n²).
    ///
    /// # Panics
    /// If `q`, `qd` or `qdd` does not have `self.dof()` entries, or if the robot has no mass
    /// properties.
    #[doc(alias = "computeJointTorqueRegressor")]
    pub fn regressor(
        &self,
        q: &(impl Joints<f64> + ?Sized),
        qd: &(impl Joints<f64> + ?Sized),
        qdd: &(impl Joints<f64> + ?Sized),
    ) -> DMatrix<f64> {
        let q = self.check_len("regressor", "q", q);
        let qd = self.check_len("regressor", "qd", qd);
        let qdd = self.check_len("regressor", "qdd", qdd);
        self.check_dynamics("regressor");
        let n = self.dof();
        let states = self.body_states(q);
        let motions = self.rnea_forward(&states, qd, Some(qdd));
        let mut links = Vec::with_capacity(n);
        self.walk_joint_frames(q, |i, frame| {
            links.push(match &self.bodies[i].link {
                Some(l) => frame.compose(l),
                None => *frame,
            });
        });
        let mut y = DMatrix::zeros(n, self.parameter_count());
        for (j, (pose, m)) in links.iter().zip(&motions).enumerate() {
            let v = motion_in(pose, &m.velocity);
            let a = motion_in(pose, &m.acceleration);
            for k in 0..BODY_PARAMETERS {
                let mut unit = [0.0; BODY_PARAMETERS];
                unit[k] = 1.0;
                let inertia = inertia_of(&unit);
                let momentum = inertia.apply(&v);
                let f = force_from(pose, &(inertia.apply(&a) + v.cross_force(&momentum)));
                for (i, state) in states.iter().enumerate().take(j + 1) {
                    y[(i, BODY_PARAMETERS * j + k)] = state.axis.dot(&f);
                }
            }
        }
        for (c, (i, term)) in joint_columns(self).into_iter().enumerate() {
            y[(i, BODY_PARAMETERS * n + c)] = match term {
                JointTerm::Armature => qdd[i],
                JointTerm::Viscous => qd[i],
                JointTerm::Coulomb => super::sign(qd[i]),
            };
        }
        y
    }
}
