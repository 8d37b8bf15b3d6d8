//! dhgen
#![cfg_attr(not(feature = "std"), no_std)]
pub use nalgebra;

/// Joint-space trajectory generation: cubic, quintic, LSPB, minimum-time, synchronized
/// multi-joint and via-point profiles (section 6.5).
pub mod trajectory;

/// Generates a specialised module for a robot at compile time; see the crate docs.
pub use dhgen_macros::robot;

// Lets generated code name `::dhgen` inside this crate's own tests and docs too.
extern crate self as dhgen;

mod arm;
mod real;
pub use arm::{Arm, ArmAllocator, ArmDynamics, JointVector};
pub use real::Real;

#[cfg(feature = "std")]
mod dynamics;
#[cfg(feature = "std")]
mod error;
#[cfg(feature = "std")]
mod kinematics;
#[cfg(feature = "std")]
mod robot;
#[cfg(feature = "std")]
pub use dhgen_model as model;
#[cfg(feature = "std")]
pub use dhgen_model::{Convention, JointKind, LoadError, RobotModel};
#[cfg(feature = "std")]
pub use dynamics::{Christoffel, ChristoffelPlane};
#[cfg(feature = "std")]
pub use error::Error;
#[cfg(feature = "std")]
pub use robot::Robot;
