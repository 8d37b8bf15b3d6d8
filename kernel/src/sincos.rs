//! Sine and cosine together, without branches, for `f64`, `f32` and packs of them.
//!
//! Joint angles live in a small range, so the argument reduction needs neither the
//! Payne–Hanek path nor branches on cancellation: for |x| ≤ [`LIMIT`],
//! `n = round(x · 2/π)` and `x − n·π/2` is formed as a double-double `y0 + y1` with π/2 in
//! four pieces (Cody and Waite), the first three of 33 bits so that their products with `n`
//! (|n| < 2¹⁷) are exact; the two subtractions that can round keep their rounding errors
//! (Dekker's fast two-sum). `sin` and `cos` of `y0 + y1` (|y0| ≤ π/4) are fdlibm's minimax
//! kernels (the polynomials of `libm`'s `k_sin` and `k_cos`, themselves within one ulp, taking the tail
//! `y1`), and the quadrant `n mod 4` swaps and negates them by selects. Lanes beyond the range
//! (and non-finite ones) are handed to `libm::sincos`, one by one.
//!
//! One code path for a scalar and a pack: a lane's result is the scalar's, bit for bit. Where
//! the target has FMA instructions ([`FUSED`]) the multiply-adds of the reduction and the
//! kernels are fused, on scalars and packs alike. The error bound (within one ulp of the true
//! sine and cosine, fused or not) is checked against a double-double reference by this
//! module's test. Packs of `f64` use it, and so do scalar `f64` generated functions where the
//! target has AVX ([`PACKED`]): their `State` takes all its joints' sines and cosines as packs
//! of four ([`Real::sincos_array`](crate::Real::sincos_array)). One value at a time, `f64`
//! keeps `libm::sincos`, which is faster so (5.3 ns a call against 12.1 for this code alone
//! and 5.4 per angle in a pack of four, default x86-64 target): it has no branch to
//! mispredict but a longer dependency chain, which only a pack amortises. The variants
//! measured and not kept: docs/experiments.md, "Sine and cosine".
//!
//! `f32` arguments get fdlibm's `f32` reduction and kernels evaluated in `f64` lanes
//! ([`sincosf_lanes`]: what `libm`'s `sincosf` computes, less its branches) where the target
//! has AVX, for packs of eight `f32` and for scalar `f32` generated code's joints four at a
//! time: 0.501 ulp at worst over 10⁷ arguments (this module's second test). With AVX2, 64
//! angles in packs of eight take 91 ns against 161 for `libm::sincosf` one by one; without
//! AVX `f32` keeps `libm::sincosf`, which is then as fast.

use nalgebra::{SimdBool, SimdComplexField, SimdPartialOrd, SimdRealField, SimdValue};
use simba::simd::{WideF32x8, WideF64x4};

/// The largest |x| the branch-free paths take; beyond it, `libm::sincos` (`sincosf` for `f32`).
pub const LIMIT: f64 = 1e5;

/// 2/π.
const INV_PIO2: f64 = f64::from_bits(0x3FE4_5F30_6DC9_C883);
/// 1.5 · 2⁵²: adding and subtracting it rounds to the nearest integer (|v| < 2⁵¹).
const TO_INT: f64 = 6_755_399_441_055_744.0;
/// π/2 in pieces: the first three have 33 significant bits (exact products with |n| < 2²⁰);
/// fdlibm's constants, as are the kernels' coefficients (bit patterns from its sources).
const PIO2_1: f64 = f64::from_bits(0x3FF9_21FB_5440_0000);
const PIO2_2: f64 = f64::from_bits(0x3DD0_B461_1A60_0000);
const PIO2_3: f64 = f64::from_bits(0x3BA3_198A_2E00_0000);
const PIO2_3T: f64 = f64::from_bits(0x397B_839A_2520_49C1);

const S1: f64 = f64::from_bits(0xBFC5_5555_5555_5549);
const S2: f64 = f64::from_bits(0x3F81_1111_1110_F8A6);
const S3: f64 = f64::from_bits(0xBF2A_01A0_19C1_61D5);
const S4: f64 = f64::from_bits(0x3EC7_1DE3_57B1_FE7D);
const S5: f64 = f64::from_bits(0xBE5A_E5E6_8A2B_9CEB);
const S6: f64 = f64::from_bits(0x3DE5_D93A_5ACF_D57C);

