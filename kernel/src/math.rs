//! The few floating-point functions the chain structure needs, for `std` and `no_std` builds alike:
//! the standard library's where it is linked (the numbers every `std` user has always had),
//! the `libm` crate's otherwise.

#[cfg(feature = "std")]
mod imp {
    pub fn sqrt(x: f64) -> f64 {
        x.sqrt()
    }
    pub fn sin_cos(x: f64) -> (f64, f64) {
        x.sin_cos()
    }
    pub fn round(x: f64) -> f64 {
        x.round()
    }
    pub fn atan2(y: f64, x: f64) -> f64 {
        y.atan2(x)
    }
}

#[cfg(not(feature = "std"))]
mod imp {
    pub fn sqrt(x: f64) -> f64 {
        libm::sqrt(x)
    }
    pub fn sin_cos(x: f64) -> (f64, f64) {
        libm::sincos(x)
    }
    pub fn round(x: f64) -> f64 {
        libm::round(x)
    }
    pub fn atan2(y: f64, x: f64) -> f64 {
        libm::atan2(y, x)
    }
}

pub(crate) use imp::{atan2, round, sin_cos, sqrt};

/// `|x|` (in `core` on every supported toolchain, written out to stay independent of it).
pub(crate) fn abs(x: f64) -> f64 {
    if x < 0.0 { -x } else { x }
}
