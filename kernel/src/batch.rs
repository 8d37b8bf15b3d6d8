//! Many configurations per call: generated functions evaluated on SIMD packs.
//!
//! Every generated function is generic over [`Real`], which the packs [`WideF64x4`] (four
//! `f64`) and [`WideF32x8`] (eight `f32`) implement: called on a pack, a function evaluates
//! four (eight) configurations at once, lane by lane as the scalar path does (branch-free
//! selects where scalar code would branch: Coulomb friction's sign, the Cholesky pivot check).
//! `f32` lanes are bit for bit the scalar results; so are `f64` lanes where the target has AVX
//! (scalar code then takes its sines and cosines from packs as well,
//! [`sincos::PACKED`](crate::sincos::PACKED)); elsewhere they agree to rounding, because the
//! pack's sine and cosine are branch-free polynomials (within one ulp) where scalar `f64` keeps
//! `libm`'s, faster one value at a time. Each generated module's `batch`
//! submodule wraps this for slices: `batch::mass_matrix(&qs, &mut out)` packs the
//! configurations, evaluates, and writes one output per configuration; [`run`] is the loop
//! they share. A payload (`batch::*_with_payload`) is one for the whole slice, [`splat`] over
//! the lanes.
//!
//! The width a pack's arithmetic really gets is the compiler's choice of target: the default
//! `x86_64` target has SSE2 (two `f64` per instruction); `-C target-cpu=native` (or
//! `x86-64-v3`) on a CPU with AVX2 gives four.
//!
//! ```
//! dhgen::robot!(mod puma = "../robots/puma560.toml");
//! let qs: Vec<[f64; 6]> = (0..10).map(|i| [0.1 * i as f64; 6]).collect();
//! let mut d = vec![Default::default(); qs.len()];
//! puma::batch::mass_matrix(&qs, &mut d).unwrap();
//! assert_eq!(d[7], puma::mass_matrix(&qs[7]));
//! ```

use crate::Real;
use nalgebra::{ArrayStorage, Isometry3, Matrix, Point3, Quaternion, Scalar, SimdBool, SimdValue};
use nalgebra::{Translation3, UnitQuaternion};
pub use simba::simd::{WideBoolF32x8, WideBoolF64x4, WideF32x8, WideF64x4};

/// A real scalar with a SIMD pack of it: `f64` (four lanes) and `f32` (eight).
pub trait Lanes: Real + nalgebra::RealField {
    /// The pack: `SimdValue::LANES` values of `Self` at once (as wide an instruction as the
    /// target allows).
    type Pack: Real + SimdValue<Element = Self> + Leaf<Lane = Self>;
    /// The pack whose lane `l` is `lane(l)`.
    fn pack(lane: impl FnMut(usize) -> Self) -> Self::Pack;
}

impl Lanes for f64 {
    type Pack = WideF64x4;
    #[inline]
    fn pack(lane: impl FnMut(usize) -> f64) -> WideF64x4 {
        WideF64x4::from(core::array::from_fn::<f64, 4, _>(lane))
    }
}

impl Lanes for f32 {
    type Pack = WideF32x8;
    #[inline]
    fn pack(lane: impl FnMut(usize) -> f32) -> WideF32x8 {
        WideF32x8::from(core::array::from_fn::<f32, 8, _>(lane))
    }
}

/// `values` in every lane: the packs of an input that is the same for every configuration of a
/// batch (a payload's ten parameters in the generated `batch::*_with_payload`).
///
/// ```
/// use dhgen::batch::splat;
/// let packs = splat(&[1.5_f64, -2.0]);
/// assert_eq!(packs[1].0.to_array(), [-2.0; 4]);
/// ```
#[inline]
pub fn splat<T: Lanes, const N: usize>(values: &[T; N]) -> [T::Pack; N] {
    values.map(|v| T::pack(|_| v))
}

