//! The root finders of the subproblems: `a cos x + b sin x = c`, real polynomials of degree
//! at most 4 and trigonometric ones of degree 2, each taking a root within rounding of a double
//! one as that double root as well (see the module documentation of `closed_form`).

use super::wrap_angle;
use core::f64::consts::{PI, TAU};
use nalgebra::Complex;
#[cfg(not(feature = "std"))]
use nalgebra::{ComplexField as _, RealField as _};

/// Up to `N` real values found by a subproblem, in a fixed array.
#[derive(Clone, Copy, Debug)]
pub(super) struct Roots<const N: usize> {
    pub(super) x: [f64; N],
    pub(super) len: usize,
    /// The equation does not depend on the unknown: every value solves it, and the one value
    /// held, 0, stands for them (a joint the pose leaves free).
    pub(super) free: bool,
}

impl<const N: usize> Roots<N> {
    pub(super) const NONE: Self = Roots {
        x: [0.0; N],
        len: 0,
        free: false,
    };

    /// Every value: 0 stands for them.
    pub(super) const FREE: Self = Roots {
        x: [0.0; N],
        len: 1,
        free: true,
    };

    pub(super) fn one(x: f64) -> Self {
        let mut r = Self::NONE;
        r.push(x);
        r
    }

    pub(super) fn push(&mut self, x: f64) {
        if self.len < N {
            self.x[self.len] = x;
            self.len += 1;
        }
    }

    pub(super) fn as_slice(&self) -> &[f64] {
        &self.x[..self.len]
    }
}

/// How well the coefficients of a trigonometric equation are known, relative to the size of
/// the terms they were computed from: 64 ulp. They come from the target pose and the arm's
/// constants through one or two products of rotations (a few ulp each), the pose itself from
/// forward kinematics of six joints (tens of ulp at most).
pub(super) const EQUATION_ROUNDING: f64 = 64.0 * f64::EPSILON;

/// How far (relative) a right-hand side may lie beyond the range of `a cos x + b sin x` and
/// still be taken as touching it: a pose out of reach by a hair (a description or target
/// rounded to twelve digits) gets the double root, which verification then judges.
pub(super) const BEYOND_RANGE: f64 = 1e-12;

/// The solutions of `a cos x + b sin x = c`, whose coefficients were computed from terms of
/// magnitude up to `size`, each to [`EQUATION_ROUNDING`].
///
/// With `ρ = √(a² + b²)` and `φ = atan2(b, a)` the roots are `φ ± acos(c/ρ)`. Coefficients
/// known to `η = EQUATION_ROUNDING · size` make `c/ρ` known to about `η/ρ`; near ±1 its two
/// roots `φ ± γ` (`γ ≈ √(2(1 − |c/ρ|))`) are then not told apart from the double root: with
/// `|c/ρ|` within `η/ρ` of 1 the double root (`φ`, or `φ + π`) is returned as well as the two
/// roots (a pose at a singularity has the double root, one beside it the two; the caller
/// verifies each). With `ρ` itself below `η` the equation does not depend on `x`: every `x`
/// solves it when `c` is below `η` too, and `x = 0` is returned to stand for them (a joint the
/// pose leaves free), else none.
pub(super) fn solve_trig(a: f64, b: f64, c: f64, size: f64) -> Roots<3> {
    let rho = a.hypot(b);
    let noise = EQUATION_ROUNDING * size;
    if !(rho.is_finite() && c.is_finite()) {
        return Roots::NONE;
    }
    if rho <= noise {
        return if c.abs() <= noise {
            Roots::FREE
        } else {
            Roots::NONE
        };
    }
    let base = b.atan2(a);
    let ratio = c / rho;
    let band = noise / rho;
    if ratio.abs() > 1.0 + band.max(BEYOND_RANGE) {
        return Roots::NONE;
    }
    let mut out = Roots::NONE;
    if ratio.abs() >= 1.0 - band {
        out.push(if ratio > 0.0 { base } else { base + PI });
    }
    if ratio.abs() < 1.0 {
        // acos through atan2 keeps full accuracy away from the boundary.
        let gamma = (1.0 - ratio * ratio).sqrt().atan2(ratio);
        out.push(base + gamma);
        out.push(base - gamma);
    }
    out
}

