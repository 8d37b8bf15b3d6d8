//! The gravity torques from composite mass moments.

use super::joint_axis;
use crate::Joints;
use crate::robot::Robot;
use crate::spatial::Motion;
use nalgebra::{DVector, Vector3};

impl Robot {
    /// The gravity torques `g(q)`: the joint torques (forces) that hold the arm still
    /// against the description's gravity, `g = ∂P/∂q` with the potential energy
    /// `P = −Σ m_i gravity · c_i`. Friction and motor inertia do not enter.
    ///
    /// # Panics
    /// If `q.len() != self.dof()`, or if the robot has no mass properties.
    pub fn gravity(&self, q: &(impl Joints<f64> + ?Sized)) -> DVector<f64> {
        let q = self.check_len("gravity", "q", q);
        self.check_dynamics("gravity");
        // Only the mass and first mass moment of each body matter: the gravity force of
        // the bodies beyond joint i acts at their common centre of mass.
        let mut bodies: Vec<(Motion, f64, Vector3<f64>)> = Vec::with_capacity(self.dof());
        self.walk_joint_frames(q, |i, frame| {
            let body = &self.bodies[i];
            let axis = joint_axis(body.joint, frame);
            let moment = (frame.r * body.com + frame.p) * body.mass;
            bodies.push((axis, body.mass, moment));
        });
        // Base acceleration −gravity; the force that accelerates the composite body beyond
        // joint i that way is `[h × (−gravity); −m gravity]` about the world origin.
        let mut g = DVector::zeros(self.dof());
        let mut mass = 0.0;
        let mut moment = Vector3::zeros();
        for (i, (axis, m, h)) in bodies.iter().enumerate().rev() {
            mass += m;
            moment += h;
            g[i] = -axis.ang.dot(&moment.cross(&self.gravity)) - axis.lin.dot(&self.gravity) * mass;
        }
        g
    }
}
