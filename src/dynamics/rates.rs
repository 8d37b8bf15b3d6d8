//! The rate of change of the inertia matrix, Ḋ(q, q̇), and Cᵀ(q, q̇) q̇: the two quantities a
//! generalized-momentum collision observer (De Luca's residual) needs every cycle.

use crate::Joints;
use crate::robot::Robot;
use nalgebra::{DMatrix, DVector};

impl Robot {
    /// The time derivative of the inertia matrix along the motion,
    /// `Ḋ(q, q̇) = Σ_i ∂D/∂q_i q̇_i`, from the identity `Ḋ = C + Cᵀ` (which holds for the
    /// Christoffel-consistent [`coriolis`](Robot::coriolis) matrix): O(n²), exact, no finite
    /// differences. Motor inertia is constant and does not enter.
    ///
    /// ```
    /// let robot = dhgen::Robot::from_toml_file("robots/puma560.toml")?;
    /// let (q, qd) = ([0.1, -0.6, 0.4, 0.3, 0.8, -0.2], [0.2, 0.1, -0.3, 0.0, 0.5, 0.1]);
    /// let d_dot = robot.mass_matrix_rate(&q, &qd);
    /// // Ḋ − 2C is skew-symmetric (passivity).
    /// let n = d_dot - robot.coriolis(&q, &qd) * 2.0;
    /// assert!((&n + n.transpose()).amax() < 1e-12);
    /// # Ok::<(), dhgen::Error>(())
    /// ```
    ///
    /// # Panics
    /// If `q` or `qd` does not have `self.dof()` entries, or if the robot has no mass
    /// properties.
    pub fn mass_matrix_rate(
        &self,
        q: &(impl Joints<f64> + ?Sized),
        qd: &(impl Joints<f64> + ?Sized),
    ) -> DMatrix<f64> {
        let q = self.check_len("mass_matrix_rate", "q", q);
        let qd = self.check_len("mass_matrix_rate", "qd", qd);
        let c = self.coriolis(q, qd);
        &c + c.transpose()
    }

    /// `Cᵀ(q, q̇) q̇`, the term of the generalized-momentum model `ṗ = τ + Cᵀq̇ − g` for
    /// `p = D q̇` (friction aside), from the O(n²) [`coriolis`](Robot::coriolis) matrix.
    ///
    /// # Panics
    /// If `q` or `qd` does not have `self.dof()` entries, or if the robot has no mass
    /// properties.
    pub fn coriolis_transpose_qd(
        &self,
        q: &(impl Joints<f64> + ?Sized),
        qd: &(impl Joints<f64> + ?Sized),
    ) -> DVector<f64> {
        let q = self.check_len("coriolis_transpose_qd", "q", q);
        let qd = self.check_len("coriolis_transpose_qd", "qd", qd);
        self.coriolis(q, qd).tr_mul(&DVector::from_column_slice(qd))
    }
}
