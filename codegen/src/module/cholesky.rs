//! The Cholesky factorisation of D(q) in its square-root-free form `L Δ Lᵀ`, without
//! branches, and what is built on it: forward dynamics' solve `D x = rhs` and the inverse
//! `D⁻¹`.
//!
//! Up to [`LOOPED_ABOVE`] joints the factorisation is unrolled into straight-line code;
//! above, it is emitted as loops over arrays (the same operations in the same order, so the
//! same values bit for bit): its unrolled code grows as n³ and at 20 joints is already
//! several times the size of the rest of forward dynamics, while a general arm's D has no
//! zero entries for the unrolled form to exploit.
//!
//! Both values come with `ok`: lane by lane, whether every pivot is above
//! `dhgen::cholesky_pivot_floor` (the rule both paths share) and the result is finite. The
//! code has no branch, so a SIMD pack's lanes each get the scalar path's answer, whatever the
//! others'.

use super::LOOPED_ABOVE;
use super::shape::Shape;
use crate::graph::OpCount;
use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

fn l(i: usize, j: usize) -> Ident {
    format_ident!("l{}_{}", i, j)
}

fn u(i: usize, j: usize) -> Ident {
    format_ident!("u{}_{}", i, j)
}

fn inv(i: usize) -> Ident {
    format_ident!("inv{}", i)
}

/// The factors of `dm` as loops: `l: [[T; DOF]; DOF]` (the unit lower triangle below the
/// diagonal), `u` (the same entries before their scaling, `u[i][j] = l[i][j] · d_j`),
/// `inv: [T; DOF]` the pivots' reciprocals `1 / d_j`, and `ok` over the pivots; the same
/// operations, in the same order, as [`factor`].
fn factor_looped() -> TokenStream {
    quote! {
        let mut largest: T = dm[(0, 0)];
        for j in 1..DOF {
            largest = na::SimdPartialOrd::simd_max(largest, dm[(j, j)]);
        }
        let floor: T = ::dhgen::__private::cholesky_pivot_floor(DOF, largest);
        let mut l: [[T; DOF]; DOF] = [[T::zero(); DOF]; DOF];
        let mut u: [[T; DOF]; DOF] = [[T::zero(); DOF]; DOF];
        let mut inv: [T; DOF] = [T::zero(); DOF];
        let mut ok = na::SimdPartialOrd::simd_gt(dm[(0, 0)], floor);
        for j in 0..DOF {
            let mut pivot: T = dm[(j, j)];
            for k in 0..j {
                pivot = pivot - u[j][k] * l[j][k];
            }
            ok = ok & na::SimdPartialOrd::simd_gt(pivot, floor);
            inv[j] = T::one() / pivot;
            for i in j + 1..DOF {
                let mut e: T = dm[(i, j)];
                for k in 0..j {
                    e = e - u[i][k] * l[j][k];
                }
                u[i][j] = e;
                l[i][j] = e * inv[j];
            }
        }
    }
}

/// The operations of the factorisation, unrolled or looped (the floor's two products
/// included).
fn factor_ops(n: usize) -> OpCount {
    // Per pivot j: j products subtracted, one reciprocal; per entry below it, j products
    // subtracted and one scaling.
    let mut ops = OpCount {
        add: n - 1,
        mul: 2,
        ..OpCount::default()
    };
    for j in 0..n {
        ops.mul += j + (n - 1 - j) * (j + 1);
        ops.add += j + (n - 1 - j) * j;
        ops.div += 1;
    }
    ops
}

