//! Velocity kinematics (chapter 5) for any [`Arm`]: the analytic Jacobian for ZYZ Euler
//! angles, the Jacobian of any point on any link, `J̇(q, q̇)`, the kinematic Hessian
//! `∂J/∂q`, manipulability (and its gradient) and condition number, singularity tests by SVD, the decoupled singularity conditions of spherical-wrist
//! arms, and inverse velocity and acceleration with a damped pseudo-inverse near
//! singularities.
//!
//! Everything works from [`Arm::jacobian`], so it is the same code for generated modules and
//! the runtime `dhgen::Robot`, and allocates nothing for generated robots
//! (`Dof = Const<N>`): the SVD here ([`JacobianSvd`]) is a one-sided Jacobi SVD on the six
//! rows of J, in place in a copy of J.
//!
//! ```
//! use dhgen::nalgebra::{SVector, Vector6};
//! use dhgen::velocity::{Damping, JacobianSvd, inverse_velocity};
//! use dhgen::Arm;
//! dhgen::robot!(mod puma = "../../robots/puma560.toml");
//!
//! let q = SVector::<f64, 6>::new(0.1, -0.5, 0.3, 0.2, 0.8, -0.4);
//! let j = puma::Robot.jacobian(&q);
//! let svd = JacobianSvd::new(&j);
//! assert!(svd.min_singular_value() > 1e-3 && svd.manipulability() > 0.0);
//!
//! // Joint rates for a desired twist [v; ω], exact away from singularities.
//! let xi = Vector6::new(0.1, 0.0, -0.05, 0.0, 0.2, 0.0);
//! let qd = inverse_velocity(&puma::Robot, &q, &xi, None, &Damping::default());
//! assert!((j * qd - xi).norm() < 1e-12);
//!
//! // The velocity-product term of the tool acceleration, J̇(q, q̇) q̇.
//! let bias = puma::Robot.jdot_qdot(&q, &qd);
//! assert!(bias.iter().all(|x| x.is_finite()));
//! ```

pub use dhgen_kernel::jacobian::{
    body_jacobian_from_jacobian, body_jdot_qdot_from, jacobian_dot, jdot_qdot_from_jacobian,
};
use dhgen_kernel::jacobian::{check_len, moved_column};
use dhgen_kernel::rotation::EulerZyz;
use dhgen_kernel::{Arm, ArmAllocator};
#[cfg(not(feature = "std"))]
use nalgebra::ComplexField as _;
use nalgebra::allocator::Allocator;
use nalgebra::{
    ArrayStorage, DefaultAllocator, Dim, Matrix3, Matrix6, OMatrix, OVector, Point3, U1, U6,
    Vector3, Vector6,
};

/// The singular value decomposition `J = U Σ Vᵀ` of a 6×n Jacobian, by one-sided Jacobi
/// rotations of its rows (accurate to high relative precision, also for small singular
/// values; allocation-free for fixed n).
///
/// Singular values are sorted in decreasing order; for n < 6 the last `6 − n` are 0.
#[derive(Clone, Debug, PartialEq)]
pub struct JacobianSvd<D: Dim>
where
    DefaultAllocator: Allocator<U6, D>,
{
    sigma: Vector6<f64>,
    /// Left singular vectors, as columns.
    u: Matrix6<f64>,
    /// Row i is `σ_i v_iᵀ` (the rows of `Uᵀ J`).
    scaled_v: OMatrix<f64, U6, D>,
    n: usize,
}

