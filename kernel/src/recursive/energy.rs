//! The potential energy and the bodies' masses and centres of mass, walking the chain.

use super::*;

/// The potential energy `P = −Σ_k m_k gravity · c_k` of `chain`'s links at the joint values
/// `value(k)` (offsets applied), centres of mass `c_k` in the world frame, by [`walk`]: the
/// runtime path's, and [`ArmDynamics::potential_energy`](crate::ArmDynamics::potential_energy)'s
/// default. A kinematics-only chain has none (0).
pub fn potential_energy<T: Real>(
    chain: ChainRef<'_>,
    value: impl FnMut(usize) -> JointValue<T>,
) -> T {
    let gravity = Vector3::from_fn(|a, _| k::<T>(chain.gravity[a]));
    let mut energy = T::zero();
    masses(chain, value, |_, mass, com| {
        energy -= gravity.dot(&com) * mass
    });
    energy
}

/// Each body's mass and centre of mass in the world frame at the joint values `value(k)`
/// (offsets applied), by [`walk`], passed base to tip to `visit(k, mass, centre)`; a
/// kinematics-only body is skipped.
pub fn masses<T: Real>(
    chain: ChainRef<'_>,
    value: impl FnMut(usize) -> JointValue<T>,
    mut visit: impl FnMut(usize, T, Vector3<T>),
) {
    walk(chain, value, |i, r, p| {
        if let Some(b) = chain.bodies.get(i).and_then(|b| b.inertial.as_ref()) {
            let com = r * Vector3::from_fn(|a, _| k::<T>(b.com[a])) + p;
            visit(i, k(b.mass), com);
        }
    });
}
