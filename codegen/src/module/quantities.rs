//! The table of generated quantities: one entry per function a generated module offers.
//!
//! An entry says everything the module needs about a quantity: its name, its one doc text
//! (used for the `State` method and the free function alike), the names other libraries give
//! it, its joint-vector inputs, what it returns, when it exists, how it is made (a symbolic
//! derivation emitted as straight-line code, or a composition of other entries), and which
//! `dhgen::Arm` / `dhgen::ArmDynamics` method it implements. Adding a quantity is one entry
//! here plus its derivation in [`crate::derive`].

use super::shape::Shape;
use super::{Context, cholesky};
use crate::derive::newton_euler::Acceleration;
use crate::derive::{
    center_of_mass, derivatives, energy, gravity, kinematics, newton_euler, payload, singularity,
};
use crate::graph::{E, SharedGraph};
use crate::poly::Poly;
use dhgen_description::parameters::Column;
use proc_macro2::TokenStream;
use quote::quote;

/// A joint-vector argument after `q`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Input {
    /// Joint velocities `qd`.
    Qd,
    /// Joint accelerations `qdd`.
    Qdd,
    /// Joint torques `tau`.
    Tau,
    /// A payload's ten inertial parameters `payload`.
    Payload,
}

impl Input {
    /// The parameter's name.
    pub fn name(self) -> &'static str {
        match self {
            Input::Qd => "qd",
            Input::Qdd => "qdd",
            Input::Tau => "tau",
            Input::Payload => "payload",
        }
    }

    /// True for a joint vector (`[T; DOF]`); false for the payload's `[T; 10]`.
    pub fn is_joint_vector(self) -> bool {
        self != Input::Payload
    }
}

/// When a quantity exists.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Availability {
    /// For every robot.
    Always,
    /// For robots with mass properties.
    Dynamics,
    /// For six-joint arms with a spherical wrist.
    DecoupledWrist,
    /// For robots with mass properties, when [`Options::derivatives`](super::Options) asks.
    Derivatives,
    /// As `Derivatives`, where D(q) is cheaper beside ∂τ than on its own
    /// ([`Context::derivatives_with_mass_matrix`](super::Context::derivatives_with_mass_matrix)).
    DerivativesWithMassMatrix,
    /// For robots with mass properties, when [`Options::regressor`](super::Options) asks.
    Regressor,
}

/// The key of each generated quantity, in the table's order ([`QUANTITIES`]`[key as usize]`
/// is its entry).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Key {
    /// `fk_matrix`.
    FkMatrix,
    /// `fk`.
    Fk,
    /// `frames_matrix`.
    FramesMatrix,
    /// `frames`.
    Frames,
    /// `jacobian`.
    Jacobian,
    /// `body_jacobian`.
    BodyJacobian,
    /// `jdot_qdot`.
    JdotQdot,
    /// `body_jdot_qdot`.
    BodyJdotQdot,
    /// `det_j11`.
    DetJ11,
    /// `det_j22`.
    DetJ22,
    /// `mass_matrix`.
    MassMatrix,
    /// `christoffel`.
    Christoffel,
    /// `coriolis`.
    Coriolis,
    /// `gravity`.
    Gravity,
    /// `inverse_dynamics_smooth`.
    InverseDynamicsSmooth,
    /// `inverse_dynamics`.
    InverseDynamics,
    /// `inverse_dynamics_with_payload_smooth`.
    InverseDynamicsWithPayloadSmooth,
    /// `inverse_dynamics_with_payload`.
    InverseDynamicsWithPayload,
    /// `bias_with_payload_smooth`.
    BiasWithPayloadSmooth,
    /// `bias_with_payload`.
    BiasWithPayload,
    /// `mass_matrix_with_payload`.
    MassMatrixWithPayload,
    /// `gravity_with_payload`.
    GravityWithPayload,
    /// `coriolis_with_payload`.
    CoriolisWithPayload,
    /// `regressor_smooth`.
    RegressorSmooth,
    /// `regressor`.
    Regressor,
    /// `base_regressor_smooth`.
    BaseRegressorSmooth,
    /// `base_regressor`.
    BaseRegressor,
    /// `bias_smooth`.
    BiasSmooth,
    /// `bias`.
    Bias,
    /// `forward_dynamics_lanes`.
    ForwardDynamicsLanes,
    /// `forward_dynamics`.
    ForwardDynamics,
    /// `forward_dynamics_with_payload_lanes`.
    ForwardDynamicsWithPayloadLanes,
    /// `forward_dynamics_with_payload`.
    ForwardDynamicsWithPayload,
    /// `kinetic_energy`.
    KineticEnergy,
    /// `potential_energy`.
    PotentialEnergy,
    /// `center_of_mass`.
    CenterOfMass,
    /// `center_of_mass_jacobian`.
    CenterOfMassJacobian,
    /// `kinetic_energy_with_payload`.
    KineticEnergyWithPayload,
    /// `potential_energy_with_payload`.
    PotentialEnergyWithPayload,
    /// `inverse_dynamics_derivatives`.
    InverseDynamicsDerivatives,
    /// `inverse_dynamics_derivatives_with_payload`.
    InverseDynamicsDerivativesWithPayload,
    /// `mass_matrix_rate`.
    MassMatrixRate,
    /// `coriolis_transpose_qd`.
    CoriolisTransposeQd,
    /// `mass_matrix_inverse_lanes`.
    MassMatrixInverseLanes,
    /// `mass_matrix_inverse`.
    MassMatrixInverse,
    /// `forward_dynamics_terms`.
    ForwardDynamicsTerms,
    /// `forward_dynamics_derivatives_lanes`.
    ForwardDynamicsDerivativesLanes,
    /// `forward_dynamics_derivatives`.
    ForwardDynamicsDerivatives,
    /// `forward_dynamics_derivatives_with_payload_lanes`.
    ForwardDynamicsDerivativesWithPayloadLanes,
    /// `forward_dynamics_derivatives_with_payload`.
    ForwardDynamicsDerivativesWithPayload,
    /// `terms`.
    Terms,
    /// `tool_terms`.
    ToolTerms,
}

impl Key {
    /// The number of quantities.
    pub const COUNT: usize = Key::ToolTerms as usize + 1;

    /// The table entry of this quantity.
    pub const fn quantity(self) -> &'static Quantity {
        &QUANTITIES[self as usize]
    }

    /// The generated function's name.
    pub const fn name(self) -> &'static str {
        self.quantity().name
    }
}

/// The order the module builds its quantities in: each after every entry it may read
/// ([`Quantity::reads`]), ties broken by the table's order (so a table written in build order,
/// as this one is, builds in its own order). Computed when the generator is compiled: a
/// cycle among the reads fails that compilation (`const` evaluation), as does a table whose
/// entries are not at their keys' places.
pub const BUILD_ORDER: [Key; Key::COUNT] = {
    let mut i = 0;
    while i < Key::COUNT {
        assert!(
            QUANTITIES[i].key as usize == i,
            "the table's entries must be in the order of their keys"
        );
        i += 1;
    }
    let mut placed = [false; Key::COUNT];
    let mut order = [Key::FkMatrix; Key::COUNT];
    let mut n = 0;
    while n < Key::COUNT {
        let mut next = None;
        let mut k = 0;
        while k < Key::COUNT && next.is_none() {
            if !placed[k] {
                let reads = QUANTITIES[k].reads;
                let mut ready = true;
                let mut r = 0;
                while r < reads.len() {
                    if !placed[reads[r] as usize] {
                        ready = false;
                    }
                    r += 1;
                }
                if ready {
                    next = Some(k);
                }
            }
            k += 1;
        }
        let Some(k) = next else {
            panic!("the quantity table's reads have a cycle");
        };
        placed[k] = true;
        order[n] = QUANTITIES[k].key;
        n += 1;
    }
    order
};

