//! Forward kinematics and the geometric Jacobian, kept as a product chain: each frame is
//! the previous one times a sparse joint step, so exact zeros and ones of the description
//! remove their multiplications.
//!
//! `P_0` (the base, and the constant part of the first joint) can be multiplied in first, so
//! that the walk starts from it, or last, onto each frame of a walk from the root frame: a
//! dense `P_0` is cheaper last, a sparse one first. Both are built; the cheaper is kept.

use crate::chain::{V3, cross};
use crate::graph::{E, SharedGraph, cost};
use dhgen_description::{ChainRef, Frame, JointKind};

/// The joint frames in the world frame, `P_0` multiplied in first or last.
pub(super) fn joint_frames(
    chain: ChainRef<'_>,
    graph: &SharedGraph,
    p0_first: bool,
) -> Vec<Frame<E>> {
    let ring = super::graph_chain(chain, graph);
    let p0 = chain.placements[0].to_ring::<E>();
    if p0_first {
        ring.joint_frames_from(p0)
    } else {
        ring.joint_frames()
            .into_iter()
            .map(|f| p0.compose(&f))
            .collect()
    }
}

/// Builds `outputs(p0_first)` both ways in fresh graphs and keeps the cheaper.
pub(super) fn cheaper_order<T>(
    mut build: impl FnMut(&SharedGraph, bool) -> T,
    roots: impl Fn(&T) -> Vec<E>,
) -> (SharedGraph, T) {
    let candidates = [true, false].map(|first| {
        let graph = SharedGraph::default();
        let out = build(&graph, first);
        (graph, out)
    });
    let total = |(graph, out): &(SharedGraph, T)| cost(graph, &roots(out));
    let [a, b] = candidates;
    if total(&b) < total(&a) { b } else { a }
}

/// The n link frames in the world frame (base applied, tool not), in a new graph.
pub fn frames(chain: ChainRef<'_>) -> (SharedGraph, Vec<Frame<E>>) {
    cheaper_order(
        |graph, first| {
            joint_frames(chain, graph, first)
                .iter()
                .zip(chain.bodies)
                .map(|(f, b)| f.compose(&b.link.to_ring()))
                .collect::<Vec<_>>()
        },
        |frames| frames.iter().flat_map(frame_entries).collect(),
    )
}

/// The tool frame in the world frame, in a new graph.
pub fn fk(chain: ChainRef<'_>) -> (SharedGraph, Frame<E>) {
    cheaper_order(
        |graph, first| tool_frame(chain, graph, first),
        frame_entries,
    )
}

fn tool_frame(chain: ChainRef<'_>, graph: &SharedGraph, p0_first: bool) -> Frame<E> {
    let last = joint_frames(chain, graph, p0_first)
        .pop()
        .expect("a chain has bodies");
    last.compose(&chain.placements[chain.dof()].to_ring())
}

fn frame_entries(f: &Frame<E>) -> Vec<E> {
    f.r.iter().flatten().chain(&f.p).cloned().collect()
}

/// The 6×n geometric Jacobian of the tool frame origin, world axes, rows `[v; ω]`,
/// column-major as `[column][row]`, in a new graph.
pub fn jacobian(chain: ChainRef<'_>) -> (SharedGraph, Vec<[E; 6]>) {
    cheaper_order(
        |graph, first| {
            let tip = tool_frame(chain, graph, first).p;
            joint_frames(chain, graph, first)
                .into_iter()
                .zip(chain.bodies)
                .map(|(f, body)| {
                    let z: V3<E> = f.z_axis();
                    column(body.joint, z.clone(), || {
                        let r: V3<E> = core::array::from_fn(|i| tip[i].clone() - f.p[i].clone());
                        cross(&z, &r)
                    })
                })
                .collect::<Vec<_>>()
        },
        |cols| cols.iter().flatten().cloned().collect(),
    )
}

