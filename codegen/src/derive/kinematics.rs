//! Forward kinematics and the geometric Jacobian, kept as a product chain: each frame is
//! the previous one times a sparse link transform, so exact zeros and ones of the DH
//! table remove their multiplications.

use crate::chain::{V3, cross};
use crate::graph::{E, SharedGraph};
use dhgen_model::{Frame, RobotModel};

/// The n link frames in the world frame (base applied, tool not).
pub fn frames(model: &RobotModel, g: &SharedGraph) -> Vec<Frame<E>> {
    let chain = super::graph_chain(model, g);
    let base = model.base_pose().map(|b| b.frame::<E>());
    chain
        .link_frames()
        .into_iter()
        .map(|f| match &base {
            Some(b) => b.compose(&f),
            None => f,
        })
        .collect()
}

/// The tool frame in the world frame.
pub fn fk(model: &RobotModel, g: &SharedGraph) -> Frame<E> {
    let last = frames(model, g).pop().expect("validated models have links");
    match model.tool_pose() {
        Some(t) => last.compose(&t.frame()),
        None => last,
    }
}

/// The 6×n geometric Jacobian of the tool frame origin, world axes, rows `[v; ω]`,
/// column-major as `[column][row]`.
pub fn jacobian(model: &RobotModel, g: &SharedGraph) -> Vec<[E; 6]> {
    let chain = super::graph_chain(model, g);
    let base = model.base_pose().map(|b| b.frame::<E>());
    let world = |f: Frame<E>| match &base {
        Some(b) => b.compose(&f),
        None => f,
    };
    let tip = fk(model, g).p;
    chain
        .joint_frames()
        .into_iter()
        .zip(&chain.kinds)
        .map(|(f, kind)| {
            let f = world(f);
            let z: V3<E> = f.z_axis();
            match kind {
                dhgen_model::JointKind::Revolute => {
                    let r: V3<E> = core::array::from_fn(|i| tip[i].clone() - f.p[i].clone());
                    let v = cross(&z, &r);
                    [
                        v[0].clone(),
                        v[1].clone(),
                        v[2].clone(),
                        z[0].clone(),
                        z[1].clone(),
                        z[2].clone(),
                    ]
                }
                dhgen_model::JointKind::Prismatic => [
                    z[0].clone(),
                    z[1].clone(),
                    z[2].clone(),
                    E::K(0.0),
                    E::K(0.0),
                    E::K(0.0),
                ],
            }
        })
        .collect()
}

/// `J̇(q, q̇) q̇` of the tool frame origin, world axes, rows `[v; ω]`.
pub fn jdot_qdot(model: &RobotModel, g: &SharedGraph) -> [E; 6] {
    let chain = super::graph_chain(model, g);
    let n = model.dof();
    let qd: Vec<E> = (0..n)
        .map(|i| E::sym(g, crate::graph::Sym::Qd(i)))
        .collect();
    // The tool frame origin in the last joint frame.
    let last = &chain.link_in_k[n - 1];
    let tip = match model.tool_pose() {
        Some(t) => last.point(&t.xyz.map(E::K)),
        None => last.p.clone(),
    };
    let a = chain.jdot_qdot(&qd, &tip);
    match model.base_pose() {
        Some(b) => {
            let f = b.frame::<E>();
            let v = crate::chain::rot(&f, &[a[0].clone(), a[1].clone(), a[2].clone()]);
            let w = crate::chain::rot(&f, &[a[3].clone(), a[4].clone(), a[5].clone()]);
            [
                v[0].clone(),
                v[1].clone(),
                v[2].clone(),
                w[0].clone(),
                w[1].clone(),
                w[2].clone(),
            ]
        }
        None => a,
    }
}