const C1: f64 = f64::from_bits(0x3FA5_5555_5555_554C);
const C2: f64 = f64::from_bits(0xBF56_C16C_16C1_5177);
const C3: f64 = f64::from_bits(0x3EFA_01A0_19CB_1590);
const C4: f64 = f64::from_bits(0xBE92_7E4F_809C_52AD);
const C5: f64 = f64::from_bits(0x3E21_EE9E_BDB4_B1C4);
const C6: f64 = f64::from_bits(0xBDA8_FAE9_BE88_38D4);

/// `a − b` as `(s, e)` with `s = fl(a − b)` and `s + e = a − b` exactly, when |a| ≥ |b| or
/// the difference is exact (then `e = 0`): Dekker's fast two-sum.
#[inline(always)]
fn fast_two_diff<T: SimdRealField + Copy>(a: T, b: T) -> (T, T) {
    let s = a - b;
    (s, (a - s) - b)
}

/// Whether [`sincos`] fuses its multiply-adds: where the target has FMA instructions (a pack's
/// fused multiply-add is then one instruction, as a scalar's is), so that scalars and packs
/// round alike on every target. With AVX2 and FMA (`-C target-cpu=x86-64-v3`), fusing takes
/// 21 % off a pack's sine and cosine and 9–18 % off fk, J, D and τ on packs.
pub const FUSED: bool = cfg!(target_feature = "fma");

/// Whether scalar `f64` code evaluates several sines and cosines as one pack
/// ([`Real::sincos_array`](crate::Real::sincos_array)): where the target has AVX, whose
/// registers hold four `f64` (`-C target-cpu=x86-64-v3` or `native` on current x86). There a
/// pack of four costs about as many instructions as one `libm::sincos` (112 against 93 for
/// angles in [−2, 2]). With two `f64` per register (SSE2, the default `x86_64` target) a pack
/// costs 323, against 4 × 104 for `libm`, and no less time (5.4 ns per angle against 5.3);
/// with the padding lanes of a last, partial pack, the PUMA 560's six joints cost 713 against
/// 610 one by one (measured, callgrind), so `libm` stays there. Other targets (NEON, for
/// one) were not measured and keep `libm`.
pub const PACKED: bool = cfg!(target_feature = "avx");

/// `a·b + c`, with one rounding when `FUSED`: the sine and cosine's, and generated code's
/// through [`Real::mul_add_fast`](crate::Real::mul_add_fast).
#[inline(always)]
pub(crate) fn mul_add<T: SimdRealField + Copy, const FUSED: bool>(a: T, b: T, c: T) -> T {
    if FUSED {
        a.simd_mul_add(b, c)
    } else {
        a * b + c
    }
}

/// `(sin x, cos x)` lane by lane, within one ulp.
///
/// ```
/// let (s, c) = dhgen::sincos::sincos(1.0f64);
/// assert!((s - 1f64.sin()).abs() <= f64::EPSILON && (c - 1f64.cos()).abs() <= f64::EPSILON);
/// ```
#[inline(always)]
pub fn sincos<T>(x: T) -> (T, T)
where
    T: SimdRealField<Element = f64> + Copy,
{
    sincos_with::<T, FUSED>(x)
}

