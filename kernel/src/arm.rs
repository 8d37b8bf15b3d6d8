//! One interface to every robot: a generated module's `Robot` and the runtime
//! [`Robot`](crate::Robot) both implement [`Arm`] (and [`ArmDynamics`] when the description
//! has mass properties), so inverse kinematics, planners and controllers are written once.
//!
//! Joint vectors are nalgebra vectors of dimension [`Arm::Dof`]: `Const<N>` for generated
//! robots, so algorithms generic over the trait allocate nothing there, and `Dyn` for the
//! runtime path.
//!
//! ```
//! use dhgen::Arm;
//! dhgen::robot!(mod planar = "../robots/planar_elbow.toml");
//!
//! fn reach<A: Arm>(arm: &A, q: &dhgen::nalgebra::OVector<f64, A::Dof>) -> f64
//! where
//!     dhgen::nalgebra::DefaultAllocator: dhgen::ArmAllocator<A::Dof>,
//! {
//!     arm.fk(q).translation.vector.norm()
//! }
//!
//! let q = dhgen::nalgebra::SVector::<f64, 2>::new(0.0, 0.0);
//! assert!((reach(&planar::Robot, &q) - 1.8).abs() < 1e-12);
//! ```

use crate::ChainRef;
use nalgebra::allocator::Allocator;
use nalgebra::{
    DefaultAllocator, Dim, Isometry3, OMatrix, OVector, Point3, Scalar, U3, U6, Vector3, Vector6,
};

/// The allocator bounds every [`Arm`] needs: joint vectors, the 6×n and 3×n Jacobians and n×n
/// matrices. Repeat `DefaultAllocator: ArmAllocator<A::Dof>` in generic code.
pub trait ArmAllocator<D: Dim>:
    Allocator<D> + Allocator<U6, D> + Allocator<U3, D> + Allocator<D, D>
{
}

impl<D: Dim, A> ArmAllocator<D> for A where
    A: Allocator<D> + Allocator<U6, D> + Allocator<U3, D> + Allocator<D, D>
{
}

/// The joint values of `chain` at `q` (offsets applied), as the trait's default methods walk
/// the chain.
fn values<'c, D: Dim>(
    chain: ChainRef<'c>,
    q: &'c OVector<f64, D>,
) -> impl FnMut(usize) -> crate::JointValue<f64> + 'c
where
    DefaultAllocator: Allocator<D>,
{
    move |i| chain.bodies[i].value(q.get(i).copied().unwrap_or(0.0))
}

/// A joint vector of an arm.
pub type JointVector<A> = OVector<f64, <A as Arm>::Dof>;

