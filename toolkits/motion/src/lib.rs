//! Motion of a dhgen arm beyond its kinematics and dynamics proper (chapters 5 and 8 of the
//! reference text), for any [`Arm`](dhgen_kernel::Arm), generated or runtime:
//! - [`velocity`]: the Jacobian's SVD, manipulability and its gradient, condition number,
//!   singularity tests, inverse velocity and acceleration, `J̇`, the kinematic Hessian, the
//!   analytic Jacobian, the decoupled singularity conditions;
//! - [`task_space`]: operational-space dynamics, `Λ a + μ + p = F`;
//! - [`simulate`]: one RK4 step of the forward dynamics.
//!
//! Allocation-free for generated arms and `no_std`; re-exported by `dhgen` (feature `motion`).
#![cfg_attr(not(feature = "std"), no_std)]

pub mod simulate;
pub mod task_space;
pub mod velocity;
