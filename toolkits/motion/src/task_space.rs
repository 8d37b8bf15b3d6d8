//! Task-space (operational-space) dynamics: the arm as seen from its tool, in Khatib's
//! formulation, for Cartesian impedance, force and operational-space control.
//!
//! Under joint torques `τ = Jᵀ F`, the tool's acceleration `a = J q̈ + J̇ q̇` obeys
//!
//! `Λ(q) a + μ(q, q̇) + p(q) = F`,
//!
//! with, for `D(q)` the mass matrix, `g(q)` the gravity torques and `b(q, q̇)` the torques at
//! zero acceleration (`C q̇ + g` plus friction, [`ArmDynamics::bias`]):
//! - `Λ = (J D⁻¹ Jᵀ)⁻¹`, the task-space inertia (Robotics Toolbox's `inertia_x` for a square
//!   `J`);
//! - `J̄ = D⁻¹ Jᵀ Λ`, the dynamically consistent generalised inverse of `J`;
//! - `p = J̄ᵀ g`, the task-space gravity (`gravload_x`);
//! - `μ = J̄ᵀ (b − g) − Λ J̇ q̇`, the task-space Coriolis, centrifugal and friction forces
//!   (`coriolis_x` times the tool twist, for a square `J`).
//!
//! For a redundant arm (more joints than task rows) the torques `Nᵀ τ₀ = τ₀ − Jᵀ J̄ᵀ τ₀`
//! ([`TaskDynamics::null_space_torque`]) leave the task's acceleration unchanged: the
//! posture behind a Cartesian task.
//!
//! `J` is any task Jacobian with rows indexed by `M` ([`TaskDynamics::new`]); [`tool`] takes the
//! tool's geometric Jacobian (rows `[v; ω]`, world axes, as
//! [`Arm::jacobian`](dhgen_kernel::Arm::jacobian)), `tool_with_payload` the same with a payload in the
//! gripper, and [`tool_position`] its three linear rows, the task an arm with fewer than six joints
//! can hold. Everything is computed from the arm's own `D`, `J`, `J̇ q̇`, `b` and `g` (generated
//! code for a generated arm), with nalgebra's Cholesky factorisations on fixed-size matrices: no
//! allocation for generated arms, and `no_std`.
//!
//! A singular `D` or a task Jacobian that has lost rank is reported, not papered over: `Λ`
//! grows as `1/σ²` with the smallest singular value `σ` of `J D^{-1/2}`, and is refused where
//! `J D⁻¹ Jᵀ` is singular to working precision (the rule of
//! [`inertia_cholesky`](dhgen_kernel::inertia_cholesky)).
//!
//! ```
//! use dhgen::nalgebra::{SVector, Vector6};
//! use dhgen::{Arm, ArmDynamics};
//! dhgen::robot!(mod puma = "../../robots/puma560.toml");
//!
//! let q = SVector::<f64, 6>::new(0.2, -0.5, 0.4, 0.3, 0.9, -0.2);
//! let qd = SVector::<f64, 6>::new(0.5, -0.3, 0.8, 1.0, -0.4, 0.2);
//! let task = dhgen::task_space::tool(&puma::Robot, &q, &qd).unwrap();
//!
//! // The force that gives the tool the acceleration `a`, as joint torques ...
//! let a = Vector6::new(0.5, -1.0, 2.0, 0.3, 0.0, -0.7);
//! let tau = task.torque(&task.force(&a));
//! // ... gives it that acceleration.
//! let qdd = puma::Robot.forward_dynamics(&q, &qd, &tau).unwrap();
//! let achieved = puma::Robot.jacobian(&q) * qdd + puma::Robot.jdot_qdot(&q, &qd);
//! assert!((achieved - a).norm() < 1e-9);
//! ```

pub use dhgen_kernel::ToolTerms;
use dhgen_kernel::{ArmAllocator, ArmDynamics};
use nalgebra::allocator::Allocator;
use nalgebra::{DefaultAllocator, Dim, DimName, OMatrix, OVector, U3, U6};

/// Why task-space dynamics could not be formed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum TaskSpaceError {
    /// An input (the configuration, the velocity, or a quantity computed from them) is not
    /// finite.
    #[error("task space: a joint value or a dynamic quantity is not finite")]
    NotFinite,
    /// The mass matrix `D(q)` is singular to working precision (an arm with a massless,
    /// rotor-less joint).
    #[error("task space: the mass matrix D(q) is singular")]
    SingularInertia,
    /// `J D⁻¹ Jᵀ` is singular to working precision: the task Jacobian has lost rank (a
    /// kinematic singularity, or more task rows than joints).
    #[error("task space: the task Jacobian has lost rank (J D⁻¹ Jᵀ is singular)")]
    SingularTask,
}