/// One Jacobian column, rows `[v; ω]`, for a joint along `z`: `[moment(); z]` for a revolute
/// joint (`moment` is `z × r` in the column's axes), `[z; 0]` for a prismatic one.
fn column(joint: JointKind, z: V3<E>, moment: impl FnOnce() -> V3<E>) -> [E; 6] {
    let (v, w) = match joint {
        JointKind::Revolute => (moment(), z),
        JointKind::Prismatic => (z, core::array::from_fn(|_| E::K(0.0))),
    };
    let [v0, v1, v2] = v;
    let [w0, w1, w2] = w;
    [v0, v1, v2, w0, w1, w2]
}

/// The 6×n body Jacobian: the tool frame's Jacobian in the tool's own axes, rows `[v; ω]`,
/// column-major as `[column][row]`, in a new graph. Walked back from the tool, so the base
/// never enters: with `B_k = T_{k+1} ⋯ T_{n−1} P_n` the tool in joint frame k (rotation `R`,
/// origin `p`), joint k turns about that frame's z axis through its origin, so its column is
/// `[Rᵀ (e_z × p); Rᵀ e_z]` (revolute) or `[Rᵀ e_z; 0]` (prismatic), and `Rᵀ x` is the sum of
/// R's rows weighted by x.
pub fn body_jacobian(chain: ChainRef<'_>) -> (SharedGraph, Vec<[E; 6]>) {
    let graph = SharedGraph::default();
    let ring = super::graph_chain(chain, &graph);
    let n = chain.dof();
    let mut tool_in_k: Frame<E> = chain.placements[n].to_ring();
    let mut columns = vec![core::array::from_fn(|_| E::K(0.0)); n];
    for k in (0..n).rev() {
        let (r, p) = (&tool_in_k.r, &tool_in_k.p);
        columns[k] = column(chain.bodies[k].joint, r[2].clone(), || {
            // Rᵀ (e_z × p) = Rᵀ [−p_y, p_x, 0] = p_x · row 1 − p_y · row 0.
            core::array::from_fn(|i| {
                p[0].clone() * r[1][i].clone() - p[1].clone() * r[0][i].clone()
            })
        });
        if k > 0 {
            tool_in_k = ring.t[k].compose(&tool_in_k);
        }
    }
    (graph, columns)
}

/// `J̇(q, q̇) q̇` of the tool frame origin, world axes, rows `[v; ω]`.
pub fn jdot_qdot(chain: ChainRef<'_>, graph: &SharedGraph) -> [E; 6] {
    let ring = super::graph_chain(chain, graph);
    let n = chain.dof();
    let qd: Vec<E> = (0..n)
        .map(|i| E::sym(graph, crate::graph::Sym::Qd(i)))
        .collect();
    // The tool frame origin in the last joint frame.
    let tip = chain.placements[n].p.map(E::K);
    let a = ring.jdot_qdot(&qd, &tip);
    // From the root frame to the world.
    let p0 = chain.placements[0].to_ring::<E>();
    let v = p0.rotate(&[a[0].clone(), a[1].clone(), a[2].clone()]);
    let w = p0.rotate(&[a[3].clone(), a[4].clone(), a[5].clone()]);
    [
        v[0].clone(),
        v[1].clone(),
        v[2].clone(),
        w[0].clone(),
        w[1].clone(),
        w[2].clone(),
    ]
}

/// `J̇_b(q, q̇) q̇` of the tool frame in the tool's own axes, rows `[v; ω]`
/// ([`RingChain::body_jdot_qdot`](crate::chain::RingChain::body_jdot_qdot)).
pub fn body_jdot_qdot(chain: ChainRef<'_>, graph: &SharedGraph) -> [E; 6] {
    let ring = super::graph_chain(chain, graph);
    let qd: Vec<E> = (0..chain.dof())
        .map(|i| E::sym(graph, crate::graph::Sym::Qd(i)))
        .collect();
    ring.body_jdot_qdot(&qd, &chain.placements[chain.dof()].to_ring())
}
