//! The joint-space inertia matrix D(q), by the composite-rigid-body algorithm, either
//! expanded into the normal form and Horner-factored, or kept as the recursion.

use super::Derivation;
use crate::graph::{E, SharedGraph};
use crate::poly::{Budget, Poly};
use dhgen_model::ChainRef;
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
    let n = chain.dof();
    let expanded = {
        let graph = SharedGraph::default();
        dv.mass_matrix_exprs(&graph).map(|e| (graph, e))
    };
    let recursive = {
        let graph = SharedGraph::default();
        let mut d = super::graph_chain(chain, &graph).mass_matrix();
        add_armature(chain, &mut d, |e, x| *e = e.clone() + E::K(x));
        let e: Vec<E> = d.into_iter().flatten().collect();
        debug_assert_eq!(e.len(), n * n);
        (graph, e)
    };
    super::cheapest(expanded.into_iter().chain([recursive]).collect())
}