/// The task-space dynamics of one task at one state `(q, q̇)`: `Λ a + μ + p = F` for the
/// task acceleration `a = J q̈ + J̇ q̇` under the torques `Jᵀ F`. `M` indexes the task's rows
/// (`U6` for the tool's twist), `D` the joints. See the [module](self) for the formulas.
#[derive(Clone, Debug)]
pub struct TaskDynamics<M: DimName, D: Dim>
where
    DefaultAllocator: Allocator<M, D> + Allocator<M, M> + Allocator<M>,
{
    jacobian: OMatrix<f64, M, D>,
    jdot_qdot: OVector<f64, M>,
    inertia: OMatrix<f64, M, M>,
    mobility: OMatrix<f64, M, M>,
    inverse_transpose: OMatrix<f64, M, D>,
    coriolis: OVector<f64, M>,
    gravity: OVector<f64, M>,
}

impl<M: DimName, D: Dim> TaskDynamics<M, D>
where
    DefaultAllocator:
        Allocator<M, D> + Allocator<M, M> + Allocator<M> + Allocator<D, D> + Allocator<D>,
{
    /// The task-space dynamics of the task with Jacobian `jacobian` (`M` rows, one column per
    /// joint), from the mass matrix `d`, the task's `J̇ q̇`, the torques at zero acceleration
    /// `bias` (`C q̇ + g` plus friction) and the gravity torques `gravity`, all at one state.
    ///
    /// Costs one Cholesky factorisation `D = L Lᵀ`, two triangular substitutions of `J`
    /// (`W = J L⁻ᵀ`, then `J D⁻¹ = W L⁻¹`), the product `J D⁻¹ Jᵀ = W Wᵀ` and its
    /// inverse. `d` is read in its lower triangle.
    ///
    /// # Panics
    ///
    /// If `d`, `bias` or `gravity` does not have one row per column of `jacobian` (only
    /// possible with `Dyn` joint dimensions), naming the sizes.
    pub fn new(
        d: OMatrix<f64, D, D>,
        jacobian: OMatrix<f64, M, D>,
        jdot_qdot: &OVector<f64, M>,
        bias: &OVector<f64, D>,
        gravity: &OVector<f64, D>,
    ) -> Result<Self, TaskSpaceError> {
        let n = jacobian.ncols();
        assert!(
            d.shape() == (n, n) && bias.len() == n && gravity.len() == n,
            "dhgen::task_space::TaskDynamics::new: `d` is {}×{}, `bias` has length {} and \
             `gravity` {}, expected {n}×{n} and {n} (one per column of `jacobian`)",
            d.nrows(),
            d.ncols(),
            bias.len(),
            gravity.len()
        );
        let finite = |x: &[f64]| x.iter().all(|v| v.is_finite());
        if !(finite(d.as_slice())
            && finite(jacobian.as_slice())
            && finite(jdot_qdot.as_slice())
            && finite(bias.as_slice())
            && finite(gravity.as_slice()))
        {
            return Err(TaskSpaceError::NotFinite);
        }
        let factor = dhgen_kernel::inertia_cholesky(d).ok_or(TaskSpaceError::SingularInertia)?;
        let l = factor.l_dirty(); // D = L Lᵀ, in the lower triangle
        // W = J L⁻ᵀ, column by column (substitution from the right: the columns of an M×n
        // matrix are contiguous M-vectors), then J D⁻¹ = W L⁻¹ the same way backwards.
        let mut w = jacobian.clone();
        for j in 0..n {
            for k in 0..j {
                let (done, mut column) = (w.column(k).clone_owned(), w.column_mut(j));
                column.axpy(-l[(j, k)], &done, 1.0);
            }
            w.column_mut(j).scale_mut(1.0 / l[(j, j)]);
        }
        // J D⁻¹ Jᵀ = W Wᵀ: symmetric and positive semi-definite by construction.
        let (m, _) = w.shape_generic();
        let mut mobility = OMatrix::<f64, M, M>::zeros_generic(m, m);
        for column in w.column_iter() {
            mobility.ger(1.0, &column, &column, 1.0);
        }
        let mut jdinv = w;
        for j in (0..n).rev() {
            for k in j + 1..n {
                let (done, mut column) = (jdinv.column(k).clone_owned(), jdinv.column_mut(j));
                column.axpy(-l[(k, j)], &done, 1.0);
            }
            jdinv.column_mut(j).scale_mut(1.0 / l[(j, j)]);
        }
        let factor =
            dhgen_kernel::inertia_cholesky(mobility.clone()).ok_or(TaskSpaceError::SingularTask)?;
        let inertia = inverse_from_cholesky(factor.l_dirty());
        let inverse_transpose = &inertia * &jdinv;
        let gravity_task = &inverse_transpose * gravity;
        let coriolis = &inverse_transpose * (bias - gravity) - &inertia * jdot_qdot;
        if !(finite(inertia.as_slice())
            && finite(inverse_transpose.as_slice())
            && finite(coriolis.as_slice())
            && finite(gravity_task.as_slice()))
        {
            return Err(TaskSpaceError::SingularTask);
        }
        Ok(TaskDynamics {
            jacobian,
            jdot_qdot: jdot_qdot.clone_owned(),
            inertia,
            mobility,
            inverse_transpose,
            coriolis,
            gravity: gravity_task,
        })
    }

    /// The task Jacobian `J`.
    pub fn jacobian(&self) -> &OMatrix<f64, M, D> {
        &self.jacobian
    }

    /// The task-space inertia `Λ = (J D⁻¹ Jᵀ)⁻¹`, symmetric positive definite.
    #[doc(alias = "inertia_x")]
    #[doc(alias = "Lambda")]
    pub fn inertia(&self) -> &OMatrix<f64, M, M> {
        &self.inertia
    }

    /// Its inverse `J D⁻¹ Jᵀ`, the task-space mobility: the task acceleration a unit force
    /// gives at rest, as a contact's Delassus matrix.
    pub fn mobility(&self) -> &OMatrix<f64, M, M> {
        &self.mobility
    }

    /// `J̄ᵀ = Λ J D⁻¹`, the transpose of the dynamically consistent generalised inverse
    /// `J̄ = D⁻¹ Jᵀ Λ` (`J J̄ = I`).
    pub fn inverse_transpose(&self) -> &OMatrix<f64, M, D> {
        &self.inverse_transpose
    }

    /// The task-space Coriolis, centrifugal and friction forces `μ = J̄ᵀ (b − g) − Λ J̇ q̇`.
    #[doc(alias = "coriolis_x")]
    pub fn coriolis(&self) -> &OVector<f64, M> {
        &self.coriolis
    }

    /// The task-space gravity forces `p = J̄ᵀ g`.
    #[doc(alias = "gravload_x")]
    pub fn gravity(&self) -> &OVector<f64, M> {
        &self.gravity
    }

    /// The task force that gives the task the acceleration `a`: `F = Λ a + μ + p`.
    pub fn force(&self, a: &OVector<f64, M>) -> OVector<f64, M> {
        &self.inertia * a + &self.coriolis + &self.gravity
    }

    /// The task acceleration `a = Λ⁻¹ (F − μ − p)` the task force `F` gives (with no other
    /// torque applied).
    #[doc(alias = "accel_x")]
    pub fn acceleration(&self, force: &OVector<f64, M>) -> OVector<f64, M> {
        &self.mobility * (force - &self.coriolis - &self.gravity)
    }

    /// The joint torques `Jᵀ F` that exert the task force `F`.
    pub fn torque(&self, force: &OVector<f64, M>) -> OVector<f64, D> {
        self.jacobian.tr_mul(force)
    }

    /// The part of the joint torques `τ₀` that does not accelerate the task:
    /// `Nᵀ τ₀ = τ₀ − Jᵀ J̄ᵀ τ₀`, in `O(M n)` without forming the projector. Add it to
    /// [`torque`](Self::torque)'s to drive a redundant arm's posture behind its task. Zero for
    /// a square, non-singular `J`.
    ///
    /// # Panics
    ///
    /// If `tau0` does not have one entry per joint (only possible with `Dyn` joint
    /// dimensions).
    pub fn null_space_torque(&self, tau0: &OVector<f64, D>) -> OVector<f64, D> {
        let n = self.jacobian.ncols();
        assert!(
            tau0.len() == n,
            "dhgen::task_space::TaskDynamics::null_space_torque: `tau0` has length {}, \
             expected {n} (one entry per joint)",
            tau0.len()
        );
        tau0 - self.jacobian.tr_mul(&(&self.inverse_transpose * tau0))
    }

    /// Forward dynamics with the task held to the acceleration `a` by a constraint (a rigid
    /// contact, a tool fixed in a vice, or a guide: Pinocchio's constrained `forwardDynamics`
    /// with the constraint Jacobian `J` and drift `J̇ q̇`): from the unconstrained
    /// accelerations `qdd_free` (the arm's forward dynamics under the applied torques), the
    /// accelerations `q̈ = q̈_free + D⁻¹ Jᵀ F` and the constraint's force
    /// `F = Λ (a − J q̈_free − J̇ q̇)`, so that `J q̈ + J̇ q̇ = a` and `D q̈ + b = τ + Jᵀ F`. Of all
    /// accelerations meeting the constraint, `q̈` is the one closest to `q̈_free` in the metric
    /// of `D` (Gauss's principle of least constraint). `a = 0` holds the task still.
    ///
    /// # Panics
    ///
    /// If `qdd_free` does not have one entry per joint (only possible with `Dyn` joint
    /// dimensions).
    #[doc(alias = "forwardDynamics")]
    #[doc(alias = "constraintDynamics")]
    pub fn constrained(
        &self,
        qdd_free: &OVector<f64, D>,
        a: &OVector<f64, M>,
    ) -> (OVector<f64, D>, OVector<f64, M>) {
        let n = self.jacobian.ncols();
        assert!(
            qdd_free.len() == n,
            "dhgen::task_space::TaskDynamics::constrained: `qdd_free` has length {}, \
             expected {n} (one entry per joint)",
            qdd_free.len()
        );
        let drift = &self.jacobian * qdd_free + &self.jdot_qdot;
        let force = &self.inertia * (a - drift);
        // D⁻¹ Jᵀ F = J̄ Λ⁻¹ F, with J̄ᵀ stored.
        let qdd = qdd_free + self.inverse_transpose.tr_mul(&(&self.mobility * &force));
        (qdd, force)
    }
}

