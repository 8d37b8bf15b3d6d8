//! The Cholesky factorisation of D(q), without branches, and what is built on it:
//! forward dynamics' solve `D x = rhs` and the inverse `D⁻¹`.
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

fn inv(i: usize) -> Ident {
    format_ident!("inv{}", i)
}

/// The factor `L` of `dm` as loops: `l: [[T; DOF]; DOF]` (lower triangle), `inv: [T; DOF]`
/// the pivots' reciprocals, and `ok` over the pivots; the same operations, in the same order,
/// as [`factor`].
fn factor_looped() -> TokenStream {
    quote! {
        let mut largest: T = dm[(0, 0)];
        for j in 1..DOF {
            largest = na::SimdPartialOrd::simd_max(largest, dm[(j, j)]);
        }
        let floor: T = ::dhgen::cholesky_pivot_floor(DOF, largest);
        let mut l: [[T; DOF]; DOF] = [[T::zero(); DOF]; DOF];
        let mut inv: [T; DOF] = [T::zero(); DOF];
        let mut ok = na::SimdPartialOrd::simd_gt(dm[(0, 0)], floor);
        for j in 0..DOF {
            let mut diag: T = dm[(j, j)];
            for k in 0..j {
                diag = diag - l[j][k] * l[j][k];
            }
            ok = ok & na::SimdPartialOrd::simd_gt(diag, floor);
            let ljj: T = na::SimdComplexField::simd_sqrt(diag);
            l[j][j] = ljj;
            inv[j] = T::one() / ljj;
            for i in j + 1..DOF {
                let mut e: T = dm[(i, j)];
                for k in 0..j {
                    e = e - l[i][k] * l[j][k];
                }
                l[i][j] = e * inv[j];
            }
        }
    }
}

/// The operations of the factorisation, unrolled or looped (the floor's two products
/// included).
fn factor_ops(n: usize) -> OpCount {
    // Per pivot j: j squares subtracted, one sqrt, one reciprocal; per entry below it, j
    // products subtracted and one scaling.
    let mut ops = OpCount {
        add: n - 1,
        mul: 2,
        ..OpCount::default()
    };
    for j in 0..n {
        ops.mul += j + (n - 1 - j) * (j + 1);
        ops.add += j + (n - 1 - j) * j;
        ops.sqrt += 1;
        ops.div += 1;
    }
    ops
}

