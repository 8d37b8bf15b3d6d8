//! Derivatives of the dynamics: ∂τ/∂q and ∂τ/∂q̇ (what MPC and trajectory optimisation
//! linearise), Ḋ(q, q̇) and Cᵀ(q, q̇) q̇ (what a momentum observer needs every cycle).
//!
//! By recursions, or by differentiating normal forms where they are small:
//! - ∂τ/∂q, ∂τ/∂q̇: the Newton-Euler recursion on duals with 2n lanes (n seeded by the joint
//!   angles, n by the joint velocities), or 2C + diag(viscous) for ∂τ/∂q̇ with ∂τ/∂q by n
//!   lanes of duals or in closed form (Carpentier and Mansard's analytic derivatives), or
//!   τ assembled from the normal forms of D, c_ijk and g differentiated symbolically,
//!   whichever is cheapest, O(n²) operations;
//! - Ḋ: one lane along q̇ over the composite-rigid-body recursion, or C + Cᵀ from the O(n²)
//!   Coriolis recursion, whichever is cheaper;
//! - Cᵀq̇ from that same C, or as the gradient of the kinetic energy, ∂T/∂q (for the
//!   Christoffel-consistent C the two are equal), by n lanes of dual numbers.
//!
//! Coulomb friction `coulomb·sign(q̇)` is not differentiable at q̇ = 0 and constant elsewhere:
//! its derivative is taken as 0 everywhere (the subgradient at 0 that is also the derivative
//! at every other velocity), so these functions differentiate the smooth part of τ.

use super::Derivation;
use crate::chain::{Coordinates, RingChain};
use crate::dual::{Dual, DualSymbols, RateSymbols};
use crate::graph::{E, SharedGraph, Sym};
use dhgen_description::ChainRef;
use std::rc::Rc;

/// Entry `(k, m)` of the viscous friction's ∂τ/∂q̇: its coefficient on the diagonal.
pub(super) fn viscous(chain: ChainRef<'_>, k: usize, m: usize) -> E {
    E::K(if k == m {
        chain.bodies[k].friction.viscous
    } else {
        0.0
    })
}

/// The Newton–Euler recursion on duals in `graph`: `lanes` = n seeds the joint variables only,
/// 2n also the joint velocities (lanes n..2n). Returns τ as duals.
fn dual_rnea(chain: ChainRef<'_>, graph: &SharedGraph, lanes: usize) -> Vec<Dual> {
    dual_rnea_with(chain, graph, lanes, |_, _| {})
}

/// [`dual_rnea`] on the chain as `modify` leaves it (the payload's derivatives add a body's
/// worth of input symbols to its last link).
pub(super) fn dual_rnea_with<'c>(
    chain: ChainRef<'c>,
    graph: &SharedGraph,
    lanes: usize,
    modify: impl FnOnce(&mut RingChain<'c, Dual>, &SharedGraph),
) -> Vec<Dual> {
    let n = chain.dof();
    let symbols = DualSymbols { graph, n: lanes };
    let qd: Vec<Dual> = (0..n)
        .map(|i| Dual {
            v: E::sym(graph, Sym::Qd(i)),
            d: if lanes > n {
                (0..lanes)
                    .map(|m| E::K(if m == n + i { 1.0 } else { 0.0 }))
                    .collect()
            } else {
                Rc::from(Vec::new())
            },
        })
        .collect();
    let qdd: Vec<Dual> = (0..n)
        .map(|i| Dual {
            v: E::sym(graph, Sym::Qdd(i)),
            d: Rc::from(Vec::new()),
        })
        .collect();
    let mut rc = RingChain::new(chain, &symbols);
    modify(&mut rc, graph);
    rc.rnea(&qd, &qdd)
}

