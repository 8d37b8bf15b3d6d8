//! A description's kinematic structure: the chain `T(q) = P0 Z1(q1) P1 ⋯ Zn(qn) Pn` that
//! every consumer reads (`dhgen_kernel::chain` explains how a DH row or a URDF joint factors
//! into it), built once from the validated model.

use crate::{Angle, Body, Convention, Frame, JointChain, JointKind, JointValue, RobotModel};

/// The chain of a description: [`RobotModel::chain`] (so that `DecoupledIk::from_model` takes
/// a description).
impl From<&RobotModel> for JointChain {
    fn from(model: &RobotModel) -> JointChain {
        model.chain()
    }
}

impl RobotModel {
    /// The kinematic structure of the robot: its chain of fixed transforms and joint
    /// motions, with each link's mass properties in its joint's frame. Build it once and
    /// keep it; see [`JointChain`].
    pub fn chain(&self) -> JointChain {
        let model = self;
        let n = model.dof();
        let conv = model.convention;
        let base = model
            .base_pose()
            .map_or_else(Frame::identity, |p| p.frame::<f64>());
        let tool = model
            .tool_pose()
            .map_or_else(Frame::identity, |p| p.frame::<f64>());
        // Per row: what stands before the joint (B_k), the link frame in the joint frame
        // (L_k), the constant half of the joint factor (C_k), and the joint's offset.
        let mut before = Vec::with_capacity(n);
        let mut link = Vec::with_capacity(n);
        let mut constant = Vec::with_capacity(n);
        let mut offset: Vec<f64> = Vec::with_capacity(n);
        for l in &model.links {
            let (b, k, c, o) = match (conv, &l.placement) {
                (Convention::Urdf, Some(p)) => {
                    // A_k = origin · Rot(axis, q) = (origin · A) · Rz(q) · Aᵀ.
                    let a = Frame {
                        r: p.alignment(),
                        p: [0.0; 3],
                    };
                    let origin = p.origin.frame::<f64>();
                    (origin.compose(&a), a.inverse(), Frame::identity(), 0.0)
                }
                _ => {
                    // F_k: the row's formula at θ = d = 0; C_k: the half of Rz(θ) Tz(d)
                    // the joint does not move; the offset: the other.
                    let fixed = l.dh_transform(conv, 1.0, 0.0, 0.0);
                    let (c, o) = match l.joint {
                        JointKind::Revolute => {
                            (JointValue::Prismatic(l.d).motion(), l.theta.radians())
                        }
                        JointKind::Prismatic => {
                            let (cos, sin) = l.theta.cos_sin();
                            (JointValue::Revolute { cos, sin }.motion(), l.d)
                        }
                    };
                    match conv {
                        Convention::Standard => (Frame::identity(), fixed, c, o),
                        _ => (fixed, Frame::identity(), c, o),
                    }
                }
            };
            before.push(b);
            link.push(k);
            constant.push(c);
            offset.push(o);
        }
        let mut placements = Vec::with_capacity(n + 1);
        placements.push(base.compose(&before[0]).compose(&constant[0]));
        for k in 1..n {
            placements.push(link[k - 1].compose(&before[k]).compose(&constant[k]));
        }
        placements.push(link[n - 1].compose(&tool));
        if conv == Convention::Urdf {
            // A URDF origin may turn the joint frame about the joint's own axis (UR's
            // parallel shoulder and elbow axes, a quarter turn apart): that turn belongs
            // to the joint's offset, as in a DH table, where the symbolic engine sees
            // parallel axes with no rotation between them and adds their angles.
            for k in 0..n {
                if model.links[k].joint == JointKind::Revolute {
                    let theta = turn_about_z(&placements[k].r);
                    if theta != 0.0 {
                        let (cos, sin) = Angle::from_radians(-theta).cos_sin();
                        placements[k] =
                            placements[k].compose(&JointValue::Revolute { cos, sin }.motion());
                        offset[k] += theta;
                    }
                }
            }
        }
        let bodies = model
            .links
            .iter()
            .zip(link)
            .zip(offset)
            .map(|((l, link), offset)| Body {
                joint: l.joint,
                offset,
                limits: l.limits,
                armature: l.motor.map_or(0.0, |m| m.armature()),
                friction: l.friction.unwrap_or_default(),
                inertial: l.inertial.map(|i| i.in_frame(&link)),
                capsule: l.collision.map(|c| c.radius),
                link,
            })
            .collect();
        JointChain::from_parts(base, placements, bodies, model.gravity)
    }
}

/// The angle θ of the last factor of `r = Rz(ψ) · Rx(α) · Rz(θ)` (ZXZ angles), with
/// |θ| ≤ π/2 where the choice is free; for a rotation about z alone (α = 0 or π), all of
/// it. Exact multiples of π/2 for rotations with entries in {−1, 0, 1}.
fn turn_about_z(r: &[[f64; 3]; 3]) -> f64 {
    let (r20, r21) = (r[2][0], r[2][1]);
    let theta = if r20 == 0.0 && r21 == 0.0 {
        if r[2][2] > 0.0 {
            // Rz(θ)
            r[1][0].atan2(r[0][0])
        } else {
            // Rx(π) · Rz(θ)
            (-r[1][0]).atan2(r[0][0])
        }
    } else {
        let t = r20.atan2(r21);
        if t.abs() > core::f64::consts::FRAC_PI_2 {
            (-r20).atan2(-r21)
        } else {
            t
        }
    };
    // −0 and 0 alike: no turn.
    theta + 0.0
}
