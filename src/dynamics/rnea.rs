//! Inverse dynamics by the recursive Newton–Euler algorithm.

use super::BodyState;
use crate::Joints;
use crate::robot::Robot;
use crate::spatial::{Force, Motion};
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
    /// (Featherstone, RBDA §5.3): no motor inertia, no friction; `qdd = None` means zero.
    pub(crate) fn rnea(
        &self,
        states: &[BodyState],
        qd: &[f64],
        qdd: Option<&[f64]>,
    ) -> DVector<f64> {
        let bodies = self.rnea_forward(states, qd, qdd);
        let mut tau = DVector::zeros(states.len());
        let mut transmitted = Force::ZERO;
        for i in (0..states.len()).rev() {
            transmitted += bodies[i].force;
            tau[i] = states[i].axis.dot(&transmitted);
        }
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
        // Gravity enters as an upward acceleration of the base, so that every body's force
        // includes its weight.
        let mut velocity = Motion::ZERO;
        let mut acceleration = Motion {
            ang: nalgebra::Vector3::zeros(),
            lin: -self.gravity,
        };
        states
            .iter()
            .enumerate()
            .map(|(i, state)| {
                let s = &state.axis;
                velocity = velocity + *s * qd[i];
                // The axis moves with the body before it: dS/dt = v × S.
                acceleration = acceleration + velocity.cross(s) * qd[i];
                if let Some(qdd) = qdd {
                    acceleration = acceleration + *s * qdd[i];
                }
                let momentum = state.inertia.apply(&velocity);
                BodyMotion {
                    velocity,
                    acceleration,
                    momentum,
                    force: state.inertia.apply(&acceleration) + velocity.cross_force(&momentum),
                }
            })
            .collect()
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
