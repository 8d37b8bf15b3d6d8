//! Forward dynamics' linear solve: `D(q) x = rhs` by an unrolled Cholesky factorisation.

use crate::graph::OpCount;
use proc_macro2::TokenStream;
use quote::{format_ident, quote};

/// Unrolled `D x = rhs` by Cholesky, `None` on a pivot at or below
/// `dhgen::cholesky_pivot_floor` (the rule both paths share), with its operation count (the
/// `n` subtractions forming `rhs = τ − bias` and the floor's n − 1 comparisons and two
/// products included).
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
    let diagonal = (1..n).map(|j| quote!(.max(dm[(#j, #j)])));
    s.push(quote! {
        let floor: T = ::dhgen::cholesky_pivot_floor(DOF, dm[(0, 0)] #(#diagonal)*);
    });
    for j in 0..n {
        let mut diag = quote!(dm[(#j, #j)]);
        for k in 0..j {
            let ljk = l(j, k);
            diag = quote!(#diag - #ljk * #ljk);
        }
        let ljj = l(j, j);
        let invj = inv(j);
        s.push(quote! {
            let #ljj: T = #diag;
            if !(#ljj > floor) {
                return None;
            }
            let #ljj: T = #ljj.sqrt();
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
        if #(!#xs.is_finite())||* {
            return None;
        }
        Some(na::SVector::<T, DOF>::from([#(#xs),*]))
    };
    (solve, ops)
}
