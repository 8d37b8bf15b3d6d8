//! Spatial (6-D) vectors and inertias in Plücker coordinates at the world origin, the
//! common language of the dynamics algorithms (Featherstone, *Rigid Body Dynamics
//! Algorithms*, ch. 2), over any [`Real`] (`f64` for [`Robot`](crate::Robot); any scalar or
//! pack for [`crate::recursive`]). Working in world coordinates lets every algorithm share
//! one kinematic pass and makes the derivatives of `D(q)` simple screw products.

use crate::Real;
use core::ops::{Add, AddAssign, Mul, Sub};
use nalgebra::{Matrix3, Vector3};

/// A motion vector `[ω; v]`: angular velocity and the velocity of the body-fixed point at
/// the world origin.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Motion<T = f64> {
    /// The angular part ω.
    pub ang: Vector3<T>,
    /// The linear part v (of the body-fixed point at the world origin).
    pub lin: Vector3<T>,
}

/// A force vector `[n; f]`: moment about the world origin and force (or the momentum
/// equivalents).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Force<T = f64> {
    /// The moment n about the world origin.
    pub ang: Vector3<T>,
    /// The force f.
    pub lin: Vector3<T>,
}

impl<T: Real> Motion<T> {
    /// The zero motion.
    #[inline]
    pub fn zero() -> Motion<T> {
        Motion {
            ang: Vector3::zeros(),
            lin: Vector3::zeros(),
        }
    }

    /// The motion cross product `self × m` (how `m`, carried by a body moving with
    /// `self`, changes).
    #[inline]
    pub fn cross(&self, m: &Motion<T>) -> Motion<T> {
        Motion {
            ang: self.ang.cross(&m.ang),
            lin: self.ang.cross(&m.lin) + self.lin.cross(&m.ang),
        }
    }

    /// The force cross product `self ×* f`.
    #[inline]
    pub fn cross_force(&self, f: &Force<T>) -> Force<T> {
        Force {
            ang: self.ang.cross(&f.ang) + self.lin.cross(&f.lin),
            lin: self.ang.cross(&f.lin),
        }
    }

    /// The power pairing `self · f`.
    #[inline]
    pub fn dot(&self, f: &Force<T>) -> T {
        self.ang.dot(&f.ang) + self.lin.dot(&f.lin)
    }
}

impl<T: Real> Add for Motion<T> {
    type Output = Motion<T>;
    #[inline]
    fn add(self, m: Motion<T>) -> Motion<T> {
        Motion {
            ang: self.ang + m.ang,
            lin: self.lin + m.lin,
        }
    }
}

impl<T: Real> Sub for Motion<T> {
    type Output = Motion<T>;
    #[inline]
    fn sub(self, m: Motion<T>) -> Motion<T> {
        Motion {
            ang: self.ang - m.ang,
            lin: self.lin - m.lin,
        }
    }
}

impl<T: Real> Mul<T> for Motion<T> {
    type Output = Motion<T>;
    #[inline]
    fn mul(self, s: T) -> Motion<T> {
        Motion {
            ang: self.ang * s,
            lin: self.lin * s,
        }
    }
}

impl<T: Real> Force<T> {
    /// The zero force.
    #[inline]
    pub fn zero() -> Force<T> {
        Force {
            ang: Vector3::zeros(),
            lin: Vector3::zeros(),
        }
    }
}

impl<T: Real> Add for Force<T> {
    type Output = Force<T>;
    #[inline]
    fn add(self, f: Force<T>) -> Force<T> {
        Force {
            ang: self.ang + f.ang,
            lin: self.lin + f.lin,
        }
    }
}

impl<T: Real> AddAssign for Force<T> {
    #[inline]
    fn add_assign(&mut self, f: Force<T>) {
        self.ang += f.ang;
        self.lin += f.lin;
    }
}

/// A spatial inertia about the world origin: mass `m`, first mass moment `h = m·c` (c the
/// centre of mass) and rotational inertia `k` about the origin. As a 6×6 matrix it is
/// `[[k, h×], [−h×, m·1]]`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inertia<T = f64> {
    /// The mass m.
    pub mass: T,
    /// The first mass moment h = m·c.
    pub h: Vector3<T>,
    /// The rotational inertia k about the world origin.
    pub k: Matrix3<T>,
}

impl<T: Real> Inertia<T> {
    /// The inertia of a body of mass `mass` with centre of mass `com` and inertia `i_com`
    /// about it (all in world coordinates), by the parallel axis theorem.
    #[inline]
    pub fn from_com(mass: T, com: &Vector3<T>, i_com: &Matrix3<T>) -> Inertia<T> {
        let k = i_com
            + (Matrix3::from_diagonal_element(com.norm_squared()) - com * com.transpose()) * mass;
        Inertia {
            mass,
            h: com * mass,
            k,
        }
    }

    /// This inertia, given about a frame's origin in that frame's axes (mass, first moment
    /// `h`, rotational inertia `k` about the origin), in world coordinates for the frame at
    /// rotation `r` and origin `p`: turned (`r h`, `r k rᵀ`), then moved from `p` to the world
    /// origin by the parallel axis theorem with a first moment,
    /// `k_O = k' + m (|p|² 1 − p pᵀ) + 2 (p·h') 1 − p h'ᵀ − h' pᵀ`, `h_O = h' + m p`
    /// (no division by the mass, which may be zero).
    #[inline]
    pub fn placed(&self, r: &Matrix3<T>, p: &Vector3<T>) -> Inertia<T> {
        let h = r * self.h;
        let k = r * self.k * r.transpose();
        let two: T = nalgebra::convert(2.0);
        let moved = (Matrix3::from_diagonal_element(p.norm_squared()) - p * p.transpose())
            * self.mass
            + Matrix3::from_diagonal_element(p.dot(&h) * two)
            - p * h.transpose()
            - h * p.transpose();
        Inertia {
            mass: self.mass,
            h: h + p * self.mass,
            k: k + moved,
        }
    }

    /// The momentum (or force) `I·v`.
    #[inline]
    pub fn apply(&self, v: &Motion<T>) -> Force<T> {
        Force {
            ang: self.k * v.ang + self.h.cross(&v.lin),
            lin: v.lin * self.mass - self.h.cross(&v.ang),
        }
    }
}

impl<T: Real> AddAssign<&Inertia<T>> for Inertia<T> {
    #[inline]
    fn add_assign(&mut self, o: &Inertia<T>) {
        self.mass += o.mass;
        self.h += o.h;
        self.k += o.k;
    }
}
