//! Converting a robot between descriptions: to a DH table in either convention
//! ([`to_dh`]), and to a URDF document ([`to_urdf`]).
//!
//! # What a conversion keeps
//! The robot itself, exactly up to rounding (about 1e-15 of the arm's size):
//! - the joint variables: `q` is the same number in both descriptions, with the same zero and
//!   the same sign (a DH frame's z axis is always taken along its joint's axis, never against
//!   it; the joint's zero moves into the `theta` offset of a revolute joint, the `d` offset of
//!   a prismatic one);
//! - the tool pose `T(q)` at every `q`, the world frame being the same: DH cannot place frame
//!   0 and the tool frame freely, so the `base` and `tool` poses carry what it cannot;
//! - the dynamics: the body each joint moves is the same rigid body, its mass properties
//!   re-expressed in the new frame of that link (a constant transform, found at `q = 0`);
//!   with the same gravity (in the world frame), motors and friction, `D(q)`, `C(q, q̇)` and
//!   `g(q)` are the same;
//! - joint limits, motors, friction, gravity, the name and the description.
//!
//! Collision capsules follow the link frames (see [`Collision`](crate::Collision)): a
//! capsule is kept when its segment's ends, the origins of the new frames `i − 1` and `i`,
//! are where they were (within 1e-12 of the arm's size), and dropped otherwise, since the
//! segment of another frame would be another shape. Converting a table to its own convention
//! keeps them all; between the conventions most move.
//!
//! # Every serial chain has a DH form
//! Any chain of revolute and prismatic joints has a DH table in either convention (Spong,
//! Hutchinson & Vidyasagar, *Robot Modeling and Control*, §3.2; Craig, *Introduction to
//! Robotics*, §3.4): put a frame's z axis on each joint axis, its x axis on the common
//! normal to the next axis (any normal when the axes are parallel, any perpendicular
//! direction when they coincide), and consecutive frames then differ by exactly the four
//! DH motions. The only frames DH cannot choose, the world frame before frame 0 and the tool
//! frame after frame n, are the `base` and `tool` poses. So [`to_dh`] fails only when a
//! converted value falls outside the format's [ranges](crate::validate::LENGTH) (nearly
//! parallel axes that are apart have a common normal far away: DH's own ill-conditioning,
//! the `d` values grow like 1/sin of the angle between the axes), or when the model given
//! was not a valid one (a model built by hand, with numbers that are not finite).
//!
//! # How the frames are chosen
//! Every new frame is chosen as close to the model's own link frame of the same number as
//! the DH rules allow. The choices the rules leave open:
//! - which way the x axis points along a common normal: the way of the model's link frame's
//!   x axis (then of the previous new frame's x axis, so that `theta` is within ±90°; then a
//!   positive `a`; then `theta = +90°`);
//! - for parallel axes, which normal: the one through the point where the previous frame's x
//!   axis meets the axis, so that `d` is 0 (Spong's rule; a URDF's joint offsets along
//!   parallel axes add up into the next `d`, as in published tables), except when the model
//!   is already a table in the convention asked for: then the one through its link frame's
//!   origin, so that the table comes back as it was;
//! - for coincident axes, the x direction: the model's link frame's x axis (made
//!   perpendicular), the origin as for parallel axes;
//! - frame 0 (standard): on joint 1's axis at the foot of the perpendicular from the base
//!   frame's origin, x along the base frame's x axis; frame 0 (modified): placed by the base
//!   frame's z axis as if it were the axis of a joint 0 (so a base frame whose z axis is
//!   joint 1's is frame 0 itself);
//! - frame n: placed by the z axis and origin of the model's last link frame as if they were
//!   the axis of a joint n + 1, so that the tool pose keeps its meaning where the rules allow
//!   (a table's last frame stays, a URDF's last link frame becomes frame n when its z axis is
//!   the last joint's).
//!
//! So converting a table to its own convention gives the same table, base, tool and capsules
//! back (up to rounding), and a URDF whose link frames are DH frames (the Panda's are Craig's)
//! gives their table.
//!
//! Axes closer than 1e-12 rad to parallel are taken as parallel (the angle format snaps such
//! angles to exact ones anyway, so this moves an axis by at most 1e-12 rad); a prismatic
//! joint's axis is the line through its joint frame's origin (only its direction matters).

