//! The solver built from an arm's structure: which geometry it is (a spherical wrist and
//! its shoulder, or three parallel axes), its constants, and the structures refused.

use super::{ArmKind, DecoupledIk, Method, Shoulder, StructureError};
use crate::{ChainRef, JointKind, Rigid};
use nalgebra::{Matrix3, Vector3};

/// Whether two axes whose directions have the cosine `cos` are parallel or anti-parallel: the
/// cosine within 1e-12 of ±1.
pub(super) fn parallel(cos: f64) -> bool {
    (cos.abs() - 1.0).abs() <= 1e-12
}

pub(super) fn kinds(prismatic: &[bool; 6]) -> [u8; 3] {
    core::array::from_fn(|i| if prismatic[i] { b'P' } else { b'R' })
}

impl DecoupledIk {
    /// Builds the solver from a validated description.
    #[cfg(feature = "std")]
    pub fn from_model(model: impl Into<crate::JointChain>) -> Result<DecoupledIk, StructureError> {
        Self::from_chain(model.into().view())
    }

    /// Builds the solver from a kinematic structure (an arm's: `Arm::chain`, a generated
    /// module's `CHAIN`).
    pub fn from_chain(chain: ChainRef<'_>) -> Result<DecoupledIk, StructureError> {
        let dof = chain.dof();
        if dof != 6 {
            return Err(StructureError::NotSixJoints { dof });
        }
        // T(q) = P0 Z1(q1 + o1) P1 ⋯: fold each offset into the transform before its joint,
        // `P_k Z_{k+1}(o)`, so that the solver's joint values are the user's.
        let frames: [Rigid; 7] = core::array::from_fn(|k| {
            let p = &chain.placements[k];
            if k < 6 {
                Rigid::from_frame(&p.compose(&chain.bodies[k].motion(0.0)))
            } else {
                Rigid::from_frame(p)
            }
        });
        let prismatic = core::array::from_fn(|i| chain.bodies[i].joint == JointKind::Prismatic);
        let limits = core::array::from_fn(|i| chain.bodies[i].limits);
        let scale = 1.0 + frames.iter().map(|f| f.p.norm()).sum::<f64>();
        let base = DecoupledIk {
            chain: frames,
            prismatic,
            limits,
            scale,
            kind: ArmKind::IntersectingShoulder,
            method: Method::Spherical {
                centre_tool: Vector3::zeros(),
                w: Vector3::zeros(),
                shoulder: Shoulder::Cylindrical {
                    f0: Vector3::zeros(),
                    u: Vector3::zeros(),
                    v: Vector3::zeros(),
                    lead_is_2: true,
                },
            },
        };
        match chain.spherical_wrist() {
            Ok(wrist) => base.spherical(Vector3::from(wrist.centre)),
            Err(why) => match base.three_parallel() {
                Some(ik) => match ik.three_parallel_degenerate() {
                    Some(reason) => Err(ik.unsupported(reason)),
                    None => Ok(ik),
                },
                None => Err(StructureError::NoDecoupling(why)),
            },
        }
    }

    pub(super) fn unsupported(&self, reason: &'static str) -> StructureError {
        StructureError::UnsupportedArm {
            joints: kinds(&self.prismatic),
            reason,
        }
    }

