//! Decoupled singularities of six-joint arms with a spherical wrist (section 5.6.1).
//!
//! With the wrist centre as the reference point the Jacobian is block triangular,
//! `J = [J11 0; J21 J22]`, so `det J = det J11 · det J22`: the arm is singular where
//! `det J11 = 0` (arm singularities) and the wrist where `det J22 = 0`. Both determinants
//! are built in the normal form, so they print compactly (the text's elbow arm gives
//! `a2 a3 s3 (a2 c2 + a3 c23)` up to sign). Both are invariant under the choice of the
//! reference frame, so they are computed in the root frame.

use crate::chain::{V3, cross};
use crate::poly::{P, Poly};
use dhgen_description::{ChainRef, JointKind, Ring};

/// `(det J11, det J22)` in the normal form, for six-joint arms with a spherical wrist
/// ([`ChainRef::spherical_wrist`]).
pub fn decoupled_determinants(chain: ChainRef<'_>) -> Option<(Poly, Poly)> {
    if chain.dof() != 6 {
        return None;
    }
    let wrist = chain.spherical_wrist().ok()?;
    super::within_budget(chain, super::GRAVITY_WORK, |budget| {
        determinants(chain, &wrist, budget)
    })?
}

fn determinants(
    chain: ChainRef<'_>,
    wrist: &dhgen_kernel::SphericalWrist,
    budget: &std::rc::Rc<crate::poly::Budget>,
) -> Option<(Poly, Poly)> {
    let frames = super::poly_chain(chain, budget).joint_frames();
    let c: V3<P> = frames[wrist.first].point(&wrist.centre.map(P::from_f64));
    let column = |j: usize| -> V3<P> {
        let z = frames[j].z_axis();
        match chain.bodies[j].joint {
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
