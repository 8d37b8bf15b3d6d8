//! The dynamics with a payload held by the tool, its ten inertial parameters kept as inputs
//! ([`Sym::Payload`]: `m, m·c` and the inertia about the tool origin, in the tool frame).
//!
//! The dynamics are linear in a body's parameters, so adding the payload's mass moments,
//! carried into the last joint frame by the tool placement `P_n`, to the last body of the
//! recursions (Newton–Euler for τ and the bias, composite bodies for D and g) costs only the
//! payload's own terms. The recursions are the plain quantities' recursion candidates; the
//! normal forms would have to be expanded in ten more variables and do not compete.

use crate::chain::{MassMoments, RingChain};
use crate::graph::{E, SharedGraph, Sym};
use dhgen_model::ChainRef;

/// The chain in graph arithmetic with the payload's mass moments added to the last body.
fn chain_with_payload<'c>(chain: ChainRef<'c>, graph: &SharedGraph) -> RingChain<'c, E> {
    let n = chain.dof();
    let p = |k: usize| E::sym(graph, Sym::Payload(k));
    let payload = MassMoments {
        m: p(0),
        h: [p(1), p(2), p(3)],
        i: [[p(4), p(5), p(7)], [p(5), p(6), p(8)], [p(7), p(8), p(9)]],
    };
    let tool = chain.placements[n].to_ring::<E>();
    let mut rc = super::graph_chain(chain, graph);
    rc.bodies[n - 1] = rc.bodies[n - 1].plus(&payload.transformed(&tool));
    rc
}

/// τ with the payload, without Coulomb friction; `qdd_zero`: the bias `C q̇ + g`.
pub fn rnea(chain: ChainRef<'_>, graph: &SharedGraph, qdd_zero: bool) -> Vec<E> {
    super::newton_euler::rnea_with(chain, graph, qdd_zero, true, chain_with_payload)
}

/// D(q) with the payload (row-major), armature included.
pub fn mass_matrix(chain: ChainRef<'_>, graph: &SharedGraph) -> Vec<E> {
    let mut d = chain_with_payload(chain, graph).mass_matrix();
    super::inertia::add_armature(chain, &mut d, |e, x| *e = e.clone() + E::K(x));
    d.into_iter().flatten().collect()
}

/// g(q) with the payload.
pub fn gravity(chain: ChainRef<'_>, graph: &SharedGraph) -> Vec<E> {
    chain_with_payload(chain, graph).gravity_torques()
}
