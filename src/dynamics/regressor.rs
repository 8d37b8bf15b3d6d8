//! The inverse dynamics are linear in the inertial parameters: `τ = Y(q, q̇, q̈) π`, the joint
//! torque regressor `Y`, and the robot's own parameters `π`, in the order and frames of
//! [`dhgen_description::parameters`] (the generated regressor's too).

use crate::Joints;
use crate::robot::{Rigid, Robot};
use dhgen_kernel::{Force, Inertia, Motion};
use nalgebra::{DMatrix, DVector, Matrix3, Vector3};

use dhgen_description::parameters::BODY_PARAMETERS;
use dhgen_description::parameters::{self as layout, Column};

/// The spatial inertia whose parameters are `p` (about the frame's origin).
pub(crate) fn inertia_of(p: &[f64; BODY_PARAMETERS]) -> Inertia {
    Inertia {
        mass: p[0],
        h: Vector3::new(p[1], p[2], p[3]),
        k: Matrix3::from(layout::inertia_of(p)).transpose(),
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

impl Robot {
    /// The number of parameters, `10·n` plus the joint-side ones (see the
    /// [`dhgen::parameters`](crate::parameters)).
    pub fn parameter_count(&self) -> usize {
        layout::columns(&self.model).len()
    }

    /// The names of the parameters, in order: `m1, mx1, my1, mz1, Ixx1, Ixy1, Iyy1, Ixz1,
    /// Iyz1, Izz1, m2, ...`, then `Ia3` (armature of joint 3), `fv3`, `fc3` (viscous and
    /// Coulomb friction of joint 3) where the description has them.
    pub fn parameter_names(&self) -> Vec<String> {
        layout::names(&self.model)
    }

    /// The robot's own parameters `π` (see the [`dhgen::parameters`](crate::parameters) for the order and frames):
    /// `regressor(q, q̇, q̈) · parameters() = inverse_dynamics(q, q̇, q̈)`.
    ///
    /// # Panics
    /// If the robot has no mass properties.
    #[doc(alias = "toDynamicParameters")]
    pub fn parameters(&self) -> DVector<f64> {
        self.check_dynamics("parameters");
        DVector::from_vec(
            layout::values(&self.model).expect("checked: every link has mass properties"),
        )
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
        for (c, column) in layout::columns(&self.model).into_iter().enumerate() {
            match column {
                Column::Body { .. } => {}
                Column::Armature(i) => y[(i, c)] = qdd[i],
                Column::Viscous(i) => y[(i, c)] = qd[i],
                Column::Coulomb(i) => y[(i, c)] = crate::Real::sign(qd[i]),
            }
        }
        y
    }
}
