//! Base parameters: the minimal set of combinations of the inertial parameters that the
//! dynamics determine, by the one rule of [`dhgen_description::parameters`] (Gautier's
//! rank-revealing QR of the regressor stacked over seeded random states) applied to the
//! runtime regressor.
//!
//! Many columns of the regressor `Y` are zero at every state (a parameter that never moves
//! anything: the first link's mass) or linear combinations of others (Ixx and Iyy of a link
//! turning about z enter only as their difference with others). `τ = Y π` is then also
//! `τ = Y_b π_b` with `Y_b` the `b` independent columns and `π_b = π_i + β π_d` regrouping the
//! dependent parameters `π_d` into the independent ones `π_i`. The test
//! `base_parameter_count_is_the_rank` checks the count against the rank of `Y` stacked over
//! 1,000 states by a singular value decomposition, an independent computation.

use crate::robot::Robot;
pub use dhgen_description::parameters::BaseParameters;

impl Robot {
    /// The robot's base parameters (see the [`dhgen::parameters`](crate::parameters)), from its
    /// regressor stacked over `max(20, 4·p/n)` seeded random states (`p` parameters, `n`
    /// joints): positions in the joint limits (±π without), velocities and accelerations in ±2.
    ///
    /// # Panics
    /// If the robot has no mass properties.
    pub fn base_parameters(&self) -> BaseParameters {
        self.check_dynamics("base_parameters");
        dhgen_description::parameters::base_parameters(&self.model, |q, qd, qdd| {
            self.regressor(q, qd, qdd)
        })
    }
}