/// [`sincos`] with its multiply-adds fused or not (both within one ulp: the test checks both).
#[inline(always)]
fn sincos_with<T, const FUSED: bool>(x: T) -> (T, T)
where
    T: SimdRealField<Element = f64> + Copy,
{
    let mul_add = mul_add::<T, FUSED>;
    let k = T::splat;
    let to_int = k(TO_INT);
    let f_n = mul_add(x, k(INV_PIO2), to_int) - to_int;
    // x − n·π/2 = a − b − c − d: `a` exact (the product is, and the difference is a multiple
    // of the coarser operand's unit below 2⁵³ of them), `b` and `c` exact products.
    let a = mul_add(-f_n, k(PIO2_1), x);
    // Either |a| is well above n·PIO2_2 or the two nearly cancel and their difference is
    // exact (fdlibm's argument, which its second and third rounds rest on); the same for the
    // next piece.
    let (s1, e1) = fast_two_diff(a, f_n * k(PIO2_2));
    let (s2, e2) = fast_two_diff(s1, f_n * k(PIO2_3));
    let lo = mul_add(-f_n, k(PIO2_3T), e1 + e2);
    let y0 = s2 + lo;
    let y1 = (s2 - y0) + lo;

    // fdlibm's kernels on y0 + y1, |y0| ≤ π/4 (plus rounding).
    let z = y0 * y0;
    let w = z * z;
    let half = k(0.5);
    let rs = mul_add(
        z * w,
        mul_add(z, k(S6), k(S5)),
        mul_add(z, mul_add(z, k(S4), k(S3)), k(S2)),
    );
    let v = z * y0;
    let sin = y0 - mul_add(-v, k(S1), mul_add(z, mul_add(-v, rs, half * y1), -y1));
    let rc = mul_add(
        w * w,
        mul_add(z, mul_add(z, k(C6), k(C5)), k(C4)),
        z * mul_add(z, mul_add(z, k(C3), k(C2)), k(C1)),
    );
    let hz = half * z;
    let one = k(1.0);
    let wc = one - hz;
    let cos = wc + (((one - wc) - hz) + mul_add(z, rc, -(y0 * y1)));

    let (mut s, mut c) = by_quadrant::<T, FUSED>(x, f_n, sin, cos);

    // Beyond the range, or not finite: libm, lane by lane.
    let outside = !x.simd_abs().simd_le(k(LIMIT));
    if outside.any() {
        for i in 0..T::LANES {
            if (outside.bitmask() >> i) & 1 == 1 {
                let (si, ci) = libm::sincos(x.extract(i));
                s.replace(i, si);
                c.replace(i, ci);
            }
        }
    }
    (s, c)
}

/// `(sin x, cos x)` from the sine and cosine of `y = x − n·π/2` (`f_n` = n, an integer
/// below 2⁵⁰ in magnitude): the quadrant `n mod 4` swaps and negates them by selects, and
/// sin(±0) is ±0 (the reductions give +0 for both).
#[inline(always)]
fn by_quadrant<T, const FUSED: bool>(x: T, f_n: T, sin: T, cos: T) -> (T, T)
where
    T: SimdRealField<Element = f64> + Copy,
{
    let k = T::splat;
    let to_int = k(TO_INT);
    let mul_add = mul_add::<T, FUSED>;
    // m = n − 4·round(n/4) ∈ {−2, −1, 0, 1, 2}, exactly.
    let m = mul_add(k(-4.0), mul_add(f_n, k(0.25), to_int) - to_int, f_n);
    let is = |c: f64| m.simd_eq(k(c));
    let odd = is(1.0) | is(-1.0);
    let neg_sin = is(2.0) | is(-2.0) | is(-1.0);
    let neg_cos = is(1.0) | is(2.0) | is(-2.0);
    let s = cos.select(odd, sin);
    let c = sin.select(odd, cos);
    let s = (-s).select(neg_sin, s);
    (x.select(x.simd_eq(T::zero()), s), (-c).select(neg_cos, c))
}

/// π/2 in two pieces for `f32` arguments (fdlibm's `__rem_pio2f`): the first of 25
/// significant bits, so that its product with n is exact for |n| < 2²⁸, and the rest.
const PIO2_1_F: f64 = f64::from_bits(0x3FF9_21FB_5000_0000);
const PIO2_1T_F: f64 = f64::from_bits(0x3E51_10B4_611A_6263);

/// fdlibm's `f32` kernels (`__kernel_sindf`, `__kernel_cosdf`), evaluated in `f64` for
/// |y| ≤ π/4: |sin(y)/y − s(y)| < 2⁻³⁷·⁵ and |cos(y) − c(y)| < 2⁻³⁴·⁴, far below half an
/// `f32` ulp.
const SF: [f64; 4] = [
    f64::from_bits(0xBFC5_5555_54CB_AC77),
    f64::from_bits(0x3F81_1110_896E_FBB2),
    f64::from_bits(0xBF2A_00F9_E2CA_E774),
    f64::from_bits(0x3EC6_CD87_8C3B_46A7),
];
const CF: [f64; 4] = [
    f64::from_bits(0xBFDF_FFFF_FD0C_5E81),
    f64::from_bits(0x3FA5_5553_E105_3A42),
    f64::from_bits(0xBF56_C087_E80F_1E27),
    f64::from_bits(0x3EF9_9342_E0EE_5069),
];

