//! The scalar types generated code is generic over.

use nalgebra::SimdRealField;
use simba::simd::{WideF32x8, WideF64x4};

/// nalgebra's `SimdRealField` (by copy) plus a combined sine and cosine: a real number, or a
/// pack of them evaluated lane by lane.
///
/// Generated functions take any `T: Real`. `f64` and `f32` compute `sincos` with one shared
/// argument reduction (the `libm` crate's port of musl, accurate to within 1 ulp), about a
/// quarter fewer instructions than separate `sin` and `cos`; a generated `State` takes all its
/// joints' at once ([`sincos_array`](Real::sincos_array)), which `f64` and `f32` evaluate four
/// at a time on a pack where the target has AVX. Any `RealField` type (a dual number, say)
/// implements `SimdRealField` with one lane and can implement this trait with the defaults.
///
/// The SIMD packs [`WideF64x4`] (four `f64`) and [`WideF32x8`] (eight `f32`) are `Real` too:
/// every generated function evaluates four (eight) configurations in one call, each lane as
/// the scalar path computes it (branches of generated code are lane-wise selects), bit for
/// bit; the one exception is `f64` on targets without AVX, where a lane's sine and cosine are
/// the branch-free polynomials of [`crate::sincos`] and the scalar's `libm`'s (both within one
/// ulp). Where the target has AVX, `f32` packs and scalar `f32` generated code take their
/// sines and cosines from [`sincos::sincosf_lanes`](crate::sincos::sincosf_lanes) four at a
/// time; elsewhere both call `libm::sincosf`. [`crate::batch`] runs slices of configurations
/// through them.
///
/// ```
/// use dhgen::Real;
/// let (s, c) = 0.5f64.sincos();
/// assert!((s - 0.5f64.sin()).abs() <= f64::EPSILON && (c - 0.5f64.cos()).abs() <= f64::EPSILON);
/// ```
pub trait Real: SimdRealField<Element: nalgebra::RealField> + Copy {
    /// `(sin x, cos x)`, lane by lane.
    #[inline]
    fn sincos(self) -> (Self, Self) {
        self.simd_sin_cos()
    }

    /// `(sin x_i, cos x_i)` for every entry of `x`: what a generated `State` computes for its
    /// revolute joints. Entry by entry with [`sincos`](Real::sincos) by default; `f64`, where
    /// the target has AVX ([`sincos::PACKED`](crate::sincos::PACKED)), evaluates them four at
    /// a time with [`sincos::sincos`](crate::sincos::sincos) on a pack, so that every entry is
    /// bit for bit what a pack's lane computes.
    ///
    /// ```
    /// use dhgen::Real;
    /// let (s, c) = f64::sincos_array([0.5, -2.0, 3.0, 1e-9, 7.0]);
    /// for (i, x) in [0.5f64, -2.0, 3.0, 1e-9, 7.0].into_iter().enumerate() {
    ///     assert!((s[i] - x.sin()).abs() <= f64::EPSILON && (c[i] - x.cos()).abs() <= f64::EPSILON);
    /// }
    /// ```
    #[inline]
    fn sincos_array<const N: usize>(x: [Self; N]) -> ([Self; N], [Self; N]) {
        sincos_each(x)
    }

    /// Which lanes are finite (neither infinite nor NaN).
    #[inline]
    fn is_finite_lanes(self) -> Self::SimdBool {
        // x − x is 0 for a finite x and NaN for ±∞ and NaN, which compares unequal.
        #[allow(clippy::eq_op)]
        let difference = self - self;
        difference.simd_eq(Self::zero())
    }

    /// `self · b + c`, what generated code writes for a product added to a value: one fused
    /// multiply-add (one rounding) where the target has FMA instructions
    /// ([`FUSED`](crate::sincos::FUSED), `-C target-cpu=x86-64-v3` or `native` on current x86),
    /// a multiplication and an addition otherwise, so that scalars and SIMD packs round alike
    /// on every target.
    ///
    /// ```
    /// use dhgen::Real;
    /// assert_eq!(Real::mul_add_fast(2.0f64, 3.0, 1.0), 7.0);
    /// ```
    #[inline(always)]
    fn mul_add_fast(self, b: Self, c: Self) -> Self {
        crate::sincos::mul_add::<Self, { crate::sincos::FUSED }>(self, b, c)
    }

