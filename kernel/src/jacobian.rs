//! The Jacobian's frame changes and time derivative, for any [`Arm`]: the body Jacobian and
//! `J̇_b q̇` from the world-axes ones, `J̇(q, q̇)` and `J̇ q̇` from `J`, a point's Jacobian column.
//! What the [`Arm`] trait's default methods compute for arms without generated forms; the
//! rest of velocity kinematics is `dhgen::velocity`.

use crate::{Arm, ArmAllocator};
use nalgebra::allocator::Allocator;
use nalgebra::{DefaultAllocator, Dim, OMatrix, OVector, U6, Vector3, Vector6};

/// Panics unless `len`, the length of the joint vector `arg` given to `function`, is the
/// arm's number of joints: the runtime path's rule (a generated arm's vectors have the right
/// length by type, so this never fires there).
#[inline]
#[track_caller]
#[doc(hidden)]
pub fn check_len(function: &str, arg: &str, len: usize, dof: usize) {
    if len != dof {
        panic!(
            "dhgen::velocity::{function}: `{arg}` has length {len}, expected {dof} (one entry \
             per joint)"
        );
    }
}

/// Column i of J̇ from column i of J, the angular velocity `omega` of the body carrying
/// axis i and `rel`, the velocity of the tool origin relative to that body's point on the
/// axis (see [`jacobian_dot`]).
fn column_dot(
    prismatic: bool,
    v: &Vector3<f64>,
    z: &Vector3<f64>,
    omega: &Vector3<f64>,
    rel_tail: &Vector3<f64>,
) -> (Vector3<f64>, Vector3<f64>) {
    if prismatic {
        (omega.cross(v), Vector3::zeros())
    } else {
        let z_dot = omega.cross(z);
        // v = z × r with r ⟂ z the offset of the tool origin from the axis: r = v × z.
        let r = v.cross(z);
        let rel = omega.cross(&r) + rel_tail;
        (z_dot.cross(&r) + z.cross(&rel), z_dot)
    }
}

/// `J̇(q, q̇)`, the time derivative of the geometric Jacobian along the joint velocity q̇,
/// derived analytically from the joint axes (no finite differences).
///
/// Column i of J is `[z_i × (p − o_i); z_i]` (revolute) or `[z_i; 0]` (prismatic). Axis i is
/// fixed in the body moved by joints 1..i−1, which turns at `ω_i = Σ_{j<i, revolute} z_j q̇_j`,
/// so `ż_i = ω_i × z_i`, and the tool origin moves relative to that body's point o_i at
/// `ṗ − ȯ_i = ω_i × (p − o_i) + Σ_{j≥i} J_v,j q̇_j`; hence
/// `d/dt [z_i × (p − o_i)] = ż_i × (p − o_i) + z_i × (ṗ − ȯ_i)`. The axes and `p − o_i` (its
/// component across the axis, which is all that enters) are read off the columns of J
/// itself: `p − o_i = J_v,i × z_i`. So this needs only [`Arm::jacobian`] and works the same
/// for every arm.
///
/// ```
/// use dhgen::nalgebra::SVector;
/// use dhgen::velocity::jacobian_dot;
/// use dhgen::Arm;
/// dhgen::robot!(mod puma = "../robots/puma560.toml");
///
/// let q = SVector::<f64, 6>::new(0.2, -0.3, 0.4, 0.5, 0.6, 0.7);
/// let qd = SVector::<f64, 6>::new(0.5, -0.1, 0.3, 0.0, 0.2, -0.4);
/// let h = 1e-6;
/// let fd = (puma::Robot.jacobian(&(q + qd * h)) - puma::Robot.jacobian(&(q - qd * h))) / (2.0 * h);
/// assert!((jacobian_dot(&puma::Robot, &q, &qd) - fd).abs().max() < 1e-8);
/// ```
///
/// # Panics
/// If `q` or `qd` does not have one entry per joint (only possible on the runtime path).
pub fn jacobian_dot<A: Arm>(
    arm: &A,
    q: &OVector<f64, A::Dof>,
    qd: &OVector<f64, A::Dof>,
) -> OMatrix<f64, U6, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    check_len("jacobian_dot", "qd", qd.len(), arm.dof());
    let j = arm.jacobian(q);
    let mut out = OMatrix::<f64, U6, A::Dof>::zeros_generic(U6, arm.dim());
    let mut tail: Vector3<f64> = j.fixed_rows::<3>(0) * qd;
    let mut omega = Vector3::zeros();
    for i in 0..arm.dof() {
        let v = j.fixed_view::<3, 1>(0, i).into_owned();
        let z_rot = j.fixed_view::<3, 1>(3, i).into_owned();
        let prismatic = arm.is_prismatic(i);
        let z = if prismatic { v } else { z_rot };
        let (dv, dw) = column_dot(prismatic, &v, &z, &omega, &tail);
        out.fixed_view_mut::<3, 1>(0, i).copy_from(&dv);
        out.fixed_view_mut::<3, 1>(3, i).copy_from(&dw);
        tail -= v * qd[i];
        if !prismatic {
            omega += z * qd[i];
        }
    }
    out
}