/// `[∂τ/∂q row-major, ∂τ/∂q̇ row-major]`: `2n²` scalars, entry `(k, m)` = ∂τ_k/∂x_m; the
/// cheapest of four kinds of candidate:
/// - the Newton–Euler recursion on duals with 2n lanes (q and q̇ seeded), in its own graph;
/// - for each derivation of C in `coriolis`, in C's graph: ∂τ/∂q̇ = 2C + diag(viscous) (for
///   the Christoffel-consistent C, ∂(C q̇)/∂q̇ = 2C), which shares what C already computes,
///   and ∂τ/∂q by n lanes (q only) of duals over Newton–Euler;
/// - for each frame's coordinates ([`coordinates`](super::coordinates)), in its own graph:
///   ∂τ/∂q in closed form ([`RingChain::inverse_dynamics_derivatives`], Carpentier and
///   Mansard's analytic derivatives) with the C of Echeandia and Wensing's terms it shares;
/// - where D, c_ijk and g have small normal forms, τ assembled from them (`assembled`, see
///   [`newton_euler::assembled`](super::newton_euler::assembled)) differentiated in its graph
///   ([`derivative`](crate::graph::derivative)) along every q_j and q̇_j, each column mixed
///   with a dual lane over Newton–Euler (∂τ/∂q) or 2C (∂τ/∂q̇) built in the same graph,
///   whichever mix costs least ([`cheapest_mix`](super::cheapest_mix)); with structure this
///   wins: Stanford arm 2,128 → 1,701, UR5 1,947 → 1,336, SCARA 99 → 26, PUMA 560 2,143 →
///   1,951 (the normal forms for ∂τ/∂q̇ and for ∂τ/∂q along q1–q3 and q6, dual lanes along
///   q4 and q5).
pub fn inverse_dynamics_derivatives(
    dv: &Derivation<'_>,
    coriolis: &[(SharedGraph, Vec<E>)],
    assembled: Option<&(SharedGraph, Vec<E>)>,
) -> (SharedGraph, Vec<E>) {
    let chain = dv.chain;
    let n = chain.dof();
    // Column m of ∂τ/∂q from `column`.
    let dq_column = |m: usize, column: &dyn Fn(usize) -> E| -> Vec<E> {
        super::along_joint(chain, m, vec![E::K(0.0); n], || {
            (0..n).map(column).collect()
        })
    };
    // ∂τ/∂q row-major from its entries (k, m).
    let dq_rows = |entry: &dyn Fn(usize, usize) -> E| -> Vec<E> {
        let columns: Vec<Vec<E>> = (0..n).map(|m| dq_column(m, &|k| entry(k, m))).collect();
        (0..n * n)
            .map(|idx| columns[idx % n][idx / n].clone())
            .collect()
    };
    let viscous = |k: usize, m: usize| viscous(chain, k, m);
    let both_lanes = {
        let graph = SharedGraph::default();
        let tau = dual_rnea(chain, &graph, 2 * n);
        let mut out = dq_rows(&|k, m| tau[k].partial(m));
        for (k, t) in tau.iter().enumerate() {
            out.extend((0..n).map(|m| t.partial(n + m) + viscous(k, m)));
        }
        (graph, out)
    };
    // Entry (k, m) of ∂τ/∂q̇ = 2C + diag(viscous), C row-major.
    let twice_c = |c: &[E], k: usize, m: usize| E::K(2.0) * c[k * n + m].clone() + viscous(k, m);
    let twice_c_rows = |c: &[E], out: &mut Vec<E>| {
        out.extend((0..n * n).map(|idx| twice_c(c, idx / n, idx % n)));
    };
    let mut candidates = vec![both_lanes];
    for (graph, c) in coriolis {
        let tau = dual_rnea(chain, graph, n);
        let mut out = dq_rows(&|k, m| tau[k].partial(m));
        twice_c_rows(c, &mut out);
        candidates.push((graph.clone(), out));
    }
    // The closed form with the C of the same terms, in joint frames and in each frame's
    // coordinates.
    for at in super::frames(chain) {
        let graph = SharedGraph::default();
        let sym = |s: fn(usize) -> Sym| (0..n).map(|i| E::sym(&graph, s(i))).collect::<Vec<E>>();
        let rc = super::graph_chain(chain, &graph);
        let (qd, qdd) = (sym(Sym::Qd), sym(Sym::Qdd));
        let [dq, c] = match at {
            Some(at) => rc.inverse_dynamics_derivatives(at, &qd, &qdd),
            None => rc.inverse_dynamics_derivatives_local(&qd, &qdd),
        };
        let mut out = dq_rows(&|k, m| dq[k][m].clone());
        twice_c_rows(&c.concat(), &mut out);
        candidates.push((graph, out));
    }
    // τ assembled from the normal forms differentiated symbolically, in its graph: forward
    // mode along each q_j (d cos θ_j = −sin θ_j, d sin θ_j = cos θ_j, d d_j = 1) and each q̇_j;
    // each column of ∂τ/∂q taken from that or from a dual lane over Newton–Euler built in
    // the same graph, each column of ∂τ/∂q̇ from that or from 2C + diag(viscous) with C
    // contracted from the symbols in the same graph, whichever mix costs least. (The
    // recursion differentiated symbolically never wins: the dual lanes are the same
    // derivatives, built with more sharing.)
    if let Some((graph, tau)) = assembled {
        // Along q_j (`wrt_q`, the angle or the displacement) or along q̇_j.
        let along = |wrt_q: bool, j: usize| {
            if wrt_q {
                crate::graph::derivative(graph, tau, crate::graph::joint_tangent(graph, j))
            } else {
                crate::graph::derivative(graph, tau, |s| E::K(f64::from(s == Sym::Qd(j))))
            }
        };
        let lanes = dual_rnea(chain, graph, n);
        let c = dv
            .christoffel_exprs(graph)
            .map(|c| super::christoffel::coriolis_from(n, graph, &c));
        let mut columns: Vec<Vec<Vec<E>>> = (0..n)
            .map(|j| {
                let symbolic = along(true, j);
                vec![
                    dq_column(j, &|k| symbolic[k].clone()),
                    dq_column(j, &|k| lanes[k].partial(j)),
                ]
            })
            .collect();
        columns.extend((0..n).map(|j| {
            let mut options = vec![along(false, j)];
            if let Some(c) = &c {
                options.push((0..n).map(|k| twice_c(c, k, j)).collect());
            }
            options
        }));
        // Row-major `(k, j)` = ∂τ_k/∂x_j from the columns: ∂τ/∂q's, then ∂τ/∂q̇'s.
        for options in &mut columns {
            for option in options.iter_mut() {
                *option = super::without_ignored_joints(chain, graph, option);
            }
        }
        let chosen = super::cheapest_mix(graph, &columns);
        let out = (0..2 * n * n)
            .map(|idx| {
                let (half, k, j) = (idx / (n * n), idx % (n * n) / n, idx % n);
                chosen[half * n + j][k].clone()
            })
            .collect();
        candidates.push((graph.clone(), out));
    }
    super::cheapest_dynamics(chain, candidates)
}

