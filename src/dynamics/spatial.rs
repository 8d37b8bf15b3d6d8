//! Spatial (6-D) vectors and inertias in Plücker coordinates at the world origin, the
//! common language of the dynamics algorithms (Featherstone, *Rigid Body Dynamics
//! Algorithms*, ch. 2). Working in world coordinates lets every algorithm share one
//! kinematic pass and makes the derivatives of `D(q)` simple screw products.

use core::ops::{Add, AddAssign, Mul, Sub};
use nalgebra::{Matrix3, Vector3};

/// A motion vector `[ω; v]`: angular velocity and the velocity of the body-fixed point at
/// the world origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Motion {
    pub ang: Vector3<f64>,
    pub lin: Vector3<f64>,
}

/// A force vector `[n; f]`: moment about the world origin and force (or the momentum
/// equivalents).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Force {
    pub ang: Vector3<f64>,
    pub lin: Vector3<f64>,
}

impl Motion {
    pub const ZERO: Motion = Motion {
        ang: Vector3::new(0.0, 0.0, 0.0),
        lin: Vector3::new(0.0, 0.0, 0.0),
    };

    /// The motion cross product `self × m` (how `m`, carried by a body moving with
    /// `self`, changes).
    #[inline]
    pub fn cross(&self, m: &Motion) -> Motion {
        Motion {
            ang: self.ang.cross(&m.ang),
            lin: self.ang.cross(&m.lin) + self.lin.cross(&m.ang),
        }
    }

    /// The force cross product `self ×* f`.
    #[inline]
    pub fn cross_force(&self, f: &Force) -> Force {
        Force {
            ang: self.ang.cross(&f.ang) + self.lin.cross(&f.lin),
            lin: self.ang.cross(&f.lin),
        }
    }

    /// The power pairing `self · f`.
    #[inline]
    pub fn dot(&self, f: &Force) -> f64 {
        self.ang.dot(&f.ang) + self.lin.dot(&f.lin)
    }
}

impl Add for Motion {
    type Output = Motion;
    #[inline]
    fn add(self, m: Motion) -> Motion {
        Motion {
            ang: self.ang + m.ang,
            lin: self.lin + m.lin,
        }
    }
}

impl Sub for Motion {
    type Output = Motion;
    #[inline]
    fn sub(self, m: Motion) -> Motion {
        Motion {
            ang: self.ang - m.ang,
            lin: self.lin - m.lin,
        }
    }
}

impl Mul<f64> for Motion {
    type Output = Motion;
    #[inline]
    fn mul(self, s: f64) -> Motion {
        Motion {
            ang: self.ang * s,
            lin: self.lin * s,
        }
    }
}

impl Force {
    pub const ZERO: Force = Force {
        ang: Vector3::new(0.0, 0.0, 0.0),
        lin: Vector3::new(0.0, 0.0, 0.0),
    };
}

impl Add for Force {
    type Output = Force;
    #[inline]
    fn add(self, f: Force) -> Force {
        Force {
            ang: self.ang + f.ang,
            lin: self.lin + f.lin,
        }
    }
}

impl AddAssign for Force {
    #[inline]
    fn add_assign(&mut self, f: Force) {
        self.ang += f.ang;
        self.lin += f.lin;
    }
}

/// A spatial inertia about the world origin: mass `m`, first mass moment `h = m·c` (c the
/// centre of mass) and rotational inertia `k` about the origin. As a 6×6 matrix it is
/// `[[k, h×], [−h×, m·1]]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Inertia {
    pub mass: f64,
    pub h: Vector3<f64>,
    pub k: Matrix3<f64>,
}

impl Inertia {
    /// The inertia of a body of mass `mass` with centre of mass `com` and inertia `i_com`
    /// about it (all in world coordinates), by the parallel axis theorem.
    #[inline]
    pub fn from_com(mass: f64, com: &Vector3<f64>, i_com: &Matrix3<f64>) -> Inertia {
        let k = i_com
            + (Matrix3::from_diagonal_element(com.norm_squared()) - com * com.transpose()) * mass;
        Inertia {
            mass,
            h: com * mass,
            k,
        }
    }

    /// The momentum (or force) `I·v`.
    #[inline]
    pub fn apply(&self, v: &Motion) -> Force {
        Force {
            ang: self.k * v.ang + self.h.cross(&v.lin),
            lin: v.lin * self.mass - self.h.cross(&v.ang),
        }
    }
}

impl AddAssign<&Inertia> for Inertia {
    #[inline]
    fn add_assign(&mut self, o: &Inertia) {
        self.mass += o.mass;
        self.h += o.h;
        self.k += o.k;
    }
}