    /// The solver of a spherical-wrist arm with wrist centre `centre` in joint frame 4.
    pub(super) fn spherical(mut self, centre: Vector3<f64>) -> Result<DecoupledIk, StructureError> {
        let c = &self.chain;
        let tol = 1e-9 * self.scale;
        // The tool in the frame of joint 4 at q4 = q5 = q6 = 0.
        let wrist_to_tool = c[4].compose(&c[5]).compose(&c[6]);
        let centre_tool = wrist_to_tool.inverse().point(&centre);
        let w = c[3].point(&centre);
        if self.prismatic[0] {
            return Err(self.unsupported("joint 1 must be revolute"));
        }
        if !self.places_the_wrist_centre(&w) {
            return Err(self.unsupported(
                "they cannot move the wrist centre in three independent directions (two of \
                 their axes coincide, all three are parallel, or the centre lies on their axes): \
                 the arm is redundant or degenerate, with a continuum of solutions or none",
            ));
        }
        let (p1, p2) = (c[1], c[2]);
        let (shoulder, kind) = if !self.prismatic[1] {
            // Axis 2 in the frame joint 1 turns: through p1.p along n2. Slide the origin to
            // the foot of the common normal of axes 1 and 2.
            let n2 = p1.r.column(2).into_owned();
            let sin = n2.xy().norm();
            let shift = if sin > 1e-12 {
                // The common normal meets axis 1 where p1.p + t n2 is closest to it.
                let t = -(p1.p.xy().dot(&n2.xy())) / (sin * sin);
                p1.p.z + t * n2.z
            } else {
                0.0
            };
            let t1 = p1.p - Vector3::z() * shift;
            let u = p1.r.transpose() * t1;
            let n = p1.r.transpose() * Vector3::z();
            let (a, b) = (u.xy().norm(), n.xy().norm());
            // Joint 3 must move the wrist centre's distance from axis 2 (or along it).
            let moves = if self.prismatic[2] {
                (p2.r.column(2).into_owned()).norm() > 0.0
            } else {
                w.xy().norm() > tol
            };
            if !moves {
                return Err(
                    self.unsupported("joint 3 does not move the wrist centre (it lies on axis 3)")
                );
            }
            let kind = match (a > tol, b > 1e-12) {
                (false, true) => ArmKind::IntersectingShoulder,
                (true, false) => ArmKind::ParallelShoulder,
                (true, true) => ArmKind::OffsetShoulder,
                (false, false) => return Err(self.unsupported("axes 1 and 2 coincide")),
            };
            (Shoulder::Revolute { shift, t1, u, n }, kind)
        } else if self.prismatic[2] {
            let u = p1.r.column(2).into_owned();
            let v = p1.r * p2.r.column(2);
            let f0 = p1.p + p1.r * (p2.p + p2.r * w);
            let lead_is_2 = u.z.abs() >= v.z.abs();
            let (lead, other) = if lead_is_2 { (u, v) } else { (v, u) };
            if lead.z.abs() < 1e-9 {
                return Err(self.unsupported("neither prismatic joint moves along axis 1"));
            }
            if (other.xy() - lead.xy() * (other.z / lead.z)).norm() < 1e-9 {
                return Err(
                    self.unsupported("the prismatic joints do not change the distance from axis 1")
                );
            }
            (
                Shoulder::Cylindrical {
                    f0,
                    u,
                    v,
                    lead_is_2,
                },
                ArmKind::Cylindrical,
            )
        } else {
            return Err(
                self.unsupported("a prismatic joint 2 needs a prismatic joint 3 (cylindrical arm)")
            );
        };
        self.kind = kind;
        self.method = Method::Spherical {
            centre_tool,
            w,
            shoulder,
        };
        Ok(self)
    }

    /// Whether joints 1–3 move the wrist centre (`w` in the frame joint 3 moves) in three
    /// independent directions: the determinant of their 3×3 Jacobian of its position, each
    /// column made a unit vector (a column shorter than a billionth of the arm's length scale
    /// counts as none), is not zero at every one of a few fixed configurations. A structure
    /// that fails (axes 2 and 3 coaxial, axes 1–3 parallel, the centre on every axis) loses a
    /// direction everywhere, and its pose has a continuum of solutions or none: no closed form
    /// here.
    pub(super) fn places_the_wrist_centre(&self, w: &Vector3<f64>) -> bool {
        const SAMPLES: [[f64; 3]; 4] = [
            [0.7, -1.1, 0.4],
            [-2.3, 0.5, 1.9],
            [1.3, 2.1, -0.8],
            [-0.4, -2.7, 2.6],
        ];
        SAMPLES.iter().any(|q| {
            let (_, jacobian) = self.wrist_centre(w, q);
            let columns: [Vector3<f64>; 3] = core::array::from_fn(|i| {
                let c = jacobian.column(i).into_owned();
                let norm = c.norm();
                if norm > 1e-9 * self.scale {
                    c / norm
                } else {
                    Vector3::zeros()
                }
            });
            Matrix3::from_columns(&columns).determinant().abs() > 1e-9
        })
    }