//! # Exact values
//! Quarter turns stay exact: a twist or an offset whose cosine and sine come out as 0 and ±1
//! is an exact quarter turn (and any angle within 1e-12 rad of one is read as one, see
//! [`Angle::from_radians`]); rotations of the base and tool poses with entries in {−1, 0, 1}
//! give exact roll, pitch and yaw; an angle within 1e-12 rad of a quarter turn is written as
//! that quarter turn's exact value (`1.5707963267948966`). Lengths (and the coordinates of the
//! base, tool and centres of mass) within 1e-14 of the arm's size of zero are written as
//! exactly zero; inertia entries within 1e-14 of the tensor's largest entry of zero likewise.
//! Each frame is found in the frame of the joint it starts from, where the description's own
//! numbers appear, so a length of the input comes out as the same number when the geometry
//! passes it through (the PUMA 560's `a = 0.0203` stays `0.0203`, not `0.020299999999999985`).
//!
//! ```
//! use dhgen_description::{Convention, RobotModel, convert::to_dh};
//! let elbow = RobotModel::from_toml_str(r#"
//!     name = "elbow"
//!     convention = "standard"
//!     [[links]]
//!     joint = "revolute"
//!     a = 1.0
//!     alpha = 0
//!     d = 0
//!     theta = 0
//!     [[links]]
//!     joint = "revolute"
//!     a = 0.8
//!     alpha = 0
//!     d = 0
//!     theta = 0
//! "#).unwrap();
//! // Craig's form: row i holds a_{i−1}; the tip beyond frame 2 (at the elbow) is the tool.
//! let craig = to_dh(&elbow, Convention::Modified).unwrap();
//! assert_eq!([craig.links[0].a, craig.links[1].a], [0.0, 1.0]);
//! assert_eq!(craig.tool.unwrap().xyz, [0.8, 0.0, 0.0]);
//! let q = [0.3, -1.2];
//! let (a, b) = (elbow.chain().view().tool_at(&q), craig.chain().view().tool_at(&q));
//! assert!((0..3).all(|i| (a.p[i] - b.p[i]).abs() < 1e-12));
//! ```

use crate::{
    Angle, ChainRef, Convention, Frame, Inertial, JointKind, JointValue, Link, Placement, Pose,
    RobotModel,
};
use std::fmt::Write as _;

/// Why a model could not be converted.
///
/// Every serial chain has a DH form (see the [module docs](self)), so a conversion only fails
/// when a converted value is outside the ranges of the description format, or when the
/// model given was not valid.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ConvertError {
    /// The converted description breaks a rule of the format: the joint (1-based, when the
    /// value belongs to one), the field, and the rule's message.
    #[error("{}{}", Where { joint: *joint, field: field.as_deref() }, message)]
    Invalid {
        /// The joint (row), 1-based; `None` for a top-level field.
        joint: Option<usize>,
        /// The field, as the description format names it (`d`, `inertia.xy`, `tool.xyz`).
        field: Option<String>,
        /// What is wrong.
        message: String,
    },
}

struct Where<'a> {
    joint: Option<usize>,
    field: Option<&'a str>,
}

impl std::fmt::Display for Where<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match (self.joint, self.field) {
            (Some(j), Some(field)) => write!(f, "joint {j}, field `{field}`: "),
            (Some(j), None) => write!(f, "joint {j}: "),
            (None, Some(field)) => write!(f, "field `{field}`: "),
            (None, None) => Ok(()),
        }
    }
}

type V = [f64; 3];

fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn scale(a: V, k: f64) -> V {
    [a[0] * k, a[1] * k, a[2] * k]
}

fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn norm(a: V) -> f64 {
    dot(a, a).sqrt()
}

fn column(f: &Frame<f64>, j: usize) -> V {
    [f.r[0][j], f.r[1][j], f.r[2][j]]
}

/// Axes whose directions' cross product is shorter than this are parallel.
const PARALLEL: f64 = 1e-12;
/// A dot product of unit vectors this close to 0 decides no sign.
const TIE: f64 = 1e-12;
/// Lengths within this fraction of the arm's size of zero are zero.
const LENGTH_SNAP: f64 = 1e-14;
/// Inertia entries within this fraction of the tensor's largest of zero are zero.
const INERTIA_SNAP: f64 = 1e-14;
/// A collision segment's ends must stay within this fraction of the arm's size.
const SEGMENT_TOLERANCE: f64 = 1e-12;

/// A line: a point and a unit direction.
#[derive(Clone, Copy, Debug)]
struct Line {
    p: V,
    u: V,
}

impl Line {
    fn project(&self, x: V) -> V {
        add(self.p, scale(self.u, dot(sub(x, self.p), self.u)))
    }
}

/// What decides the choices the DH rules leave open: a point (which normal of parallel axes)
/// and x directions in order of preference.
#[derive(Clone, Copy, Debug)]
struct Hint {
    point: V,
    x: [Option<V>; 2],
}

/// A common normal of two lines: its direction `x` (from line a towards line b when
/// `a > 0`), its signed length along `x`, and its feet on the two lines.
#[derive(Clone, Copy, Debug)]
struct Normal {
    x: V,
    a: f64,
    foot_a: V,
    foot_b: V,
}