/// `f(x) = c0 + a cos x + b sin x`, from its values at 0, π/2 and π: `(a, b, c0)`.
pub(super) fn trig_coefficients(f: impl Fn(f64, f64) -> f64) -> (f64, f64, f64) {
    let (f0, f90, f180) = (f(1.0, 0.0), f(0.0, 1.0), f(-1.0, 0.0));
    let c0 = 0.5 * (f0 + f180);
    (0.5 * (f0 - f180), f90 - c0, c0)
}

/// The angles where the affine trigonometric function `f(cos x, sin x)`, made of terms of
/// magnitude up to `size`, vanishes (see [`solve_trig`]).
pub(super) fn trig_roots(f: impl Fn(f64, f64) -> f64, size: f64) -> Roots<3> {
    let (a, b, c0) = trig_coefficients(f);
    solve_trig(a, b, -c0, size)
}

/// The real roots of the polynomial `Σ c[k] x^k` (degree at most 4, leading coefficients
/// that vanish relative to the others dropped), by Aberth–Ehrlich iteration on the complex
/// roots, those with a negligible imaginary part polished by Newton's method on the real
/// polynomial.
pub(super) fn real_polynomial_roots(c: [f64; 5], size: f64) -> Roots<6> {
    let scale = c.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if scale == 0.0 || !scale.is_finite() {
        return Roots::NONE;
    }
    let mut degree = 4;
    while degree > 0 && c[degree].abs() <= 1e-13 * scale {
        degree -= 1;
    }
    // The value and its first two derivatives, by Horner's scheme.
    let eval = |x: f64| -> (f64, f64, f64) {
        let (mut v, mut d, mut dd) = (0.0, 0.0, 0.0);
        for k in (0..=degree).rev() {
            dd = dd * x + 2.0 * d;
            d = d * x + v;
            v = v * x + c[k];
        }
        (v, d, dd)
    };
    // The coefficients' own rounding (`size`) and that of the terms at x.
    let noise = |x: f64| {
        let terms = (0..=degree).fold(0.0, |sum, k| sum + (c[k] * x.powi(k as i32)).abs());
        EQUATION_ROUNDING * (size + terms)
    };
    let mut out = Roots::NONE;
    let coefficients: [Complex<f64>; 5] = core::array::from_fn(|k| Complex::new(c[k], 0.0));
    for z in complex_roots(&coefficients, degree).as_slice() {
        // Each complex root's real part, polished on the real polynomial, is a real root if
        // the polynomial vanishes there (a pair a rounding off the axis gives its double root).
        let near_axis = z.im.abs() <= 1e-6 * (1.0 + z.re.abs());
        let small = |x: f64| 1e-16 * (1.0 + x.abs());
        let near = real_roots_near(z.re, near_axis, eval, noise(z.re), small);
        for x in near.into_iter().flatten() {
            if !out
                .as_slice()
                .iter()
                .any(|y| (y - x).abs() <= 1e-9 * (1.0 + x.abs()))
            {
                out.push(x);
            }
        }
    }
    out
}

/// The angles where a trigonometric polynomial of degree 2,
/// `f = a0 + a1 cos x + b1 sin x + a2 cos 2x + b2 sin 2x` (given as a function), vanishes:
/// the roots on the unit circle of `z² f(z)`, `z = e^{ix}`, polished by Newton's method on
/// `f` itself.
pub(super) fn trig2_roots(f: impl Fn(f64) -> f64, size: f64) -> Roots<6> {
    // The coefficients from five samples (exact for degree 2).
    let samples: [f64; 5] = core::array::from_fn(|k| f(TAU * k as f64 / 5.0));
    let coefficient = |harmonic: f64, sine: bool| -> f64 {
        samples
            .iter()
            .enumerate()
            .map(|(k, v)| {
                let x = harmonic * TAU * k as f64 / 5.0;
                v * if sine { x.sin() } else { x.cos() }
            })
            .sum::<f64>()
            * 0.4
    };
    let a0 = samples.iter().sum::<f64>() / 5.0;
    let (a1, b1) = (coefficient(1.0, false), coefficient(1.0, true));
    let (a2, b2) = (coefficient(2.0, false), coefficient(2.0, true));
    let scale = [a0, a1, b1, a2, b2]
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    let mut out = Roots::NONE;
    if scale == 0.0 || !scale.is_finite() {
        return out;
    }
    if a2.hypot(b2) <= 1e-13 * scale {
        for x in solve_trig(a1, b1, -a0, size).as_slice() {
            out.push(*x);
        }
        return out;
    }
    // z² f(z) = ((a2 − i b2) z⁴ + (a1 − i b1) z³ + 2 a0 z² + (a1 + i b1) z + (a2 + i b2)) / 2.
    let p = [
        Complex::new(a2, b2),
        Complex::new(a1, b1),
        Complex::new(2.0 * a0, 0.0),
        Complex::new(a1, -b1),
        Complex::new(a2, -b2),
    ];
    let value = |x: f64| -> (f64, f64, f64) {
        let (c1, s1) = (x.cos(), x.sin());
        let (c2, s2) = ((2.0 * x).cos(), (2.0 * x).sin());
        (
            a0 + a1 * c1 + b1 * s1 + a2 * c2 + b2 * s2,
            -a1 * s1 + b1 * c1 - 2.0 * a2 * s2 + 2.0 * b2 * c2,
            -a1 * c1 - b1 * s1 - 4.0 * a2 * c2 - 4.0 * b2 * s2,
        )
    };
    let noise = EQUATION_ROUNDING * size;
    for z in complex_roots(&p, 4).as_slice() {
        // Each root's angle, polished on f, is a real root if f vanishes there (a pair of
        // roots a rounding off the unit circle gives its double root).
        let near_circle = (modulus(*z) - 1.0).abs() <= 1e-3;
        let near = real_roots_near(z.im.atan2(z.re), near_circle, value, noise, |_| 1e-16);
        for x in near.into_iter().flatten() {
            let x = wrap_angle(x);
            if !out
                .as_slice()
                .iter()
                .any(|y| wrap_angle(y - x).abs() <= 1e-9)
            {
                out.push(x);
            }
        }
    }
    out
}

