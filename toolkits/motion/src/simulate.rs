//! Simulating an arm: integrating its forward dynamics `q̈ = f(q, q̇, τ)` through time, for a
//! plant in the loop of a controller under test (Robotics Toolbox's `fdyn`, one step at a
//! time so that the controller sets the torque between steps).
//!
//! Works for any [`ArmDynamics`]: a generated module's `Robot` (allocation-free, its generated
//! forward dynamics) or `dhgen::Robot`. Joint angles are not wrapped.
//!
//! ```
//! use dhgen::nalgebra::SVector;
//! use dhgen::ArmDynamics;
//! dhgen::robot!(mod elbow = "../../robots/planar_elbow.toml");
//!
//! // Released at rest, the arm falls; with no friction its energy T + P stays constant.
//! let (mut q, mut qd) = (SVector::<f64, 2>::new(0.3, 0.2), SVector::<f64, 2>::zeros());
//! let energy = |q: &SVector<f64, 2>, qd: &SVector<f64, 2>| {
//!     elbow::Robot.kinetic_energy(q, qd) + elbow::Robot.potential_energy(q)
//! };
//! let e0 = energy(&q, &qd);
//! for _ in 0..1000 {
//!     let step = dhgen::simulate::rk4_step(&elbow::Robot, &q, &qd, &SVector::zeros(), 1e-3);
//!     (q, qd) = step.unwrap();
//! }
//! assert!(qd.norm() > 1.0);
//! assert!((energy(&q, &qd) - e0).abs() < 1e-6 * e0.abs());
//! ```

use dhgen_kernel::{ArmAllocator, ArmDynamics, JointVector};
use nalgebra::allocator::Allocator;
use nalgebra::{DefaultAllocator, Dim, OVector};

/// One step of the classical fourth-order Runge–Kutta method over `dt` seconds, the torque
/// `tau` held: the state `(q, q̇)` at `t + dt` from the state at `t`, with a local error of
/// order `dt⁵`. Four evaluations of the arm's forward dynamics; `None` where one of them has
/// no answer (`D(q)` singular to working precision, or a non-finite acceleration) or the new
/// state is not finite (a step too long for `f64`): `Some` is always finite.
pub fn rk4_step<A: ArmDynamics>(
    arm: &A,
    q: &OVector<f64, A::Dof>,
    qd: &OVector<f64, A::Dof>,
    tau: &OVector<f64, A::Dof>,
    dt: f64,
) -> Option<(JointVector<A>, JointVector<A>)>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    rk4_step_with(|q, qd| arm.forward_dynamics(q, qd, tau), q, qd, dt)
}

/// [`rk4_step`] for any acceleration `q̈ = f(q, q̇)`: a plant that is not an [`ArmDynamics`]
/// (a generated module's `forward_dynamics_with_payload`, an arm with external forces).
/// `None` where `f` gives none or the new state is not finite.
pub fn rk4_step_with<D: Dim>(
    mut acceleration: impl FnMut(&OVector<f64, D>, &OVector<f64, D>) -> Option<OVector<f64, D>>,
    q: &OVector<f64, D>,
    qd: &OVector<f64, D>,
    dt: f64,
) -> Option<(OVector<f64, D>, OVector<f64, D>)>
where
    DefaultAllocator: Allocator<D>,
{
    let half = dt / 2.0;
    let k1 = acceleration(q, qd)?;
    let (q2, qd2) = (q + qd * half, qd + &k1 * half);
    let k2 = acceleration(&q2, &qd2)?;
    let (q3, qd3) = (q + &qd2 * half, qd + &k2 * half);
    let k3 = acceleration(&q3, &qd3)?;
    let (q4, qd4) = (q + &qd3 * dt, qd + &k3 * dt);
    let k4 = acceleration(&q4, &qd4)?;
    let sixth = dt / 6.0;
    let q_next = q + (qd + qd2 * 2.0 + qd3 * 2.0 + qd4) * sixth;
    let qd_next = qd + (k1 + k2 * 2.0 + k3 * 2.0 + k4) * sixth;
    let finite = q_next.iter().chain(qd_next.iter()).all(|x| x.is_finite());
    finite.then_some((q_next, qd_next))
}
