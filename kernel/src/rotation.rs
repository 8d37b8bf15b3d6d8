//! Parametrisations of rotations (section 3.5) on nalgebra's types: only what nalgebra
//! lacks.
//!
//! # What nalgebra already has
//! | concept | nalgebra |
//! |---|---|
//! | basic rotations `R_{x,θ}`, `R_{y,θ}`, `R_{z,θ}` | `Rotation3::from_axis_angle(&Vector3::x_axis(), θ)` (and `y_axis`, `z_axis`) |
//! | skew-symmetric `S(a)` (section 5.1) | [`Vector3::cross_matrix`](nalgebra::Vector3::cross_matrix); [`vee`] is its inverse |
//! | roll-pitch-yaw to a rotation (section 3.5.2) | `Rotation3::from_euler_angles(roll, pitch, yaw)` = `Rz(yaw) Ry(pitch) Rx(roll)`, the text's `R_XYZ = R_{z,φ} R_{y,θ} R_{x,ψ}` with ψ = roll, θ = pitch, φ = yaw |
//! | a rotation to roll-pitch-yaw | `Rotation3::euler_angles()`: one branch, pitch by `asin` (loses about half the digits near pitch = ±π/2); [`Rpy::from_rotation`] gives both branches and stays accurate there |
//! | axis-angle to a rotation (Rodrigues) | `Rotation3::from_axis_angle(&axis, θ)`, `Rotation3::new(k θ)` |
//! | a rotation to axis-angle | `Rotation3::axis_angle()`: `None` at θ = 0 **and at θ = π**, angle by `acos`; `UnitQuaternion::from_rotation_matrix(r).scaled_axis()` is accurate; [`axis_angle`] and [`rotation_vector`] work on the matrix directly, with θ = 0 and θ = π defined |
//! | quaternions, composition, inverse | `UnitQuaternion`, `Rotation3 * Rotation3`, `inverse()` |
//! | ZYZ Euler angles | `Rotation3::euler_angles_ordered([z, y, z], false)` gives one branch and panics on non-orthonormal axes; [`EulerZyz`] gives both branches (section 3.5.1) with a documented choice at θ = 0 and θ = π |
//!
//! Every function here takes `atan2` in Rust's order, `y.atan2(x)`: the text's `atan2(x, y)`
//! is `y.atan2(x)` (see the errata in docs/references.md).
//!
//! ```
//! use dhgen::nalgebra::{Rotation3, Vector3};
//! use dhgen::rotation::{EulerZyz, Rpy, axis_angle};
//!
//! let r = Rotation3::<f64>::from_euler_angles(0.3, -0.2, 1.1);
//! // ZYZ Euler angles: two branches, both give back r.
//! for e in EulerZyz::from_rotation(&r) {
//!     assert!((e.to_rotation().matrix() - r.matrix()).abs().max() < 1e-14);
//! }
//! // Roll-pitch-yaw: the first branch is nalgebra's convention (|pitch| ≤ π/2).
//! let [rpy, _] = Rpy::from_rotation(&r);
//! assert!((rpy.roll - 0.3).abs() < 1e-14 && (rpy.yaw - 1.1).abs() < 1e-14);
//! // Axis-angle, defined at θ = π too.
//! let half_turn = Rotation3::from_axis_angle(&Vector3::y_axis(), std::f64::consts::PI);
//! let (axis, theta) = axis_angle(&half_turn);
//! assert!((theta - std::f64::consts::PI).abs() < 1e-15 && (axis.y - 1.0).abs() < 1e-15);
//! ```

use nalgebra::{Matrix3, RealField, Rotation3, Unit, Vector3};

/// Below this `sin θ` (ZYZ) or `cos(pitch)` (roll-pitch-yaw) a parametrisation is treated as
/// singular: only the sum or the difference of the outer angles is determined, and the
/// documented choice is made. Treating the rotation as exactly singular there changes it by
/// at most this much.
pub const SINGULAR_EPS: f64 = 1e-12;

fn c<T: RealField>(x: f64) -> T {
    nalgebra::convert(x)
}

/// Wraps an angle into (−π, π]; NaN for a NaN or infinite angle.
///
/// The remainder is exact (`x % 2π`, as `fmod`), so a huge angle such as 1e17 rad still lands
/// in (−π, π]; a subtraction of a rounded multiple of 2π would leave up to `ulp(x)` over.
pub fn wrap_angle<T: RealField + Copy>(x: T) -> T {
    let two_pi = T::two_pi();
    let mut y = x % two_pi;
    if y <= -T::pi() {
        y += two_pi;
    } else if y > T::pi() {
        y -= two_pi;
    }
    y
}