/// fdlibm's `sinf`/`cosf` reduction and kernels on `f32` arguments held exactly in `f64`
/// lanes, for |x| ≤ [`LIMIT`]: `(n, sin y, cos y)` with `y = x − n·π/2`, |y| ≤ π/4, to `f64`
/// precision (within about 2⁻³⁴ relative, so within one `f32` ulp once rounded to `f32`).
/// π/2 in 25 + 53 bits is ample for the 24 bits of an `f32`; `libm`'s `sincosf` evaluates the
/// same polynomials in `f64`, with a shorter reduction of its own for |x| ≤ 9π/4.
#[inline(always)]
fn sincosf_reduced<T, const FUSED: bool>(x: T) -> (T, T, T)
where
    T: SimdRealField<Element = f64> + Copy,
{
    let mul_add = mul_add::<T, FUSED>;
    let k = T::splat;
    let to_int = k(TO_INT);
    let f_n = mul_add(x, k(INV_PIO2), to_int) - to_int;
    // Exact (the product is, and the difference has at most 24 significant bits), then one
    // rounding.
    let y = mul_add(-f_n, k(PIO2_1T_F), mul_add(-f_n, k(PIO2_1_F), x));
    let z = y * y;
    let w = z * z;
    let sz = z * y;
    let sin = mul_add(
        sz * w,
        mul_add(z, k(SF[3]), k(SF[2])),
        mul_add(sz, mul_add(z, k(SF[1]), k(SF[0])), y),
    );
    let cos = mul_add(
        w * z,
        mul_add(z, k(CF[3]), k(CF[2])),
        mul_add(w, k(CF[1]), mul_add(z, k(CF[0]), k(1.0))),
    );
    (f_n, sin, cos)
}

/// `(sin x, cos x)` of four `f32` values held exactly in `f64` lanes, lane by lane, before
/// their rounding to `f32`: without branches for |x| ≤ [`LIMIT`] (fdlibm's `f32` reduction
/// and kernels, the quadrant by selects), `libm::sincosf` beyond (and for ±∞ and NaN; exact
/// in `f64`). Once rounded, within one `f32` ulp (0.501 measured); `libm`'s `sincosf`, whose
/// shorter reductions for |x| ≤ 9π/4 round differently, gives the same `f32` results but in
/// 64 of 10⁷ arguments (by one ulp).
///
/// Used where the target has AVX ([`PACKED`]): by [`WideF32x8`]'s sine and cosine, and by
/// `f32`'s [`Real::sincos_array`](crate::Real::sincos_array), so that a scalar `f32`
/// generated function's sines and cosines are a pack's lanes bit for bit. With AVX2, about 20
/// instructions per value (a pack of eight `f32`: 160, as two packs of four) against
/// `libm::sincosf`'s 50 (angles in [−3, 3], callgrind). With two `f64` per register (SSE2)
/// the selects and both kernels cost more than `libm`'s branches, so there `f32` keeps
/// `libm::sincosf`, one value at a time and lane by lane.
#[inline(always)]
pub fn sincosf_lanes(x: WideF64x4) -> (WideF64x4, WideF64x4) {
    let (f_n, sin, cos) = sincosf_reduced::<WideF64x4, FUSED>(x);
    let (mut s, mut c) = by_quadrant::<WideF64x4, FUSED>(x, f_n, sin, cos);
    let outside = !x.simd_abs().simd_le(WideF64x4::splat(LIMIT));
    if outside.any() {
        for i in 0..4 {
            if (outside.bitmask() >> i) & 1 == 1 {
                let (si, ci) = libm::sincosf(x.extract(i) as f32);
                s.replace(i, f64::from(si));
                c.replace(i, f64::from(ci));
            }
        }
    }
    (s, c)
}

/// [`sincosf_lanes`] on four `f32` values, rounded back to `f32`: what a pack of eight does
/// per half, and scalar `f32`'s [`Real::sincos_array`](crate::Real::sincos_array) per four
/// joints, where the target has AVX.
#[inline(always)]
pub(crate) fn sincosf_four(x: [f32; 4]) -> ([f32; 4], [f32; 4]) {
    let (s, c) = sincosf_lanes(WideF64x4::from(x.map(f64::from)));
    (
        s.0.to_array().map(|v| v as f32),
        c.0.to_array().map(|v| v as f32),
    )
}

