//! The robot's structure as a `const` of the generated module (`CHAIN`): the numbers it was
//! generated from, for algorithms that run on the structure (inverse kinematics, planning).

use dhgen_kernel::closed_form::{ArmKind, DecoupledIk, Method, Shoulder};
use dhgen_kernel::{ChainRef, JointKind, Rigid};
use proc_macro2::TokenStream;
use quote::quote;

use crate::emit::float as lit;

fn frame_literal(f: &dhgen_description::Frame<f64>) -> TokenStream {
    let rows = f.r.iter().map(|row| {
        let row = row.iter().map(|x| lit(*x));
        quote!([#(#row),*])
    });
    let p = f.p.iter().map(|x| lit(*x));
    quote!(::dhgen::__private::Frame { r: [#(#rows),*], p: [#(#p),*] })
}

/// The structure as a `const` expression of `::dhgen::__private::ChainRef<'static>`.
pub fn chain_literal(chain: ChainRef<'_>) -> TokenStream {
    let placements = chain.placements.iter().map(frame_literal);
    let bodies = chain.bodies.iter().map(|b| {
        let joint = match b.joint {
            JointKind::Revolute => quote!(::dhgen::__private::JointKind::Revolute),
            JointKind::Prismatic => quote!(::dhgen::__private::JointKind::Prismatic),
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
                quote!(Some(::dhgen::__private::Inertial { mass: #mass, com: [#(#com),*], inertia: [#(#rows),*] }))
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
            ::dhgen::__private::Body {
                joint: #joint,
                offset: #offset,
                limits: #limits,
                armature: #armature,
                friction: ::dhgen::__private::Friction { viscous: #viscous, coulomb: #coulomb },
                link: #link,
                inertial: #inertial,
                capsule: #capsule,
            }
        }
    });
    let gravity = chain.gravity.iter().map(|x| lit(*x));
    let base = frame_literal(&chain.base);
    quote! {
        ::dhgen::__private::ChainRef {
            base: #base,
            placements: &[#(#placements),*],
            bodies: &[#(#bodies),*],
            gravity: [#(#gravity),*],
        }
    }
}

fn vector3(v: &nalgebra_types::Vector3) -> TokenStream {
    let [x, y, z] = [v.x, v.y, v.z].map(lit);
    quote!(::dhgen::__private::nalgebra::Vector3::new(#x, #y, #z))
}

fn matrix3(m: &nalgebra_types::Matrix3) -> TokenStream {
    let entries = (0..3).flat_map(|r| (0..3).map(move |c| lit(m[(r, c)])));
    quote!(::dhgen::__private::nalgebra::Matrix3::new(#(#entries),*))
}

fn rigid(f: &Rigid) -> TokenStream {
    let (r, p) = (matrix3(&f.r), vector3(&f.p));
    quote!(::dhgen::__private::Rigid { r: #r, p: #p })
}

/// The nalgebra types the solver's constants use (dhgen-description's own re-export).
mod nalgebra_types {
    pub type Vector3 = dhgen_description::nalgebra::Vector3<f64>;
    pub type Matrix3 = dhgen_description::nalgebra::Matrix3<f64>;
}

/// The closed-form inverse kinematics solver, precomputed, as a `const` expression of
/// `::dhgen::__private::closed_form::DecoupledIk`.
pub fn ik_literal(ik: &DecoupledIk) -> TokenStream {
    let chain = ik.chain.iter().map(rigid);
    let prismatic = ik.prismatic;
    let limits = ik.limits.iter().map(|l| match l {
        Some([lo, hi]) => {
            let (lo, hi) = (lit(*lo), lit(*hi));
            quote!(Some([#lo, #hi]))
        }
        None => quote!(None),
    });
    let scale = lit(ik.scale);
    let kind = match ik.kind {
        ArmKind::IntersectingShoulder => quote!(IntersectingShoulder),
        ArmKind::ParallelShoulder => quote!(ParallelShoulder),
        ArmKind::OffsetShoulder => quote!(OffsetShoulder),
        ArmKind::Cylindrical => quote!(Cylindrical),
        ArmKind::ThreeParallel => quote!(ThreeParallel),
    };
    let method = match &ik.method {
        Method::Spherical {
            centre_tool,
            w,
            shoulder,
        } => {
            let (centre_tool, w) = (vector3(centre_tool), vector3(w));
            let shoulder = match shoulder {
                Shoulder::Revolute { shift, t1, u, n } => {
                    let shift = lit(*shift);
                    let (t1, u, n) = (vector3(t1), vector3(u), vector3(n));
                    quote!(::dhgen::__private::closed_form::Shoulder::Revolute {
                        shift: #shift, t1: #t1, u: #u, n: #n
                    })
                }
                Shoulder::Cylindrical {
                    f0,
                    u,
                    v,
                    lead_is_2,
                } => {
                    let (f0, u, v) = (vector3(f0), vector3(u), vector3(v));
                    quote!(::dhgen::__private::closed_form::Shoulder::Cylindrical {
                        f0: #f0, u: #u, v: #v, lead_is_2: #lead_is_2
                    })
                }
            };
            quote!(::dhgen::__private::closed_form::Method::Spherical {
                centre_tool: #centre_tool, w: #w, shoulder: #shoulder
            })
        }
        Method::ThreeParallel {
            n,
            x_tool,
            x4,
            kappa,
            sigma,
            sigma3,
            sigma34,
            k0,
        } => {
            let (n, x_tool, x4, k0) = (vector3(n), vector3(x_tool), vector3(x4), matrix3(k0));
            let (kappa, sigma, sigma3, sigma34) =
                (lit(*kappa), lit(*sigma), lit(*sigma3), lit(*sigma34));
            quote!(::dhgen::__private::closed_form::Method::ThreeParallel {
                n: #n, x_tool: #x_tool, x4: #x4, kappa: #kappa, sigma: #sigma,
                sigma3: #sigma3, sigma34: #sigma34, k0: #k0
            })
        }
    };
    quote! {
        ::dhgen::__private::closed_form::DecoupledIk {
            chain: [#(#chain),*],
            prismatic: [#(#prismatic),*],
            limits: [#(#limits),*],
            scale: #scale,
            kind: ::dhgen::__private::closed_form::ArmKind::#kind,
            method: #method,
        }
    }
}