impl<D: Dim> JacobianSvd<D>
where
    DefaultAllocator: Allocator<U6, D>,
{
    /// Decomposes `j`.
    pub fn new(j: &OMatrix<f64, U6, D>) -> Self {
        let mut w = j.clone();
        // Built from storage: a `DefaultAllocator: Allocator<U6, D>` bound in scope hides the
        // allocator impls that `identity()` and `from_fn` would need for 6×6.
        let mut u = Matrix6::from_array_storage(ArrayStorage(core::array::from_fn(|c| {
            core::array::from_fn(|r| if r == c { 1.0 } else { 0.0 })
        })));
        for _sweep in 0..40 {
            let mut rotated = false;
            for i in 0..6 {
                for k in (i + 1)..6 {
                    let a = w.row(i).norm_squared();
                    let b = w.row(k).norm_squared();
                    let c = w.row(i).dot(&w.row(k));
                    if c == 0.0 || c.abs() <= 1e-15 * (a * b).sqrt() {
                        continue;
                    }
                    rotated = true;
                    let zeta = (b - a) / (2.0 * c);
                    let t = zeta.signum() / (zeta.abs() + (1.0 + zeta * zeta).sqrt());
                    let cs = 1.0 / (1.0 + t * t).sqrt();
                    let sn = cs * t;
                    for col in 0..w.ncols() {
                        let (x, y) = (w[(i, col)], w[(k, col)]);
                        w[(i, col)] = cs * x - sn * y;
                        w[(k, col)] = sn * x + cs * y;
                    }
                    for row in 0..6 {
                        let (x, y) = (u[(row, i)], u[(row, k)]);
                        u[(row, i)] = cs * x - sn * y;
                        u[(row, k)] = sn * x + cs * y;
                    }
                }
            }
            if !rotated {
                break;
            }
        }
        let norm = |i: usize| w.row(i).norm();
        let mut sigma = Vector6::new(norm(0), norm(1), norm(2), norm(3), norm(4), norm(5));
        // Sort decreasing, permuting rows of w and columns of u alike.
        for i in 0..6 {
            let best = (i..6)
                .max_by(|&a, &b| {
                    sigma[a]
                        .partial_cmp(&sigma[b])
                        .unwrap_or(core::cmp::Ordering::Equal)
                })
                .unwrap_or(i);
            if best != i {
                sigma.swap_rows(i, best);
                w.swap_rows(i, best);
                u.swap_columns(i, best);
            }
        }
        JacobianSvd {
            sigma,
            u,
            scaled_v: w,
            n: j.ncols(),
        }
    }

    /// The singular values σ1 ≥ … ≥ σ6.
    pub fn singular_values(&self) -> Vector6<f64> {
        self.sigma
    }

    /// The left singular vectors (columns), in the order of the singular values.
    pub fn u(&self) -> &Matrix6<f64> {
        &self.u
    }

    /// Number of singular values that can be non-zero: `min(6, n)`.
    pub fn rank_bound(&self) -> usize {
        self.n.min(6)
    }

    /// The smallest of the `min(6, n)` singular values: 0 exactly at a singularity.
    pub fn min_singular_value(&self) -> f64 {
        match self.rank_bound() {
            0 => 0.0,
            r => self.sigma[r - 1],
        }
    }

    /// Number of singular values above `tolerance`.
    pub fn rank(&self, tolerance: f64) -> usize {
        self.sigma.iter().filter(|&&s| s > tolerance).count()
    }

    /// Yoshikawa's manipulability `√det(J Jᵀ) = σ1 ⋯ σ6` for n ≥ 6; for n < 6 the product of
    /// the n singular values, `√det(Jᵀ J)` (`J Jᵀ` is then always singular).
    pub fn manipulability(&self) -> f64 {
        self.sigma.iter().take(self.rank_bound()).product()
    }

    /// The condition number `σ_max / σ_min` over the `min(6, n)` singular values; infinite at
    /// a singularity.
    pub fn condition_number(&self) -> f64 {
        let min = self.min_singular_value();
        if min == 0.0 {
            f64::INFINITY
        } else {
            self.sigma[0] / min
        }
    }

    /// Singular values at most this fraction of σ1 count as zero in the undamped
    /// pseudo-inverse and the null-space projector.
    const CUTOFF: f64 = 1e-12;

    fn cutoff(&self) -> f64 {
        Self::CUTOFF * self.sigma[0]
    }

    /// `J⁺_λ ξ = Σ σ_i/(σ_i² + λ²) v_i (u_i · ξ)`: the damped least-squares inverse
    /// `Jᵀ (J Jᵀ + λ² I)⁻¹ ξ`; for λ = 0 the Moore–Penrose pseudo-inverse (singular values
    /// below 1e-12 σ1 dropped).
    pub fn solve(&self, xi: &Vector6<f64>, lambda: f64) -> OVector<f64, D>
    where
        DefaultAllocator: Allocator<D>,
    {
        let mut out = OVector::<f64, D>::zeros_generic(self.scaled_v.shape_generic().1, U1);
        let cutoff = self.cutoff();
        for i in 0..6 {
            let s = self.sigma[i];
            if s <= cutoff || s == 0.0 {
                continue;
            }
            let factor = self.u.column(i).dot(xi) / (s * s + lambda * lambda);
            for c in 0..self.n {
                out[c] += factor * self.scaled_v[(i, c)];
            }
        }
        out
    }

    /// `(I − J⁺J) b`: the part of `b` in the null space of J (joint motions that do not move
    /// the tool).
    pub fn null_space_projection(&self, b: &OVector<f64, D>) -> OVector<f64, D>
    where
        DefaultAllocator: Allocator<D>,
    {
        let mut out = b.clone();
        let cutoff = self.cutoff();
        for i in 0..6 {
            let s = self.sigma[i];
            if s <= cutoff || s == 0.0 {
                continue;
            }
            let factor = (0..self.n)
                .map(|c| self.scaled_v[(i, c)] * b[c])
                .sum::<f64>()
                / (s * s);
            for c in 0..self.n {
                out[c] -= factor * self.scaled_v[(i, c)];
            }
        }
        out
    }

    /// The (damped, for λ > 0) pseudo-inverse as an n×6 matrix.
    pub fn pseudo_inverse(&self, lambda: f64) -> OMatrix<f64, D, U6>
    where
        DefaultAllocator: Allocator<D, U6>,
    {
        let cols = self.scaled_v.shape_generic().1;
        let mut out = OMatrix::<f64, D, U6>::zeros_generic(cols, U6);
        let cutoff = self.cutoff();
        for i in 0..6 {
            let s = self.sigma[i];
            if s <= cutoff || s == 0.0 {
                continue;
            }
            let factor = 1.0 / (s * s + lambda * lambda);
            for c in 0..self.n {
                for r in 0..6 {
                    out[(c, r)] += factor * self.scaled_v[(i, c)] * self.u[(r, i)];
                }
            }
        }
        out
    }
}