/// The factor `L` of `dm` unrolled (`l{i}_{j}`, with `inv{j} = 1 / l{j}_{j}`) and `ok` over
/// the pivots.
fn factor(n: usize) -> Vec<TokenStream> {
    let mut s = Vec::new();
    let mut largest = quote!(dm[(0, 0)]);
    for j in 1..n {
        largest = quote!(na::SimdPartialOrd::simd_max(#largest, dm[(#j, #j)]));
    }
    s.push(quote! {
        let floor: T = ::dhgen::cholesky_pivot_floor(DOF, #largest);
    });
    for j in 0..n {
        let mut diag = quote!(dm[(#j, #j)]);
        for k in 0..j {
            let ljk = l(j, k);
            diag = quote!(#diag - #ljk * #ljk);
        }
        let ljj = l(j, j);
        let invj = inv(j);
        let ok = if j == 0 {
            quote!(let ok = na::SimdPartialOrd::simd_gt(#ljj, floor);)
        } else {
            quote!(let ok = ok & na::SimdPartialOrd::simd_gt(#ljj, floor);)
        };
        s.push(quote! {
            let #ljj: T = #diag;
            #ok
            let #ljj: T = na::SimdComplexField::simd_sqrt(#ljj);
            let #invj: T = T::one() / #ljj;
        });
        for i in j + 1..n {
            let mut e = quote!(dm[(#i, #j)]);
            for k in 0..j {
                let (lik, ljk) = (l(i, k), l(j, k));
                e = quote!(#e - #lik * #ljk);
            }
            let lij = l(i, j);
            s.push(quote!(let #lij: T = (#e) * #invj;));
        }
    }
    s
}

/// `D x = rhs` (`dm`, `rhs` in scope) as `(x, ok)`, with its operation count (the
/// `n` subtractions forming `rhs = τ − bias` included).
pub fn solve(n: usize) -> (TokenStream, OpCount) {
    let mut ops = factor_ops(n);
    ops.add += n;
    // Forward and back substitution: a row's products and one scaling each.
    for i in 0..n {
        ops.mul += 2 * i + 2;
        ops.add += 2 * i;
    }
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
                y[i] = e * inv[i];
            }
            let mut x: [T; DOF] = [T::zero(); DOF];
            for i in (0..DOF).rev() {
                let mut e: T = y[i];
                for k in i + 1..DOF {
                    e = e - l[k][i] * x[k];
                }
                x[i] = e * inv[i];
            }
            for xi in x {
                ok = ok & ::dhgen::Real::is_finite_lanes(xi);
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
        let (yi, invi) = (y(i), inv(i));
        s.push(quote!(let #yi: T = (#e) * #invi;));
    }
    for i in (0..n).rev() {
        let mut e = {
            let yi = y(i);
            quote!(#yi)
        };
        for k in i + 1..n {
            let (lki, xk) = (l(k, i), x(k));
            e = quote!(#e - #lki * #xk);
        }
        let (xi, invi) = (x(i), inv(i));
        s.push(quote!(let #xi: T = (#e) * #invi;));
    }
    let xs: Vec<_> = (0..n).map(x).collect();
    // Only a finite acceleration is an answer (non-finite inputs give `None`, as on the
    // runtime path).
    let solve = quote! {
        #(#s)*
        let ok = ok #(& ::dhgen::Real::is_finite_lanes(#xs))*;
        (na::SVector::<T, DOF>::from([#(#xs),*]), ok)
    };
    (solve, ops)
}

/// `D⁻¹` (`dm` in scope) as `(inverse, ok)`, with its operation count: `M = L⁻¹`
/// (lower triangular, its diagonal the pivots' reciprocals), then `D⁻¹ = Mᵀ M` on and above
/// the diagonal, mirrored below. `ok`: every pivot above the floor and, if `finite`, every
/// entry finite (a caller that multiplies D⁻¹ by a finite vector and checks the product
/// learns the same: a non-finite entry makes its row's product non-finite).
pub fn inverse(n: usize, finite: bool) -> (TokenStream, OpCount) {
    let mut ops = factor_ops(n);
    let m = |i: usize, j: usize| format_ident!("m{}_{}", i, j);
    // Row i of M below the diagonal, m_ij = −(Σ_{k=j}^{i−1} l_ik m_kj) · inv_i: i − j + 1
    // products and i − j − 1 sums; (D⁻¹)_ab = Σ_{k ≥ b} m_ka m_kb for a ≤ b: n − b products
    // and n − b − 1 sums, for each of the b + 1 rows a ≤ b.
    for i in 0..n {
        for j in 0..i {
            ops.mul += i - j + 1;
            ops.add += i - j - 1;
        }
    }
    for b in 0..n {
        ops.mul += (b + 1) * (n - b);
        ops.add += (b + 1) * (n - b - 1);
    }
    if n > LOOPED_ABOVE {
        let factor = factor_looped();
        let check = if finite {
            quote!(ok = ok & ::dhgen::Real::is_finite_lanes(e);)
        } else {
            quote!()
        };
        let zeros = Shape::Square.init();
        let inverse = quote! {
            #factor
            // m = L⁻¹, its diagonal the pivots' reciprocals.
            let mut m: [[T; DOF]; DOF] = [[T::zero(); DOF]; DOF];
            for i in 0..DOF {
                m[i][i] = inv[i];
                for j in 0..i {
                    let mut e: T = l[i][j] * inv[j];
                    for k in j + 1..i {
                        e = e + l[i][k] * m[k][j];
                    }
                    m[i][j] = -e * inv[i];
                }
            }
            let mut out: na::SMatrix<T, DOF, DOF> = #zeros;
            for a in 0..DOF {
                for b in a..DOF {
                    let mut e: T = m[b][a] * m[b][b];
                    for k in b + 1..DOF {
                        e = e + m[k][a] * m[k][b];
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
    // Row i of M below the diagonal: m_ij = −(Σ_{k=j}^{i−1} l_ik m_kj) · inv_i.
    for i in 0..n {
        for j in 0..i {
            let mut e = quote!();
            for k in j..i {
                let (lik, mkj) = (l(i, k), m(k, j));
                let term = if k == j {
                    // m_jj is inv_j.
                    let invj = inv(j);
                    quote!(#lik * #invj)
                } else {
                    quote!(#lik * #mkj)
                };
                e = if k == j { term } else { quote!(#e + #term) };
            }
            let (mij, invi) = (m(i, j), inv(i));
            s.push(quote!(let #mij: T = -(#e) * #invi;));
        }
    }
    // (D⁻¹)_ab = Σ_{k ≥ b} m_ka m_kb for a ≤ b.
    let mut entries = Vec::new();
    for a in 0..n {
        for b in a..n {
            let term = |k: usize| {
                let mka = if k == a { inv(a) } else { m(k, a) };
                let mkb = if k == b { inv(b) } else { m(k, b) };
                quote!(#mka * #mkb)
            };
            let mut e = term(b);
            for k in b + 1..n {
                let t = term(k);
                e = quote!(#e + #t);
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
        let ok = ok #(& ::dhgen::Real::is_finite_lanes(#names))*;
        let mut out: na::SMatrix<T, DOF, DOF> = #zeros;
        #(#stores)*
        (out, ok)
    };
    (inverse, ops)
}
