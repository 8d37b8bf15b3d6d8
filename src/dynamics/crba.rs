//! The joint-space inertia matrix by the composite rigid body algorithm.

use super::{BodyState, accumulate_composites};
use crate::Joints;
use crate::robot::Robot;
use nalgebra::DMatrix;

impl Robot {
    /// The joint-space inertia matrix `D(q)` (n×n, symmetric), by the composite rigid body
    /// algorithm, including the reflected motor inertias `Jm·G²` on the diagonal.
    ///
    /// # Panics
    /// If `q.len() != self.dof()`, or if the robot has no mass properties.
    pub fn mass_matrix(&self, q: &(impl Joints<f64> + ?Sized)) -> DMatrix<f64> {
        let q = self.check_len("mass_matrix", "q", q);
        self.check_dynamics("mass_matrix");
        let mut states = self.body_states(q);
        accumulate_composites(&mut states);
        self.crba(&states)
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
