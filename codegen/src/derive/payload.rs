//! The dynamics with a payload held by the tool, its ten inertial parameters kept as inputs
//! ([`Sym::Payload`]: `m, m·c` and the inertia about the tool origin, in the tool frame).
//!
//! The dynamics are linear in a body's parameters, so adding the payload's mass moments,
//! carried into the last joint frame by the tool placement `P_n`, to the last body of the
//! recursions (Newton–Euler for τ and the bias, composite bodies for D and g) costs only the
//! payload's own terms. The recursions are the plain quantities' recursion candidates; the
//! normal forms would have to be expanded in ten more variables and do not compete.

use crate::chain::{MassMoments, RingChain};
use crate::dual::Dual;
use crate::graph::{E, SharedGraph, Sym};
use dhgen_description::{ChainRef, Ring};

/// Adds the payload's mass moments (its parameters the inputs, each made a value of the
/// chain's arithmetic by `lift`), carried into the last joint frame by the tool placement, to
/// the last body of `rc`.
fn add_payload<R: Ring>(rc: &mut RingChain<'_, R>, graph: &SharedGraph, lift: impl Fn(E) -> R) {
    let n = rc.dof();
    let payload = MassMoments::of(|k| lift(E::sym(graph, Sym::Payload(k))));
    let tool = rc.chain.placements[n].to_ring::<R>();
    rc.bodies[n - 1] = rc.bodies[n - 1].plus(&payload.transformed(&tool));
}

/// The chain in graph arithmetic with the payload's mass moments added to the last body.
fn chain_with_payload<'c>(chain: ChainRef<'c>, graph: &SharedGraph) -> RingChain<'c, E> {
    let mut rc = super::graph_chain(chain, graph);
    add_payload(&mut rc, graph, |e| e);
    rc
}

/// C(q, q̇) with the payload (row-major): of the plain C's two O(n²) derivations run on the
/// chain with the payload (the recursion on dual numbers, and Echeandia and Wensing's
/// algorithm in every frame's coordinates), the cheaper: PUMA 560 1,464 operations, Panda
/// 2,380, a general 12-joint arm 6,179, where the recursion alone costs 1,924, 3,463 and
/// 17,784.
pub fn coriolis(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    let recursive = super::christoffel::coriolis_recursive_with(chain, |rc, graph| {
        add_payload(rc, graph, |v| Dual {
            v,
            d: std::rc::Rc::from(Vec::new()),
        });
    });
    let spatial =
        super::christoffel::coriolis_spatial_with(chain, |rc, graph| add_payload(rc, graph, |e| e));
    super::cheapest(vec![recursive, spatial])
}

/// `[∂τ/∂q, ∂τ/∂q̇]` with the payload (each row-major, entry `(k, m)` = ∂τ_k/∂x_m, viscous
/// friction on the diagonal of ∂τ/∂q̇), the cheapest of two of the plain derivatives'
/// candidates run on the chain with the payload: the Newton–Euler recursion on duals with 2n
/// lanes (q and q̇ seeded), and Carpentier and Mansard's closed form with the C of the same
/// terms (∂τ/∂q̇ = 2C + viscous) in joint frames and in each frame's coordinates. No joint is
/// dropped as a symmetry of the dynamics: the last link's symmetry about its axis, which
/// lets the plain derivations drop its joint, is broken by the payload. The closed form in
/// joint frames wins on the PUMA 560 (2,352 operations, where the plain derivatives cost
/// 1,531), the Panda (3,515 against 3,271) and the Stanford arm, in one frame's coordinates on
/// the UR5, the SCARA and random general arms; the dual lanes, built as every candidate is,
/// cost 1.1–2.9× the best.
pub fn inverse_dynamics_derivatives(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    let n = chain.dof();
    let viscous = |k: usize, m: usize| super::derivatives::viscous(chain, k, m);
    // Row-major from the entries (k, m) of ∂τ/∂q, then of ∂τ/∂q̇.
    let rows = |dq: &dyn Fn(usize, usize) -> E, dqd: &dyn Fn(usize, usize) -> E| -> Vec<E> {
        let entry = |idx: usize, f: &dyn Fn(usize, usize) -> E| f(idx / n, idx % n);
        (0..n * n)
            .map(|idx| entry(idx, dq))
            .chain((0..n * n).map(|idx| entry(idx, dqd) + viscous(idx / n, idx % n)))
            .collect()
    };
    let lanes = {
        let graph = SharedGraph::default();
        let tau = super::derivatives::dual_rnea_with(chain, &graph, 2 * n, |rc, graph| {
            add_payload(rc, graph, |v| Dual {
                v,
                d: std::rc::Rc::from(Vec::new()),
            });
        });
        let out = rows(&|k, m| tau[k].partial(m), &|k, m| tau[k].partial(n + m));
        (graph, out)
    };
    let mut candidates = vec![lanes];
    for at in super::frames(chain) {
        let graph = SharedGraph::default();
        let sym = |s: fn(usize) -> Sym| (0..n).map(|i| E::sym(&graph, s(i))).collect::<Vec<E>>();
        let (qd, qdd) = (sym(Sym::Qd), sym(Sym::Qdd));
        let rc = chain_with_payload(chain, &graph);
        let [dq, c] = match at {
            Some(at) => rc.inverse_dynamics_derivatives(at, &qd, &qdd),
            None => rc.inverse_dynamics_derivatives_local(&qd, &qdd),
        };
        let out = rows(&|k, m| dq[k][m].clone(), &|k, m| {
            E::K(2.0) * c[k][m].clone()
        });
        candidates.push((graph, out));
    }
    super::cheapest(candidates)
}

/// τ with the payload, without Coulomb friction; `qdd_zero`: the bias `C q̇ + g`.
pub fn rnea(
    chain: ChainRef<'_>,
    graph: &SharedGraph,
    qdd: super::newton_euler::Acceleration,
) -> Vec<E> {
    super::newton_euler::rnea_with(chain, graph, qdd, chain_with_payload)
}

/// D(q) with the payload (row-major), armature included: the cheapest of the plain D's
/// recursive candidates run on the chain with the payload.
pub fn mass_matrix(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    super::cheapest(super::inertia::recursive_candidates(chain, |rc, graph| {
        add_payload(rc, graph, |e| e)
    }))
}

/// g(q) with the payload.
pub fn gravity(chain: ChainRef<'_>, graph: &SharedGraph) -> Vec<E> {
    chain_with_payload(chain, graph).gravity_torques()
}

/// The kinetic energy with the payload: the links' (the payload in the last) along the
/// velocity recursion, and the rotors'.
pub fn kinetic_energy(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    let graph = SharedGraph::default();
    let t = super::energy::kinetic_energy_along(&chain_with_payload(chain, &graph), &graph);
    (graph, vec![t])
}

/// The potential energy with the payload, by the plain one's recursion.
pub fn potential_energy(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    let graph = SharedGraph::default();
    let p = chain_with_payload(chain, &graph).potential_energy();
    (graph, vec![p])
}
