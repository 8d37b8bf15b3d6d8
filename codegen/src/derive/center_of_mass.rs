//! The centre of mass of the links, `c(q)`, and its Jacobian `J_c = ∂c/∂q`, world frame
//! (Pinocchio's `centerOfMass` and `jacobianCenterOfMass`), from the links as described (not
//! [grouped](crate::chain::grouped): grouping keeps the dynamics, not per-link sums such as
//! this one).
//!
//! One walk tip to base gives, per joint k, the mass `M_k` of links k.. and their first
//! moment `h_k` about joint frame k's origin in its axes, and at the root the whole arm's
//! (the walk of the potential energy, `P = −M gravity · c`). Column k of `J_c` is then the
//! velocity that joint k alone gives those links' centre, in frame k's axes `e_z × h_k / M`
//! (revolute) or `e_z M_k / M` (prismatic), turned into the world by frame k's rotation: O(n)
//! operations; `c` differentiated along each joint in its graph is the other candidate.

use crate::chain::{V3, described};
use crate::graph::{E, SharedGraph, joint_tangent};
use dhgen_description::{ChainRef, JointKind};

/// `1 / M` for the links' total mass `M`, or 1 where they have none (every first moment is
/// then zero, and so are `c` and `J_c`, as on the runtime path).
fn inverse_mass(chain: ChainRef<'_>) -> f64 {
    let mass: f64 = described::<f64>(chain).map(|(m, _)| m).sum();
    if mass > 0.0 { 1.0 / mass } else { 1.0 }
}

/// `[M, c_x, c_y, c_z]`: the links' total mass and their centre of mass in the world frame,
/// in a new graph.
pub fn center_of_mass(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    let graph = SharedGraph::default();
    let ring = super::graph_chain(chain, &graph);
    let (_, (mass, h)) = ring.first_moments(described(chain));
    // World = P_0 · root: c = (R_0 h + M p_0) / M.
    let p0 = chain.placements[0];
    let inv = inverse_mass(chain);
    let c = (0..3).map(|r| {
        let turned = (0..3).fold(E::K(0.0), |acc, i| acc + E::K(p0.r[r][i]) * h[i].clone());
        (turned + mass.clone() * E::K(p0.p[r])) * E::K(inv)
    });
    let out = std::iter::once(mass.clone()).chain(c).collect();
    (graph, out)
}

/// The 3×n Jacobian of the centre of mass, world axes, column-major, in a new graph: by the
/// columns above (the joint frames' rotations built with `P_0` first or last), or `c`
/// differentiated along each joint in its graph, whichever costs least.
pub fn center_of_mass_jacobian(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    let differentiated = {
        let (graph, mc) = center_of_mass(chain);
        let c = &mc[1..];
        let columns: Vec<E> = (0..chain.dof())
            .flat_map(|j| crate::graph::derivative(&graph, c, joint_tangent(&graph, j)))
            .collect();
        (graph, columns)
    };
    super::cheapest(vec![by_columns(chain), differentiated])
}

/// [`center_of_mass_jacobian`] column by column.
fn by_columns(chain: ChainRef<'_>) -> (SharedGraph, Vec<E>) {
    let inv = inverse_mass(chain);
    let (graph, columns) = super::kinematics::cheaper_order(
        |graph, first| {
            let ring = super::graph_chain(chain, graph);
            let (per_joint, _) = ring.first_moments(described(chain));
            super::kinematics::joint_frames(chain, graph, first)
                .into_iter()
                .zip(per_joint)
                .zip(chain.bodies)
                .map(|((frame, (mass, h)), body)| {
                    // The velocity in frame k's axes, then R_k times it.
                    let local: V3<E> = match body.joint {
                        JointKind::Revolute => [
                            -(h[1].clone() * E::K(inv)),
                            h[0].clone() * E::K(inv),
                            E::K(0.0),
                        ],
                        JointKind::Prismatic => [E::K(0.0), E::K(0.0), mass * E::K(inv)],
                    };
                    crate::chain::rot(&frame, &local)
                })
                .collect::<Vec<V3<E>>>()
        },
        |columns| columns.iter().flatten().cloned().collect(),
    );
    let out = columns.into_iter().flatten().collect();
    (graph, out)
}
