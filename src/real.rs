//! The scalar types generated code is generic over.

/// nalgebra's `RealField` (by copy) plus a combined sine and cosine.
///
/// Generated functions take any `T: Real`. `f64` and `f32` compute `sincos` with one shared
/// argument reduction (the `libm` crate's port of musl, accurate to within 1 ulp), about a
/// quarter fewer instructions than separate `sin` and `cos`; any other `RealField` type can
/// implement the trait with the default, which calls `sin_cos`.
///
/// ```
/// use dhgen::Real;
/// let (s, c) = 0.5f64.sincos();
/// assert!((s - 0.5f64.sin()).abs() <= f64::EPSILON && (c - 0.5f64.cos()).abs() <= f64::EPSILON);
/// ```
pub trait Real: nalgebra::RealField + Copy {
    /// `(sin x, cos x)`.
    #[inline]
    fn sincos(self) -> (Self, Self) {
        self.sin_cos()
    }
}

impl Real for f64 {
    #[inline]
    fn sincos(self) -> (f64, f64) {
        libm::sincos(self)
    }
}

impl Real for f32 {
    #[inline]
    fn sincos(self) -> (f32, f32) {
        libm::sincosf(self)
    }
}