/// How a quantity is made.
pub enum Made {
    /// Straight-line code: the derivation's scalars, in the order of the quantity's shape.
    Derived(SharedGraph, Vec<E>),
    /// A method body built from other entries, named in `reads` (their joints are prepared).
    Composed {
        /// The body of the `State` method.
        body: TokenStream,
        /// The entries it calls (among its entry's [`Quantity::reads`]).
        reads: &'static [Key],
        /// Arithmetic of its own, reported under a name (the Cholesky solve).
        ops: Option<(&'static str, crate::OpCount)>,
    },
    /// A call of the runtime path's loop in `dhgen::recursive` (reading every joint): for
    /// arms of more than [`LOOPED_ABOVE`](super::LOOPED_ABOVE) joints, and where the loop
    /// takes less time than the cheapest derivation (see
    /// [`LOOP_D_ABOVE_PER_JOINT`](super::LOOP_D_ABOVE_PER_JOINT)).
    Looped(TokenStream),
    /// [`Derived`](Made::Derived) in two stages: the outputs that do not read the input first,
    /// then the input from a closure given them, then the rest (the quantity also gets a
    /// private `<name>_then` method taking that closure).
    Staged(SharedGraph, Vec<E>, Input),
}

/// One of the two traits a generated `Robot` implements.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Trait {
    /// `dhgen::Arm`.
    Arm,
    /// `dhgen::ArmDynamics`.
    ArmDynamics,
}

/// The trait method a quantity implements, for `f64` and nalgebra joint vectors.
#[derive(Clone, Copy)]
pub enum ArmMethod {
    /// `dhgen::Arm::<name>` with the quantity's own signature.
    Arm,
    /// `dhgen::ArmDynamics::<name>` with the quantity's own signature.
    Dynamics,
    /// A method of another form (writing into a buffer), of the trait given: its tokens.
    Custom(Trait, fn() -> TokenStream),
}

/// One generated quantity.
pub struct Quantity {
    /// Its key: its place in [`QUANTITIES`].
    pub key: Key,
    /// The `State` method, the free function and the trait method.
    pub name: &'static str,
    /// What it is: the doc text of the method and the free function.
    pub doc: &'static str,
    /// Its names in Pinocchio and the Robotics Toolbox (`#[doc(alias)]` on the generated
    /// function, the trait method and the runtime method alike; docs/names.md lists them).
    pub aliases: &'static [&'static str],
    /// Arguments after `q`.
    pub inputs: &'static [Input],
    /// What it returns.
    pub shape: Shape,
    /// When it exists.
    pub available: Availability,
    /// Part of the module's interface (a `State` method and a free function), or a private
    /// helper of other entries.
    pub public: bool,
    /// Every entry it may read, for any robot (a composition reads those among them it calls):
    /// what [`BUILD_ORDER`] is computed from.
    pub reads: &'static [Key],
    /// How it is made.
    pub make: fn(&Context<'_>) -> Made,
    /// The trait method it implements.
    pub arm: Option<ArmMethod>,
}

fn derived(graph: SharedGraph, exprs: Vec<E>) -> Made {
    Made::Derived(graph, exprs)
}

fn composed(body: TokenStream, reads: &'static [Key]) -> Made {
    Made::Composed {
        body,
        reads,
        ops: None,
    }
}

