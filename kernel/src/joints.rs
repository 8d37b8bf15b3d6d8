//! Joint vectors at the public boundary: one convention for every function that takes joint
//! values.
//!
//! - [`Joints`]: anything that holds joint values contiguously: arrays, slices, `Vec`s and
//!   nalgebra vectors (`SVector`, `DVector`). The runtime [`Robot`](crate::Robot) takes it
//!   and checks the length at run time.
//! - [`JointArray`]: the fixed-size ones, arrays `[T; N]` and `SVector<T, N>`. Generated
//!   functions take it: the length is checked by the compiler, so they cannot panic.
//!
//! So the value a generated function returns (an `SVector`) goes straight back in:
//!
//! ```
//! dhgen::robot!(mod puma = "../robots/puma560.toml");
//! let (q, qd, qdd) = ([0.1, -0.6, 0.4, 0.3, 0.8, -0.2], [0.2; 6], [0.5; 6]);
//! let tau = puma::inverse_dynamics(&q, &qd, &qdd); // SVector<f64, 6>
//! let back = puma::forward_dynamics(&q, &qd, &tau).unwrap();
//! assert!((back - dhgen::nalgebra::SVector::from(qdd)).amax() < 1e-9);
//! ```

use nalgebra::{Dim, IsContiguous, Matrix, RawStorage, SVector, Scalar, U1};

/// Joint values held contiguously, one per joint, viewed as a slice.
pub trait Joints<T> {
    /// The values, joint 1 first.
    fn joints(&self) -> &[T];
}

impl<T> Joints<T> for [T] {
    fn joints(&self) -> &[T] {
        self
    }
}

impl<T, const N: usize> Joints<T> for [T; N] {
    fn joints(&self) -> &[T] {
        self
    }
}

#[cfg(feature = "std")]
impl<T> Joints<T> for Vec<T> {
    fn joints(&self) -> &[T] {
        self
    }
}

impl<T: Scalar, R: Dim, S: RawStorage<T, R, U1> + IsContiguous> Joints<T> for Matrix<T, R, U1, S> {
    fn joints(&self) -> &[T] {
        self.as_slice()
    }
}

/// Exactly `N` joint values, known at compile time: what generated functions take.
pub trait JointArray<T, const N: usize>: Joints<T> {
    /// The values as an array.
    fn to_array(&self) -> [T; N];
}

impl<T: Copy, const N: usize> JointArray<T, N> for [T; N] {
    #[inline]
    fn to_array(&self) -> [T; N] {
        *self
    }
}

impl<T: Scalar + Copy, const N: usize> JointArray<T, N> for SVector<T, N> {
    #[inline]
    fn to_array(&self) -> [T; N] {
        self.data.0[0]
    }
}
