//! Proof that `dhgen::robot!` output needs only `core` and nalgebra: this crate is
//! `#![no_std]`, depends on `dhgen` without default features, and instantiates the generated
//! kinematics and dynamics for `f32` and `f64` (generic functions are compiled only where
//! they are instantiated), and, for a module built with `derivatives` and `regressor`, every
//! function of the module (the `_lanes` forms through the functions that return them as
//! `Option`s), the derivatives, the regressor and the payload's forms among them, and one of
//! its `batch` slice functions (they share `dhgen::batch::run`).
//!
//! Building it for a target without `std`, e.g.
//! `cargo build -p dhgen-nostd-check --target thumbv7em-none-eabihf`, is the full check:
//! there, nothing can pull `std` in behind the generated code's back.

#![no_std]

use dhgen::nalgebra as na;

dhgen::robot!(pub mod puma560 = "../robots/puma560.toml");
dhgen::robot!(pub mod panda = "../robots/panda.toml");
dhgen::robot!(pub mod puma560_everything = "../robots/puma560.toml", derivatives, regressor);

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

/// Defines `$function`, which calls every generated function of `$robot` (a module built with
/// `derivatives` and `regressor`) in scalar `$t` and returns the sum of one entry of each, so
/// that each is compiled for `$t`.
macro_rules! evaluate_everything {
    ($function:ident, $robot:ident, $t:ty, $what:literal) => {
        #[doc = concat!("Calls every generated function of ", $what, " and sums one entry of each.")]
        #[must_use]
        pub fn $function(
            q: &[$t; $robot::DOF],
            qd: &[$t; $robot::DOF],
            qdd: &[$t; $robot::DOF],
            payload: &[$t; 10],
        ) -> $t {
            use $robot as r;
            let tau = r::inverse_dynamics(q, qd, qdd);
            let (mass, com) = r::center_of_mass(q);
            let (dq, dqd) = r::inverse_dynamics_derivatives(q, qd, qdd);
            let (pq, pqd) = r::inverse_dynamics_derivatives_with_payload(q, qd, qdd, payload);
            let solved = r::forward_dynamics_derivatives(q, qd, &tau)
                .map_or(0.0, |(a, b, c)| a[(1, 0)] + b[(1, 0)] + c[(1, 0)]);
            let solved_payload = r::forward_dynamics_derivatives_with_payload(q, qd, &tau, payload)
                .map_or(0.0, |(a, b, c)| a[(1, 0)] + b[(1, 0)] + c[(1, 0)]);
            let terms = r::terms(q, qd);
            let tool = r::tool_terms(q, qd);
            let mut batch = [na::SMatrix::<$t, { r::DOF }, { r::DOF }>::zeros(); 2];
            let batched =
                r::batch::mass_matrix(&[*q, *qd], &mut batch).map_or(0.0, |()| batch[1][(0, 0)]);
            r::fk_matrix(q)[(0, 3)]
                + r::fk(q).translation.vector.x
                + r::jacobian(q)[(0, 1)]
                + r::mass_matrix(q)[(1, 1)]
                + r::gravity(q)[1]
                + r::forward_dynamics(q, qd, &tau).map_or(0.0, |a| a[1])
                + r::frames(q)[2].translation.vector.x
                + r::frames_matrix(q)[2][(0, 3)]
                + r::body_jacobian(q)[(0, 1)]
                + r::jdot_qdot(q, qd)[0]
                + r::body_jdot_qdot(q, qd)[0]
                + r::det_j11(q)
                + r::det_j22(q)
                + r::christoffel(q)[1][2][0]
                + r::coriolis(q, qd)[(1, 2)]
                + r::bias(q, qd)[1]
                + r::kinetic_energy(q, qd)
                + r::potential_energy(q)
                + mass
                + com.x
                + r::center_of_mass_jacobian(q)[(0, 1)]
                + r::inverse_dynamics_with_payload(q, qd, qdd, payload)[1]
                + r::bias_with_payload(q, qd, payload)[1]
                + r::mass_matrix_with_payload(q, payload)[(1, 1)]
                + r::gravity_with_payload(q, payload)[1]
                + r::coriolis_with_payload(q, qd, payload)[(1, 2)]
                + r::forward_dynamics_with_payload(q, qd, &tau, payload).map_or(0.0, |a| a[1])
                + r::kinetic_energy_with_payload(q, qd, payload)
                + r::potential_energy_with_payload(q, payload)
                + r::regressor(q, qd, qdd)[(1, 7)]
                + r::base_regressor(q, qd, qdd)[(1, 3)]
                + r::base_parameters(&[0.5; r::PARAMETERS])[0]
                + dq[(1, 2)]
                + dqd[(1, 2)]
                + pq[(1, 2)]
                + pqd[(1, 2)]
                + solved
                + solved_payload
                + r::mass_matrix_rate(q, qd)[(1, 2)]
                + r::coriolis_transpose_qd(q, qd)[1]
                + r::mass_matrix_inverse(q).map_or(0.0, |m| m[(1, 2)])
                + terms.gravity[1]
                + tool.bias[1]
                + batched
        }
    };
}

evaluate_everything!(
    puma560_everything_f64,
    puma560_everything,
    f64,
    "the PUMA 560 in `f64`"
);
evaluate_everything!(
    puma560_everything_f32,
    puma560_everything,
    f32,
    "the PUMA 560 in `f32`"
);