/// A value computed on packs, read back one lane at a time.
pub trait Unpack {
    /// The value of one lane.
    type Lane;
    /// Lane `i` (`i <` the number of lanes).
    fn lane(&self, i: usize) -> Self::Lane;
    /// Lane `i` written over `out` (in place, entry by entry, for large values).
    #[inline]
    fn lane_into(&self, i: usize, out: &mut Self::Lane) {
        *out = self.lane(i);
    }
    /// The first `out.len()` lanes written over `out`, lane `l` to `out[l]`.
    #[inline]
    fn unpack_into(&self, out: &mut [Self::Lane]) {
        self.unpack_at(out, |o: &mut Self::Lane| o);
    }
    /// The first `out.len()` lanes written over the parts `at(&mut out[l])` of `out`: how a
    /// value inside a larger one (an entry of an array) is unpacked pack by pack, each pack
    /// read once and its lanes spread over the outputs, where lane-by-lane unpacking would
    /// read every pack once per lane.
    #[inline]
    fn unpack_at<L>(&self, out: &mut [L], at: impl Fn(&mut L) -> &mut Self::Lane) {
        for (l, o) in out.iter_mut().enumerate() {
            self.lane_into(l, at(o));
        }
    }
    /// A run of values (an array's or a matrix's entries, in memory order) unpacked at once:
    /// entry `k`'s first `out.len()` lanes written over `at(&mut out[l])[k]`. Entry by entry
    /// unless overridden: packs of `f64` and `f32` transpose blocks of entries in registers,
    /// so each configuration's entries are written as whole rows.
    #[inline]
    fn unpack_run_at<L>(items: &[Self], out: &mut [L], at: impl Fn(&mut L) -> &mut [Self::Lane])
    where
        Self: Sized,
    {
        for (k, x) in items.iter().enumerate() {
            x.unpack_at(out, |o: &mut L| &mut at(o)[k]);
        }
    }
}

/// Whether arrays and matrices of packs are unpacked as runs ([`Unpack::unpack_run_at`]):
/// only where the target has 256-bit vectors (AVX). Without them `wide` transposes lane by
/// lane and the runs' slices cost bounds checks, so entry by entry (each entry's place a
/// constant) executes fewer instructions (PUMA 560 Christoffel symbols through `batch` on the
/// default target: 2,848 per configuration entry by entry, 3,082 in runs). With AVX2 the runs
/// take 10–15 % less time on the Christoffel symbols (PUMA 560 and Panda) and are even on D
/// and J.
const UNPACK_RUNS: bool = cfg!(target_feature = "avx");

/// [`Unpack::unpack_run_at`] for packs of `W` lanes: blocks of `W` entries transposed by
/// `transpose` (row `l` = lane `l` of the block's entries) and written as rows when every
/// lane is wanted, the rest entry by entry.
#[inline(always)]
fn unpack_run_transposed<P, L, const W: usize>(
    items: &[P],
    out: &mut [L],
    at: impl Fn(&mut L) -> &mut [P::Lane],
    transpose: impl Fn(&[P]) -> [[P::Lane; W]; W],
) where
    P: Unpack,
    P::Lane: Copy,
{
    let whole = if out.len() == W {
        items.len() - items.len() % W
    } else {
        0
    };
    for (b, block) in items[..whole].chunks_exact(W).enumerate() {
        for (o, row) in out.iter_mut().zip(&transpose(block)) {
            at(o)[b * W..(b + 1) * W].copy_from_slice(row);
        }
    }
    for (k, x) in items.iter().enumerate().skip(whole) {
        x.unpack_at(out, |o: &mut L| &mut at(o)[k]);
    }
}

/// A pack itself: its lanes as an array.
pub trait Leaf: Unpack + Copy {
    /// Every lane.
    fn lanes(&self) -> &[Self::Lane];
}

impl Leaf for WideF64x4 {
    #[inline]
    fn lanes(&self) -> &[f64] {
        self.0.as_array()
    }
}

impl Leaf for WideF32x8 {
    #[inline]
    fn lanes(&self) -> &[f32] {
        self.0.as_array()
    }
}

