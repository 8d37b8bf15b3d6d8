//! Angles as written in a description: radians, `"90deg"`, `"-pi/2"`.
//!
//! Multiples of a quarter turn are remembered as such, so that `cos(pi/2)` is exactly
//! 0 (not 6e-17) both at run time and in the symbolic engine, where an exact zero
//! removes whole terms from the generated code.

use crate::math;
use core::f64::consts::PI;

/// An angle in radians, with exact cosine and sine when it is a multiple of 90°.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Angle {
    rad: f64,
    /// `(cos, sin)` exactly, in {-1, 0, 1}, when the angle is a multiple of π/2.
    quarter: Option<(i8, i8)>,
}

impl Angle {
    /// An angle of `rad` radians; values within 1e-12 rad of a multiple of π/2 count as
    /// that multiple (so `1.5707963267948966` has an exact cosine of 0).
    pub fn from_radians(rad: f64) -> Angle {
        let turns = rad / (PI / 2.0);
        let k = math::round(turns);
        let quarter = if math::abs(rad - k * PI / 2.0) <= 1e-12 && math::abs(k) < 1e6 {
            Some(match (k as i64).rem_euclid(4) {
                0 => (1, 0),
                1 => (0, 1),
                2 => (-1, 0),
                _ => (0, -1),
            })
        } else {
            None
        };
        Angle { rad, quarter }
    }

    /// Zero radians.
    pub const ZERO: Angle = Angle {
        rad: 0.0,
        quarter: Some((1, 0)),
    };

    /// The angle in radians.
    pub fn radians(self) -> f64 {
        self.rad
    }

    /// `(cos, sin)`, exact for multiples of π/2.
    pub fn cos_sin(self) -> (f64, f64) {
        match self.quarter {
            Some((c, s)) => (f64::from(c), f64::from(s)),
            None => {
                let (s, c) = math::sin_cos(self.rad);
                (c, s)
            }
        }
    }

    /// `(cos, sin)` as exact integers when the angle is a multiple of π/2.
    pub fn quarter_turn(self) -> Option<(i8, i8)> {
        self.quarter
    }

    #[cfg(feature = "std")]
    /// Parses the string form: a number with an optional `deg`/`rad` suffix, or an
    /// expression in `pi` such as `pi`, `-pi/2`, `3*pi/4`, `pi/2.5`.
    pub fn parse(text: &str) -> Result<Angle, String> {
        let t: String = text.chars().filter(|c| !c.is_whitespace()).collect();
        let t = t.to_ascii_lowercase();
        let bad = || {
            format!(
                "cannot parse angle {text:?}: write radians as a number, or a string like \"90deg\", \"-pi/2\", \"3*pi/4\""
            )
        };
        if t.is_empty() {
            return Err(bad());
        }
        let num = |s: &str| -> Option<f64> {
            let v: f64 = s.parse().ok()?;
            v.is_finite().then_some(v)
        };
        if let Some(v) = t.strip_suffix("deg").or_else(|| t.strip_suffix('°')) {
            let deg = num(v).ok_or_else(bad)?;
            // Degrees that are whole multiples of 90 are exact quarter turns.
            return Ok(Angle::from_radians(deg.to_radians()));
        }
        if let Some(v) = t.strip_suffix("rad") {
            return num(v).map(Angle::from_radians).ok_or_else(bad);
        }
        if t.contains("pi") {
            let (sign, rest) = match t.strip_prefix('-') {
                Some(r) => (-1.0, r),
                None => (1.0, t.strip_prefix('+').unwrap_or(&t)),
            };
            let (numer, denom) = match rest.split_once('/') {
                Some((n, d)) => (n, Some(d)),
                None => (rest, None),
            };
            let factor = if numer == "pi" {
                1.0
            } else if let Some(f) = numer.strip_suffix("*pi") {
                num(f).ok_or_else(bad)?
            } else {
                return Err(bad());
            };
            let div = match denom {
                Some(d) => num(d).filter(|d| *d != 0.0).ok_or_else(bad)?,
                None => 1.0,
            };
            let rad = sign * factor * PI / div;
            if !rad.is_finite() {
                return Err(format!(
                    "angle {text:?} is {rad} rad; give an angle of finite size"
                ));
            }
            return Ok(Angle::from_radians(rad));
        }
        num(&t).map(Angle::from_radians).ok_or_else(bad)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_turns_are_exact() {
        for text in ["90deg", "pi/2", "1.5707963267948966", " 90 deg "] {
            let a = Angle::parse(text).unwrap();
            assert_eq!(a.cos_sin(), (0.0, 1.0), "{text}");
        }
        assert_eq!(Angle::parse("-pi/2").unwrap().cos_sin(), (0.0, -1.0));
        assert_eq!(Angle::parse("pi").unwrap().cos_sin(), (-1.0, 0.0));
        assert_eq!(Angle::parse("-270deg").unwrap().cos_sin(), (0.0, 1.0));
        assert_eq!(Angle::from_radians(0.3).quarter_turn(), None);
    }

    #[test]
    fn other_forms() {
        let a = Angle::parse("3*pi/4").unwrap().radians();
        assert!((a - 3.0 * PI / 4.0).abs() < 1e-15);
        assert!((Angle::parse("0.25rad").unwrap().radians() - 0.25).abs() < 1e-15);
        assert!((Angle::parse("45deg").unwrap().radians() - PI / 4.0).abs() < 1e-15);
        for bad in [
            "",
            "ninety",
            "pi/0",
            "2pi",
            "deg",
            "nan",
            "infdeg",
            "1e308*pi",
            "pi/1e-320",
        ] {
            assert!(Angle::parse(bad).is_err(), "{bad}");
        }
    }
}
