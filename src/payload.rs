//! A payload held by the tool, given at run time: what the gripper picked up.
//!
//! The dynamics are linear in the inertial parameters, so a payload adds
//! `Jᵀ(q) · W(q, q̇, q̈; π_p)` to the arm's own terms: `J` the tool's geometric Jacobian, and
//! `W` the wrench the payload needs at the tool frame's origin, linear in its ten parameters
//! `π_p`. Nothing is re-derived: the functions here take any arm, generated (`m::Robot`) or
//! runtime (`dhgen::Robot`), through [`ArmDynamics`], and add the payload's terms to the arm's.
//!
//! For τ in a control loop, generated modules have a faster form: `m::inverse_dynamics_with_payload(q,
//! qd, qdd, &payload.parameters())` runs the Newton–Euler recursion once with the payload's ten
//! parameters as inputs of the last body (PUMA 560: 513 operations against 457 for τ alone;
//! Panda 882 against 818), where `inverse_dynamics` here adds `Jᵀ W` from the Jacobian and
//! `J̇ q̇` (about 3× the cost of τ); likewise `m::bias_with_payload`, `m::mass_matrix_with_payload`,
//! `m::gravity_with_payload` and the energies, `m::kinetic_energy_with_payload` and
//! `m::potential_energy_with_payload`. The centre of mass with the payload
//! ([`center_of_mass`], [`center_of_mass_jacobian`]) combines the arm's, generated where the
//! arm is, with the payload's, rigid on the tool.
//!
//! ```
//! dhgen::robot!(mod puma560 = "robots/puma560.toml");
//! use dhgen::payload::{Payload, inverse_dynamics};
//!
//! // 2 kg, 5 cm out along the tool's z axis, a 10 cm cube.
//! let box_ = Payload::new(2.0, [0.0, 0.0, 0.05], [[3.3e-3, 0.0, 0.0], [0.0, 3.3e-3, 0.0], [0.0, 0.0, 3.3e-3]])
//!     .unwrap();
//! let q = dhgen::nalgebra::SVector::from([0.1, -0.6, 0.4, 0.3, 0.8, -0.2]);
//! let zero = dhgen::nalgebra::SVector::<f64, 6>::zeros();
//! let tau = inverse_dynamics(&puma560::Robot, &box_, &q, &zero, &zero);
//! let tau0 = dhgen::ArmDynamics::inverse_dynamics(&puma560::Robot, &q, &zero, &zero);
//! assert!((tau - tau0).norm() > 1.0); // holding 2 kg takes torque
//! ```

use crate::{Arm, ArmAllocator, ArmDynamics};
use dhgen_kernel::ToolTerms;
use nalgebra::{
    DefaultAllocator, Isometry3, Matrix3, Matrix6, OMatrix, OVector, Point3, U3, Vector3, Vector6,
};

/// A rigid body fixed in the tool frame: mass, centre of mass and inertia about it, in the
/// tool frame's axes. Built only through [`Payload::new`], which checks it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Payload {
    mass: f64,
    com: [f64; 3],
    inertia: [[f64; 3]; 3],
}

/// Why a payload was refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("payload: {0}")]
pub struct PayloadError(String);

impl Payload {
    /// A payload of `mass` kg with centre of mass `com` (m, tool frame) and inertia tensor
    /// `inertia` about the centre of mass (kg·m², tool-frame axes). Refused, with the reason,
    /// by the rules and ranges of the description format
    /// ([`dhgen_description::validate`]): a negative or non-finite mass or one above
    /// [`MASS`](dhgen_description::validate::MASS) (10⁶ kg), a centre of mass that is not finite or
    /// has a coordinate beyond [`LENGTH`](dhgen_description::validate::LENGTH) (10³ m, as a link's
    /// `com`), an inertia tensor that is not symmetric, not positive semi-definite, breaks the
    /// triangle inequality or has an entry beyond [`INERTIA`](dhgen_description::validate::INERTIA).
    /// Within these ranges the ten [`parameters`](Payload::parameters) are finite (checked
    /// too), so the payload's terms are finite wherever the arm's are.
    pub fn new(mass: f64, com: [f64; 3], inertia: [[f64; 3]; 3]) -> Result<Payload, PayloadError> {
        use dhgen_description::validate::{LENGTH, check_inertia_tensor, check_mass};
        check_mass(mass).map_err(PayloadError)?;
        if com.iter().any(|c| !c.is_finite()) {
            return Err(PayloadError(format!(
                "centre of mass {com:?} is not finite"
            )));
        }
        // The range of a link's `com` in a description, in its words.
        for (axis, c) in ["x", "y", "z"].into_iter().zip(com) {
            LENGTH
                .check_value(c)
                .map_err(|why| PayloadError(format!("centre of mass {com:?}, {axis}: {why}")))?;
        }
        for (a, b) in [(1, 0), (2, 0), (2, 1)] {
            if inertia[a][b] != inertia[b][a] {
                return Err(PayloadError(format!(
                    "inertia tensor is not symmetric: [{a}][{b}] = {} but [{b}][{a}] = {}",
                    inertia[a][b], inertia[b][a]
                )));
            }
        }
        check_inertia_tensor(&inertia, mass, false).map_err(PayloadError)?;
        let payload = Payload { mass, com, inertia };
        // Within the ranges above (10⁶ kg at 10³ m, entries up to 10⁹ kg·m²) every parameter
        // is below 10¹³; checked anyway, so that no range change can let a NaN through.
        let parameters = payload.parameters();
        if let Some(k) = parameters.iter().position(|p| !p.is_finite()) {
            return Err(PayloadError(format!(
                "parameter `{}` about the tool origin is {}, not finite: mass {mass:?} kg at \
                 {com:?} m is too far out",
                crate::parameters::BODY_PARAMETER_NAMES[k],
                parameters[k]
            )));
        }
        Ok(payload)
    }

