//! The generated module, driven by the table of [`quantities`]: for each quantity a `State`
//! method, a preparer computing only the joints it reads, a free function, and the trait
//! method it implements; around them the module's constants (its structure included), the
//! `State` type and the trait impls.
//!
//! One file per concern: [`quantities`] (what is generated), [`shape`] (return types and
//! where each scalar goes), [`state`] (the per-configuration sines and cosines),
//! [`cholesky`] (forward dynamics' solve), [`structure`] (the `CHAIN` constant), [`tidy`]
//! (printed code that reads well); the builder that turns entries into items is here.

pub mod cholesky;
pub mod quantities;
pub mod shape;
pub mod state;
pub mod structure;
pub mod tidy;

use crate::derive::{Derivation, christoffel, derivatives, inertia, newton_euler, regressor};
use crate::emit::{self, Output};
use crate::graph::{E, OpCount, SharedGraph, Sym};
use crate::limits::Unsupported;
use dhgen_description::parameters::{BaseParameters, Column};
use dhgen_description::{ChainRef, JointKind, RobotModel};
use proc_macro2::{Ident, Span, TokenStream};
use quantities::{ArmMethod, Availability, BUILD_ORDER, Input, Key, Made, Quantity, Trait};
use quote::{format_ident, quote};
use shape::Shape;
use std::cell::OnceCell;
use std::collections::HashMap;

/// The generated module and what it costs.
pub struct Generated {
    /// The `mod name { ... }` item.
    pub tokens: TokenStream,
    /// Arithmetic operations per generated function.
    pub ops: Vec<(String, OpCount)>,
    /// The functions that call the runtime path's loops in `dhgen::recursive` instead of
    /// straight-line code (see [`LOOPED_ABOVE`] and [`LOOP_D_ABOVE_PER_JOINT`]), so have no
    /// count in `ops`.
    pub looped: Vec<String>,
}

/// A derivation of C(q, q̇) the module may emit ([`Context::coriolis_choice`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CoriolisCandidate {
    /// C contracted symbolically from the normal forms of the Christoffel symbols.
    FromSymbols,
    /// The O(n²) Coriolis recursion on dual numbers.
    DualRecursion,
    /// Echeandia and Wensing's O(n²) algorithm.
    Spatial,
    /// The Christoffel symbols emitted, and contracted with q̇ at run time (2n³ operations
    /// beyond the symbols).
    SymbolsAtRunTime,
}

impl CoriolisCandidate {
    /// The candidates in order of preference: of equal cost, the first wins.
    pub const BY_PREFERENCE: [CoriolisCandidate; 4] = [
        CoriolisCandidate::FromSymbols,
        CoriolisCandidate::DualRecursion,
        CoriolisCandidate::Spatial,
        CoriolisCandidate::SymbolsAtRunTime,
    ];
}

/// The most joints for which D(q), C(q, q̇), c_ijk and the Cholesky factorisation may be
/// emitted as straight-line code. Above, forward dynamics' factorisation is emitted as loops
/// (`cholesky`), D, C (with a payload too) and c_ijk call the runtime path's loops
/// (`dhgen::recursive`), and Ḋ = C + Cᵀ and Cᵀq̇ are taken from that C: a general arm's
/// straight-line code for them outgrows the instruction cache there (at 16 joints generated D
/// took 0.78× the runtime's time), and the loops make the module as fast as the runtime path
/// by construction. The measurements: docs/experiments.md, "Thresholds of the loops".
pub const LOOPED_ABOVE: usize = 12;

/// Up to [`LOOPED_ABOVE`] joints, D(q) calls the loops when its cheapest derivation costs
/// more than this many operations per joint: the loops, sines and cosines included, take
/// about as long as 240 operations of straight-line D per joint (0.23–0.33 ns an operation on
/// the default x86-64 target). docs/experiments.md, "Thresholds of the loops".
pub const LOOP_D_ABOVE_PER_JOINT: usize = 240;

/// Up to [`LOOPED_ABOVE`] joints, C(q, q̇) calls the loops when its cheapest derivation costs
/// more than this many operations per joint (the loops take about as long as 375 operations
/// of straight-line C per joint, where the code's size makes placement decide).
pub const LOOP_C_ABOVE_PER_JOINT: usize = 375;

/// Up to [`LOOPED_ABOVE`] joints, C(q, q̇) with a payload calls the loop (as C does, with the
/// payload's inertia added to the last body) where C does, and where its own straight-line
/// code costs more than this many operations per joint: it runs slower per operation than C's
/// (general 10: 1,162 ns against the runtime C's 919).
pub const LOOP_C_WITH_PAYLOAD_ABOVE_PER_JOINT: usize = 350;

/// Up to [`LOOPED_ABOVE`] joints, the Christoffel symbols call the runtime's loop
/// (`dhgen::recursive::christoffel`) where their straight-line code costs more than this many
/// operations per n³ (n the joints): straight-line symbols take 0.18–0.20 ns an operation,
/// the loop about 2 ns per n³.
pub const LOOP_CHRISTOFFEL_ABOVE_PER_CUBE: usize = 10;