/// `(R Rᵀ)⁻¹ = R⁻ᵀ R⁻¹` for `R` the lower triangle of `r` (its strict upper triangle is
/// ignored), with the diagonal of `R` non-zero: `R⁻¹` by substitution in place, then the
/// product's lower triangle, mirrored. About a third of the work of solving against the
/// identity, and exactly symmetric.
fn inverse_from_cholesky<M: DimName>(r: &OMatrix<f64, M, M>) -> OMatrix<f64, M, M>
where
    DefaultAllocator: Allocator<M, M>,
{
    let m = r.nrows();
    let mut inv = OMatrix::<f64, M, M>::zeros();
    for j in 0..m {
        inv[(j, j)] = 1.0 / r[(j, j)];
        for i in j + 1..m {
            let sum: f64 = (j..i).map(|k| r[(i, k)] * inv[(k, j)]).sum();
            inv[(i, j)] = -sum / r[(i, i)];
        }
    }
    let mut out = OMatrix::<f64, M, M>::zeros();
    for i in 0..m {
        for k in 0..=i {
            let v: f64 = (i..m).map(|j| inv[(j, i)] * inv[(j, k)]).sum();
            out[(i, k)] = v;
            out[(k, i)] = v;
        }
    }
    out
}

/// The task-space dynamics of the tool frame's twist `[v; ω]` (world axes, the rows of
/// [`Arm::jacobian`](dhgen_kernel::Arm::jacobian)) at `(q, q̇)`. Needs six independent joint
/// directions: an arm with fewer than six joints, or at a kinematic singularity, gives
/// [`TaskSpaceError::SingularTask`]; [`tool_position`] is the task such arms can hold.
pub fn tool<A: ArmDynamics>(
    arm: &A,
    q: &OVector<f64, A::Dof>,
    qd: &OVector<f64, A::Dof>,
) -> Result<TaskDynamics<U6, A::Dof>, TaskSpaceError>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    tool_from_terms(arm.tool_terms(q, qd))
}