    /// No payload.
    pub const NONE: Payload = Payload {
        mass: 0.0,
        com: [0.0; 3],
        inertia: [[0.0; 3]; 3],
    };

    /// The ten parameters about the tool frame's origin, tool-frame axes, in the order of
    /// [`BODY_PARAMETER_NAMES`](crate::parameters::BODY_PARAMETER_NAMES).
    pub fn parameters(&self) -> [f64; 10] {
        crate::parameters::body_parameters(self.mass, &self.com, &self.inertia)
    }

    /// Mass, kg.
    pub fn mass(&self) -> f64 {
        self.mass
    }

    /// Centre of mass, tool frame, m.
    pub fn com(&self) -> [f64; 3] {
        self.com
    }

    /// Inertia about the centre of mass, tool-frame axes, kg·m².
    pub fn inertia(&self) -> [[f64; 3]; 3] {
        self.inertia
    }
}

impl crate::Robot {
    /// This robot holding `payload` at its tool: the payload joined rigidly to the last link
    /// (carried into the link's frame by the tool pose), so that every runtime quantity
    /// includes it, the derivatives of the dynamics and the regressor as well as τ, D, C, g and
    /// q̈. The same as writing the body into the description; what the generated
    /// `*_with_payload` functions compute with the payload as an input. A new model: build one
    /// per payload, not per call. `None` if the robot has no mass properties.
    ///
    /// ```
    /// use dhgen::payload::Payload;
    /// let arm = dhgen::Robot::from_toml_file("robots/puma560.toml")?;
    /// let part = Payload::new(2.0, [0.0, 0.0, 0.05], [[3e-3, 0.0, 0.0], [0.0, 3e-3, 0.0], [0.0, 0.0, 3e-3]])
    ///     .unwrap();
    /// let holding = arm.with_payload(&part).unwrap();
    /// let q = dhgen::nalgebra::DVector::from_row_slice(&[0.1, -0.6, 0.4, 0.3, 0.8, -0.2]);
    /// let (qd, qdd) = (q.map(|_| 0.2), q.map(|_| 0.5));
    /// let (dq, dqd) = holding.inverse_dynamics_derivatives(&q, &qd, &qdd);
    /// let tau = dhgen::payload::inverse_dynamics(&arm, &part, &q, &qd, &qdd);
    /// assert!((holding.inverse_dynamics(&q, &qd, &qdd) - tau).amax() < 1e-12);
    /// # Ok::<(), dhgen::Error>(())
    /// ```
    #[must_use]
    pub fn with_payload(&self, payload: &Payload) -> Option<crate::Robot> {
        if !self.has_dynamics() {
            return None;
        }
        let mut model = self.model().clone();
        let tool = model
            .tool
            .map_or_else(dhgen_description::Frame::identity, |t| t.frame::<f64>());
        let held = dhgen_description::Inertial {
            mass: payload.mass,
            com: payload.com,
            inertia: payload.inertia,
        }
        .in_frame(&tool);
        let last = model.links.last_mut()?;
        last.inertial = Some(last.inertial?.combined(&held));
        Some(crate::Robot::from_model(model))
    }
}

/// The payload in world axes at the tool pose: mass, first moment `h = m·c` and inertia about
/// the tool origin.
struct World {
    mass: f64,
    h: Vector3<f64>,
    i: Matrix3<f64>,
}