/// D(q) row-major built in `graph`, beside the outputs `outs` of ∂τ's derivation there, and
/// the operations it adds to them: of the normal form and the composite-rigid-body recursion
/// in joint frames or in any frame's coordinates, the one adding fewest. ∂τ's derivation
/// holds much of what D needs (the normal forms' terms, composite inertias), so D costs a
/// fraction of its own cheapest derivation there: PUMA 560 99 operations instead of 171
/// (the normal form), Panda 161 instead of 443 (beside Carpentier and Mansard's closed
/// form).
pub fn mass_matrix_beside(dv: &Derivation<'_>, graph: &SharedGraph, outs: &[E]) -> (Vec<E>, usize) {
    let chain = dv.chain;
    let n = chain.dof();
    let before = crate::graph::cost(graph, outs);
    let recursive = |at: Option<Coordinates>| {
        let d = super::inertia::recursive(chain, &super::graph_chain(chain, graph), at);
        super::without_ignored_joints(chain, graph, &d)
    };
    dv.mass_matrix_exprs(graph)
        .into_iter()
        .chain(super::frames(chain).map(recursive))
        .inspect(|d| debug_assert_eq!(d.len(), n * n))
        .map(|d| {
            let added = crate::graph::cost(graph, outs.iter().chain(&d)) - before;
            (d, added)
        })
        .min_by_key(|(_, added)| *added)
        .expect("at least one candidate")
}