/// A unit vector perpendicular to `z`: the first hint's component perpendicular to it when
/// that is not (nearly) zero, else the next hint's, else a coordinate axis's.
fn perpendicular(hints: &[Option<V>], z: V) -> V {
    let least = (0..3)
        .min_by(|&i, &j| z[i].abs().total_cmp(&z[j].abs()))
        .unwrap_or(0);
    let mut e = [0.0; 3];
    e[least] = 1.0;
    for x in hints.iter().flatten().copied().chain([e]) {
        let r = sub(x, scale(z, dot(x, z)));
        let n = norm(r);
        if n > 1e-6 {
            return scale(r, 1.0 / n);
        }
    }
    // Unreachable for a unit z (the least aligned axis is at least 0.8 off it); a z that is
    // not finite lands here, and validation reports the numbers it gives.
    e
}

/// Orients a unit normal `n` (signed length `a` along it) by the hints: the side the
/// first hint's x axis points to, else the next's, else `a > 0`, else the side that makes
/// the angle from the first hint's x axis a positive quarter turn about `axis`.
fn orient(n: V, a: f64, hint: &Hint, axis: V) -> (V, f64) {
    for x in hint.x.iter().flatten() {
        let h = dot(n, *x);
        if h.abs() > TIE {
            return if h < 0.0 {
                (scale(n, -1.0), clean(-a))
            } else {
                (n, a)
            };
        }
    }
    let flip = if a != 0.0 {
        a < 0.0
    } else {
        hint.x
            .iter()
            .flatten()
            .next()
            .is_some_and(|x| dot(cross(*x, n), axis) < 0.0)
    };
    if flip {
        (scale(n, -1.0), clean(-a))
    } else {
        (n, a)
    }
}

/// The common normal of lines `a` and `b`, chosen by `hint` where the lines leave it open;
/// lengths within `tol` of zero are zero.
fn common_normal(la: &Line, lb: &Line, hint: &Hint, tol: f64) -> Normal {
    let c = cross(la.u, lb.u);
    let s = norm(c);
    let snap = |x: f64| if x.abs() <= tol { 0.0 } else { x };
    if s > PARALLEL {
        // Closest points: la.p + sa·la.u and lb.p + tb·lb.u, from the cross products (no
        // 1 − cos² cancellation).
        let w = sub(lb.p, la.p);
        let cc = s * s;
        let sa = dot(cross(w, lb.u), c) / cc;
        let tb = dot(cross(w, la.u), c) / cc;
        let n = scale(c, 1.0 / s);
        let (x, a) = orient(n, snap(dot(w, n)), hint, la.u);
        Normal {
            x,
            a,
            foot_a: add(la.p, scale(la.u, sa)),
            foot_b: add(lb.p, scale(lb.u, tb)),
        }
    } else {
        // Parallel: the normal in the plane through the hint's point.
        let foot_a = la.project(hint.point);
        let foot_b = lb.project(hint.point);
        let d = sub(foot_b, foot_a);
        let w = sub(d, scale(la.u, dot(d, la.u)));
        let dist = snap(norm(w));
        if dist == 0.0 {
            // Coincident: any perpendicular.
            Normal {
                x: perpendicular(&hint.x, la.u),
                a: 0.0,
                foot_a,
                foot_b,
            }
        } else {
            let (x, a) = orient(scale(w, 1.0 / norm(w)), dist, hint, la.u);
            Normal {
                x,
                a,
                foot_a,
                foot_b,
            }
        }
    }
}

/// The angle that turns `from` into `to` about `axis` (all three unit, `from` and `to`
/// perpendicular to `axis`): exact quarter turns from exact vectors.
fn angle_about(from: V, to: V, axis: V) -> Angle {
    exact(dot(cross(from, to), axis).atan2(dot(from, to)))
}

/// The angle of `rad` radians; one that [`Angle::from_radians`] takes for a quarter turn
/// gets the exact value of that quarter turn (`1.5707963267948966`, not `…68`), and −0 is 0.
fn exact(rad: f64) -> Angle {
    let angle = Angle::from_radians(rad);
    if angle.quarter_turn().is_some() {
        let k = (rad / core::f64::consts::FRAC_PI_2).round();
        Angle::from_radians(clean(k * core::f64::consts::FRAC_PI_2))
    } else {
        Angle::from_radians(clean(rad))
    }
}

/// A frame with origin `o`, z axis `z` and x axis along `x` made perpendicular to it.
fn frame(o: V, x: V, z: V) -> Frame<f64> {
    let x = perpendicular(&[Some(x)], z);
    let y = cross(z, x);
    Frame {
        r: core::array::from_fn(|i| [x[i], y[i], z[i]]),
        p: o,
    }
}

/// `x`, with zeros positive.
fn clean(x: f64) -> f64 {
    x + 0.0
}

/// Roll, pitch and yaw of a rotation, exact quarter turns for entries in {−1, 0, 1}.
fn rpy(r: &[[f64; 3]; 3]) -> [Angle; 3] {
    crate::model::rpy_of(r).map(exact)
}

/// A frame as a pose; translations within `tol` of zero are zero.
fn pose(f: &Frame<f64>, tol: f64) -> Pose {
    Pose {
        xyz: f.p.map(|x| if x.abs() <= tol { 0.0 } else { clean(x) }),
        rpy: rpy(&f.r),
    }
}

