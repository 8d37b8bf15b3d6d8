//! Proof that `dhgen::robot!` output needs only `core` and nalgebra: this crate is
//! `#![no_std]`, depends on `dhgen` without default features, and instantiates every
//! generated kinematics and dynamics function for `f32` and `f64`.
//!
//! Building it for a target without `std`, e.g.
//! `cargo build -p dhgen-nostd-check --target thumbv7em-none-eabihf`, is the full check:
//! there, nothing can pull `std` in behind the generated code's back.

#![no_std]

use dhgen::nalgebra as na;

dhgen::robot!(pub mod puma560 = "../robots/puma560.toml");
dhgen::robot!(pub mod panda = "../robots/panda.toml");

/// Every generated quantity of an `N`-joint robot at one state `(q, q̇, q̈)`.
#[derive(Clone, Copy, Debug)]
pub struct Evaluation<T: na::Scalar, const N: usize> {
    /// Tool pose, `fk(q)`.
    pub pose: na::Isometry3<T>,
    /// Geometric Jacobian, `jacobian(q)`.
    pub jacobian: na::SMatrix<T, 6, N>,
    /// Joint-space inertia matrix, `mass_matrix(q)`.
    pub mass_matrix: na::SMatrix<T, N, N>,
    /// Gravity torques, `gravity(q)`.
    pub gravity: na::SVector<T, N>,
    /// Joint torques, `inverse_dynamics(q, q̇, q̈)`.
    pub torque: na::SVector<T, N>,
    /// `forward_dynamics(q, q̇, τ)` applied to `torque`: q̈ again, up to rounding.
    pub acceleration: Option<na::SVector<T, N>>,
}

/// Defines `$function`, which evaluates robot module `$robot` in scalar `$t`. Concrete
/// (non-generic) functions, so that the generated code is compiled for each scalar.
macro_rules! evaluate {
    ($function:ident, $robot:ident, $t:ty, $what:literal) => {
        #[doc = concat!("Evaluates every generated function of ", $what, ".")]
        #[must_use]
        pub fn $function(
            q: &[$t; $robot::DOF],
            qd: &[$t; $robot::DOF],
            qdd: &[$t; $robot::DOF],
        ) -> Evaluation<$t, { $robot::DOF }> {
            let torque = $robot::inverse_dynamics(q, qd, qdd);
            Evaluation {
                pose: $robot::fk(q),
                jacobian: $robot::jacobian(q),
                mass_matrix: $robot::mass_matrix(q),
                gravity: $robot::gravity(q),
                torque,
                acceleration: $robot::forward_dynamics(q, qd, &torque),
            }
        }
    };
}

evaluate!(puma560_f64, puma560, f64, "the PUMA 560 in `f64`");
evaluate!(puma560_f32, puma560, f32, "the PUMA 560 in `f32`");
evaluate!(panda_f64, panda, f64, "the Panda in `f64`");
evaluate!(panda_f32, panda, f32, "the Panda in `f32`");
