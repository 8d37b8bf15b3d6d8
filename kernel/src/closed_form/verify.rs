//! Every candidate checked by forward kinematics, polished first where the closed forms'
//! rounding left it short of the pose; duplicates dropped.

use super::{DecoupledIk, POLISHED, SAME_SOLUTION, Solutions, VERIFY_TOLERANCE, wrap_angle};
use crate::Rigid;
use core::f64::consts::TAU;
#[cfg(not(feature = "std"))]
use nalgebra::{ComplexField as _, RealField as _};
use nalgebra::{Matrix6, SVector, Vector3, Vector6};

/// Newton-type refinement: `attempt(q)` gives the error at `q` and the next iterate (none when
/// the step cannot be taken); an iterate is accepted while the error falls (a NaN is no fall),
/// at most 8 times, stopping once the error is at most `done`.
pub(super) fn refine<Q: Copy>(mut q: Q, done: f64, attempt: impl Fn(&Q) -> (f64, Option<Q>)) -> Q {
    let (mut error, mut next) = attempt(&q);
    for _ in 0..8 {
        if error <= done {
            break;
        }
        let Some(candidate) = next else {
            break;
        };
        let (e, n) = attempt(&candidate);
        if e.partial_cmp(&error) != Some(core::cmp::Ordering::Less) {
            break;
        }
        (q, error, next) = (candidate, e, n);
    }
    q
}

/// `[Δp; Δθ]` taking `a` to `b`: the difference of origins and the rotation vector of
/// `R_b R_aᵀ`, both in the outer frame (the angle from `atan2(|v|, (tr R − 1)/2)`, `v` the
/// axial vector of its skew part, accurate at small angles).
pub(super) fn pose_difference(a: &Rigid, b: &Rigid) -> Vector6<f64> {
    let r = b.r * a.r.transpose();
    let v = 0.5
        * Vector3::new(
            r[(2, 1)] - r[(1, 2)],
            r[(0, 2)] - r[(2, 0)],
            r[(1, 0)] - r[(0, 1)],
        );
    let sin = v.norm();
    let angle = sin.atan2(0.5 * (r.trace() - 1.0));
    let w = if sin > 0.0 { v * (angle / sin) } else { v };
    let dp = b.p - a.p;
    Vector6::new(dp.x, dp.y, dp.z, w.x, w.y, w.z)
}

/// Position error and rotation angle between two frames; the angle from
/// `‖Ra − Rb‖_F = 2√2 sin(θ/2)`, accurate for small angles.
pub(super) fn frame_error(a: &Rigid, b: &Rigid) -> (f64, f64) {
    let chord = (a.r - b.r).norm() / (2.0 * core::f64::consts::SQRT_2);
    ((a.p - b.p).norm(), 2.0 * chord.min(1.0).asin())
}

impl DecoupledIk {
    /// `q` refined by Gauss–Newton steps on the whole pose ([`refine`]; the pseudo-inverse of
    /// the arm's Jacobian, singular values below 1e-12 of the largest dropped, so that a
    /// singular configuration moves least along the directions the pose leaves free). A
    /// singular pose leaves a double root's joint accurate to √ε only, and the rest of the
    /// candidate inherits the error; two or three steps restore full precision.
    pub(super) fn polished(&self, q: SVector<f64, 6>, target: &Rigid) -> SVector<f64, 6> {
        refine(q, POLISHED, |q| {
            let (frame, jacobian) = self.fk_and_jacobian(q);
            let error = pose_difference(&frame, target);
            let svd = jacobian.svd(true, true);
            let cutoff = 1e-12 * svd.singular_values.max();
            (
                error.norm(),
                svd.solve(&error, cutoff).ok().map(|step| q + step),
            )
        })
    }

    pub(super) fn fk_frame(&self, q: &SVector<f64, 6>) -> Rigid {
        self.walk(q, |_, _| {})
    }

    /// `T(q)`, calling `at_joint(i, frame)` with the frame joint `i` moves (its z axis the
    /// joint's, in the world) on the way.
    pub(super) fn walk(
        &self,
        q: &SVector<f64, 6>,
        mut at_joint: impl FnMut(usize, &Rigid),
    ) -> Rigid {
        let mut f = self.chain[0];
        for i in 0..6 {
            at_joint(i, &f);
            f = f.moved(self.joint(i), q[i]).compose(&self.chain[i + 1]);
        }
        f
    }

    /// `T(q)` and the geometric Jacobian of the tool's origin, world axes, rows `[v; ω]`.
    pub(super) fn fk_and_jacobian(&self, q: &SVector<f64, 6>) -> (Rigid, Matrix6<f64>) {
        let mut axes = [(Vector3::zeros(), Vector3::zeros()); 6];
        let tool = self.walk(q, |i, f| axes[i] = (f.r.column(2).into_owned(), f.p));
        let mut jacobian = Matrix6::zeros();
        for (i, (z, o)) in axes.iter().enumerate() {
            let (v, w) = if self.prismatic[i] {
                (*z, Vector3::zeros())
            } else {
                (z.cross(&(tool.p - o)), *z)
            };
            jacobian.fixed_view_mut::<3, 1>(0, i).copy_from(&v);
            jacobian.fixed_view_mut::<3, 1>(3, i).copy_from(&w);
        }
        (tool, jacobian)
    }

    /// The frame after joint 3 (`P0 Z1 P1 Z2 P2 Z3`), in the world.
    pub(super) fn arm_frame(&self, arm: &[f64; 3]) -> Rigid {
        let mut g = self.chain[0];
        for (i, &qi) in arm.iter().enumerate() {
            g = g.moved(self.joint(i), qi);
            if i < 2 {
                g = g.compose(&self.chain[i + 1]);
            }
        }
        g
    }

    /// Appends the candidate `q` if it reproduces `target` to [`VERIFY_TOLERANCE`] and is not
    /// already there; a candidate missing the pose by more than the arithmetic does
    /// ([`POLISHED`]) is [`polished`](Self::polished) first.
    pub(super) fn push_verified(&self, q: [f64; 6], target: &Rigid, out: &mut Solutions) {
        let known = |q: &SVector<f64, 6>| {
            out.iter()
                .any(|s| (0..6).all(|j| self.joint_distance(j, s[j], q[j]) < SAME_SOLUTION))
        };
        let mut q = self.normalise(SVector::from(q));
        if known(&q) {
            return;
        }
        let (mut dp, mut dr) = frame_error(&self.fk_frame(&q), target);
        if dp > POLISHED * self.scale || dr > POLISHED {
            q = self.normalise(self.polished(q, target));
            if known(&q) {
                return;
            }
            (dp, dr) = frame_error(&self.fk_frame(&q), target);
        }
        if dp <= VERIFY_TOLERANCE && dr <= VERIFY_TOLERANCE {
            out.push(q);
        }
    }

    pub(super) fn joint_distance(&self, j: usize, a: f64, b: f64) -> f64 {
        if self.prismatic[j] {
            (a - b).abs()
        } else {
            wrap_angle(a - b).abs()
        }
    }

    /// Wraps revolute values into (−π, π], then by ±2π into the limits where that fits.
    pub(super) fn normalise(&self, mut q: SVector<f64, 6>) -> SVector<f64, 6> {
        for j in 0..6 {
            if self.prismatic[j] {
                continue;
            }
            let mut x = wrap_angle(q[j]);
            if let Some([lo, hi]) = self.limits[j] {
                if x < lo && x + TAU <= hi {
                    x += TAU;
                } else if x > hi && x - TAU >= lo {
                    x -= TAU;
                }
            }
            q[j] = x;
        }
        q
    }
}
