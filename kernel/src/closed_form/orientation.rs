//! Inverse orientation: the wrist joints (spherical wrist), and the whole of an arm with three
//! parallel axes, whose position and orientation are solved together.

use super::position::ArmSolution;
use super::position::azimuth;
use super::roots::{nearest_within, solve_trig, trig_coefficients, trig_roots};
use super::{DecoupledIk, Method, Solutions};
use crate::Rigid;
#[cfg(not(feature = "std"))]
use nalgebra::{ComplexField as _, RealField as _};
use nalgebra::{Matrix3, Vector3};

pub(super) fn rz(q: f64) -> Matrix3<f64> {
    let (s, c) = q.sin_cos();
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// The angle of the rotation about z that a rotation matrix is (its xy block).
pub(super) fn z_angle(m: &Matrix3<f64>) -> f64 {
    m[(1, 0)].atan2(m[(0, 0)])
}

impl DecoupledIk {
    /// Appends the wrist solutions of one arm solution.
    ///
    /// A joint the position leaves free (q1 with the wrist centre on axis 1, q2 on axis 2) turns
    /// the frame the wrist starts from: it takes the value nearest 0 at which the wrist can
    /// point axis 6 as the pose asks (any value for a wrist whose axes are at right angles).
    pub(super) fn solve_wrist(&self, arm: &ArmSolution, target: &Rigid, out: &mut Solutions) {
        let (a4, a5, a6) = (self.chain[4].r, self.chain[5].r, self.chain[6].r);
        let a = a5.column(2).into_owned();
        let k4 = a4.transpose() * Vector3::z();
        let alpha = k4.x * a.x + k4.y * a.y;
        let beta = k4.y * a.x - k4.x * a.y;
        // M = Rz(q4) A4 Rz(q5) A5 Rz(q6), and the q5 equation's right-hand side.
        let m_of = |q: &[f64; 3]| {
            self.arm_frame(q).compose(&self.chain[3]).r.transpose() * target.r * a6.transpose()
        };
        let rhs = |m: &Matrix3<f64>| m[(2, 2)] - k4.z * a.z;
        let mut q = arm.q;
        for j in (0..2).filter(|&j| arm.free[j]) {
            let rho = alpha.hypot(beta);
            q[j] = nearest_within(
                |c, s| {
                    let mut at = q;
                    at[j] = s.atan2(c);
                    rhs(&m_of(&at))
                },
                -rho,
                rho,
                1.0,
            );
        }
        let arm = q;
        let m = m_of(&arm);
        let b = m.column(2).into_owned();
        for &q5 in solve_trig(alpha, beta, rhs(&m), 1.0).as_slice() {
            let v = a4 * rz(q5) * a;
            // Rz(q4) v = b; at the wrist singularity (axis 6 along axis 4) q4 = 0.
            let q4 = if b.xy().norm() < 1e-9 || v.xy().norm() < 1e-9 {
                0.0
            } else {
                b.y.atan2(b.x) - v.y.atan2(v.x)
            };
            let q6 = z_angle(&((rz(q4) * a4 * rz(q5) * a5).transpose() * m));
            self.push_verified([arm[0], arm[1], arm[2], q4, q5, q6], target, out);
        }
    }

    pub(super) fn solve_three_parallel(&self, target: &Rigid, out: &mut Solutions) {
        let Method::ThreeParallel {
            n,
            x_tool,
            x4,
            kappa,
            sigma,
            sigma3,
            sigma34,
            k0,
        } = self.method
        else {
            return;
        };
        let c = &self.chain;
        let tiny = 1e-12 * self.scale;
        let area = self.scale * self.scale;
        let z = Vector3::z();
        let x_root = c[0].inverse().point(&target.point(&x_tool));
        // q1: (Rz(q1) n) · X = κ.
        let alpha = n.x * x_root.x + n.y * x_root.y;
        let beta = n.x * x_root.y - n.y * x_root.x;
        let axis6 = c[0].r.transpose() * target.r * c[6].r.transpose() * z;
        let (t1, t2, t3) = (c[1].p, c[2].p, c[3].p);
        // q5: σ e_z · A4 Rz(q5) v6 = n · axis 6 (both in the frame after joint 1).
        let v6 = c[5].r * z;
        let k4 = c[4].r.transpose() * z;
        let a5 = k4.x * v6.x + k4.y * v6.y;
        let b5 = k4.y * v6.x - k4.x * v6.y;
        let q5_rhs = |q1: f64| sigma * n.dot(&(rz(q1).transpose() * axis6)) - k4.z * v6.z;
        let q1s = solve_trig(alpha, beta, kappa - n.z * x_root.z, self.scale);
        for &q1 in q1s.as_slice() {
            // X on axis 1 leaves q1 free: the value nearest 0 at which q5 can align axis 6.
            let q1 = if q1s.free {
                let rho = a5.hypot(b5);
                nearest_within(|cc, ss| q5_rhs(ss.atan2(cc)), -rho, rho, 1.0)
            } else {
                q1
            };
            let r0 = rz(q1);
            let x1 = r0.transpose() * x_root;
            for &q5 in solve_trig(a5, b5, q5_rhs(q1), 1.0).as_slice() {
                // R1ᵀ M = Rz(ψ) G Rz(q6) with G = K0 A4 Rz(q5) A5.
                let m = c[1].r.transpose()
                    * r0.transpose()
                    * c[0].r.transpose()
                    * target.r
                    * c[6].r.transpose();
                let g = k0 * c[4].r * rz(q5) * c[5].r;
                let (g0, g1) = (g[(2, 0)], g[(2, 1)]);
                let (m0, m1) = (m[(2, 0)], m[(2, 1)]);
                let psi_of = |q6: f64| z_angle(&(m * rz(q6).transpose() * g.transpose()));
                // X's position fixes the origin of the frame after joint 4: V = Rz(q2) s(q3).
                let v_of = |q6: f64| c[1].r.transpose() * (x1 - t1) - rz(psi_of(q6)) * k0 * x4;
                let s = |q3: f64| t2 + c[2].r * rz(q3) * t3;
                let q3_roots = |v: &Vector3<f64>| {
                    trig_roots(
                        |cc, ss| s(ss.atan2(cc)).xy().norm_squared() - v.xy().norm_squared(),
                        area,
                    )
                };
                let q6 = if g0.hypot(g1) >= 1e-9 {
                    (g1 * m0 - g0 * m1).atan2(g0 * m0 + g1 * m1)
                } else {
                    // Axis 6 along axes 2–4: only ψ + q6 is fixed, but X off axis 4 makes ψ
                    // move the planar arm's target V: q6 is the value nearest 0 at which |V|
                    // lies within the planar arm's reach |s(q3)|.
                    let (a, b, c0) =
                        trig_coefficients(|cc, ss| s(ss.atan2(cc)).xy().norm_squared());
                    let rho = a.hypot(b);
                    nearest_within(
                        |cc, ss| v_of(ss.atan2(cc)).xy().norm_squared(),
                        c0 - rho,
                        c0 + rho,
                        area,
                    )
                };
                let psi = psi_of(q6);
                let v = v_of(q6);
                let q3s = q3_roots(&v);
                for &q3 in q3s.as_slice() {
                    // (A free q2 is any: q4 takes up ψ.)
                    let Some((q2, _)) = azimuth(&v, &s(q3), tiny) else {
                        continue;
                    };
                    let q4 = sigma34 * (psi - q2 - sigma3 * q3);
                    self.push_verified([q1, q2, q3, q4, q5, q6], target, out);
                }
            }
        }
    }
}
