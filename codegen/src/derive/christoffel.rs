//! Christoffel symbols `c_ijk = ½(∂d_kj/∂q_i + ∂d_ki/∂q_j − ∂d_ij/∂q_k)` (k the equation
//! index), by exact differentiation of D's normal form or by dual numbers.

use super::Derivation;
use crate::graph::{E, SharedGraph};
use crate::poly::Poly;
use dhgen_description::ChainRef;

/// `c[i][j][k]` in the normal form (motor inertia is constant and drops out).
pub fn christoffel_polys(chain: ChainRef<'_>, d: &[Vec<Poly>]) -> Vec<Vec<Vec<Poly>>> {
    let n = chain.dof();
    let v = super::vars(chain);
    // dd[m][a][b] = ∂d_ab/∂q_m; D is symmetric, so only a <= b is differentiated.
    let dd: Vec<Vec<Vec<Poly>>> = (0..n)
        .map(|m| {
            let mut out = vec![vec![Poly::zero(); n]; n];
            for a in 0..n {
                for b in a..n {
                    let p = d[a][b].derivative(m, &v);
                    out[b][a] = p.clone();
                    out[a][b] = p;
                }
            }
            out
        })
        .collect();
    (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    (0..n)
                        .map(|k| dd[i][k][j].add(&dd[j][k][i]).sub(&dd[k][i][j]).scale(0.5))
                        .collect()
                })
                .collect()
        })
        .collect()
}

/// `c[i][j][k]` as expressions, flattened `(i·n + j)·n + k`: the normal form
/// differentiated exactly, or the composite-rigid-body recursion differentiated by dual
/// numbers, whichever is cheaper.
pub fn christoffel(dv: &Derivation<'_>) -> (SharedGraph, Vec<E>) {
    let mut candidates = vec![christoffel_dual(dv.chain)];
    let graph = SharedGraph::default();
    if dv.normal_form_is_small()
        && let Some(e) = dv.christoffel_exprs(&graph)
    {
        candidates.push((graph, e));
    }
    super::cheapest_dynamics(dv.chain, candidates)
}

fn christoffel_dual(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    let n = chain.dof();
    let graph = SharedGraph::default();
    let duals = crate::chain::RingChain::new(chain, &crate::dual::DualSymbols { graph: &graph, n });
    let d = duals.mass_matrix();
    let dd = |m: usize, a: usize, b: usize| d[a][b].partial(m);
    let mut out = Vec::with_capacity(n * n * n);
    for i in 0..n {
        for j in 0..n {
            for k in 0..n {
                let c = (dd(i, k, j) + dd(j, k, i) - dd(k, i, j)) * E::K(0.5);
                out.push(c);
            }
        }
    }
    (graph, out)
}

/// `C(q, q̇)` row-major, `C_kj = Σ_i c_ijk q̇_i`, over the given Christoffel expressions.
pub fn coriolis_from(n: usize, graph: &SharedGraph, c: &[E]) -> Vec<E> {
    let qd: Vec<E> = (0..n)
        .map(|i| E::sym(graph, crate::graph::Sym::Qd(i)))
        .collect();
    (0..n * n)
        .map(|idx| {
            let (k, j) = (idx / n, idx % n);
            (0..n).fold(E::K(0.0), |acc, i| {
                acc + c[(i * n + j) * n + k].clone() * qd[i].clone()
            })
        })
        .collect()
}

/// `C(q, q̇)` row-major by Echeandia and Wensing's O(n²) algorithm, the cheapest of its
/// forms: in one frame's coordinates, the root frame's
/// ([`RingChain::coriolis_matrix`](crate::chain::RingChain::coriolis_matrix), the runtime
/// path's algorithm: the candidate for arms without structure) or a joint frame's, or in joint
/// frames ([`RingChain::coriolis_matrix_local`](crate::chain::RingChain::coriolis_matrix_local),
/// where the structure of the joint transforms and of the bodies' inertias stays visible:
/// Panda 1,927 → 1,602 operations, industrial 12-joint arm 3,817 → 3,305).
pub fn coriolis_spatial(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    coriolis_spatial_with(chain, |_, _| {})
}

/// [`coriolis_spatial`] on the chain changed by `adjust` (the payload's derivation adds a
/// body's worth of input symbols to its last link).
pub(crate) fn coriolis_spatial_with<'c>(
    chain: ChainRef<'c>,
    adjust: impl Fn(&mut crate::chain::RingChain<'c, E>, &SharedGraph),
) -> (SharedGraph, Vec<E>) {
    let candidates = super::frames(chain)
        .map(|at| {
            let graph = SharedGraph::default();
            let qd: Vec<E> = (0..chain.dof())
                .map(|i| E::sym(&graph, crate::graph::Sym::Qd(i)))
                .collect();
            let mut rc = super::graph_chain(chain, &graph);
            adjust(&mut rc, &graph);
            let c = match at {
                Some(at) => rc.coriolis_matrix_in(at, &qd),
                None => rc.coriolis_matrix_local(&qd),
            };
            (graph, c.into_iter().flatten().collect())
        })
        .collect();
    super::cheapest(candidates)
}

/// `C(q, q̇)` row-major in O(n²) operations, from the identity
/// `C = ½ (Ḋ + M − Mᵀ)` with `M = ∂(D q̇)/∂q`, which follows from the definition of the
/// symbols (`Σ_i q̇_i ∂d_kj/∂q_i = Ḋ_kj`, `Σ_i q̇_i ∂d_ki/∂q_j = ∂(D q̇)_k/∂q_j`, D symmetric):
/// `Ḋ` by one lane of dual numbers (the derivative along q̇) over the composite-rigid-body
/// recursion, `M` by n lanes over the momentum recursion `D q̇`, both O(n²), instead of the n³
/// symbols.
pub fn coriolis_recursive(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    coriolis_recursive_with(chain, |_, _| {})
}

/// [`coriolis_recursive`] on the chain changed by `adjust` (the payload's derivation adds a
/// body's worth of input symbols to its last link).
pub(crate) fn coriolis_recursive_with<'c>(
    chain: ChainRef<'c>,
    adjust: impl Fn(&mut crate::chain::RingChain<'c, crate::dual::Dual>, &SharedGraph),
) -> (SharedGraph, Vec<E>) {
    use crate::chain::RingChain;
    use crate::dual::{Dual, DualSymbols, RateSymbols};
    let n = chain.dof();
    let graph = SharedGraph::default();
    let mut rate = RingChain::new(chain, &RateSymbols { graph: &graph });
    adjust(&mut rate, &graph);
    let d_dot = rate.mass_matrix();
    let qd: Vec<Dual> = (0..n)
        .map(|i| Dual {
            v: E::sym(&graph, crate::graph::Sym::Qd(i)),
            d: std::rc::Rc::from(Vec::new()),
        })
        .collect();
    let mut duals = RingChain::new(chain, &DualSymbols { graph: &graph, n });
    adjust(&mut duals, &graph);
    let momentum = duals.momentum(&qd);
    let c = (0..n * n)
        .map(|idx| {
            let (k, j) = (idx / n, idx % n);
            (d_dot[k][j].partial(0) + momentum[k].partial(j) - momentum[j].partial(k)) * E::K(0.5)
        })
        .collect();
    (graph, c)
}
