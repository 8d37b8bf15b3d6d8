//! The per-configuration `State`: each joint's sine and cosine (or displacement) computed
//! once, and the preparers that compute only the joints one quantity reads.

use super::Context;
use crate::emit::constant;
use dhgen_description::{Angle, JointKind};
use proc_macro2::TokenStream;
use quote::quote;

/// The statements that fill `State { c, s, d }` from `q` (an array) for the given joints
/// (all when `None`), ending in the value.
pub fn fill(cx: &Context<'_>, joints: Option<&[usize]>) -> TokenStream {
    let chain = cx.chain;
    let value = |j: usize| {
        let offset = chain.bodies[j].offset;
        if offset == 0.0 {
            quote!(q[#j])
        } else {
            let k = constant(offset);
            quote!(q[#j] + #k)
        }
    };
    let of_kind = |kind: JointKind| {
        (0..chain.bodies.len())
            .filter(|j| joints.is_none_or(|js| js.contains(j)) && chain.bodies[*j].joint == kind)
            .collect::<Vec<_>>()
    };
    let (revolute, prismatic) = (of_kind(JointKind::Revolute), of_kind(JointKind::Prismatic));
    let lengths_lines = prismatic.iter().map(|&j| {
        let v = value(j);
        quote!(d[#j] = #v;)
    });
    // Every revolute joint's sine and cosine in one call (packs of four for `f64` where the
    // target has AVX), so that a scalar's are bit for bit a pack lane's. An offset that is a
    // quarter turn (as the description reads it: within 1e-12 rad of k·π/2, zero included)
    // turns the sine and cosine of q exactly instead of rounding q + offset:
    // sin(q + o) = sin q · cos o + cos q · sin o, cos(q + o) = cos q · cos o − sin q · sin o.
    let trig_lines = if revolute.is_empty() {
        quote!()
    } else {
        let turns: Vec<_> = revolute
            .iter()
            .map(|&j| Angle::from_radians(chain.bodies[j].offset).quarter_turn())
            .collect();
        let values = revolute.iter().zip(&turns).map(|(&j, turn)| {
            if turn.is_some() {
                quote!(q[#j])
            } else {
                value(j)
            }
        });
        let stores = revolute
            .iter()
            .zip(&turns)
            .enumerate()
            .map(|(k, (&j, turn))| {
                let (sin, cos) = (quote!(sa[#k]), quote!(ca[#k]));
                let (sj, cj) = match turn {
                    None | Some((1, 0)) => (sin, cos),
                    Some((0, 1)) => (cos, quote!(-#sin)),
                    Some((-1, 0)) => (quote!(-#sin), quote!(-#cos)),
                    Some(_) => (quote!(-#cos), sin),
                };
                quote!(s[#j] = #sj; c[#j] = #cj;)
            });
        quote! {
            let (sa, ca) = ::dhgen::__private::Real::sincos_array([#(#values),*]);
            #(#stores)*
        }
    };
    // Only arrays that some line fills are declared `mut` (no warnings in user crates).
    let trig = if revolute.is_empty() {
        quote!(let c = [T::zero(); DOF]; let s = [T::zero(); DOF];)
    } else {
        quote!(let mut c = [T::zero(); DOF]; let mut s = [T::zero(); DOF];)
    };
    let lengths = if prismatic.is_empty() {
        quote!(let d = [T::zero(); DOF];)
    } else {
        quote!(let mut d = [T::zero(); DOF];)
    };
    let read = if joints.is_some_and(<[usize]>::is_empty) {
        // A quantity that reads no joint (a constant) ignores the configuration.
        quote!(let _ = q;)
    } else {
        quote!(let q = q.to_array();)
    };
    quote! {
        #read
        #trig
        #lengths
        #trig_lines
        #(#lengths_lines)*
        State { c, s, d }
    }
}

/// The `State` type and its constructor.
pub fn definition(cx: &Context<'_>) -> TokenStream {
    let fill = fill(cx, None);
    quote! {
        /// One configuration, prepared: the sine and cosine of every revolute joint's full
        /// angle and the full displacement of every prismatic joint, computed once and
        /// shared by every quantity evaluated at this configuration.
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct State<T: na::Scalar> {
            /// cos θ_j (revolute joints; 0 for prismatic ones).
            pub c: [T; DOF],
            /// sin θ_j (revolute joints; 0 for prismatic ones).
            pub s: [T; DOF],
            /// d_j (prismatic joints; 0 for revolute ones).
            pub d: [T; DOF],
        }

        impl<T: ::dhgen::__private::Real> State<T> {
            /// Prepares configuration `q` (an array or an `SVector`).
            #[must_use]
            pub fn new(q: &impl ::dhgen::__private::JointArray<T, DOF>) -> Self {
                #fill
            }
        }
    }
}

/// `tau[j] += coulomb_j · sign(q̇_j)` for the joints with Coulomb friction.
pub fn coulomb(cx: &Context<'_>) -> TokenStream {
    friction_terms(
        cx,
        |f| f.coulomb,
        |k, j| quote!(#k * ::dhgen::__private::Real::sign(qd[#j])),
    )
}

/// `tau[j] += term(k_j, j)` for each joint whose `k_j = coefficient(its friction)` is not
/// zero (`k_j` as a constant of type `T`).
pub fn friction_terms(
    cx: &Context<'_>,
    coefficient: impl Fn(&dhgen_description::Friction) -> f64,
    term: impl Fn(TokenStream, usize) -> TokenStream,
) -> TokenStream {
    let lines = cx
        .chain
        .bodies
        .iter()
        .enumerate()
        .filter(|(_, b)| coefficient(&b.friction) != 0.0)
        .map(|(j, b)| {
            let t = term(constant(coefficient(&b.friction)), j);
            quote!(tau[#j] += #t;)
        });
    quote!(#(#lines)*)
}