impl Unpack for WideF64x4 {
    type Lane = f64;
    #[inline]
    fn lane(&self, i: usize) -> f64 {
        self.lanes()[i]
    }
    #[inline]
    fn unpack_at<L>(&self, out: &mut [L], at: impl Fn(&mut L) -> &mut f64) {
        for (o, &v) in out.iter_mut().zip(self.lanes()) {
            *at(o) = v;
        }
    }
    #[inline]
    fn unpack_run_at<L>(items: &[Self], out: &mut [L], at: impl Fn(&mut L) -> &mut [f64]) {
        unpack_run_transposed::<_, _, 4>(items, out, at, |b| {
            wide::f64x4::transpose([b[0].0, b[1].0, b[2].0, b[3].0]).map(|r| r.to_array())
        });
    }
}

impl Unpack for WideF32x8 {
    type Lane = f32;
    #[inline]
    fn lane(&self, i: usize) -> f32 {
        self.lanes()[i]
    }
    #[inline]
    fn unpack_at<L>(&self, out: &mut [L], at: impl Fn(&mut L) -> &mut f32) {
        for (o, &v) in out.iter_mut().zip(self.lanes()) {
            *at(o) = v;
        }
    }
    #[inline]
    fn unpack_run_at<L>(items: &[Self], out: &mut [L], at: impl Fn(&mut L) -> &mut [f32]) {
        unpack_run_transposed::<_, _, 8>(items, out, at, |b| {
            wide::f32x8::transpose(core::array::from_fn(|k| b[k].0)).map(|r| r.to_array())
        });
    }
}

impl<P, const R: usize, const C: usize> Unpack
    for Matrix<P, nalgebra::Const<R>, nalgebra::Const<C>, ArrayStorage<P, R, C>>
where
    P: Scalar + Leaf,
    P::Lane: Scalar + Copy,
{
    type Lane = nalgebra::SMatrix<P::Lane, R, C>;
    #[inline]
    fn lane(&self, i: usize) -> Self::Lane {
        self.map(|x| x.lane(i))
    }
    #[inline]
    fn lane_into(&self, i: usize, out: &mut Self::Lane) {
        for (o, x) in out.as_mut_slice().iter_mut().zip(self.as_slice()) {
            x.lane_into(i, o);
        }
    }
    /// The entries as one run ([`Unpack::unpack_run_at`]) or entry by entry (see
    /// `UNPACK_RUNS`), each pack read once.
    #[inline]
    fn unpack_at<L>(&self, out: &mut [L], at: impl Fn(&mut L) -> &mut Self::Lane) {
        if UNPACK_RUNS {
            P::unpack_run_at(self.as_slice(), out, |o: &mut L| at(o).as_mut_slice());
        } else {
            for (k, x) in self.as_slice().iter().enumerate() {
                x.unpack_at(out, |o: &mut L| &mut at(o).as_mut_slice()[k]);
            }
        }
    }
}

impl<X: Unpack, const N: usize> Unpack for [X; N] {
    type Lane = [X::Lane; N];
    #[inline]
    fn lane(&self, i: usize) -> Self::Lane {
        core::array::from_fn(|k| self[k].lane(i))
    }
    #[inline]
    fn lane_into(&self, i: usize, out: &mut Self::Lane) {
        for (o, x) in out.iter_mut().zip(self) {
            x.lane_into(i, o);
        }
    }
    /// As for matrices.
    #[inline]
    fn unpack_at<L>(&self, out: &mut [L], at: impl Fn(&mut L) -> &mut Self::Lane) {
        if UNPACK_RUNS {
            X::unpack_run_at(self, out, |o: &mut L| &mut at(o)[..]);
        } else {
            for (k, x) in self.iter().enumerate() {
                x.unpack_at(out, |o: &mut L| &mut at(o)[k]);
            }
        }
    }
}

