//! The joint-space inertia matrix by the composite rigid body algorithm, and the kinetic
//! energy it is the quadratic form of.

use super::{BodyState, accumulate_composites};
use crate::Joints;
use crate::robot::Robot;
use nalgebra::{DMatrix, DVector};

impl Robot {
    /// The joint-space inertia matrix `D(q)` (n×n, symmetric), by the composite rigid body
    /// algorithm, including the reflected motor inertias `Jm·G²` on the diagonal.
    ///
    /// # Panics
    /// If `q.len() != self.dof()`, or if the robot has no mass properties.
    #[doc(alias = "crba")]
    #[doc(alias = "inertia")]
    pub fn mass_matrix(&self, q: &(impl Joints<f64> + ?Sized)) -> DMatrix<f64> {
        let q = self.check_len("mass_matrix", "q", q);
        self.check_dynamics("mass_matrix");
        let mut states = self.body_states(q);
        accumulate_composites(&mut states);
        self.crba(&states)
    }

    /// The kinetic energy `T(q, q̇) = ½ q̇ᵀ D(q) q̇` of the links and rotors.
    ///
    /// ```
    /// let robot = dhgen::Robot::from_file("robots/planar_elbow.toml").unwrap();
    /// let (q, qd) = ([0.3, -0.5], [1.0, 0.0]);
    /// // The shoulder alone turning at 1 rad/s: T = ½ D₁₁.
    /// let t = robot.kinetic_energy(&q, &qd);
    /// assert!((t - 0.5 * robot.mass_matrix(&q)[(0, 0)]).abs() < 1e-12);
    /// ```
    ///
    /// # Panics
    /// If `q` or `qd` does not have one entry per joint, or if the robot has no mass
    /// properties.
    #[doc(alias = "computeKineticEnergy")]
    pub fn kinetic_energy(
        &self,
        q: &(impl Joints<f64> + ?Sized),
        qd: &(impl Joints<f64> + ?Sized),
    ) -> f64 {
        let qd = DVector::from_column_slice(self.check_len("kinetic_energy", "qd", qd));
        0.5 * qd.dot(&(self.mass_matrix(q) * &qd))
    }

    /// `D(q)` from body states whose composites are accumulated ([`crate::recursive`]'s
    /// CRBA, shared with generated modules of long arms).
    pub(crate) fn crba(&self, states: &[BodyState]) -> DMatrix<f64> {
        let n = states.len();
        let mut d = DMatrix::zeros(n, n);
        crate::recursive::crba(self.chain(), states, |i, j, v| d[(i, j)] = v);
        d
    }
}
