//! Inverse kinematics (section 4.3): from a desired tool pose to joint values.
//!
//! - [`DecoupledIk`]: closed form by kinematic decoupling for six-joint arms with a
//!   spherical wrist (PUMA 560, Stanford arm, the cylindrical arm, ...). Returns **all**
//!   solutions (at most 8) in a fixed-capacity [`Solutions`], each verified by forward
//!   kinematics. Built from the DH table ([`DecoupledIk::from_model`]) or from any
//!   [`Arm`](crate::Arm) ([`DecoupledIk::from_arm`]: works for generated modules, also without
//!   `std`); solving allocates nothing.
//! - [`NumericIk`]: damped least squares (Levenberg–Marquardt) for any chain (redundant arms,
//!   prismatic joints), generic over [`Arm`](crate::Arm), with joint limits, tolerances, an
//!   iteration cap and a seed; allocation-free in its loop for generated robots.
//!
//! Both measure the pose error with [`pose_error`].
//!
//! ```
//! use dhgen::ik::{DecoupledIk, NumericIk};
//! use dhgen::nalgebra::SVector;
//! dhgen::robot!(mod puma = "robots/puma560.toml");
//!
//! let q = SVector::<f64, 6>::new(0.2, -0.3, 0.1, 0.4, 0.6, -0.5);
//! let pose = puma::fk(&q);
//!
//! // Closed form: every solution.
//! let all = DecoupledIk::from_arm(&puma::Robot).unwrap().solve(&pose);
//! assert!(all.len() >= 2);
//!
//! // Numeric: one solution near the seed.
//! let seed = q + SVector::repeat(0.1);
//! let found = NumericIk::default().solve(&puma::Robot, &pose, &seed).unwrap();
//! assert!(found.position_error < 1e-10 && found.orientation_error < 1e-10);
//! ```

mod decoupled;
mod numeric;

pub use decoupled::{ArmKind, DecoupledIk, Solutions, StructureError, VERIFY_TOLERANCE};
pub use numeric::{IkError, NumericIk, Solution};

use nalgebra::Isometry3;
#[cfg(not(feature = "std"))]
use nalgebra::RealField as _;

/// The distance between two poses: `(position error in m, orientation error in rad)`, the
/// latter the angle of the rotation taking one orientation to the other, computed as
/// `2 atan2(|v|, |w|)` of the relative quaternion (accurate for small angles, where the
/// `acos` of nalgebra's `angle()` is not).
pub fn pose_error(a: &Isometry3<f64>, b: &Isometry3<f64>) -> (f64, f64) {
    let dp = (a.translation.vector - b.translation.vector).norm();
    let rel = a.rotation.inverse() * b.rotation;
    let q = rel.quaternion();
    let dr = 2.0 * q.vector().norm().atan2(q.scalar().abs());
    (dp, dr)
}
