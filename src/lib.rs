//! dhgen
//!
//! Robot arms from Denavit–Hartenberg tables: the [`robot!`] macro turns a DH table into a
//! module of specialised, allocation-free, `no_std` Rust (forward kinematics, the geometric
//! Jacobian, D(q), the Christoffel symbols, C(q, q̇), g(q), inverse and forward dynamics),
//! derived and simplified symbolically at compile time; [`Robot`] computes the same
//! quantities for any table loaded at run time.
//!
//! # Quick start
//!
//! Describe the arm in TOML (the format: `docs/robot-description.md`; ready-made ones in
//! `robots/`), and generate its module. The path is relative to your `Cargo.toml`:
//!
//! ```
//! dhgen::robot!(pub mod puma560 = "robots/puma560.toml");
//!
//! let q = [0.1, -0.6, 0.4, 0.3, 0.8, -0.2];
//! let qd = [0.2, 0.1, -0.3, 0.0, 0.5, 0.1];
//! let state = puma560::State::new(&q); // sin/cos of every joint, once
//! let pose = state.fk(); // Isometry3: base · A1 ⋯ A6 · tool
//! let jacobian = state.jacobian(); // 6×6, rows [v; ω], world axes
//! let (d, c, g) = (state.mass_matrix(), state.coriolis(&qd), state.gravity());
//!
//! // A computed-torque law: τ = D(q) v + C(q, q̇) q̇ + g(q).
//! let v = dhgen::nalgebra::SVector::<f64, 6>::repeat(0.5);
//! let tau = d * v + c * dhgen::nalgebra::SVector::from(qd) + g;
//! // ... which is the generated inverse dynamics at q̈ = v.
//! let id = puma560::inverse_dynamics(&q, &qd, &[0.5; 6]);
//! assert!((tau - id).amax() < 1e-9);
//! assert!(pose.translation.vector.norm() > 0.0 && jacobian.rank(1e-9) == 6);
//!
//! // Forward dynamics, for simulation: q̈ under τ (`None` where D(q) is singular or q̈ is not
//! // finite). What one generated function returns goes straight into the next.
//! let qdd = puma560::forward_dynamics(&q, &qd, &id).expect("D(q) is positive definite");
//! assert!((qdd - v).amax() < 1e-9);
//! ```
//!
//! The same robot at run time (needs the default `std` feature):
//!
//! ```
//! let robot = dhgen::Robot::from_toml_file("robots/puma560.toml")?;
//! let d = robot.mass_matrix(&[0.0; 6]);
//! assert_eq!(d.nrows(), 6);
//! # Ok::<(), dhgen::Error>(())
//! ```
//!
//! Both implement [`Arm`] and [`ArmDynamics`], so algorithms can be written once for either.
//! The [`trajectory`] module plans joint-space motions to feed a controller.
//!
//! # Further
//! - `cargo run --release --example computed_torque`: the PUMA 560 tracking a quintic
//!   trajectory under computed-torque control at 1 kHz, against a plant with a heavier
//!   link 6; prints the tracking error and the time per control step, draws an SVG.
//! - The `dhgen` command line (`cargo install --path cli`): `dhgen info`, `eval`, `emit`,
//!   `latex`, `ops` on a description file.
//! - `docs/conventions.md`: standard and modified DH, joint offsets, the Christoffel index
//!   order (`c[i][j][k] = c_ijk`, k the equation index), units, gravity, non-finite input
//!   and wrong-length joint vectors, `f32`, `no_std`, faster macro expansion.
#![cfg_attr(not(feature = "std"), no_std)]
pub use nalgebra;

/// Joint-space trajectory generation: cubic, quintic, LSPB, minimum-time, synchronized
/// multi-joint and via-point profiles (section 6.5).
pub mod trajectory;

/// Generates a specialised module for a robot at compile time; see the crate docs.
pub use dhgen_macros::robot;

// Lets generated code name `::dhgen` inside this crate's own tests and docs too.
extern crate self as dhgen;

/// What `robot!` generates, browsable: the PUMA 560 of `robots/puma560.toml`, expanded here
/// for the documentation only (this module exists in `cargo doc` builds, not in the
/// library). Every generated module has the same items: `DOF`, `CHAIN` and the other
/// constants, `State` with one method per quantity, a free function per quantity, `Robot`
/// implementing [`Arm`] and [`ArmDynamics`], and `Terms`.
#[cfg(doc)]
pub mod example {
    crate::robot!(pub mod puma560 = "robots/puma560.toml");
}

mod arm;
pub mod batch;
mod joints;
mod real;
pub mod recursive;
pub mod sincos;
mod spatial;
pub use arm::{Arm, ArmAllocator, ArmDynamics, JointVector};
pub use joints::{JointArray, Joints};
pub use real::{Real, cholesky_pivot_floor, inertia_cholesky};

// Rotations (section 3.5): ZYZ Euler angles, roll-pitch-yaw, axis-angle; what nalgebra lacks.
pub mod rotation;

// Inverse kinematics (section 4.3): closed form by kinematic decoupling, and numeric.
pub mod ik;

// Velocity kinematics (chapter 5): analytic Jacobian, J̇, singularities, inverse velocity.
pub mod velocity;

// Task-space (operational-space) dynamics: Λ, J̄, μ, p and the null-space torques.
pub mod task_space;

// Simulation: one Runge–Kutta step of the forward dynamics, for a plant in the loop.
pub mod simulate;

#[cfg(feature = "std")]
mod dynamics;
#[cfg(feature = "std")]
mod error;
#[cfg(feature = "std")]
mod kinematics;
/// Path planning (sections 6.1 to 6.4): collision checking, potential fields, probabilistic
/// roadmaps. Needs the `planning` feature (on by default).
#[cfg(feature = "planning")]
pub mod planning;
#[cfg(feature = "std")]
mod robot;
/// The robot model: the description format, validation, and the kinematic structure
/// ([`model::ChainRef`]) that generated modules carry and [`Arm::chain`] returns.
pub use dhgen_model as model;
pub use dhgen_model::{ChainRef, JointKind};
#[cfg(feature = "std")]
pub use dhgen_model::{Convention, JointChain, LoadError, RobotModel};
#[cfg(feature = "std")]
pub use dynamics::{Christoffel, ChristoffelPlane};
#[cfg(feature = "std")]
pub mod payload;
/// Inertial parameters: the regressor `Y` with `τ = Y π` ([`Robot::regressor`],
/// [`Robot::parameters`], and `regressor` in generated modules) and the base parameters
/// ([`Robot::base_parameters`], [`BaseParameters`](parameters::BaseParameters), and
/// `base_regressor` in generated modules).
///
/// The order of the parameters (ten per link, `m, m·cx, m·cy, m·cz, Ixx, Ixy, Iyy, Ixz, Iyz,
/// Izz` in the link's frame about its origin, then armature and friction), the frames they are
/// expressed in, and the base-parameter method (Gautier's pivoted QR over seeded states) are
/// defined once, in [`dhgen_model::parameters`], re-exported here.
#[cfg(feature = "std")]
pub mod parameters {
    pub use dhgen_model::parameters::{
        BODY_PARAMETER_NAMES, BODY_PARAMETERS, BaseParameters, Column, Links, ParameterError,
        body_parameters, columns, names, reduce, sample_states, values, with_values,
    };
}
// Identification: the base parameters from measured motion, by least squares on the regressor.
#[cfg(feature = "std")]
pub mod identification;
#[cfg(feature = "std")]
pub use error::Error;
#[cfg(feature = "std")]
pub use robot::Robot;
