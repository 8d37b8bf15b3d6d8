//! The runtime [`Robot`](crate::Robot) behind the [`Arm`](crate::Arm) and
//! [`ArmDynamics`](crate::ArmDynamics) interface.

use crate::ChainRef;
use crate::Robot;
use crate::{Arm, ArmDynamics};
use nalgebra::{DMatrix, DVector, Dyn, Isometry3, Matrix6xX, Vector6};

impl Arm for Robot {
    type Dof = Dyn;

    fn chain(&self) -> ChainRef<'_> {
        Robot::chain(self)
    }

    fn dof(&self) -> usize {
        Robot::dof(self)
    }

    fn dim(&self) -> Dyn {
        Dyn(Robot::dof(self))
    }

    fn fk(&self, q: &DVector<f64>) -> Isometry3<f64> {
        Robot::fk(self, q)
    }

    fn frames_into(&self, q: &DVector<f64>, out: &mut [Isometry3<f64>]) {
        for (o, f) in out.iter_mut().zip(Robot::frames(self, q)) {
            *o = f;
        }
    }

    fn jacobian(&self, q: &DVector<f64>) -> Matrix6xX<f64> {
        Robot::jacobian(self, q)
    }

    fn body_jacobian(&self, q: &DVector<f64>) -> Matrix6xX<f64> {
        Robot::body_jacobian(self, q)
    }

    fn body_jdot_qdot(&self, q: &DVector<f64>, qd: &DVector<f64>) -> Vector6<f64> {
        Robot::body_jdot_qdot(self, q, qd)
    }
}

impl ArmDynamics for Robot {
    fn mass_matrix(&self, q: &DVector<f64>) -> DMatrix<f64> {
        Robot::mass_matrix(self, q)
    }

    fn christoffel_into(&self, q: &DVector<f64>, out: &mut [f64]) {
        let c = Robot::christoffel(self, q);
        let n = c.dof();
        for (idx, o) in out.iter_mut().enumerate().take(n * n * n) {
            *o = c.get(idx / (n * n), (idx / n) % n, idx % n);
        }
    }

    fn coriolis(&self, q: &DVector<f64>, qd: &DVector<f64>) -> DMatrix<f64> {
        Robot::coriolis(self, q, qd)
    }

    fn gravity(&self, q: &DVector<f64>) -> DVector<f64> {
        Robot::gravity(self, q)
    }

    fn kinetic_energy(&self, q: &DVector<f64>, qd: &DVector<f64>) -> f64 {
        Robot::kinetic_energy(self, q, qd)
    }

    fn potential_energy(&self, q: &DVector<f64>) -> f64 {
        Robot::potential_energy(self, q)
    }

    fn bias(&self, q: &DVector<f64>, qd: &DVector<f64>) -> DVector<f64> {
        Robot::bias(self, q, qd)
    }

    fn inverse_dynamics(
        &self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        qdd: &DVector<f64>,
    ) -> DVector<f64> {
        Robot::inverse_dynamics(self, q, qd, qdd)
    }

    fn forward_dynamics(
        &self,
        q: &DVector<f64>,
        qd: &DVector<f64>,
        tau: &DVector<f64>,
    ) -> Option<DVector<f64>> {
        Robot::forward_dynamics(self, q, qd, tau)
    }
}