/// `dm = L Δ Lᵀ` unrolled, `L` unit lower triangular (`l{i}_{j}` below the diagonal, with
/// `u{i}_{j} = l{i}_{j} · d_j` the entry before its scaling) and `Δ` the pivots `d_j` (as
/// their reciprocals `inv{j}`), and `ok` over the pivots.
///
/// The square-root-free form of Cholesky's `L Lᵀ` (`d_j` is the square of its `j`-th
/// diagonal entry: the same pivots, checked against the same floor) with the same number of
/// products. Each pivot waits for the one before through a product, a subtraction and a
/// division, where `L Lᵀ` also waited for a square root: generated q̈ (x86-64-v3) PUMA 560
/// 111 → 79 ns, Panda 184 → 156, Stanford arm 109 → 71, UR5 106 → 73.
fn factor(n: usize) -> Vec<TokenStream> {
    let mut s = Vec::new();
    let mut largest = quote!(dm[(0, 0)]);
    for j in 1..n {
        largest = quote!(na::SimdPartialOrd::simd_max(#largest, dm[(#j, #j)]));
    }
    s.push(quote! {
        let floor: T = ::dhgen::__private::cholesky_pivot_floor(DOF, #largest);
    });
    for j in 0..n {
        let mut pivot = quote!(dm[(#j, #j)]);
        for k in 0..j {
            let (ujk, ljk) = (u(j, k), l(j, k));
            pivot = quote!(#pivot - #ujk * #ljk);
        }
        let invj = inv(j);
        let ok = if j == 0 {
            quote!(let ok = na::SimdPartialOrd::simd_gt(pivot, floor);)
        } else {
            quote!(let ok = ok & na::SimdPartialOrd::simd_gt(pivot, floor);)
        };
        s.push(quote! {
            let pivot: T = #pivot;
            #ok
            let #invj: T = T::one() / pivot;
        });
        for i in j + 1..n {
            let mut e = quote!(dm[(#i, #j)]);
            for k in 0..j {
                let (uik, ljk) = (u(i, k), l(j, k));
                e = quote!(#e - #uik * #ljk);
            }
            let (uij, lij) = (u(i, j), l(i, j));
            s.push(quote!(let #uij: T = #e; let #lij: T = #uij * #invj;));
        }
    }
    s
}

/// `D x = rhs` (`dm`, `rhs` in scope) as `(x, ok)`, with its operation count (the
/// `n` subtractions forming `rhs = τ − bias` included): `L y = rhs` forward, then
/// `Lᵀ x = Δ⁻¹ y` back.
pub fn solve(n: usize) -> (TokenStream, OpCount) {
    let mut ops = factor_ops(n);
    ops.add += n;
    // Forward and back substitution: a row's products (i forward, n − 1 − i back) and one
    // scaling each.
    ops.mul += n * n;
    ops.add += n * (n - 1);
    if n > LOOPED_ABOVE {
        let factor = factor_looped();
        let solve = quote! {
            #factor
            let mut y: [T; DOF] = [T::zero(); DOF];
            for i in 0..DOF {
                let mut e: T = rhs[i];
                for k in 0..i {
                    e = e - l[i][k] * y[k];
                }
                y[i] = e;
            }
            let mut x: [T; DOF] = [T::zero(); DOF];
            for i in (0..DOF).rev() {
                let mut e: T = y[i] * inv[i];
                for k in i + 1..DOF {
                    e = e - l[k][i] * x[k];
                }
                x[i] = e;
            }
            for xi in x {
                ok = ok & ::dhgen::__private::Real::is_finite_lanes(xi);
            }
            (na::SVector::<T, DOF>::from(x), ok)
        };
        return (solve, ops);
    }
    let mut s = factor(n);
    let y = |i: usize| format_ident!("y{}", i);
    let x = |i: usize| format_ident!("x{}", i);
    for i in 0..n {
        let mut e = quote!(rhs[#i]);
        for k in 0..i {
            let (lik, yk) = (l(i, k), y(k));
            e = quote!(#e - #lik * #yk);
        }
        let yi = y(i);
        s.push(quote!(let #yi: T = #e;));
    }
    for i in (0..n).rev() {
        let (yi, invi) = (y(i), inv(i));
        let mut e = quote!(#yi * #invi);
        for k in i + 1..n {
            let (lki, xk) = (l(k, i), x(k));
            e = quote!(#e - #lki * #xk);
        }
        let xi = x(i);
        s.push(quote!(let #xi: T = #e;));
    }
    let xs: Vec<_> = (0..n).map(x).collect();
    // Only a finite acceleration is an answer (non-finite inputs give `None`, as on the
    // runtime path).
    let solve = quote! {
        #(#s)*
        let ok = ok #(& ::dhgen::__private::Real::is_finite_lanes(#xs))*;
        (na::SVector::<T, DOF>::from([#(#xs),*]), ok)
    };
    (solve, ops)
}

/// What the inverse's `ok` flag checks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Check {
    /// Every pivot above the floor.
    Pivots,
    /// Every pivot above the floor and every entry finite.
    PivotsAndFinite,
}

/// `D⁻¹` (`dm` in scope) as `(inverse, ok)`, with its operation count: `M = L⁻¹` (unit
/// lower triangular), `W = Δ⁻¹ M` below the diagonal, then `D⁻¹ = Mᵀ Δ⁻¹ M = Mᵀ W` on and
/// above the diagonal, mirrored below. `ok`: every pivot above the floor and, with
/// [`Check::PivotsAndFinite`], every entry finite (a caller that multiplies D⁻¹ by a finite
/// vector and checks the product learns the same: a non-finite entry makes its row's product
/// non-finite).
pub fn inverse(n: usize, check: Check) -> (TokenStream, OpCount) {
    let finite = check == Check::PivotsAndFinite;
    let mut ops = factor_ops(n);
    let m = |i: usize, j: usize| format_ident!("m{}_{}", i, j);
    let w = |i: usize, j: usize| format_ident!("w{}_{}", i, j);
    // Row i of M below the diagonal, m_ij = −(l_ij + Σ_{k=j+1}^{i−1} l_ik m_kj): i − j − 1
    // products and sums; w_ij = inv_i m_ij: one product; (D⁻¹)_ab = m_ba inv_b +
    // Σ_{k > b} m_ka w_kb for a < b (n − b products, n − b − 1 sums), inv_a + Σ_{k > a}
    // m_ka w_ka for a = b (one product fewer).
    for i in 0..n {
        for j in 0..i {
            ops.mul += i - j;
            ops.add += i - j - 1;
        }
    }
    for b in 0..n {
        ops.mul += (b + 1) * (n - b) - 1;
        ops.add += (b + 1) * (n - b - 1);
    }
    if n > LOOPED_ABOVE {
        let factor = factor_looped();
        let check = if finite {
            quote!(ok = ok & ::dhgen::__private::Real::is_finite_lanes(e);)
        } else {
            quote!()
        };
        let zeros = Shape::Square.init();
        let inverse = quote! {
            #factor
            // m = L⁻¹ below its unit diagonal, w = Δ⁻¹ m.
            let mut m: [[T; DOF]; DOF] = [[T::zero(); DOF]; DOF];
            let mut w: [[T; DOF]; DOF] = [[T::zero(); DOF]; DOF];
            for i in 0..DOF {
                for j in 0..i {
                    let mut e: T = l[i][j];
                    for k in j + 1..i {
                        e = e + l[i][k] * m[k][j];
                    }
                    m[i][j] = -e;
                    w[i][j] = inv[i] * m[i][j];
                }
            }
            let mut out: na::SMatrix<T, DOF, DOF> = #zeros;
            for a in 0..DOF {
                for b in a..DOF {
                    let mut e: T = if a == b { inv[b] } else { m[b][a] * inv[b] };
                    for k in b + 1..DOF {
                        e = e + m[k][a] * w[k][b];
                    }
                    #check
                    out[(a, b)] = e;
                    out[(b, a)] = e;
                }
            }
            (out, ok)
        };
        return (inverse, ops);
    }
    let mut s = factor(n);
    for i in 0..n {
        for j in 0..i {
            let mut e = {
                let lij = l(i, j);
                quote!(#lij)
            };
            for k in j + 1..i {
                let (lik, mkj) = (l(i, k), m(k, j));
                e = quote!(#e + #lik * #mkj);
            }
            let (mij, wij, invi) = (m(i, j), w(i, j), inv(i));
            s.push(quote!(let #mij: T = -(#e); let #wij: T = #invi * #mij;));
        }
    }
    let mut entries = Vec::new();
    for a in 0..n {
        for b in a..n {
            let invb = inv(b);
            let mut e = if a == b {
                quote!(#invb)
            } else {
                let mba = m(b, a);
                quote!(#mba * #invb)
            };
            for k in b + 1..n {
                let (mka, wkb) = (m(k, a), w(k, b));
                e = quote!(#e + #mka * #wkb);
            }
            let name = format_ident!("d{}_{}", a, b);
            s.push(quote!(let #name: T = #e;));
            entries.push((a, b, name));
        }
    }
    let stores = entries.iter().map(|(a, b, name)| {
        if a == b {
            quote!(out[(#a, #b)] = #name;)
        } else {
            quote!(out[(#a, #b)] = #name; out[(#b, #a)] = #name;)
        }
    });
    let names = entries.iter().filter(|_| finite).map(|(_, _, name)| name);
    let zeros = Shape::Square.init();
    let inverse = quote! {
        #(#s)*
        let ok = ok #(& ::dhgen::__private::Real::is_finite_lanes(#names))*;
        let mut out: na::SMatrix<T, DOF, DOF> = #zeros;
        #(#stores)*
        (out, ok)
    };
    (inverse, ops)
}