/// Real roots of `f` (which gives its value and first two derivatives) from the estimate
/// `x`, known to `noise`: `x` polished by [`newton`], and, where `x` or the polished root is a
/// near-double root — the parabola through it has its extremum within `noise` of zero, so
/// that the pair of roots beside the extremum cannot be told from a double root — the
/// extremum (Newton's method on `f′`, a simple root there) if `f` vanishes there to `noise`:
/// a double root accurate to rounding rather than to √ε. Both are candidates (the noise is a
/// bound: a pair that is told apart is kept as well). The polished root is kept if `x` came
/// from a root `near_axis` of the real line (or of the unit circle) or if `f` vanishes there
/// to `noise` (a complex pair a rounding off the axis); the extremum if `f` vanishes there.
pub(super) fn real_roots_near(
    x: f64,
    near_axis: bool,
    f: impl Fn(f64) -> (f64, f64, f64),
    noise: f64,
    small: impl Fn(f64) -> f64,
) -> [Option<f64>; 2] {
    let double_root = |x: f64| {
        let (v, d, dd) = f(x);
        if dd != 0.0 && (v - d * d / (2.0 * dd)).abs() <= noise {
            Some(newton(x, |x| (f(x).1, f(x).2), &small))
        } else {
            None
        }
    };
    // Near a double root Newton's first step on f leaps away (f′ nearly vanishes there), so
    // the estimate is tried as one before polishing too.
    let extremum = double_root(x);
    let root = newton(x, |x| (f(x).0, f(x).1), &small);
    let extremum = extremum.or_else(|| double_root(root));
    let vanishes = |x: &f64| x.is_finite() && f(*x).0.abs() <= noise;
    [
        Some(root).filter(|x| x.is_finite() && (near_axis || vanishes(x))),
        extremum.filter(vanishes),
    ]
}

/// A root of `f` polished by Newton's method from `x` (`f` gives the value and the
/// derivative), at most 50 steps, until a step is below `small(x)`.
pub(super) fn newton(mut x: f64, f: impl Fn(f64) -> (f64, f64), small: impl Fn(f64) -> f64) -> f64 {
    for _ in 0..50 {
        let (v, d) = f(x);
        if d == 0.0 {
            break;
        }
        let step = v / d;
        x -= step;
        if step.abs() <= small(x) {
            break;
        }
    }
    x
}

/// `|z|`.
pub(super) fn modulus(z: Complex<f64>) -> f64 {
    z.re.hypot(z.im)
}