/// What a module holds beyond the default set of functions, chosen where it is generated
/// (`robot!(pub mod arm = "arm.toml", derivatives)`, `dhgen emit --derivatives`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Options {
    /// The derivatives of the dynamics (`inverse_dynamics_derivatives`,
    /// `forward_dynamics_derivatives`, `mass_matrix_inverse`, `mass_matrix_rate`,
    /// `coriolis_transpose_qd`): about 2.5× the generated code of a 7-joint arm, so only on
    /// request.
    pub derivatives: bool,
    /// The joint torque regressor and the base parameters (`regressor`, `base_regressor`,
    /// `base_parameters` and the `PARAMETERS` and `BASE_*` constants): for identification,
    /// about the generated code of τ ten times over, so only on request.
    pub regressor: bool,
}

impl Options {
    /// The option words `robot!` accepts after the description, with what each adds.
    pub const WORDS: &'static [(&'static str, &'static str)] = &[
        (
            "derivatives",
            "∂τ/∂q, ∂τ/∂q̇, ∂q̈/∂q, ∂q̈/∂q̇, D⁻¹, Ḋ(q, q̇) and Cᵀ(q, q̇) q̇",
        ),
        (
            "regressor",
            "the regressor Y(q, q̇, q̈), the base regressor and the base parameters",
        ),
    ];

    /// Turns on the option named `word`; `false` when there is none of that name.
    pub fn set(&mut self, word: &str) -> bool {
        match word {
            "derivatives" => self.derivatives = true,
            "regressor" => self.regressor = true,
            _ => return false,
        }
        true
    }
}

/// What every quantity's derivation may read: the structure and the derivations shared
/// between quantities (the normal forms, the Christoffel symbols), each built once.
pub struct Context<'c> {
    /// The robot's description.
    pub model: &'c RobotModel,
    /// The robot's structure.
    pub chain: ChainRef<'c>,
    /// The inertial parameters' columns (`dhgen_description::parameters`).
    pub columns: Vec<Column>,
    /// What the module holds beyond the default.
    pub options: Options,
    /// Its symbolic derivations.
    pub derivation: Derivation<'c>,
    christoffel: OnceCell<(SharedGraph, Vec<E>)>,
    mass_matrix: OnceCell<Option<(SharedGraph, Vec<E>)>>,
    coriolis: OnceCell<Vec<(SharedGraph, Vec<E>)>>,
    coriolis_choice: OnceCell<Option<CoriolisCandidate>>,
    assembled: OnceCell<Option<(SharedGraph, Vec<E>)>>,
    tau_derivatives: OnceCell<(SharedGraph, Vec<E>)>,
    with_mass_matrix: OnceCell<Option<(SharedGraph, Vec<E>)>>,
    regressor: OnceCell<(SharedGraph, Vec<E>)>,
    base: OnceCell<BaseParameters>,
}

impl<'c> Context<'c> {
    fn new(model: &'c RobotModel, chain: ChainRef<'c>, options: Options) -> Self {
        Context {
            model,
            chain,
            columns: dhgen_description::parameters::columns(model),
            options,
            derivation: Derivation::new(chain),
            christoffel: OnceCell::new(),
            mass_matrix: OnceCell::new(),
            coriolis: OnceCell::new(),
            coriolis_choice: OnceCell::new(),
            assembled: OnceCell::new(),
            tau_derivatives: OnceCell::new(),
            with_mass_matrix: OnceCell::new(),
            regressor: OnceCell::new(),
            base: OnceCell::new(),
        }
    }

    /// The regressor `Y` without its Coulomb columns, row-major, built once for `regressor`
    /// and `base_regressor`.
    pub fn regressor(&self) -> &(SharedGraph, Vec<E>) {
        self.regressor.get_or_init(|| {
            let graph = SharedGraph::default();
            let y = regressor::regressor(self.chain, &self.columns, &graph);
            (graph, y)
        })
    }

    /// The base parameters, found once.
    pub fn base_parameters(&self) -> &BaseParameters {
        self.base
            .get_or_init(|| regressor::base_parameters(self.model))
    }

    /// The cheapest derivation of the Christoffel symbols, `(i·n + j)·n + k`.
    pub fn christoffel(&self) -> &(SharedGraph, Vec<E>) {
        self.christoffel
            .get_or_init(|| christoffel::christoffel(&self.derivation))
    }

    /// The derivations of C(q, q̇) (row-major), each built once and shared by the quantities
    /// that start from C (which take the cheapest, the first of equal cost): the O(n²)
    /// recursion on dual numbers, C from the Christoffel symbols in their shared graph, and
    /// Echeandia and Wensing's O(n²) algorithm (the cheapest of its forms: in joint frames or
    /// in one frame's coordinates). [`coriolis_derivation`](Self::coriolis_derivation) names
    /// them.
    pub fn coriolis_derivations(&self) -> &[(SharedGraph, Vec<E>)] {
        self.coriolis.get_or_init(|| {
            let (graph, c) = self.christoffel();
            let direct = christoffel::coriolis_from(self.chain.dof(), graph, c);
            [
                christoffel::coriolis_recursive(self.chain),
                (graph.clone(), direct),
                christoffel::coriolis_spatial(self.chain),
            ]
            .into_iter()
            .map(|(graph, c)| {
                let c = crate::derive::without_ignored_joints(self.chain, &graph, &c);
                (graph, c)
            })
            .collect()
        })
    }