/// True when the smallest of the `min(6, n)` singular values of `j` is below `threshold`.
pub fn is_singular<D: Dim>(j: &OMatrix<f64, U6, D>, threshold: f64) -> bool
where
    DefaultAllocator: Allocator<U6, D>,
{
    JacobianSvd::new(j).min_singular_value() < threshold
}

/// Yoshikawa's manipulability of `j`; see [`JacobianSvd::manipulability`].
pub fn manipulability<D: Dim>(j: &OMatrix<f64, U6, D>) -> f64
where
    DefaultAllocator: Allocator<U6, D>,
{
    JacobianSvd::new(j).manipulability()
}

/// The condition number of `j`; see [`JacobianSvd::condition_number`].
pub fn condition_number<D: Dim>(j: &OMatrix<f64, U6, D>) -> f64
where
    DefaultAllocator: Allocator<U6, D>,
{
    JacobianSvd::new(j).condition_number()
}

/// The kinematic Hessian of `j`, the world-axes Jacobian of [`Arm::jacobian`]: item k is
/// `∂J/∂q_k`, a 6×n matrix (Pinocchio's `getKinematicHessian` in `LOCAL_WORLD_ALIGNED`, the
/// Robotics Toolbox's `hessian0(q)[k]`). Second-order inverse kinematics, the gradient of
/// manipulability ([`manipulability_gradient`]) and `J̇ = Σ_k ∂J/∂q_k q̇_k` are built on it.
///
/// It is a function of J alone. Write column i of J as `[v_i; ω_i]` (ω_i = 0 for a prismatic
/// joint). Moving joint k turns (or shifts) everything after it rigidly, and moves the tool
/// origin by `v_k`; so column i changes by
/// - `[ω_k × v_i; ω_k × ω_i]` for k ≤ i (joint i's axis and the tool turn together about
///   axis k, or shift together along a prismatic axis k, which changes nothing), and
/// - `[ω_i × v_k; 0]` for k > i (only the tool origin moves, and `v_i = ω_i × (p − o_i)`).
///
/// The linear rows are the Hessian of the tool position, so `∂v_i/∂q_k = ∂v_k/∂q_i`.
/// Allocation-free for generated robots; each item costs O(n).
///
/// ```
/// use dhgen::nalgebra::{Matrix6, SVector};
/// use dhgen::velocity::{jacobian_dot, kinematic_hessian};
/// use dhgen::Arm;
/// dhgen::robot!(mod puma = "../../robots/puma560.toml");
///
/// let q = SVector::<f64, 6>::new(0.2, -0.3, 0.4, 0.5, 0.6, 0.7);
/// let j = puma::Robot.jacobian(&q);
/// let h = 1e-6;
/// let dq = SVector::<f64, 6>::new(0.0, 0.0, h, 0.0, 0.0, 0.0);
/// let fd = (puma::Robot.jacobian(&(q + dq)) - puma::Robot.jacobian(&(q - dq))) / (2.0 * h);
/// let d2 = kinematic_hessian(&j).nth(2).unwrap(); // ∂J/∂q_3
/// assert!((d2 - fd).abs().max() < 1e-8);
///
/// // J̇ along q̇ is the Hessian contracted with q̇.
/// let qd = SVector::<f64, 6>::new(0.5, -0.1, 0.3, 0.0, 0.2, -0.4);
/// let jdot: Matrix6<f64> = kinematic_hessian(&j).zip(qd.iter()).map(|(hk, &v)| hk * v).sum();
/// assert!((jdot - jacobian_dot(&puma::Robot, &q, &qd)).abs().max() < 1e-12);
/// ```
#[doc(alias = "hessian0")]
#[doc(alias = "getKinematicHessian")]
pub fn kinematic_hessian<D: Dim>(
    j: &OMatrix<f64, U6, D>,
) -> impl ExactSizeIterator<Item = OMatrix<f64, U6, D>> + '_
where
    DefaultAllocator: Allocator<U6, D>,
{
    let part = |j: &OMatrix<f64, U6, D>, c: usize, row: usize| {
        Vector3::new(j[(row, c)], j[(row + 1, c)], j[(row + 2, c)])
    };
    (0..j.ncols()).map(move |k| {
        let (vk, wk) = (part(j, k, 0), part(j, k, 3));
        let mut out = OMatrix::<f64, U6, D>::zeros_generic(U6, j.shape_generic().1);
        for i in 0..j.ncols() {
            let (dv, dw) = hessian_column(k <= i, (vk, wk), (part(j, i, 0), part(j, i, 3)));
            out.fixed_view_mut::<3, 1>(0, i).copy_from(&dv);
            out.fixed_view_mut::<3, 1>(3, i).copy_from(&dw);
        }
        out
    })
}