    /// Lane-wise sign with `sign(0) = 0`: `1` where positive, `−1` where negative, `0`
    /// elsewhere (zero and NaN): Coulomb friction's `coulomb · sign(q̇)`.
    #[inline]
    fn sign(self) -> Self {
        let zero = Self::zero();
        let one = Self::one();
        one.select(self.simd_gt(zero), (-one).select(self.simd_lt(zero), zero))
    }
}

/// `(sin x_i, cos x_i)` entry by entry with [`Real::sincos`]: `sincos_array`'s default, and
/// `f64`'s where its sines and cosines are not packed.
#[inline(always)]
fn sincos_each<T: Real, const N: usize>(x: [T; N]) -> ([T; N], [T; N]) {
    let mut s = x;
    let mut c = x;
    for i in 0..N {
        (s[i], c[i]) = x[i].sincos();
    }
    (s, c)
}

/// `f` (a sine and cosine of four values at once) on every entry of `x`: full packs with
/// constant-length copies, then one pack padded with zeros. (One loop over padded packs,
/// tried, compiled differently for x86-64-v3: 16 % more instructions in one build's Panda
/// fk_matrix, and an encoding valgrind 3.19 cannot decode.)
#[inline(always)]
fn in_packs_of_four<E: Copy + Default, const N: usize>(
    x: [E; N],
    f: impl Fn([E; 4]) -> ([E; 4], [E; 4]),
) -> ([E; N], [E; N]) {
    let mut s = [E::default(); N];
    let mut c = [E::default(); N];
    let mut start = 0;
    while start + 4 <= N {
        let (ps, pc) = f([x[start], x[start + 1], x[start + 2], x[start + 3]]);
        s[start..start + 4].copy_from_slice(&ps);
        c[start..start + 4].copy_from_slice(&pc);
        start += 4;
    }
    if start < N {
        let at = |l: usize| start + l;
        let (ps, pc) = f(core::array::from_fn(|l| {
            if at(l) < N { x[at(l)] } else { E::default() }
        }));
        for l in 0..N - start {
            (s[at(l)], c[at(l)]) = (ps[l], pc[l]);
        }
    }
    (s, c)
}

impl Real for f64 {
    #[inline]
    fn sincos(self) -> (f64, f64) {
        libm::sincos(self)
    }

    #[inline]
    fn sincos_array<const N: usize>(x: [f64; N]) -> ([f64; N], [f64; N]) {
        if !crate::sincos::PACKED {
            return sincos_each(x);
        }
        in_packs_of_four(x, |lanes| {
            let (s, c) = crate::sincos::sincos(WideF64x4::from(lanes));
            (s.0.to_array(), c.0.to_array())
        })
    }

    #[inline]
    fn is_finite_lanes(self) -> bool {
        self.is_finite()
    }
}

impl Real for f32 {
    #[inline]
    fn sincos(self) -> (f32, f32) {
        libm::sincosf(self)
    }

    /// Where the target has AVX ([`sincos::PACKED`](crate::sincos::PACKED)), four at a time
    /// in packs of `f64` ([`sincos::sincosf_lanes`](crate::sincos::sincosf_lanes)), each
    /// entry bit for bit what a [`WideF32x8`]'s lane computes; `libm::sincosf` one by one
    /// elsewhere.
    #[inline]
    fn sincos_array<const N: usize>(x: [f32; N]) -> ([f32; N], [f32; N]) {
        if !crate::sincos::PACKED {
            return sincos_each(x);
        }
        in_packs_of_four(x, crate::sincos::sincosf_four)
    }

    #[inline]
    fn is_finite_lanes(self) -> bool {
        self.is_finite()
    }
}

/// Four `f64` lanes. The sine and cosine are this crate's branch-free ones on the whole pack
/// (within one ulp), the ones a generated `State` of scalar `f64` uses too where the target
/// has AVX ([`sincos::PACKED`](crate::sincos::PACKED)): there a lane's results are the scalar
/// path's bit for bit; elsewhere scalar `f64` keeps `libm`'s, faster one value at a time, and
/// a lane agrees with it to rounding (1e-13 relative in practice). Everything after the sine
/// and cosine is the same arithmetic.
impl Real for WideF64x4 {
    #[inline]
    fn sincos(self) -> (Self, Self) {
        crate::sincos::sincos(self)
    }
}

/// Eight `f32` lanes, each as scalar `f32` generated code computes it, bit for bit: the sine
/// and cosine are [`sincos::sincosf_pack`](crate::sincos::sincosf_pack)'s (branch-free on
/// packs of `f64` where the target has AVX, `libm::sincosf` lane by lane elsewhere).
impl Real for WideF32x8 {
    #[inline]
    fn sincos(self) -> (Self, Self) {
        crate::sincos::sincosf_pack(self)
    }
}