/// Kinematics of a serial arm.
pub trait Arm
where
    DefaultAllocator: ArmAllocator<Self::Dof>,
{
    /// The dimension of joint vectors: `Const<N>` (generated) or `Dyn` (runtime).
    type Dof: Dim;

    /// The arm's kinematic structure: its fixed transforms, joints, limits, link frames,
    /// mass properties and collision capsules, the same numbers its kinematics and dynamics
    /// are computed from (a generated module's `CHAIN`, a runtime robot's
    /// `dhgen::Robot::chain`).
    fn chain(&self) -> ChainRef<'_>;

    /// Number of joints.
    fn dof(&self) -> usize {
        self.chain().dof()
    }

    /// The joint dimension as a value, to build vectors with `OVector::zeros_generic`.
    fn dim(&self) -> Self::Dof;

    /// Joint limits `[lower, upper]` of joint `j` (0-based), if the description gives them.
    fn limits(&self, j: usize) -> Option<[f64; 2]> {
        self.chain().bodies.get(j)?.limits
    }

    /// Whether joint `j` is prismatic.
    fn is_prismatic(&self, j: usize) -> bool {
        self.chain()
            .bodies
            .get(j)
            .is_some_and(|b| b.joint == crate::JointKind::Prismatic)
    }

    /// Pose of the tool frame in the world frame: base · A1 ⋯ An · tool.
    #[doc(alias = "fkine")]
    #[doc(alias = "forwardKinematics")]
    fn fk(&self, q: &OVector<f64, Self::Dof>) -> Isometry3<f64>;

    /// Writes the link frames (world frame, tool not applied) into `out`, as many as fit.
    fn frames_into(&self, q: &OVector<f64, Self::Dof>, out: &mut [Isometry3<f64>]);

    /// Geometric Jacobian of the tool frame origin, world axes, rows `[v; ω]`.
    #[doc(alias = "jacob0")]
    #[doc(alias = "computeJointJacobians")]
    #[doc(alias = "getFrameJacobian")]
    fn jacobian(&self, q: &OVector<f64, Self::Dof>) -> OMatrix<f64, U6, Self::Dof>;

    /// `J̇(q, q̇) q̇` of the tool frame origin, world axes, rows `[v; ω]`: the tool's
    /// acceleration at `q̈ = 0`. By default from the Jacobian
    /// (`dhgen::velocity::jdot_qdot_from_jacobian`); generated
    /// modules override it with their straight-line code.
    #[doc(alias = "jacob0_dot")]
    #[doc(alias = "getFrameClassicalAcceleration")]
    fn jdot_qdot(&self, q: &OVector<f64, Self::Dof>, qd: &OVector<f64, Self::Dof>) -> Vector6<f64> {
        crate::jacobian::jdot_qdot_from_jacobian(self, &self.jacobian(q), qd)
    }

    /// The tool frame's geometric Jacobian in the tool's own axes, its body Jacobian: rows
    /// `[v; ω]`, the tool origin's velocity and the tool's angular velocity, both resolved in
    /// the tool frame, `J_b = diag(Rᵀ, Rᵀ) J` for the tool's rotation `R` (Pinocchio's `LOCAL`
    /// frame Jacobian). It is the Jacobian of a velocity command given in the tool frame, and
    /// `J_bᵀ F` maps a wrench measured by a wrist force sensor to joint torques. It does not
    /// depend on the base placement. By default from [`fk`](Self::fk) and
    /// [`jacobian`](Self::jacobian)
    /// (`dhgen::velocity::body_jacobian_from_jacobian`);
    /// generated modules override it with straight-line code walked back from the tool, which
    /// never computes the base's joints' frames (PUMA 560: 730 instructions, as many as
    /// `jacobian`, against 1,916 for this default on the same arm), and
    /// `dhgen::Robot` takes the tool's rotation from its Jacobian's walk of the chain.
    ///
    /// ```
    /// use dhgen::Arm;
    /// use dhgen::nalgebra::{SVector, Vector6};
    /// dhgen::robot!(mod puma = "../robots/puma560.toml");
    ///
    /// let q = SVector::<f64, 6>::new(0.2, -0.3, 0.4, 0.5, 0.6, 0.7);
    /// let jb = puma::Robot.body_jacobian(&q);
    /// // The PUMA's last joint turns its tool about the tool's own z axis, at any q.
    /// assert!((jb.column(5) - Vector6::new(0.0, 0.0, 0.0, 0.0, 0.0, 1.0)).norm() < 1e-12);
    /// ```
    #[doc(alias = "jacobe")]
    fn body_jacobian(&self, q: &OVector<f64, Self::Dof>) -> OMatrix<f64, U6, Self::Dof> {
        crate::jacobian::body_jacobian_from_jacobian(&self.fk(q), self.jacobian(q))
    }

    /// `J̇_b(q, q̇) q̇`: the rate of the tool's velocity in its own axes at zero joint
    /// acceleration, as in `d/dt (J_b q̇) = J_b q̈ + J̇_b q̇` with
    /// [`body_jacobian`](Self::body_jacobian) `J_b`; what a task-space controller working in
    /// tool axes needs beside `J_b` (Pinocchio's `getFrameJacobianTimeVariation(LOCAL)` times
    /// q̇, its `getFrameAcceleration(LOCAL)` at q̈ = 0). From the world-axes terms `[v; ω] = J q̇` and
    /// `[a; α] = J̇ q̇` ([`jdot_qdot`](Self::jdot_qdot)): `[Rᵀ a − ω_b × v_b; Rᵀ α]`, with
    /// `v_b = Rᵀ v`, `ω_b = Rᵀ ω` (the tool axes turn with ω, which adds `−ω_b × v_b` to the
    /// linear part; the classical acceleration of the tool origin in tool axes is `Rᵀ a`).
    /// `dhgen::Robot` computes all three from one walk of the chain; generated
    /// modules override it with straight-line code from the outward pass in joint frames, which
    /// never carries a frame to the base (PUMA 560: 175 operations, against 234 for
    /// `jdot_qdot` alone).
    ///
    /// ```
    /// use dhgen::Arm;
    /// use dhgen::nalgebra::SVector;
    /// dhgen::robot!(mod puma = "../robots/puma560.toml");
    ///
    /// let (q, qd) = (SVector::<f64, 6>::repeat(0.3), SVector::<f64, 6>::repeat(0.5));
    /// // Against the central difference of J_b q̇ along q(t) = q + t q̇ (q̈ = 0).
    /// let h = 1e-5;
    /// let fd = (puma::Robot.body_jacobian(&(q + qd * h)) * qd
    ///     - puma::Robot.body_jacobian(&(q - qd * h)) * qd)
    ///     / (2.0 * h);
    /// assert!((puma::Robot.body_jdot_qdot(&q, &qd) - fd).amax() < 1e-8);
    /// ```
    #[doc(alias = "getFrameJacobianTimeVariation")]
    fn body_jdot_qdot(
        &self,
        q: &OVector<f64, Self::Dof>,
        qd: &OVector<f64, Self::Dof>,
    ) -> Vector6<f64> {
        crate::jacobian::body_jdot_qdot_from(
            &self.fk(q),
            &(self.jacobian(q) * qd),
            &self.jdot_qdot(q, qd),
        )
    }
}

