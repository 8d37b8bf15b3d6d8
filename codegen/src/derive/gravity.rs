//! The gravity torques g(q): expanded normal form, or the composite-body recursion.

use super::Derivation;
use crate::graph::{E, SharedGraph};
use crate::poly::Poly;
use dhgen_model::RobotModel;

/// g(q) in the normal form.
pub fn gravity_polys(model: &RobotModel) -> Vec<Poly> {
    super::poly_chain(model)
        .gravity_torques()
        .into_iter()
        .map(|p| p.poly)
        .collect()
}

/// g(q) as expressions, whichever derivation is cheaper.
pub fn gravity(dv: &Derivation<'_>) -> (SharedGraph, Vec<E>) {
    let expanded = {
        let g = SharedGraph::default();
        let e = dv.gravity_exprs(&g);
        (g, e)
    };
    let recursive = {
        let g = SharedGraph::default();
        let e = super::graph_chain(dv.model, &g).gravity_torques();
        (g, e)
    };
    super::cheapest(vec![expanded, recursive])
}
