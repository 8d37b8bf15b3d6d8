//! Forward kinematics and the geometric Jacobian of the runtime [`Robot`].

use crate::Joints;
use crate::robot::{Rigid, Robot};
use dhgen_description::JointKind;
use nalgebra::{Isometry3, Matrix6xX, Vector6};

impl Robot {
    /// Walks the chain base to tip, calling `visit(i, frame)` with the world pose of each
    /// body's joint frame (whose z axis and origin carry joint i), and returns the last one:
    /// [`crate::recursive`]'s walk, which the dynamics share. The caller has checked the
    /// length of `q`.
    #[inline]
    pub(crate) fn walk_joint_frames(
        &self,
        q: &[f64],
        mut visit: impl FnMut(usize, &Rigid),
    ) -> Rigid {
        let chain = self.chain();
        let (r, p) = crate::recursive::walk(
            chain,
            |i| self.joint_value(i, q[i]),
            |i, &r, &p| visit(i, &Rigid { r, p }),
        );
        Rigid { r, p }
    }

    /// Joint `i`'s variable at `q` (offset applied): the cosine and sine of a revolute
    /// joint's full angle, the full displacement of a prismatic one. (Not
    /// `Body::value`, whose exact quarter turns are for the description's constants: a joint
    /// value that happens to be a multiple of π/2 gains nothing from them, and the test costs
    /// a division and a rounding per joint and call.)
    #[inline]
    pub(crate) fn joint_value(&self, i: usize, q: f64) -> dhgen_description::JointValue<f64> {
        let body = &self.bodies[i];
        let v = q + body.offset;
        match body.joint {
            JointKind::Revolute => {
                let (sin, cos) = v.sin_cos();
                dhgen_description::JointValue::Revolute { cos, sin }
            }
            JointKind::Prismatic => dhgen_description::JointValue::Prismatic(v),
        }
    }

    /// Forward kinematics: the tool pose `base · A_1(q_1) ⋯ A_n(q_n) · tool` in the world
    /// frame.
    ///
    /// # Panics
    /// If `q.len() != self.dof()`.
    #[doc(alias = "fkine")]
    #[doc(alias = "forwardKinematics")]
    pub fn fk(&self, q: &(impl Joints<f64> + ?Sized)) -> Isometry3<f64> {
        let q = self.check_len("fk", "q", q);
        self.walk_joint_frames(q, |_, _| {})
            .compose(&self.tool)
            .to_isometry()
    }

    /// The n link frames `base · A_1 ⋯ A_i` (i = 1..n) in the world frame: the base pose is
    /// applied, the tool pose is not.
    ///
    /// # Panics
    /// If `q.len() != self.dof()`.
    #[doc(alias = "updateFramePlacements")]
    pub fn frames(&self, q: &(impl Joints<f64> + ?Sized)) -> Vec<Isometry3<f64>> {
        let q = self.check_len("frames", "q", q);
        let mut frames = Vec::with_capacity(self.dof());
        self.walk_joint_frames(q, |i, joint_frame| {
            let link = match &self.bodies[i].link {
                Some(l) => joint_frame.compose(l),
                None => *joint_frame,
            };
            frames.push(link.to_isometry());
        });
        frames
    }

    /// The 6×n geometric Jacobian of the tool frame origin, in world axes, rows
    /// `[v; ω]`: column i is `[z × (p_e − p_z); z]` for a revolute joint and `[z; 0]` for a
    /// prismatic one, where `z` and `p_z` are joint i's axis and the origin of the frame
    /// carrying it (joint frame i: frame i−1 for standard DH, frame i for modified DH) and
    /// `p_e` is the tool origin.
    ///
    /// # Panics
    /// If `q.len() != self.dof()`.
    #[doc(alias = "jacob0")]
    #[doc(alias = "computeJointJacobians")]
    #[doc(alias = "getFrameJacobian")]
    pub fn jacobian(&self, q: &(impl Joints<f64> + ?Sized)) -> Matrix6xX<f64> {
        let q = self.check_len("jacobian", "q", q);
        self.jacobian_and_last_frame(q).0
    }

    /// The body Jacobian `J_b = diag(Rᵀ, Rᵀ) J` ([`crate::Arm::body_jacobian`]): the tool
    /// origin's velocity and the tool's angular velocity in the tool's own axes, from one walk
    /// of the chain (the Jacobian's, whose last frame gives the tool's rotation `R`).
    ///
    /// # Panics
    /// If `q.len() != self.dof()`.
    #[doc(alias = "jacobe")]
    pub fn body_jacobian(&self, q: &(impl Joints<f64> + ?Sized)) -> Matrix6xX<f64> {
        let q = self.check_len("body_jacobian", "q", q);
        let (j, last) = self.jacobian_and_last_frame(q);
        dhgen_kernel::jacobian::turn_jacobian(&self.tool_rotation_t(&last), j)
    }

    /// `J̇_b q̇` in the tool's own axes ([`crate::Arm::body_jdot_qdot`]), from one walk of the
    /// chain: the Jacobian and the tool's rotation, then `J q̇` and `J̇ q̇` from the Jacobian.
    ///
    /// # Panics
    /// If `q.len()` or `qd.len()` is not `self.dof()`.
    #[doc(alias = "getFrameJacobianTimeVariation")]
    pub fn body_jdot_qdot(
        &self,
        q: &(impl Joints<f64> + ?Sized),
        qd: &(impl Joints<f64> + ?Sized),
    ) -> Vector6<f64> {
        let q = self.check_len("body_jdot_qdot", "q", q);
        let qd = nalgebra::DVector::from_column_slice(self.check_len("body_jdot_qdot", "qd", qd));
        let (j, last) = self.jacobian_and_last_frame(q);
        let jdot_qdot = dhgen_kernel::jacobian::jdot_qdot_from_jacobian(self, &j, &qd);
        dhgen_kernel::jacobian::turn_jdot_qdot(&self.tool_rotation_t(&last), &(j * qd), &jdot_qdot)
    }

    /// `Rᵀ` for the tool's world rotation `R`, from the last joint frame's pose (the tool's
    /// position is not needed by the body quantities).
    fn tool_rotation_t(&self, last: &Rigid) -> nalgebra::Matrix3<f64> {
        (last.r * self.tool.r).transpose()
    }

    /// The Jacobian (as [`jacobian`](Self::jacobian)) and the last joint frame's world pose
    /// (the tool's, less the tool placement), from one walk. The caller has checked the length
    /// of `q`.
    fn jacobian_and_last_frame(&self, q: &[f64]) -> (Matrix6xX<f64>, Rigid) {
        let mut j = Matrix6xX::zeros(self.dof());
        // p_e is only known at the end of the walk, so a revolute column first holds
        // p_z × z = −z × p_z, and z × p_e is added afterwards.
        let last = self.walk_joint_frames(q, |i, frame| {
            let z = frame.r.column(2);
            let mut col = j.column_mut(i);
            match self.bodies[i].joint {
                JointKind::Revolute => {
                    col.fixed_rows_mut::<3>(0).copy_from(&frame.p.cross(&z));
                    col.fixed_rows_mut::<3>(3).copy_from(&z);
                }
                JointKind::Prismatic => col.fixed_rows_mut::<3>(0).copy_from(&z),
            }
        });
        let p_e = last.r * self.tool.p + last.p;
        for (i, body) in self.bodies.iter().enumerate() {
            if body.joint == JointKind::Revolute {
                let z = j.fixed_view::<3, 1>(3, i).into_owned();
                let mut v = j.fixed_view_mut::<3, 1>(0, i);
                v += z.cross(&p_e);
            }
        }
        (j, last)
    }
}