/// `Some(pose)` unless it is the identity.
fn non_identity(p: Pose) -> Option<Pose> {
    (!p.is_identity()).then_some(p)
}

/// Mass properties given in frame `f`, re-expressed in the outer frame; small entries
/// snapped to zero.
fn in_frame(i: &Inertial, f: &Frame<f64>, tol: f64) -> Inertial {
    let moved = i.in_frame(f);
    // The upper triangle mirrored: exactly symmetric.
    let t = &moved.inertia;
    let inertia: [[f64; 3]; 3] =
        core::array::from_fn(|a| core::array::from_fn(|b| t[a.min(b)][a.max(b)]));
    let big = inertia.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let inertia = inertia.map(|row| {
        row.map(|x| {
            if x.abs() <= INERTIA_SNAP * big {
                0.0
            } else {
                clean(x)
            }
        })
    });
    Inertial {
        mass: i.mass,
        com: moved
            .com
            .map(|x| if x.abs() <= tol { 0.0 } else { clean(x) }),
        inertia,
    }
}

/// The chain at `q = 0`. Each step of the frame construction works in the frame of the joint
/// whose axis it starts from, where the chain's constants are given directly (exact values
/// stay exact); the world frame serves for frame 0, the tool and the mass properties.
struct AtZero {
    /// Joint frame k + 1 in joint frame k (world for k = 0): `P_k · Z_{k+1}(offset)`.
    steps: Vec<Frame<f64>>,
    /// Joint frames, world.
    joints: Vec<Frame<f64>>,
    /// The model's link frames `0..=n`, world (frame 0: the base frame).
    links: Vec<Frame<f64>>,
    /// Link frame k + 1 in joint frame k + 1.
    local_links: Vec<Frame<f64>>,
    /// The tool in joint frame n (`P_n`).
    tool_local: Frame<f64>,
    /// The arm's size: lengths are snapped and compared relative to it.
    scale: f64,
}

fn at_zero(chain: &ChainRef<'_>) -> AtZero {
    let n = chain.dof();
    let steps: Vec<Frame<f64>> = chain
        .bodies
        .iter()
        .enumerate()
        .map(|(k, b)| chain.placements[k].compose(&b.motion(0.0)))
        .collect();
    let mut joints: Vec<Frame<f64>> = Vec::with_capacity(n);
    for s in &steps {
        let next = joints.last().map_or(*s, |j| j.compose(s));
        joints.push(next);
    }
    let mut links = vec![chain.base];
    links.extend(
        joints
            .iter()
            .zip(chain.bodies)
            .map(|(j, b)| j.compose(&b.link)),
    );
    AtZero {
        tool_local: chain.placements[n],
        local_links: chain.bodies.iter().map(|b| b.link).collect(),
        steps,
        joints,
        links,
        scale: chain.length_scale(),
    }
}

fn z_line(f: &Frame<f64>) -> Line {
    let u = f.z_axis();
    Line {
        p: f.p,
        u: scale(u, 1.0 / norm(u)),
    }
}

/// The z axis of the frame a step works in.
const Z_AXIS: Line = Line {
    p: [0.0; 3],
    u: [0.0, 0.0, 1.0],
};

/// The DH parameters of one row.
struct Row {
    a: f64,
    alpha: Angle,
    d: f64,
    theta: Angle,
}

/// The line step `i` (frame i, joint frame i's coordinates, 1-based) ends on: axis i + 1,
/// or for the last frame the z axis of the model's last link frame.
fn next_line(z: &AtZero, i: usize) -> Line {
    let n = z.steps.len();
    if i < n {
        z_line(&z.steps[i])
    } else {
        z_line(&z.local_links[n - 1])
    }
}

/// The hint of step `i` (1-based), in joint frame i: the model's link frame i's x axis, then
/// the previous new frame's; the model's link frame i's origin when `keep` or for the last
/// frame, else `point` (where the previous frame's x axis meets axis i, so that `d` is 0 for
/// parallel axes).
fn hint(z: &AtZero, i: usize, prev: &Frame<f64>, point: V, keep: bool) -> Hint {
    let old = &z.local_links[i - 1];
    Hint {
        point: if keep || i == z.steps.len() {
            old.p
        } else {
            point
        },
        x: [Some(column(old, 0)), Some(column(prev, 0))],
    }
}