/// `(sin x, cos x)` of eight `f32` lanes, each within one ulp: [`sincosf_lanes`] on two
/// packs of four `f64` where the target has AVX ([`PACKED`]), `libm::sincosf` lane by lane
/// elsewhere; in both cases each lane is what scalar `f32` generated code computes.
///
/// ```
/// use dhgen::batch::WideF32x8;
/// let x = [0.5f32, -2.0, 3.0, 1e-9, 7.0, 100.0, 2e5, -0.0];
/// let (s, c) = dhgen::sincos::sincosf_pack(WideF32x8(x.into()));
/// let (s, c) = (s.0.to_array(), c.0.to_array());
/// for i in 0..8 {
///     assert!((s[i] - x[i].sin()).abs() <= f32::EPSILON);
///     assert!((c[i] - x[i].cos()).abs() <= f32::EPSILON);
/// }
/// ```
#[inline]
pub fn sincosf_pack(x: WideF32x8) -> (WideF32x8, WideF32x8) {
    let lanes = x.0.to_array();
    let mut s = [0.0f32; 8];
    let mut c = [0.0f32; 8];
    if PACKED {
        for half in 0..2 {
            let at = 4 * half;
            let (hs, hc) = sincosf_four(core::array::from_fn(|l| lanes[at + l]));
            s[at..at + 4].copy_from_slice(&hs);
            c[at..at + 4].copy_from_slice(&hc);
        }
    } else {
        for (i, &xi) in lanes.iter().enumerate() {
            (s[i], c[i]) = libm::sincosf(xi);
        }
    }
    (WideF32x8(s.into()), WideF32x8(c.into()))
}

/// The one-ulp bound, against sine and cosine evaluated in double-double arithmetic
/// (≈ 106 bits: the reduction by a four-double π/2 with exact products, then Taylor series),
/// over 10⁷ arguments: the whole range uniformly, the joint range densely, the neighbours of
/// multiples of π/2 (where the reduction cancels) and of odd multiples of π/4 (where the
/// rounding of n switches), the range's edges, tiny, subnormal and signed-zero arguments.
#[cfg(all(test, feature = "std"))]
mod tests {
    use super::{
        FUSED, LIMIT, by_quadrant, sincos, sincos_with, sincosf_lanes, sincosf_pack,
        sincosf_reduced,
    };
    use nalgebra::SimdValue;

    /// The `f32` reduction and kernels with the quadrant by selects (a pack's path), fused or
    /// not, before the rounding to `f32`.
    fn sincosf_wide<const FUSED: bool>(x: f64) -> (f64, f64) {
        let (f_n, s, c) = sincosf_reduced::<f64, FUSED>(x);
        by_quadrant::<f64, FUSED>(x, f_n, s, c)
    }

    /// An unevaluated sum `hi + lo`, |lo| ≤ ulp(hi)/2.
    #[derive(Clone, Copy)]
    struct Dd(f64, f64);

    fn two_sum(a: f64, b: f64) -> Dd {
        let s = a + b;
        let bb = s - a;
        Dd(s, (a - (s - bb)) + (b - bb))
    }

    fn two_prod(a: f64, b: f64) -> Dd {
        let p = a * b;
        Dd(p, a.mul_add(b, -p))
    }

    fn add(a: Dd, b: Dd) -> Dd {
        let s = two_sum(a.0, b.0);
        let t = two_sum(a.1, b.1);
        let s = two_sum(s.0, s.1 + t.0);
        two_sum(s.0, s.1 + t.1)
    }

    fn mul(a: Dd, b: Dd) -> Dd {
        let p = two_prod(a.0, b.0);
        two_sum(p.0, p.1 + (a.0 * b.1 + a.1 * b.0))
    }

    fn div_small(a: Dd, d: f64) -> Dd {
        let q = a.0 / d;
        let r = add(a, Dd(-two_prod(q, d).0, -two_prod(q, d).1));
        two_sum(q, r.0 / d)
    }

