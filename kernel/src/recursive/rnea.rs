//! Recursive Newton–Euler: the bias torques, and `D(q)` with them from one pass.

use super::*;

/// The forward pass of the recursive Newton–Euler algorithm (Featherstone, RBDA §5.3, in
/// world coordinates): for each body i, `put(i, velocity, acceleration, momentum, force)`:
/// its spatial velocity, its acceleration with gravity entering as an upward acceleration of
/// the base (so every body's force includes its weight), its momentum `I v` and its net force
/// `I a + v ×* I v`; `qdd = None` means zero acceleration.
pub fn rnea_forward<T: Real>(
    chain: ChainRef<'_>,
    states: &[BodyState<T>],
    qd: &[T],
    qdd: Option<&[T]>,
    mut put: impl FnMut(usize, Motion<T>, Motion<T>, Force<T>, Force<T>),
) {
    let mut velocity = Motion::zero();
    let mut acceleration = Motion {
        ang: Vector3::zeros(),
        lin: -Vector3::from_fn(|a, _| k::<T>(chain.gravity[a])),
    };
    for (i, (state, &qdi)) in states.iter().zip(qd).enumerate() {
        let s = &state.axis;
        velocity = velocity + *s * qdi;
        // The axis moves with the body before it: dS/dt = v × S.
        acceleration = acceleration + velocity.cross(s) * qdi;
        if let Some(qddi) = qdd.and_then(|a| a.get(i)) {
            acceleration = acceleration + *s * *qddi;
        }
        let momentum = state.inertia.apply(&velocity);
        let force = state.inertia.apply(&acceleration) + velocity.cross_force(&momentum);
        put(i, velocity, acceleration, momentum, force);
    }
}

/// The backward pass: `τ_i = S_i · Σ_{k ≥ i} f_k` into `set(i, τ_i)`, `forces` the bodies'
/// net forces `f_k` base to tip (rigid-body torques only: no armature, no friction).
pub fn rnea_backward<T: Real>(
    states: &[BodyState<T>],
    forces: impl DoubleEndedIterator<Item = Force<T>> + ExactSizeIterator,
    mut set: impl FnMut(usize, T),
) {
    let mut transmitted = Force::zero();
    for (i, (state, force)) in states.iter().zip(forces).enumerate().rev() {
        transmitted += force;
        set(i, state.axis.dot(&transmitted));
    }
}

/// `D(q)` (as [`mass_matrix`]) and the bias torques `C(q, q̇) q̇ + g(q) + friction` (inverse
/// dynamics at zero acceleration, by recursive Newton–Euler) from one pass over the bodies:
/// what forward dynamics `q̈ = D⁻¹(τ − bias)` needs.
#[must_use]
pub fn mass_matrix_and_bias<T: Real, const N: usize>(
    chain: ChainRef<'_>,
    cos: &[T; N],
    sin: &[T; N],
    d: &[T; N],
    qd: &[T; N],
) -> (SMatrix<T, N, N>, [T; N]) {
    let mut states = states_at(chain, cos, sin, d);
    let mut forces = [Force::zero(); N];
    rnea_forward(chain, &states, qd, None, |i, _, _, _, force| {
        if let Some(f) = forces.get_mut(i) {
            *f = force;
        }
    });
    let mut bias = [T::zero(); N];
    rnea_backward(&states, forces.into_iter(), |i, t| {
        if let (Some(b), Some(body), Some(&qdi)) = (bias.get_mut(i), chain.bodies.get(i), qd.get(i))
        {
            *b = t + friction(body, qdi);
        }
    });
    accumulate_composites(&mut states);
    let mut out = SMatrix::<T, N, N>::zeros();
    crba(chain, &states, |i, j, v| set(&mut out, i, j, v));
    (out, bias)
}