/// Ḋ(q, q̇) row-major, the cheapest of the rate lane over the composite-rigid-body recursion
/// and C + Cᵀ for each derivation of C in `coriolis`.
pub fn mass_matrix_rate(
    chain: ChainRef<'_>,
    coriolis: &[(SharedGraph, Vec<E>)],
) -> (SharedGraph, Vec<E>) {
    let n = chain.dof();
    let rate = {
        let graph = SharedGraph::default();
        let d = RingChain::new(chain, &RateSymbols { graph: &graph }).mass_matrix();
        let e = (0..n * n)
            .map(|idx| d[idx / n][idx % n].partial(0))
            .collect();
        (graph, e)
    };
    let mut candidates = vec![rate];
    candidates.extend(coriolis.iter().map(|(graph, c)| {
        let e = (0..n * n)
            .map(|idx| {
                let (k, j) = (idx / n, idx % n);
                c[k * n + j].clone() + c[j * n + k].clone()
            })
            .collect();
        (graph.clone(), e)
    }));
    super::cheapest(candidates)
}

/// Cᵀ(q, q̇) q̇ (entry j is Σ_k C_kj q̇_k), the cheapest of: contracted from each derivation
/// of C in `coriolis`, or the gradient ∂T/∂q of the kinetic energy `T = ½ q̇ᵀ D q̇`, which
/// it equals for the Christoffel-consistent C (Panda 1,690 → 1,177 operations, PUMA 560
/// 651 → 259).
pub fn coriolis_transpose_qd(
    chain: ChainRef<'_>,
    coriolis: &[(SharedGraph, Vec<E>)],
) -> (SharedGraph, Vec<E>) {
    let n = chain.dof();
    // Σ_k C_kj q̇_k = Σ_ik c_ijk q̇_i q̇_k = ½ q̇ᵀ (∂D/∂q_j) q̇ (the symbols' other two terms
    // cancel in the double sum): the gradient of the kinetic energy, by n lanes of dual
    // numbers over its recursion; zero along a joint the dynamics cannot see.
    let gradient = {
        let graph = SharedGraph::default();
        let qd: Vec<Dual> = (0..n)
            .map(|i| Dual {
                v: E::sym(&graph, Sym::Qd(i)),
                d: Rc::from(Vec::new()),
            })
            .collect();
        let t = RingChain::new(chain, &DualSymbols { graph: &graph, n }).kinetic_energy(&qd);
        let e: Vec<E> = (0..n)
            .map(|j| super::along_joint(chain, j, E::K(0.0), || t.partial(j)))
            .collect();
        let e = super::without_ignored_joints(chain, &graph, &e);
        (graph, e)
    };
    let candidates = coriolis
        .iter()
        .map(|(graph, c)| {
            let qd: Vec<E> = (0..n).map(|i| E::sym(graph, Sym::Qd(i))).collect();
            let e = (0..n)
                .map(|j| {
                    (0..n).fold(E::K(0.0), |acc, k| {
                        acc + c[k * n + j].clone() * qd[k].clone()
                    })
                })
                .collect();
            (graph.clone(), e)
        })
        .chain(std::iter::once(gradient))
        .collect();
    super::cheapest(candidates)
}
