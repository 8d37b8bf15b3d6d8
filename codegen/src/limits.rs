//! What the generator takes: the work it will do for one description is bounded, and every
//! constant it would print is finite. A description outside these bounds is an
//! [`Unsupported`] error naming why (and, for a constant, the link and field it came from),
//! never a panic or an unbounded build.
//!
//! Validation already keeps every value of a description within physical ranges
//! (`dhgen_description::validate::LENGTH` and the others), so the constants of a valid description
//! are finite; [`check`] verifies that again on the structure the generator reads, because a
//! non-finite literal cannot be printed as Rust.

use dhgen_description::{ChainRef, Frame};
use std::fmt;

/// The most joints the generator takes for a robot with mass properties. The Christoffel
/// symbols alone are n³ values; at 30 general joints an unoptimised generator needs about
/// 13 s and 1 GB (the curve is in `scripts/scale.sh`). Longer chains use the runtime path,
/// `dhgen::Robot`, whose algorithms are O(n) to O(n²).
pub const MAX_DYNAMICS_DOF: usize = 32;

/// The most joints the generator takes for a kinematics-only robot (pose, Jacobians): the
/// generated code grows as n², to about a megabyte of source at 100 general joints.
pub const MAX_KINEMATICS_DOF: usize = 100;

/// Why the generator does not take a (valid) description.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Unsupported {
    /// The 1-based link the problem comes from, when it comes from one.
    pub link: Option<usize>,
    /// The description field it comes from, when known.
    pub field: Option<&'static str>,
    /// What is wrong and what to do.
    pub message: String,
}

impl fmt::Display for Unsupported {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.link, self.field) {
            (Some(l), Some(field)) => write!(f, "link {l}, field `{field}`: ")?,
            (Some(l), None) => write!(f, "link {l}: ")?,
            (None, Some(field)) => write!(f, "field `{field}`: ")?,
            (None, None) => {}
        }
        f.write_str(&self.message)
    }
}

impl std::error::Error for Unsupported {}

fn frame_finite(frame: &Frame<f64>) -> bool {
    frame
        .r
        .iter()
        .flatten()
        .chain(&frame.p)
        .all(|x| x.is_finite())
}

/// Checks that the generator will take `chain`: its size within [`MAX_DYNAMICS_DOF`] or
/// [`MAX_KINEMATICS_DOF`], and every constant finite.
///
/// # Errors
/// [`Unsupported`], naming the limit, or the link and field of a non-finite constant.
pub fn check(chain: ChainRef<'_>) -> Result<(), Unsupported> {
    let n = chain.dof();
    let (limit, what) = if chain.has_dynamics() {
        (MAX_DYNAMICS_DOF, "with mass properties")
    } else {
        (MAX_KINEMATICS_DOF, "for kinematics")
    };
    if n > limit {
        return Err(Unsupported {
            link: None,
            field: Some("links"),
            message: format!(
                "the robot has {n} joints; `robot!` generates code for at most {limit} joints \
                 {what} (generated code grows as n² to n³). Use the runtime path, \
                 `dhgen::Robot`, for longer chains{}",
                if chain.has_dynamics() && n <= MAX_KINEMATICS_DOF {
                    ", or drop the mass properties to generate kinematics only"
                } else {
                    ""
                }
            ),
        });
    }
    let bad = |link: Option<usize>, field: &'static str| Unsupported {
        link,
        field: Some(field),
        message: "a constant derived from this field is not finite; \
                  the generator prints only finite numbers"
            .into(),
    };
    if !frame_finite(&chain.base) {
        return Err(bad(None, "base"));
    }
    if chain.gravity.iter().any(|g| !g.is_finite()) {
        return Err(bad(None, "gravity"));
    }
    // P_{k-1} comes from row k's constants (and P_0 from the base); P_n from the tool.
    for (k, p) in chain.placements.iter().enumerate() {
        if !frame_finite(p) {
            return Err(if k == n {
                bad(None, "tool")
            } else {
                bad(Some(k + 1), "a, alpha, d, theta")
            });
        }
    }
    for (k, b) in chain.bodies.iter().enumerate() {
        let link = Some(k + 1);
        if !b.offset.is_finite() || !frame_finite(&b.link) {
            return Err(bad(link, "a, alpha, d, theta"));
        }
        if b.limits.is_some_and(|l| l.iter().any(|x| !x.is_finite())) {
            return Err(bad(link, "limits"));
        }
        if !b.armature.is_finite() {
            return Err(bad(link, "motor"));
        }
        if !b.friction.viscous.is_finite() || !b.friction.coulomb.is_finite() {
            return Err(bad(link, "friction"));
        }
        if let Some(i) = &b.inertial {
            if !i.mass.is_finite() {
                return Err(bad(link, "mass"));
            }
            if i.com.iter().any(|x| !x.is_finite()) {
                return Err(bad(link, "com"));
            }
            if i.inertia.iter().flatten().any(|x| !x.is_finite()) {
                return Err(bad(link, "inertia"));
            }
        }
        if b.capsule.is_some_and(|r| !r.is_finite()) {
            return Err(bad(link, "collision"));
        }
    }
    Ok(())
}
