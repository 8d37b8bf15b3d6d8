//! Rigid body dynamics of the runtime [`Robot`], one algorithm per file:
//! - [`rnea`]: inverse dynamics by recursive Newton–Euler;
//! - [`crba`]: the joint-space inertia matrix by composite rigid bodies;
//! - [`gravity`]: the gravity torques from composite mass moments, and the potential energy;
//! - [`christoffel`]: the Christoffel symbols from analytic derivatives of `D(q)`;
//! - [`coriolis`]: the Christoffel-consistent Coriolis matrix in O(n²);
//! - [`forward`]: forward dynamics by CRBA, RNEA and a Cholesky solve;
//! - [`derivatives`]: ∂τ/∂q by tangents of the recursion, ∂τ/∂q̇, D⁻¹, ∂q̈/∂(q, q̇, τ);
//! - [`rates`]: Ḋ(q, q̇) and Cᵀ(q, q̇) q̇;
//! - [`regressor`]: the inertial parameters π and the joint torque regressor Y, τ = Y π;
//! - [`base_parameters`]: the minimal set of parameter combinations Y determines.
//!
//! All of them share one per-call pass ([`Robot::body_states`]) that puts each joint axis and
//! each body inertia into world coordinates; the constants come from
//! [`Robot::from_model`](crate::Robot::from_model).
//!
//! Motor inertia (`Jm·G²` on `D_ii`) and friction (`viscous·q̇ + coulomb·sign(q̇)`, with
//! `sign(0) = 0`) are joint-side terms: they enter the mass matrix, inverse and forward
//! dynamics, but not the Christoffel symbols, the Coriolis matrix or gravity.

pub mod base_parameters;
mod christoffel;
mod coriolis;
mod crba;
mod derivatives;
mod forward;
mod gravity;
mod rates;
pub mod regressor;
mod rnea;

pub use christoffel::{Christoffel, ChristoffelPlane};

use crate::recursive::body_states;
pub(crate) use crate::recursive::{BodyState, accumulate_composites};
use crate::robot::{Rigid, Robot};
use dhgen_description::JointKind;
use dhgen_kernel::Motion;

impl Robot {
    /// The world-frame joint axes and body inertias at `q` (length already checked), by the
    /// pass [`crate::recursive`] shares with generated modules of long arms.
    pub(crate) fn body_states(&self, q: &[f64]) -> Vec<BodyState> {
        let chain = self.chain();
        let mut states = Vec::with_capacity(self.dof());
        body_states(chain, |i| self.joint_value(i, q[i]), |_, s| states.push(s));
        states
    }

    /// The joint-side friction torque of joint `i` at velocity `qd`.
    #[inline]
    pub(crate) fn friction(&self, i: usize, qd: f64) -> f64 {
        crate::recursive::friction(&self.chain().bodies[i], qd)
    }
}

/// The unit motion `S` of a joint carried by the z axis of `frame` (see
/// [`crate::recursive`]'s `joint_axis`).
#[inline]
pub(crate) fn joint_axis(joint: JointKind, frame: &Rigid) -> Motion {
    crate::recursive::joint_axis(joint, &frame.r, &frame.p)
}
