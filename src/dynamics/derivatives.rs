//! Derivatives of the dynamics on the runtime path, analytic and O(n²): ∂τ/∂q by tangents of
//! the world-frame Newton–Euler recursion, ∂τ/∂q̇ = 2C + diag(viscous), and forward dynamics'
//! derivatives ∂q̈/∂x = −D⁻¹ ∂τ/∂x.
//!
//! In world coordinates a change of joint m moves every body after it rigidly by the screw
//! S_m: the axes S_k and inertias I_k of bodies k ≥ m change at the rates
//! `δS_k = S_m × S_k` and `δI_k y = S_m ×* (I_k y) − I_k (S_m × y)`, and nothing before joint
//! m changes. Carrying these tangents through the recursion (one O(n) pass per joint) gives
//! column m of ∂τ/∂q exactly, with no finite differences: the algorithm of Carpentier and
//! Mansard (RSS 2018) in its plainest, forward-mode form.

use crate::Joints;
use crate::robot::Robot;
use dhgen_kernel::{Force, Motion};
use nalgebra::{DMatrix, DVector};

impl Robot {
    /// The derivatives of inverse dynamics, `(∂τ/∂q, ∂τ/∂q̇)` at `(q, q̇, q̈)`, entry `(k, m)` =
    /// ∂τ_k/∂x_m (∂τ/∂q̈ is [`mass_matrix`](Robot::mass_matrix)). Coulomb friction, constant
    /// away from q̇ = 0, contributes 0 (also its subgradient at 0); viscous friction adds its
    /// coefficient to the diagonal of ∂τ/∂q̇. The same as the generated
    /// `inverse_dynamics_derivatives` of `robot!(..., derivatives)`.
    ///
    /// ```
    /// let robot = dhgen::Robot::from_toml_file("robots/puma560.toml")?;
    /// let (q, qd, qdd) = ([0.1, -0.6, 0.4, 0.3, 0.8, -0.2], [0.2; 6], [0.5; 6]);
    /// let (dq, _) = robot.inverse_dynamics_derivatives(&q, &qd, &qdd);
    /// // Column 2 is the rate of change of τ as joint 2 moves.
    /// let h = 1e-6;
    /// let (mut a, mut b) = (q, q);
    /// a[1] += h;
    /// b[1] -= h;
    /// let fd = (robot.inverse_dynamics(&a, &qd, &qdd) - robot.inverse_dynamics(&b, &qd, &qdd)) / (2.0 * h);
    /// assert!((dq.column(1) - fd).amax() < 1e-6);
    /// # Ok::<(), dhgen::Error>(())
    /// ```
    ///
    /// # Panics
    /// If `q`, `qd` or `qdd` does not have `self.dof()` entries, or if the robot has no mass
    /// properties.
    #[doc(alias = "computeRNEADerivatives")]
    pub fn inverse_dynamics_derivatives(
        &self,
        q: &(impl Joints<f64> + ?Sized),
        qd: &(impl Joints<f64> + ?Sized),
        qdd: &(impl Joints<f64> + ?Sized),
    ) -> (DMatrix<f64>, DMatrix<f64>) {
        let q = self.check_len("inverse_dynamics_derivatives", "q", q);
        let qd = self.check_len("inverse_dynamics_derivatives", "qd", qd);
        let qdd = self.check_len("inverse_dynamics_derivatives", "qdd", qdd);
        self.check_dynamics("inverse_dynamics_derivatives");
        let n = self.dof();
        let states = self.body_states(q);
        // The nominal recursion, keeping what the tangents need.
        let bodies = self.rnea_forward(&states, qd, Some(qdd));
        // Transmitted forces F_k = Σ_{j ≥ k} f_j.
        let mut transmitted = vec![Force::zero(); n];
        let mut sum = Force::zero();
        for k in (0..n).rev() {
            sum += bodies[k].force;
            transmitted[k] = sum;
        }
        let mut dq = DMatrix::zeros(n, n);
        // δf_k for the current joint m: zero before m (nothing there moves).
        let mut df = vec![Force::zero(); n];
        for m in 0..n {
            let sm = states[m].axis;
            // δI_k y = S_m ×* (I_k y) − I_k (S_m × y), for bodies k ≥ m.
            let d_inertia = |k: usize, y: &Motion| -> Force {
                sm.cross_force(&states[k].inertia.apply(y))
                    + states[k].inertia.apply(&(sm.cross(y) * -1.0))
            };
            let mut dv = Motion::zero();
            let mut da = Motion::zero();
            df[..m].fill(Force::zero());
            for k in m..n {
                let state = &states[k];
                let ds = sm.cross(&state.axis);
                dv = dv + ds * qd[k];
                da = da
                    + (dv.cross(&state.axis) + bodies[k].velocity.cross(&ds)) * qd[k]
                    + ds * qdd[k];
                let d_momentum = d_inertia(k, &bodies[k].velocity) + state.inertia.apply(&dv);
                df[k] = d_inertia(k, &bodies[k].acceleration)
                    + state.inertia.apply(&da)
                    + dv.cross_force(&bodies[k].momentum)
                    + bodies[k].velocity.cross_force(&d_momentum);
            }
            // δτ_k = δS_k · F_k + S_k · δF_k, with δF_k = Σ_{j ≥ k} δf_j (zero before m but
            // for what the bodies after m transmit).
            let mut d_sum = Force::zero();
            for k in (0..n).rev() {
                d_sum += df[k];
                let mut d_tau = states[k].axis.dot(&d_sum);
                if k >= m {
                    d_tau += sm.cross(&states[k].axis).dot(&transmitted[k]);
                }
                dq[(k, m)] = d_tau;
            }
        }
        // ∂(C q̇)/∂q̇ = 2C for the Christoffel-consistent C (c_ijk symmetric in i, j).
        let mut dqd = self.coriolis(q, qd) * 2.0;
        for (k, body) in self.bodies.iter().enumerate() {
            dqd[(k, k)] += body.viscous;
        }
        (dq, dqd)
    }