/// Column i of `∂J/∂q_k` from columns k and i of J, `(v, ω)` each; `after` when k ≤ i.
/// Outside the generic bound (nalgebra's inference would take `Allocator<U6, D>` for the
/// cross product's).
fn hessian_column(
    after: bool,
    (vk, wk): (Vector3<f64>, Vector3<f64>),
    (vi, wi): (Vector3<f64>, Vector3<f64>),
) -> (Vector3<f64>, Vector3<f64>) {
    if after {
        (wk.cross(&vi), wk.cross(&wi))
    } else {
        (wi.cross(&vk), Vector3::zeros())
    }
}

/// `∂(J q̇)/∂q`: how the tool's velocity `[v; ω]` (world axes, at the tool origin) changes with
/// q at a fixed joint velocity q̇; column k is `(∂J/∂q_k) q̇` ([`kinematic_hessian`]): the
/// linearisation of a Cartesian velocity constraint or cost for model-predictive control.
/// Contracted with q̇ it gives `J̇ q̇` ([`Arm::jdot_qdot`]). With Pinocchio one assembles it
/// from `getFrameVelocityDerivatives` in `LOCAL`, `R ∂v_b/∂q_k + ω_k × (R v_b)` for both halves
/// (its issue #1256); its `LOCAL_WORLD_ALIGNED` derivative is another quantity, not the
/// partial derivative of the world-axes velocity.
///
/// # Panics
/// If `qd` does not have one entry per column of `j` (only possible on the runtime path).
pub fn tool_velocity_partial<D: Dim>(
    j: &OMatrix<f64, U6, D>,
    qd: &OVector<f64, D>,
) -> OMatrix<f64, U6, D>
where
    DefaultAllocator: Allocator<U6, D> + Allocator<D>,
{
    check_len("tool_velocity_partial", "qd", qd.len(), j.ncols());
    let mut out = OMatrix::<f64, U6, D>::zeros_generic(U6, j.shape_generic().1);
    for (k, hk) in kinematic_hessian(j).enumerate() {
        out.set_column(k, &(hk * qd));
    }
    out
}

/// The rows of the Jacobian a manipulability measure reads (the Robotics Toolbox's `axes`):
/// all six, the three of the tool's linear velocity, or the three of its angular velocity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axes {
    /// `[v; ω]`: rows 0 to 5.
    All,
    /// `v`: rows 0 to 2.
    Translation,
    /// `ω`: rows 3 to 5.
    Rotation,
}

impl Axes {
    fn rows(self) -> core::ops::Range<usize> {
        match self {
            Axes::All => 0..6,
            Axes::Translation => 0..3,
            Axes::Rotation => 3..6,
        }
    }
}

