//! Seeded random valid arms, for scale tests and benchmarks: the same seed gives the same
//! arm on every platform and version (SplitMix64, no dependency).
//!
//! Two styles:
//! - [`ArmStyle::General`]: twists and joint offsets anywhere in (−π, π) (never a quarter
//!   turn), link lengths and offsets everywhere, full inertia tensors: no structure for the
//!   symbolic engine to exploit (what a URDF with rounded angles looks like);
//! - [`ArmStyle::Industrial`]: twists and offsets in {0, ±90°}, some lengths and offsets
//!   zero, as in catalogue arms.
//!
//! Every link has mass properties (a solid box of random size and density, turned by a random
//! rotation, so the inertia is physical), and about one joint in seven is prismatic (with
//! limits). The result passes validation.
//!
//! ```
//! use dhgen_description::random::{ArmStyle, random_arm};
//! let arm = random_arm(10, ArmStyle::General, 7);
//! assert_eq!(arm.dof(), 10);
//! assert_eq!(arm, random_arm(10, ArmStyle::General, 7));
//! let text = arm.to_toml();
//! assert_eq!(dhgen_description::RobotModel::from_toml_str(&text).unwrap(), arm);
//! ```

use crate::{Angle, Convention, Inertial, JointKind, Link, RobotModel};
use core::f64::consts::{FRAC_PI_2, PI};
pub use dhgen_kernel::stream::Stream;

/// What kind of arm [`random_arm`] makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArmStyle {
    /// No exact angles, nothing zero.
    General,
    /// Twists and offsets in {0, ±90°}, some lengths zero.
    Industrial,
}

/// An angle in (−π, π) at least 0.05 rad away from every multiple of π/2.
fn general_angle(s: &mut Stream) -> f64 {
    loop {
        let a = s.uniform(-PI, PI);
        let k = (a / FRAC_PI_2).round();
        if (a - k * FRAC_PI_2).abs() > 0.05 {
            return a;
        }
    }
}

/// The inertia tensor (about the centre) of a solid box of `mass` and edges `e`, turned by
/// the rotation of unit quaternion `q`.
fn box_inertia(mass: f64, e: [f64; 3], q: [f64; 4]) -> [[f64; 3]; 3] {
    let k = mass / 12.0;
    let principal = [
        k * (e[1] * e[1] + e[2] * e[2]),
        k * (e[0] * e[0] + e[2] * e[2]),
        k * (e[0] * e[0] + e[1] * e[1]),
    ];
    let [w, x, y, z] = q;
    let r = [
        [
            1.0 - 2.0 * (y * y + z * z),
            2.0 * (x * y - w * z),
            2.0 * (x * z + w * y),
        ],
        [
            2.0 * (x * y + w * z),
            1.0 - 2.0 * (x * x + z * z),
            2.0 * (y * z - w * x),
        ],
        [
            2.0 * (x * z - w * y),
            2.0 * (y * z + w * x),
            1.0 - 2.0 * (x * x + y * y),
        ],
    ];
    // Each product computed once and mirrored: the tensor is exactly symmetric.
    let entry = |a: usize, b: usize| -> f64 {
        let (a, b) = (a.min(b), a.max(b));
        (0..3).map(|k| r[a][k] * principal[k] * r[b][k]).sum()
    };
    core::array::from_fn(|a| core::array::from_fn(|b| entry(a, b)))
}

fn unit_quaternion(s: &mut Stream) -> [f64; 4] {
    loop {
        let q = [0; 4].map(|_| s.uniform(-1.0, 1.0));
        let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
        if n > 0.1 && n <= 1.0 {
            return q.map(|x| x / n);
        }
    }
}

/// A valid arm of `dof` joints (standard DH), reproducible from `seed`.
pub fn random_arm(dof: usize, style: ArmStyle, seed: u64) -> RobotModel {
    let mut s = Stream(seed ^ (dof as u64).wrapping_mul(0x2545_F491_4F6C_DD1D));
    let links = (0..dof)
        .map(|_| {
            let prismatic = s.next_f64() < 1.0 / 7.0;
            let (a, alpha, d, theta) = match style {
                ArmStyle::General => (
                    s.uniform(0.05, 0.5),
                    general_angle(&mut s),
                    s.uniform(-0.2, 0.3),
                    general_angle(&mut s),
                ),
                ArmStyle::Industrial => {
                    let quarter = [0.0, FRAC_PI_2, -FRAC_PI_2];
                    let a = if s.next_f64() < 0.4 {
                        0.0
                    } else {
                        s.uniform(0.05, 0.5)
                    };
                    let d = if s.next_f64() < 0.4 {
                        0.0
                    } else {
                        s.uniform(-0.2, 0.3)
                    };
                    (a, s.pick(&quarter), d, s.pick(&quarter))
                }
            };
            let mass = s.uniform(0.5, 5.0);
            let edges = [0; 3].map(|_| s.uniform(0.02, 0.3));
            let inertia = box_inertia(mass, edges, unit_quaternion(&mut s));
            // The centre of mass somewhere along the link.
            let com = [
                -a * s.uniform(0.2, 0.8),
                s.uniform(-0.05, 0.05),
                s.uniform(-0.05, 0.05),
            ];
            Link {
                joint: if prismatic {
                    JointKind::Prismatic
                } else {
                    JointKind::Revolute
                },
                a,
                alpha: Angle::from_radians(alpha),
                d,
                theta: Angle::from_radians(theta),
                limits: if prismatic {
                    Some([0.0, s.uniform(0.2, 0.8)])
                } else {
                    Some([-PI, PI])
                },
                inertial: Some(Inertial { mass, com, inertia }),
                motor: None,
                friction: None,
                collision: None,
                placement: None,
            }
        })
        .collect();
    let style_name = match style {
        ArmStyle::General => "general",
        ArmStyle::Industrial => "industrial",
    };
    RobotModel {
        name: format!("random_{style_name}_{dof}_{seed}"),
        description: Some(format!(
            "Random {style_name} arm, {dof} joints, seed {seed} (dhgen_description::random)"
        )),
        convention: Convention::Standard,
        gravity: crate::validate::DEFAULT_GRAVITY,
        base: None,
        tool: None,
        links,
    }
}
