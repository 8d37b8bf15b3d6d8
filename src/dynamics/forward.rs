//! Forward dynamics: CRBA, RNEA and a Cholesky solve.

use super::accumulate_composites;
use crate::Joints;
use crate::robot::Robot;
use nalgebra::DVector;

impl Robot {
    /// Forward dynamics: the joint accelerations `q̈ = D⁻¹ (τ − C q̇ − g − τ_f)` under joint
    /// torques (forces) `tau`, with `D` including the motor inertias and `τ_f` the joint
    /// friction `viscous·q̇ + coulomb·sign(q̇)` (`sign(0) = 0`, so a joint at rest has no
    /// Coulomb friction). Inverts [`inverse_dynamics`](Robot::inverse_dynamics).
    ///
    /// Returns `None` where `D(q)` is not positive definite (its Cholesky factorisation
    /// fails), which a physical description never produces but a description with
    /// massless links may.
    ///
    /// # Panics
    /// If `q`, `qd` or `tau` does not have `self.dof()` entries, or if the robot has no mass
    /// properties.
    pub fn forward_dynamics(
        &self,
        q: &(impl Joints<f64> + ?Sized),
        qd: &(impl Joints<f64> + ?Sized),
        tau: &(impl Joints<f64> + ?Sized),
    ) -> Option<DVector<f64>> {
        let q = self.check_len("forward_dynamics", "q", q);
        let qd = self.check_len("forward_dynamics", "qd", qd);
        let tau = self.check_len("forward_dynamics", "tau", tau);
        self.check_dynamics("forward_dynamics");
        let mut states = self.body_states(q);
        let bias = self.rnea(&states, qd, None);
        accumulate_composites(&mut states);
        let d = self.crba(&states);
        let mut rhs = DVector::from_fn(self.dof(), |i, _| {
            tau[i] - bias[i] - self.friction(i, qd[i])
        });
        let cholesky = d.cholesky()?;
        cholesky.solve_mut(&mut rhs);
        Some(rhs)
    }
}
