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

    /// `D(q)` from body states whose composites are accumulated: with `F_j = I^C_j S_j` the
    /// force needed to move joint j alone at unit acceleration, `D_ij = S_i · F_j` for
    /// `i ≤ j` (joint i feels what moves beyond both joints).
    pub(crate) fn crba(&self, states: &[BodyState]) -> DMatrix<f64> {
        let n = states.len();
        let mut d = DMatrix::zeros(n, n);
        for j in 0..n {
            let f = states[j].composite.apply(&states[j].axis);
            d[(j, j)] = states[j].axis.dot(&f) + self.bodies[j].armature;
            for i in 0..j {
                let dij = states[i].axis.dot(&f);
                d[(i, j)] = dij;
                d[(j, i)] = dij;
            }
        }
        d
    }
}