/// The inverse of `S(a)` ([`Vector3::cross_matrix`]): the vector of the skew-symmetric part of
/// `m`, `vee(S(a)) = a`. For a non-skew `m` it returns `vee((m − mᵀ)/2)`.
pub fn vee<T: RealField + Copy>(m: &Matrix3<T>) -> Vector3<T> {
    let half = c::<T>(0.5);
    Vector3::new(
        (m[(2, 1)] - m[(1, 2)]) * half,
        (m[(0, 2)] - m[(2, 0)]) * half,
        (m[(1, 0)] - m[(0, 1)]) * half,
    )
}

/// ZYZ Euler angles `(φ, θ, ψ)` (section 3.5.1): `R = R_{z,φ} R_{y,θ} R_{z,ψ}`, rotations
/// about the current axes z, y, z.
///
/// This is the convention of section 3.5.1 and of the whole library (section 5.5 of the text
/// names the angles the other way round; see the errata in docs/references.md).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EulerZyz<T> {
    /// φ: first rotation, about z.
    pub phi: T,
    /// θ: second rotation, about the current y.
    pub theta: T,
    /// ψ: third rotation, about the current z.
    pub psi: T,
}

impl<T: RealField + Copy> EulerZyz<T> {
    /// The angles `(φ, θ, ψ)`.
    pub fn new(phi: T, theta: T, psi: T) -> Self {
        EulerZyz { phi, theta, psi }
    }

    /// The angles as a vector `[φ, θ, ψ]`.
    pub fn to_vector(&self) -> Vector3<T> {
        Vector3::new(self.phi, self.theta, self.psi)
    }

    /// The rotation `R_{z,φ} R_{y,θ} R_{z,ψ}`, equation (5) of the text.
    pub fn to_rotation(&self) -> Rotation3<T> {
        let (sf, cf) = self.phi.sin_cos();
        let (st, ct) = self.theta.sin_cos();
        let (ss, cs) = self.psi.sin_cos();
        Rotation3::from_matrix_unchecked(Matrix3::new(
            cf * ct * cs - sf * ss,
            -cf * ct * ss - sf * cs,
            cf * st,
            sf * ct * cs + cf * ss,
            -sf * ct * ss + cf * cs,
            sf * st,
            -st * cs,
            st * ss,
            ct,
        ))
    }

    /// True inside the singular band `|sin θ| < SINGULAR_EPS` (θ = 0 or π), where only
    /// `φ + ψ` or `φ − ψ` is determined.
    pub fn is_singular(&self) -> bool {
        self.theta.sin().abs() < c(SINGULAR_EPS)
    }

    /// Both sets of ZYZ angles of `r`: `[θ ∈ [0, π] branch, θ ∈ [−π, 0] branch]`, all angles in
    /// (−π, π]. The second is `(φ + π, −θ, ψ + π)`.
    ///
    /// # Singular cases
    /// When `sin θ < SINGULAR_EPS` (r13 = r23 = 0) only `φ + ψ` (θ = 0) or `φ − ψ` (θ = π) is
    /// determined. The choice made is **ψ = 0**: θ = 0 gives `(atan2(r21, r11), 0, 0)` and
    /// θ = π gives `(atan2(−r12, −r11), π, 0)`; both entries of the array are then equal.
    ///
    /// # Accuracy
    /// θ comes from `atan2(√(r13² + r23²), r33)`, accurate at every angle (an `acos` would lose
    /// half the digits near 0 and π). Near θ = 0 the individual angles `atan2(r23, r13)`,
    /// `atan2(r32, −r31)` are ill-conditioned but their sum is not: the sum is taken from
    /// `atan2(r21 − r12, r11 + r22)` (and near θ = π the difference from
    /// `atan2(−(r12 + r21), r22 − r11)`), so the result reproduces `r` to rounding error even
    /// just outside the singular band.
    pub fn from_rotation(r: &Rotation3<T>) -> [EulerZyz<T>; 2] {
        let m = r.matrix();
        let (r11, r12, r13) = (m[(0, 0)], m[(0, 1)], m[(0, 2)]);
        let (r21, r22, r23) = (m[(1, 0)], m[(1, 1)], m[(1, 2)]);
        let (r31, r32, r33) = (m[(2, 0)], m[(2, 1)], m[(2, 2)]);
        let s_theta = (r13 * r13 + r23 * r23).sqrt();
        let first = if s_theta < c(SINGULAR_EPS) {
            if r33 > T::zero() {
                EulerZyz::new(r21.atan2(r11), T::zero(), T::zero())
            } else {
                EulerZyz::new((-r12).atan2(-r11), T::pi(), T::zero())
            }
        } else {
            let theta = s_theta.atan2(r33);
            let phi = r23.atan2(r13);
            let psi = r32.atan2(-r31);
            let half = c::<T>(0.5);
            if r33 >= T::zero() {
                // (1 + cos θ) (cos(φ+ψ), sin(φ+ψ)) = (r11 + r22, r21 − r12).
                let sum = (r21 - r12).atan2(r11 + r22);
                let fix = wrap_angle(sum - (phi + psi)) * half;
                EulerZyz::new(wrap_angle(phi + fix), theta, wrap_angle(psi + fix))
            } else {
                // (1 − cos θ) (cos(φ−ψ), sin(φ−ψ)) = (r22 − r11, −(r12 + r21)).
                let diff = (-(r12 + r21)).atan2(r22 - r11);
                let fix = wrap_angle(diff - (phi - psi)) * half;
                EulerZyz::new(wrap_angle(phi + fix), theta, wrap_angle(psi - fix))
            }
        };
        let second = if s_theta < c(SINGULAR_EPS) {
            first
        } else {
            EulerZyz::new(
                wrap_angle(first.phi + T::pi()),
                -first.theta,
                wrap_angle(first.psi + T::pi()),
            )
        };
        [first, second]
    }
}

