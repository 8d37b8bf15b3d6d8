//! The composite rigid body algorithm: `D(q)`.

use super::*;

/// `D(q)` from body states whose composites are accumulated, entry by entry into `set(i, j,
/// value)`: with `F_j = I^C_j S_j` the force needed to move joint j alone at unit
/// acceleration, `D_ij = S_i · F_j` for `i ≤ j` (joint i feels what moves beyond both joints),
/// plus each joint's armature on the diagonal.
pub fn crba<T: Real>(
    chain: ChainRef<'_>,
    states: &[BodyState<T>],
    mut set: impl FnMut(usize, usize, T),
) {
    for (j, (state, body)) in states.iter().zip(chain.bodies).enumerate() {
        let f = state.composite.apply(&state.axis);
        set(j, j, state.axis.dot(&f) + k::<T>(body.armature));
        for (i, before) in states[..j].iter().enumerate() {
            let dij = before.axis.dot(&f);
            set(i, j, dij);
            set(j, i, dij);
        }
    }
}

/// The joint-space inertia matrix `D(q)` of `chain` (armature included) by the composite
/// rigid body algorithm, at the configuration given by each revolute joint's cosine and sine
/// and each prismatic joint's displacement (offsets applied; the other entries are not
/// read). `chain` has `N` bodies (a generated module's `CHAIN` and `DOF`); a kinematics-only
/// chain gives its armatures alone.
#[must_use]
pub fn mass_matrix<T: Real, const N: usize>(
    chain: ChainRef<'_>,
    cos: &[T; N],
    sin: &[T; N],
    d: &[T; N],
) -> SMatrix<T, N, N> {
    let mut states = states_at(chain, cos, sin, d);
    accumulate_composites(&mut states);
    let mut out = SMatrix::<T, N, N>::zeros();
    crba(chain, &states, |i, j, v| set(&mut out, i, j, v));
    out
}
