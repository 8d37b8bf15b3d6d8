//! The Christoffel-consistent Coriolis matrix in O(n²).

use crate::Joints;
use crate::recursive::{CoriolisBody, coriolis_into};
use crate::robot::Robot;
use nalgebra::DMatrix;

impl Robot {
    /// The Coriolis and centrifugal matrix `C(q, q̇)` with `C_kj = Σ_i c_ijk q̇_i`
    /// (the Christoffel symbols of [`christoffel`](Robot::christoffel)), so that
    /// `C q̇` is the Coriolis and centrifugal torque and `Ḋ − 2C` is skew-symmetric.
    /// Friction and motor inertia do not enter.
    ///
    /// Computed in O(n²) without the symbols (Echeandia & Wensing, "Numerical methods to
    /// compute the Coriolis matrix and Christoffel symbols for rigid-body systems", 2021):
    /// each body contributes `B = ½(v×* I − I v× + (I v)×̄)`, summed tip to base into `B^C`;
    /// with `Ṡ_j = v_j × S_j`, `C_kj = S_k·(I^C_j Ṡ_j + B^C_j S_j)` for `k ≤ j` and
    /// `C_kj = Ṡ_j·I^C_k S_k + S_j·B^C_kᵀ S_k` for `k > j`.
    ///
    /// # Panics
    /// If `q` or `qd` does not have `self.dof()` entries, or if the robot has no mass
    /// properties.
    #[doc(alias = "computeCoriolisMatrix")]
    pub fn coriolis(
        &self,
        q: &(impl Joints<f64> + ?Sized),
        qd: &(impl Joints<f64> + ?Sized),
    ) -> DMatrix<f64> {
        let q = self.check_len("coriolis", "q", q);
        let qd = self.check_len("coriolis", "qd", qd);
        self.check_dynamics("coriolis");
        let n = self.dof();
        let mut states = self.body_states(q);
        let mut scratch = vec![CoriolisBody::zero(); n];
        let mut c = DMatrix::zeros(n, n);
        coriolis_into(&mut states, qd, &mut scratch, |k, j, v| c[(k, j)] = v);
        c
    }
}