    /// (sin x, cos x) to about 2⁻¹⁰⁰ relative.
    fn reference(x: f64) -> (Dd, Dd) {
        const PIO2: [f64; 4] = [
            core::f64::consts::FRAC_PI_2,
            6.123_233_995_736_766e-17,
            -1.497_384_904_859_169_8e-33,
            5.562_271_104_316_826e-50,
        ];
        let n = (x / PIO2[0]).round();
        let mut r = Dd(x, 0.0);
        for p in PIO2 {
            let t = two_prod(n, p);
            r = add(r, Dd(-t.0, -t.1));
        }
        let r2 = mul(r, r);
        let (mut s, mut c) = (r, Dd(1.0, 0.0));
        let (mut ts, mut tc) = (r, Dd(1.0, 0.0));
        for k in 1..30 {
            let k = f64::from(k);
            ts = div_small(mul(ts, r2), -(2.0 * k) * (2.0 * k + 1.0));
            tc = div_small(mul(tc, r2), -(2.0 * k - 1.0) * (2.0 * k));
            s = add(s, ts);
            c = add(c, tc);
        }
        let neg = |d: Dd| Dd(-d.0, -d.1);
        match (n.rem_euclid(4.0)) as u8 {
            0 => (s, c),
            1 => (c, neg(s)),
            2 => (neg(s), neg(c)),
            _ => (neg(c), s),
        }
    }

    /// |y − exact| in units of the last place of the exact value.
    fn ulps(y: f64, exact: Dd) -> f64 {
        let err = ((y - exact.0) - exact.1).abs();
        let a = exact.0.abs();
        let mut ulp = f64::from_bits(a.to_bits() + 1) - a;
        // Just below a power of two the spacing is half.
        if a.to_bits() & ((1u64 << 52) - 1) == 0 && exact.0.signum() * exact.1 < 0.0 {
            ulp /= 2.0;
        }
        err / ulp
    }

    fn step(x: f64, ulps: i64) -> f64 {
        f64::from_bits((x.to_bits() as i64 + ulps) as u64)
    }

    /// The worst errors in ulps of sine and cosine over `points` (`errors` at a point and its
    /// reference sine and cosine; `None` leaves the point out), printed and held under one.
    fn assert_under_one_ulp<X: Copy + core::fmt::LowerExp>(
        label: &str,
        points: &[X],
        references: &[(Dd, Dd)],
        errors: impl Fn(X, Dd, Dd) -> Option<(f64, f64)>,
    ) {
        let (mut worst_s, mut worst_c) = ((0.0, points[0]), (0.0, points[0]));
        for (&x, &(rs, rc)) in points.iter().zip(references) {
            let Some((es, ec)) = errors(x, rs, rc) else {
                continue;
            };
            if es > worst_s.0 {
                worst_s = (es, x);
            }
            if ec > worst_c.0 {
                worst_c = (ec, x);
            }
        }
        for (what, (worst, at)) in [("sin", worst_s), ("cos", worst_c)] {
            std::println!("{label}: {what} worst {worst:.4} ulp at {at:e}");
            assert!(worst < 1.0, "{label}: {what} {worst:.4} ulp at {at:e}");
        }
    }