/// Yoshikawa's manipulability `m` of the rows `axes` of `j` (the world-axes Jacobian of
/// [`Arm::jacobian`]) and its gradient `∂m/∂q` (the Robotics Toolbox's `jacobm`): the
/// secondary task that steers a redundant arm away from singularities (q̇ = J⁺ξ +
/// (I − J⁺J) k ∂m/∂q, or a cost term of a quadratic-programming controller).
///
/// With J_a the selected rows and r = min(rows, n), m is the product of J_a's r largest
/// singular values (`√det(J_a J_aᵀ)` when n ≥ rows; for `Axes::All`, [`manipulability`]), and
/// `∂m/∂q_k = m ⟨(J_a⁺)ᵀ, ∂J_a/∂q_k⟩`, the Frobenius product with the pseudo-inverse from the
/// SVD and the [`kinematic_hessian`]. `None` where J_a has lost rank (a singular value below
/// 1e-12 of the largest): m is then 0 and not differentiable, as |x| is not at 0.
///
/// ```
/// use dhgen::nalgebra::SVector;
/// use dhgen::velocity::{manipulability, manipulability_gradient, Axes};
/// use dhgen::Arm;
/// dhgen::robot!(mod puma = "../../robots/puma560.toml");
///
/// let q = SVector::<f64, 6>::new(0.2, -0.3, 0.4, 0.5, 0.6, 0.7);
/// let j = puma::Robot.jacobian(&q);
/// let (m, grad) = manipulability_gradient(&j, Axes::All).unwrap();
/// assert_eq!(m, manipulability(&j));
/// let (h, dq) = (1e-6, SVector::<f64, 6>::new(0.0, 0.0, 0.0, 0.0, 1.0, 0.0));
/// let m_at = |q: SVector<f64, 6>| manipulability(&puma::Robot.jacobian(&q));
/// assert!((grad[4] - (m_at(q + dq * h) - m_at(q - dq * h)) / (2.0 * h)).abs() < 1e-8);
///
/// // At the wrist singularity (q5 = 0) J has lost rank: m = 0 has no gradient.
/// let q = SVector::<f64, 6>::new(0.2, -0.3, 0.4, 0.5, 0.0, 0.7);
/// assert!(manipulability_gradient(&puma::Robot.jacobian(&q), Axes::All).is_none());
/// ```
#[doc(alias = "jacobm")]
pub fn manipulability_gradient<D: Dim>(
    j: &OMatrix<f64, U6, D>,
    axes: Axes,
) -> Option<(f64, OVector<f64, D>)>
where
    DefaultAllocator: Allocator<U6, D> + Allocator<D>,
{
    let rows = axes.rows();
    let mut selected = j.clone();
    for r in (0..6).filter(|r| !rows.contains(r)) {
        selected.row_mut(r).fill(0.0);
    }
    let svd = JacobianSvd::new(&selected);
    let count = rows.len().min(j.ncols());
    let sigma = &svd.sigma;
    if count == 0 || sigma[count - 1] <= svd.cutoff() || sigma[count - 1] == 0.0 {
        return None;
    }
    let m: f64 = sigma.iter().take(count).product();
    // (J_a⁺)ᵀ = Σ_i u_i v_iᵀ / σ_i, with row i of `scaled_v` σ_i v_iᵀ. Its rows outside `axes`
    // are zero, so the full Hessian may stand for J_a's.
    let mut w = OMatrix::<f64, U6, D>::zeros_generic(U6, j.shape_generic().1);
    for i in 0..count {
        let factor = 1.0 / (sigma[i] * sigma[i]);
        for c in 0..j.ncols() {
            for r in 0..6 {
                w[(r, c)] += factor * svd.u[(r, i)] * svd.scaled_v[(i, c)];
            }
        }
    }
    let mut grad = OVector::<f64, D>::zeros_generic(j.shape_generic().1, U1);
    for (k, hk) in kinematic_hessian(j).enumerate() {
        grad[k] = m * w.dot(&hk);
    }
    Some((m, grad))
}

/// How the pseudo-inverse is damped near singularities (Nakamura & Hanafusa): no damping
/// while the smallest singular value σ is at least `threshold`, so that `J q̇ = ξ` holds
/// exactly there; below it `λ² = max_damping² (1 − (σ/threshold)²)`, which keeps
/// `|q̇| ≤ |ξ| / min(threshold, 2 λ)`-like bounds instead of growing as 1/σ.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Damping {
    /// The singular value below which damping starts. Default 0.01.
    pub threshold: f64,
    /// The damping λ at σ = 0. Default 0.05.
    pub max_damping: f64,
}

