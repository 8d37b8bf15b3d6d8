//! Rigid transforms over any ring, and a joint's variable as a ring element: the arithmetic
//! both paths build the chain from (the runtime path on `f64`, the generator on its symbolic
//! polynomials).

/// The arithmetic the DH conventions need. Implemented by `f64` (the runtime path) and by
/// the symbolic polynomials of `dhgen-codegen`, so both paths derive their transforms from
/// the one formula of the DH conventions (`Link::transform` in `dhgen-description`).
pub trait Ring:
    Clone
    + core::ops::Add<Output = Self>
    + core::ops::Sub<Output = Self>
    + core::ops::Mul<Output = Self>
    + core::ops::Neg<Output = Self>
{
    /// The constant `x`.
    fn from_f64(x: f64) -> Self;
}

impl Ring for f64 {
    fn from_f64(x: f64) -> Self {
        x
    }
}

/// A rigid transform over a [`Ring`]: rotation `r` (row-major) and translation `p`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame<R> {
    /// Rotation matrix, row-major.
    pub r: [[R; 3]; 3],
    /// Translation.
    pub p: [R; 3],
}

impl<R: Ring> Frame<R> {
    /// The identity transform.
    pub fn identity() -> Frame<R> {
        let o = R::from_f64(0.0);
        let i = R::from_f64(1.0);
        Frame {
            r: [
                [i.clone(), o.clone(), o.clone()],
                [o.clone(), i.clone(), o.clone()],
                [o.clone(), o.clone(), i],
            ],
            p: [o.clone(), o.clone(), o],
        }
    }

    /// `self · other`.
    pub fn compose(&self, other: &Frame<R>) -> Frame<R> {
        let r = core::array::from_fn(|i| {
            core::array::from_fn(|j| {
                self.r[i][0].clone() * other.r[0][j].clone()
                    + self.r[i][1].clone() * other.r[1][j].clone()
                    + self.r[i][2].clone() * other.r[2][j].clone()
            })
        });
        let p = core::array::from_fn(|i| {
            self.r[i][0].clone() * other.p[0].clone()
                + self.r[i][1].clone() * other.p[1].clone()
                + self.r[i][2].clone() * other.p[2].clone()
                + self.p[i].clone()
        });
        Frame { r, p }
    }

    /// Applies the transform to a point.
    pub fn point(&self, v: &[R; 3]) -> [R; 3] {
        core::array::from_fn(|i| {
            self.r[i][0].clone() * v[0].clone()
                + self.r[i][1].clone() * v[1].clone()
                + self.r[i][2].clone() * v[2].clone()
                + self.p[i].clone()
        })
    }

    /// The inverse transform: `(Rᵀ, −Rᵀ p)`.
    pub fn inverse(&self) -> Frame<R> {
        let r: [[R; 3]; 3] =
            core::array::from_fn(|i| core::array::from_fn(|j| self.r[j][i].clone()));
        let p = core::array::from_fn(|i| {
            -(r[i][0].clone() * self.p[0].clone()
                + r[i][1].clone() * self.p[1].clone()
                + r[i][2].clone() * self.p[2].clone())
        });
        Frame { r, p }
    }

    /// Rotates a vector (no translation).
    pub fn rotate(&self, v: &[R; 3]) -> [R; 3] {
        core::array::from_fn(|i| {
            self.r[i][0].clone() * v[0].clone()
                + self.r[i][1].clone() * v[1].clone()
                + self.r[i][2].clone() * v[2].clone()
        })
    }

    /// The z axis (third column of the rotation).
    pub fn z_axis(&self) -> [R; 3] {
        [
            self.r[0][2].clone(),
            self.r[1][2].clone(),
            self.r[2][2].clone(),
        ]
    }
}

impl Frame<f64> {
    /// The same transform in another ring (each entry a constant there).
    pub fn to_ring<R: Ring>(&self) -> Frame<R> {
        Frame {
            r: self.r.map(|row| row.map(R::from_f64)),
            p: self.p.map(R::from_f64),
        }
    }

    /// True when the rotation is exactly the identity (no rounding tolerance: structural
    /// zeros and ones of a description are exact).
    pub fn rotation_is_identity(&self) -> bool {
        self.r == [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    }
}

/// The value of a joint variable as a ring element: for a revolute joint its cosine and
/// sine, for a prismatic joint the displacement itself.
#[derive(Clone, Debug)]
pub enum JointValue<R> {
    /// `cos q`, `sin q` of a revolute joint.
    Revolute {
        /// cos q
        cos: R,
        /// sin q
        sin: R,
    },
    /// `q` of a prismatic joint.
    Prismatic(R),
}

impl<R: Ring> JointValue<R> {
    /// The joint's motion `Z`: `Rz(θ)` from the cosine and sine of a revolute joint's full
    /// angle, `Tz(d)` from a prismatic joint's full displacement.
    pub fn motion(self) -> Frame<R> {
        let (o, i) = (R::from_f64(0.0), R::from_f64(1.0));
        match self {
            JointValue::Revolute { cos, sin } => Frame {
                r: [
                    [cos.clone(), -sin.clone(), o.clone()],
                    [sin, cos, o.clone()],
                    [o.clone(), o.clone(), i],
                ],
                p: [o.clone(), o.clone(), o],
            },
            JointValue::Prismatic(d) => Frame {
                r: [
                    [i.clone(), o.clone(), o.clone()],
                    [o.clone(), i.clone(), o.clone()],
                    [o.clone(), o.clone(), i],
                ],
                p: [o.clone(), o, d],
            },
        }
    }
}

/// The kind of a joint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum JointKind {
    /// `θ_i = q_i + theta`, `d` constant.
    Revolute,
    /// `d_i = q_i + d`, `theta` constant.
    Prismatic,
}
