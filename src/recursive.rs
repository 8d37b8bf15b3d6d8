//! The recursive rigid-body algorithms on caller-owned memory, over any [`Real`]: the
//! composite rigid body algorithm for `D(q)`, the O(n²) Coriolis recursion for `C(q, q̇)`
//! (also with a payload held by the tool), the Christoffel symbols from the analytic
//! derivatives of `D` and recursive Newton–Euler for the bias torques, without allocation and
//! without `std`.
//!
//! They are the runtime path's algorithms — [`Robot`](crate::Robot) runs them on `f64` with
//! its bodies in a `Vec` — and generated modules of more than 12 joints (the code generator's
//! `LOOPED_ABOVE`) call them with their `CHAIN` and stack arrays: there, the straight-line
//! form of `D(q)` and `C(q, q̇)` outgrows the instruction cache (a general 12-joint arm's
//! unrolled `C` already streams about 90 KB of code per call) and loses to these loops, so a
//! generated module is never slower than the runtime path (the same holds for the n³
//! Christoffel symbols, and for `Ḋ = C + Cᵀ` and `Cᵀq̇`, which such a module takes from
//! [`coriolis`]). Smaller modules call them only
//! where the cheapest symbolic derivation of D or C costs more operations per joint than the
//! loops take time for (the generator's `LOOP_D_ABOVE_PER_JOINT` and
//! `LOOP_C_ABOVE_PER_JOINT`); elsewhere the symbolic derivations win and are emitted. The
//! symbolic engine checks these loops at 2 to 30 joints (`tests/integration/ring_algorithms.rs`).
//!
//! Everything is in world coordinates (Plücker coordinates at the world origin): one pass
//! puts every joint axis and body inertia there ([`mass_matrix`] and [`coriolis`] start
//! with it), the composite inertias are summed tip to base, and `D` and `C` are pairings of
//! axes with forces.
//!
//! ```
//! // The planar elbow arm's D(q) at q = (0.3, −0.5), here and by the runtime path.
//! let robot = dhgen::Robot::from_file("robots/planar_elbow.toml").unwrap();
//! let q = [0.3_f64, -0.5];
//! let (sin, cos) = (q.map(f64::sin), q.map(f64::cos));
//! let d = dhgen::recursive::mass_matrix(robot.chain(), &cos, &sin, &[0.0; 2]);
//! assert!((d - robot.mass_matrix(&q)).abs().max() < 1e-14);
//! ```

use crate::Real;
use crate::spatial::{Force, Inertia, Motion};
use dhgen_model::{Body, ChainRef, JointKind, JointValue};
use nalgebra::{Matrix3, SMatrix, Vector3, convert};

/// One body at one configuration, in world coordinates.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BodyState<T = f64> {
    /// The joint's unit motion `S_i`: `[z; p × z]` (revolute) or `[0; z]` (prismatic).
    pub axis: Motion<T>,
    /// The body's own spatial inertia.
    pub inertia: Inertia<T>,
    /// The composite inertia of this body and all bodies after it (filled by
    /// [`accumulate_composites`]).
    pub composite: Inertia<T>,
}

impl<T: Real> BodyState<T> {
    /// A body without mass on a zero axis: the value arrays start from.
    pub fn zero() -> BodyState<T> {
        let inertia = Inertia {
            mass: T::zero(),
            h: Vector3::zeros(),
            k: Matrix3::zeros(),
        };
        BodyState {
            axis: Motion::zero(),
            inertia,
            composite: inertia,
        }
    }
}

/// The unit motion `S` of a joint carried by the z axis of the frame `(r, p)`: `[z; p × z]`
/// for a revolute joint (rotation about the line through `p`), `[0; z]` for a prismatic one.
#[inline]
pub(crate) fn joint_axis<T: Real>(joint: JointKind, r: &Matrix3<T>, p: &Vector3<T>) -> Motion<T> {
    let z = r.column(2).into_owned();
    match joint {
        JointKind::Revolute => Motion {
            ang: z,
            lin: p.cross(&z),
        },
        JointKind::Prismatic => Motion {
            ang: Vector3::zeros(),
            lin: z,
        },
    }
}

