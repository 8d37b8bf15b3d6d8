//! The gravity torques from composite mass moments, the potential energy they are the
//! gradient of, and the centre of mass.

use super::joint_axis;
use crate::ArmDynamics;
use crate::Joints;
use crate::robot::Robot;
use dhgen_kernel::Motion;
use nalgebra::{DVector, Matrix3xX, Point3, Vector3};

impl Robot {
    /// The gravity torques `g(q)`: the joint torques (forces) that hold the arm still
    /// against the description's gravity, `g = ∂P/∂q` with the potential energy
    /// `P = −Σ m_i gravity · c_i`. Friction and motor inertia do not enter.
    ///
    /// # Panics
    /// If `q.len() != self.dof()`, or if the robot has no mass properties.
    #[doc(alias = "gravload")]
    #[doc(alias = "computeGeneralizedGravity")]
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

    /// The potential energy `P(q) = −Σ m_i gravity · c_i` of the links in the description's
    /// gravity, centres of mass `c_i` in the world frame (so zero at the world origin, and the
    /// base pose counts): the text's `Σ gᵗ r_ci m_i` with its `g` pointing up. The gravity
    /// torques are its gradient, `g(q) = ∂P/∂q`; with no torque and no friction acting,
    /// `T + P` is conserved.
    ///
    /// ```
    /// let robot = dhgen::Robot::from_file("robots/planar_elbow.toml").unwrap();
    /// let (q, h) = ([0.3, -0.5], 1e-6);
    /// let nudged = [q[0], q[1] + h];
    /// let slope = (robot.potential_energy(&nudged) - robot.potential_energy(&q)) / h;
    /// assert!((slope - robot.gravity(&q)[1]).abs() < 1e-4);
    /// ```
    ///
    /// # Panics
    /// If `q.len() != self.dof()`, or if the robot has no mass properties.
    #[doc(alias = "computePotentialEnergy")]
    pub fn potential_energy(&self, q: &(impl Joints<f64> + ?Sized)) -> f64 {
        let q = self.check_len("potential_energy", "q", q);
        self.check_dynamics("potential_energy");
        crate::recursive::potential_energy(self.chain(), |i| self.joint_value(i, q[i]))
    }

    /// The links' total mass and centre of mass in the world frame at `q`
    /// ([`ArmDynamics::center_of_mass`](crate::ArmDynamics::center_of_mass)).
    ///
    /// # Panics
    /// If `q.len() != self.dof()`, or if the robot has no mass properties.
    #[doc(alias = "centerOfMass")]
    pub fn center_of_mass(&self, q: &(impl Joints<f64> + ?Sized)) -> (f64, Point3<f64>) {
        let q = self.check_len("center_of_mass", "q", q);
        self.check_dynamics("center_of_mass");
        ArmDynamics::center_of_mass(self, &DVector::from_column_slice(q))
    }

    /// The Jacobian of the centre of mass, 3×n in world axes
    /// ([`ArmDynamics::center_of_mass_jacobian`](crate::ArmDynamics::center_of_mass_jacobian)).
    ///
    /// # Panics
    /// If `q.len() != self.dof()`, or if the robot has no mass properties.
    #[doc(alias = "jacobianCenterOfMass")]
    pub fn center_of_mass_jacobian(&self, q: &(impl Joints<f64> + ?Sized)) -> Matrix3xX<f64> {
        let q = self.check_len("center_of_mass_jacobian", "q", q);
        self.check_dynamics("center_of_mass_jacobian");
        ArmDynamics::center_of_mass_jacobian(self, &DVector::from_column_slice(q))
    }
}