fn world<A: Arm>(arm: &A, p: &Payload, q: &OVector<f64, A::Dof>) -> World
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    world_at(&arm.fk(q), p)
}

/// [`world`] at the tool pose `tool`.
fn world_at(tool: &Isometry3<f64>, p: &Payload) -> World {
    let r = tool.rotation.to_rotation_matrix().into_inner();
    let tool = crate::dynamics::regressor::inertia_of(&p.parameters());
    World {
        mass: tool.mass,
        h: r * tool.h,
        i: r * tool.k * r.transpose(),
    }
}

/// The wrench `[force; moment about the tool origin]` (world axes) that moves the payload
/// with tool twist `v = [v; ω]` and classical acceleration `a = [a; α]` under gravity `g`.
fn wrench(w: &World, v: &Vector6<f64>, a: &Vector6<f64>, g: &Vector3<f64>) -> Vector6<f64> {
    let (omega, lin) = (v.fixed_rows::<3>(3), a.fixed_rows::<3>(0) - g);
    let alpha = a.fixed_rows::<3>(3);
    let force = lin * w.mass + alpha.cross(&w.h) + omega.cross(&omega.cross(&w.h));
    let moment = w.i * alpha + omega.cross(&(w.i * omega)) + w.h.cross(&lin);
    Vector6::new(force.x, force.y, force.z, moment.x, moment.y, moment.z)
}

fn gravity_vector<A: Arm>(arm: &A) -> Vector3<f64>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    Vector3::from(arm.chain().gravity)
}

/// Inverse dynamics with the payload: the arm's `τ` plus `Jᵀ W`.
pub fn inverse_dynamics<A: ArmDynamics>(
    arm: &A,
    payload: &Payload,
    q: &OVector<f64, A::Dof>,
    qd: &OVector<f64, A::Dof>,
    qdd: &OVector<f64, A::Dof>,
) -> OVector<f64, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    arm.inverse_dynamics(q, qd, qdd) + payload_torque(arm, payload, q, qd, Some(qdd))
}

/// `C q̇ + g` plus friction with the payload.
pub fn bias<A: ArmDynamics>(
    arm: &A,
    payload: &Payload,
    q: &OVector<f64, A::Dof>,
    qd: &OVector<f64, A::Dof>,
) -> OVector<f64, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    arm.bias(q, qd) + payload_torque(arm, payload, q, qd, None)
}

/// The payload's share of inverse dynamics, `Jᵀ W(q, q̇, q̈)` (`q̈ = None`: zero).
pub fn payload_torque<A: Arm>(
    arm: &A,
    payload: &Payload,
    q: &OVector<f64, A::Dof>,
    qd: &OVector<f64, A::Dof>,
    qdd: Option<&OVector<f64, A::Dof>>,
) -> OVector<f64, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let j = arm.jacobian(q);
    let v = &j * qd;
    let mut a = arm.jdot_qdot(q, qd);
    if let Some(qdd) = qdd {
        a += &j * qdd;
    }
    let w = world(arm, payload, q);
    j.tr_mul(&wrench(&w, &v, &a, &gravity_vector(arm)))
}

/// The payload's 6×6 spatial inertia at the tool origin, world axes, rows `[force; moment]`
/// against `[a; α]`.
fn spatial_inertia(w: &World) -> Matrix6<f64> {
    let mut m = Matrix6::zeros();
    let hx = w.h.cross_matrix();
    m.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&(Matrix3::identity() * w.mass));
    m.fixed_view_mut::<3, 3>(0, 3).copy_from(&(-hx));
    m.fixed_view_mut::<3, 3>(3, 0).copy_from(&hx);
    m.fixed_view_mut::<3, 3>(3, 3).copy_from(&w.i);
    m
}

/// The mass matrix with the payload: `D(q) + Jᵀ M J`, `M` the payload's spatial inertia at
/// the tool origin.
pub fn mass_matrix<A: ArmDynamics>(
    arm: &A,
    payload: &Payload,
    q: &OVector<f64, A::Dof>,
) -> OMatrix<f64, A::Dof, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    arm.mass_matrix(q) + inertia_torques(&arm.jacobian(q), &world(arm, payload, q))
}

/// The payload's share of the mass matrix, `Jᵀ M J`.
fn inertia_torques<D: nalgebra::Dim>(
    j: &OMatrix<f64, nalgebra::U6, D>,
    w: &World,
) -> OMatrix<f64, D, D>
where
    DefaultAllocator: ArmAllocator<D>,
{
    j.tr_mul(&(spatial_inertia(w) * j))
}