    #[test]
    fn sincos_within_one_ulp() {
        let mut rng = crate::stream::Stream(0x51C0);
        let mut points: Vec<f64> = Vec::with_capacity(10_100_000);
        for _ in 0..4_000_000 {
            points.push((rng.uniform(0.0, 1.0) * 2.0 - 1.0) * LIMIT);
        }
        for _ in 0..3_000_000 {
            points.push((rng.uniform(0.0, 1.0) * 2.0 - 1.0) * 4.0 * core::f64::consts::PI);
        }
        // Neighbours of k·π/4 (multiples of π/2: cancellation; odd multiples of π/4: the
        // rounding of n switches), for k up to the range's end.
        let kmax = (LIMIT / core::f64::consts::FRAC_PI_4) as u64;
        for _ in 0..400_000 {
            let k = (rng.uniform(0.0, 1.0) * kmax as f64) as u64;
            let centre = k as f64 * core::f64::consts::FRAC_PI_4;
            for d in -3..=3 {
                points.push(step(centre, d));
                points.push(-step(centre, d));
            }
        }
        for d in 0..50_000 {
            points.push(step(LIMIT, -d));
            points.push(step(LIMIT, d));
            points.push(-step(LIMIT, d));
            points.push(f64::from_bits(d as u64)); // subnormals and +0
            points.push(-f64::from_bits(d as u64 * 0x1_0000_0000)); // subnormals, tiny
        }
        for e in -1074..=16 {
            points.push(2f64.powi(e));
            points.push(-(2f64.powi(e)));
        }
        assert!(points.len() >= 10_000_000, "{} points", points.len());
        // Both variants, whichever this target compiles `sincos` to: unfused multiply-adds, and
        // fused ones (f64::mul_add, one rounding, in hardware or in software alike).
        let references: Vec<_> = points.iter().map(|&x| reference(x)).collect();
        for (fused, f) in [
            (false, sincos_with::<f64, false> as fn(f64) -> (f64, f64)),
            (true, sincos_with::<f64, true>),
        ] {
            assert_under_one_ulp(
                &format!("fused {fused}"),
                &points,
                &references,
                |x, rs, rc| {
                    let (s, c) = f(x);
                    Some((ulps(s, rs), ulps(c, rc)))
                },
            );
        }
        assert_eq!(
            sincos(0.7f64),
            sincos_with::<f64, FUSED>(0.7),
            "sincos is the target's variant"
        );
        // A pack's lanes are the scalar's, bit for bit, the fallback lanes included.
        for chunk in points
            .chunks(4)
            .step_by(997)
            .chain([&[1e6, -0.0, 0.5, f64::NAN][..]])
        {
            let x = simba::simd::WideF64x4([chunk[0], chunk[1], chunk[2], chunk[3]].into());
            let (s, c) = sincos(x);
            for (i, &xi) in chunk.iter().enumerate() {
                let (si, ci) = sincos(xi);
                assert_eq!(s.0.to_array()[i].to_bits(), si.to_bits(), "sin {xi}");
                assert_eq!(c.0.to_array()[i].to_bits(), ci.to_bits(), "cos {xi}");
            }
        }
        // Every entry of an array (a full pack and a partial one), bit for bit this sine and
        // cosine's where they are packed, `libm`'s elsewhere.
        let x = [0.25, -3.0, 1e6, 7.5, -0.0, 2.0, f64::NAN];
        let (s, c) = <f64 as crate::Real>::sincos_array(x);
        for (i, x) in x.into_iter().enumerate() {
            let (si, ci) = if super::PACKED {
                sincos(x)
            } else {
                libm::sincos(x)
            };
            assert_eq!(
                (s[i].to_bits(), c[i].to_bits()),
                (si.to_bits(), ci.to_bits()),
                "{x}"
            );
        }
        // Signed zero and the cases beyond the range (libm's).
        assert_eq!(sincos(-0.0f64).0.to_bits(), (-0.0f64).to_bits());
        for x in [f64::NAN, f64::INFINITY, 1e6, -3e9, f64::MAX] {
            let (s, c) = sincos(x);
            let (ls, lc) = libm::sincos(x);
            assert!(
                s.to_bits() == ls.to_bits() && c.to_bits() == lc.to_bits(),
                "{x}"
            );
        }
    }

    /// |y − exact| in units of the last place of an `f32` at the exact value.
    fn ulps_f32(y: f32, exact: Dd) -> f64 {
        let err = ((f64::from(y) - exact.0) - exact.1).abs();
        let near = (exact.0 as f32).abs();
        let mut ulp = f64::from(f32::from_bits(near.to_bits() + 1)) - f64::from(near);
        // Just below a power of two the spacing is half.
        if near.to_bits() & 0x7F_FFFF == 0 && near.to_bits() != 0 && exact.0.abs() < f64::from(near)
        {
            ulp /= 2.0;
        }
        err / ulp
    }

    fn step_f32(x: f32, ulps: i32) -> f32 {
        f32::from_bits((x.to_bits() as i32 + ulps) as u32)
    }