/// Standard DH rows for the chain at zero (see the module docs for the choices); with frame
/// 0 in the world.
fn standard_rows(z: &AtZero, tol: f64, keep: bool) -> (Frame<f64>, Vec<Row>) {
    let n = z.steps.len();
    let snap = |x: f64| if x.abs() <= tol { 0.0 } else { clean(x) };
    let base = &z.links[0];
    let axis1 = z_line(&z.joints[0]);
    let frame0 = frame(
        axis1.project(base.p),
        perpendicular(&[Some(column(base, 0))], axis1.u),
        axis1.u,
    );
    // The previous new frame, in the coordinates of the current step.
    let mut prev = z.steps[0].inverse().compose(&frame0);
    let mut rows = Vec::with_capacity(n);
    for i in 1..=n {
        let lb = next_line(z, i);
        let nm = common_normal(&Z_AXIS, &lb, &hint(z, i, &prev, prev.p, keep), tol);
        let next = frame(nm.foot_b, nm.x, lb.u);
        let (px, pz) = (column(&prev, 0), prev.z_axis());
        let x = column(&next, 0);
        rows.push(Row {
            a: nm.a,
            alpha: angle_about(pz, lb.u, x),
            d: snap(dot(sub(nm.foot_a, prev.p), pz)),
            theta: angle_about(px, x, pz),
        });
        if i < n {
            prev = z.steps[i].inverse().compose(&next);
        }
    }
    (frame0, rows)
}

/// Modified DH rows for the chain at zero (see the module docs for the choices); with frame
/// 0 in the world.
fn modified_rows(z: &AtZero, tol: f64, keep: bool) -> (Frame<f64>, Vec<Row>) {
    let n = z.steps.len();
    let snap = |x: f64| if x.abs() <= tol { 0.0 } else { clean(x) };
    let base = &z.links[0];
    // Frame 0 on the base frame's z axis, towards axis 1 (world).
    let nm0 = common_normal(
        &z_line(base),
        &z_line(&z.joints[0]),
        &Hint {
            point: base.p,
            x: [Some(column(base, 0)), None],
        },
        tol,
    );
    let frame0 = frame(nm0.foot_a, nm0.x, z_line(base).u);
    let to_first = z.steps[0].inverse();
    // The previous frame, its normal's foot on the current axis and its length, in the
    // coordinates of the current step.
    let mut prev = to_first.compose(&frame0);
    let mut foot = to_first.point(&nm0.foot_b);
    let mut a = nm0.a;
    let mut rows = Vec::with_capacity(n);
    for i in 1..=n {
        let nm = common_normal(
            &Z_AXIS,
            &next_line(z, i),
            &hint(z, i, &prev, foot, keep),
            tol,
        );
        let f = frame(nm.foot_a, nm.x, Z_AXIS.u);
        let (px, pz) = (column(&prev, 0), prev.z_axis());
        rows.push(Row {
            a,
            alpha: angle_about(pz, Z_AXIS.u, px),
            d: snap(dot(sub(nm.foot_a, foot), Z_AXIS.u)),
            theta: angle_about(px, column(&f, 0), Z_AXIS.u),
        });
        if i < n {
            let back = z.steps[i].inverse();
            prev = back.compose(&f);
            foot = back.point(&nm.foot_b);
            a = nm.a;
        }
    }
    (frame0, rows)
}

/// Validates a converted model by writing and reading it back (the reading is the model
/// returned).
fn validated(model: &RobotModel) -> Result<RobotModel, ConvertError> {
    RobotModel::from_toml_named(&model.to_toml(), "<converted>").map_err(|e| match e {
        crate::LoadError::Invalid { error, .. } => ConvertError::Invalid {
            joint: error.link,
            field: error.field,
            message: error.message,
        },
        other => ConvertError::Invalid {
            joint: None,
            field: None,
            message: other.to_string(),
        },
    })
}