impl Default for Damping {
    fn default() -> Self {
        Damping {
            threshold: 1e-2,
            max_damping: 5e-2,
        }
    }
}

impl Damping {
    /// No damping at all (the Moore–Penrose pseudo-inverse everywhere).
    pub const NONE: Damping = Damping {
        threshold: 0.0,
        max_damping: 0.0,
    };

    /// λ for a smallest singular value `sigma_min`.
    pub fn lambda(&self, sigma_min: f64) -> f64 {
        if sigma_min >= self.threshold || self.threshold <= 0.0 {
            0.0
        } else {
            let r = sigma_min / self.threshold;
            self.max_damping * (1.0 - r * r).sqrt()
        }
    }
}

/// Inverse velocity (section 5.7): `q̇ = J⁺ ξ + (I − J⁺ J) b` for the twist `ξ = [v; ω]` of
/// the tool (world axes), with J⁺ damped per `damping` near singularities. `null` is `b`, a
/// joint motion projected onto the null space (redundant arms); `None` for `b = 0`, the
/// least-norm joint rates.
///
/// # Panics
/// If `q` or `null` does not have one entry per joint (only possible on the runtime path).
pub fn inverse_velocity<A: Arm>(
    arm: &A,
    q: &OVector<f64, A::Dof>,
    xi: &Vector6<f64>,
    null: Option<&OVector<f64, A::Dof>>,
    damping: &Damping,
) -> OVector<f64, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    if let Some(b) = null {
        check_len("inverse_velocity", "null", b.len(), arm.dof());
    }
    let svd = JacobianSvd::new(&arm.jacobian(q));
    let lambda = damping.lambda(svd.min_singular_value());
    let mut qd = svd.solve(xi, lambda);
    if let Some(b) = null {
        qd += svd.null_space_projection(b);
    }
    qd
}

/// Inverse acceleration (section 5.7): `q̈ = J⁺ (ẍ − J̇ q̇) + (I − J⁺ J) b` for the tool
/// acceleration `ẍ = [a; α]` (linear acceleration of the tool origin and angular
/// acceleration, world axes), with [`Arm::jdot_qdot`] for `J̇ q̇` and J⁺ damped per `damping`.
///
/// # Panics
/// If `q`, `qd` or `null` does not have one entry per joint (only possible on the runtime
/// path).
pub fn inverse_acceleration<A: Arm>(
    arm: &A,
    q: &OVector<f64, A::Dof>,
    qd: &OVector<f64, A::Dof>,
    xdd: &Vector6<f64>,
    null: Option<&OVector<f64, A::Dof>>,
    damping: &Damping,
) -> OVector<f64, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    check_len("inverse_acceleration", "qd", qd.len(), arm.dof());
    if let Some(b) = null {
        check_len("inverse_acceleration", "null", b.len(), arm.dof());
    }
    let j = arm.jacobian(q);
    let bias = jdot_qdot_from_jacobian(arm, &j, qd);
    let svd = JacobianSvd::new(&j);
    let lambda = damping.lambda(svd.min_singular_value());
    let mut qdd = svd.solve(&(xdd - bias), lambda);
    if let Some(b) = null {
        qdd += svd.null_space_projection(b);
    }
    qdd
}

