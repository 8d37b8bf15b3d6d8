//! The robot's structure as a `const` of the generated module (`CHAIN`): the numbers it was
//! generated from, for algorithms that run on the structure (inverse kinematics, planning).

use dhgen_model::{ChainRef, JointKind};
use proc_macro2::TokenStream;
use quote::quote;

/// `x` as an `f64` literal.
fn lit(x: f64) -> TokenStream {
    let l = proc_macro2::Literal::f64_suffixed(x);
    quote!(#l)
}

fn frame_literal(f: &dhgen_model::Frame<f64>) -> TokenStream {
    let rows = f.r.iter().map(|row| {
        let row = row.iter().map(|x| lit(*x));
        quote!([#(#row),*])
    });
    let p = f.p.iter().map(|x| lit(*x));
    quote!(::dhgen::model::Frame { r: [#(#rows),*], p: [#(#p),*] })
}

/// The structure as a `const` expression of `::dhgen::ChainRef<'static>`.
pub fn chain_literal(chain: ChainRef<'_>) -> TokenStream {
    let placements = chain.placements.iter().map(frame_literal);
    let bodies = chain.bodies.iter().map(|b| {
        let joint = match b.joint {
            JointKind::Revolute => quote!(::dhgen::JointKind::Revolute),
            JointKind::Prismatic => quote!(::dhgen::JointKind::Prismatic),
        };
        let offset = lit(b.offset);
        let limits = match b.limits {
            Some([lo, hi]) => {
                let (lo, hi) = (lit(lo), lit(hi));
                quote!(Some([#lo, #hi]))
            }
            None => quote!(None),
        };
        let armature = lit(b.armature);
        let (viscous, coulomb) = (lit(b.friction.viscous), lit(b.friction.coulomb));
        let link = frame_literal(&b.link);
        let inertial = match &b.inertial {
            Some(i) => {
                let mass = lit(i.mass);
                let com = i.com.iter().map(|x| lit(*x));
                let rows = i.inertia.iter().map(|row| {
                    let row = row.iter().map(|x| lit(*x));
                    quote!([#(#row),*])
                });
                quote!(Some(::dhgen::model::Inertial { mass: #mass, com: [#(#com),*], inertia: [#(#rows),*] }))
            }
            None => quote!(None),
        };
        let capsule = match b.capsule {
            Some(r) => {
                let r = lit(r);
                quote!(Some(#r))
            }
            None => quote!(None),
        };
        quote! {
            ::dhgen::model::Body {
                joint: #joint,
                offset: #offset,
                limits: #limits,
                armature: #armature,
                friction: ::dhgen::model::Friction { viscous: #viscous, coulomb: #coulomb },
                link: #link,
                inertial: #inertial,
                capsule: #capsule,
            }
        }
    });
    let gravity = chain.gravity.iter().map(|x| lit(*x));
    let base = frame_literal(&chain.base);
    quote! {
        ::dhgen::ChainRef {
            base: #base,
            placements: &[#(#placements),*],
            bodies: &[#(#bodies),*],
            gravity: [#(#gravity),*],
        }
    }
}