impl<A: Unpack, B: Unpack> Unpack for (A, B)
where
    // The lanes are plain values (numbers, matrices); the bound lets a closure project a
    // pair's half for every lifetime.
    A::Lane: 'static,
    B::Lane: 'static,
{
    type Lane = (A::Lane, B::Lane);
    #[inline]
    fn lane(&self, i: usize) -> Self::Lane {
        (self.0.lane(i), self.1.lane(i))
    }
    #[inline]
    fn lane_into(&self, i: usize, out: &mut Self::Lane) {
        self.0.lane_into(i, &mut out.0);
        self.1.lane_into(i, &mut out.1);
    }
    #[inline]
    fn unpack_at<L>(&self, out: &mut [L], at: impl Fn(&mut L) -> &mut Self::Lane) {
        self.0.unpack_at(out, |o: &mut L| &mut at(o).0);
        self.1.unpack_at(out, |o: &mut L| &mut at(o).1);
    }
}

impl<A: Unpack, B: Unpack, C: Unpack> Unpack for (A, B, C)
where
    A::Lane: 'static,
    B::Lane: 'static,
    C::Lane: 'static,
{
    type Lane = (A::Lane, B::Lane, C::Lane);
    #[inline]
    fn lane(&self, i: usize) -> Self::Lane {
        (self.0.lane(i), self.1.lane(i), self.2.lane(i))
    }
    #[inline]
    fn lane_into(&self, i: usize, out: &mut Self::Lane) {
        self.0.lane_into(i, &mut out.0);
        self.1.lane_into(i, &mut out.1);
        self.2.lane_into(i, &mut out.2);
    }
    #[inline]
    fn unpack_at<L>(&self, out: &mut [L], at: impl Fn(&mut L) -> &mut Self::Lane) {
        self.0.unpack_at(out, |o: &mut L| &mut at(o).0);
        self.1.unpack_at(out, |o: &mut L| &mut at(o).1);
        self.2.unpack_at(out, |o: &mut L| &mut at(o).2);
    }
}

impl<P> Unpack for Point3<P>
where
    P: Scalar + Leaf,
    P::Lane: Scalar + Copy,
{
    type Lane = Point3<P::Lane>;
    #[inline]
    fn lane(&self, i: usize) -> Self::Lane {
        Point3::from(self.coords.lane(i))
    }
}

impl<P> Unpack for Isometry3<P>
where
    P: Real + Leaf,
    P::Lane: nalgebra::RealField + Copy,
{
    type Lane = Isometry3<P::Lane>;
    #[inline]
    fn lane(&self, i: usize) -> Self::Lane {
        let t = self.translation.vector.lane(i);
        let q = self.rotation.quaternion().coords.lane(i);
        Isometry3::from_parts(
            Translation3::from(t),
            UnitQuaternion::new_unchecked(Quaternion::from(q)),
        )
    }
}

/// A value with the mask of the lanes where it is an answer (generated
/// `forward_dynamics_lanes`), read back as `Some` or `None` per lane.
#[derive(Clone, Copy, Debug)]
pub struct Masked<V, B>(pub V, pub B);

impl<V, B: SimdBool> Masked<V, B> {
    /// Whether lane `i` holds an answer.
    #[inline]
    fn holds(&self, i: usize) -> bool {
        (self.1.bitmask() >> i) & 1 == 1
    }
}

impl<V: Unpack, B: SimdBool> Unpack for Masked<V, B> {
    type Lane = Option<V::Lane>;
    #[inline]
    fn lane(&self, i: usize) -> Self::Lane {
        self.holds(i).then(|| self.0.lane(i))
    }
    #[inline]
    fn lane_into(&self, i: usize, out: &mut Self::Lane) {
        match out {
            Some(o) if self.holds(i) => self.0.lane_into(i, o),
            _ => *out = self.lane(i),
        }
    }
}

/// The inputs and the outputs of a batch call differ in length.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "batch: {inputs} configurations but {outputs} outputs (every slice must have one per configuration)"
)]
pub struct LengthMismatch {
    /// The length of the first input slice that differs from the outputs' (or of `q`).
    pub inputs: usize,
    /// The length of the output slice.
    pub outputs: usize,
}