    /// The one-ulp bound of the `f32` sine and cosine, against the same double-double
    /// reference, over 10⁷ `f32` arguments chosen as for `f64`; and packs of eight equal to
    /// scalars bit for bit, `libm`'s `sincosf` beyond the range.
    #[test]
    fn sincosf_within_one_ulp() {
        let mut rng = crate::stream::Stream(0x51C1);
        let mut points: Vec<f32> = Vec::with_capacity(10_100_000);
        let limit = LIMIT as f32;
        for _ in 0..4_000_000 {
            points.push(((rng.uniform(0.0, 1.0) * 2.0 - 1.0) * LIMIT) as f32);
        }
        for _ in 0..3_000_000 {
            points.push(((rng.uniform(0.0, 1.0) * 2.0 - 1.0) * 4.0 * core::f64::consts::PI) as f32);
        }
        let kmax = (LIMIT / core::f64::consts::FRAC_PI_4) as u64;
        for _ in 0..200_000 {
            let k = (rng.uniform(0.0, 1.0) * kmax as f64) as u64;
            let centre = (k as f64 * core::f64::consts::FRAC_PI_4) as f32;
            for d in -3..=3 {
                points.push(step_f32(centre, d));
                points.push(-step_f32(centre, d));
            }
        }
        // Every f32 next to the first 2,000 multiples of π/4 (the joint range and beyond).
        for k in 0..2_000u32 {
            let centre = (f64::from(k) * core::f64::consts::FRAC_PI_4) as f32;
            for d in -40..=40 {
                points.push(step_f32(centre, d));
            }
        }
        for d in 0..50_000 {
            points.push(step_f32(limit, -d));
            points.push(step_f32(limit, d));
            points.push(-step_f32(limit, d));
            points.push(f32::from_bits(d as u32)); // subnormals and +0
            points.push(-f32::from_bits(d as u32 * 0x100)); // subnormals, tiny
        }
        for e in -149..=16 {
            points.push(2f32.powi(e));
            points.push(-(2f32.powi(e)));
        }
        assert!(points.len() >= 10_000_000, "{} points", points.len());
        let references: Vec<_> = points.iter().map(|&x| reference(f64::from(x))).collect();
        for (fused, f) in [
            (false, sincosf_wide::<false> as fn(f64) -> (f64, f64)),
            (true, sincosf_wide::<true>),
        ] {
            let label = format!("f32, fused {fused}");
            assert_under_one_ulp(&label, &points, &references, |x, rs, rc| {
                // Beyond the range (and not finite): libm's.
                (x.abs() <= limit).then(|| {
                    let (s, c) = f(f64::from(x));
                    (ulps_f32(s as f32, rs), ulps_f32(c as f32, rc))
                })
            });
        }
        // A value through a pack of four (lane 0): the target's variant within the range,
        // libm's beyond it.
        let packed = |x: f32| -> (f32, f32) {
            let (s, c) = sincosf_lanes(simba::simd::WideF64x4::splat(f64::from(x)));
            (s.0.to_array()[0] as f32, c.0.to_array()[0] as f32)
        };
        let (mut differ, mut beyond) = (0usize, 0usize);
        for &x in &points {
            let (s, c) = packed(x);
            if x.abs() <= limit {
                let (ws, wc) = sincosf_wide::<FUSED>(f64::from(x));
                assert_eq!(
                    (s.to_bits(), c.to_bits()),
                    ((ws as f32).to_bits(), (wc as f32).to_bits())
                );
            } else {
                beyond += 1;
            }
            differ += usize::from((s, c) != libm::sincosf(x));
        }
        std::println!(
            "f32: {differ} of {} differ from libm's sincosf ({beyond} beyond the range)",
            points.len()
        );
        assert_eq!(packed(-0.0).0.to_bits(), (-0.0f32).to_bits());
        for x in [
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            1e6,
            -3e9,
            f32::MAX,
            -1.00001e5,
        ] {
            let (s, c) = packed(x);
            let (ls, lc) = libm::sincosf(x);
            assert!(
                s.to_bits() == ls.to_bits() && c.to_bits() == lc.to_bits(),
                "{x}"
            );
        }
        // What f32 generated code computes, one value at a time and in packs of eight: the
        // packed variant where the target has AVX, libm's elsewhere, bit for bit either way.
        let target = |x: f32| {
            if super::PACKED {
                packed(x)
            } else {
                libm::sincosf(x)
            }
        };
        for chunk in points.chunks(8).step_by(499).chain([&[
            1e6,
            -0.0,
            0.5,
            f32::NAN,
            f32::INFINITY,
            3.0,
            -1e5,
            2e5,
        ][..]])
        {
            let x: [f32; 8] = core::array::from_fn(|i| chunk[i]);
            let (s, c) = sincosf_pack(simba::simd::WideF32x8(x.into()));
            let (s, c) = (s.0.to_array(), c.0.to_array());
            let (sa, ca) = <f32 as crate::Real>::sincos_array(x);
            for (i, &xi) in x.iter().enumerate() {
                let (si, ci) = target(xi);
                assert_eq!(
                    (s[i].to_bits(), c[i].to_bits()),
                    (si.to_bits(), ci.to_bits()),
                    "{xi}"
                );
                assert_eq!(
                    (sa[i].to_bits(), ca[i].to_bits()),
                    (si.to_bits(), ci.to_bits()),
                    "{xi}"
                );
            }
        }
    }
}
