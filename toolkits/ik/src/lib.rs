//! Inverse kinematics (section 4.3): from a desired tool pose to joint values.
//!
//! - [`DecoupledIk`]: closed form by kinematic decoupling for six-joint arms whose last three
//!   axes meet (Pieper's condition, at any twist angles: PUMA 560, Stanford arm, the
//!   cylindrical arm, arms with shoulder offsets) or whose axes 2, 3, 4 are parallel (the
//!   Universal Robots arms). Returns **all** solutions (at most 8) in a fixed-capacity
//!   [`Solutions`], each verified by forward kinematics. Built from an arm's structure
//!   ([`DecoupledIk::from_chain`] with [`Arm::chain`](dhgen_kernel::Arm::chain), or a description's);
//!   a generated module carries its solver precomputed as the constant `IK` (with
//!   `ik(&pose)`). Solving allocates nothing, also without `std`. The method and the choices
//!   at singular poses are documented in [`dhgen_kernel::closed_form`].
//! - [`NumericIk`]: damped least squares (Levenberg–Marquardt) for any chain (redundant arms,
//!   prismatic joints), generic over [`Arm`](dhgen_kernel::Arm), with joint limits, tolerances, an
//!   iteration cap and a seed; allocation-free in its loop for generated robots. It reaches
//!   the whole pose or part of it ([`Task`]: the position alone, the position and the
//!   tool's z axis, or the components of a mask in world axes, such as a pose up to a turn
//!   about the vertical), so arms of fewer than six joints have targets they can reach. For a
//!   redundant arm, [`NumericIk::solve_preferring`] moves the solution along the arm's
//!   self-motion to the one nearest a posture, the most manipulable, or the least costly by
//!   a function of yours ([`Preference`]).
//!
//! Both measure the pose error with [`pose_error`] ([`Task::errors`] for part of a pose).
//!
//! ```
//! use dhgen::ik::{DecoupledIk, NumericIk};
//! use dhgen::nalgebra::SVector;
//! dhgen::robot!(mod puma = "../../robots/puma560.toml");
//!
//! let q = SVector::<f64, 6>::new(0.2, -0.3, 0.1, 0.4, 0.6, -0.5);
//! let pose = puma::fk(&q);
//!
//! // Closed form: every solution.
//! let all = puma::IK.solve(&pose);
//! assert_eq!(all, DecoupledIk::from_chain(puma::CHAIN).unwrap().solve(&pose));
//! assert!(all.len() >= 2);
//!
//! // Numeric: one solution near the seed.
//! let seed = q + SVector::repeat(0.1);
//! let found = NumericIk::default().solve(&puma::Robot, &pose, &seed).unwrap();
//! assert!(found.position_error < 1e-10 && found.orientation_error < 1e-10);
//! ```

#![cfg_attr(not(feature = "std"), no_std)]

mod numeric;
mod preference;
mod task;

pub use dhgen_kernel::closed_form::{
    ArmKind, DecoupledIk, Solutions, StructureError, VERIFY_TOLERANCE,
};
pub use dhgen_kernel::pose_error;
pub use numeric::{IkError, NumericIk, Solution};
pub use preference::{CostFunction, Preference};
pub use task::Task;