/// Roll-pitch-yaw angles (section 3.5.2): rotations about the **fixed** x, y, z axes in that
/// order, `R = R_{z,yaw} R_{y,pitch} R_{x,roll}`.
///
/// The text writes `R_XYZ = R_{z,φ} R_{y,θ} R_{x,ψ}` with ψ = roll, θ = pitch, φ = yaw. This is
/// nalgebra's convention (`Rotation3::from_euler_angles(roll, pitch, yaw)`,
/// `Rotation3::euler_angles() -> (roll, pitch, yaw)`) and URDF's `rpy`, the one the robot
/// description uses for `base` and `tool`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rpy<T> {
    /// Rotation about the fixed x axis (ψ in the text), applied first.
    pub roll: T,
    /// Rotation about the fixed y axis (θ).
    pub pitch: T,
    /// Rotation about the fixed z axis (φ), applied last.
    pub yaw: T,
}

impl<T: RealField + Copy> Rpy<T> {
    /// The angles `(roll, pitch, yaw)`.
    pub fn new(roll: T, pitch: T, yaw: T) -> Self {
        Rpy { roll, pitch, yaw }
    }

    /// The rotation `R_{z,yaw} R_{y,pitch} R_{x,roll}`; the same matrix as
    /// `Rotation3::from_euler_angles(roll, pitch, yaw)`.
    pub fn to_rotation(&self) -> Rotation3<T> {
        Rotation3::from_euler_angles(self.roll, self.pitch, self.yaw)
    }

