//! The kinetic energy `T(q, q̇) = ½ q̇ᵀ D(q) q̇` (armature included): the quadratic form over
//! the cheapest D(q), or the links' energies summed along the velocity recursion, whichever is
//! cheaper; and the potential energy `P(q)`.

use super::Derivation;
use crate::chain::RingChain;
use crate::graph::{E, SharedGraph, Sym};
use dhgen_description::JointKind;

/// `[T]`, in a new graph.
pub fn kinetic_energy(dv: &Derivation<'_>) -> (SharedGraph, Vec<E>) {
    let chain = dv.chain;
    let n = chain.dof();
    let quadratic = {
        let (graph, d) = super::inertia::mass_matrix(dv);
        let qd: Vec<E> = (0..n).map(|i| E::sym(&graph, Sym::Qd(i))).collect();
        // ½ Σ_i d_ii q̇_i² + Σ_{i<j} d_ij q̇_i q̇_j, D being symmetric.
        let mut t = E::K(0.0);
        for i in 0..n {
            let row = (i..n).fold(
                E::K(0.5) * d[i * n + i].clone() * qd[i].clone(),
                |acc, j| {
                    if j == i {
                        acc
                    } else {
                        acc + d[i * n + j].clone() * qd[j].clone()
                    }
                },
            );
            t = t + row * qd[i].clone();
        }
        (graph, vec![t])
    };
    let recursive = {
        let graph = SharedGraph::default();
        let t = kinetic_energy_along(&super::graph_chain(chain, &graph), &graph);
        (graph, vec![t])
    };
    super::cheapest_dynamics(dv.chain, vec![quadratic, recursive])
}

/// The kinetic energy of the links of `rc` (in `graph`) summed along the velocity recursion,
/// and of the rotors.
pub fn kinetic_energy_along(rc: &RingChain<'_, E>, graph: &SharedGraph) -> E {
    let qd: Vec<E> = (0..rc.dof()).map(|i| E::sym(graph, Sym::Qd(i))).collect();
    let links = rc.kinetic_energy(&qd);
    let rotors = rc
        .chain
        .bodies
        .iter()
        .zip(&qd)
        .fold(E::K(0.0), |acc, (b, w)| {
            acc + E::K(0.5 * b.armature) * (w.clone() * w.clone())
        });
    links + rotors
}

/// `[P]`, the potential energy `−Σ m_k gravity · c_k` (world frame), in a new graph: the
/// recursion over the chain or its normal form, whichever is cheaper. Of the joints the
/// dynamics ignore ([`ChainRef::dynamics_ignore`](dhgen_description::ChainRef::dynamics_ignore)),
/// only the revolute ones leave `P` unchanged (a first prismatic joint along gravity lifts
/// the whole arm: `g(q)` does not depend on it, `P` does), so only those are dropped.
pub fn potential_energy(dv: &Derivation<'_>) -> (SharedGraph, Vec<E>) {
    let chain = dv.chain;
    let expanded = dv.potential_energy_poly().map(|poly| {
        let graph = SharedGraph::default();
        let e = super::polys_to_exprs(&[poly], &graph, chain);
        (graph, e)
    });
    let recursive = {
        let graph = SharedGraph::default();
        let p = super::graph_chain(chain, &graph).potential_energy();
        (graph, vec![p])
    };
    let candidates = expanded
        .into_iter()
        .chain([recursive])
        .map(|(graph, e)| {
            let e = super::without_joints(chain, &graph, &e, |j| {
                chain.bodies[j].joint == JointKind::Revolute && chain.dynamics_ignore(j)
            });
            (graph, e)
        })
        .collect();
    super::cheapest(candidates)
}