/// The geometric Jacobian of a point `p` (world coordinates) that moves with link `link`
/// (1 to n: the link joint `link` moves, whose frame is `frames()[link − 1]`; 0: the base),
/// rows `[v; ω]` as [`Arm::jacobian`]'s: column j ≤ `link` is `[z_j × (p − o_j); z_j]` for a
/// revolute joint and `[z_j; 0]` for a prismatic one, the columns of the joints after the
/// link are zero. What Pinocchio's `getFrameJacobian` (`LOCAL_WORLD_ALIGNED`) gives for a frame
/// on any body and Robotics Toolbox's `jacob0(q, end=...)`: for control points along the arm
/// (collision avoidance, whole-arm contact). Taken from the tool's Jacobian and pose, since
/// column j of any point differs from the tool's by `z_j × (p − p_tool)`; allocation-free for
/// generated robots. `None` if `link` is above n.
///
/// ```
/// use dhgen::nalgebra::{Point3, SVector};
/// use dhgen::velocity::point_jacobian;
/// use dhgen::Arm;
/// dhgen::robot!(mod puma = "../../robots/puma560.toml");
///
/// // A point 10 cm along link 3's x axis, and how it moves.
/// let q = SVector::<f64, 6>::new(0.2, -0.3, 0.4, 0.5, 0.6, 0.7);
/// let point = |q: &SVector<f64, 6>| puma::State::new(q).frames()[2] * Point3::new(0.1, 0.0, 0.0);
/// let j = point_jacobian(&puma::Robot, &q, 3, &point(&q)).unwrap();
/// let (dq, h) = (SVector::<f64, 6>::new(0.3, -0.2, 0.5, 1.0, 1.0, 1.0), 1e-6);
/// let v = (point(&(q + dq * h)) - point(&(q - dq * h))) / (2.0 * h);
/// assert!(((j * dq).fixed_rows::<3>(0) - v).norm() < 1e-8);
/// assert!(j.columns(3, 3).iter().all(|&x| x == 0.0)); // joints 4 to 6 do not move it
/// ```
pub fn point_jacobian<A: Arm>(
    arm: &A,
    q: &OVector<f64, A::Dof>,
    link: usize,
    p: &Point3<f64>,
) -> Option<OMatrix<f64, U6, A::Dof>>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    if link > arm.dof() {
        return None;
    }
    let mut j = arm.jacobian(q);
    let offset = p.coords - arm.fk(q).translation.vector;
    for c in 0..arm.dof() {
        if c < link {
            let v = moved_column(&j, c, &offset);
            j.fixed_view_mut::<3, 1>(0, c).copy_from(&v);
        } else {
            j.column_mut(c).fill(0.0);
        }
    }
    Some(j)
}

/// `B(α)` of the ZYZ Euler angles `α = (φ, θ, ψ)` (`R = Rz(φ) Ry(θ) Rz(ψ)`): `ω = B(α) α̇`,
/// with rows `(0, −s_φ, c_φ s_θ)`, `(0, c_φ, s_φ s_θ)`, `(1, 0, c_θ)` (section 5.5 with the errata in docs/references.md);
/// `det B = −s_θ`, singular at θ = 0, π.
pub fn euler_rate_matrix(e: &EulerZyz<f64>) -> Matrix3<f64> {
    let (sf, cf) = e.phi.sin_cos();
    let (st, ct) = e.theta.sin_cos();
    Matrix3::new(0.0, -sf, cf * st, 0.0, cf, sf * st, 1.0, 0.0, ct)
}

/// The analytic Jacobian of [`analytic_jacobian`] and the Euler angles it was taken at.
#[derive(Clone, Debug, PartialEq)]
pub struct AnalyticJacobian<D: Dim>
where
    DefaultAllocator: Allocator<U6, D>,
{
    /// `J_a`, rows `[ḋ; φ̇, θ̇, ψ̇]`.
    pub jacobian: OMatrix<f64, U6, D>,
    /// The ZYZ Euler angles α of the tool orientation.
    pub euler: EulerZyz<f64>,
}