/// The wrench that holds the payload still against gravity `g`, `[−m g; −h × g]`.
fn weight(w: &World, g: &Vector3<f64>) -> Vector6<f64> {
    wrench(w, &Vector6::zeros(), &Vector6::zeros(), g)
}

/// [`ArmDynamics::tool_terms`] with the payload: D(q) + Jᵀ M J, the tool's J and `J̇ q̇` (the
/// payload rides on the tool frame, so they are the arm's), the bias and the gravity torques
/// with the payload. One call of the arm's `tool_terms` and one tool pose, where the separate
/// functions here ([`mass_matrix`], [`bias`], [`gravity`]) each compute J and the pose again.
///
/// ```
/// dhgen::robot!(mod puma560 = "robots/puma560.toml");
/// use dhgen::payload::{Payload, tool_terms};
///
/// let inertia = [[2e-3, 0.0, 0.0], [0.0, 2e-3, 0.0], [0.0, 0.0, 1e-3]];
/// let part = Payload::new(1.5, [0.0, 0.02, 0.06], inertia).unwrap();
/// let q = dhgen::nalgebra::SVector::from([0.1, -0.6, 0.4, 0.3, 0.8, -0.2]);
/// let qd = dhgen::nalgebra::SVector::from([0.5, -0.2, 0.3, 1.0, -0.7, 0.4]);
/// let t = tool_terms(&puma560::Robot, &part, &q, &qd);
/// let d = dhgen::payload::mass_matrix(&puma560::Robot, &part, &q);
/// assert!((t.mass_matrix - d).norm() < 1e-12 * d.norm());
/// ```
pub fn tool_terms<A: ArmDynamics>(
    arm: &A,
    payload: &Payload,
    q: &OVector<f64, A::Dof>,
    qd: &OVector<f64, A::Dof>,
) -> ToolTerms<f64, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let mut t = arm.tool_terms(q, qd);
    let w = world(arm, payload, q);
    let g = gravity_vector(arm);
    let v = &t.jacobian * qd;
    t.mass_matrix += inertia_torques(&t.jacobian, &w);
    t.bias += t.jacobian.tr_mul(&wrench(&w, &v, &t.jdot_qdot, &g));
    t.gravity += t.jacobian.tr_mul(&weight(&w, &g));
    t
}

/// Gravity torques with the payload: `g(q) − Jᵀ [m g; h × g]`.
pub fn gravity<A: ArmDynamics>(
    arm: &A,
    payload: &Payload,
    q: &OVector<f64, A::Dof>,
) -> OVector<f64, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let weight = weight(&world(arm, payload, q), &gravity_vector(arm));
    arm.gravity(q) + arm.jacobian(q).tr_mul(&weight)
}

/// Forward dynamics with the payload: `(D + Jᵀ M J) q̈ = τ − bias`, both from one
/// [`tool_terms`], by the one rule for a singular inertia matrix
/// ([`inertia_cholesky`](crate::inertia_cholesky)); `None` where it is singular to working
/// precision or q̈ is not finite.
pub fn forward_dynamics<A: ArmDynamics>(
    arm: &A,
    payload: &Payload,
    q: &OVector<f64, A::Dof>,
    qd: &OVector<f64, A::Dof>,
    tau: &OVector<f64, A::Dof>,
) -> Option<OVector<f64, A::Dof>>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let t = tool_terms(arm, payload, q, qd);
    let qdd = crate::inertia_cholesky(t.mass_matrix)?.solve(&(tau - t.bias));
    qdd.iter().all(|x| x.is_finite()).then_some(qdd)
}

/// The kinetic energy with the payload: the arm's plus the payload's, `½ vᵀ M v` for the tool
/// twist `v = J q̇` and `M` the payload's spatial inertia at the tool origin.
pub fn kinetic_energy<A: ArmDynamics>(
    arm: &A,
    payload: &Payload,
    q: &OVector<f64, A::Dof>,
    qd: &OVector<f64, A::Dof>,
) -> f64
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let v = arm.jacobian(q) * qd;
    let m = spatial_inertia(&world(arm, payload, q));
    arm.kinetic_energy(q, qd) + 0.5 * v.dot(&(m * v))
}

