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