    /// Why an arm with axes 2, 3, 4 parallel loses a direction at every configuration, if it
    /// does: joints 2–4 are a planar arm of two links, the distances between axes 2 and 3 and
    /// between axes 3 and 4 (in the frames joints 2 and 3 move), and a link of length zero
    /// (two coaxial joints) leaves a continuum of solutions or none; so does axis 5 parallel
    /// to them (four parallel axes: the tool turns about two directions only).
    pub(super) fn three_parallel_degenerate(&self) -> Option<&'static str> {
        let c = &self.chain;
        if c[2].p.xy().norm().min(c[3].p.xy().norm()) <= 1e-9 * self.scale {
            Some(
                "axes 2, 3, 4 are parallel but two of them coincide: the planar arm they make \
                 has a link of length zero (a continuum of solutions or none)",
            )
        } else if parallel((c[4].r * Vector3::z()).z) {
            Some(
                "axes 2, 3, 4 and 5 are parallel: the tool turns about two directions only (a \
                 continuum of solutions or none)",
            )
        } else {
            None
        }
    }

    /// The solver of an arm with axes 2, 3, 4 parallel and axes 5, 6 meeting, if it is one.
    pub(super) fn three_parallel(mut self) -> Option<DecoupledIk> {
        if self.prismatic.iter().any(|p| *p) {
            return None;
        }
        let c = self.chain;
        let z = Vector3::z();
        // Axes 3 and 4 parallel to axis 2 (up to sign), in their predecessors' frames.
        let s3 = (c[2].r * z).z;
        let s4 = (c[3].r * z).z;
        if !(parallel(s3) && parallel(s4)) {
            return None;
        }
        let n = c[1].r * z;
        // Axis 1 must not be parallel to them, or q1 would not change X's n-component.
        if n.xy().norm() < 1e-9 {
            return None;
        }
        // X: where axes 5 and 6 meet, in the frame after joint 4 (axis 5 is its z axis
        // through c[4].p, axis 6 is c[4]·c[5]'s).
        let f6 = c[4].compose(&c[5]);
        let (o5, d5) = (c[4].p, c[4].r * z);
        let (o6, d6) = (f6.p, f6.r * z);
        let w0 = o5 - o6;
        let k = d5.dot(&d6);
        let denom = 1.0 - k * k;
        if denom < 1e-12 {
            return None;
        }
        let (d, e) = (d5.dot(&w0), d6.dot(&w0));
        let x5 = o5 + d5 * ((k * e - d) / denom);
        let x6 = o6 + d6 * ((e - k * d) / denom);
        if (x5 - x6).norm() > 1e-9 * self.scale {
            return None;
        }
        let x4 = x5;
        let x_tool = f6.compose(&c[6]).inverse().point(&x4);
        // The frame after joint 4 at q2 = q3 = q4 = 0, in the frame after joint 1.
        let b0 = c[1].compose(&c[2]).compose(&c[3]);
        let kappa = n.dot(&b0.point(&x4));
        let sigma = (b0.r.transpose() * n).z;
        self.kind = ArmKind::ThreeParallel;
        self.method = Method::ThreeParallel {
            n,
            x_tool,
            x4,
            kappa,
            sigma,
            sigma3: s3.signum(),
            sigma34: (s3 * s4).signum(),
            k0: c[1].r.transpose() * b0.r,
        };
        Some(self)
    }
}
