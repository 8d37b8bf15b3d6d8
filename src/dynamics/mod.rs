//! Rigid body dynamics of the runtime [`Robot`], one algorithm per file:
//! - [`rnea`]: inverse dynamics by recursive Newton–Euler;
//! - [`crba`]: the joint-space inertia matrix by composite rigid bodies;
//! - [`gravity`]: the gravity torques from composite mass moments;
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
mod spatial;

pub use christoffel::{Christoffel, ChristoffelPlane};

use crate::robot::{Rigid, Robot};
use dhgen_model::JointKind;
use spatial::{Inertia, Motion};

/// One body at one configuration, in world coordinates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BodyState {
    /// The joint's unit motion `S_i`: `[z; p × z]` (revolute) or `[0; z]` (prismatic).
    pub axis: Motion,
    /// The body's own spatial inertia.
    pub inertia: Inertia,
    /// The composite inertia of this body and all bodies after it (filled by
    /// [`accumulate_composites`]).
    pub composite: Inertia,
}

impl Robot {
    /// The world-frame joint axes and body inertias at `q` (length already checked).
    pub(crate) fn body_states(&self, q: &[f64]) -> Vec<BodyState> {
        let mut states = Vec::with_capacity(self.dof());
        self.walk_joint_frames(q, |i, frame| {
            let body = &self.bodies[i];
            let axis = joint_axis(body.joint, frame);
            let com = frame.r * body.com + frame.p;
            let i_com = frame.r * body.inertia * frame.r.transpose();
            let inertia = Inertia::from_com(body.mass, &com, &i_com);
            states.push(BodyState {
                axis,
                inertia,
                composite: inertia,
            });
        });
        states
    }

    /// The joint-side friction torque of joint `i` at velocity `qd`.
    #[inline]
    pub(crate) fn friction(&self, i: usize, qd: f64) -> f64 {
        let body = &self.bodies[i];
        body.viscous * qd + body.coulomb * sign(qd)
    }
}

/// The unit motion `S` of a joint carried by the z axis of `frame`: `[z; p × z]` for a
/// revolute joint (rotation about the line through `p`), `[0; z]` for a prismatic one.
#[inline]
pub(crate) fn joint_axis(joint: JointKind, frame: &Rigid) -> Motion {
    let z = frame.r.column(2).into_owned();
    match joint {
        JointKind::Revolute => Motion {
            ang: z,
            lin: frame.p.cross(&z),
        },
        JointKind::Prismatic => Motion {
            ang: nalgebra::Vector3::zeros(),
            lin: z,
        },
    }
}

/// Sums the inertias tip to base: `composite_i = Σ_{k ≥ i} inertia_k`.
pub(crate) fn accumulate_composites(states: &mut [BodyState]) {
    for i in (1..states.len()).rev() {
        let after = states[i].composite;
        states[i - 1].composite += &after;
    }
}

/// The sign of `x`, with `sign(0) = 0` (`f64::signum` gives ±1 for ±0).
#[inline]
pub(crate) fn sign(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}