/// `x` as a `T`.
#[inline]
fn k<T: Real>(x: f64) -> T {
    convert::<f64, T>(x)
}

/// Walks the chain at the joint values `value(k)` (offsets applied): `T(q) = P_0 Z_1 P_1 ⋯`
/// by composing each placement, then turning the frame's columns by the joint (or moving it
/// along its z axis), calling `visit(k, r, p)` with joint frame k in the world frame and
/// returning the last one (the runtime path's walk for kinematics and dynamics alike).
pub(crate) fn walk<T: Real>(
    chain: ChainRef<'_>,
    mut value: impl FnMut(usize) -> JointValue<T>,
    mut visit: impl FnMut(usize, &Matrix3<T>, &Vector3<T>),
) -> (Matrix3<T>, Vector3<T>) {
    let mut r: Matrix3<T> = Matrix3::identity();
    let mut p: Vector3<T> = Vector3::zeros();
    for (i, (placement, _)) in chain.placements.iter().zip(chain.bodies).enumerate() {
        let pr = Matrix3::from_fn(|a, b| k::<T>(placement.r[a][b]));
        let pp = Vector3::from_fn(|a, _| k::<T>(placement.p[a]));
        if i == 0 {
            (r, p) = (pr, pp);
        } else {
            p += r * pp;
            r *= pr;
        }
        match value(i) {
            JointValue::Revolute { cos, sin } => {
                let x = r.column(0).into_owned();
                let y = r.column(1).into_owned();
                r.set_column(0, &(x * cos + y * sin));
                r.set_column(1, &(y * cos - x * sin));
            }
            JointValue::Prismatic(d) => p += r.column(2) * d,
        }
        visit(i, &r, &p);
    }
    (r, p)
}

/// The world-frame joint axes and body inertias at the joint values `value(k)` (offsets
/// applied), by [`walk`], passed base to tip to `put(k, state)`; returns the last joint frame
/// (`walk`'s). A kinematics-only body has zero inertia.
pub(crate) fn body_states<T: Real>(
    chain: ChainRef<'_>,
    value: impl FnMut(usize) -> JointValue<T>,
    mut put: impl FnMut(usize, BodyState<T>),
) -> (Matrix3<T>, Vector3<T>) {
    walk(chain, value, |i, r, p| {
        let Some(body) = chain.bodies.get(i) else {
            return;
        };
        let axis = joint_axis(body.joint, r, p);
        let inertia = match &body.inertial {
            Some(b) => {
                let com = r * Vector3::from_fn(|a, _| k::<T>(b.com[a])) + p;
                let i_com = r * Matrix3::from_fn(|a, c| k::<T>(b.inertia[a][c])) * r.transpose();
                Inertia::from_com(k(b.mass), &com, &i_com)
            }
            None => BodyState::zero().inertia,
        };
        put(
            i,
            BodyState {
                axis,
                inertia,
                composite: inertia,
            },
        );
    })
}