/// The same robot as a description in `convention`: same joint variables, tool pose and
/// dynamics at every `q` (see the [module docs](self) for what is kept exactly and how the
/// frames are chosen).
///
/// - [`Convention::Standard`], [`Convention::Modified`]: a DH table, from any model (a `urdf`
///   one, or a table in either convention). The `base` and `tool` poses hold what the table
///   cannot (`None` when that is the identity); each link's `com` and `inertia` are
///   re-expressed in its new link frame; collision capsules whose segment moves are dropped.
/// - [`Convention::Urdf`]: a `urdf` model is returned as it is; a DH table becomes `urdf`
///   rows whose axes are all `[0, 0, 1]`, each row's link frame being its joint's frame
///   (the frame the joint turns about the z axis of), with the joint offsets folded into the
///   origins, and the base pose kept.
///
/// The result has been written as TOML and read back ([`RobotModel::to_toml`],
/// [`RobotModel::from_toml_str`]): it is a valid description, and what is returned is that
/// reading.
///
/// # Errors
/// [`ConvertError::Invalid`], naming the joint and field, when a converted value is outside
/// the format's ranges or the model given was not valid (see [`ConvertError`]).
pub fn to_dh(model: &RobotModel, convention: Convention) -> Result<RobotModel, ConvertError> {
    if model.links.is_empty() {
        return Err(ConvertError::Invalid {
            joint: None,
            field: Some("links".into()),
            message: "the model has no joints".into(),
        });
    }
    if convention == Convention::Urdf {
        return if model.convention == Convention::Urdf {
            validated(model)
        } else {
            validated(&urdf_model(model))
        };
    }
    let chain = model.chain();
    let chain = chain.view();
    let z = at_zero(&chain);
    let tol = LENGTH_SNAP * z.scale;
    // A table in the convention asked for already has link frames that obey the rules:
    // keep their origins on parallel axes too.
    let keep = model.convention == convention;
    let (frame0, rows) = match convention {
        Convention::Standard => standard_rows(&z, tol, keep),
        _ => modified_rows(&z, tol, keep),
    };
    let base = pose(&frame0, tol);
    let mut links: Vec<Link> = model
        .links
        .iter()
        .zip(&rows)
        .map(|(l, r)| Link {
            joint: l.joint,
            a: r.a,
            alpha: r.alpha,
            d: r.d,
            theta: r.theta,
            limits: l.limits,
            inertial: None,
            motor: l.motor,
            friction: l.friction,
            collision: l.collision,
            placement: None,
        })
        .collect();
    // E_k = D_k⁻¹ J_k: the model's joint frame k in the new link frame k, at q = 0, by the
    // table itself (snapped values, exact quarter turns), so that the tool and the mass
    // properties agree with the model as written. The recursion E_k = A_k⁻¹ E_{k−1} S_k
    // composes the constants of both chains side by side, so the values they share cancel
    // exactly.
    let mut e = vec![base.frame::<f64>().inverse()];
    for (l, step) in links.iter().zip(&z.steps) {
        let value = match l.joint {
            JointKind::Revolute => JointValue::Revolute { cos: 1.0, sin: 0.0 },
            JointKind::Prismatic => JointValue::Prismatic(0.0),
        };
        let a = l.transform(convention, value);
        let next = a.inverse().compose(&e[e.len() - 1]).compose(step);
        e.push(next);
    }
    let n = links.len();
    let tool = pose(&e[n].compose(&z.tool_local), tol);
    // The model's link frame origins in the new link frames.
    let moved: Vec<V> = core::iter::once(e[0].point(&z.links[0].p))
        .chain((0..n).map(|k| e[k + 1].point(&z.local_links[k].p)))
        .collect();
    keep_capsules(&mut links, &moved, z.scale);
    for (k, l) in links.iter_mut().enumerate() {
        l.inertial = chain.bodies[k]
            .inertial
            .map(|i| in_frame(&i, &e[k + 1], tol));
    }
    validated(&RobotModel {
        name: model.name.clone(),
        description: model.description.clone(),
        convention,
        gravity: model.gravity,
        base: non_identity(base),
        tool: non_identity(tool),
        links,
    })
}

/// Drops the collision capsules whose segment ends (the origins of link frames i − 1 and i)
/// move: `moved[k]` is the model's link frame k origin in the new link frame k, at q = 0.
fn keep_capsules(links: &mut [Link], moved: &[V], scale: f64) {
    let tol = SEGMENT_TOLERANCE * scale;
    let same = |k: usize| norm(moved[k]) <= tol;
    for (i, l) in links.iter_mut().enumerate() {
        if l.collision.is_some() && !(same(i) && same(i + 1)) {
            l.collision = None;
        }
    }
}

/// One joint of a URDF-style description: its origin (the joint frame at rest in the
/// previous link frame), axis and the mass properties in its child link frame.
struct UrdfJointRow {
    origin: Pose,
    axis: [f64; 3],
    inertial: Option<Inertial>,
}

/// The joint rows of a DH model in the URDF form: child link frame = joint frame (axis z,
/// inertial as the chain has it), origins `P_{k−1} · Z_k(offset_k)`; the first row's origin
/// taken from `before` (the frame it is given in: the world, or the base frame).
fn dh_as_urdf_rows(
    chain: &ChainRef<'_>,
    before: Option<&Frame<f64>>,
    tol: f64,
) -> (Vec<UrdfJointRow>, Pose) {
    let rows = chain
        .bodies
        .iter()
        .enumerate()
        .map(|(k, b)| {
            let origin = chain.placements[k].compose(&b.motion(0.0));
            let origin = match (k, before) {
                (0, Some(f)) => f.inverse().compose(&origin),
                _ => origin,
            };
            UrdfJointRow {
                origin: pose(&origin, tol),
                axis: [0.0, 0.0, 1.0],
                inertial: b.inertial,
            }
        })
        .collect();
    (rows, pose(&chain.placements[chain.dof()], tol))
}