/// A dual number with one derivative lane (feature `num-dual`): any generated function
/// evaluated at `q + ε v` returns its value and its directional derivative along `v`.
///
/// ```
/// # #[cfg(feature = "num-dual")] {
/// use num_dual::Dual64;
/// dhgen::robot!(mod puma = "../robots/puma560.toml");
/// let q = [0.1, -0.6, 0.4, 0.3, 0.8, -0.2];
/// // ∂g/∂q₂: seed joint 2.
/// let x: [Dual64; 6] = std::array::from_fn(|i| {
///     let d = Dual64::from(q[i]);
///     if i == 1 { d.derivative() } else { d }
/// });
/// let g = puma::gravity(&x);
/// let h = 1e-6;
/// let (mut a, mut b) = (q, q);
/// a[1] += h;
/// b[1] -= h;
/// let fd = (puma::gravity(&a) - puma::gravity(&b)) / (2.0 * h);
/// assert!((0..6).all(|k| (g[k].eps - fd[k]).abs() < 1e-6));
/// # }
/// ```
#[cfg(feature = "num-dual")]
impl Real for num_dual::Dual64 {}

/// A dual number with `N` derivative lanes (feature `num-dual`): a whole Jacobian of a
/// generated function in one evaluation.
#[cfg(feature = "num-dual")]
impl<const N: usize> Real for num_dual::DualSVec64<N> {}

/// The rule for "the inertia matrix is singular", the same on the generated and the runtime
/// path: forward dynamics factors `D(q)` by Cholesky and returns `None` when a pivot (the
/// square of a diagonal entry of the factor `L` in `L Lᵀ`, the same as an entry of `Δ` in the
/// square-root-free `L Δ Lᵀ` generated code uses) is at or below
/// `8 · n · ε · max_i D_ii`, with `ε` the scalar's machine epsilon.
///
/// Rounding errors of the factorisation are of the order of `n · ε · max_i D_ii`, so a pivot
/// below the floor carries no information: the matrix is singular to working precision (a
/// link without inertia about its own joint axis, for example), and the accelerations a
/// solve would return are rounding noise. In `f64` the floor rejects matrices whose
/// condition number exceeds about `10¹³/n`; in `f32` about `10⁵/n`.
///
/// ```
/// // A 2-joint arm whose second joint moves no inertia: D = [[2, 0], [0, 1e-18]].
/// let floor = dhgen::cholesky_pivot_floor(2, 2.0_f64);
/// assert!(1e-18 <= floor && 1e-12 > floor);
/// ```
pub fn cholesky_pivot_floor<T: SimdRealField>(n: usize, max_diagonal: T) -> T {
    nalgebra::convert::<f64, T>(8.0 * n as f64) * T::simd_default_epsilon() * max_diagonal
}

/// The Cholesky factor of an inertia matrix under the rule of [`cholesky_pivot_floor`]:
/// `None` when the factorisation fails or a pivot is at or below the floor (singular to
/// working precision). The check behind `forward_dynamics`' and `mass_matrix_inverse`'s `None`
/// on the runtime path; generated modules apply the same floor pivot by pivot in their
/// unrolled, branch-free factorisation.
///
/// ```
/// use dhgen::nalgebra::Matrix2;
/// assert!(dhgen::inertia_cholesky(Matrix2::new(2.0, 0.0, 0.0, 1.0)).is_some());
/// assert!(dhgen::inertia_cholesky(Matrix2::new(2.0, 0.0, 0.0, 1e-18)).is_none());
/// ```
pub fn inertia_cholesky<T: nalgebra::RealField + Copy, D: nalgebra::Dim>(
    d: nalgebra::OMatrix<T, D, D>,
) -> Option<nalgebra::Cholesky<T, D>>
where
    nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<D, D>,
{
    let n = d.nrows();
    if n == 0 {
        return d.cholesky();
    }
    let max_diagonal = (1..n).fold(d[(0, 0)], |m, i| m.max(d[(i, i)]));
    let floor = cholesky_pivot_floor(n, max_diagonal);
    let factor = d.cholesky()?;
    let l = factor.l_dirty();
    (0..n)
        .all(|i| l[(i, i)] * l[(i, i)] > floor)
        .then_some(factor)
}