/// Column `c` of the linear rows of the Jacobian of a point at `offset` from the tool origin
/// (world axes), from the tool's Jacobian `j`: `v_c + ω_c × offset`, where joint c moves the
/// point (what `point_jacobian` and the centre of mass's Jacobian are made of).
pub fn moved_column<D: Dim>(
    j: &OMatrix<f64, U6, D>,
    c: usize,
    offset: &Vector3<f64>,
) -> Vector3<f64>
where
    DefaultAllocator: Allocator<U6, D>,
{
    // Outside the generic bound (nalgebra's inference would take `Allocator<U6, D>` for the
    // cross product's).
    fn moved(v: Vector3<f64>, w: Vector3<f64>, offset: &Vector3<f64>) -> Vector3<f64> {
        v + w.cross(offset)
    }
    moved(
        j.fixed_view::<3, 1>(0, c).into_owned(),
        j.fixed_view::<3, 1>(3, c).into_owned(),
        offset,
    )
}

/// The body Jacobian from the tool pose and the world-axes Jacobian `J`: each column's `v` and
/// `ω` turned into tool axes, `diag(Rᵀ, Rᵀ) J`. What [`Arm::body_jacobian`] computes for arms
/// without a generated `body_jacobian`.
pub fn body_jacobian_from_jacobian<D: Dim>(
    tool: &nalgebra::Isometry3<f64>,
    j: OMatrix<f64, U6, D>,
) -> OMatrix<f64, U6, D>
where
    DefaultAllocator: Allocator<U6, D>,
{
    turn_jacobian(tool.rotation.to_rotation_matrix().transpose().matrix(), j)
}

/// Each column's `v` and `ω` of `j` turned by `rt`: `diag(rt, rt) j`.
pub fn turn_jacobian<D: Dim>(
    rt: &nalgebra::Matrix3<f64>,
    mut j: OMatrix<f64, U6, D>,
) -> OMatrix<f64, U6, D>
where
    DefaultAllocator: Allocator<U6, D>,
{
    for mut c in j.column_iter_mut() {
        let v = rt * nalgebra::Vector3::new(c[0], c[1], c[2]);
        let w = rt * nalgebra::Vector3::new(c[3], c[4], c[5]);
        c.copy_from_slice(&[v.x, v.y, v.z, w.x, w.y, w.z]);
    }
    j
}

/// `J̇_b q̇` ([`Arm::body_jdot_qdot`]) from the tool pose, the tool's velocity `[v; ω] = J q̇`
/// and `[a; α] = J̇ q̇`, all in world axes: `[Rᵀ a − ω_b × v_b; Rᵀ α]` with `v_b = Rᵀ v`,
/// `ω_b = Rᵀ ω`.
pub fn body_jdot_qdot_from(
    tool: &nalgebra::Isometry3<f64>,
    velocity: &Vector6<f64>,
    jdot_qdot: &Vector6<f64>,
) -> Vector6<f64> {
    let rt = tool.rotation.to_rotation_matrix().transpose();
    turn_jdot_qdot(rt.matrix(), velocity, jdot_qdot)
}

/// [`body_jdot_qdot_from`] with the tool's rotation given transposed, `rt = Rᵀ`.
pub fn turn_jdot_qdot(
    rt: &nalgebra::Matrix3<f64>,
    velocity: &Vector6<f64>,
    jdot_qdot: &Vector6<f64>,
) -> Vector6<f64> {
    let part = |x: &Vector6<f64>, at: usize| rt * x.fixed_rows::<3>(at);
    let (v, w) = (part(velocity, 0), part(velocity, 3));
    let (a, alpha) = (part(jdot_qdot, 0) - w.cross(&v), part(jdot_qdot, 3));
    Vector6::new(a.x, a.y, a.z, alpha.x, alpha.y, alpha.z)
}

/// `J̇(q, q̇) q̇` from the Jacobian `j` at q: the tool acceleration `[a; α]` at zero joint
/// acceleration, as in `ẍ = J q̈ + J̇ q̇`. Same derivation as [`jacobian_dot`], summed on the
/// fly (no n×6 temporary). What [`Arm::jdot_qdot`] computes for arms without a generated
/// `jdot_qdot`.
///
/// # Panics
/// If `qd` does not have one entry per joint (only possible on the runtime path).
pub fn jdot_qdot_from_jacobian<A: Arm + ?Sized>(
    arm: &A,
    j: &OMatrix<f64, U6, A::Dof>,
    qd: &OVector<f64, A::Dof>,
) -> Vector6<f64>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    check_len("jdot_qdot_from_jacobian", "qd", qd.len(), arm.dof());
    let mut tail: Vector3<f64> = j.fixed_rows::<3>(0) * qd;
    let mut omega = Vector3::zeros();
    let mut acc = Vector6::zeros();
    for i in 0..arm.dof() {
        let v = j.fixed_view::<3, 1>(0, i).into_owned();
        let z_rot = j.fixed_view::<3, 1>(3, i).into_owned();
        let prismatic = arm.is_prismatic(i);
        let z = if prismatic { v } else { z_rot };
        let (dv, dw) = column_dot(prismatic, &v, &z, &omega, &tail);
        acc.fixed_rows_mut::<3>(0).axpy(qd[i], &dv, 1.0);
        acc.fixed_rows_mut::<3>(3).axpy(qd[i], &dw, 1.0);
        tail -= v * qd[i];
        if !prismatic {
            omega += z * qd[i];
        }
    }
    acc
}
