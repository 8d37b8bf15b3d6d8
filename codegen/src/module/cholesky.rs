//! Forward dynamics' linear solve: `D(q) x = rhs` by an unrolled Cholesky factorisation.

use crate::graph::OpCount;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// Unrolled `D x = rhs` by Cholesky, with its operation count (the `n` subtractions forming
/// `rhs = τ − bias` and the floor's n − 1 comparisons and two products included).
///
/// The value is `(x, ok)`: `ok` holds, lane by lane, where every pivot is above
/// `dhgen::cholesky_pivot_floor` (the rule both paths share) and `x` is finite. The code has
/// no branch: a SIMD pack's lanes each get the scalar path's answer, whatever the others'.
pub fn solve(n: usize) -> (TokenStream, OpCount) {
    // Per pivot j: j squares subtracted, one sqrt, one reciprocal; per entry below it, j
    // products subtracted and one scaling; forward and back substitution: a row's products
    // and one scaling each.
    let mut ops = OpCount {
        add: n + (n - 1),
        mul: 2,
        ..OpCount::default()
    };
    for j in 0..n {
        ops.mul += j + (n - 1 - j) * (j + 1);
        ops.add += j + (n - 1 - j) * j;
        ops.sqrt += 1;
        ops.div += 1;
    }
    for i in 0..n {
        ops.mul += 2 * i + 2;
        ops.add += 2 * i;
    }
    let l = |i: usize, j: usize| format_ident!("l{}_{}", i, j);
    let inv = |i: usize| format_ident!("inv{}", i);
    let y = |i: usize| format_ident!("y{}", i);
    let x = |i: usize| format_ident!("x{}", i);
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