    /// τ assembled from the normal forms ([`newton_euler::assembled`]), where they are small,
    /// built once: a candidate for τ and, differentiated, for its derivatives.
    pub fn assembled_inverse_dynamics(&self) -> Option<&(SharedGraph, Vec<E>)> {
        self.assembled
            .get_or_init(|| newton_euler::assembled(&self.derivation))
            .as_ref()
    }

    /// The cheapest derivation of `[∂τ/∂q, ∂τ/∂q̇]` (each row-major), built once: for
    /// `inverse_dynamics_derivatives`, and for `forward_dynamics_derivatives`, which skips
    /// the columns that are structurally zero in its products.
    pub fn inverse_dynamics_derivatives(&self) -> &(SharedGraph, Vec<E>) {
        self.tau_derivatives.get_or_init(|| {
            derivatives::inverse_dynamics_derivatives(
                &self.derivation,
                self.coriolis_derivations(),
                self.assembled_inverse_dynamics(),
            )
        })
    }

    /// `[∂τ/∂q, ∂τ/∂q̇, D]` (each row-major) in the graph of ∂τ's derivation, D by
    /// [`derivatives::mass_matrix_beside`], where D costs fewer operations there than its own
    /// cheapest derivation (`forward_dynamics_derivatives` then factorises that D); `None`
    /// where it does not, or where D calls the runtime's loops.
    pub fn derivatives_with_mass_matrix(&self) -> Option<&(SharedGraph, Vec<E>)> {
        self.with_mass_matrix
            .get_or_init(|| {
                let (own_graph, own) = self.mass_matrix()?;
                let (graph, outs) = self.inverse_dynamics_derivatives();
                let (d, added) = derivatives::mass_matrix_beside(&self.derivation, graph, outs);
                (added < crate::graph::cost(own_graph, own)).then(|| {
                    let mut all = outs.clone();
                    all.extend(d);
                    (graph.clone(), all)
                })
            })
            .as_ref()
    }

    /// True above [`LOOPED_ABOVE`] joints: D and C call the runtime path's loops.
    pub fn looped(&self) -> bool {
        self.chain.dof() > LOOPED_ABOVE
    }

    /// The derivation of C(q, q̇) that is `candidate`, where it is a derivation (the symbols
    /// contracted at run time are the symbols' own).
    pub fn coriolis_derivation(
        &self,
        candidate: CoriolisCandidate,
    ) -> Option<&(SharedGraph, Vec<E>)> {
        let all = self.coriolis_derivations();
        match candidate {
            CoriolisCandidate::DualRecursion => Some(&all[0]),
            CoriolisCandidate::FromSymbols => Some(&all[1]),
            CoriolisCandidate::Spatial => Some(&all[2]),
            CoriolisCandidate::SymbolsAtRunTime => None,
        }
    }

    /// The derivation `coriolis` emits: the cheapest candidate, the first of equal cost in
    /// [`CoriolisCandidate::BY_PREFERENCE`]; `None` where it calls the runtime's loop instead
    /// (above [`LOOPED_ABOVE`] joints, or where the cheapest costs more than the loop,
    /// [`LOOP_C_ABOVE_PER_JOINT`] per joint). C with a payload follows it. Decided once.
    pub fn coriolis_choice(&self) -> Option<CoriolisCandidate> {
        *self.coriolis_choice.get_or_init(|| {
            if self.looped() {
                return None;
            }
            let n = self.chain.dof();
            let cost = |candidate| match self.coriolis_derivation(candidate) {
                Some((graph, c)) => crate::graph::cost(graph, c),
                None => {
                    let (graph, c) = self.christoffel();
                    crate::graph::cost(graph, c) + 2 * n * n * n
                }
            };
            let best = CoriolisCandidate::BY_PREFERENCE
                .into_iter()
                .map(|candidate| (cost(candidate), candidate))
                .min_by_key(|&(cost, _)| cost)?;
            (best.0 <= LOOP_C_ABOVE_PER_JOINT * n).then_some(best.1)
        })
    }

    /// The cheapest derivation of D(q), built once; `None` where the module calls the
    /// runtime's loops for it instead (above [`LOOPED_ABOVE`] joints, or where it costs more
    /// than [`LOOP_D_ABOVE_PER_JOINT`] operations per joint).
    pub fn mass_matrix(&self) -> Option<&(SharedGraph, Vec<E>)> {
        self.mass_matrix
            .get_or_init(|| {
                if self.looped() {
                    return None;
                }
                let (graph, d) = inertia::mass_matrix(&self.derivation);
                let ops = crate::graph::cost(&graph, &d);
                (ops <= LOOP_D_ABOVE_PER_JOINT * self.chain.dof()).then_some((graph, d))
            })
            .as_ref()
    }

    /// Coulomb friction added to `tau` (empty without Coulomb friction).
    pub fn coulomb(&self) -> TokenStream {
        state::coulomb(self)
    }

    fn available(&self, a: Availability) -> bool {
        match a {
            Availability::Always => true,
            Availability::Dynamics => self.chain.has_dynamics(),
            Availability::Derivatives => self.options.derivatives && self.chain.has_dynamics(),
            Availability::DerivativesWithMassMatrix => {
                self.available(Availability::Derivatives)
                    && self.derivatives_with_mass_matrix().is_some()
            }
            Availability::Regressor => self.options.regressor && self.chain.has_dynamics(),
            Availability::DecoupledWrist => {
                crate::derive::singularity::decoupled_determinants(self.chain).is_some()
            }
        }
    }
}

