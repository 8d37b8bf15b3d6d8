//! The O(n²) Coriolis recursion: `C(q, q̇)`, also with a payload held by the tool.

use super::*;

/// What the Coriolis recursion keeps per body besides its [`BodyState`].
#[derive(Clone, Copy, Debug)]
pub struct CoriolisBody<T = f64> {
    /// `Ṡ_i = v_i × S_i`.
    axis_rate: Motion<T>,
    /// `P = ½(İ_ωω − n×)` of this body, then summed tip to base.
    p: Matrix3<T>,
    /// The linear momentum, then summed tip to base.
    l: Vector3<T>,
}

impl<T: Real> CoriolisBody<T> {
    /// The value arrays start from.
    pub fn zero() -> CoriolisBody<T> {
        CoriolisBody {
            axis_rate: Motion::zero(),
            p: Matrix3::zeros(),
            l: Vector3::zeros(),
        }
    }
}

/// The cross-product matrix `x̂` with `x̂ y = x × y`.
#[inline]
fn hat<T: Real>(x: &Vector3<T>) -> Matrix3<T> {
    let o = T::zero();
    Matrix3::new(o, -x.z, x.y, x.z, o, -x.x, -x.y, x.x, o)
}

/// `C(q, q̇)` (Echeandia & Wensing 2021) from body states (composites not yet accumulated:
/// this accumulates them) and the joint velocities `qd`, entry by entry into `set(k, j,
/// value)`, with `scratch` one entry per body. Each body contributes
/// `B = ½(v×* I − I v× + (I v)×̄)`, summed tip to base into `B^C`; with `Ṡ_j = v_j × S_j`,
/// `C_kj = S_k·(I^C_j Ṡ_j + B^C_j S_j)` for `k ≤ j` and
/// `C_kj = Ṡ_j·I^C_k S_k + S_j·B^C_kᵀ S_k` for `k > j`. In world coordinates
/// `B = [[P, 0], [−l×, 0]]` with `P = ½(İ_ωω − n×)`, where `İ_ωω` is the rate of change of the
/// rotational inertia about the origin and `[n; l] = I v` the momentum; so `B` composes from
/// a 3×3 matrix and a vector per body.
pub fn coriolis_into<T: Real>(
    states: &mut [BodyState<T>],
    qd: &[T],
    scratch: &mut [CoriolisBody<T>],
    mut set: impl FnMut(usize, usize, T),
) {
    let half: T = k(0.5);
    let two: T = k(2.0);
    let mut velocity = Motion::zero();
    for ((state, &qdi), body) in states.iter().zip(qd).zip(scratch.iter_mut()) {
        velocity = velocity + state.axis * qdi;
        let inertia = &state.inertia;
        let momentum = inertia.apply(&velocity);
        let (w, u) = (&velocity.ang, &velocity.lin);
        let w_hat = hat(w);
        let k_rate = w_hat * inertia.k - inertia.k * w_hat
            + Matrix3::from_diagonal_element(two * inertia.h.dot(u))
            - u * inertia.h.transpose()
            - inertia.h * u.transpose();
        *body = CoriolisBody {
            axis_rate: velocity.cross(&state.axis),
            p: (k_rate - hat(&momentum.ang)) * half,
            l: momentum.lin,
        };
    }
    accumulate_composites(states);
    for i in (1..scratch.len()).rev() {
        let (p, l) = (scratch[i].p, scratch[i].l);
        scratch[i - 1].p += p;
        scratch[i - 1].l += l;
    }
    for (j, (state, body)) in states.iter().zip(scratch.iter()).enumerate() {
        let s = &state.axis;
        let composite = &state.composite;
        let rate = composite.apply(&body.axis_rate);
        let f1 = Force {
            ang: rate.ang + body.p * s.ang,
            lin: rate.lin + s.ang.cross(&body.l),
        };
        let f2 = composite.apply(s);
        let f3 = Force {
            ang: body.p.transpose() * s.ang + body.l.cross(&s.lin),
            lin: Vector3::zeros(),
        };
        set(j, j, s.dot(&f1));
        for (kk, (before, before_body)) in states[..j].iter().zip(scratch.iter()).enumerate() {
            // Row k < j: C_kj; column k < j of row j: C_jk.
            set(kk, j, before.axis.dot(&f1));
            set(j, kk, before_body.axis_rate.dot(&f2) + before.axis.dot(&f3));
        }
    }
}