/// Evaluates `f` on packs of as many configurations as `T::Pack` has lanes and writes each lane's value to its
/// place in `out`: configuration `c` is `inputs[k][c]` for each input `k` (`q`, `q̇`, ...),
/// its value `out[c]`. A last, partial pack repeats the last configuration in its spare lanes
/// (and writes only the real ones).
///
/// # Errors
/// [`LengthMismatch`] (and nothing written) unless every input slice is as long as `out`.
pub fn run<T, const N: usize, const K: usize, O>(
    inputs: [&[[T; N]]; K],
    out: &mut [O::Lane],
    f: impl Fn(&[[T::Pack; N]; K]) -> O,
) -> Result<(), LengthMismatch>
where
    T: Lanes,
    O: Unpack,
{
    if let Some(bad) = inputs.iter().find(|x| x.len() != out.len()) {
        return Err(LengthMismatch {
            inputs: bad.len(),
            outputs: out.len(),
        });
    }
    let lanes = <T::Pack as SimdValue>::LANES;
    // One buffer of packs, refilled in place for each group of configurations and lent to
    // `f`: building a fresh array per group and moving it into the call copied every pack
    // several times over (Panda τ through `batch`: 1,495 → 1,338 instructions per
    // configuration on the default target, 645 → 578 with AVX2).
    let mut packed: [[T::Pack; N]; K] = [[T::pack(|_| T::zero()); N]; K];
    let fill = |packed: &mut [[T::Pack; N]; K], start: usize, count: usize| {
        for (packs, input) in packed.iter_mut().zip(&inputs) {
            let rows = &input[start..start + count];
            for (j, pack) in packs.iter_mut().enumerate() {
                // A partial group's spare lanes repeat its last configuration.
                *pack = T::pack(|l| rows[l.min(count - 1)][j]);
            }
        }
    };
    // Full groups: every slice length a compile-time constant, so packing and unpacking
    // compile to plain loads and stores.
    let full = out.len() - out.len() % lanes;
    let (head, tail) = out.split_at_mut(full);
    for (start, chunk) in (0..full).step_by(lanes).zip(head.chunks_exact_mut(lanes)) {
        fill(&mut packed, start, lanes);
        f(&packed).unpack_into(chunk);
    }
    if !tail.is_empty() {
        fill(&mut packed, full, tail.len());
        f(&packed).unpack_into(tail);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{Unpack, WideF32x8, WideF64x4};

    /// A run unpacked at once equals its entries unpacked lane by lane, for every run length
    /// around the block sizes and every number of wanted lanes (a partial group wants fewer).
    #[test]
    fn runs_unpack_as_entries_do() {
        fn check<P: Unpack + Copy>(lanes: usize, pack: impl Fn(usize) -> P)
        where
            P::Lane: Copy + PartialEq + core::fmt::Debug + Default,
        {
            for len in 0..=2 * lanes + 3 {
                let items: [P; 20] = core::array::from_fn(&pack);
                let items = &items[..len];
                for wanted in 1..=lanes {
                    let mut out = [[P::Lane::default(); 20]; 8];
                    P::unpack_run_at(items, &mut out[..wanted], |o: &mut [P::Lane; 20]| {
                        &mut o[..len]
                    });
                    for (l, row) in out.iter().enumerate().take(wanted) {
                        for (k, x) in items.iter().enumerate() {
                            assert_eq!(row[k], x.lane(l), "entry {k} lane {l} of {len}");
                        }
                    }
                }
            }
        }
        check(4, |k| {
            WideF64x4(core::array::from_fn::<f64, 4, _>(|l| (10 * k + l) as f64).into())
        });
        check(8, |k| {
            WideF32x8(core::array::from_fn::<f32, 8, _>(|l| (10 * k + l) as f32).into())
        });
    }
}
