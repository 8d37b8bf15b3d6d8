//! Inverse dynamics by the recursive Newton–Euler algorithm.

use super::BodyState;
use crate::Joints;
use crate::recursive::{rnea_backward, rnea_forward};
use crate::robot::Robot;
use dhgen_kernel::{Force, Motion};
use nalgebra::DVector;

impl Robot {
    /// Inverse dynamics: the joint torques (forces) `τ = D(q) q̈ + C(q, q̇) q̇ + g(q) + τ_f(q̇)`
    /// that produce acceleration `qdd` at velocity `qd`, by the recursive Newton–Euler
    /// algorithm. `D` includes the motor inertias `Jm·G²` and `τ_f` is the joint friction
    /// `viscous·q̇ + coulomb·sign(q̇)` (`sign(0) = 0`).
    ///
    /// # Panics
    /// If `q`, `qd` or `qdd` does not have `self.dof()` entries, or if the robot has no mass
    /// properties.
    #[doc(alias = "rnea")]
    #[doc(alias = "rne")]
    pub fn inverse_dynamics(
        &self,
        q: &(impl Joints<f64> + ?Sized),
        qd: &(impl Joints<f64> + ?Sized),
        qdd: &(impl Joints<f64> + ?Sized),
    ) -> DVector<f64> {
        let q = self.check_len("inverse_dynamics", "q", q);
        let qd = self.check_len("inverse_dynamics", "qd", qd);
        let qdd = self.check_len("inverse_dynamics", "qdd", qdd);
        self.check_dynamics("inverse_dynamics");
        let states = self.body_states(q);
        let mut tau = self.rnea(&states, qd, Some(qdd));
        for (i, body) in self.bodies.iter().enumerate() {
            tau[i] += body.armature * qdd[i] + self.friction(i, qd[i]);
        }
        tau
    }

    /// The torques at zero acceleration, `C(q, q̇) q̇ + g(q)` plus friction: the inverse
    /// dynamics at `q̈ = 0` (what a computed-torque law adds to `D(q) v`).
    ///
    /// # Panics
    /// If `q` or `qd` does not have `self.dof()` entries, or if the robot has no mass
    /// properties.
    #[doc(alias = "nonLinearEffects")]
    pub fn bias(
        &self,
        q: &(impl Joints<f64> + ?Sized),
        qd: &(impl Joints<f64> + ?Sized),
    ) -> DVector<f64> {
        let q = self.check_len("bias", "q", q);
        let qd = self.check_len("bias", "qd", qd);
        self.check_dynamics("bias");
        let states = self.body_states(q);
        let mut tau = self.rnea(&states, qd, None);
        for (i, t) in tau.iter_mut().enumerate() {
            *t += self.friction(i, qd[i]);
        }
        tau
    }

    /// The rigid-body part of inverse dynamics, with gravity, in world coordinates
    /// ([`crate::recursive`]'s Newton–Euler passes): no motor inertia, no friction;
    /// `qdd = None` means zero.
    pub(crate) fn rnea(
        &self,
        states: &[BodyState],
        qd: &[f64],
        qdd: Option<&[f64]>,
    ) -> DVector<f64> {
        let bodies = self.rnea_forward(states, qd, qdd);
        let mut tau = DVector::zeros(states.len());
        rnea_backward(states, bodies.iter().map(|b| b.force), |i, t| tau[i] = t);
        tau
    }

    /// The forward pass of the Newton–Euler recursion: each body's velocity, acceleration
    /// (gravity included as an upward acceleration of the base) and net force, world frame.
    pub(crate) fn rnea_forward(
        &self,
        states: &[BodyState],
        qd: &[f64],
        qdd: Option<&[f64]>,
    ) -> Vec<BodyMotion> {
        let mut out = Vec::with_capacity(states.len());
        rnea_forward(
            self.chain(),
            states,
            qd,
            qdd,
            |_, velocity, acceleration, momentum, force| {
                out.push(BodyMotion {
                    velocity,
                    acceleration,
                    momentum,
                    force,
                });
            },
        );
        out
    }
}

/// One body in the Newton–Euler forward pass, world frame.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BodyMotion {
    /// Spatial velocity.
    pub velocity: Motion,
    /// Spatial acceleration, gravity included (the base accelerates upwards).
    pub acceleration: Motion,
    /// Momentum `I v`.
    pub momentum: Force,
    /// Net force `I a + v ×* I v`.
    pub force: Force,
}