/// The Coriolis and centrifugal matrix `C(q, q̇)` of `chain`, Christoffel-consistent
/// (`C_kj = Σ_i c_ijk q̇_i`, so `Ḋ − 2C` is skew-symmetric), by the O(n²) recursion of
/// Echeandia and Wensing, at the configuration given as for [`mass_matrix`] and the joint
/// velocities `qd`.
#[must_use]
pub fn coriolis<T: Real, const N: usize>(
    chain: ChainRef<'_>,
    cos: &[T; N],
    sin: &[T; N],
    d: &[T; N],
    qd: &[T; N],
) -> SMatrix<T, N, N> {
    coriolis_of(states_at(chain, cos, sin, d), qd)
}

/// C(q, q̇) of the bodies `states` (composites not yet accumulated) at the joint velocities
/// `qd`, by [`coriolis_into`] on stack arrays.
fn coriolis_of<T: Real, const N: usize>(
    mut states: [BodyState<T>; N],
    qd: &[T; N],
) -> SMatrix<T, N, N> {
    let mut scratch = [CoriolisBody::zero(); N];
    let mut out = SMatrix::<T, N, N>::zeros();
    coriolis_into(&mut states, qd, &mut scratch, |i, j, v| {
        set(&mut out, i, j, v)
    });
    out
}

/// [`coriolis`] with a payload held by the tool: `payload` is its ten inertial parameters
/// (mass, first moment `m·c` and inertia about the tool origin, in tool axes: the order of
/// [`BODY_PARAMETER_NAMES`](crate::parameters::BODY_PARAMETER_NAMES), as
/// `dhgen::payload::Payload::parameters` gives them), added to the last body.
#[must_use]
pub fn coriolis_with_payload<T: Real, const N: usize>(
    chain: ChainRef<'_>,
    cos: &[T; N],
    sin: &[T; N],
    d: &[T; N],
    qd: &[T; N],
    payload: &[T; 10],
) -> SMatrix<T, N, N> {
    let mut states = [BodyState::zero(); N];
    let (r, p) = body_states(chain, prepared(chain, cos, sin, d), into(&mut states));
    if let Some(last) = states.last_mut() {
        last.inertia += &held(chain, &r, &p, payload);
        last.composite = last.inertia;
    }
    coriolis_of(states, qd)
}

/// A payload's inertia about the world origin, held by the tool of `chain` whose last joint
/// frame is `(r, p)`; `payload` as for [`coriolis_with_payload`].
fn held<T: Real>(
    chain: ChainRef<'_>,
    r: &Matrix3<T>,
    p: &Vector3<T>,
    payload: &[T; 10],
) -> Inertia<T> {
    // The tool frame, `P_n` placed in the last joint frame (the identity without one).
    let (rt, pt) = match chain.placements.get(chain.bodies.len()) {
        Some(tool) => (
            r * Matrix3::from_fn(|a, b| k::<T>(tool.r[a][b])),
            p + r * Vector3::from_fn(|a, _| k::<T>(tool.p[a])),
        ),
        None => (*r, *p),
    };
    let entries = crate::parameters::INERTIA_ENTRIES;
    let in_tool = Inertia {
        mass: payload[0],
        h: Vector3::new(payload[1], payload[2], payload[3]),
        k: Matrix3::from_fn(|a, b| payload[entries[a][b]]),
    };
    in_tool.placed(&rt, &pt)
}
