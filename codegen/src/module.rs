//! The generated module: a per-configuration `State` (sine and cosine of every joint
//! computed once), methods for each quantity, and free functions taking `&[T; DOF]`.

use crate::derive::{
    Derivation, christoffel, gravity, inertia, kinematics, newton_euler, singularity,
};
use crate::emit::{self, Output, constant};
use crate::graph::{E, OpCount, SharedGraph};
use dhgen_model::{ChainRef, JointKind, RobotModel};
use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

/// The generated module and what it costs.
pub struct Generated {
    /// The `mod name { ... }` item.
    pub tokens: TokenStream,
    /// Arithmetic operations per generated function.
    pub ops: Vec<(String, OpCount)>,
}

/// The signature of one generated `State` method.
struct Method {
    name: &'static str,
    /// `Some(doc)` for a public method.
    doc: Option<&'static str>,
    /// Extra joint-vector parameters (`qd`, `qdd`), each `&[T; DOF]`.
    inputs: &'static [&'static str],
    out_ty: TokenStream,
    out_init: TokenStream,
}

impl Method {
    /// A method of the configuration only, returning `out_ty`.
    fn of_q(
        name: &'static str,
        doc: &'static str,
        out_ty: TokenStream,
        out_init: TokenStream,
    ) -> Method {
        Method {
            name,
            doc: Some(doc),
            inputs: &[],
            out_ty,
            out_init,
        }
    }
}

