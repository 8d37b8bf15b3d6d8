//! Inverse dynamics `τ = D q̈ + C q̇ + g (+ motor inertia, friction)`.
//!
//! Two derivations compete: the recursive Newton-Euler algorithm run symbolically
//! (linear in the number of links, shares the frame rotations), and the assembled
//! `D q̈ + Σ c_ijk q̇_i q̇_j + g` from the normal forms. The cheaper is kept.

use super::Derivation;
use crate::graph::{E, SharedGraph, Sym};
use dhgen_model::RobotModel;

/// Motor inertia and friction terms added to joint i's torque (friction's Coulomb part
/// is emitted separately, since `sign` is not arithmetic).
fn motor_term(model: &RobotModel, i: usize, qdd: &E) -> E {
    match model.links[i].motor {
        Some(m) => E::K(m.reflected_inertia()) * qdd.clone(),
        None => E::K(0.0),
    }
}

fn viscous_term(model: &RobotModel, i: usize, qd: &E) -> E {
    match model.links[i].friction {
        Some(f) => E::K(f.viscous) * qd.clone(),
        None => E::K(0.0),
    }
}

/// The bias torques without gravity or with it, and with q̈ as given: the Newton-Euler
/// recursion, plus motor inertia and viscous friction.
pub fn rnea_exprs(
    model: &RobotModel,
    g: &SharedGraph,
    qdd_zero: bool,
    with_gravity: bool,
) -> Vec<E> {
    let n = model.dof();
    let chain = super::graph_chain(model, g);
    let qd: Vec<E> = (0..n).map(|i| E::sym(g, Sym::Qd(i))).collect();
    let qdd: Vec<E> = (0..n)
        .map(|i| {
            if qdd_zero {
                E::K(0.0)
            } else {
                E::sym(g, Sym::Qdd(i))
            }
        })
        .collect();
    chain
        .rnea(&qd, &qdd, with_gravity)
        .into_iter()
        .enumerate()
        .map(|(i, t)| t + motor_term(model, i, &qdd[i]) + viscous_term(model, i, &qd[i]))
        .collect()
}

/// τ without Coulomb friction, whichever derivation is cheaper.
pub fn inverse_dynamics(dv: &Derivation<'_>) -> (SharedGraph, Vec<E>) {
    let model = dv.model;
    let n = model.dof();
    let recursive = {
        let g = SharedGraph::default();
        let e = rnea_exprs(model, &g, false, true);
        (g, e)
    };
    if !dv.normal_form_is_small() {
        return recursive;
    }
    let assembled = {
        let g = SharedGraph::default();
        let d = dv.mass_matrix_exprs(&g);
        let c = dv.christoffel_exprs(&g);
        let gr = dv.gravity_exprs(&g);
        let qd: Vec<E> = (0..n).map(|i| E::sym(&g, Sym::Qd(i))).collect();
        let qdd: Vec<E> = (0..n).map(|i| E::sym(&g, Sym::Qdd(i))).collect();
        let e = (0..n)
            .map(|k| {
                let mut t = gr[k].clone();
                for j in 0..n {
                    t = t + d[k * n + j].clone() * qdd[j].clone();
                    // Σ_ij c_ijk q̇_i q̇_j with the symmetry c_ijk = c_jik.
                    for i in 0..=j {
                        let f = if i == j { 1.0 } else { 2.0 };
                        t = t + E::K(f)
                            * c[(i * n + j) * n + k].clone()
                            * (qd[i].clone() * qd[j].clone());
                    }
                }
                t + viscous_term(model, k, &qd[k])
            })
            .collect();
        (g, e)
    };
    super::cheapest(vec![recursive, assembled])
}