    /// `D(q)⁻¹` by Cholesky factorisation; `None` where D(q) is singular to working precision
    /// (the rule of [`forward_dynamics`](Robot::forward_dynamics)).
    ///
    /// # Panics
    /// If `q` does not have `self.dof()` entries, or if the robot has no mass properties.
    #[doc(alias = "computeMinverse")]
    pub fn mass_matrix_inverse(&self, q: &(impl Joints<f64> + ?Sized)) -> Option<DMatrix<f64>> {
        let q = self.check_len("mass_matrix_inverse", "q", q);
        let inverse = crate::inertia_cholesky(self.mass_matrix(q))?.inverse();
        inverse.iter().all(|x| x.is_finite()).then_some(inverse)
    }

    /// The derivatives of forward dynamics, `(∂q̈/∂q, ∂q̈/∂q̇, ∂q̈/∂τ = D⁻¹)` at `(q, q̇, τ)`,
    /// from ∂q̈/∂x = −D⁻¹ ∂τ/∂x at the accelerations τ produces; `None` where
    /// [`forward_dynamics`](Robot::forward_dynamics) is.
    ///
    /// # Panics
    /// If `q`, `qd` or `tau` does not have `self.dof()` entries, or if the robot has no mass
    /// properties.
    #[doc(alias = "computeABADerivatives")]
    pub fn forward_dynamics_derivatives(
        &self,
        q: &(impl Joints<f64> + ?Sized),
        qd: &(impl Joints<f64> + ?Sized),
        tau: &(impl Joints<f64> + ?Sized),
    ) -> Option<(DMatrix<f64>, DMatrix<f64>, DMatrix<f64>)> {
        let q = self.check_len("forward_dynamics_derivatives", "q", q);
        let qd = self.check_len("forward_dynamics_derivatives", "qd", qd);
        let tau = self.check_len("forward_dynamics_derivatives", "tau", tau);
        let inverse = self.mass_matrix_inverse(q)?;
        let qdd: DVector<f64> = &inverse * (DVector::from_column_slice(tau) - self.bias(q, qd));
        if qdd.iter().any(|x| !x.is_finite()) {
            return None;
        }
        let (dq, dqd) = self.inverse_dynamics_derivatives(q, qd, qdd.as_slice());
        Some((-(&inverse * dq), -(&inverse * dqd), inverse))
    }
}
