//! The Christoffel symbols from analytic derivatives of the mass matrix.

use super::accumulate_composites;
use crate::Joints;
use crate::recursive::christoffel_into;
use crate::robot::Robot;
use core::ops::Index;
use dhgen_kernel::{Force, Motion};

/// The Christoffel symbols of the first kind of `D(q)`, in the textbook's index order
/// (Spong, eq. 7.52): `c[i][j][k] = c_ijk = ½ (∂d_kj/∂q_i + ∂d_ki/∂q_j − ∂d_ij/∂q_k)`,
/// where **k is the equation index** and i, j index velocities: the Coriolis and
/// centrifugal torque of joint k is `Σ_ij c_ijk q̇_i q̇_j`, and `C_kj = Σ_i c_ijk q̇_i`.
/// Symmetric in i and j.
///
/// Other sources put the equation index first (Robotics Toolbox's `Gamma[k][j][i]`,
/// Pinocchio's `C[k][i][j]`): there `Gamma[k][j][i] = c[i][j][k]`.
///
/// Indexed as `c[i][j][k]` (each `c[i]` is a [`ChristoffelPlane`]) or `c.get(i, j, k)`.
#[derive(Clone, Debug, PartialEq)]
pub struct Christoffel {
    planes: Vec<ChristoffelPlane>,
}

/// The n×n symbols `c_ijk` for one velocity index i, indexed `[j][k]`.
#[derive(Clone, Debug, PartialEq)]
pub struct ChristoffelPlane {
    n: usize,
    /// Row-major: `values[j * n + k] = c_ijk`.
    values: Vec<f64>,
}

impl Christoffel {
    /// Number of joints n (the symbols form an n×n×n array).
    pub fn dof(&self) -> usize {
        self.planes.len()
    }

    /// `c_ijk`, k the equation index.
    ///
    /// # Panics
    /// If an index is not below [`dof`](Christoffel::dof).
    pub fn get(&self, i: usize, j: usize, k: usize) -> f64 {
        self[i][j][k]
    }
}

impl Index<usize> for Christoffel {
    type Output = ChristoffelPlane;
    fn index(&self, i: usize) -> &ChristoffelPlane {
        &self.planes[i]
    }
}

impl Index<usize> for ChristoffelPlane {
    type Output = [f64];
    fn index(&self, j: usize) -> &[f64] {
        assert!(
            j < self.n,
            "Christoffel index {j} out of range for {} joints",
            self.n
        );
        &self.values[j * self.n..(j + 1) * self.n]
    }
}

impl Robot {
    /// The Christoffel symbols `c_ijk` of `D(q)` (k the equation index, see
    /// [`Christoffel`]), from the analytic derivatives of `D`, never finite differences.
    /// Motor inertias are constant and so do not enter.
    ///
    /// With `S_i` the world-frame joint screws, `I^C_l` the composite inertia of the bodies
    /// from l on and `×` the spatial cross product, for `a ≤ b`:
    /// `∂D_ab/∂q_l` is 0 for `l ≤ a` (moving joint l then moves both joints and every body
    /// involved rigidly), `(S_a × S_l)·I^C_b S_b` for `a < l < b`, and
    /// `(S_a × S_l)·I^C_l S_b + (S_b × S_l)·I^C_l S_a` for `l ≥ b`.
    ///
    /// # Panics
    /// If `q.len() != self.dof()`, or if the robot has no mass properties.
    pub fn christoffel(&self, q: &(impl Joints<f64> + ?Sized)) -> Christoffel {
        let q = self.check_len("christoffel", "q", q);
        self.check_dynamics("christoffel");
        let n = self.dof();
        let mut states = self.body_states(q);
        accumulate_composites(&mut states);
        let mut moved = vec![Force::zero(); n * n];
        let mut screw = vec![Motion::zero(); n * n];
        let mut all = vec![0.0; n * n * n];
        christoffel_into(&states, &mut moved, &mut screw, &mut all);
        let planes = all
            .chunks_exact(n * n)
            .map(|plane| ChristoffelPlane {
                n,
                values: plane.to_vec(),
            })
            .collect();
        Christoffel { planes }
    }
}