/// The straight-line part `call` (reading `reads`) bound to `var`, then `after`: what Coulomb
/// friction adds, which is not arithmetic (`sign`) and so comes after; `mut` only when there is
/// something to add.
fn then(var: TokenStream, call: TokenStream, after: TokenStream, reads: &'static [Key]) -> Made {
    let binding = if after.is_empty() {
        quote!(let #var)
    } else {
        quote!(let mut #var)
    };
    composed(
        quote! {
            #binding = #call;
            #after
            #var
        },
        reads,
    )
}

/// A smooth torque (`call`, reading `reads`) plus the joints' Coulomb friction.
fn with_coulomb(cx: &Context<'_>, call: TokenStream, reads: &'static [Key]) -> Made {
    then(quote!(tau), call, cx.coulomb(), reads)
}

/// A regressor's smooth part (`call`, reading `reads`) whose column `k` is the full
/// regressor's column `kept[k]`, with the Coulomb columns' `sign(q̇_i)` set.
fn with_coulomb_columns(
    cx: &Context<'_>,
    kept: impl IntoIterator<Item = usize>,
    call: TokenStream,
    reads: &'static [Key],
) -> Made {
    let signs = kept
        .into_iter()
        .enumerate()
        .filter_map(|(k, c)| match cx.columns[c] {
            Column::Coulomb(i) => {
                Some(quote!(y[(#i, #k)] = ::dhgen::__private::Real::sign(qd[#i]);))
            }
            _ => None,
        });
    then(quote!(y), call, quote!(#(#signs)*), reads)
}

/// The derivatives of forward dynamics: with the mask of the lanes where they are an answer
/// (`lanes`: `forward_dynamics_derivatives_lanes`, for SIMD packs), or as an `Option`
/// (`forward_dynamics_derivatives`). Two bodies rather than the `Option` from the masked
/// form, whose three n×n matrices would be copied once more on the way (Panda: 1.7 % more
/// instructions per call, PUMA 560: 2.7 %); both call the same staged terms. With `payload`,
/// those with a payload held by the tool (`*_with_payload`): D, g and the staged ∂τ with the
/// payload's parameters as inputs.
/// The form of a quantity that may fail lane by lane.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Answer {
    /// `(value, mask)`: the mask of the lanes where the value is an answer (the `_lanes`
    /// helpers, for SIMD packs).
    Lanes,
    /// `Option<value>`: `Some` when every lane is an answer.
    Option,
}

/// What the tool holds in a derivation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Held {
    /// Nothing: the arm's own dynamics.
    Nothing,
    /// A payload, whose ten parameters are an input (`*_with_payload`).
    Payload,
}

/// Whether a Cholesky solve reports its operations (once per module: every solve is the
/// same).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum SolveOps {
    /// Reported under `cholesky_solve`.
    Report,
    /// Already reported by another quantity.
    Reported,
}

fn forward_dynamics_derivatives(cx: &Context<'_>, answer: Answer, held: Held) -> Made {
    let lanes = answer == Answer::Lanes;
    let payload = held == Held::Payload;
    let n = cx.chain.dof();
    let joints = 0..n;
    // ½ viscous_j q̇_j where the joint has viscous friction.
    let viscous = super::state::friction_terms(cx, |f| 0.5 * f.viscous, |k, j| quote!(#k * qd[#j]));
    let coulomb = cx.coulomb();
    // The bias h from ∂τ/∂q̇ (`dqd`), which does not depend on q̈: the velocity terms
    // of τ are quadratic in q̇ (so Σ_j q̇_j ∂/∂q̇_j doubles them) and viscous friction
    // is linear, so h = g + ½ (∂τ/∂q̇ + diag(viscous)) q̇ + Coulomb; then q̈ = D⁻¹(τ − h).
    // Friction, if any, is added to the bias in place.
    let mutable = (!viscous.is_empty() || !coulomb.is_empty()).then(|| quote!(mut));
    let acceleration = quote! {
        let half = ::dhgen::__private::nalgebra::convert::<f64, T>(0.5);
        let #mutable tau: [T; DOF] = ::core::array::from_fn(|k| {
            let s = dqd
                .row(k)
                .iter()
                .zip(qd)
                .fold(T::zero(), |s, (&d, &v)| s + d * v);
            g[k] + half * s
        });
        #viscous
        #coulomb
        (inverse * (applied - na::SVector::<T, DOF>::from(tau))).into()
    };
    // Per column of ∂τ/∂q and of ∂τ/∂q̇, whether it may be non-zero (with a payload, every
    // column: it breaks the symmetries that zero some).
    let (_, e) = cx.inverse_dynamics_derivatives();
    let used = |half: usize| -> Vec<bool> {
        (0..n)
            .map(|m| {
                payload
                    || (0..n).any(|k| !matches!(e[half * n * n + k * n + m], E::K(x) if x == 0.0))
            })
            .collect()
    };
    let (used_q, used_qd) = (used(0), used(1));
    // −D⁻¹ X column by column, in place (column m of the product reads only column m
    // of X), in plain loops the compiler unrolls (40 % fewer instructions than
    // nalgebra's general product at 6 × 6), with fused multiply-adds; `used`: the
    // columns of X that may be non-zero (−D⁻¹ times a structurally zero column is
    // zero, and is not computed). Building the products where the result holds them
    // and D⁻¹ where D was leaves one copy, of the result.
    let products = quote! {
        let columns = &inverse.data.0;
        let minus_inverse_times = |x: &mut na::SMatrix<T, DOF, DOF>, used: [bool; DOF]| {
            for (x, _) in x.data.0.iter_mut().zip(used).filter(|(_, u)| *u) {
                let mut p = [T::zero(); DOF];
                for (column, &xk) in columns.iter().zip(&*x) {
                    for (o, &a) in p.iter_mut().zip(column) {
                        *o = ::dhgen::__private::Real::mul_add_fast(-a, xk, *o);
                    }
                }
                *x = p;
            }
        };
        minus_inverse_times(dq, [#(#used_q),*]);
        minus_inverse_times(dqd, [#(#used_qd),*]);
    };
    let finite = quote!(let ok = ok #(& ::dhgen::__private::Real::is_finite_lanes(qdd[#joints]))*;);
    // ∂τ/∂q, ∂τ/∂q̇ (and D, factorised between the stages, where it is cheaper beside
    // them) with q̈ computed between the stages.
    let (body, reads): (_, &'static [Key]) =
        if !payload && cx.derivatives_with_mass_matrix().is_some() {
            // Its entries need no check of their own: q̈ = D⁻¹(τ − h) is checked.
            let (inverse, _) = cholesky::inverse(n, cholesky::Check::Pivots);
            let finish = if lanes {
                quote!((terms, ok))
            } else {
                quote!(na::SimdBool::all(ok).then_some(terms))
            };
            (
                quote! {
                    // No lane is an answer until D is factored.
                    let mut factored = !::dhgen::__private::Real::is_finite_lanes(T::zero());
                    let mut terms = (zero(), zero(), zero());
                    let qdd = self.forward_dynamics_terms_then(qd, |(_, dqd, dm)| {
                        let (inverse, ok) = { #inverse };
                        // D⁻¹ where D was, for the result; q̈ from the local copy (read
                        // back from memory right after its stores, the Panda's q̈ took
                        // 40 % longer: the loads wait for the stores).
                        *dm = inverse;
                        factored = ok;
                        let inverse = &inverse;
                        #acceleration
                    }, &mut terms);
                    let ok = factored;
                    #finite
                    let (dq, dqd, inverse) = &mut terms;
                    #products
                    #finish
                },
                &[Key::ForwardDynamicsTerms, Key::Gravity],
            )
        } else {
            // D⁻¹ on its own, then ∂τ staged at q̈: of the arm, or with the payload's parameters
            // as inputs.
            let (inverse, staged, inputs, reads): (_, _, _, &'static [Key]) = if payload {
                let (inverse, _) = cholesky::inverse(n, cholesky::Check::PivotsAndFinite);
                (
                    quote!({
                        let dm = self.mass_matrix_with_payload(payload);
                        #inverse
                    }),
                    quote!(inverse_dynamics_derivatives_with_payload_then),
                    quote!(qd, payload),
                    &[
                        Key::MassMatrixWithPayload,
                        Key::GravityWithPayload,
                        Key::InverseDynamicsDerivativesWithPayload,
                    ],
                )
            } else {
                (
                    quote!(self.mass_matrix_inverse_lanes()),
                    quote!(inverse_dynamics_derivatives_then),
                    quote!(qd),
                    &[
                        Key::MassMatrixInverseLanes,
                        Key::Gravity,
                        Key::InverseDynamicsDerivatives,
                    ],
                )
            };
            let finish = if lanes {
                quote!(((terms.0, terms.1, inverse), ok))
            } else {
                quote!(na::SimdBool::all(ok).then(|| (terms.0, terms.1, inverse)))
            };
            (
                quote! {
                    let (inverse, ok) = #inverse;
                    let mut terms = (zero(), zero());
                    let qdd = self.#staged(#inputs, |(_, dqd)| {
                        let inverse = &inverse;
                        #acceleration
                    }, &mut terms);
                    #finite
                    let (dq, dqd) = &mut terms;
                    #products
                    #finish
                },
                reads,
            )
        };
    let g = if payload {
        quote!(self.gravity_with_payload(payload))
    } else {
        quote!(self.gravity())
    };
    composed(
        quote! {
            let g = #g;
            let applied = na::SVector::<T, DOF>::from(*tau);
            let zero = || na::SMatrix::<T, DOF, DOF>::from_data(na::ArrayStorage([[T::zero(); DOF]; DOF]));
            #body
        },
        reads,
    )
}

/// A lane-wise value and mask (`call`, reading `reads`) as an `Option`: `Some` when every
/// lane holds an answer (for a scalar, when it does).
fn all_lanes(call: TokenStream, reads: &'static [Key]) -> Made {
    composed(
        quote! {
            let (value, ok) = #call;
            na::SimdBool::all(ok).then_some(value)
        },
        reads,
    )
}

/// Forward dynamics `q̈ = D⁻¹(τ − h)` by the Cholesky solve, `operands` binding D and h
/// (`dm`, `h`: the values of `mass_matrix` and `bias`, reading `reads`); the solve's own
/// operations reported under `cholesky_solve` when `report` asks.
fn solved(
    cx: &Context<'_>,
    operands: TokenStream,
    reads: &'static [Key],
    report: SolveOps,
) -> Made {
    let (solve, ops) = cholesky::solve(cx.chain.dof());
    Made::Composed {
        body: quote! {
            #operands
            let rhs: [T; DOF] = ::core::array::from_fn(|i| tau[i] - h[i]);
            #solve
        },
        reads,
        ops: (report == SolveOps::Report).then_some(("cholesky_solve", ops)),
    }
}

fn frame_entries(f: &dhgen_description::Frame<E>) -> Vec<E> {
    (0..3)
        .flat_map(|r| {
            let mut row: Vec<E> = f.r[r].to_vec();
            row.push(f.p[r].clone());
            row
        })
        .collect()
}

fn wrist_determinant(cx: &Context<'_>, pick: fn(&(Poly, Poly)) -> &Poly) -> Made {
    let polys = singularity::decoupled_determinants(cx.chain)
        .expect("only made for arms with a decoupled wrist");
    let graph = SharedGraph::default();
    let e = crate::derive::polys_to_exprs(std::slice::from_ref(pick(&polys)), &graph, cx.chain);
    derived(graph, e)
}

/// The generated quantities, each after those it reads.
pub const QUANTITIES: [Quantity; Key::COUNT] = [
    Quantity {
        key: Key::FkMatrix,
        name: "fk_matrix",
        doc: "Pose of the tool frame in the world frame as a homogeneous matrix, \
              base · A1 ⋯ An · tool: the fast path (no conversion to a quaternion).",
        aliases: &["fkine", "forwardKinematics"],
        inputs: &[],
        shape: Shape::Homogeneous,
        available: Availability::Always,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, f) = kinematics::fk(cx.chain);
            derived(graph, frame_entries(&f))
        },
        arm: None,
    },
    Quantity {
        key: Key::Fk,
        name: "fk",
        doc: "Pose of the tool frame in the world frame, base · A1 ⋯ An · tool, as a \
              translation and a unit quaternion (from `fk_matrix`).",
        aliases: &["fkine", "forwardKinematics"],
        inputs: &[],
        shape: Shape::Pose,
        available: Availability::Always,
        public: true,
        reads: &[Key::FkMatrix],
        make: |_| composed(quote!(isometry(&self.fk_matrix())), &[Key::FkMatrix]),
        arm: Some(ArmMethod::Arm),
    },
    Quantity {
        key: Key::FramesMatrix,
        name: "frames_matrix",
        doc: "The link frames in the world frame (base applied, tool not) as homogeneous \
              matrices.",
        aliases: &["updateFramePlacements"],
        inputs: &[],
        shape: Shape::HomogeneousPerJoint,
        available: Availability::Always,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, frames) = kinematics::frames(cx.chain);
            derived(graph, frames.iter().flat_map(frame_entries).collect())
        },
        arm: None,
    },
    Quantity {
        key: Key::Frames,
        name: "frames",
        doc: "The link frames in the world frame (base applied, tool not).",
        aliases: &["updateFramePlacements"],
        inputs: &[],
        shape: Shape::PosePerJoint,
        available: Availability::Always,
        public: true,
        reads: &[Key::FramesMatrix],
        make: |_| {
            composed(
                quote! {
                    // A loop into an array, not `core::array::from_fn`: built by
                    // `from_fn` (or `map`), the six conversions took 6× the time in
                    // `f32` and 1.7× in `f64`.
                    let mut out = [na::Isometry3::identity(); DOF];
                    for (o, m) in out.iter_mut().zip(&self.frames_matrix()) {
                        *o = isometry(m);
                    }
                    out
                },
                &[Key::FramesMatrix],
            )
        },
        arm: Some(ArmMethod::Custom(Trait::Arm, || {
            quote! {
                fn frames_into(&self, q: &na::SVector<f64, DOF>, out: &mut [na::Isometry3<f64>]) {
                    for (o, f) in out.iter_mut().zip(State::for_frames(q).frames()) {
                        *o = f;
                    }
                }
            }
        })),
    },
    Quantity {
        key: Key::Jacobian,
        name: "jacobian",
        doc: "Geometric Jacobian of the tool frame origin in world axes, rows [v; ω].",
        aliases: &["jacob0", "computeJointJacobians", "getFrameJacobian"],
        inputs: &[],
        shape: Shape::Jacobian,
        available: Availability::Always,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, columns) = kinematics::jacobian(cx.chain);
            derived(graph, columns.into_iter().flatten().collect())
        },
        arm: Some(ArmMethod::Arm),
    },
    Quantity {
        key: Key::BodyJacobian,
        name: "body_jacobian",
        doc: "The tool frame's geometric Jacobian in the tool's own axes (the body Jacobian), \
              rows [v; ω]: it does not depend on the base.",
        aliases: &["jacobe"],
        inputs: &[],
        shape: Shape::Jacobian,
        available: Availability::Always,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, columns) = kinematics::body_jacobian(cx.chain);
            derived(graph, columns.into_iter().flatten().collect())
        },
        arm: Some(ArmMethod::Arm),
    },
    Quantity {
        key: Key::JdotQdot,
        name: "jdot_qdot",
        doc: "J̇(q, q̇) q̇ of the tool frame origin in world axes, rows [v; ω]: the tool's \
              acceleration at q̈ = 0.",
        aliases: &["jacob0_dot", "getFrameClassicalAcceleration"],
        inputs: &[Input::Qd],
        shape: Shape::Vector6,
        available: Availability::Always,
        public: true,
        reads: &[],
        make: |cx| {
            let graph = SharedGraph::default();
            let acc = kinematics::jdot_qdot(cx.chain, &graph);
            derived(graph, acc.to_vec())
        },
        arm: Some(ArmMethod::Arm),
    },
    Quantity {
        key: Key::BodyJdotQdot,
        name: "body_jdot_qdot",
        doc: "J̇_b(q, q̇) q̇ in the tool's own axes, rows [v; ω]: the rate of the tool's body \
              velocity (`body_jacobian` times q̇) at q̈ = 0, from the outward pass in joint frames.",
        aliases: &["getFrameJacobianTimeVariation"],
        inputs: &[Input::Qd],
        shape: Shape::Vector6,
        available: Availability::Always,
        public: true,
        reads: &[],
        make: |cx| {
            let graph = SharedGraph::default();
            let acc = kinematics::body_jdot_qdot(cx.chain, &graph);
            derived(graph, acc.to_vec())
        },
        arm: Some(ArmMethod::Arm),
    },
    Quantity {
        key: Key::DetJ11,
        name: "det_j11",
        doc: "det J11 (the Jacobian about the wrist centre): zero at arm singularities \
              (section 5.6.1).",
        aliases: &[],
        inputs: &[],
        shape: Shape::Scalar,
        available: Availability::DecoupledWrist,
        public: true,
        reads: &[],
        make: |cx| wrist_determinant(cx, |d| &d.0),
        arm: None,
    },
    Quantity {
        key: Key::DetJ22,
        name: "det_j22",
        doc: "det J22 = z3 · (z4 × z5): zero at wrist singularities (section 5.6.1).",
        aliases: &[],
        inputs: &[],
        shape: Shape::Scalar,
        available: Availability::DecoupledWrist,
        public: true,
        reads: &[],
        make: |cx| wrist_determinant(cx, |d| &d.1),
        arm: None,
    },
    Quantity {
        key: Key::MassMatrix,
        name: "mass_matrix",
        doc: "Joint-space inertia matrix D(q), armature (reflected motor inertia) included.",
        aliases: &["crba", "inertia"],
        inputs: &[],
        shape: Shape::Square,
        available: Availability::Dynamics,
        public: true,
        reads: &[],
        make: |cx| match cx.mass_matrix() {
            Some((graph, d)) => derived(graph.clone(), d.clone()),
            None => Made::Looped(quote!(::dhgen::__private::recursive::mass_matrix(
                CHAIN, &self.c, &self.s, &self.d
            ))),
        },
        arm: Some(ArmMethod::Dynamics),
    },
    Quantity {
        key: Key::Christoffel,
        name: "christoffel",
        doc: "Christoffel symbols: `[i][j][k]` = c_ijk = ½(∂d_kj/∂q_i + ∂d_ki/∂q_j − \
              ∂d_ij/∂q_k), k the equation index.",
        aliases: &[],
        inputs: &[],
        shape: Shape::Cube,
        available: Availability::Dynamics,
        public: true,
        reads: &[],
        make: |cx| {
            // Above `LOOPED_ABOVE` joints, the runtime's loops, as for D and C: the n³
            // symbols' straight-line code outgrows the instruction cache (general 20-joint
            // arm: 40 µs against the runtime's 29); below, where the straight-line code costs
            // more than the loop (`LOOP_CHRISTOFFEL_ABOVE_PER_CUBE`).
            let looped = || {
                Made::Looped(quote!(::dhgen::__private::recursive::christoffel(
                    CHAIN, &self.c, &self.s, &self.d
                )))
            };
            if cx.looped() {
                return looped();
            }
            let (graph, c) = cx.christoffel();
            let n = cx.chain.dof();
            if crate::graph::cost(graph, c) > super::LOOP_CHRISTOFFEL_ABOVE_PER_CUBE * n * n * n {
                return looped();
            }
            derived(graph.clone(), c.clone())
        },
        arm: Some(ArmMethod::Custom(Trait::ArmDynamics, || {
            quote! {
                fn christoffel_into(&self, q: &na::SVector<f64, DOF>, out: &mut [f64]) {
                    let c = State::for_christoffel(q).christoffel();
                    for (o, v) in out.iter_mut().zip(c.iter().flatten().flatten()) {
                        *o = *v;
                    }
                }
            }
        })),
    },
    Quantity {
        key: Key::Coriolis,
        name: "coriolis",
        doc: "Coriolis and centrifugal matrix C(q, q̇), C_kj = Σ_i c_ijk q̇_i (so Ḋ − 2C is \
              skew-symmetric).",
        aliases: &["computeCoriolisMatrix"],
        inputs: &[Input::Qd],
        shape: Shape::Square,
        available: Availability::Dynamics,
        public: true,
        reads: &[Key::Christoffel],
        make: |cx| {
            // Four candidates: C straight from the symbols (zero symbols fold away), the O(n²)
            // recursion on dual numbers, Echeandia and Wensing's O(n²) algorithm (the runtime
            // path's), or contracting the n³ symbols at run time; the fewest operations win.
            // Above `LOOPED_ABOVE` joints, or where the cheapest costs more than
            // `LOOP_C_ABOVE_PER_JOINT` operations per joint, the runtime's loop.
            let looped_coriolis = || {
                Made::Looped(quote!(::dhgen::__private::recursive::coriolis(
                    CHAIN, &self.c, &self.s, &self.d, qd
                )))
            };
            let Some(best) = cx.coriolis_choice() else {
                return looped_coriolis();
            };
            match cx.coriolis_derivation(best) {
                Some((graph, c)) => derived(graph.clone(), c.clone()),
                None => composed(
                    {
                        let zeros = Shape::Square.init();
                        quote! {
                            let c = self.christoffel();
                            let mut out: na::SMatrix<T, DOF, DOF> = #zeros;
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
                    },
                    &[Key::Christoffel],
                ),
            }
        },
        arm: Some(ArmMethod::Dynamics),
    },
    Quantity {
        key: Key::Gravity,
        name: "gravity",
        doc: "Gravity torques g(q): the torques that hold the arm still.",
        aliases: &["gravload", "computeGeneralizedGravity"],
        inputs: &[],
        shape: Shape::Vector,
        available: Availability::Dynamics,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, g) = gravity::gravity(&cx.derivation);
            derived(graph, g)
        },
        arm: Some(ArmMethod::Dynamics),
    },
    Quantity {
        key: Key::InverseDynamicsSmooth,
        name: "inverse_dynamics_smooth",
        doc: "",
        aliases: &[],
        inputs: &[Input::Qd, Input::Qdd],
        shape: Shape::Vector,
        available: Availability::Dynamics,
        public: false,
        reads: &[],
        make: |cx| {
            let (graph, tau) =
                newton_euler::inverse_dynamics(cx.chain, cx.assembled_inverse_dynamics());
            derived(graph, tau)
        },
        arm: None,
    },
    Quantity {
        key: Key::InverseDynamics,
        name: "inverse_dynamics",
        doc: "Inverse dynamics τ = D(q) q̈ + C(q, q̇) q̇ + g(q), plus armature and friction.",
        aliases: &["rnea", "rne"],
        inputs: &[Input::Qd, Input::Qdd],
        shape: Shape::Vector,
        available: Availability::Dynamics,
        public: true,
        reads: &[Key::InverseDynamicsSmooth],
        make: |cx| {
            with_coulomb(
                cx,
                quote!(self.inverse_dynamics_smooth(qd, qdd)),
                &[Key::InverseDynamicsSmooth],
            )
        },
        arm: Some(ArmMethod::Dynamics),
    },
    Quantity {
        key: Key::InverseDynamicsWithPayloadSmooth,
        name: "inverse_dynamics_with_payload_smooth",
        doc: "",
        aliases: &[],
        inputs: &[Input::Qd, Input::Qdd, Input::Payload],
        shape: Shape::Vector,
        available: Availability::Dynamics,
        public: false,
        reads: &[],
        make: |cx| {
            let graph = SharedGraph::default();
            let tau = payload::rnea(cx.chain, &graph, Acceleration::Symbolic);
            derived(graph, tau)
        },
        arm: None,
    },
    Quantity {
        key: Key::InverseDynamicsWithPayload,
        name: "inverse_dynamics_with_payload",
        doc: "Inverse dynamics with a payload held by the tool: `payload` is its ten inertial \
              parameters about the tool frame's origin, in the tool frame (`m, m·cx, m·cy, m·cz, \
              Ixx, Ixy, Iyy, Ixz, Iyz, Izz`, what `dhgen::payload::Payload::parameters` gives). \
              The arm's τ and the payload's in one pass of the recursion: τ is linear in the \
              payload's parameters, which stay inputs rather than constants.",
        aliases: &[],
        inputs: &[Input::Qd, Input::Qdd, Input::Payload],
        shape: Shape::Vector,
        available: Availability::Dynamics,
        public: true,
        reads: &[Key::InverseDynamicsWithPayloadSmooth],
        make: |cx| {
            with_coulomb(
                cx,
                quote!(self.inverse_dynamics_with_payload_smooth(qd, qdd, payload)),
                &[Key::InverseDynamicsWithPayloadSmooth],
            )
        },
        arm: None,
    },
    Quantity {
        key: Key::BiasWithPayloadSmooth,
        name: "bias_with_payload_smooth",
        doc: "",
        aliases: &[],
        inputs: &[Input::Qd, Input::Payload],
        shape: Shape::Vector,
        available: Availability::Dynamics,
        public: false,
        reads: &[],
        make: |cx| {
            let graph = SharedGraph::default();
            let bias = payload::rnea(cx.chain, &graph, Acceleration::Zero);
            derived(graph, bias)
        },
        arm: None,
    },
    Quantity {
        key: Key::BiasWithPayload,
        name: "bias_with_payload",
        doc: "The torques at zero acceleration with a payload held by the tool (`payload`: its \
              ten parameters, as for `inverse_dynamics_with_payload`).",
        aliases: &[],
        inputs: &[Input::Qd, Input::Payload],
        shape: Shape::Vector,
        available: Availability::Dynamics,
        public: true,
        reads: &[Key::BiasWithPayloadSmooth],
        make: |cx| {
            with_coulomb(
                cx,
                quote!(self.bias_with_payload_smooth(qd, payload)),
                &[Key::BiasWithPayloadSmooth],
            )
        },
        arm: None,
    },
    Quantity {
        key: Key::MassMatrixWithPayload,
        name: "mass_matrix_with_payload",
        doc: "D(q) with a payload held by the tool (`payload`: its ten parameters, as for \
              `inverse_dynamics_with_payload`).",
        aliases: &[],
        inputs: &[Input::Payload],
        shape: Shape::Square,
        available: Availability::Dynamics,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, d) = payload::mass_matrix(cx.chain);
            derived(graph, d)
        },
        arm: None,
    },
    Quantity {
        key: Key::GravityWithPayload,
        name: "gravity_with_payload",
        doc: "g(q) with a payload held by the tool (`payload`: its ten parameters, as for \
              `inverse_dynamics_with_payload`).",
        aliases: &[],
        inputs: &[Input::Payload],
        shape: Shape::Vector,
        available: Availability::Dynamics,
        public: true,
        reads: &[],
        make: |cx| {
            let graph = SharedGraph::default();
            let g = payload::gravity(cx.chain, &graph);
            derived(graph, g)
        },
        arm: None,
    },
    Quantity {
        key: Key::CoriolisWithPayload,
        name: "coriolis_with_payload",
        doc: "C(q, q̇) with a payload held by the tool (`payload`: its ten parameters, as for \
              `inverse_dynamics_with_payload`).",
        aliases: &[],
        inputs: &[Input::Qd, Input::Payload],
        shape: Shape::Square,
        available: Availability::Dynamics,
        public: true,
        reads: &[],
        make: |cx| {
            // Where C calls the runtime's loop, so does C with the payload, and where its own
            // straight-line code costs more than `LOOP_C_WITH_PAYLOAD_ABOVE_PER_JOINT`.
            let looped = || {
                Made::Looped(quote!(
                    ::dhgen::__private::recursive::coriolis_with_payload(
                        CHAIN, &self.c, &self.s, &self.d, qd, payload
                    )
                ))
            };
            if cx.coriolis_choice().is_none() {
                return looped();
            }
            let (graph, c) = payload::coriolis(cx.chain);
            let n = cx.chain.dof();
            if crate::graph::cost(&graph, &c) > super::LOOP_C_WITH_PAYLOAD_ABOVE_PER_JOINT * n {
                return looped();
            }
            derived(graph, c)
        },
        arm: None,
    },
    Quantity {
        key: Key::RegressorSmooth,
        name: "regressor_smooth",
        doc: "",
        aliases: &[],
        inputs: &[Input::Qd, Input::Qdd],
        shape: Shape::Regressor,
        available: Availability::Regressor,
        public: false,
        reads: &[],
        make: |cx| {
            let (graph, y) = cx.regressor();
            derived(graph.clone(), y.clone())
        },
        arm: None,
    },
    Quantity {
        key: Key::Regressor,
        name: "regressor",
        doc: "The joint torque regressor Y(q, q̇, q̈), `DOF × PARAMETERS`, with τ = Y π for \
              every parameter vector π (`PARAMETER_VALUES` is the robot's own; order and frames \
              in `dhgen::parameters`): what identification stacks over a trajectory.",
        aliases: &["computeJointTorqueRegressor"],
        inputs: &[Input::Qd, Input::Qdd],
        shape: Shape::Regressor,
        available: Availability::Regressor,
        public: true,
        reads: &[Key::RegressorSmooth],
        make: |cx| {
            with_coulomb_columns(
                cx,
                0..cx.columns.len(),
                quote!(self.regressor_smooth(qd, qdd)),
                &[Key::RegressorSmooth],
            )
        },
        arm: None,
    },
    Quantity {
        key: Key::BaseRegressorSmooth,
        name: "base_regressor_smooth",
        doc: "",
        aliases: &[],
        inputs: &[Input::Qd, Input::Qdd],
        shape: Shape::BaseRegressor,
        available: Availability::Regressor,
        public: false,
        reads: &[],
        make: |cx| {
            let (graph, y) = cx.regressor();
            let p = cx.columns.len();
            let base = cx.base_parameters();
            let yb = (0..cx.chain.dof())
                .flat_map(|r| base.independent.iter().map(move |&c| y[r * p + c].clone()))
                .collect();
            derived(graph.clone(), yb)
        },
        arm: None,
    },
    Quantity {
        key: Key::BaseRegressor,
        name: "base_regressor",
        doc: "The base regressor Y_b(q, q̇, q̈), `DOF × BASE_PARAMETERS`: the independent \
              columns of `regressor` (`BASE_COLUMNS`), with τ = Y_b π_b for π_b = \
              `base_parameters(π)`.",
        aliases: &[],
        inputs: &[Input::Qd, Input::Qdd],
        shape: Shape::BaseRegressor,
        available: Availability::Regressor,
        public: true,
        reads: &[Key::BaseRegressorSmooth],
        make: |cx| {
            with_coulomb_columns(
                cx,
                cx.base_parameters().independent.iter().copied(),
                quote!(self.base_regressor_smooth(qd, qdd)),
                &[Key::BaseRegressorSmooth],
            )
        },
        arm: None,
    },
    Quantity {
        key: Key::BiasSmooth,
        name: "bias_smooth",
        doc: "",
        aliases: &[],
        inputs: &[Input::Qd],
        shape: Shape::Vector,
        available: Availability::Dynamics,
        public: false,
        reads: &[],
        make: |cx| {
            let graph = SharedGraph::default();
            let bias = newton_euler::rnea_exprs(cx.chain, &graph, Acceleration::Zero);
            let bias = crate::derive::without_ignored_joints(cx.chain, &graph, &bias);
            derived(graph, bias)
        },
        arm: None,
    },
    Quantity {
        key: Key::Bias,
        name: "bias",
        doc: "The torques at zero acceleration, C(q, q̇) q̇ + g(q) + friction: what a \
              computed-torque law adds to D(q) v.",
        aliases: &["nonLinearEffects"],
        inputs: &[Input::Qd],
        shape: Shape::Vector,
        available: Availability::Dynamics,
        public: true,
        reads: &[Key::BiasSmooth],
        make: |cx| with_coulomb(cx, quote!(self.bias_smooth(qd)), &[Key::BiasSmooth]),
        arm: Some(ArmMethod::Dynamics),
    },
    Quantity {
        key: Key::ForwardDynamicsLanes,
        name: "forward_dynamics_lanes",
        doc: "Forward dynamics q̈ = D⁻¹(τ − C q̇ − g − friction) by a Cholesky solve \
              without branches, and the mask of the lanes where it is an answer: a pivot \
              above `dhgen::cholesky_pivot_floor` and a finite q̈ (for a scalar, a `bool`). \
              What `forward_dynamics` returns as an `Option`, for SIMD packs (`dhgen::batch`) \
              whose lanes each get the scalar path's answer.",
        aliases: &[],
        inputs: &[Input::Qd, Input::Tau],
        shape: Shape::VectorMask,
        available: Availability::Dynamics,
        public: true,
        reads: &[Key::MassMatrix, Key::Bias],
        make: |cx| {
            if cx.mass_matrix().is_none() {
                // D and the bias torques from one pass of the runtime's loops.
                return solved(
                    cx,
                    quote! {
                        let (dm, h) = ::dhgen::__private::recursive::mass_matrix_and_bias(
                            CHAIN, &self.c, &self.s, &self.d, qd,
                        );
                    },
                    &[Key::MassMatrix],
                    SolveOps::Report,
                );
            }
            solved(
                cx,
                quote!(let dm = self.mass_matrix(); let h = self.bias(qd);),
                &[Key::MassMatrix, Key::Bias],
                SolveOps::Report,
            )
        },
        arm: None,
    },
    Quantity {
        key: Key::ForwardDynamics,
        name: "forward_dynamics",
        doc: "Forward dynamics q̈ = D⁻¹(τ − C q̇ − g − friction) by a Cholesky solve; \
              `None` where D(q) is singular to working precision (a pivot at or below \
              `dhgen::cholesky_pivot_floor`, the runtime path's rule too) or the acceleration is \
              not finite (non-finite or overflowing inputs); for a SIMD pack, `None` unless \
              every lane has an answer (`forward_dynamics_lanes` gives them lane by lane).",
        aliases: &["aba", "accel", "fdyn"],
        inputs: &[Input::Qd, Input::Tau],
        shape: Shape::OptionVector,
        available: Availability::Dynamics,
        public: true,
        reads: &[Key::ForwardDynamicsLanes],
        make: |_| {
            all_lanes(
                quote!(self.forward_dynamics_lanes(qd, tau)),
                &[Key::ForwardDynamicsLanes],
            )
        },
        arm: Some(ArmMethod::Dynamics),
    },
    Quantity {
        key: Key::ForwardDynamicsWithPayloadLanes,
        name: "forward_dynamics_with_payload_lanes",
        doc: "`forward_dynamics_with_payload` with the mask of the lanes where it is an answer, \
              as `forward_dynamics_lanes` is to `forward_dynamics`.",
        aliases: &[],
        inputs: &[Input::Qd, Input::Tau, Input::Payload],
        shape: Shape::VectorMask,
        available: Availability::Dynamics,
        public: true,
        reads: &[Key::BiasWithPayload, Key::MassMatrixWithPayload],
        make: |cx| {
            solved(
                cx,
                quote! {
                    let dm = self.mass_matrix_with_payload(payload);
                    let h = self.bias_with_payload(qd, payload);
                },
                &[Key::MassMatrixWithPayload, Key::BiasWithPayload],
                SolveOps::Reported,
            )
        },
        arm: None,
    },
    Quantity {
        key: Key::ForwardDynamicsWithPayload,
        name: "forward_dynamics_with_payload",
        doc: "Forward dynamics with a payload held by the tool (`payload`: its ten parameters, \
              as for `inverse_dynamics_with_payload`), by the unrolled Cholesky solve of \
              `forward_dynamics` on `mass_matrix_with_payload` and `bias_with_payload`; `None` \
              as for `forward_dynamics`.",
        aliases: &[],
        inputs: &[Input::Qd, Input::Tau, Input::Payload],
        shape: Shape::OptionVector,
        available: Availability::Dynamics,
        public: true,
        reads: &[Key::ForwardDynamicsWithPayloadLanes],
        make: |_| {
            all_lanes(
                quote!(self.forward_dynamics_with_payload_lanes(qd, tau, payload)),
                &[Key::ForwardDynamicsWithPayloadLanes],
            )
        },
        arm: None,
    },
    Quantity {
        key: Key::KineticEnergy,
        name: "kinetic_energy",
        doc: "Kinetic energy T(q, q̇) = ½ q̇ᵀ D(q) q̇ of the links and rotors.",
        aliases: &["computeKineticEnergy"],
        inputs: &[Input::Qd],
        shape: Shape::Scalar,
        available: Availability::Dynamics,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, t) = energy::kinetic_energy(&cx.derivation);
            derived(graph, t)
        },
        arm: Some(ArmMethod::Dynamics),
    },
    Quantity {
        key: Key::PotentialEnergy,
        name: "potential_energy",
        doc: "Potential energy P(q) = −Σ m_k gravity · c_k of the links in the description's \
              gravity, centres of mass c_k in the world frame (zero at the world origin): \
              g(q) = ∂P/∂q, and T + P is conserved when no torque acts.",
        aliases: &["computePotentialEnergy"],
        inputs: &[],
        shape: Shape::Scalar,
        available: Availability::Dynamics,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, p) = energy::potential_energy(&cx.derivation);
            derived(graph, p)
        },
        arm: Some(ArmMethod::Dynamics),
    },
    Quantity {
        key: Key::CenterOfMass,
        name: "center_of_mass",
        doc: "The links' total mass M and their centre of mass c in the world frame, \
              `(M, c)` (links fixed to the base, which no joint moves, are not counted; c is \
              the world origin if M is 0): the potential energy is `−M gravity · c`.",
        aliases: &["centerOfMass"],
        inputs: &[],
        shape: Shape::MassAndPoint,
        available: Availability::Dynamics,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, c) = center_of_mass::center_of_mass(cx.chain);
            derived(graph, c)
        },
        arm: Some(ArmMethod::Dynamics),
    },
    Quantity {
        key: Key::CenterOfMassJacobian,
        name: "center_of_mass_jacobian",
        doc: "The Jacobian of the centre of mass, 3×n in world axes: `ċ = J_c q̇`, and the \
              gravity torques are `g(q) = −M J_cᵀ gravity` (zero if the links have no mass).",
        aliases: &["jacobianCenterOfMass"],
        inputs: &[],
        shape: Shape::PointJacobian,
        available: Availability::Dynamics,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, j) = center_of_mass::center_of_mass_jacobian(cx.chain);
            derived(graph, j)
        },
        arm: Some(ArmMethod::Dynamics),
    },
    Quantity {
        key: Key::KineticEnergyWithPayload,
        name: "kinetic_energy_with_payload",
        doc: "Kinetic energy with a payload held by the tool (`payload`: its ten parameters, as \
              for `inverse_dynamics_with_payload`): ½ q̇ᵀ D(q) q̇ with \
              `mass_matrix_with_payload`.",
        aliases: &[],
        inputs: &[Input::Qd, Input::Payload],
        shape: Shape::Scalar,
        available: Availability::Dynamics,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, t) = payload::kinetic_energy(cx.chain);
            derived(graph, t)
        },
        arm: None,
    },
    Quantity {
        key: Key::PotentialEnergyWithPayload,
        name: "potential_energy_with_payload",
        doc: "Potential energy with a payload held by the tool (`payload`: its ten parameters, \
              as for `inverse_dynamics_with_payload`): `potential_energy` and the payload's \
              weight at the height of its centre of mass; `gravity_with_payload` is its \
              gradient.",
        aliases: &[],
        inputs: &[Input::Payload],
        shape: Shape::Scalar,
        available: Availability::Dynamics,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, p) = payload::potential_energy(cx.chain);
            derived(graph, p)
        },
        arm: None,
    },
    Quantity {
        key: Key::InverseDynamicsDerivatives,
        name: "inverse_dynamics_derivatives",
        doc: "The derivatives of inverse dynamics, `(∂τ/∂q, ∂τ/∂q̇)` at (q, q̇, q̈), entry \
              `(k, m)` = ∂τ_k/∂x_m (∂τ/∂q̈ is D(q)); what MPC and trajectory optimisation \
              linearise. Coulomb friction, constant away from q̇ = 0, contributes 0 (its \
              subgradient at 0 too).",
        aliases: &["computeRNEADerivatives"],
        inputs: &[Input::Qd, Input::Qdd],
        shape: Shape::SquarePair,
        available: Availability::Derivatives,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, e) = cx.inverse_dynamics_derivatives().clone();
            // ∂τ/∂q̇ does not read q̈: `forward_dynamics_derivatives` takes the bias torques
            // from it before q̈ is known.
            Made::Staged(graph, e, Input::Qdd)
        },
        arm: None,
    },
    Quantity {
        key: Key::InverseDynamicsDerivativesWithPayload,
        name: "inverse_dynamics_derivatives_with_payload",
        doc: "The derivatives of inverse dynamics with a payload held by the tool, `(∂τ/∂q, \
              ∂τ/∂q̇)` at (q, q̇, q̈) (`payload`: its ten parameters, as for \
              `inverse_dynamics_with_payload`; ∂τ/∂q̈ is `mass_matrix_with_payload`): what MPC \
              linearises while the arm carries what it picked up, with the payload's \
              parameters inputs rather than constants. Coulomb friction contributes 0, as in \
              `inverse_dynamics_derivatives`.",
        aliases: &[],
        inputs: &[Input::Qd, Input::Qdd, Input::Payload],
        shape: Shape::SquarePair,
        available: Availability::Derivatives,
        public: true,
        reads: &[],
        make: |cx| {
            let (graph, e) = payload::inverse_dynamics_derivatives(cx.chain);
            // ∂τ/∂q̇ does not read q̈: `forward_dynamics_derivatives_with_payload` takes the
            // bias torques from it before q̈ is known.
            Made::Staged(graph, e, Input::Qdd)
        },
        arm: None,
    },
    Quantity {
        key: Key::MassMatrixRate,
        name: "mass_matrix_rate",
        doc: "The time derivative of the inertia matrix, Ḋ(q, q̇) = Σ_i ∂D/∂q_i q̇_i \
              (= C + Cᵀ): with [`coriolis_transpose_qd`](Self::coriolis_transpose_qd), what \
              a generalized-momentum collision observer needs every cycle.",
        aliases: &[],
        inputs: &[Input::Qd],
        shape: Shape::Square,
        available: Availability::Derivatives,
        public: true,
        reads: &[Key::Coriolis],
        make: |cx| {
            // Past `LOOPED_ABOVE` joints, C + Cᵀ from C's loop (the runtime path's own way):
            // straight-line, general 30 took 0.84× the runtime's time. Below, straight-line
            // even where C calls its loop (general 10 and 12: 744–780 and 1,022 ns, against
            // 839 and 968–1,034 from the loop).
            if cx.looped() {
                return composed(
                    quote!(let c = self.coriolis(qd); c + c.transpose()),
                    &[Key::Coriolis],
                );
            }
            let (graph, e) = derivatives::mass_matrix_rate(cx.chain, cx.coriolis_derivations());
            derived(graph, e)
        },
        arm: None,
    },
    Quantity {
        key: Key::CoriolisTransposeQd,
        name: "coriolis_transpose_qd",
        doc: "Cᵀ(q, q̇) q̇, the term of a generalized-momentum observer's model \
              (ṗ = τ + Cᵀq̇ − g for p = D q̇; De Luca's residual).",
        aliases: &[],
        inputs: &[Input::Qd],
        shape: Shape::Vector,
        available: Availability::Derivatives,
        public: true,
        reads: &[Key::Coriolis],
        make: |cx| {
            // As `mass_matrix_rate`: from C's loop past `LOOPED_ABOVE` joints (straight-line,
            // general 30 took 0.91× the runtime's time), straight-line below (general 12: 751–784
            // ns against 1,029 from the loop).
            if cx.looped() {
                return composed(
                    quote!(self.coriolis(qd).transpose() * na::SVector::<T, DOF>::from(*qd)),
                    &[Key::Coriolis],
                );
            }
            let (graph, e) =
                derivatives::coriolis_transpose_qd(cx.chain, cx.coriolis_derivations());
            derived(graph, e)
        },
        arm: None,
    },
    Quantity {
        key: Key::MassMatrixInverseLanes,
        name: "mass_matrix_inverse_lanes",
        doc: "D(q)⁻¹ by the Cholesky factorisation of `forward_dynamics`, without \
              branches, and the mask of the lanes where it is an answer (pivots above \
              `dhgen::cholesky_pivot_floor`, finite entries); for a scalar, a `bool`.",
        aliases: &[],
        inputs: &[],
        shape: Shape::SquareMask,
        available: Availability::Derivatives,
        public: true,
        reads: &[Key::MassMatrix],
        make: |cx| {
            let (inverse, ops) =
                cholesky::inverse(cx.chain.dof(), cholesky::Check::PivotsAndFinite);
            Made::Composed {
                body: quote! {
                    let dm = self.mass_matrix();
                    #inverse
                },
                reads: &[Key::MassMatrix],
                ops: Some(("cholesky_inverse", ops)),
            }
        },
        arm: None,
    },
    Quantity {
        key: Key::MassMatrixInverse,
        name: "mass_matrix_inverse",
        doc: "D(q)⁻¹ by Cholesky factorisation; `None` where D(q) is singular to working \
              precision (the pivot rule of `forward_dynamics`); for a SIMD pack, `None` unless \
              every lane has an answer (`mass_matrix_inverse_lanes` gives them lane by lane).",
        aliases: &["computeMinverse"],
        inputs: &[],
        shape: Shape::OptionSquare,
        available: Availability::Derivatives,
        public: true,
        reads: &[Key::MassMatrixInverseLanes],
        make: |_| {
            all_lanes(
                quote!(self.mass_matrix_inverse_lanes()),
                &[Key::MassMatrixInverseLanes],
            )
        },
        arm: None,
    },
    Quantity {
        key: Key::ForwardDynamicsTerms,
        name: "forward_dynamics_terms",
        doc: "∂τ/∂q, ∂τ/∂q̇ and D(q) in one derivation, staged at q̈: what \
              `forward_dynamics_derivatives` evaluates where D costs less beside ∂τ.",
        aliases: &[],
        inputs: &[Input::Qd, Input::Qdd],
        shape: Shape::SquareTriple,
        available: Availability::DerivativesWithMassMatrix,
        public: false,
        reads: &[],
        make: |cx| {
            let (graph, e) = cx
                .derivatives_with_mass_matrix()
                .expect("available only with it")
                .clone();
            Made::Staged(graph, e, Input::Qdd)
        },
        arm: None,
    },
    Quantity {
        key: Key::ForwardDynamicsDerivativesLanes,
        name: "forward_dynamics_derivatives_lanes",
        doc: "`forward_dynamics_derivatives` with the mask of the lanes where it is an answer \
              (D(q) not singular to working precision and q̈ finite; for a scalar, a `bool`), \
              as `forward_dynamics_lanes` is to `forward_dynamics`: for SIMD packs \
              (`dhgen::batch`) whose lanes each get the scalar path's answer.",
        aliases: &[],
        inputs: &[Input::Qd, Input::Tau],
        shape: Shape::SquareTripleMask,
        available: Availability::Derivatives,
        public: true,
        reads: &[
            Key::Gravity,
            Key::MassMatrixWithPayload,
            Key::GravityWithPayload,
            Key::InverseDynamicsDerivatives,
            Key::InverseDynamicsDerivativesWithPayload,
            Key::MassMatrixInverseLanes,
            Key::ForwardDynamicsTerms,
        ],
        make: |cx| forward_dynamics_derivatives(cx, Answer::Lanes, Held::Nothing),
        arm: None,
    },
    Quantity {
        key: Key::ForwardDynamicsDerivatives,
        name: "forward_dynamics_derivatives",
        doc: "The derivatives of forward dynamics, `(∂q̈/∂q, ∂q̈/∂q̇, ∂q̈/∂τ = D⁻¹)` at (q, q̇, τ), \
              from ∂q̈/∂x = −D⁻¹ ∂τ/∂x at q̈ = D⁻¹(τ − C q̇ − g − friction); `None` where D(q) \
              is singular to working precision or q̈ is not finite, as for `forward_dynamics` \
              (for a SIMD pack, unless every lane has an answer: \
              `forward_dynamics_derivatives_lanes` gives them lane by lane).",
        aliases: &["computeABADerivatives"],
        inputs: &[Input::Qd, Input::Tau],
        shape: Shape::OptionSquareTriple,
        available: Availability::Derivatives,
        public: true,
        reads: &[
            Key::Gravity,
            Key::MassMatrixWithPayload,
            Key::GravityWithPayload,
            Key::InverseDynamicsDerivatives,
            Key::InverseDynamicsDerivativesWithPayload,
            Key::MassMatrixInverseLanes,
            Key::ForwardDynamicsTerms,
        ],
        make: |cx| forward_dynamics_derivatives(cx, Answer::Option, Held::Nothing),
        arm: None,
    },
    Quantity {
        key: Key::ForwardDynamicsDerivativesWithPayloadLanes,
        name: "forward_dynamics_derivatives_with_payload_lanes",
        doc: "`forward_dynamics_derivatives_with_payload` with the mask of the lanes where it is \
              an answer, as `forward_dynamics_derivatives_lanes` is to \
              `forward_dynamics_derivatives`.",
        aliases: &[],
        inputs: &[Input::Qd, Input::Tau, Input::Payload],
        shape: Shape::SquareTripleMask,
        available: Availability::Derivatives,
        public: true,
        reads: &[
            Key::Gravity,
            Key::MassMatrixWithPayload,
            Key::GravityWithPayload,
            Key::InverseDynamicsDerivatives,
            Key::InverseDynamicsDerivativesWithPayload,
            Key::MassMatrixInverseLanes,
            Key::ForwardDynamicsTerms,
        ],
        make: |cx| forward_dynamics_derivatives(cx, Answer::Lanes, Held::Payload),
        arm: None,
    },
    Quantity {
        key: Key::ForwardDynamicsDerivativesWithPayload,
        name: "forward_dynamics_derivatives_with_payload",
        doc: "The derivatives of forward dynamics with a payload held by the tool, \
              `(∂q̈/∂q, ∂q̈/∂q̇, ∂q̈/∂τ = D⁻¹)` at (q, q̇, τ) (`payload`: its ten parameters, as \
              for `inverse_dynamics_with_payload`), as `forward_dynamics_derivatives` computes \
              them: D⁻¹ by the Cholesky factorisation of `mass_matrix_with_payload`, the bias \
              from ∂τ/∂q̇ with the payload (which does not read q̈), q̈, then ∂τ/∂q at that q̈ \
              and −D⁻¹ times both; `None` as for `forward_dynamics_derivatives`.",
        aliases: &[],
        inputs: &[Input::Qd, Input::Tau, Input::Payload],
        shape: Shape::OptionSquareTriple,
        available: Availability::Derivatives,
        public: true,
        reads: &[
            Key::Gravity,
            Key::MassMatrixWithPayload,
            Key::GravityWithPayload,
            Key::InverseDynamicsDerivatives,
            Key::InverseDynamicsDerivativesWithPayload,
            Key::MassMatrixInverseLanes,
            Key::ForwardDynamicsTerms,
        ],
        make: |cx| forward_dynamics_derivatives(cx, Answer::Option, Held::Payload),
        arm: None,
    },
    Quantity {
        key: Key::Terms,
        name: "terms",
        doc: "D, C, g and J at once, as a controller needs them, sharing one state's sines \
              and cosines.",
        aliases: &["computeAllTerms"],
        inputs: &[Input::Qd],
        shape: Shape::Terms,
        available: Availability::Dynamics,
        public: true,
        reads: &[Key::Jacobian, Key::MassMatrix, Key::Coriolis, Key::Gravity],
        make: |_| {
            composed(
                quote! {
                    Terms {
                        mass_matrix: self.mass_matrix(),
                        coriolis: self.coriolis(qd),
                        gravity: self.gravity(),
                        jacobian: self.jacobian(),
                    }
                },
                &[Key::MassMatrix, Key::Coriolis, Key::Gravity, Key::Jacobian],
            )
        },
        arm: None,
    },
    Quantity {
        key: Key::ToolTerms,
        name: "tool_terms",
        doc: "D(q), the tool's Jacobian J(q) and J̇q̇, the bias torques and g(q) at once, \
              sharing one state's sines and cosines: what task-space dynamics \
              (`dhgen::task_space`) reads.",
        aliases: &[],
        inputs: &[Input::Qd],
        shape: Shape::ToolTerms,
        available: Availability::Dynamics,
        public: true,
        reads: &[
            Key::Jacobian,
            Key::JdotQdot,
            Key::MassMatrix,
            Key::Gravity,
            Key::Bias,
        ],
        make: |_| {
            composed(
                quote! {
                    ::dhgen::__private::ToolTerms {
                        mass_matrix: self.mass_matrix(),
                        jacobian: self.jacobian(),
                        jdot_qdot: self.jdot_qdot(qd),
                        bias: self.bias(qd),
                        gravity: self.gravity(),
                    }
                },
                &[
                    Key::MassMatrix,
                    Key::Jacobian,
                    Key::JdotQdot,
                    Key::Bias,
                    Key::Gravity,
                ],
            )
        },
        arm: Some(ArmMethod::Dynamics),
    },
];

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::BTreeSet;

    fn read(path: &str) -> String {
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
        std::fs::read_to_string(format!("{root}/{path}")).unwrap()
    }

    /// `fn name` → the `#[doc(alias = ...)]` attributes just above it, in `source`.
    fn aliases_in(source: &str) -> Vec<(String, BTreeSet<String>)> {
        let lines: Vec<&str> = source.lines().collect();
        let mut out = Vec::new();
        for (i, line) in lines.iter().enumerate() {
            let t = line.trim_start();
            let Some(rest) = t.strip_prefix("fn ").or_else(|| t.strip_prefix("pub fn ")) else {
                continue;
            };
            let name: String = rest
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            let mut aliases = BTreeSet::new();
            let mut k = i;
            while k > 0 {
                k -= 1;
                let above = lines[k].trim_start();
                if let Some(a) = above.strip_prefix("#[doc(alias = \"") {
                    aliases.insert(a.trim_end_matches("\")]").to_string());
                } else if !(above.starts_with("///") || above.starts_with("#[")) {
                    break;
                }
            }
            out.push((name, aliases));
        }
        out
    }

    #[test]
    fn the_traits_and_the_runtime_carry_the_tables_aliases() {
        let sources = [
            "kernel/src/arm.rs",
            "src/kinematics.rs",
            "src/dynamics/crba.rs",
            "src/dynamics/coriolis.rs",
            "src/dynamics/gravity.rs",
            "src/dynamics/rnea.rs",
            "src/dynamics/forward.rs",
            "src/dynamics/derivatives.rs",
            "src/dynamics/christoffel.rs",
            "src/dynamics/rates.rs",
            "src/dynamics/regressor.rs",
        ];
        let mut wrong = Vec::new();
        for path in sources {
            for (name, aliases) in aliases_in(&read(path)) {
                let Some(q) = QUANTITIES.iter().find(|q| q.name == name && q.public) else {
                    continue;
                };
                let table: BTreeSet<String> = q.aliases.iter().map(|a| a.to_string()).collect();
                if aliases != table {
                    wrong.push(format!("{path}: {name} {aliases:?}, the table {table:?}"));
                }
            }
        }
        assert!(
            wrong.is_empty(),
            "aliases that disagree:\n{}",
            wrong.join("\n")
        );
    }

    #[test]
    fn docs_names_md_names_every_quantity_and_alias() {
        let names = read("docs/names.md");
        let missing: Vec<String> = QUANTITIES
            .iter()
            .filter(|q| q.public && !q.name.ends_with("_lanes"))
            .flat_map(|q| std::iter::once(q.name).chain(q.aliases.iter().copied()))
            .filter(|word| !names.contains(&format!("`{word}")))
            .map(str::to_string)
            .collect();
        assert!(
            missing.is_empty(),
            "docs/names.md does not name {missing:?}"
        );
    }
}
