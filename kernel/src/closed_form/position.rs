//! Inverse position: the joints 1–3 that put the wrist centre where the pose asks.

use super::roots::{
    Roots, quartic_in_displacement, real_polynomial_roots, solve_trig, trig_roots, trig2_roots,
};
use super::verify::refine;
use super::{ArmKind, DecoupledIk, Shoulder};
use crate::{JointKind, Rigid};
#[cfg(not(feature = "std"))]
use nalgebra::{ComplexField as _, RealField as _};
use nalgebra::{Matrix3, Vector2, Vector3};

/// The angle turning the xy part of `from` onto that of `to` about z, and whether it is free.
/// With `to` on the axis (relative to `tiny`) every angle does: 0 stands for them (`from`,
/// made of roots that a singular pose leaves accurate only to √ε, may miss the axis by more;
/// polishing on the pose settles it); `None` when `from` is on the axis and `to` is not.
pub(super) fn azimuth(to: &Vector3<f64>, from: &Vector3<f64>, tiny: f64) -> Option<(f64, bool)> {
    let (a, b) = (to.xy().norm(), from.xy().norm());
    if a < tiny {
        Some((0.0, true))
    } else if b < tiny {
        None
    } else {
        Some((to.y.atan2(to.x) - from.y.atan2(from.x), false))
    }
}

/// Candidate solutions `(q1, q2, q3)` of the inverse position problem: at most 4, and more at
/// a singular pose, where a near-double root is also tried as the double root
/// ([`solve_trig`], [`real_roots_near`]): up to 6 values of q3 times 3 of q2.
pub(super) struct ArmSolutions {
    pub(super) q: [ArmSolution; ArmSolutions::CAPACITY],
    pub(super) len: usize,
}

/// `(q1, q2, q3)`, and which of them the wrist centre's position leaves free (on axis 1 or 2;
/// set to 0 until the wrist chooses them).
#[derive(Clone, Copy, Debug)]
pub(super) struct ArmSolution {
    pub(super) q: [f64; 3],
    pub(super) free: [bool; 3],
}

impl ArmSolutions {
    pub(super) const CAPACITY: usize = 18;

    pub(super) const NONE: ArmSolutions = ArmSolutions {
        q: [ArmSolution {
            q: [0.0; 3],
            free: [false; 3],
        }; ArmSolutions::CAPACITY],
        len: 0,
    };

    pub(super) fn push(&mut self, q: [f64; 3], free: [bool; 3]) {
        if self.len < Self::CAPACITY {
            self.q[self.len] = ArmSolution { q, free };
            self.len += 1;
        }
    }

    pub(super) fn as_slice(&self) -> &[ArmSolution] {
        &self.q[..self.len]
    }
}

impl DecoupledIk {
    /// The wrist centre (`w` in the frame joint 3 moves) at `(q1, q2, q3)`, in the frame joint
    /// 1 turns, and its Jacobian over the three joints.
    pub(super) fn wrist_centre(
        &self,
        w: &Vector3<f64>,
        q: &[f64; 3],
    ) -> (Vector3<f64>, Matrix3<f64>) {
        let mut f = Rigid::IDENTITY;
        let mut axes = [(Vector3::zeros(), Vector3::zeros()); 3];
        for i in 0..3 {
            if i > 0 {
                f = f.compose(&self.chain[i]);
            }
            axes[i] = (f.r.column(2).into_owned(), f.p);
            f.apply_joint(self.joint(i), q[i]);
        }
        let centre = f.point(w);
        let columns: [Vector3<f64>; 3] = core::array::from_fn(|i| {
            let (z, o) = axes[i];
            if self.prismatic[i] {
                z
            } else {
                z.cross(&(centre - o))
            }
        });
        (centre, Matrix3::from_columns(&columns))
    }

    /// `q` refined by Newton's method on the wrist centre's position `p` (in the frame joint 1
    /// turns, [`refine`]): a skew shoulder's closed form divides by its offset squared, which
    /// the rounding of its inputs does not survive when the offset is small (CAD's tens of
    /// micrometres for a zero), leaving q2 far from the root; the pose's Jacobian is then too
    /// ill-conditioned for [`polished`](Self::polished), the position's is not.
    pub(super) fn polished_arm(&self, w: &Vector3<f64>, p: &Vector3<f64>, q: [f64; 3]) -> [f64; 3] {
        refine(q, 1e-14 * self.scale, |q| {
            let (centre, jacobian) = self.wrist_centre(w, q);
            let error = centre - p;
            let next = jacobian
                .lu()
                .solve(&error)
                .map(|step| core::array::from_fn(|i| q[i] - step[i]));
            (error.norm(), next)
        })
    }

