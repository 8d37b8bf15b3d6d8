//! The working rigid transform of the numeric code (the runtime path, closed-form inverse
//! kinematics): a rotation matrix and a translation. Composing two is a plain 3×3 product,
//! cheaper than nalgebra's quaternion-based `Isometry3`, which is only built for results
//! handed to the user.

use crate::{Frame, JointKind};
#[cfg(not(feature = "std"))]
use nalgebra::ComplexField as _;
use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};

/// A rigid transform `x ↦ r x + p`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rigid {
    /// Rotation: the columns are the frame's axes in the outer frame.
    pub r: Matrix3<f64>,
    /// Origin of the frame in the outer frame.
    pub p: Vector3<f64>,
}

impl Rigid {
    /// The identity transform.
    pub const IDENTITY: Rigid = Rigid {
        r: Matrix3::new(1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0),
        p: Vector3::new(0.0, 0.0, 0.0),
    };

    /// Converts a row-major frame.
    pub fn from_frame(f: &Frame<f64>) -> Rigid {
        Rigid {
            r: Matrix3::from_fn(|i, j| f.r[i][j]),
            p: Vector3::from(f.p),
        }
    }

    /// `self · other`.
    #[inline]
    pub fn compose(&self, other: &Rigid) -> Rigid {
        Rigid {
            r: self.r * other.r,
            p: self.r * other.p + self.p,
        }
    }

    /// The inverse transform.
    pub fn inverse(&self) -> Rigid {
        let rt = self.r.transpose();
        Rigid {
            r: rt,
            p: -(rt * self.p),
        }
    }

    /// Applies the transform to a point.
    pub fn point(&self, v: &Vector3<f64>) -> Vector3<f64> {
        self.r * v + self.p
    }

    /// Right-multiplies by the joint motion: `Rz(v)` for a revolute joint, `Tz(v)` for a
    /// prismatic one, `v` the full joint value (offset included).
    #[inline]
    pub fn apply_joint(&mut self, joint: JointKind, v: f64) {
        match joint {
            JointKind::Prismatic => self.p += self.r.column(2) * v,
            JointKind::Revolute => {
                let (s, c) = v.sin_cos();
                let x = self.r.column(0).into_owned();
                let y = self.r.column(1).into_owned();
                self.r.set_column(0, &(x * c + y * s));
                self.r.set_column(1, &(y * c - x * s));
            }
        }
    }

    /// `self · Z(v)`: the frame right-multiplied by a joint's motion.
    pub fn moved(&self, joint: JointKind, v: f64) -> Rigid {
        let mut out = *self;
        out.apply_joint(joint, v);
        out
    }

    /// From an nalgebra isometry.
    pub fn from_isometry(iso: &Isometry3<f64>) -> Rigid {
        Rigid {
            r: *iso.rotation.to_rotation_matrix().matrix(),
            p: iso.translation.vector,
        }
    }

    /// The transform as an nalgebra isometry.
    pub fn to_isometry(self) -> Isometry3<f64> {
        let rotation =
            UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(self.r));
        Isometry3::from_parts(Translation3::from(self.p), rotation)
    }
}

/// The distance between two poses: `(position error in m, orientation error in rad)`, the
/// latter the angle of the rotation taking one orientation to the other, computed as
/// `2 atan2(|v|, |w|)` of the relative quaternion (accurate for small angles, where the
/// `acos` of nalgebra's `angle()` is not).
pub fn pose_error(a: &Isometry3<f64>, b: &Isometry3<f64>) -> (f64, f64) {
    let dp = (a.translation.vector - b.translation.vector).norm();
    let rel = a.rotation.inverse() * b.rotation;
    let q = rel.quaternion();
    let dr = 2.0 * <f64 as nalgebra::RealField>::atan2(q.vector().norm(), q.scalar().abs());
    (dp, dr)
}
