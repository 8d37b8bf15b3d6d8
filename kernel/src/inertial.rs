//! A link's mass properties and a joint's friction, as the chain carries them.

use crate::Frame;

/// Mass properties of one link, in that link's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Inertial {
    /// Mass, kg.
    pub mass: f64,
    /// Centre of mass in link frame i, m.
    pub com: [f64; 3],
    /// Inertia tensor about the centre of mass, link-frame axes, kg·m²
    /// (`[[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]`, products as tensor entries).
    pub inertia: [[f64; 3]; 3],
}

impl Inertial {
    /// The description format's six inertia fields, in order, and the tensor entry each names
    /// (`inertia = { xx, yy, zz, xy, yz, xz }`, products as tensor entries).
    pub const FIELDS: [(&'static str, [usize; 2]); 6] = [
        ("xx", [0, 0]),
        ("yy", [1, 1]),
        ("zz", [2, 2]),
        ("xy", [0, 1]),
        ("yz", [1, 2]),
        ("xz", [0, 2]),
    ];

    /// The inertia tensor as the description format's fields ([`Inertial::FIELDS`]).
    pub fn inertia_fields(&self) -> [(&'static str, f64); 6] {
        Inertial::FIELDS.map(|(name, [a, b])| (name, self.inertia[a][b]))
    }

    /// The same body described in an outer frame, `f` placing this body's frame in it: the
    /// centre of mass moved by `f`, the inertia turned, `R I Rᵀ`.
    pub fn in_frame(&self, f: &Frame<f64>) -> Inertial {
        let r = &f.r;
        // R I Rᵀ
        let ri: [[f64; 3]; 3] = core::array::from_fn(|a| {
            core::array::from_fn(|b| (0..3).map(|k| r[a][k] * self.inertia[k][b]).sum())
        });
        Inertial {
            mass: self.mass,
            com: f.point(&self.com),
            inertia: core::array::from_fn(|a| {
                core::array::from_fn(|b| (0..3).map(|k| ri[a][k] * r[b][k]).sum())
            }),
        }
    }

    /// Two bodies given in the same frame, rigidly joined: the masses add, the centre of mass
    /// is their weighted mean, each inertia moves to it by the parallel-axis theorem. Two
    /// massless bodies give a massless one at the origin with the inertias' sum.
    pub fn combined(&self, other: &Inertial) -> Inertial {
        let mass = self.mass + other.mass;
        if mass == 0.0 {
            return Inertial {
                mass,
                com: [0.0; 3],
                inertia: core::array::from_fn(|a| {
                    core::array::from_fn(|b| self.inertia[a][b] + other.inertia[a][b])
                }),
            };
        }
        let com: [f64; 3] =
            core::array::from_fn(|k| (self.com[k] * self.mass + other.com[k] * other.mass) / mass);
        // m (|d|² 1 − d dᵀ), d from the common centre of mass to the body's own.
        let shift = |b: &Inertial, i: usize, j: usize| {
            let d: [f64; 3] = core::array::from_fn(|k| b.com[k] - com[k]);
            let dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
            b.mass * (if i == j { dd } else { 0.0 } - d[i] * d[j])
        };
        Inertial {
            mass,
            com,
            inertia: core::array::from_fn(|i| {
                core::array::from_fn(|j| {
                    self.inertia[i][j]
                        + shift(self, i, j)
                        + other.inertia[i][j]
                        + shift(other, i, j)
                })
            }),
        }
    }
}

/// Joint-side friction: `τ_f = viscous·q̇ + coulomb·sign(q̇)`; the default is none.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Friction {
    /// Viscous coefficient, N·m·s/rad (N·s/m for prismatic joints).
    pub viscous: f64,
    /// Coulomb friction, N·m (N).
    pub coulomb: f64,
}