/// Rigid-body dynamics of a serial arm (`τ = D q̈ + C q̇ + g`, plus motor inertia and
/// friction when described).
pub trait ArmDynamics: Arm
where
    DefaultAllocator: ArmAllocator<Self::Dof>,
{
    /// Joint-space inertia matrix D(q).
    #[doc(alias = "crba")]
    #[doc(alias = "inertia")]
    fn mass_matrix(&self, q: &OVector<f64, Self::Dof>) -> OMatrix<f64, Self::Dof, Self::Dof>;

    /// Writes the Christoffel symbols `c_ijk` (k the equation index) into `out` in the order
    /// `(i·n + j)·n + k`, as many as fit (`n³` for all). By default from the Coriolis matrix,
    /// which is linear in `q̇`: `c_ijk = C(q, e_i)_kj`, exactly (n evaluations of C);
    /// generated modules and the runtime path override it.
    fn christoffel_into(&self, q: &OVector<f64, Self::Dof>, out: &mut [f64]) {
        let n = self.dof();
        let mut e = OVector::<f64, Self::Dof>::zeros_generic(self.dim(), nalgebra::U1);
        for i in 0..n {
            e[i] = 1.0;
            let c = self.coriolis(q, &e);
            e[i] = 0.0;
            for j in 0..n {
                for k in 0..n {
                    if let Some(o) = out.get_mut((i * n + j) * n + k) {
                        *o = c[(k, j)];
                    }
                }
            }
        }
    }

    /// Coriolis matrix C(q, q̇), `C_kj = Σ_i c_ijk q̇_i`.
    #[doc(alias = "computeCoriolisMatrix")]
    fn coriolis(
        &self,
        q: &OVector<f64, Self::Dof>,
        qd: &OVector<f64, Self::Dof>,
    ) -> OMatrix<f64, Self::Dof, Self::Dof>;

    /// Gravity torques g(q).
    #[doc(alias = "gravload")]
    #[doc(alias = "computeGeneralizedGravity")]
    fn gravity(&self, q: &OVector<f64, Self::Dof>) -> OVector<f64, Self::Dof>;

    /// The torques at zero acceleration, `C(q, q̇) q̇ + g(q)` plus friction. By default the
    /// inverse dynamics at `q̈ = 0`.
    #[doc(alias = "nonLinearEffects")]
    fn bias(
        &self,
        q: &OVector<f64, Self::Dof>,
        qd: &OVector<f64, Self::Dof>,
    ) -> OVector<f64, Self::Dof> {
        let zero = OVector::<f64, Self::Dof>::zeros_generic(self.dim(), nalgebra::U1);
        self.inverse_dynamics(q, qd, &zero)
    }

    /// D(q), the tool's Jacobian J(q) and `J̇ q̇`, the bias torques and g(q) at once: what
    /// `dhgen::task_space` reads. By default five calls; generated modules
    /// override it to compute all five from one state's sines and cosines.
    fn tool_terms(
        &self,
        q: &OVector<f64, Self::Dof>,
        qd: &OVector<f64, Self::Dof>,
    ) -> ToolTerms<f64, Self::Dof> {
        ToolTerms {
            mass_matrix: self.mass_matrix(q),
            jacobian: self.jacobian(q),
            jdot_qdot: self.jdot_qdot(q, qd),
            bias: self.bias(q, qd),
            gravity: self.gravity(q),
        }
    }

    /// Kinetic energy `T(q, q̇) = ½ q̇ᵀ D(q) q̇` of the links and rotors. By default from
    /// the mass matrix.
    #[doc(alias = "computeKineticEnergy")]
    fn kinetic_energy(&self, q: &OVector<f64, Self::Dof>, qd: &OVector<f64, Self::Dof>) -> f64 {
        0.5 * qd.dot(&(self.mass_matrix(q) * qd))
    }

    /// Potential energy `P(q) = −Σ m_k gravity · c_k` of the links, centres of mass in the
    /// world frame: `g(q) = ∂P/∂q`. By default by walking [`chain`](Arm::chain) (the runtime
    /// path's algorithm); generated modules override it.
    #[doc(alias = "computePotentialEnergy")]
    fn potential_energy(&self, q: &OVector<f64, Self::Dof>) -> f64 {
        crate::recursive::potential_energy(self.chain(), values(self.chain(), q))
    }

    /// The links' total mass `M` and centre of mass `c` in the world frame (links fixed to the
    /// base, which no joint moves, are not counted; `c` is the world origin if `M` is 0):
    /// Pinocchio's `centerOfMass`. The potential energy is `−M gravity · c`. By default by
    /// walking [`chain`](Arm::chain) (the runtime path's algorithm); generated modules
    /// override it with their own derivation.
    #[doc(alias = "centerOfMass")]
    fn center_of_mass(&self, q: &OVector<f64, Self::Dof>) -> (f64, Point3<f64>) {
        let chain = self.chain();
        let (mut total, mut moment) = (0.0, Vector3::zeros());
        crate::recursive::masses(chain, values(chain, q), |_, mass, com| {
            total += mass;
            moment += com * mass;
        });
        let c = if total > 0.0 { moment / total } else { moment };
        (total, Point3::new(c.x, c.y, c.z))
    }

    /// The Jacobian of the centre of mass, 3×n in world axes: `ċ = J_c q̇`, Pinocchio's
    /// `jacobianCenterOfMass`; the gravity torques are `g(q) = −M J_cᵀ gravity`. The mass-weighted
    /// mean of the Jacobians of the links' centres of mass (as
    /// `dhgen::velocity::point_jacobian` builds them from the tool's Jacobian
    /// and pose) by default; zero if the links have no mass. Generated modules override it
    /// with their own derivation.
    ///
    /// ```
    /// use dhgen::nalgebra::{SVector, Vector3};
    /// use dhgen::ArmDynamics;
    /// dhgen::robot!(mod puma = "../robots/puma560.toml");
    ///
    /// let q = SVector::<f64, 6>::new(0.2, -0.3, 0.4, 0.5, 0.6, 0.7);
    /// let (mass, c) = puma::Robot.center_of_mass(&q);
    /// let jc = puma::Robot.center_of_mass_jacobian(&q);
    /// // Gravity acts on the whole arm at its centre of mass.
    /// let gravity = Vector3::new(0.0, 0.0, -9.81);
    /// assert!((-(jc.transpose() * gravity) * mass - puma::gravity(&q)).norm() < 1e-10);
    /// assert!((puma::potential_energy(&q) + mass * gravity.dot(&c.coords)).abs() < 1e-10);
    /// ```
    #[doc(alias = "jacobianCenterOfMass")]
    fn center_of_mass_jacobian(&self, q: &OVector<f64, Self::Dof>) -> OMatrix<f64, U3, Self::Dof> {
        let chain = self.chain();
        let j = self.jacobian(q);
        let tool = self.fk(q).translation.vector;
        let mut out = OMatrix::<f64, U3, Self::Dof>::zeros_generic(U3, self.dim());
        let mut total = 0.0;
        crate::recursive::masses(chain, values(chain, q), |k, mass, com| {
            // Body k's centre moves with joints 1..=k: column c gains m (v_c + ω_c × (com − tool)).
            total += mass;
            let offset = com - tool;
            for c in 0..(k + 1).min(out.ncols()) {
                let mut column = out.column_mut(c);
                column += crate::jacobian::moved_column(&j, c, &offset) * mass;
            }
        });
        if total > 0.0 { out / total } else { out }
    }

    /// Inverse dynamics τ(q, q̇, q̈).
    #[doc(alias = "rnea")]
    #[doc(alias = "rne")]
    fn inverse_dynamics(
        &self,
        q: &OVector<f64, Self::Dof>,
        qd: &OVector<f64, Self::Dof>,
        qdd: &OVector<f64, Self::Dof>,
    ) -> OVector<f64, Self::Dof>;

    /// Forward dynamics q̈(q, q̇, τ); `None` where D(q) is singular to working precision
    /// (see [`cholesky_pivot_floor`](crate::cholesky_pivot_floor)) or q̈ is not finite.
    #[doc(alias = "aba")]
    #[doc(alias = "accel")]
    #[doc(alias = "fdyn")]
    fn forward_dynamics(
        &self,
        q: &OVector<f64, Self::Dof>,
        qd: &OVector<f64, Self::Dof>,
        tau: &OVector<f64, Self::Dof>,
    ) -> Option<OVector<f64, Self::Dof>>;
}

/// The joint-space terms task-space dynamics is built from, at one state `(q, q̇)`: what
/// [`ArmDynamics::tool_terms`] returns. Generated arms compute the five from one state's sines
/// and cosines (their `tool_terms`), the runtime path by separate calls.
#[derive(Clone, Debug, PartialEq)]
pub struct ToolTerms<T: Scalar, D: Dim>
where
    DefaultAllocator: ArmAllocator<D>,
{
    /// The mass matrix D(q).
    pub mass_matrix: OMatrix<T, D, D>,
    /// The tool frame's geometric Jacobian J(q) (rows `[v; ω]`, world axes).
    pub jacobian: OMatrix<T, U6, D>,
    /// The tool's `J̇(q, q̇) q̇`.
    pub jdot_qdot: OVector<T, U6>,
    /// The torques at zero acceleration `b(q, q̇) = C q̇ + g` plus friction.
    pub bias: OVector<T, D>,
    /// The gravity torques g(q).
    pub gravity: OVector<T, D>,
}
