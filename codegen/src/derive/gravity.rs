//! The gravity torques g(q): expanded normal form, or the composite-body recursion.

use super::Derivation;
use crate::graph::{E, SharedGraph};
use crate::poly::{Budget, Poly};
use dhgen_description::ChainRef;
use std::rc::Rc;

/// g(q) in the normal form.
pub fn gravity_polys(chain: ChainRef<'_>, budget: &Rc<Budget>) -> Vec<Poly> {
    super::poly_chain(chain, budget)
        .gravity_torques()
        .into_iter()
        .map(|p| p.poly)
        .collect()
}

/// g(q) as expressions, whichever derivation is cheaper.
pub fn gravity(dv: &Derivation<'_>) -> (SharedGraph, Vec<E>) {
    let expanded = {
        let graph = SharedGraph::default();
        dv.gravity_exprs(&graph).map(|e| (graph, e))
    };
    let recursive = {
        let graph = SharedGraph::default();
        let e = super::graph_chain(dv.chain, &graph).gravity_torques();
        (graph, e)
    };
    super::cheapest_dynamics(dv.chain, expanded.into_iter().chain([recursive]).collect())
}