/// The roots of `Σ c[k] z^k` (degree `degree ≤ 4`), by Aberth–Ehrlich iteration.
pub(super) fn complex_roots(c: &[Complex<f64>; 5], degree: usize) -> Roots4C {
    let mut out = Roots4C {
        z: [Complex::new(0.0, 0.0); 4],
        len: 0,
    };
    if degree == 0 {
        return out;
    }
    let lead = c[degree];
    // Monic coefficients.
    let a: [Complex<f64>; 5] = core::array::from_fn(|k| {
        if k <= degree {
            c[k] / lead
        } else {
            Complex::new(0.0, 0.0)
        }
    });
    let eval = |z: Complex<f64>| -> (Complex<f64>, Complex<f64>) {
        let (mut v, mut d) = (Complex::new(0.0, 0.0), Complex::new(0.0, 0.0));
        for k in (0..=degree).rev() {
            d = d * z + v;
            v = v * z + a[k];
        }
        (v, d)
    };
    // Starting points on a circle of the roots' size (Cauchy's bound), off the axes.
    let radius = 1.0 + (0..degree).fold(0.0_f64, |m, k| m.max(modulus(a[k])));
    let radius = radius.min(1e6);
    let mut z: [Complex<f64>; 4] = core::array::from_fn(|k| {
        let angle = TAU * k as f64 / degree as f64 + 0.4;
        Complex::new(angle.cos(), angle.sin()) * (0.5 * radius)
    });
    for _ in 0..200 {
        let mut moved = 0.0_f64;
        for i in 0..degree {
            let (v, d) = eval(z[i]);
            if modulus(v) == 0.0 {
                continue;
            }
            let ratio = v / d;
            let mut sum = Complex::new(0.0, 0.0);
            for j in 0..degree {
                if j != i {
                    let diff = z[i] - z[j];
                    if modulus(diff) > 0.0 {
                        sum += Complex::new(1.0, 0.0) / diff;
                    }
                }
            }
            let step = ratio / (Complex::new(1.0, 0.0) - ratio * sum);
            if step.re.is_finite() && step.im.is_finite() {
                z[i] -= step;
                moved = moved.max(modulus(step) / (1.0 + modulus(z[i])));
            }
        }
        if moved < 1e-15 {
            break;
        }
    }
    for zi in &z[..degree] {
        out.z[out.len] = *zi;
        out.len += 1;
    }
    out
}

/// Up to four complex roots.
pub(super) struct Roots4C {
    pub(super) z: [Complex<f64>; 4],
    pub(super) len: usize,
}

impl Roots4C {
    pub(super) fn as_slice(&self) -> &[Complex<f64>] {
        &self.z[..self.len]
    }
}

/// The value nearest 0 of a joint the position leaves free at which `g` (affine in the
/// joint's cosine and sine, made of terms of magnitude `size`) lies in `[lo, hi]`, where the
/// rest of the arm can then complete the pose: 0 when it does there, else the nearest value
/// where `g` reaches `lo` or `hi` (the completing joint then at a double root); 0 when none.
pub(super) fn nearest_within(g: impl Fn(f64, f64) -> f64, lo: f64, hi: f64, size: f64) -> f64 {
    if (lo..=hi).contains(&g(1.0, 0.0)) {
        return 0.0;
    }
    let (a, b, c0) = trig_coefficients(g);
    let mut nearest: Option<f64> = None;
    for bound in [lo, hi] {
        for &x in solve_trig(a, b, bound - c0, size).as_slice() {
            let x = wrap_angle(x);
            if nearest.is_none_or(|y| x.abs() < y.abs()) {
                nearest = Some(x);
            }
        }
    }
    nearest.unwrap_or(0.0)
}

/// The real roots of `f`, a polynomial of degree at most 4 in a prismatic joint's
/// displacement, from five samples.
pub(super) fn quartic_in_displacement(f: &dyn Fn(f64) -> f64, size: f64) -> Roots<6> {
    // Newton's divided differences at −2..2, expanded to monomial coefficients.
    let xs = [-2.0, -1.0, 0.0, 1.0, 2.0];
    let mut dd: [f64; 5] = core::array::from_fn(|i| f(xs[i]));
    for level in 1..5 {
        for i in (level..5).rev() {
            dd[i] = (dd[i] - dd[i - 1]) / (xs[i] - xs[i - level]);
        }
    }
    // p(x) = dd0 + dd1 (x − x0) + dd2 (x − x0)(x − x1) + …, by Horner on the nested form.
    let mut c = [0.0; 5];
    c[0] = dd[4];
    for (degree, k) in (0..4).rev().enumerate() {
        // c ← c · (x − xs[k]) + dd[k]; c has degree `degree` before.
        let mut next = [0.0; 5];
        for d in 0..=degree {
            next[d + 1] += c[d];
            next[d] -= c[d] * xs[k];
        }
        next[0] += dd[k];
        c = next;
    }
    real_polynomial_roots(c, size)
}