/// Collects the generated methods, their part functions and their operation counts.
#[derive(Default)]
struct Builder {
    methods: Vec<TokenStream>,
    parts: Vec<TokenStream>,
    ops: Vec<(String, OpCount)>,
    /// The joints each method reads, so a free function prepares only those.
    joints: Vec<(&'static str, Vec<usize>)>,
    /// Which joints are revolute (need a `sin_cos`).
    revolute: Vec<bool>,
}

impl Builder {
    fn joints_of(&self, names: &[&str]) -> Vec<usize> {
        let mut js: Vec<usize> = self
            .joints
            .iter()
            .filter(|(n, _)| names.contains(n))
            .flat_map(|(_, j)| j.iter().copied())
            .collect();
        js.sort_unstable();
        js.dedup();
        js
    }
}

impl Builder {
    /// Emits `outputs` as the body of a `State` method: inline when small, otherwise as
    /// private part methods called in turn, sharing values through a scratch array.
    fn add(&mut self, m: Method, g: &SharedGraph, outputs: Vec<Output>) {
        let Method {
            name,
            doc,
            inputs,
            out_ty,
            out_init,
        } = m;
        let params_of = |names: &[&str]| {
            let ids = names.iter().map(|n| format_ident!("{}", n));
            quote!(#(#ids: &[T; DOF],)*)
        };
        let args_of = |names: &[&str]| {
            let ids = names.iter().map(|n| format_ident!("{}", n));
            quote!(#(#ids,)*)
        };
        let params = params_of(inputs);
        let emitted = emit::emit(g, outputs);
        let mut ops = emitted.ops;
        ops.sincos = emitted
            .joints
            .iter()
            .filter(|&&j| self.revolute.get(j).copied().unwrap_or(false))
            .count();
        self.ops.push((name.to_string(), ops));
        self.joints.push((name, emitted.joints.clone()));
        let fname = Ident::new(name, Span::call_site());
        let body = if emitted.parts.len() == 1 {
            let stmts = &emitted.parts[0];
            quote!(#(#stmts)*)
        } else {
            let w = emitted.scratch.max(1);
            let mut calls = vec![quote!(let mut w = [T::zero(); #w];)];
            for (i, stmts) in emitted.parts.iter().enumerate() {
                let part = format_ident!("{}_part{}", name, i);
                // Each part takes only the joint vectors it reads.
                let used: Vec<&str> = inputs
                    .iter()
                    .copied()
                    .filter(|n| emitted.part_inputs[i].contains(n))
                    .collect();
                let (part_params, part_args) = (params_of(&used), args_of(&used));
                let u = emitted.part_uses[i];
                let out = if u.out {
                    format_ident!("out")
                } else {
                    format_ident!("_out")
                };
                let scratch = if u.scratch {
                    format_ident!("w")
                } else {
                    format_ident!("_w")
                };
                self.parts.push(quote! {
                    #[inline(never)]
                    fn #part(&self, #part_params #scratch: &mut [T; #w], #out: &mut #out_ty) {
                        #(#stmts)*
                    }
                });
                calls.push(quote!(self.#part(#part_args &mut w, &mut out);));
            }
            quote!(#(#calls)*)
        };
        // A scalar is assigned exactly once: declare it without a dead initial value.
        let declare = if out_init.is_empty() {
            quote!(let out: #out_ty;)
        } else {
            quote!(let mut out: #out_ty = #out_init;)
        };
        let method = quote! {
            fn #fname(&self, #params) -> #out_ty {
                #declare
                #body
                out
            }
        };
        match doc {
            Some(doc) => self
                .methods
                .push(quote!(#[doc = #doc] #[must_use] pub #method)),
            None => self.parts.push(method),
        }
    }
}

/// Operation counts of every function generated for `model`.
pub fn op_counts(model: &RobotModel) -> Vec<(String, OpCount)> {
    let name = Ident::new("robot", Span::call_site());
    generate(model, TokenStream::new(), &name, "").ops
}

/// Generates the module `vis mod name { ... }` for `model`.
pub fn generate(model: &RobotModel, vis: TokenStream, name: &Ident, doc: &str) -> Generated {
    let n = model.dof();
    let structure = model.chain();
    let chain = structure.view();
    let mut b = Builder {
        revolute: chain
            .bodies
            .iter()
            .map(|l| l.joint == JointKind::Revolute)
            .collect(),
        ..Builder::default()
    };

    // Forward kinematics: the 4×4 homogeneous matrix and the link frames.
    let (g, f) = kinematics::fk(chain);
    b.add(
        Method::of_q(
            "fk_matrix",
            "Pose of the tool frame in the world frame as a homogeneous matrix: base · A1 ⋯ An · tool.",
            quote!(na::Matrix4<T>),
            quote!(na::Matrix4::identity()),
        ),
        &g,
        frame_outputs(&f, quote!(out)),
    );

    let (g, frames) = kinematics::frames(chain);
    let outs = frames
        .iter()
        .enumerate()
        .flat_map(|(i, f)| frame_outputs(f, quote!(out[#i])))
        .collect();
    b.add(
        Method::of_q(
            "frames_matrix",
            "The link frames in the world frame (base applied, tool not) as homogeneous matrices.",
            quote!([na::Matrix4<T>; DOF]),
            quote!([na::Matrix4::identity(); DOF]),
        ),
        &g,
        outs,
    );

    let (g, columns) = kinematics::jacobian(chain);
    let outs = columns
        .iter()
        .enumerate()
        .flat_map(|(c, col)| {
            col.iter().enumerate().map(move |(r, e)| Output {
                target: quote!(out[(#r, #c)]),
                value: e.clone(),
            })
        })
        .collect();
    b.add(
        Method::of_q(
            "jacobian",
            "Geometric Jacobian of the tool frame origin, world axes, rows [v; ω].",
            quote!(na::SMatrix<T, 6, DOF>),
            quote!(na::SMatrix::zeros()),
        ),
        &g,
        outs,
    );

    let g = SharedGraph::default();
    let acc = kinematics::jdot_qdot(chain, &g);
    b.add(
        Method {
            name: "jdot_qdot",
            doc: Some("J̇(q, q̇) q̇ of the tool frame origin, world axes, rows [v; ω]: the tool's acceleration at q̈ = 0."),
            inputs: &["qd"],
            out_ty: quote!(na::SVector<T, 6>),
            out_init: quote!(na::SVector::zeros()),
        },
        &g,
        vector_outputs(&acc),
    );

    // Arms with a spherical wrist: the decoupled singularity conditions, symbolically.
    let determinants = singularity::decoupled_determinants(chain);
    if let Some((j11, j22)) = &determinants {
        let docs = [
            (
                "det_j11",
                j11,
                "det J11: zero at arm singularities (section 5.6.1; Jacobian about the wrist centre).",
            ),
            (
                "det_j22",
                j22,
                "det J22 = z3 · (z4 × z5): zero at wrist singularities (section 5.6.1).",
            ),
        ];
        for (name, poly, doc) in docs {
            let g = SharedGraph::default();
            let e = crate::derive::polys_to_exprs(std::slice::from_ref(poly), &g, chain);
            b.add(
                Method::of_q(name, doc, quote!(T), TokenStream::new()),
                &g,
                vec![Output {
                    target: quote!(out),
                    value: e[0].clone(),
                }],
            );
        }
    }
    let spherical = determinants.is_some();
    let spherical_wrist = chain.spherical_wrist().is_ok();

    let dynamics = model.has_dynamics();
    let mut coriolis_direct = false;
    if dynamics {
        let dv = Derivation::new(chain);
        let (g, d) = inertia::mass_matrix(&dv);
        b.add(
            Method::of_q(
                "mass_matrix",
                "Joint-space inertia matrix D(q) (motor inertia included).",
                quote!(na::SMatrix<T, DOF, DOF>),
                quote!(na::SMatrix::zeros()),
            ),
            &g,
            matrix_outputs(&d, n),
        );

        let (g, c) = christoffel::christoffel(&dv);
        let outs = (0..n)
            .flat_map(|i| (0..n).flat_map(move |j| (0..n).map(move |k| (i, j, k))))
            .map(|(i, j, k)| Output {
                target: quote!(out[#i][#j][#k]),
                value: c[(i * n + j) * n + k].clone(),
            })
            .collect();
        b.add(
            Method::of_q(
                "christoffel",
                "Christoffel symbols: `[i][j][k]` = c_ijk = ½(∂d_kj/∂q_i + ∂d_ki/∂q_j − ∂d_ij/∂q_k), k the equation index.",
                quote!([[[T; DOF]; DOF]; DOF]),
                quote!([[[T::zero(); DOF]; DOF]; DOF]),
            ),
            &g,
            outs,
        );

        // C straight from the symbols (zero symbols fold away) when that beats contracting
        // the whole n³ array at run time.
        let cor = christoffel::coriolis_from(n, &g, &c);
        let roots: Vec<_> = cor.iter().map(|e| e.id_in(&g)).collect();
        let direct = crate::graph::count(&g.borrow(), roots).total();
        let symbols = b.ops.last().map_or(0, |(_, c)| c.total());
        if direct < symbols + 2 * n * n * n {
            b.add(
                Method {
                    name: "coriolis",
                    doc: Some("Coriolis and centrifugal matrix: C_kj = Σ_i c_ijk q̇_i (so Ḋ − 2C is skew-symmetric)."),
                    inputs: &["qd"],
                    out_ty: quote!(na::SMatrix<T, DOF, DOF>),
                    out_init: quote!(na::SMatrix::zeros()),
                },
                &g,
                matrix_outputs(&cor, n),
            );
        }
        coriolis_direct = direct < symbols + 2 * n * n * n;

        let (g, gr) = gravity::gravity(&dv);
        b.add(
            Method::of_q(
                "gravity",
                "Gravity torques g(q): the torques that hold the arm still.",
                quote!(na::SVector<T, DOF>),
                quote!(na::SVector::zeros()),
            ),
            &g,
            vector_outputs(&gr),
        );

        let (g, tau) = newton_euler::inverse_dynamics(&dv);
        b.add(
            Method {
                name: "inverse_dynamics_smooth",
                doc: None,
                inputs: &["qd", "qdd"],
                out_ty: quote!(na::SVector<T, DOF>),
                out_init: quote!(na::SVector::zeros()),
            },
            &g,
            vector_outputs(&tau),
        );

        let g = SharedGraph::default();
        let bias = newton_euler::rnea_exprs(chain, &g, true, true);
        b.add(
            Method {
                name: "bias_smooth",
                doc: None,
                inputs: &["qd"],
                out_ty: quote!(na::SVector<T, DOF>),
                out_init: quote!(na::SVector::zeros()),
            },
            &g,
            vector_outputs(&bias),
        );
    }
    let state_all = state_new(chain, None);
    let coriolis_loop = if dynamics && !coriolis_direct {
        quote! {
            /// Coriolis and centrifugal matrix: C_kj = Σ_i c_ijk q̇_i (so Ḋ − 2C is
            /// skew-symmetric), contracted from the generated Christoffel symbols.
            #[must_use]
            pub fn coriolis(&self, qd: &[T; DOF]) -> na::SMatrix<T, DOF, DOF> {
                let c = self.christoffel();
                let mut out = na::SMatrix::<T, DOF, DOF>::zeros();
                for k in 0..DOF {
                    for j in 0..DOF {
                        let mut sum = T::zero();
                        for i in 0..DOF {
                            sum += c[i][j][k] * qd[i];
                        }
                        out[(k, j)] = sum;
                    }
                }
                out
            }
        }
    } else {
        quote!()
    };
    // Free functions prepare only the joints their quantity reads (D(q) never needs q1).
    let uses: &[(&str, &[&str])] = &[
        ("fk", &["fk_matrix"]),
        ("jdot_qdot", &["jdot_qdot"]),
        ("det_j11", &["det_j11"]),
        ("det_j22", &["det_j22"]),
        ("frames", &["frames_matrix"]),
        ("jacobian", &["jacobian"]),
        ("mass_matrix", &["mass_matrix"]),
        ("christoffel", &["christoffel"]),
        ("coriolis", &["christoffel"]),
        ("gravity", &["gravity"]),
        ("inverse_dynamics", &["inverse_dynamics_smooth"]),
        ("forward_dynamics", &["mass_matrix", "bias_smooth"]),
    ];
    let preparers = uses
        .iter()
        .filter(|(q, _)| {
            let kinematic = matches!(*q, "fk" | "frames" | "jacobian" | "jdot_qdot");
            let wrist = matches!(*q, "det_j11" | "det_j22");
            kinematic || (wrist && spherical) || (dynamics && !wrist)
        })
        .map(|(q, names)| {
            let f = format_ident!("for_{}", q);
            let joints = b.joints_of(names);
            let body = state_new(chain, Some(&joints));
            // A quantity that reads no joint (a constant) ignores the configuration.
            let q = if joints.is_empty() {
                format_ident!("_q")
            } else {
                format_ident!("q")
            };
            quote! {
                #[inline]
                fn #f(#q: &[T; DOF]) -> Self {
                    #body
                }
            }
        })
        .collect::<Vec<_>>();
    let coulomb = coulomb(chain);
    let tau_mut = if coulomb.is_empty() {
        quote!()
    } else {
        quote!(mut)
    };
    let dyn_items = if dynamics {
        let (chol, chol_ops) = cholesky_solve(n);
        b.ops.push(("cholesky_solve".to_string(), chol_ops));
        quote! {
            /// Inverse dynamics τ = D(q) q̈ + C(q, q̇) q̇ + g(q), plus motor inertia and friction.
            #[must_use]
            pub fn inverse_dynamics(&self, qd: &[T; DOF], qdd: &[T; DOF]) -> na::SVector<T, DOF> {
                let #tau_mut tau = self.inverse_dynamics_smooth(qd, qdd);
                #coulomb
                tau
            }

            /// The torques at zero acceleration: C(q, q̇) q̇ + g(q) + friction.
            #[must_use]
            pub fn bias(&self, qd: &[T; DOF]) -> na::SVector<T, DOF> {
                let #tau_mut tau = self.bias_smooth(qd);
                #coulomb
                tau
            }

            /// Forward dynamics q̈ = D⁻¹(τ − C q̇ − g − friction) by an unrolled Cholesky
            /// solve; `None` where D(q) is not positive definite.
            #[must_use]
            pub fn forward_dynamics(&self, qd: &[T; DOF], tau: &[T; DOF]) -> Option<na::SVector<T, DOF>> {
                let dm = self.mass_matrix();
                let h = self.bias(qd);
                let rhs: [T; DOF] = ::core::array::from_fn(|i| tau[i] - h[i]);
                #chol
            }

            #coriolis_loop

            /// D, C, g and J at once, sharing this state's sines and cosines.
            #[must_use]
            pub fn terms(&self, qd: &[T; DOF]) -> Terms<T> {
                Terms {
                    mass_matrix: self.mass_matrix(),
                    coriolis: self.coriolis(qd),
                    gravity: self.gravity(),
                    jacobian: self.jacobian(),
                }
            }
        }
    } else {
        quote!()
    };
    let dyn_free = if dynamics {
        quote! {
            /// Joint-space inertia matrix D(q).
            #[must_use]
            pub fn mass_matrix<T: ::dhgen::Real>(q: &[T; DOF]) -> na::SMatrix<T, DOF, DOF> {
                State::for_mass_matrix(q).mass_matrix()
            }
            /// Christoffel symbols, `[i][j][k]` = c_ijk with k the equation index.
            #[must_use]
            pub fn christoffel<T: ::dhgen::Real>(q: &[T; DOF]) -> [[[T; DOF]; DOF]; DOF] {
                State::for_christoffel(q).christoffel()
            }
            /// Coriolis matrix C(q, q̇), C_kj = Σ_i c_ijk q̇_i.
            #[must_use]
            pub fn coriolis<T: ::dhgen::Real>(q: &[T; DOF], qd: &[T; DOF]) -> na::SMatrix<T, DOF, DOF> {
                State::for_coriolis(q).coriolis(qd)
            }
            /// Gravity torques g(q).
            #[must_use]
            pub fn gravity<T: ::dhgen::Real>(q: &[T; DOF]) -> na::SVector<T, DOF> {
                State::for_gravity(q).gravity()
            }
            /// Inverse dynamics τ(q, q̇, q̈).
            #[must_use]
            pub fn inverse_dynamics<T: ::dhgen::Real>(q: &[T; DOF], qd: &[T; DOF], qdd: &[T; DOF]) -> na::SVector<T, DOF> {
                State::for_inverse_dynamics(q).inverse_dynamics(qd, qdd)
            }
            /// Forward dynamics q̈(q, q̇, τ); `None` where D(q) is not positive definite.
            #[must_use]
            pub fn forward_dynamics<T: ::dhgen::Real>(q: &[T; DOF], qd: &[T; DOF], tau: &[T; DOF]) -> Option<na::SVector<T, DOF>> {
                State::for_forward_dynamics(q).forward_dynamics(qd, tau)
            }
            /// D, C, g and J at one configuration, as a controller needs them.
            #[derive(Clone, Copy, Debug, PartialEq)]
            pub struct Terms<T: na::Scalar> {
                /// D(q)
                pub mass_matrix: na::SMatrix<T, DOF, DOF>,
                /// C(q, q̇)
                pub coriolis: na::SMatrix<T, DOF, DOF>,
                /// g(q)
                pub gravity: na::SVector<T, DOF>,
                /// J(q)
                pub jacobian: na::SMatrix<T, 6, DOF>,
            }
        }
    } else {
        quote!()
    };
    let wrist_free = if spherical {
        quote! {
            /// det J11 (Jacobian about the wrist centre): zero at arm singularities.
            #[must_use]
            pub fn det_j11<T: ::dhgen::Real>(q: &[T; DOF]) -> T {
                State::for_det_j11(q).det_j11()
            }
            /// det J22 = z3 · (z4 × z5): zero at wrist singularities.
            #[must_use]
            pub fn det_j22<T: ::dhgen::Real>(q: &[T; DOF]) -> T {
                State::for_det_j22(q).det_j22()
            }
            /// The closed-form inverse kinematics solver of this arm (kinematic decoupling,
            /// section 4.3): build it once and call `solve` for each pose.
            pub fn ik_solver() -> Result<::dhgen::ik::DecoupledIk, ::dhgen::ik::StructureError> {
                ::dhgen::ik::DecoupledIk::from_chain(CHAIN)
            }
            /// All closed-form inverse kinematics solutions of `pose` (up to 8), each
            /// verified by forward kinematics; empty when the pose is unreachable.
            pub fn ik(pose: &na::Isometry3<f64>) -> Result<::dhgen::ik::Solutions, ::dhgen::ik::StructureError> {
                Ok(ik_solver()?.solve(pose))
            }
        }
    } else {
        quote!()
    };
    // `sign` (Coulomb friction, with sign(0) = 0) only where some joint has Coulomb friction.
    let sign_fn = if dynamics && chain.bodies.iter().any(|l| l.friction.coulomb != 0.0) {
        quote! {
            fn sign<T: ::dhgen::Real>(x: T) -> T {
                if x > T::zero() {
                    T::one()
                } else if x < T::zero() {
                    -T::one()
                } else {
                    T::zero()
                }
            }
        }
    } else {
        quote!()
    };
    let (methods, parts) = (&b.methods, &b.parts);
    let robot_name = &model.name;
    let chain_const = chain_literal(chain);
    let arm_dynamics = if dynamics {
        quote! {
            impl ::dhgen::ArmDynamics for Model {
                fn mass_matrix(&self, q: &na::SVector<f64, DOF>) -> na::SMatrix<f64, DOF, DOF> {
                    State::for_mass_matrix(&(*q).into()).mass_matrix()
                }
                fn coriolis(&self, q: &na::SVector<f64, DOF>, qd: &na::SVector<f64, DOF>) -> na::SMatrix<f64, DOF, DOF> {
                    State::for_coriolis(&(*q).into()).coriolis(&(*qd).into())
                }
                fn gravity(&self, q: &na::SVector<f64, DOF>) -> na::SVector<f64, DOF> {
                    State::for_gravity(&(*q).into()).gravity()
                }
                fn inverse_dynamics(&self, q: &na::SVector<f64, DOF>, qd: &na::SVector<f64, DOF>, qdd: &na::SVector<f64, DOF>) -> na::SVector<f64, DOF> {
                    State::for_inverse_dynamics(&(*q).into()).inverse_dynamics(&(*qd).into(), &(*qdd).into())
                }
                fn forward_dynamics(&self, q: &na::SVector<f64, DOF>, qd: &na::SVector<f64, DOF>, tau: &na::SVector<f64, DOF>) -> Option<na::SVector<f64, DOF>> {
                    State::for_forward_dynamics(&(*q).into()).forward_dynamics(&(*qd).into(), &(*tau).into())
                }
            }
        }
    } else {
        quote!()
    };
    let tokens = quote! {
        #[doc = #doc]
        #[allow(clippy::all, clippy::pedantic, clippy::nursery)]
        #vis mod #name {
            use ::dhgen::nalgebra as na;

            /// Number of joints.
            pub const DOF: usize = #n;
            /// The robot's name.
            pub const NAME: &str = #robot_name;
            /// Whether the description has mass properties (dynamics functions exist).
            pub const HAS_DYNAMICS: bool = #dynamics;

            /// One configuration, prepared: the sine and cosine of every revolute joint's
            /// full angle and the full displacement of every prismatic joint, computed once
            /// and shared by every quantity evaluated at this configuration.
            #[derive(Clone, Copy, Debug, PartialEq)]
            pub struct State<T: na::Scalar> {
                /// cos θ_j (revolute joints; 0 for prismatic ones).
                pub c: [T; DOF],
                /// sin θ_j (revolute joints; 0 for prismatic ones).
                pub s: [T; DOF],
                /// d_j (prismatic joints; 0 for revolute ones).
                pub d: [T; DOF],
            }

            impl<T: ::dhgen::Real> State<T> {
                /// Prepares configuration `q`.
                #[must_use]
                pub fn new(q: &[T; DOF]) -> Self {
                    #state_all
                }

                /// Pose of the tool frame in the world frame: base · A1 ⋯ An · tool.
                #[must_use]
                pub fn fk(&self) -> na::Isometry3<T> {
                    isometry(&self.fk_matrix())
                }

                /// The link frames in the world frame (base applied, tool not).
                #[must_use]
                pub fn frames(&self) -> [na::Isometry3<T>; DOF] {
                    let m = self.frames_matrix();
                    ::core::array::from_fn(|i| isometry(&m[i]))
                }

                #(#methods)*
                #dyn_items
                #(#parts)*
                #(#preparers)*
            }

            /// Pose of the tool frame in the world frame.
            #[must_use]
            pub fn fk<T: ::dhgen::Real>(q: &[T; DOF]) -> na::Isometry3<T> {
                State::for_fk(q).fk()
            }
            /// The link frames in the world frame (tool not applied).
            #[must_use]
            pub fn frames<T: ::dhgen::Real>(q: &[T; DOF]) -> [na::Isometry3<T>; DOF] {
                State::for_frames(q).frames()
            }
            /// Geometric Jacobian of the tool frame origin, world axes, rows [v; ω].
            #[must_use]
            pub fn jacobian<T: ::dhgen::Real>(q: &[T; DOF]) -> na::SMatrix<T, 6, DOF> {
                State::for_jacobian(q).jacobian()
            }
            /// J̇(q, q̇) q̇ of the tool frame origin (the tool's acceleration at q̈ = 0).
            #[must_use]
            pub fn jdot_qdot<T: ::dhgen::Real>(q: &[T; DOF], qd: &[T; DOF]) -> na::SVector<T, 6> {
                State::for_jdot_qdot(q).jdot_qdot(qd)
            }
            /// Whether the last three axes meet in one point (a spherical wrist); for a
            /// six-joint arm, `det_j11`, `det_j22`, `ik` and `ik_solver` then exist.
            pub const SPHERICAL_WRIST: bool = #spherical_wrist;
            #wrist_free
            #dyn_free

            /// The robot as a value implementing [`::dhgen::Arm`] (f64), for algorithms written
            /// once for every robot (inverse kinematics, planners, controllers).
            #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
            pub struct Model;

            /// The robot's kinematic structure: fixed transforms, joints (kinds, offsets,
            /// limits, armature, friction), link frames, mass properties and collision
            /// capsules. The numbers this module was generated from, for algorithms built on
            /// the structure (inverse kinematics, planning); see [`::dhgen::ChainRef`].
            pub const CHAIN: ::dhgen::ChainRef<'static> = #chain_const;

            impl ::dhgen::Arm for Model {
                type Dof = na::Const<DOF>;
                fn chain(&self) -> ::dhgen::ChainRef<'_> {
                    CHAIN
                }
                fn dof(&self) -> usize {
                    DOF
                }
                fn dim(&self) -> na::Const<DOF> {
                    na::Const
                }
                fn fk(&self, q: &na::SVector<f64, DOF>) -> na::Isometry3<f64> {
                    State::for_fk(&(*q).into()).fk()
                }
                fn frames_into(&self, q: &na::SVector<f64, DOF>, out: &mut [na::Isometry3<f64>]) {
                    for (o, f) in out.iter_mut().zip(State::for_frames(&(*q).into()).frames()) {
                        *o = f;
                    }
                }
                fn jacobian(&self, q: &na::SVector<f64, DOF>) -> na::SMatrix<f64, 6, DOF> {
                    State::for_jacobian(&(*q).into()).jacobian()
                }
            }
            #arm_dynamics

            fn isometry<T: ::dhgen::Real>(m: &na::Matrix4<T>) -> na::Isometry3<T> {
                let r = na::Rotation3::from_matrix_unchecked(m.fixed_view::<3, 3>(0, 0).into_owned());
                na::Isometry3::from_parts(
                    na::Translation3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)]),
                    na::UnitQuaternion::from_rotation_matrix(&r),
                )
            }

            #sign_fn
        }
    };
    Generated {
        tokens: unsuffix_indices(tokens),
        ops: b.ops,
    }
}

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
fn chain_literal(chain: ChainRef<'_>) -> TokenStream {
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

fn frame_outputs(f: &dhgen_model::Frame<E>, out: TokenStream) -> Vec<Output> {
    let mut v = Vec::new();
    for r in 0..3 {
        for c in 0..3 {
            v.push(Output {
                target: quote!(#out[(#r, #c)]),
                value: f.r[r][c].clone(),
            });
        }
        v.push(Output {
            target: quote!(#out[(#r, 3)]),
            value: f.p[r].clone(),
        });
    }
    v
}

fn matrix_outputs(m: &[E], n: usize) -> Vec<Output> {
    (0..n * n)
        .map(|idx| {
            let (r, c) = (idx / n, idx % n);
            Output {
                target: quote!(out[(#r, #c)]),
                value: m[idx].clone(),
            }
        })
        .collect()
}

fn vector_outputs(v: &[E]) -> Vec<Output> {
    v.iter()
        .enumerate()
        .map(|(i, e)| Output {
            target: quote!(out[#i]),
            value: e.clone(),
        })
        .collect()
}

/// The body of a `State` constructor preparing the given joints (all when `None`).
fn state_new(chain: ChainRef<'_>, joints: Option<&[usize]>) -> TokenStream {
    let used = |j: &usize| joints.is_none_or(|js| js.contains(j));
    let lines = chain
        .bodies
        .iter()
        .enumerate()
        .filter(|(j, _)| used(j))
        .map(|(j, b)| {
            let value = if b.offset == 0.0 {
                quote!(q[#j])
            } else {
                let k = constant(b.offset);
                quote!(q[#j] + #k)
            };
            match b.joint {
                JointKind::Revolute => {
                    quote!(let (sj, cj) = ::dhgen::Real::sincos(#value); s[#j] = sj; c[#j] = cj;)
                }
                JointKind::Prismatic => quote!(d[#j] = #value;),
            }
        });
    // Only arrays that some line fills are declared `mut` (no warnings in user crates).
    let any = |kind: JointKind| {
        chain
            .bodies
            .iter()
            .enumerate()
            .any(|(j, b)| used(&j) && b.joint == kind)
    };
    let trig = if any(JointKind::Revolute) {
        quote!(let mut c = [T::zero(); DOF]; let mut s = [T::zero(); DOF];)
    } else {
        quote!(let c = [T::zero(); DOF]; let s = [T::zero(); DOF];)
    };
    let lengths = if any(JointKind::Prismatic) {
        quote!(let mut d = [T::zero(); DOF];)
    } else {
        quote!(let d = [T::zero(); DOF];)
    };
    quote! {
        #trig
        #lengths
        #(#lines)*
        State { c, s, d }
    }
}

fn coulomb(chain: ChainRef<'_>) -> TokenStream {
    let lines = chain
        .bodies
        .iter()
        .enumerate()
        .filter(|(_, b)| b.friction.coulomb != 0.0)
        .map(|(j, b)| {
            let k = constant(b.friction.coulomb);
            quote!(tau[#j] += #k * sign(qd[#j]);)
        });
    quote!(#(#lines)*)
}

/// Unrolled `D x = rhs` by Cholesky, `None` on a non-positive pivot, with its operation
/// count (the `n` subtractions forming `rhs = τ − bias` included).
fn cholesky_solve(n: usize) -> (TokenStream, OpCount) {
    // Per pivot j: j squares subtracted, one sqrt, one reciprocal; per entry below it, j
    // products subtracted and one scaling; forward and back substitution: a row's products
    // and one scaling each.
    let mut ops = OpCount {
        add: n,
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
            if !(#ljj > T::zero()) {
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
    let xs = (0..n).map(x);
    let solve = quote! {
        #(#s)*
        Some(na::SVector::<T, DOF>::from([#(#xs),*]))
    };
    (solve, ops)
}

/// `1usize` → `1`: quote writes integer literals with their type suffix, which only adds
/// noise to indices in printed code.
fn unsuffix_indices(tokens: TokenStream) -> TokenStream {
    use proc_macro2::{Group, Literal, TokenTree};
    tokens
        .into_iter()
        .map(|t| match t {
            TokenTree::Group(g) => {
                let mut ng = Group::new(g.delimiter(), unsuffix_indices(g.stream()));
                ng.set_span(g.span());
                TokenTree::Group(ng)
            }
            TokenTree::Literal(l) => match l
                .to_string()
                .strip_suffix("usize")
                .and_then(|d| d.parse::<usize>().ok())
            {
                Some(v) => {
                    let mut nl = Literal::usize_unsuffixed(v);
                    nl.set_span(l.span());
                    TokenTree::Literal(nl)
                }
                None => TokenTree::Literal(l),
            },
            other => other,
        })
        .collect()
}
