//! Inverse dynamics `τ = D q̈ + C q̇ + g (+ motor inertia, friction)`.
//!
//! Two derivations compete: the recursive Newton-Euler algorithm run symbolically
//! (linear in the number of links, shares the frame rotations), and the assembled
//! `D q̈ + Σ c_ijk q̇_i q̇_j + g` from the normal forms. The cheaper is kept.

use super::Derivation;
use crate::chain::RingChain;
use crate::graph::{E, SharedGraph, Sym};
use dhgen_description::ChainRef;

/// The armature and viscous friction torques of joint i (friction's Coulomb part is emitted
/// separately, since `sign` is not arithmetic).
fn joint_terms(chain: ChainRef<'_>, i: usize, qd: &E, qdd: &E) -> E {
    let b = &chain.bodies[i];
    E::K(b.armature) * qdd.clone() + E::K(b.friction.viscous) * qd.clone()
}

/// The joint accelerations a Newton–Euler derivation runs at.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Acceleration {
    /// q̈ = 0: the bias torques.
    Zero,
    /// The symbols `qdd`: the torques τ.
    Symbolic,
}

/// The torques at joint accelerations `qdd`: the Newton-Euler recursion (gravity included),
/// plus motor inertia and viscous friction.
pub fn rnea_exprs(chain: ChainRef<'_>, graph: &SharedGraph, qdd: Acceleration) -> Vec<E> {
    rnea_with(chain, graph, qdd, super::graph_chain)
}

/// [`rnea_exprs`] on the chain `build` makes in graph arithmetic (the payload's derivations add
/// a body's worth of input symbols to its last link). The joint symbols are made first, so
/// the generated statements come in the same order whatever the chain.
pub(crate) fn rnea_with<'c>(
    chain: ChainRef<'c>,
    graph: &SharedGraph,
    acceleration: Acceleration,
    build: impl FnOnce(ChainRef<'c>, &SharedGraph) -> RingChain<'c, E>,
) -> Vec<E> {
    let n = chain.dof();
    let qd: Vec<E> = (0..n).map(|i| E::sym(graph, Sym::Qd(i))).collect();
    let qdd: Vec<E> = (0..n)
        .map(|i| match acceleration {
            Acceleration::Zero => E::K(0.0),
            Acceleration::Symbolic => E::sym(graph, Sym::Qdd(i)),
        })
        .collect();
    build(chain, graph)
        .rnea(&qd, &qdd)
        .into_iter()
        .enumerate()
        .map(|(i, t)| t + joint_terms(chain, i, &qd[i], &qdd[i]))
        .collect()
}

/// τ without Coulomb friction, whichever derivation is cheaper: the recursion, or `assembled`
/// (τ assembled from the normal forms, [`assembled`], where they are small).
pub fn inverse_dynamics(
    chain: ChainRef<'_>,
    assembled: Option<&(SharedGraph, Vec<E>)>,
) -> (SharedGraph, Vec<E>) {
    let recursive = {
        let graph = SharedGraph::default();
        let e = rnea_exprs(chain, &graph, Acceleration::Symbolic);
        (graph, e)
    };
    super::cheapest_dynamics(
        chain,
        std::iter::once(recursive)
            .chain(assembled.cloned())
            .collect(),
    )
}

/// τ without Coulomb friction assembled from the normal forms, `D q̈ + Σ c_ijk q̇_i q̇_j + g`
/// plus viscous friction (armature is in D), where they are small enough to build.
pub fn assembled(dv: &Derivation<'_>) -> Option<(SharedGraph, Vec<E>)> {
    let chain = dv.chain;
    let n = chain.dof();
    if !dv.normal_form_is_small() {
        return None;
    }
    let graph = SharedGraph::default();
    let (Some(d), Some(c), Some(gr)) = (
        dv.mass_matrix_exprs(&graph),
        dv.christoffel_exprs(&graph),
        dv.gravity_exprs(&graph),
    ) else {
        return None;
    };
    let assembled = {
        let qd: Vec<E> = (0..n).map(|i| E::sym(&graph, Sym::Qd(i))).collect();
        let qdd: Vec<E> = (0..n).map(|i| E::sym(&graph, Sym::Qdd(i))).collect();
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
                t + E::K(chain.bodies[k].friction.viscous) * qd[k].clone()
            })
            .collect();
        (graph, e)
    };
    Some(assembled)
}
