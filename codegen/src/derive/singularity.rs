//! Decoupled singularities of six-joint arms with a spherical wrist (section 5.6.1).
//!
//! With the wrist centre as the reference point the Jacobian is block triangular,
//! `J = [J11 0; J21 J22]`, so `det J = det J11 · det J22`: the arm is singular where
//! `det J11 = 0` (arm singularities) and the wrist where `det J22 = 0`. Both determinants
//! are built in the normal form, so they print compactly (the text's elbow arm gives
//! `a2 a3 s3 (a2 c2 + a3 c23)` up to sign).

use crate::chain::{Chain, JointSymbols, V3, cross};
use crate::poly::{P, Poly};
use dhgen_model::{JointKind, Ring, RobotModel};

/// Joint values at q = 0 (the offsets of the table).
struct AtZero<'m>(&'m RobotModel);

impl JointSymbols<f64> for AtZero<'_> {
    fn angle(&self, j: usize) -> (f64, f64) {
        self.0.links[j].theta.cos_sin()
    }
    fn length(&self, j: usize) -> f64 {
        self.0.links[j].d
    }
}

fn sub(a: &V3<f64>, b: &V3<f64>) -> V3<f64> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: &V3<f64>, b: &V3<f64>) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The wrist centre in joint frame 4 (where joint 4 turns), if the last three axes of a
/// six-joint arm are revolute and meet in one point.
pub fn spherical_wrist(model: &RobotModel) -> Option<V3<f64>> {
    if model.dof() != 6
        || model.links[3..]
            .iter()
            .any(|l| l.joint != JointKind::Revolute)
    {
        return None;
    }
    let scale = 1.0
        + model
            .links
            .iter()
            .map(|l| l.a.abs() + l.d.abs())
            .sum::<f64>();
    let frames = Chain::new(model, &AtZero(model)).joint_frames();
    let (o4, z4) = (frames[3].p, frames[3].z_axis());
    let (o5, z5) = (frames[4].p, frames[4].z_axis());
    let (o6, z6) = (frames[5].p, frames[5].z_axis());
    // Closest points of axes 4 and 5: o4 + s z4 and o5 + t z5.
    let w = sub(&o4, &o5);
    let (b, d, e) = (dot(&z4, &z5), dot(&z4, &w), dot(&z5, &w));
    let denom = 1.0 - b * b;
    if denom < 1e-12 {
        return None; // parallel axes do not meet in one point
    }
    let s = (b * e - d) / denom;
    let t = (e - b * d) / denom;
    let p4: V3<f64> = core::array::from_fn(|i| o4[i] + s * z4[i]);
    let p5: V3<f64> = core::array::from_fn(|i| o5[i] + t * z5[i]);
    let gap = sub(&p4, &p5);
    let off6 = cross(&z6, &sub(&p4, &o6));
    let tol = 1e-9 * scale;
    if dot(&gap, &gap).sqrt() > tol || dot(&off6, &off6).sqrt() > tol {
        return None;
    }
    // In joint frame 4's coordinates (R4ᵀ (p − o4)), where it stays fixed.
    let r = &frames[3].r;
    let rel = sub(&p4, &o4);
    Some(core::array::from_fn(|i| {
        r[0][i] * rel[0] + r[1][i] * rel[1] + r[2][i] * rel[2]
    }))
}

/// `(det J11, det J22)` in the normal form, for arms with a spherical wrist.
pub fn decoupled_determinants(model: &RobotModel) -> Option<(Poly, Poly)> {
    let centre = spherical_wrist(model)?;
    let chain = super::poly_chain(model);
    let frames = chain.joint_frames();
    let c: V3<P> = frames[3].point(&centre.map(P::from_f64));
    let column = |j: usize| -> V3<P> {
        let z = frames[j].z_axis();
        match model.links[j].joint {
            JointKind::Revolute => {
                let r: V3<P> = core::array::from_fn(|i| c[i].clone() - frames[j].p[i].clone());
                cross(&z, &r)
            }
            JointKind::Prismatic => z,
        }
    };
    let triple = |a: &V3<P>, b: &V3<P>, c: &V3<P>| -> Poly {
        let bc = cross(b, c);
        (a[0].clone() * bc[0].clone() + a[1].clone() * bc[1].clone() + a[2].clone() * bc[2].clone())
            .poly
    };
    let j11 = triple(&column(0), &column(1), &column(2));
    let j22 = triple(
        &frames[3].z_axis(),
        &frames[4].z_axis(),
        &frames[5].z_axis(),
    );
    Some((j11, j22))
}
