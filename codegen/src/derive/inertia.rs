//! The joint-space inertia matrix D(q), by the composite-rigid-body algorithm, either
//! expanded into the normal form and Horner-factored, or kept as the recursion.

use super::Derivation;
use crate::graph::{E, SharedGraph};
use crate::poly::Poly;
use dhgen_model::RobotModel;

/// D(q) in the normal form, motor inertia included (row-major).
pub fn mass_matrix_polys(model: &RobotModel) -> Vec<Vec<Poly>> {
    let mut d: Vec<Vec<Poly>> = super::poly_chain(model)
        .mass_matrix()
        .into_iter()
        .map(|row| row.into_iter().map(|p| p.poly).collect())
        .collect();
    add_motors(model, &mut d, |p, x| *p = p.clone().add_constant(x));
    d
}

pub(crate) fn add_motors<X>(model: &RobotModel, d: &mut [Vec<X>], add: impl Fn(&mut X, f64)) {
    for (i, l) in model.links.iter().enumerate() {
        if let Some(m) = l.motor {
            add(&mut d[i][i], m.reflected_inertia());
        }
    }
}

/// D(q) as expressions (row-major, n×n), whichever derivation is cheaper.
pub fn mass_matrix(dv: &Derivation<'_>) -> (SharedGraph, Vec<E>) {
    let model = dv.model;
    let n = model.dof();
    let expanded = {
        let g = SharedGraph::default();
        let e = dv.mass_matrix_exprs(&g);
        (g, e)
    };
    let recursive = {
        let g = SharedGraph::default();
        let mut d = super::graph_chain(model, &g).mass_matrix();
        add_motors(model, &mut d, |e, x| *e = e.clone() + E::K(x));
        let e: Vec<E> = d.into_iter().flatten().collect();
        debug_assert_eq!(e.len(), n * n);
        (g, e)
    };
    super::cheapest(vec![expanded, recursive])
}
