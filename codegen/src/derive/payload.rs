//! The dynamics with a payload held by the tool, its ten inertial parameters kept as inputs
//! ([`Sym::Payload`]: `m, m·c` and the inertia about the tool origin, in the tool frame).
//!
//! The dynamics are linear in a body's parameters, so adding the payload's mass moments,
//! carried into the last joint frame by the tool placement `P_n`, to the last body of the
//! recursions (Newton–Euler for τ and the bias, composite bodies for D and g) costs only the
//! payload's own terms. The recursions are the plain quantities' recursion candidates; the
//! normal forms would have to be expanded in ten more variables and do not compete.

use crate::chain::{MassMoments, RingChain};
use crate::dual::Dual;
use crate::graph::{E, SharedGraph, Sym};
use dhgen_model::{ChainRef, Ring};

/// Adds the payload's mass moments (its parameters the inputs, each made a value of the
/// chain's arithmetic by `lift`), carried into the last joint frame by the tool placement, to
/// the last body of `rc`.
fn add_payload<R: Ring>(rc: &mut RingChain<'_, R>, graph: &SharedGraph, lift: impl Fn(E) -> R) {
    let n = rc.dof();
    let payload = MassMoments::of(|k| lift(E::sym(graph, Sym::Payload(k))));
    let tool = rc.chain.placements[n].to_ring::<R>();
    rc.bodies[n - 1] = rc.bodies[n - 1].plus(&payload.transformed(&tool));
}

/// The chain in graph arithmetic with the payload's mass moments added to the last body.
fn chain_with_payload<'c>(chain: ChainRef<'c>, graph: &SharedGraph) -> RingChain<'c, E> {
    let mut rc = super::graph_chain(chain, graph);
    add_payload(&mut rc, graph, |e| e);
    rc
}

/// C(q, q̇) with the payload (row-major): of the plain C's two O(n²) derivations run on the
/// chain with the payload (the recursion on dual numbers, and Echeandia and Wensing's
/// algorithm in every frame's coordinates), the cheaper: PUMA 560 1,464 operations, Panda
/// 2,380, a general 12-joint arm 6,179, where the recursion alone costs 1,924, 3,463 and
/// 17,784.
pub fn coriolis(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    let recursive = super::christoffel::coriolis_recursive_with(chain, |rc, graph| {
        add_payload(rc, graph, |v| Dual {
            v,
            d: std::rc::Rc::from(Vec::new()),
        });
    });
    let spatial =
        super::christoffel::coriolis_spatial_with(chain, |rc, graph| add_payload(rc, graph, |e| e));
    super::cheapest(vec![recursive, spatial])
}

/// τ with the payload, without Coulomb friction; `qdd_zero`: the bias `C q̇ + g`.
pub fn rnea(chain: ChainRef<'_>, graph: &SharedGraph, qdd_zero: bool) -> Vec<E> {
    super::newton_euler::rnea_with(chain, graph, qdd_zero, true, chain_with_payload)
}

/// D(q) with the payload (row-major), armature included: the cheapest of the plain D's
/// recursive candidates run on the chain with the payload.
pub fn mass_matrix(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    super::cheapest(super::inertia::recursive_candidates(chain, |rc, graph| {
        add_payload(rc, graph, |e| e)
    }))
}

/// g(q) with the payload.
pub fn gravity(chain: ChainRef<'_>, graph: &SharedGraph) -> Vec<E> {
    chain_with_payload(chain, graph).gravity_torques()
}