/// The doc text of a generated module, the same for `robot!` and `dhgen emit`.
pub fn module_doc(model: &RobotModel) -> String {
    match &model.description {
        Some(d) => format!("{d} ({}-DOF, generated by `dhgen::robot!`).", model.dof()),
        None => format!(
            "Robot `{}` ({}-DOF, generated by `dhgen::robot!`).",
            model.name,
            model.dof()
        ),
    }
}

/// Operation counts of every function generated for `model`.
///
/// # Errors
/// [`Unsupported`] when the generator does not take the description (see [`generate`]).
pub fn op_counts(model: &RobotModel) -> Result<Vec<(String, OpCount)>, Unsupported> {
    op_counts_with(model, Options::default())
}

/// [`op_counts`] with [`Options`].
///
/// # Errors
/// As [`generate`].
pub fn op_counts_with(
    model: &RobotModel,
    options: Options,
) -> Result<Vec<(String, OpCount)>, Unsupported> {
    let name = Ident::new("robot", Span::call_site());
    Ok(generate_with(model, TokenStream::new(), &name, options)?.ops)
}

/// The items the table makes, collected in module order.
#[derive(Default)]
struct Items {
    methods: Vec<TokenStream>,
    /// The `batch` submodule's functions.
    batch: Vec<TokenStream>,
    private: Vec<TokenStream>,
    preparers: Vec<TokenStream>,
    free: Vec<TokenStream>,
    arm: Vec<TokenStream>,
    dynamics: Vec<TokenStream>,
    ops: Vec<(String, OpCount)>,
    looped: Vec<String>,
    /// The joints each quantity made so far reads.
    joints: HashMap<Key, Vec<usize>>,
}

/// Whether `body` names `input` anywhere (in any group): an input a function does not read
/// (q̇ in C(q, q̇) of a one-joint arm, which is zero) is bound to `_` instead, so that the
/// emitted file stays free of unused-variable warnings.
fn reads(body: &TokenStream, input: &Ident) -> bool {
    body.clone().into_iter().any(|tree| match tree {
        proc_macro2::TokenTree::Ident(i) => &i == input,
        proc_macro2::TokenTree::Group(g) => reads(&g.stream(), input),
        _ => false,
    })
}

fn idents(inputs: &[Input]) -> Vec<Ident> {
    inputs
        .iter()
        .map(|i| format_ident!("{}", i.name()))
        .collect()
}

/// The type of an input as the private methods and parts take it: a joint vector
/// `&[T; DOF]`, or the payload's `&[T; 10]`.
fn array_ty(name: &str) -> TokenStream {
    if name == Input::Payload.name() {
        quote!(&[T; 10])
    } else {
        quote!(&[T; DOF])
    }
}