/// The potential energy `P = −Σ_k m_k gravity · c_k` of `chain`'s links at the joint values
/// `value(k)` (offsets applied), centres of mass `c_k` in the world frame, by [`walk`]: the
/// runtime path's, and [`ArmDynamics::potential_energy`](crate::ArmDynamics::potential_energy)'s
/// default. A kinematics-only chain has none (0).
pub(crate) fn potential_energy<T: Real>(
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
pub(crate) fn masses<T: Real>(
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

/// `put` for a fixed-size array: `out[i] = v` (every index is below N; `get_mut` keeps the
/// code free of panics).
#[inline]
fn into<V, const N: usize>(out: &mut [V; N]) -> impl FnMut(usize, V) + '_ {
    move |i, v| {
        if let Some(e) = out.get_mut(i) {
            *e = v;
        }
    }
}

/// Sums the inertias tip to base: `composite_i = Σ_{k ≥ i} inertia_k`.
pub(crate) fn accumulate_composites<T: Real>(states: &mut [BodyState<T>]) {
    for i in (1..states.len()).rev() {
        let after = states[i].composite;
        states[i - 1].composite += &after;
    }
}

/// `D(q)` from body states whose composites are accumulated, entry by entry into `set(i, j,
/// value)`: with `F_j = I^C_j S_j` the force needed to move joint j alone at unit
/// acceleration, `D_ij = S_i · F_j` for `i ≤ j` (joint i feels what moves beyond both joints),
/// plus each joint's armature on the diagonal.
pub(crate) fn crba<T: Real>(
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

/// What the Coriolis recursion keeps per body besides its [`BodyState`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct CoriolisBody<T = f64> {
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
pub(crate) fn coriolis_into<T: Real>(
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

/// The forward pass of the recursive Newton–Euler algorithm (Featherstone, RBDA §5.3, in
/// world coordinates): for each body i, `put(i, velocity, acceleration, momentum, force)`:
/// its spatial velocity, its acceleration with gravity entering as an upward acceleration of
/// the base (so every body's force includes its weight), its momentum `I v` and its net force
/// `I a + v ×* I v`; `qdd = None` means zero acceleration.
pub(crate) fn rnea_forward<T: Real>(
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
pub(crate) fn rnea_backward<T: Real>(
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

/// The joint-side friction torque of `body` at velocity `qd`: `viscous·q̇ + coulomb·sign(q̇)`
/// with `sign(0) = 0`.
#[inline]
pub(crate) fn friction<T: Real>(body: &Body, qd: T) -> T {
    k::<T>(body.friction.viscous) * qd + k::<T>(body.friction.coulomb) * qd.sign()
}

/// The joint values of the prepared configuration `(cos, sin, d)`, as generated modules'
/// `State` holds it: the cosine and sine of each revolute joint's full angle, the full
/// displacement of each prismatic joint.
fn prepared<'a, T: Real>(
    chain: ChainRef<'a>,
    cos: &'a [T],
    sin: &'a [T],
    d: &'a [T],
) -> impl FnMut(usize) -> JointValue<T> + 'a {
    // Every index is below N (one per body); `get` keeps the code free of panics.
    let at = |v: &[T], i: usize| v.get(i).copied().unwrap_or_else(T::zero);
    move |i| match chain.bodies.get(i).map(|b| b.joint) {
        Some(JointKind::Prismatic) => JointValue::Prismatic(at(d, i)),
        _ => JointValue::Revolute {
            cos: at(cos, i),
            sin: at(sin, i),
        },
    }
}

/// The body states of `chain` at the prepared configuration `(cos, sin, d)` (see
/// [`mass_matrix`]), composites not yet accumulated, in a stack array.
fn states_at<T: Real, const N: usize>(
    chain: ChainRef<'_>,
    cos: &[T; N],
    sin: &[T; N],
    d: &[T; N],
) -> [BodyState<T>; N] {
    let mut states = [BodyState::zero(); N];
    body_states(chain, prepared(chain, cos, sin, d), into(&mut states));
    states
}

/// `out[(i, j)] = v` (every index is below N; `get_mut` keeps the code free of panics).
#[inline]
fn set<T: Real, const N: usize>(out: &mut SMatrix<T, N, N>, i: usize, j: usize, v: T) {
    if let Some(e) = out.get_mut((i, j)) {
        *e = v;
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
/// `dhgen::parameters::BODY_PARAMETER_NAMES`, as [`Payload::parameters`] gives them), added to
/// the last body.
///
/// [`Payload::parameters`]: crate::payload::Payload::parameters
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
    let entries = dhgen_model::parameters::INERTIA_ENTRIES;
    let in_tool = Inertia {
        mass: payload[0],
        h: Vector3::new(payload[1], payload[2], payload[3]),
        k: Matrix3::from_fn(|a, b| payload[entries[a][b]]),
    };
    in_tool.placed(&rt, &pt)
}

/// The Christoffel symbols `c_ijk` (k the equation index) into `out`, row-major
/// (`out[(i·n + j)·n + k]`, n = `states.len()`), from body states whose composites are
/// accumulated, with `moved` and `screw` scratch of n² entries each. With `S_i` the joint
/// screws, `I^C_l` the composite inertias and `×` the spatial cross product, for `a ≤ b`:
/// `∂D_ab/∂q_l` is 0 for `l ≤ a`, `(S_a × S_l)·I^C_b S_b` for `a < l < b`, and
/// `(S_a × S_l)·I^C_l S_b + (S_b × S_l)·I^C_l S_a` for `l ≥ b`; these derivatives are written
/// into `out` first, then each triple of indices is turned into its symbols in place
/// (`c_ijk = ½(∂d_kj/∂q_i + ∂d_ki/∂q_j − ∂d_ij/∂q_k)` reads three derivatives and gives three
/// symbols, each at the places its symmetries put it), so no third array of n³ is needed.
/// Slices shorter than that are left as they are (callers size them; no panic either way).
pub(crate) fn christoffel_into<T: Real>(
    states: &[BodyState<T>],
    moved: &mut [Force<T>],
    screw: &mut [Motion<T>],
    out: &mut [T],
) {
    let n = states.len();
    if moved.len() < n * n || screw.len() < n * n || out.len() < n * n * n {
        return;
    }
    // moved[l·n + j] = I^C_l S_j for j ≤ l; screw[a·n + l] = S_a × S_l for a < l.
    for (l, sl) in states.iter().enumerate() {
        for (j, sj) in states.iter().enumerate().take(l + 1) {
            moved[l * n + j] = sl.composite.apply(&sj.axis);
        }
        for (a, sa) in states.iter().enumerate().take(l) {
            screw[a * n + l] = sa.axis.cross(&sl.axis);
        }
    }
    // out[(l·n + a)·n + b] = ∂D_ab/∂q_l.
    out.fill(T::zero());
    for a in 0..n {
        for b in a..n {
            for l in a + 1..n {
                let mut v = screw[a * n + l].dot(&moved[l.max(b) * n + b]);
                if l > b {
                    v += screw[b * n + l].dot(&moved[l * n + a]);
                }
                out[(l * n + a) * n + b] = v;
                out[(l * n + b) * n + a] = v;
            }
        }
    }
    // Per triple x ≤ y ≤ z: the derivatives d_x = ∂D_yz/∂q_x, d_y = ∂D_xz/∂q_y,
    // d_z = ∂D_xy/∂q_z, and the symbols c_xyz = c_yxz = ½(d_x + d_y − d_z),
    // c_xzy = c_zxy = ½(d_x + d_z − d_y), c_yzx = c_zyx = ½(d_y + d_z − d_x).
    let half: T = k(0.5);
    let at = |i: usize, j: usize, k: usize| (i * n + j) * n + k;
    for x in 0..n {
        for y in x..n {
            for z in y..n {
                let (dx, dy, dz) = (out[at(x, y, z)], out[at(y, x, z)], out[at(z, x, y)]);
                let c_xyz = half * ((dx + dy) - dz);
                let c_xzy = half * ((dx + dz) - dy);
                let c_yzx = half * ((dy + dz) - dx);
                out[at(x, y, z)] = c_xyz;
                out[at(y, x, z)] = c_xyz;
                out[at(x, z, y)] = c_xzy;
                out[at(z, x, y)] = c_xzy;
                out[at(y, z, x)] = c_yzx;
                out[at(z, y, x)] = c_yzx;
            }
        }
    }
}

/// The Christoffel symbols of `chain`'s `D(q)`, `[i][j][k]` = `c_ijk` (k the equation index),
/// at the configuration given as for [`mass_matrix`]: the runtime path's algorithm
/// ([`Robot::christoffel`](crate::Robot::christoffel)), O(n³), from the analytic derivatives
/// of D. Motor inertias are constant and do not enter.
#[must_use]
pub fn christoffel<T: Real, const N: usize>(
    chain: ChainRef<'_>,
    cos: &[T; N],
    sin: &[T; N],
    d: &[T; N],
) -> [[[T; N]; N]; N] {
    let mut states = states_at(chain, cos, sin, d);
    accumulate_composites(&mut states);
    let mut moved = [[Force::zero(); N]; N];
    let mut screw = [[Motion::zero(); N]; N];
    let mut out = [[[T::zero(); N]; N]; N];
    christoffel_into(
        &states,
        moved.as_flattened_mut(),
        screw.as_flattened_mut(),
        out.as_flattened_mut().as_flattened_mut(),
    );
    out
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
