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
    /// Returns `None` where `D(q)` is singular to working precision: a pivot of its Cholesky
    /// factorisation at or below [`cholesky_pivot_floor`](crate::cholesky_pivot_floor),
    /// the rule generated code follows too. A physical description never produces it; a
    /// description whose links carry no inertia about their joint axes (Robotics Toolbox's
    /// UR3 and UR5) does, at every configuration. It also returns `None` when the acceleration
    /// it finds is not finite: an input that is NaN or infinite, or one so large that the
    /// arithmetic overflows (see "Non-finite input" in docs/conventions.md).
    ///
    /// # Panics
    /// If `q`, `qd` or `tau` does not have `self.dof()` entries, or if the robot has no mass
    /// properties.
    #[doc(alias = "aba")]
    #[doc(alias = "accel")]
    #[doc(alias = "fdyn")]
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
        let cholesky = crate::inertia_cholesky(d)?;
        cholesky.solve_mut(&mut rhs);
        // Only a finite acceleration is an answer (the generated code's rule too).
        rhs.iter().all(|x| x.is_finite()).then_some(rhs)
    }
}