/// A DH model as a `urdf` model (axes z, link frames = joint frames, base kept).
fn urdf_model(model: &RobotModel) -> RobotModel {
    let chain = model.chain();
    let chain = chain.view();
    let z = at_zero(&chain);
    let tol = LENGTH_SNAP * z.scale;
    let base = model.base_pose().copied();
    let before = base.map(|b| b.frame::<f64>());
    let (rows, tool) = dh_as_urdf_rows(&chain, before.as_ref(), tol);
    let mut links: Vec<Link> = model
        .links
        .iter()
        .zip(rows)
        .map(|(l, r)| Link {
            joint: l.joint,
            a: 0.0,
            alpha: Angle::ZERO,
            d: 0.0,
            theta: Angle::ZERO,
            limits: l.limits,
            inertial: r.inertial,
            motor: l.motor,
            friction: l.friction,
            collision: l.collision,
            placement: Some(Placement {
                origin: r.origin,
                axis: r.axis,
            }),
        })
        .collect();
    // The new link frames are the joint frames (and the same base frame).
    let moved: Vec<V> = core::iter::once([0.0; 3])
        .chain(z.local_links.iter().map(|l| l.p))
        .collect();
    keep_capsules(&mut links, &moved, z.scale);
    RobotModel {
        name: model.name.clone(),
        description: model.description.clone(),
        convention: Convention::Urdf,
        gravity: model.gravity,
        base,
        tool: non_identity(tool),
        links,
    }
}

/// `x` as URDF writes it: the shortest text that reads back as the same `f64`.
fn num(x: f64) -> String {
    format!("{:?}", clean(x))
}

fn nums(v: &[f64]) -> String {
    v.iter().map(|x| num(*x)).collect::<Vec<_>>().join(" ")
}

/// Text for an XML attribute value.
fn attribute(s: &str) -> String {
    let mut out = String::new();
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if c.is_control() => {
                let _ = write!(out, "&#{};", u32::from(c));
            }
            c => out.push(c),
        }
    }
    out
}

/// Text for an XML comment (which may not hold `--` nor end in `-`), on one line.
fn comment(s: &str) -> String {
    let mut out: String = s
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    while out.contains("--") {
        out = out.replace("--", "- -");
    }
    if out.ends_with('-') {
        out.push(' ');
    }
    out
}

fn origin_element(p: &Pose) -> String {
    format!(
        "<origin xyz=\"{}\" rpy=\"{}\"/>",
        nums(&p.xyz),
        nums(&p.rpy.map(Angle::radians))
    )
}

