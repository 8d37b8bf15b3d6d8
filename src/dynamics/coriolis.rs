//! The Christoffel-consistent Coriolis matrix in O(n²).

use super::accumulate_composites;
use super::spatial::{Force, Motion};
use crate::Joints;
use crate::robot::Robot;
use nalgebra::{DMatrix, Matrix3, Vector3};

/// The cross-product matrix `x̂` with `x̂ y = x × y`.
#[inline]
fn hat(x: &Vector3<f64>) -> Matrix3<f64> {
    Matrix3::new(0.0, -x.z, x.y, x.z, 0.0, -x.x, -x.y, x.x, 0.0)
}

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
        // In world coordinates B = [[P, 0], [−l×, 0]] with P = ½(İ_ωω − n×), where İ_ωω is
        // the rate of change of the rotational inertia about the origin and [n; l] = I v the
        // momentum; so B composes from a 3×3 matrix and a vector per body.
        let mut velocity = Motion::ZERO;
        let mut axis_rate = Vec::with_capacity(n);
        let mut p = Vec::with_capacity(n);
        let mut l = Vec::with_capacity(n);
        for (state, &qdi) in states.iter().zip(qd) {
            velocity = velocity + state.axis * qdi;
            axis_rate.push(velocity.cross(&state.axis));
            let inertia = &state.inertia;
            let momentum = inertia.apply(&velocity);
            let (w, u) = (&velocity.ang, &velocity.lin);
            let w_hat = hat(w);
            let k_rate = w_hat * inertia.k - inertia.k * w_hat
                + Matrix3::from_diagonal_element(2.0 * inertia.h.dot(u))
                - u * inertia.h.transpose()
                - inertia.h * u.transpose();
            p.push((k_rate - hat(&momentum.ang)) * 0.5);
            l.push(momentum.lin);
        }
        accumulate_composites(&mut states);
        for i in (1..n).rev() {
            let (pi, li) = (p[i], l[i]);
            p[i - 1] += pi;
            l[i - 1] += li;
        }
        let mut c = DMatrix::zeros(n, n);
        for j in 0..n {
            let s = &states[j].axis;
            let composite = &states[j].composite;
            let rate = composite.apply(&axis_rate[j]);
            let f1 = Force {
                ang: rate.ang + p[j] * s.ang,
                lin: rate.lin + s.ang.cross(&l[j]),
            };
            let f2 = composite.apply(s);
            let f3 = Force {
                ang: p[j].transpose() * s.ang + l[j].cross(&s.lin),
                lin: Vector3::zeros(),
            };
            c[(j, j)] = s.dot(&f1);
            for k in 0..j {
                // Row k < j: C_kj; column k < j of row j: C_jk.
                c[(k, j)] = states[k].axis.dot(&f1);
                c[(j, k)] = axis_rate[k].dot(&f2) + states[k].axis.dot(&f3);
            }
        }
        c
    }
}