impl Items {
    /// Makes one quantity: its `State` method (and parts), preparer, free function and
    /// trait method.
    fn add(&mut self, cx: &Context<'_>, q: &Quantity) {
        let name = format_ident!("{}", q.name);
        let t = quote!(T);
        let ty = q.shape.ty(&t);
        let inputs = idents(q.inputs);
        let body = match (q.make)(cx) {
            Made::Derived(graph, exprs) => self.straight_line(cx, q, &graph, exprs, None),
            Made::Staged(graph, exprs, late) => {
                let body = self.straight_line(cx, q, &graph, exprs, Some(late));
                if !q.public {
                    // Only its staged method (`<name>_then`) is called.
                    return;
                }
                body
            }
            Made::Looped(body) => {
                self.joints.insert(q.key, (0..cx.chain.dof()).collect());
                self.looped.push(q.name.to_string());
                body
            }
            Made::Composed { body, reads, ops } => {
                debug_assert!(
                    reads.iter().all(|r| q.reads.contains(r)),
                    "{} reads {reads:?}",
                    q.name
                );
                // Made before it by BUILD_ORDER; a read unavailable for this robot is a fault
                // of the table that the catalogue's expansion in the tests finds.
                let mut joints: Vec<usize> = reads
                    .iter()
                    .flat_map(|r| {
                        self.joints
                            .get(r)
                            .unwrap_or_else(|| panic!("{} reads {}, not made", q.name, r.name()))
                            .iter()
                            .copied()
                    })
                    .collect();
                joints.sort_unstable();
                joints.dedup();
                self.joints.insert(q.key, joints);
                if let Some((what, count)) = ops {
                    self.ops.push((what.to_string(), count));
                } else if q.public
                    && reads
                        .iter()
                        .all(|r| self.looped.iter().any(|l| l == r.name()))
                {
                    // Arithmetic of its own aside, the loops it calls (Ḋ = C + Cᵀ).
                    self.looped.push(q.name.to_string());
                }
                body
            }
        };
        let unread: Vec<&Ident> = inputs.iter().filter(|i| !reads(&body, i)).collect();
        let body = quote! {
            #(let _ = #unread;)*
            #body
        };
        let array_tys: Vec<TokenStream> = q.inputs.iter().map(|i| array_ty(i.name())).collect();
        if !q.public {
            let params = quote!(#(#inputs: #array_tys,)*);
            self.private.push(quote! {
                fn #name(&self, #params) -> #ty {
                    #body
                }
            });
            return;
        }
        let doc = q.doc;
        let aliases = q.aliases.iter().map(|a| quote!(#[doc(alias = #a)]));
        let aliases = quote!(#(#aliases)*);
        let public_tys: Vec<TokenStream> = q
            .inputs
            .iter()
            .map(|i| {
                if i.is_joint_vector() {
                    quote!(&impl ::dhgen::__private::JointArray<T, DOF>)
                } else {
                    array_ty(i.name())
                }
            })
            .collect();
        let params = quote!(#(#inputs: #public_tys,)*);
        let joint_inputs: Vec<&Ident> = inputs
            .iter()
            .zip(q.inputs)
            .filter(|(n, i)| i.is_joint_vector() && !unread.contains(n))
            .map(|(n, _)| n)
            .collect();
        self.methods.push(quote! {
            #[doc = #doc]
            #aliases
            #[must_use]
            pub fn #name(&self, #params) -> #ty {
                #(let #joint_inputs = &#joint_inputs.to_array();)*
                #body
            }
        });
        let preparer = format_ident!("for_{}", q.name);
        let fill = state::fill(cx, Some(&self.joints[&q.key]));
        self.preparers.push(quote! {
            #[inline]
            fn #preparer(q: &impl ::dhgen::__private::JointArray<T, DOF>) -> Self {
                #fill
            }
        });
        self.free.push(quote! {
            #[doc = #doc]
            #aliases
            #[must_use]
            pub fn #name<T: ::dhgen::__private::Real>(q: &impl ::dhgen::__private::JointArray<T, DOF>, #params) -> #ty {
                State::#preparer(q).#name(#(#inputs),*)
            }
        });
        self.add_batch(q, &inputs);
        let f64_ty = q.shape.ty(&quote!(f64));
        let same = quote! {
            fn #name(&self, q: &na::SVector<f64, DOF>, #(#inputs: &na::SVector<f64, DOF>),*) -> #f64_ty {
                State::#preparer(q).#name(#(#inputs),*)
            }
        };
        match q.arm {
            None => {}
            Some(ArmMethod::Arm) => self.arm.push(same),
            Some(ArmMethod::Dynamics) => self.dynamics.push(same),
            Some(ArmMethod::Custom(Trait::Arm, tokens)) => self.arm.push(tokens()),
            Some(ArmMethod::Custom(Trait::ArmDynamics, tokens)) => self.dynamics.push(tokens()),
        }
    }