/// The robot as a URDF document: links `base_link`, `link1` … `linkn` and, when the tool
/// pose is not the identity, `tool` (on a fixed joint `tool_joint`); joints `joint1` …
/// `jointn`. Loaders that follow the URDF specification (Pinocchio, Robotics Toolbox,
/// [`crate::urdf::read`]) read the same joint variables, kinematics and rigid-body dynamics:
///
/// - a `urdf` model's rows are written as they are (origin, axis, mass properties in the
///   child link frame); a DH model's child link frame k is its joint frame k (axis
///   `0 0 1`, mass properties as the [chain](crate::JointChain) has them), with each joint's
///   offset folded into its origin (URDF has none): the origin of joint k is
///   `P_{k−1} · Rz(offset)` (or `· Tz(offset)`), so the child frame at `q` is exactly the
///   joint frame at `q`;
/// - `base_link` is the world frame: the base pose is folded into the first joint's origin;
/// - the tool is the `tool` link: read it back with `tip = "tool"` (readers that take the
///   end of the movable joints as the tip stop at `linkn`);
/// - a revolute joint with limits is `revolute` with `<limit lower upper effort="0"
///   velocity="0"/>` (the model has no effort or velocity limits: 0 stands for "not given"),
///   one without is `continuous` (the same joint; Pinocchio represents its configuration by
///   the pair `cos q`, `sin q`); a prismatic joint without limits has a `<limit>` without
///   `lower` and `upper`, which URDF reads as 0 and 0 (and [`crate::urdf::read`] as no
///   limits);
/// - friction is `<dynamics damping="viscous" friction="coulomb"/>`;
/// - numbers are written in Rust's shortest round-trip form, so they read back exactly;
///   angles of a quarter turn are `1.5707963267948966` (which readers snap back, see
///   [`crate::urdf`]).
///
/// Lost, with an XML comment saying so: motors (URDF has no rotor inertia or gear ratio, so
/// the armature `Jm·G²` is not in the document), gravity (URDF has none; loaders assume
/// `0 0 −9.81` in the world frame), collision capsules (a URDF `<collision>` shape at its
/// own origin is a different description). Joint names are not the model's (it has none).
pub fn to_urdf(model: &RobotModel) -> String {
    let chain = model.chain();
    let chain = chain.view();
    let tol = LENGTH_SNAP * chain.length_scale();
    let (rows, tool) = if model.convention == Convention::Urdf
        && model.links.iter().all(|l| l.placement.is_some())
    {
        let base = model.base_pose().map(|b| b.frame::<f64>());
        let rows = model
            .links
            .iter()
            .enumerate()
            .map(|(k, l)| {
                let p = l.placement.unwrap_or(Placement {
                    origin: Pose {
                        xyz: [0.0; 3],
                        rpy: [Angle::ZERO; 3],
                    },
                    axis: [0.0, 0.0, 1.0],
                });
                let origin = match (k, &base) {
                    (0, Some(b)) => pose(&b.compose(&p.origin.frame::<f64>()), tol),
                    _ => p.origin,
                };
                UrdfJointRow {
                    origin,
                    axis: p.axis,
                    inertial: l.inertial,
                }
            })
            .collect();
        let tool = model.tool_pose().copied().unwrap_or(Pose {
            xyz: [0.0; 3],
            rpy: [Angle::ZERO; 3],
        });
        (rows, tool)
    } else {
        dh_as_urdf_rows(&chain, None, tol)
    };
    let mut out = String::new();
    let _ = writeln!(out, "<?xml version=\"1.0\"?>");
    let _ = writeln!(
        out,
        "<!-- Written by dhgen from the description `{}`{}. -->",
        comment(&model.name),
        model
            .description
            .as_deref()
            .map_or_else(String::new, |d| format!(" ({})", comment(d)))
    );
    let g = model.gravity;
    let _ = writeln!(
        out,
        "<!-- Gravity of the description: {} m/s^2 in the frame of base_link; URDF has no \
         gravity (loaders assume 0 0 -9.81). -->",
        comment(&nums(&g))
    );
    if model.links.iter().any(|l| l.collision.is_some()) {
        let _ = writeln!(
            out,
            "<!-- The description's collision capsules are not written: URDF collision \
             shapes are another description. -->"
        );
    }
    let _ = writeln!(out, "<robot name=\"{}\">", attribute(&model.name));
    let _ = writeln!(out, "  <link name=\"base_link\"/>");
    for (k, (row, l)) in rows.iter().zip(&model.links).enumerate() {
        let i = k + 1;
        let parent = if k == 0 {
            "base_link".to_string()
        } else {
            format!("link{k}")
        };
        let kind = match (l.joint, l.limits) {
            (JointKind::Prismatic, _) => "prismatic",
            (JointKind::Revolute, Some(_)) => "revolute",
            (JointKind::Revolute, None) => "continuous",
        };
        let _ = writeln!(out, "  <joint name=\"joint{i}\" type=\"{kind}\">");
        let _ = writeln!(out, "    <parent link=\"{parent}\"/>");
        let _ = writeln!(out, "    <child link=\"link{i}\"/>");
        let _ = writeln!(out, "    {}", origin_element(&row.origin));
        let _ = writeln!(out, "    <axis xyz=\"{}\"/>", nums(&row.axis));
        match (l.joint, l.limits) {
            (_, Some([lo, hi])) => {
                let _ = writeln!(
                    out,
                    "    <limit lower=\"{}\" upper=\"{}\" effort=\"0\" velocity=\"0\"/>",
                    num(lo),
                    num(hi)
                );
            }
            (JointKind::Prismatic, None) => {
                let _ = writeln!(out, "    <limit effort=\"0\" velocity=\"0\"/>");
            }
            (JointKind::Revolute, None) => {}
        }
        if let Some(f) = l.friction
            && (f.viscous != 0.0 || f.coulomb != 0.0)
        {
            let _ = writeln!(
                out,
                "    <dynamics damping=\"{}\" friction=\"{}\"/>",
                num(f.viscous),
                num(f.coulomb)
            );
        }
        if let Some(m) = l.motor {
            let _ = writeln!(
                out,
                "    <!-- motor: rotor inertia {} kg m^2, gear ratio {}, armature {} kg m^2; \
                 URDF has no element for it -->",
                num(m.inertia),
                num(m.gear),
                num(m.armature())
            );
        }
        let _ = writeln!(out, "  </joint>");
        match &row.inertial {
            None => {
                let _ = writeln!(out, "  <link name=\"link{i}\"/>");
            }
            Some(m) => {
                let t = &m.inertia;
                let _ = writeln!(out, "  <link name=\"link{i}\">");
                let _ = writeln!(out, "    <inertial>");
                let _ = writeln!(
                    out,
                    "      <origin xyz=\"{}\" rpy=\"0 0 0\"/>",
                    nums(&m.com)
                );
                let _ = writeln!(out, "      <mass value=\"{}\"/>", num(m.mass));
                let _ = writeln!(
                    out,
                    "      <inertia ixx=\"{}\" ixy=\"{}\" ixz=\"{}\" iyy=\"{}\" iyz=\"{}\" izz=\"{}\"/>",
                    num(t[0][0]),
                    num(t[0][1]),
                    num(t[0][2]),
                    num(t[1][1]),
                    num(t[1][2]),
                    num(t[2][2])
                );
                let _ = writeln!(out, "    </inertial>");
                let _ = writeln!(out, "  </link>");
            }
        }
    }
    if !tool.is_identity() {
        let n = rows.len();
        let _ = writeln!(out, "  <joint name=\"tool_joint\" type=\"fixed\">");
        let _ = writeln!(out, "    <parent link=\"link{n}\"/>");
        let _ = writeln!(out, "    <child link=\"tool\"/>");
        let _ = writeln!(out, "    {}", origin_element(&tool));
        let _ = writeln!(out, "  </joint>");
        let _ = writeln!(out, "  <link name=\"tool\"/>");
    }
    let _ = writeln!(out, "</robot>");
    out
}
