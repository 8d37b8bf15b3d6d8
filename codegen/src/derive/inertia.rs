//! The joint-space inertia matrix D(q), by the composite-rigid-body algorithm, either
//! expanded into the normal form and Horner-factored, or kept as the recursion (in joint
//! frames, or in one frame's coordinates as the runtime path computes it).

use super::Derivation;
use crate::chain::{Coordinates, RingChain};
use crate::graph::{E, SharedGraph};
use crate::poly::{Budget, Poly};
use dhgen_description::ChainRef;
use std::rc::Rc;

/// D(q) in the normal form, motor inertia included (row-major).
pub fn mass_matrix_polys(chain: ChainRef<'_>, budget: &Rc<Budget>) -> Vec<Vec<Poly>> {
    let mut d: Vec<Vec<Poly>> = super::poly_chain(chain, budget)
        .mass_matrix()
        .into_iter()
        .map(|row| row.into_iter().map(|p| p.poly).collect())
        .collect();
    add_armature(chain, &mut d, |p, x| *p = p.clone().add_constant(x));
    d
}

/// D(q) row-major by the composite-rigid-body recursion on `rc`, in joint frames (`None`) or in
/// one frame's coordinates, armature included.
pub(crate) fn recursive(
    chain: ChainRef<'_>,
    rc: &RingChain<'_, E>,
    at: Option<Coordinates>,
) -> Vec<E> {
    let mut d = match at {
        None => rc.mass_matrix(),
        Some(at) => rc.mass_matrix_in(at),
    };
    add_armature(chain, &mut d, |e, x| *e = e.clone() + E::K(x));
    d.into_iter().flatten().collect()
}

/// Adds each joint's armature to the diagonal.
pub(crate) fn add_armature<X>(chain: ChainRef<'_>, d: &mut [Vec<X>], add: impl Fn(&mut X, f64)) {
    for (i, b) in chain.bodies.iter().enumerate() {
        if b.armature != 0.0 {
            add(&mut d[i][i], b.armature);
        }
    }
}

/// D(q) as expressions (row-major, n×n), whichever derivation is cheaper.
pub fn mass_matrix(dv: &Derivation<'_>) -> (SharedGraph, Vec<E>) {
    let chain = dv.chain;
    let expanded = {
        let graph = SharedGraph::default();
        dv.mass_matrix_exprs(&graph).map(|e| (graph, e))
    };
    super::cheapest_dynamics(
        chain,
        expanded
            .into_iter()
            .chain(recursive_candidates(chain, |_, _| {}))
            .collect(),
    )
}

/// D(q) by the composite-rigid-body recursion, armature included, on the chain changed by
/// `adjust` (the payload's derivation adds a body's worth of input symbols to its last link):
/// in joint frames, carrying each wrench down the chain, and in one frame's coordinates
/// ([`RingChain::mass_matrix_in`](crate::chain::RingChain::mass_matrix_in), the runtime
/// path's algorithm) for the root frame and the middle joint's (where the fewest joint
/// variables separate the bodies from the frame; the other frames rarely win and cost
/// generation time).
pub(crate) fn recursive_candidates<'c>(
    chain: ChainRef<'c>,
    adjust: impl Fn(&mut RingChain<'c, E>, &SharedGraph),
) -> Vec<(SharedGraph, Vec<E>)> {
    let n = chain.dof();
    [
        None,
        Some(Coordinates::Root),
        Some(Coordinates::Joint(n / 2)),
    ]
    .into_iter()
    .map(|at| {
        let graph = SharedGraph::default();
        let mut rc = super::graph_chain(chain, &graph);
        adjust(&mut rc, &graph);
        let e = recursive(chain, &rc, at);
        debug_assert_eq!(e.len(), n * n);
        (graph, e)
    })
    .collect()
}
