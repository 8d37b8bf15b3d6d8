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

/// C(q, q̇) with the payload (row-major), by the O(n²) recursion of the plain C on the chain
/// with the payload. (The plain C's cheapest derivation plus the recursion on the payload
/// alone costs more: PUMA 560 591 + 1,760 operations against 2,008, Panda 2,423 + 2,789
/// against 3,617.)
pub fn coriolis(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    super::christoffel::coriolis_recursive_with(chain, |rc, graph| {
        add_payload(rc, graph, |v| Dual {
            v,
            d: std::rc::Rc::from(Vec::new()),
        });
    })
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