/// The potential energy with the payload: the arm's plus the payload's weight at the height of
/// its centre of mass, `−gravity · (m p + h)`, `p` the tool origin and `h = m·c` in world
/// axes (`gravity` above is its gradient).
pub fn potential_energy<A: ArmDynamics>(arm: &A, payload: &Payload, q: &OVector<f64, A::Dof>) -> f64
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let tool = arm.fk(q);
    let w = world_at(&tool, payload);
    let moment = tool.translation.vector * w.mass + w.h;
    arm.potential_energy(q) - gravity_vector(arm).dot(&moment)
}

/// The mass and centre of mass of the links and the payload together, world frame: `(M + m,
/// (M c + m p + h) / (M + m))`, with the arm's `(M, c)`
/// ([`center_of_mass`](ArmDynamics::center_of_mass)), `p` the tool origin and `h = m·c_p` the
/// payload's first moment in world axes (`c` is the world origin if both masses are 0). What
/// a balance or support-polygon check needs while the arm carries the payload.
///
/// ```
/// dhgen::robot!(mod puma560 = "robots/puma560.toml");
/// use dhgen::payload::{Payload, center_of_mass};
///
/// let part = Payload::new(2.0, [0.0, 0.0, 0.05], [[3e-3, 0.0, 0.0], [0.0, 3e-3, 0.0], [0.0, 0.0, 3e-3]])
///     .unwrap();
/// let q = dhgen::nalgebra::SVector::from([0.1, -0.6, 0.4, 0.3, 0.8, -0.2]);
/// let (mass, c) = center_of_mass(&puma560::Robot, &part, &q);
/// let (arm_mass, _) = dhgen::ArmDynamics::center_of_mass(&puma560::Robot, &q);
/// assert!((mass - arm_mass - 2.0).abs() < 1e-12);
/// // The weight of both acts at c: the potential energy is −(M + m) gravity · c.
/// let p = dhgen::payload::potential_energy(&puma560::Robot, &part, &q);
/// assert!((p - mass * 9.81 * c.z).abs() < 1e-9);
/// ```
#[doc(alias = "centerOfMass")]
pub fn center_of_mass<A: ArmDynamics>(
    arm: &A,
    payload: &Payload,
    q: &OVector<f64, A::Dof>,
) -> (f64, Point3<f64>)
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let tool = arm.fk(q);
    let w = world_at(&tool, payload);
    let (mass, c) = arm.center_of_mass(q);
    let total = mass + w.mass;
    let moment = c.coords * mass + tool.translation.vector * w.mass + w.h;
    let c = if total > 0.0 { moment / total } else { moment };
    (total, Point3::new(c.x, c.y, c.z))
}

/// The Jacobian of [`center_of_mass`], 3×n in world axes: `(M J_c + m J_p) / (M + m)`, with
/// the arm's `J_c` ([`center_of_mass_jacobian`](ArmDynamics::center_of_mass_jacobian)) and
/// `J_p` the payload's centre's, a point rigid on the tool (as
/// [`point_jacobian`](crate::velocity::point_jacobian) builds it); zero if both masses are 0.
#[doc(alias = "jacobianCenterOfMass")]
pub fn center_of_mass_jacobian<A: ArmDynamics>(
    arm: &A,
    payload: &Payload,
    q: &OVector<f64, A::Dof>,
) -> OMatrix<f64, U3, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let j = arm.jacobian(q);
    let w = world(arm, payload, q);
    let (mass, _) = arm.center_of_mass(q);
    let total = mass + w.mass;
    let mut out = arm.center_of_mass_jacobian(q) * mass;
    // A payload of no mass has no first moment either, and adds nothing.
    if w.mass > 0.0 {
        let offset = w.h / w.mass;
        for (k, mut column) in out.column_iter_mut().enumerate() {
            column += dhgen_kernel::jacobian::moved_column(&j, k, &offset) * w.mass;
        }
    }
    if total > 0.0 { out / total } else { out }
}

#[cfg(feature = "motion")]
/// [`tool`](crate::task_space::tool) for the arm holding `payload` in its tool frame: the task-space dynamics of arm
/// and payload together, from [`payload`](crate::payload)'s mass matrix, bias and gravity
/// torques (the Jacobian and `J̇ q̇` are the arm's: the payload rides on the tool frame), all
/// from one [`payload::tool_terms`](crate::payload::tool_terms).
pub fn tool_with_payload<A: ArmDynamics>(
    arm: &A,
    payload: &Payload,
    q: &OVector<f64, A::Dof>,
    qd: &OVector<f64, A::Dof>,
) -> Result<
    dhgen_motion::task_space::TaskDynamics<nalgebra::U6, A::Dof>,
    dhgen_motion::task_space::TaskSpaceError,
>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    dhgen_motion::task_space::tool_from_terms(tool_terms(arm, payload, q, qd))
}