    /// Both sets of roll-pitch-yaw angles of `r`: `[|pitch| ≤ π/2 branch (nalgebra's),
    /// |pitch| ≥ π/2 branch]`, all angles in (−π, π]. The second is
    /// `(roll + π, π − pitch, yaw + π)`.
    ///
    /// # Singular cases
    /// When `cos(pitch) < SINGULAR_EPS` (pitch = ±π/2, r11 = r21 = 0) only `roll − yaw`
    /// (pitch = π/2) or `roll + yaw` (pitch = −π/2) is determined. The choice made is
    /// **yaw = 0**, as nalgebra's `euler_angles`: `(atan2(r12, r22), π/2, 0)` or
    /// `(atan2(−r12, r22), −π/2, 0)`; both entries are then equal.
    ///
    /// # Accuracy
    /// Pitch is `atan2(−r31, √(r11² + r21²))`, accurate near ±π/2 where `asin` is not; as in
    /// [`EulerZyz::from_rotation`] the well-conditioned combination of roll and yaw
    /// (`roll − yaw = atan2(r12 − r23, r22 + r13)` for pitch ≥ 0,
    /// `roll + yaw = atan2(−(r12 + r23), r22 − r13)` for pitch < 0) corrects the individual
    /// angles near the singularity.
    pub fn from_rotation(r: &Rotation3<T>) -> [Rpy<T>; 2] {
        let m = r.matrix();
        let (r11, r12, r13) = (m[(0, 0)], m[(0, 1)], m[(0, 2)]);
        let (r21, r22, r23) = (m[(1, 0)], m[(1, 1)], m[(1, 2)]);
        let (r31, r32, r33) = (m[(2, 0)], m[(2, 1)], m[(2, 2)]);
        let c_pitch = (r11 * r11 + r21 * r21).sqrt();
        let first = if c_pitch < c(SINGULAR_EPS) {
            if r31 < T::zero() {
                Rpy::new(r12.atan2(r22), T::frac_pi_2(), T::zero())
            } else {
                Rpy::new((-r12).atan2(r22), -T::frac_pi_2(), T::zero())
            }
        } else {
            let pitch = (-r31).atan2(c_pitch);
            let roll = r32.atan2(r33);
            let yaw = r21.atan2(r11);
            let half = c::<T>(0.5);
            if r31 <= T::zero() {
                // (1 + sin p) (cos(roll−yaw), sin(roll−yaw)) = (r22 + r13, r12 − r23).
                let diff = (r12 - r23).atan2(r22 + r13);
                let fix = wrap_angle(diff - (roll - yaw)) * half;
                Rpy::new(wrap_angle(roll + fix), pitch, wrap_angle(yaw - fix))
            } else {
                // (1 − sin p) (cos(roll+yaw), sin(roll+yaw)) = (r22 − r13, −(r12 + r23)).
                let sum = (-(r12 + r23)).atan2(r22 - r13);
                let fix = wrap_angle(sum - (roll + yaw)) * half;
                Rpy::new(wrap_angle(roll + fix), pitch, wrap_angle(yaw + fix))
            }
        };
        let second = if c_pitch < c(SINGULAR_EPS) {
            first
        } else {
            Rpy::new(
                wrap_angle(first.roll + T::pi()),
                wrap_angle(T::pi() - first.pitch),
                wrap_angle(first.yaw + T::pi()),
            )
        };
        [first, second]
    }
}

/// The equivalent axis and angle of `r` (section 3.5.3): `r = R_{k,θ}` with θ ∈ [0, π].
///
/// θ is `atan2(|vee(R − Rᵀ)| , (tr R − 1)/2)`, accurate at every angle. For θ ≤ π/2 the axis
/// is `vee(R − Rᵀ)/(2 sin θ)` (the errata's formula); for θ > π/2, where that quotient loses
/// accuracy and is 0/0 at θ = π, it is the largest column of
/// `k kᵀ = ((R + Rᵀ)/2 − cos θ I)/(1 − cos θ)`, signed by the skew part.
///
/// Choices: at θ = 0 (identity, any axis) the axis is z; at θ = π, where `k` and `−k` give the
/// same rotation, the axis is the one whose largest-magnitude component is positive.
pub fn axis_angle<T: RealField + Copy>(r: &Rotation3<T>) -> (Unit<Vector3<T>>, T) {
    let m = r.matrix();
    let w = vee(m); // sin θ · k
    let s = w.norm();
    let cos = (m.trace() - T::one()) * c::<T>(0.5);
    let theta = s.atan2(cos);
    if s == T::zero() && cos > T::zero() {
        return (Vector3::z_axis(), T::zero());
    }
    let axis = if cos >= T::zero() {
        w / s
    } else {
        let sym = (m + m.transpose()) * c::<T>(0.5);
        let kk = (sym - Matrix3::identity() * cos) / (T::one() - cos);
        let i = (0..3)
            .max_by(|&a, &b| {
                kk[(a, a)]
                    .partial_cmp(&kk[(b, b)])
                    .unwrap_or(core::cmp::Ordering::Equal)
            })
            .unwrap_or(0);
        let mut k: Vector3<T> = kk.column(i) / kk[(i, i)].sqrt();
        // Sign from the skew part (sin θ k); at θ = π, where it vanishes, by the convention.
        let along = k.dot(&w);
        if along < T::zero() || (along == T::zero() && k[i] < T::zero()) {
            k = -k;
        }
        k
    };
    (Unit::new_normalize(axis), theta)
}

/// The rotation vector `k θ` of `r` (the logarithm map, θ ∈ [0, π]); zero for the identity.
/// Its inverse is `Rotation3::new(v)`.
pub fn rotation_vector<T: RealField + Copy>(r: &Rotation3<T>) -> Vector3<T> {
    let (axis, theta) = axis_angle(r);
    axis.into_inner() * theta
}