    /// Up to 4 `(q1, q2, q3)` putting the wrist centre at `p` (in the frame joint 1 turns).
    pub(super) fn solve_position(
        &self,
        shoulder: &Shoulder,
        w: &Vector3<f64>,
        p: &Vector3<f64>,
    ) -> ArmSolutions {
        let mut out = ArmSolutions::NONE;
        let mut push = |q: [f64; 3], free: [bool; 3]| out.push(q, free);
        let tiny = 1e-12 * self.scale;
        let (length, area) = (self.scale, self.scale * self.scale);
        match *shoulder {
            Shoulder::Revolute { shift, t1, u, n } => {
                let joint3 = self.joint(2);
                let p2 = self.chain[2];
                // h(q3): the wrist centre in the frame joint 2 turns.
                let h = |q3: f64| p2.moved(joint3, q3).point(w);
                let ps = p - Vector3::z() * shift;
                let (a, b) = (u.xy().norm(), n.xy().norm());
                // E1: L1 = 2 u·Rz(q2) h − 2 u_z h_z ... written as the q2-free part:
                let l1 = |h: &Vector3<f64>| {
                    ps.norm_squared() - h.norm_squared() - t1.norm_squared() - 2.0 * u.z * h.z
                };
                let l2 = |h: &Vector3<f64>| ps.z - t1.z - n.z * h.z;
                // Given q3, q2 from `k · Rz(q2) h = rhs` for a direction k in the xy plane, of
                // terms of magnitude `size`; with the wrist centre on axis 2 the equation does
                // not depend on q2, which is free (0) where it holds.
                let q2_from = |k: &Vector2<f64>, h: &Vector3<f64>, rhs: f64, size: f64| {
                    let (hx, hy) = (h.x, h.y);
                    solve_trig(k.x * hx + k.y * hy, k.y * hx - k.x * hy, rhs, size)
                };
                let q3s = match self.kind {
                    ArmKind::IntersectingShoulder => self.joint3_roots(&|q3| l1(&h(q3)), area),
                    ArmKind::ParallelShoulder => self.joint3_roots(&|q3| l2(&h(q3)), length),
                    _ => {
                        let residual = |q3: f64| {
                            let hv = h(q3);
                            let x = l1(&hv) / (2.0 * a);
                            let y = l2(&hv) / b;
                            x * x + y * y - hv.xy().norm_squared()
                        };
                        // Terms of the size of X², Y² and |h|².
                        let size = (area / a).powi(2) + (length / b).powi(2) + area;
                        if self.prismatic[2] {
                            quartic_in_displacement(&residual, size)
                        } else {
                            trig2_roots(residual, size)
                        }
                    }
                };
                for &q3 in q3s.as_slice() {
                    let hv = h(q3);
                    let q2s = match self.kind {
                        ArmKind::IntersectingShoulder => q2_from(&n.xy(), &hv, l2(&hv), length),
                        ArmKind::ParallelShoulder => q2_from(&u.xy(), &hv, 0.5 * l1(&hv), area),
                        _ => {
                            // Rz(q2) h_xy = X û + Y n̂ (û ⟂ n̂ in the plane).
                            let (x, y) = (l1(&hv) / (2.0 * a), l2(&hv) / b);
                            let target = u.xy() * (x / a) + n.xy() * (y / b);
                            if hv.xy().norm() < tiny {
                                Roots::<3>::FREE
                            } else {
                                Roots::one(target.y.atan2(target.x) - hv.y.atan2(hv.x))
                            }
                        }
                    };
                    for &q2 in q2s.as_slice() {
                        let g = self.chain[1].moved(JointKind::Revolute, q2).point(&hv);
                        if let Some((q1, free1)) = azimuth(p, &g, tiny) {
                            let q = [q1, q2, q3];
                            // q2 and q3 went through X/a and Y/b: refined where a or b (the
                            // shoulder's offset, the sine of its angle) is small.
                            let q = match self.kind {
                                ArmKind::OffsetShoulder => self.polished_arm(w, p, q),
                                _ => q,
                            };
                            push(q, [free1, q2s.free, false]);
                        }
                    }
                }
            }
            Shoulder::Cylindrical {
                f0,
                u,
                v,
                lead_is_2,
            } => {
                let (lead, other) = if lead_is_2 { (u, v) } else { (v, u) };
                // Height: q_lead = (p_z − f0_z − q_other other_z) / lead_z; radius: quadratic.
                let base = f0 + lead * ((p.z - f0.z) / lead.z);
                let dir = other - lead * (other.z / lead.z);
                let (a, b) = (base.xy(), dir.xy());
                let bb = b.norm_squared();
                let roots = real_polynomial_roots(
                    [
                        a.norm_squared() - p.xy().norm_squared(),
                        2.0 * a.dot(&b),
                        bb,
                        0.0,
                        0.0,
                    ],
                    area,
                );
                for &q_other in roots.as_slice() {
                    let q_lead = (p.z - f0.z - q_other * other.z) / lead.z;
                    let (q2, q3) = if lead_is_2 {
                        (q_lead, q_other)
                    } else {
                        (q_other, q_lead)
                    };
                    let f = f0 + u * q2 + v * q3;
                    if let Some((q1, free1)) = azimuth(p, &f, tiny) {
                        push([q1, q2, q3], [free1, false, false]);
                    }
                }
            }
        }
        out
    }

    /// The values of joint 3 where `f` (affine in its cosine and sine, or quadratic in its
    /// displacement; of terms of magnitude `size`) vanishes.
    pub(super) fn joint3_roots(&self, f: &dyn Fn(f64) -> f64, size: f64) -> Roots<6> {
        let mut out = Roots::NONE;
        if self.prismatic[2] {
            // f is quadratic in the displacement: from three samples.
            let (f0, f1, fm) = (f(0.0), f(1.0), f(-1.0));
            let c2 = 0.5 * (f1 + fm) - f0;
            let c1 = 0.5 * (f1 - fm);
            for x in real_polynomial_roots([f0, c1, c2, 0.0, 0.0], size).as_slice() {
                out.push(*x);
            }
        } else {
            for x in trig_roots(|c, s| f(s.atan2(c)), size).as_slice() {
                out.push(*x);
            }
        }
        out
    }
}