/// The task of the tool's whole twist from its joint-space terms (what [`tool`] takes of an
/// arm; `dhgen::task_space::tool_with_payload` gives it an arm's with a payload's).
pub fn tool_from_terms<D: Dim>(t: ToolTerms<f64, D>) -> Result<TaskDynamics<U6, D>, TaskSpaceError>
where
    DefaultAllocator: ArmAllocator<D>,
{
    TaskDynamics::<U6, D>::new(t.mass_matrix, t.jacobian, &t.jdot_qdot, &t.bias, &t.gravity)
}

/// The task-space dynamics of the tool frame's origin (the three linear rows of
/// [`Arm::jacobian`](dhgen_kernel::Arm::jacobian), world axes) at `(q, q̇)`: the task of a Cartesian
/// position or impedance controller that leaves the orientation free.
pub fn tool_position<A: ArmDynamics>(
    arm: &A,
    q: &OVector<f64, A::Dof>,
    qd: &OVector<f64, A::Dof>,
) -> Result<TaskDynamics<U3, A::Dof>, TaskSpaceError>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let t = arm.tool_terms(q, qd);
    let linear = t.jacobian.fixed_rows::<3>(0).into_owned();
    let jdq = t.jdot_qdot.fixed_rows::<3>(0).into_owned();
    TaskDynamics::<U3, A::Dof>::new(t.mass_matrix, linear, &jdq, &t.bias, &t.gravity)
}