/// The analytic Jacobian `J_a` for ZYZ Euler angles (section 5.5): `[ḋ; α̇] = J_a q̇`, with
/// `J = [I 0; 0 B(α)] J_a`, so `J_a = [I 0; 0 B(α)⁻¹] J`. α are the Euler angles of the tool
/// orientation, branch θ ∈ (0, π) ([`EulerZyz::from_rotation`]'s first), also returned.
/// `None` where B(α) is singular (`sin θ` below 1e-9: the tool z axis parallel to the world z
/// axis), where the Euler rates are unbounded.
///
/// ```
/// use dhgen::nalgebra::SVector;
/// use dhgen::velocity::{analytic_jacobian, euler_rate_matrix};
/// use dhgen::Arm;
/// dhgen::robot!(mod puma = "../../robots/puma560.toml");
///
/// let q = SVector::<f64, 6>::new(0.2, -0.3, 0.4, 0.5, 0.6, 0.7);
/// let a = analytic_jacobian(&puma::Robot, &q).unwrap();
/// // ω = B(α) α̇ recovers the geometric Jacobian's angular rows.
/// let j = puma::Robot.jacobian(&q);
/// let omega = euler_rate_matrix(&a.euler) * a.jacobian.fixed_view::<3, 6>(3, 0);
/// assert!((omega - j.fixed_view::<3, 6>(3, 0)).abs().max() < 1e-12);
/// ```
///
/// # Panics
/// If `q` does not have one entry per joint (only possible on the runtime path: `None` is
/// kept for the singular orientation, not for a caller's bug).
pub fn analytic_jacobian<A: Arm>(
    arm: &A,
    q: &OVector<f64, A::Dof>,
) -> Option<AnalyticJacobian<A::Dof>>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let pose = arm.fk(q);
    let [e, _] = EulerZyz::from_rotation(&pose.rotation.to_rotation_matrix());
    let (sf, cf) = e.phi.sin_cos();
    let (st, ct) = e.theta.sin_cos();
    if st.abs() < 1e-9 {
        return None;
    }
    let mut j = arm.jacobian(q);
    // B⁻¹ ω: θ̇ = −s_φ ω_x + c_φ ω_y, ψ̇ = (c_φ ω_x + s_φ ω_y)/s_θ, φ̇ = ω_z − c_θ ψ̇.
    for c in 0..arm.dof() {
        let (wx, wy, wz) = (j[(3, c)], j[(4, c)], j[(5, c)]);
        let theta_dot = -sf * wx + cf * wy;
        let psi_dot = (cf * wx + sf * wy) / st;
        let phi_dot = wz - ct * psi_dot;
        j[(3, c)] = phi_dot;
        j[(4, c)] = theta_dot;
        j[(5, c)] = psi_dot;
    }
    Some(AnalyticJacobian {
        jacobian: j,
        euler: e,
    })
}

/// The decoupled singularity conditions of a six-joint arm with a spherical wrist
/// (section 5.6.1): with J taken at the wrist centre, `J = [J11 0; J21 J22]` and
/// `det J = det J11 · det J22`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DecoupledDeterminants {
    /// `det J11`: arm singularities (zero when the wrist centre cannot move in some
    /// direction by joints 1-3). For the elbow arm of section 5.6.1.2 it is
    /// `−a2 a3 s3 (a2 c2 + a3 c23)` with J's columns in joint order (the text's sign differs;
    /// the zero set is the same).
    pub arm: f64,
    /// `det J22 = det [z3 z4 z5]`: wrist singularities, zero when axes 4 and 6 line up
    /// (θ5 = 0 or π).
    pub wrist: f64,
}

/// `det J11` and `det J22` of a six-joint arm at `q`, given the wrist centre in the tool frame
/// (e.g. `dhgen::ik::DecoupledIk::wrist_centre_in_tool`).
/// `None` unless the arm has six joints. `arm · wrist` equals `det J` (shifting J's reference
/// point does not change its determinant).
///
/// ```
/// use dhgen::ik::DecoupledIk;
/// use dhgen::nalgebra::SVector;
/// use dhgen::velocity::decoupled_determinants;
/// dhgen::robot!(mod puma = "../../robots/puma560.toml");
///
/// let centre = DecoupledIk::from_chain(puma::CHAIN).unwrap().wrist_centre_in_tool().expect("a spherical wrist");
/// // θ5 = 0: a wrist singularity, the arm part is regular.
/// let q = SVector::<f64, 6>::new(0.2, -0.3, 0.4, 0.5, 0.0, 0.7);
/// let d = decoupled_determinants(&puma::Robot, &q, &centre).unwrap();
/// assert!(d.wrist.abs() < 1e-15 && d.arm.abs() > 1e-3);
/// ```
///
/// # Panics
/// If the arm has six joints and `q` does not have six entries (only possible on the runtime
/// path: `None` is kept for an arm without six joints, not for a caller's bug).
pub fn decoupled_determinants<A: Arm>(
    arm: &A,
    q: &OVector<f64, A::Dof>,
    centre_in_tool: &Vector3<f64>,
) -> Option<DecoupledDeterminants>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    if arm.dof() != 6 {
        return None;
    }
    let pose = arm.fk(q);
    let offset = pose.rotation * centre_in_tool; // c − p
    let j = arm.jacobian(q);
    // Linear velocity of the wrist centre: v_c = v_p + ω × (c − p).
    let j11 = Matrix3::from_fn(|r, c| {
        let w = Vector3::new(j[(3, c)], j[(4, c)], j[(5, c)]);
        j[(r, c)] + w.cross(&offset)[r]
    });
    let j22 = Matrix3::from_fn(|r, c| j[(3 + r, 3 + c)]);
    Some(DecoupledDeterminants {
        arm: j11.determinant(),
        wrist: j22.determinant(),
    })
}
