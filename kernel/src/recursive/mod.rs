//! The recursive rigid-body algorithms on caller-owned memory, over any [`Real`]: the
//! composite rigid body algorithm for `D(q)`, the O(n²) Coriolis recursion for `C(q, q̇)`
//! (also with a payload held by the tool), the Christoffel symbols from the analytic
//! derivatives of `D` and recursive Newton–Euler for the bias torques, without allocation and
//! without `std`.
//!
//! They are the runtime path's algorithms — `dhgen::Robot` runs them on `f64` with
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
//! let robot = dhgen::Robot::from_file("../robots/planar_elbow.toml").unwrap();
//! let q = [0.3_f64, -0.5];
//! let (sin, cos) = (q.map(f64::sin), q.map(f64::cos));
//! let d = dhgen::recursive::mass_matrix(robot.chain(), &cos, &sin, &[0.0; 2]);
//! assert!((d - robot.mass_matrix(&q)).abs().max() < 1e-14);
//! ```

mod christoffel;
mod coriolis;
mod crba;
mod energy;
mod rnea;

pub use christoffel::{christoffel, christoffel_into};
pub use coriolis::{CoriolisBody, coriolis, coriolis_into, coriolis_with_payload};
pub use crba::{crba, mass_matrix};
pub use energy::{masses, potential_energy};
pub use rnea::{mass_matrix_and_bias, rnea_backward, rnea_forward};

use crate::Real;
use crate::spatial::{Force, Inertia, Motion};
use crate::{Body, ChainRef, JointKind, JointValue};
use nalgebra::{Matrix3, SMatrix, Vector3, convert};

/// One body at one configuration, in world coordinates.
#[derive(Clone, Copy, Debug)]
pub struct BodyState<T = f64> {
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
pub fn joint_axis<T: Real>(joint: JointKind, r: &Matrix3<T>, p: &Vector3<T>) -> Motion<T> {
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
pub fn walk<T: Real>(
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
pub fn body_states<T: Real>(
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
pub fn accumulate_composites<T: Real>(states: &mut [BodyState<T>]) {
    for i in (1..states.len()).rev() {
        let after = states[i].composite;
        states[i - 1].composite += &after;
    }
}

/// The joint-side friction torque of `body` at velocity `qd`: `viscous·q̇ + coulomb·sign(q̇)`
/// with `sign(0) = 0`.
#[inline]
pub fn friction<T: Real>(body: &Body, qd: T) -> T {
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