    /// The `batch` function of a public quantity whose value [`::dhgen::__private::batch::Unpack`] reads
    /// lane by lane (an `Option` from the lane-wise form: `forward_dynamics` is
    /// `forward_dynamics_lanes`, masked, and so are `mass_matrix_inverse` and
    /// `forward_dynamics_derivatives`). Joint vectors come one per configuration; a payload is
    /// one for all of them (the object the arm holds while a planner samples its motions),
    /// spread over every lane once per call.
    fn add_batch(&mut self, q: &Quantity, inputs: &[Ident]) {
        let t = quote!(T);
        let (name, ty, wrap) = match q.shape {
            Shape::OptionVector
            | Shape::OptionSquare
            | Shape::OptionSquareTriple
            | Shape::Terms
            | Shape::ToolTerms => {
                return;
            }
            Shape::VectorMask => (
                q.name.trim_end_matches("_lanes"),
                quote!(Option<na::SVector<T, DOF>>),
                true,
            ),
            Shape::SquareMask => (
                q.name.trim_end_matches("_lanes"),
                quote!(Option<na::SMatrix<T, DOF, DOF>>),
                true,
            ),
            Shape::SquareTripleMask => (
                q.name.trim_end_matches("_lanes"),
                quote!(
                    Option<(
                        na::SMatrix<T, DOF, DOF>,
                        na::SMatrix<T, DOF, DOF>,
                        na::SMatrix<T, DOF, DOF>,
                    )>
                ),
                true,
            ),
            shape => (q.name, shape.ty(&t), false),
        };
        let call = format_ident!("{}", q.name);
        let name = format_ident!("{}", name);
        let (joint, shared): (Vec<_>, Vec<_>) = inputs
            .iter()
            .zip(q.inputs)
            .partition(|(_, i)| i.is_joint_vector());
        let joint: Vec<&Ident> = joint.into_iter().map(|(n, _)| n).collect();
        let (shared, shared_tys): (Vec<&Ident>, Vec<TokenStream>) = shared
            .into_iter()
            .map(|(n, i)| (n, array_ty(i.name())))
            .unzip();
        let value = quote!(super::#call(q, #(#inputs),*));
        let value = if wrap {
            quote!({
                let (value, ok) = #value;
                ::dhgen::__private::batch::Masked(value, ok)
            })
        } else {
            value
        };
        let doc = format!(
            " [`{call}`](super::{call}) for each configuration: `out[c]` from `q[c]`{}{}, {} \
             configurations per call (`dhgen::batch`).",
            joint
                .iter()
                .map(|i| format!(", `{i}[c]`"))
                .collect::<String>(),
            shared
                .iter()
                .map(|i| format!(" and `{i}` (the same for every configuration)"))
                .collect::<String>(),
            "four `f64` or eight `f32`"
        );
        self.batch.push(quote! {
            #[doc = #doc]
            ///
            /// # Errors
            /// `LengthMismatch` (nothing written) unless every slice has `out.len()` entries.
            pub fn #name<T: ::dhgen::__private::batch::Lanes>(
                q: &[[T; DOF]],
                #(#joint: &[[T; DOF]],)*
                #(#shared: #shared_tys,)*
                out: &mut [#ty],
            ) -> Result<(), ::dhgen::__private::batch::LengthMismatch> {
                #(let #shared = &::dhgen::__private::batch::splat(#shared);)*
                ::dhgen::__private::batch::run([q, #(#joint),*], out, |[q, #(#joint),*]| #value)
            }
        });
    }

    /// The body of a derived quantity's method: its outputs computed inline when small,
    /// otherwise by private part methods called in turn, sharing values through a scratch
    /// array.
    ///
    /// With a `late` input ([`Made::Staged`]), the body calls a private method
    /// `<name>_then(&self, <other inputs>, late: impl FnOnce(&mut Out) -> [T; DOF], out: &mut
    /// Out) -> [T; DOF]`, which computes the outputs that do not read `late` into `out`, then
    /// `late` from them by the closure (which may overwrite what the later stage does not
    /// write: `forward_dynamics_derivatives` turns D into D⁻¹ in place), then the rest, and returns the value of `late` it
    /// used.
    fn straight_line(
        &mut self,
        cx: &Context<'_>,
        q: &Quantity,
        graph: &SharedGraph,
        exprs: Vec<E>,
        late: Option<Input>,
    ) -> TokenStream {
        let t = quote!(T);
        let outputs = |targets: Vec<TokenStream>| -> Vec<Output> {
            assert_eq!(
                targets.len(),
                exprs.len(),
                "{}: shape and derivation",
                q.name
            );
            targets
                .into_iter()
                .zip(exprs.iter().cloned())
                .map(|(target, value)| Output { target, value })
                .collect()
        };
        let mut ty = q.shape.ty(&t);
        let late_sym = |s: Sym| late.is_some_and(|i| emit::input_array(s) == Some(i.name()));
        let mut emitted = emit::emit_staged(
            graph,
            outputs(q.shape.targets(cx.chain.dof(), exprs.len())),
            late.is_some().then_some(&late_sym as &dyn Fn(Sym) -> bool),
        );
        // A scalar split into parts is passed between them as a one-element array.
        let scalar_in_parts = q.shape == Shape::Scalar && emitted.parts.len() > 1;
        if scalar_in_parts {
            ty = quote!([T; 1]);
            emitted = emit::emit(graph, outputs(vec![quote!(out[0])]));
        }
        let mut ops = emitted.ops;
        ops.sincos = emitted
            .joints
            .iter()
            .filter(|&&j| cx.chain.bodies[j].joint == JointKind::Revolute)
            .count();
        self.ops.push((q.name.to_string(), ops));
        self.joints.insert(q.key, emitted.joints.clone());
        let names: Vec<&str> = q.inputs.iter().map(|i| i.name()).collect();
        // Between the stages, the late input from the closure of the same name.
        let hook = late.map(|i| {
            let l = format_ident!("{}", i.name());
            assert!(
                emitted.part_inputs[..emitted.late_part]
                    .iter()
                    .all(|used| !used.contains(&i.name())),
                "{}: an early part reads {}",
                q.name,
                i.name()
            );
            quote!(let #l = &#l(&mut *out);)
        });
        let computed = if emitted.parts.len() == 1 || (hook.is_some() && emitted.parts.len() == 2) {
            // Inline, the stages (if any) in turn; values crossing them pass through `w`.
            let mut stmts = Vec::new();
            if emitted.part_uses.iter().any(|u| u.scratch) {
                let w = emitted.scratch;
                stmts.push(quote!(let mut w = [T::zero(); #w];));
            }
            for (i, part) in emitted.parts.iter().enumerate() {
                if i == emitted.late_part {
                    stmts.extend(hook.clone());
                }
                stmts.extend(part.iter().cloned());
            }
            quote!(#(#stmts)*)
        } else {
            let w = emitted.scratch.max(1);
            let mut calls = vec![quote!(let mut w = [T::zero(); #w];)];
            for (i, stmts) in emitted.parts.iter().enumerate() {
                if i == emitted.late_part {
                    calls.extend(hook.clone());
                }
                if stmts.is_empty() {
                    continue;
                }
                let part = format_ident!("{}_part{}", q.name, i);
                // Each part takes only the joint vectors it reads.
                let used: Vec<Ident> = names
                    .iter()
                    .filter(|n| emitted.part_inputs[i].contains(n))
                    .map(|n| format_ident!("{}", n))
                    .collect();
                let used_tys: Vec<TokenStream> = names
                    .iter()
                    .filter(|n| emitted.part_inputs[i].contains(n))
                    .map(|n| array_ty(n))
                    .collect();
                let u = emitted.part_uses[i];
                let out = format_ident!("{}", if u.out { "out" } else { "_out" });
                let scratch = format_ident!("{}", if u.scratch { "w" } else { "_w" });
                self.private.push(quote! {
                    #[inline(never)]
                    fn #part(&self, #(#used: #used_tys,)* #scratch: &mut [T; #w], #out: &mut #ty) {
                        #(#stmts)*
                    }
                });
                // The staged method has `out` by reference already.
                let out = if late.is_some() {
                    quote!(out)
                } else {
                    quote!(&mut out)
                };
                calls.push(quote!(self.#part(#(#used,)* &mut w, #out);));
            }
            quote!(#(#calls)*)
        };
        if let Some(late) = late {
            // The staged method, and the quantity's own body calling it with the late input
            // given.
            let l = format_ident!("{}", late.name());
            let then = format_ident!("{}_then", q.name);
            let early: Vec<Ident> = names
                .iter()
                .filter(|&&n| n != late.name())
                .map(|n| format_ident!("{}", n))
                .collect();
            let early_tys: Vec<TokenStream> =
                early.iter().map(|n| array_ty(&n.to_string())).collect();
            let unread: Vec<&Ident> = early.iter().filter(|i| !reads(&computed, i)).collect();
            let computed = quote! {
                #(let _ = #unread;)*
                #computed
            };
            let init = q
                .shape
                .init()
                .expect("a staged quantity has an initial value");
            self.private.push(quote! {
                #[inline]
                fn #then(
                    &self,
                    #(#early: #early_tys,)*
                    #l: impl FnOnce(&mut #ty) -> [T; DOF],
                    out: &mut #ty,
                ) -> [T; DOF] {
                    #computed
                    *#l
                }
            });
            return quote! {
                let mut out: #ty = #init;
                self.#then(#(#early,)* |_| *#l, &mut out);
                out
            };
        }
        // A scalar is assigned exactly once: declare it without a dead initial value.
        let (declare, value) = match q.shape.init() {
            _ if scalar_in_parts => (quote!(let mut out: #ty = [T::zero()];), quote!(out[0])),
            Some(init) => (quote!(let mut out: #ty = #init;), quote!(out)),
            None => (quote!(let out: #ty;), quote!(out)),
        };
        quote! {
            #declare
            #computed
            #value
        }
    }
}

/// Generates the module `vis mod name { ... }` for `model`.
///
/// # Errors
/// [`Unsupported`] for a description beyond what the generator takes
/// ([`limits`](crate::limits): too many joints, a non-finite constant).
pub fn generate(
    model: &RobotModel,
    vis: TokenStream,
    name: &Ident,
) -> Result<Generated, Unsupported> {
    generate_with(model, vis, name, Options::default())
}

/// [`generate`] with [`Options`].
///
/// # Errors
/// As [`generate`].
pub fn generate_with(
    model: &RobotModel,
    vis: TokenStream,
    name: &Ident,
    options: Options,
) -> Result<Generated, Unsupported> {
    let structure = model.chain();
    crate::limits::check(structure.view())?;
    let cx = Context::new(model, structure.view(), options);
    let chain = cx.chain;
    let n = chain.dof();
    let mut items = Items::default();
    for q in BUILD_ORDER
        .iter()
        .map(|k| k.quantity())
        .filter(|q| cx.available(q.available))
    {
        items.add(&cx, q);
    }
    let Items {
        methods,
        batch,
        private,
        preparers,
        free,
        arm,
        dynamics,
        ops,
        looped,
        ..
    } = items;

    let doc = module_doc(model);
    let robot_name = &model.name;
    let has_dynamics = chain.has_dynamics();
    let spherical_wrist = chain.spherical_wrist().is_ok();
    let chain_const = structure::chain_literal(chain);
    let state = state::definition(&cx);
    // Closed-form inverse kinematics where the structure decouples, solved at compile time.
    let ik = dhgen_kernel::closed_form::DecoupledIk::from_chain(chain)
        .ok()
        .map(|solver| {
            let solver = structure::ik_literal(&solver);
            quote! {
                /// The closed-form inverse kinematics solver of this arm (kinematic decoupling,
                /// section 4.3), precomputed from its structure when the module was generated.
                pub const IK: ::dhgen::__private::closed_form::DecoupledIk = #solver;
                /// All closed-form inverse kinematics solutions of `pose` (up to 8), each
                /// verified by forward kinematics; empty when the pose is unreachable.
                #[must_use]
                pub fn ik(pose: &na::Isometry3<f64>) -> ::dhgen::__private::closed_form::Solutions {
                    IK.solve(pose)
                }
            }
        });
    let terms = has_dynamics.then(|| {
        quote! {
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
    });
    let arm_dynamics = has_dynamics.then(|| {
        quote! {
            impl ::dhgen::__private::ArmDynamics for Robot {
                #(#dynamics)*
            }
        }
    });
    let parameters = cx
        .available(Availability::Regressor)
        .then(|| parameters(&cx));
    let tokens = quote! {
        #[doc = #doc]
        #[allow(clippy::all, clippy::pedantic, clippy::nursery)]
        #vis mod #name {
            use ::dhgen::__private::nalgebra as na;

            /// Number of joints.
            pub const DOF: usize = #n;
            /// The robot's name.
            pub const NAME: &str = #robot_name;
            /// Whether the description has mass properties (dynamics functions exist).
            pub const HAS_DYNAMICS: bool = #has_dynamics;
            /// Whether the last three axes meet in one point (a spherical wrist); for a
            /// six-joint arm, `det_j11` and `det_j22` then exist (and `IK` and `ik`, which
            /// also exist for arms with axes 2, 3, 4 parallel).
            pub const SPHERICAL_WRIST: bool = #spherical_wrist;
            /// The robot's kinematic structure: fixed transforms, joints (kinds, offsets,
            /// limits, armature, friction), link frames, mass properties and collision
            /// capsules. The numbers this module was generated from, for algorithms built on
            /// the structure (inverse kinematics, planning); see [`::dhgen::__private::ChainRef`].
            pub const CHAIN: ::dhgen::__private::ChainRef<'static> = #chain_const;

            #state

            impl<T: ::dhgen::__private::Real> State<T> {
                #(#methods)*
                #(#private)*
                #(#preparers)*
            }

            #(#free)*

            /// Every function above whose value is read lane by lane, for slices of
            /// configurations: evaluated on SIMD packs (`dhgen::batch`), each configuration's
            /// value equal to the scalar function's.
            pub mod batch {
                // `na`, `DOF` and the sizes of the outputs (this module's functions shadow
                // the scalar ones, which it calls as `super::name`).
                use super::*;
                #(#batch)*
            }
            #parameters
            #terms
            #ik

            /// The robot as a value implementing [`::dhgen::__private::Arm`] (and
            /// [`::dhgen::__private::ArmDynamics`] with mass properties), for `f64`: for algorithms
            /// written once for every robot (inverse kinematics, planners, controllers).
            #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
            pub struct Robot;

            impl ::dhgen::__private::Arm for Robot {
                type Dof = na::Const<DOF>;
                fn chain(&self) -> ::dhgen::__private::ChainRef<'_> {
                    CHAIN
                }
                fn dof(&self) -> usize {
                    DOF
                }
                fn dim(&self) -> na::Const<DOF> {
                    na::Const
                }
                #(#arm)*
            }
            #arm_dynamics

            fn isometry<T: ::dhgen::__private::Real>(m: &na::Matrix4<T>) -> na::Isometry3<T> {
                let r = na::Rotation3::from_matrix_unchecked(m.fixed_view::<3, 3>(0, 0).into_owned());
                na::Isometry3::from_parts(
                    na::Translation3::new(m[(0, 3)], m[(1, 3)], m[(2, 3)]),
                    na::UnitQuaternion::from_rotation_matrix(&r),
                )
            }

        }
    };
    Ok(Generated {
        tokens: tidy::unsuffix_indices(tokens),
        ops,
        looped,
    })
}

/// The inertial parameters' constants and `base_parameters(π)`.
fn parameters(cx: &Context<'_>) -> TokenStream {
    use crate::emit::{constant, float};
    let p = cx.columns.len();
    let names = dhgen_description::parameters::names(cx.model);
    let values = dhgen_description::parameters::values(cx.model)
        .expect("a model with dynamics has every link's mass properties")
        .into_iter()
        .map(float);
    let base = cx.base_parameters();
    let b = base.count();
    let columns = &base.independent;
    let rules = base.rules(&names);
    let sums = (0..b).map(|k| {
        let i = base.independent[k];
        let terms = base.dependent.iter().enumerate().filter_map(|(m, &d)| {
            let beta = base.beta[(k, m)];
            if beta == 0.0 {
                None
            } else if beta == 1.0 {
                Some(quote!(+ pi[#d]))
            } else if beta == -1.0 {
                Some(quote!(- pi[#d]))
            } else {
                let c = constant(beta);
                Some(quote!(+ #c * pi[#d]))
            }
        });
        quote!(pi[#i] #(#terms)*)
    });
    quote! {
        /// The number of inertial parameters: ten per link, then the armature and friction
        /// coefficients the description has (order and frames: `dhgen::parameters`).
        pub const PARAMETERS: usize = #p;
        /// The parameters' names, in order (`m1, mx1, ..., Izz1, m2, ...`, `Ia3`, `fv3`, `fc3`).
        pub const PARAMETER_NAMES: [&str; PARAMETERS] = [#(#names),*];
        /// The robot's own parameters π, as described: `regressor(..) · π` is
        /// `inverse_dynamics(..)`.
        pub const PARAMETER_VALUES: [f64; PARAMETERS] = [#(#values),*];
        /// The number of base parameters: combinations of the parameters that the dynamics
        /// determine (`dhgen::parameters` for the method).
        pub const BASE_PARAMETERS: usize = #b;
        /// The columns of `regressor` that `base_regressor` keeps (the independent parameters).
        pub const BASE_COLUMNS: [usize; BASE_PARAMETERS] = [#(#columns),*];
        /// Each base parameter as the regrouping of the parameters it stands for, by name.
        pub const BASE_PARAMETER_RULES: [&str; BASE_PARAMETERS] = [#(#rules),*];

        /// The base parameters π_b = π_i + β π_d of parameters `pi` (in the order of
        /// `PARAMETER_NAMES`): `base_regressor(..) · base_parameters(π)` is
        /// `regressor(..) · π`.
        #[must_use]
        pub fn base_parameters<T: ::dhgen::__private::Real>(pi: &[T; PARAMETERS]) -> [T; BASE_PARAMETERS] {
            [#(#sums),*]
        }
    }
}
