//! Reading URDF: the serial chain of a URDF file as a [`RobotModel`] of the
//! [`urdf` convention](crate::Convention::Urdf).
//!
//! What is read, in the terms of the [URDF specification](http://wiki.ros.org/urdf/XML):
//! - the chain runs from the root link (or the link named `base`) to the `tip` link. Without a
//!   `tip`, the chain ends at the one link that is moved by a movable joint and has no movable
//!   joint below it (when there are several, the error lists them), or further down at the end
//!   of a run of fixed joints from it in which every link has exactly one child (a flange, a
//!   tool frame: what dhgen's own URDF export writes);
//! - `revolute`, `continuous` and `prismatic` joints on the chain are the robot's joints, in
//!   order, with their `<origin>` (xyz, rpy), `<axis>` (default x, as URDF says), position
//!   `<limit lower upper>` (velocity and effort are kept in [`UrdfJoint`]) and
//!   `<dynamics damping friction>` as viscous and Coulomb friction;
//! - `fixed` joints are merged: into the next joint's origin, into the tool transform after
//!   the last joint, and their links' mass properties into the body they are fixed to (as
//!   Pinocchio does). Movable joints off the chain (a gripper's fingers, the other arm of a
//!   two-arm robot) are held at `q = 0` and merged the same way; so are the links above
//!   `base`, whose mass the fixed base carries. A `floating` or `planar` joint off the chain
//!   joins a free body (an object, a cart), which does not load the arm: it is left out with
//!   everything below it and listed in [`UrdfRobot::left_out`];
//! - `<inertial>` with its own `<origin>` (the tensor is rotated into the link frame), its
//!   `<mass value>` and all six attributes of `<inertia>` (as ROS's urdfdom requires);
//!   a file with no `<inertial>` at all is a kinematics-only robot; otherwise a body the
//!   joints move with none (after merging) is massless, as in Pinocchio and KDL, and listed
//!   in [`UrdfRobot::massless`];
//! - `<visual>`, `<collision>`, `<transmission>`, `<gazebo>` and unknown elements are ignored:
//!   collision capsules of dhgen are segments between link frames, which a URDF's boxes and
//!   cylinders at their own origins do not describe.
//!
//! Gravity is URDF's usual `[0, 0, −9.81]` in the root link's frame. The model's world frame
//! is the base link's (every joint above it at 0), so with a `base` turned against the root
//! the model's `gravity` is that vector seen from the base link.
//!
//! Errors (floating, planar and movable mimic joints on the chain, closed chains, unknown
//! links, a negative mass or an inertia tensor that is not
//! positive semi-definite on a link a moving body carries, a zero axis, a number outside the
//! description format's [ranges](crate::validate::Range), wherever it is in the file, but for
//! the position limits of joints off the chain, which play no part) name the
//! file, line and column, the link or joint and the attribute as URDF writes it
//! (``joint `j1` <limit lower>``). The links the fixed base carries (with every branch that
//! leaves the chain before its first moving joint) may hold mass properties no body can have
//! (within the ranges): a published URDF's 1 mg antenna on the base, with a tensor that is not
//! positive semi-definite, does not stop its arm from loading. Inertia tensors need not obey
//! the triangle inequality: published URDFs often do not, and Pinocchio accepts them.
//!
//! # Exact quarter turns
//! URDF angles are decimals (`1.5707963267948966`, `1.5708`). An angle within
//! [`UrdfOptions::snap`] (default 1e-9 rad) of a multiple of π/2 is read as exactly that
//! multiple, and so is an axis within that angle of a coordinate axis, so that the symbolic
//! engine sees the exact zeros the file means. Every snap is listed in [`UrdfRobot::snaps`]
//! (and by `dhgen info`); a wider tolerance (`1e-4` reads `1.5708` as π/2) is an explicit
//! choice of the user.

use crate::raw::{LineIndex, Position, Table, Value};
use crate::validate::{self, ANGLE, FRICTION, INERTIA, LENGTH, MASS, Range};
use crate::{Angle, Frame, Inertial, LoadError, Pose, RobotModel};
use core::f64::consts::FRAC_PI_2;
use nalgebra::Vector3;
use std::collections::{HashMap, HashSet};

/// How to read a URDF file.
#[derive(Clone, Debug, PartialEq)]
pub struct UrdfOptions {
    /// The link where the chain starts (fixed in the world); `None`: the root link.
    pub base: Option<String>,
    /// The link where the chain ends; `None`: the one end of the file's movable joints.
    pub tip: Option<String>,
    /// Angles within this many radians of a multiple of π/2 (and axes within this angle of a
    /// coordinate axis) are read as exact; default [`UrdfOptions::DEFAULT_SNAP`]. From 0 (no
    /// snapping) to [`UrdfOptions::MAX_SNAP`]: [`read`] refuses anything else (NaN, a negative
    /// or an infinite tolerance) with an error rather than reading a different robot.
    pub snap: f64,
}

impl UrdfOptions {
    /// The default snapping tolerance, 1e-9 rad: decimals written to 10 or more significant
    /// digits snap, `1.5708` does not.
    pub const DEFAULT_SNAP: f64 = 1e-9;

    /// The widest snapping tolerance [`read`] accepts, 0.1 rad (5.7°): wide enough for any
    /// decimal a file writes for a quarter turn (`1.57` is 8e-4 rad off), narrow enough that
    /// the snap stays a reading of the file. At π/4 every angle would snap to a quarter turn,
    /// a different robot.
    pub const MAX_SNAP: f64 = 0.1;

    /// The rule for [`snap`](UrdfOptions::snap), the one every front end applies (this
    /// reader, `robot!`'s `snap = …`, `dhgen --snap`): a number from 0 to
    /// [`MAX_SNAP`](UrdfOptions::MAX_SNAP). This rejects NaN, which would silently disable
    /// snapping, and a negative tolerance, which would too. The error says the rule; the caller
    /// names the value where it was written.
    pub fn check_snap(snap: f64) -> Result<f64, String> {
        if (0.0..=UrdfOptions::MAX_SNAP).contains(&snap) {
            return Ok(snap);
        }
        Err(format!(
            "the tolerance for reading angles as exact quarter turns is in radians, from 0 to \
             {} (default {:e})",
            UrdfOptions::MAX_SNAP,
            UrdfOptions::DEFAULT_SNAP
        ))
    }
}

impl Default for UrdfOptions {
    fn default() -> Self {
        UrdfOptions {
            base: None,
            tip: None,
            snap: Self::DEFAULT_SNAP,
        }
    }
}

/// One value the reader read as exact: where, what the file says, and what was used.
#[derive(Clone, Debug, PartialEq)]
pub struct Snap {
    /// Line and column of the attribute.
    pub loc: Position,
    /// The element and attribute, e.g. ``joint `shoulder_lift_joint` <origin rpy> roll``.
    pub what: String,
    /// The value in the file (for an axis: its angle to the coordinate axis is `from − to`).
    pub from: f64,
    /// The exact value used.
    pub to: f64,
}

/// A movable joint of the chain as the file names it, with what the model does not hold.
#[derive(Clone, Debug, PartialEq)]
pub struct UrdfJoint {
    /// The joint's name.
    pub name: String,
    /// The link it moves.
    pub child: String,
    /// `<limit velocity>`, rad/s or m/s, when given.
    pub velocity: Option<f64>,
    /// `<limit effort>`, N·m or N, when given.
    pub effort: Option<f64>,
}

/// A URDF file read as a serial robot.
#[derive(Clone, Debug, PartialEq)]
pub struct UrdfRobot {
    /// The validated model.
    pub model: RobotModel,
    /// The chain's first link (fixed in the world).
    pub base: String,
    /// The chain's last link: the tool frame.
    pub tip: String,
    /// The robot's joints, base to tip.
    pub joints: Vec<UrdfJoint>,
    /// Movable joints off the chain, held at zero; their links' mass is merged into the body
    /// they hang from.
    pub locked: Vec<String>,
    /// Floating and planar joints off the chain: what they join is a free body (an object, a
    /// mobile base elsewhere in the file), not attached to the arm, so each is left out with
    /// everything below it (no mass merged, nothing held).
    pub left_out: Vec<String>,
    /// Links a joint moves that have no `<inertial>`, nor anything fixed to them, in a file
    /// where other links have one: read as massless, as Pinocchio and KDL read them (the
    /// virtual links between the axes of a spherical joint written as three revolute ones),
    /// and listed (by `dhgen info` too) in case one is an omission.
    pub massless: Vec<String>,
    /// Values read as exact quarter turns or coordinate axes.
    pub snaps: Vec<Snap>,
}

/// Reads URDF text; `origin` names the file in error messages.
///
/// Options are checked first: a [`UrdfOptions::snap`] outside 0 to
/// [`UrdfOptions::MAX_SNAP`] is an error.
pub fn read(text: &str, origin: &str, options: &UrdfOptions) -> Result<UrdfRobot, LoadError> {
    // Placed at the start of the text: it is about the options, not the file.
    UrdfOptions::check_snap(options.snap).map_err(|why| LoadError::Urdf {
        origin: origin.to_string(),
        loc: Position { line: 1, column: 1 },
        message: format!("snap = {:?}: {why}", options.snap),
    })?;
    let doc = roxmltree::Document::parse(text).map_err(|e| {
        let p = e.pos();
        LoadError::Urdf {
            origin: origin.to_string(),
            loc: Position {
                line: p.row as usize,
                column: p.col as usize,
            },
            message: format!("invalid XML: {e}"),
        }
    })?;
    Reader {
        origin,
        options,
        doc: &doc,
        lines: LineIndex::new(text),
        snaps: Vec::new(),
    }
    .robot()
}

impl RobotModel {
    /// Reads a URDF robot with the default options (see [`crate::urdf`]).
    pub fn from_urdf_str(text: &str) -> Result<RobotModel, LoadError> {
        read(text, "<string>", &UrdfOptions::default()).map(|r| r.model)
    }

    /// Reads a URDF file with the default options (see [`crate::urdf`]).
    pub fn from_urdf_file(path: impl AsRef<std::path::Path>) -> Result<RobotModel, LoadError> {
        read_file(path, &UrdfOptions::default()).map(|r| r.model)
    }
}

/// Reads a URDF file.
pub fn read_file(
    path: impl AsRef<std::path::Path>,
    options: &UrdfOptions,
) -> Result<UrdfRobot, LoadError> {
    let path = path.as_ref();
    let origin = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| LoadError::Io {
        origin: origin.clone(),
        source,
    })?;
    read_bytes(&bytes, &origin, options)
}

/// Reads URDF given as bytes (a file's contents); bytes that are not UTF-8 are an error at
/// the first one that is not.
pub fn read_bytes(
    bytes: &[u8],
    origin: &str,
    options: &UrdfOptions,
) -> Result<UrdfRobot, LoadError> {
    match core::str::from_utf8(bytes) {
        Ok(text) => read(text, origin, options),
        Err(e) => Err(LoadError::Urdf {
            origin: origin.to_string(),
            loc: crate::raw::utf8_error_position(bytes, &e),
            message: "the file is not UTF-8 text".into(),
        }),
    }
}

/// True for a file name that ends in `.urdf` (any case): what the command line and `robot!`
/// read as URDF rather than TOML.
pub fn is_urdf_path(path: &std::path::Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("urdf"))
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Revolute,
    Continuous,
    Prismatic,
    Fixed,
    Floating,
    Planar,
}

impl Kind {
    fn movable(self) -> bool {
        matches!(self, Kind::Revolute | Kind::Continuous | Kind::Prismatic)
    }
}

struct Link {
    name: String,
    loc: Position,
    inertial: Option<(Inertial, Position)>,
    /// What no body can have in its `<inertial>` (a negative mass, a tensor that is not
    /// positive semi-definite) and where: an error only if a moving body carries the link;
    /// the fixed base and the branches off the chain may hold anything.
    unphysical: Option<(Position, String)>,
}

struct Joint {
    name: String,
    loc: Position,
    kind: Kind,
    parent: usize,
    child: usize,
    origin: Frame<f64>,
    axis: (Vector3<f64>, Position),
    /// `<limit lower upper>`, each where it is written; held to the range of the joint's kind
    /// of quantity only on the chain (a joint off it is held at 0, its limits play no part).
    limits: Option<([(f64, Position); 2], Position)>,
    velocity: Option<f64>,
    effort: Option<f64>,
    /// `<dynamics damping friction>`, each where it is written (absent: 0, at the element).
    dynamics: Option<[(f64, Position); 2]>,
    mimic: bool,
}

struct Reader<'a> {
    origin: &'a str,
    options: &'a UrdfOptions,
    doc: &'a roxmltree::Document<'a>,
    /// Line starts of the text: roxmltree's own `text_pos_at` scans the text from its start
    /// on every call, which made reading a file quadratic in its size.
    lines: LineIndex<'a>,
    snaps: Vec<Snap>,
}

impl<'a> Reader<'a> {
    fn pos(&self, offset: usize) -> Position {
        self.lines.position(offset)
    }

    fn node_pos(&self, n: roxmltree::Node<'_, '_>) -> Position {
        self.pos(n.range().start)
    }

    fn err(&self, loc: Position, message: impl Into<String>) -> LoadError {
        LoadError::Urdf {
            origin: self.origin.to_string(),
            loc,
            message: message.into(),
        }
    }

    /// The attribute's value and position, if present.
    fn attr(&self, n: roxmltree::Node<'_, '_>, name: &str) -> Option<(String, Position)> {
        let a = n.attributes().find(|a| a.name() == name)?;
        Some((a.value().to_string(), self.pos(a.range().start)))
    }

    /// `N` numbers separated by spaces, finite and, with a `range`, within it (the ranges of
    /// the description format, so that the file is held to the rules of a TOML one).
    fn numbers<const N: usize>(
        &self,
        what: &str,
        value: &str,
        loc: Position,
        range: Option<Range>,
    ) -> Result<[f64; N], LoadError> {
        let parts: Vec<&str> = value.split_whitespace().collect();
        let bad = || {
            self.err(
                loc,
                format!(
                    "{what}: expected {N} number{}, found {value:?}",
                    if N == 1 { "" } else { "s" }
                ),
            )
        };
        if parts.len() != N {
            return Err(bad());
        }
        let mut out = [0.0; N];
        for (slot, part) in out.iter_mut().zip(&parts) {
            let x: f64 = part.parse().map_err(|_| bad())?;
            if !x.is_finite() {
                return Err(self.err(loc, format!("{what}: {part} is not a finite number")));
            }
            if let Some(range) = range {
                range
                    .check_value(x)
                    .map_err(|message| self.err(loc, format!("{what}: {message}")))?;
            }
            *slot = x;
        }
        Ok(out)
    }

    /// The number in attribute `name` of element `n` of `owner` (``joint `j1` ``), named in
    /// messages as URDF writes it: ``joint `j1` <limit lower>``.
    fn number_attr(
        &self,
        n: roxmltree::Node<'_, '_>,
        owner: &str,
        name: &str,
        range: Option<Range>,
    ) -> Result<Option<(f64, Position)>, LoadError> {
        match self.attr(n, name) {
            None => Ok(None),
            Some((v, loc)) => {
                let what = format!("{owner} <{} {name}>", n.tag_name().name());
                let [x] = self.numbers::<1>(&what, &v, loc, range)?;
                Ok(Some((x, loc)))
            }
        }
    }

    /// An angle, snapped to a multiple of π/2 within the tolerance.
    fn snap_angle(&mut self, x: f64, loc: Position, what: String) -> f64 {
        let k = (x / FRAC_PI_2).round();
        let exact = k * FRAC_PI_2;
        if x != exact && (x - exact).abs() <= self.options.snap && k.abs() < 1e6 {
            self.snaps.push(Snap {
                loc,
                what,
                from: x,
                to: exact,
            });
            exact
        } else {
            x
        }
    }

    /// `<origin xyz rpy>` of an element (identity when absent), rpy snapped.
    fn origin(
        &mut self,
        parent: roxmltree::Node<'_, '_>,
        what: &str,
    ) -> Result<Frame<f64>, LoadError> {
        let Some(o) = parent.children().find(|c| c.has_tag_name("origin")) else {
            return Ok(Frame::identity());
        };
        let xyz = match self.attr(o, "xyz") {
            Some((v, loc)) => {
                self.numbers::<3>(&format!("{what} <origin xyz>"), &v, loc, Some(LENGTH))?
            }
            None => [0.0; 3],
        };
        let rpy = match self.attr(o, "rpy") {
            Some((v, loc)) => {
                let raw =
                    self.numbers::<3>(&format!("{what} <origin rpy>"), &v, loc, Some(ANGLE))?;
                let names = ["roll", "pitch", "yaw"];
                let mut out = [0.0; 3];
                for i in 0..3 {
                    out[i] =
                        self.snap_angle(raw[i], loc, format!("{what} <origin rpy> {}", names[i]));
                }
                out
            }
            None => [0.0; 3],
        };
        Ok(Pose {
            xyz,
            rpy: rpy.map(Angle::from_radians),
        }
        .frame())
    }

    fn robot(mut self) -> Result<UrdfRobot, LoadError> {
        let root = self.doc.root_element();
        if !root.has_tag_name("robot") {
            return Err(self.err(
                self.node_pos(root),
                format!(
                    "the root element is <{}>; a URDF file is a <robot> element",
                    root.tag_name().name()
                ),
            ));
        }
        let name = self
            .attr(root, "name")
            .map_or_else(|| "robot".to_string(), |(n, _)| n.to_string());
        let (links, index) = self.links(root)?;
        let joints = self.joints(root, &links, &index)?;
        let robot = self.chain(&name, &links, &joints, &index)?;
        Ok(UrdfRobot {
            snaps: self.snaps,
            ..robot
        })
    }

    fn links(
        &mut self,
        root: roxmltree::Node<'a, 'a>,
    ) -> Result<(Vec<Link>, HashMap<String, usize>), LoadError> {
        let mut links = Vec::new();
        let mut index = HashMap::new();
        for n in root.children().filter(|c| c.has_tag_name("link")) {
            let loc = self.node_pos(n);
            let Some((name, _)) = self.attr(n, "name") else {
                return Err(self.err(loc, "a <link> without a `name` attribute"));
            };
            if index.insert(name.to_string(), links.len()).is_some() {
                return Err(self.err(loc, format!("link `{name}` is defined twice")));
            }
            let what = format!("link `{name}`");
            let (inertial, unphysical) = match n.children().find(|c| c.has_tag_name("inertial")) {
                None => (None, None),
                Some(i) => {
                    let (inertial, unphysical) = self.inertial(i, &what)?;
                    (Some((inertial, self.node_pos(i))), unphysical)
                }
            };
            links.push(Link {
                name: name.to_string(),
                loc,
                inertial,
                unphysical,
            });
        }
        if links.is_empty() {
            return Err(self.err(self.node_pos(root), "the robot has no <link>"));
        }
        Ok((links, index))
    }

    /// One `<inertial>`, expressed in its link's frame, with what makes it unphysical (a
    /// negative mass, a tensor that is not positive semi-definite) if anything does.
    fn inertial(
        &mut self,
        n: roxmltree::Node<'_, '_>,
        what: &str,
    ) -> Result<(Inertial, Option<(Position, String)>), LoadError> {
        let here = self.node_pos(n);
        let at = format!("{what} <inertial>");
        let origin = self.origin(n, &at)?;
        let mass_node = n
            .children()
            .find(|c| c.has_tag_name("mass"))
            .ok_or_else(|| self.err(here, format!("{at} has no <mass>")))?;
        let (mass, mass_loc) = self
            .number_attr(mass_node, &at, "value", Some(MASS))?
            .ok_or_else(|| {
                self.err(
                    self.node_pos(mass_node),
                    format!("{at} <mass> has no `value`"),
                )
            })?;
        let mut unphysical = validate::check_mass(mass)
            .err()
            .map(|message| (mass_loc, format!("{at} <mass value>: {message}")));
        let inertia_node = n
            .children()
            .find(|c| c.has_tag_name("inertia"))
            .ok_or_else(|| self.err(here, format!("{at} has no <inertia>")))?;
        // URDF requires all six (ROS's urdfdom rejects an <inertia> that lacks one): a
        // missing one is more likely an omission than a zero.
        let mut e = [0.0; 6];
        for (slot, key) in e.iter_mut().zip(["ixx", "iyy", "izz", "ixy", "iyz", "ixz"]) {
            *slot = self
                .number_attr(inertia_node, &at, key, Some(INERTIA))?
                .ok_or_else(|| {
                    self.err(
                        self.node_pos(inertia_node),
                        format!(
                            "{at} <inertia> has no `{key}`; URDF requires all six of ixx, ixy, \
                             ixz, iyy, iyz, izz (write 0 for a zero)"
                        ),
                    )
                })?
                .0;
        }
        let [xx, yy, zz, xy, yz, xz] = e;
        let tensor = [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]];
        if let Err(message) = validate::check_inertia_tensor(&tensor, mass, true) {
            unphysical.get_or_insert((
                self.node_pos(inertia_node),
                format!("{at} <inertia>: {message}"),
            ));
        }
        let inertial = Inertial {
            mass,
            com: [0.0; 3],
            inertia: tensor,
        };
        Ok((inertial.in_frame(&origin), unphysical))
    }

    fn joints(
        &mut self,
        root: roxmltree::Node<'a, 'a>,
        links: &[Link],
        index: &HashMap<String, usize>,
    ) -> Result<Vec<Joint>, LoadError> {
        let mut joints: Vec<Joint> = Vec::new();
        let mut names: HashSet<String> = HashSet::new();
        let mut parent_of: Vec<Option<usize>> = vec![None; links.len()];
        for n in root.children().filter(|c| c.has_tag_name("joint")) {
            let loc = self.node_pos(n);
            let Some((name, _)) = self.attr(n, "name") else {
                return Err(self.err(loc, "a <joint> without a `name` attribute"));
            };
            let what = format!("joint `{name}`");
            if !names.insert(name.clone()) {
                return Err(self.err(loc, format!("{what} is defined twice")));
            }
            let (kind_text, kind_loc) = self
                .attr(n, "type")
                .ok_or_else(|| self.err(loc, format!("{what} has no `type` attribute")))?;
            let kind = match kind_text.as_str() {
                "revolute" => Kind::Revolute,
                "continuous" => Kind::Continuous,
                "prismatic" => Kind::Prismatic,
                "fixed" => Kind::Fixed,
                "floating" => Kind::Floating,
                "planar" => Kind::Planar,
                other => {
                    return Err(self.err(
                        kind_loc,
                        format!(
                            "{what} has type {other:?}; URDF joint types are revolute, \
                             continuous, prismatic, fixed, floating and planar"
                        ),
                    ));
                }
            };
            let end = |tag: &str| -> Result<usize, LoadError> {
                let e = n
                    .children()
                    .find(|c| c.has_tag_name(tag))
                    .ok_or_else(|| self.err(loc, format!("{what} has no <{tag}>")))?;
                let (link, link_loc) = self.attr(e, "link").ok_or_else(|| {
                    self.err(self.node_pos(e), format!("{what} <{tag}> has no `link`"))
                })?;
                index.get(link.as_str()).copied().ok_or_else(|| {
                    self.err(
                        link_loc,
                        format!("{what} <{tag} link>: there is no link `{link}`"),
                    )
                })
            };
            let parent = end("parent")?;
            let child = end("child")?;
            if let Some(other) = parent_of[child] {
                return Err(self.err(
                    loc,
                    format!(
                        "{what} makes a closed chain: its child link `{}` is already the child \
                         of joint `{}`; dhgen reads trees (serial chains) only",
                        links[child].name, joints[other].name
                    ),
                ));
            }
            parent_of[child] = Some(joints.len());
            let origin = self.origin(n, &what)?;
            let axis = match n.children().find(|c| c.has_tag_name("axis")) {
                None => (Vector3::new(1.0, 0.0, 0.0), loc),
                Some(a) => {
                    let (v, aloc) = self.attr(a, "xyz").ok_or_else(|| {
                        self.err(self.node_pos(a), format!("{what} <axis> has no `xyz`"))
                    })?;
                    let u = Vector3::from(self.numbers::<3>(
                        &format!("{what} <axis xyz>"),
                        &v,
                        aloc,
                        None,
                    )?);
                    // The numbers are finite: a zero or tiny vector has no direction.
                    if kind.movable() && u.norm() <= validate::MIN_AXIS_LENGTH {
                        return Err(self.err(
                            aloc,
                            format!(
                                "{what} <axis xyz>: the axis {v:?} has no direction (its length \
                                 {} is at most {:e}); give a direction such as \"0 0 1\"",
                                validate::short(u.norm()),
                                validate::MIN_AXIS_LENGTH
                            ),
                        ));
                    }
                    (u, aloc)
                }
            };
            let limit = n.children().find(|c| c.has_tag_name("limit"));
            let mut limits = None;
            let (mut velocity, mut effort) = (None, None);
            if let Some(l) = limit {
                // Finite here; in the range of the joint's kind of quantity where the joint is
                // on the chain (`Reader::chain`).
                let lower = self.number_attr(l, &what, "lower", None)?;
                let upper = self.number_attr(l, &what, "upper", None)?;
                velocity = self.number_attr(l, &what, "velocity", None)?.map(|x| x.0);
                effort = self.number_attr(l, &what, "effort", None)?.map(|x| x.0);
                let lo = lower.map_or(0.0, |x| x.0);
                let hi = upper.map_or(0.0, |x| x.0);
                // URDF's defaults are 0 and 0: a joint whose limits are both absent or equal
                // has no position limits worth the name; a continuous joint has none at all.
                if kind != Kind::Continuous && (lower.is_some() || upper.is_some()) && lo != hi {
                    let lloc = lower.or(upper).map_or(loc, |x| x.1);
                    let at = |x: Option<(f64, Position)>| x.map_or(lloc, |x| x.1);
                    limits = Some(([(lo, at(lower)), (hi, at(upper))], lloc));
                }
            }
            let dynamics = match n.children().find(|c| c.has_tag_name("dynamics")) {
                None => None,
                Some(d) => {
                    let value = |name| -> Result<(f64, Position), LoadError> {
                        Ok(self
                            .number_attr(d, &what, name, Some(FRICTION))?
                            .unwrap_or((0.0, self.node_pos(d))))
                    };
                    Some([value("damping")?, value("friction")?])
                }
            };
            let mimic = n.children().any(|c| c.has_tag_name("mimic"));
            joints.push(Joint {
                name: name.to_string(),
                loc,
                kind,
                parent,
                child,
                origin,
                axis,
                limits,
                velocity,
                effort,
                dynamics,
                mimic,
            });
        }
        Ok(joints)
    }

    #[allow(clippy::type_complexity)]
    fn chain(
        &mut self,
        name: &str,
        links: &[Link],
        joints: &[Joint],
        index: &HashMap<String, usize>,
    ) -> Result<UrdfRobot, LoadError> {
        let first = self.node_pos(self.doc.root_element());
        let mut parent_joint: Vec<Option<usize>> = vec![None; links.len()];
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); links.len()];
        for (j, joint) in joints.iter().enumerate() {
            parent_joint[joint.child] = Some(j);
            children[joint.parent].push(j);
        }
        // The root: the one link no joint moves; a tree has exactly one, reaching every link.
        let roots: Vec<usize> = (0..links.len())
            .filter(|&l| parent_joint[l].is_none())
            .collect();
        let root = match roots.as_slice() {
            [r] => *r,
            [] => {
                return Err(self.err(
                    first,
                    "every link is the child of a joint: the joints form a cycle (a closed \
                     chain), which dhgen does not read",
                ));
            }
            many => {
                let names: Vec<&str> = many.iter().map(|&l| links[l].name.as_str()).collect();
                return Err(self.err(
                    links[many[1]].loc,
                    format!(
                        "the file holds {} separate trees (root links `{}`); a robot is one tree",
                        many.len(),
                        names.join("`, `")
                    ),
                ));
            }
        };
        // Depth from the root; a link the root does not reach sits on a cycle.
        let mut reached = vec![false; links.len()];
        // The links in depth-first order from the root: every link before its children.
        let mut order = Vec::with_capacity(links.len());
        let mut stack = vec![root];
        while let Some(l) = stack.pop() {
            reached[l] = true;
            order.push(l);
            stack.extend(children[l].iter().map(|&j| joints[j].child));
        }
        if let Some(l) = reached.iter().position(|r| !r) {
            let j = parent_joint[l].map_or(0, |j| j);
            return Err(self.err(
                joints[j].loc,
                format!(
                    "joint `{}` is part of a cycle (link `{}` is not reachable from the root \
                     `{}`): closed chains are not read",
                    joints[j].name, links[l].name, links[root].name
                ),
            ));
        }
        let link_named = |reader: &Self, n: &str, what: &str| {
            index.get(n).copied().ok_or_else(|| {
                let mut names: Vec<&str> = links.iter().map(|l| l.name.as_str()).collect();
                names.sort_unstable();
                reader.err(
                    first,
                    format!(
                        "{what} `{n}` is not a link of the file; its links are `{}`",
                        names.join("`, `")
                    ),
                )
            })
        };
        let base = match &self.options.base {
            Some(b) => link_named(self, b, "the base")?,
            None => root,
        };
        // Whether a movable joint is below each link decides the default tip; children first,
        // so each link is looked at once.
        let mut below_movable = vec![false; links.len()];
        for &l in order.iter().rev() {
            below_movable[l] = children[l]
                .iter()
                .any(|&j| joints[j].kind.movable() || below_movable[joints[j].child]);
        }
        let tip = match &self.options.tip {
            Some(t) => link_named(self, t, "the tip")?,
            None => {
                // Ends of the movable tree below the base: children of movable joints with no
                // movable joint below them.
                let mut ends = Vec::new();
                let mut stack = vec![base];
                while let Some(l) = stack.pop() {
                    for &j in &children[l] {
                        let c = joints[j].child;
                        if joints[j].kind.movable() && !below_movable[c] {
                            ends.push(c);
                        }
                        stack.push(c);
                    }
                }
                ends.sort_unstable();
                match ends.as_slice() {
                    // A flange or tool frame fixed below the end, alone, is the tip.
                    [t] => {
                        let mut t = *t;
                        while let [j] = children[t].as_slice()
                            && joints[*j].kind == Kind::Fixed
                        {
                            t = joints[*j].child;
                        }
                        t
                    }
                    [] => {
                        return Err(self.err(
                            links[base].loc,
                            format!(
                                "no movable joint below link `{}`: a robot needs at least one \
                                 revolute, continuous or prismatic joint",
                                links[base].name
                            ),
                        ));
                    }
                    many => {
                        let names: Vec<&str> =
                            many.iter().map(|&l| links[l].name.as_str()).collect();
                        return Err(self.err(
                            first,
                            format!(
                                "the file is a tree with {} ends ({}); name the end of the \
                                 chain with `tip`, e.g. tip = \"{}\"",
                                many.len(),
                                names
                                    .iter()
                                    .map(|n| format!("`{n}`"))
                                    .collect::<Vec<_>>()
                                    .join(", "),
                                names[0]
                            ),
                        ));
                    }
                }
            }
        };
        // The path base → tip, as joints.
        let mut path = Vec::new();
        let mut l = tip;
        while l != base {
            let Some(j) = parent_joint[l] else {
                return Err(self.err(
                    first,
                    format!(
                        "the tip `{}` is not below the base `{}`",
                        links[tip].name, links[base].name
                    ),
                ));
            };
            path.push(j);
            l = joints[j].parent;
        }
        path.reverse();
        let mut on_path = vec![false; joints.len()];
        for &j in &path {
            on_path[j] = true;
        }
        for &j in &path {
            let joint = &joints[j];
            let why = match joint.kind {
                Kind::Floating => Some("a floating joint (a free body)"),
                Kind::Planar => Some("a planar joint (three degrees of freedom)"),
                // A fixed joint has no value to follow: its `<mimic>` means nothing.
                _ if joint.mimic && joint.kind.movable() => {
                    Some("a mimic joint (its value follows another joint's)")
                }
                _ => None,
            };
            if let Some(why) = why {
                return Err(self.err(
                    joint.loc,
                    format!(
                        "joint `{}` on the chain from `{}` to `{}` is {why}; dhgen reads \
                         revolute, continuous, prismatic and fixed joints",
                        joint.name, links[base].name, links[tip].name
                    ),
                ));
            }
        }
        let moving: Vec<usize> = path
            .iter()
            .copied()
            .filter(|&j| joints[j].kind.movable())
            .collect();
        // Position limits in the range of the joint's kind of quantity, on the chain only.
        for &j in &moving {
            let joint = &joints[j];
            let range = if joint.kind == Kind::Prismatic {
                LENGTH
            } else {
                ANGLE
            };
            for ((x, at), side) in joint
                .limits
                .iter()
                .flat_map(|l| l.0)
                .zip(["lower", "upper"])
            {
                range.check_value(x).map_err(|message| {
                    self.err(
                        at,
                        format!(
                            "joint `{}` <limit {side}>: {message}{}",
                            joint.name,
                            if joint.kind == Kind::Prismatic {
                                ""
                            } else {
                                " (a joint that turns without limits is `continuous`)"
                            }
                        ),
                    )
                })?;
            }
        }
        if moving.is_empty() {
            return Err(self.err(
                links[tip].loc,
                format!(
                    "no movable joint between `{}` and `{}`",
                    links[base].name, links[tip].name
                ),
            ));
        }
        // Mass properties: each moving joint's child link with everything rigidly attached
        // to it (fixed joints, movable joints off the chain at q = 0), in its frame.
        let has_dynamics = links.iter().any(|l| l.inertial.is_some());
        let mut locked = Vec::new();
        let mut left_out = Vec::new();
        let mut massless = Vec::new();
        // Also the first link of the body whose `<inertial>` is unphysical, if any.
        let body = |start: usize, locked: &mut Vec<String>, left_out: &mut Vec<String>| {
            let mut total = Inertial {
                mass: 0.0,
                com: [0.0; 3],
                inertia: [[0.0; 3]; 3],
            };
            let mut any = false;
            let mut unphysical = None;
            let mut stack = vec![(start, Frame::identity())];
            while let Some((l, tf)) = stack.pop() {
                if let Some((m, _)) = &links[l].inertial {
                    total = total.combined(&m.in_frame(&tf));
                    any = true;
                }
                if unphysical.is_none() {
                    unphysical = links[l].unphysical.clone();
                }
                for &j in &children[l] {
                    match joints[j].kind {
                        _ if on_path[j] && joints[j].kind.movable() => continue,
                        // A free body (a floating or planar joint: an object, a mobile base
                        // elsewhere in the file) does not load the arm: it is not attached.
                        Kind::Floating | Kind::Planar => {
                            left_out.push(joints[j].name.clone());
                            continue;
                        }
                        Kind::Fixed => {}
                        Kind::Revolute | Kind::Continuous | Kind::Prismatic => {
                            locked.push(joints[j].name.clone());
                        }
                    }
                    stack.push((joints[j].child, tf.compose(&joints[j].origin)));
                }
            }
            (total, any, unphysical)
        };
        // The links above the first moving joint are the fixed base; their off-chain
        // movable joints are locked too (listed), their mass is not the robot's.
        let _ = body(base, &mut locked, &mut left_out);
        let mut bodies = Vec::new();
        for &j in &moving {
            let (m, any, unphysical) = body(joints[j].child, &mut locked, &mut left_out);
            if let Some((loc, message)) = unphysical {
                return Err(self.err(loc, message));
            }
            if has_dynamics && !any {
                massless.push(links[joints[j].child].name.clone());
            }
            bodies.push(m);
        }
        locked.sort();
        locked.dedup();
        left_out.sort();
        // The description tree: placements accumulate fixed joints up to each moving joint.
        let mut rows = Vec::new();
        let mut pending = Frame::identity();
        let mut k = 0;
        let mut out_joints = Vec::new();
        for &j in &path {
            let joint = &joints[j];
            pending = pending.compose(&joint.origin);
            if !joint.kind.movable() {
                continue;
            }
            let axis = self.snap_axis(joint.axis.0, joint.axis.1, &joint.name);
            rows.push(self.row(
                joint,
                &pending,
                axis,
                has_dynamics.then_some(&bodies[k]),
                links,
            ));
            out_joints.push(UrdfJoint {
                name: joint.name.clone(),
                child: links[joint.child].name.clone(),
                velocity: joint.velocity,
                effort: joint.effort,
            });
            pending = Frame::identity();
            k += 1;
        }
        let loc = first;
        let mut top = vec![
            ("name".to_string(), loc, Value::Str(name.to_string(), loc)),
            (
                "convention".to_string(),
                loc,
                Value::Str("urdf".into(), loc),
            ),
            (
                "allow_nonphysical_inertia".to_string(),
                loc,
                Value::Bool(true, loc),
            ),
        ];
        if !(pending.rotation_is_identity() && pending.p == [0.0; 3]) {
            top.push(("tool".to_string(), loc, pose_value(&pending, loc)));
        }
        // Gravity is URDF's usual [0, 0, −9.81] in the root link's frame; the description's
        // world is the base link's frame (the links above it are fixed in the world, with
        // every joint among them at 0), so a base turned against the root sees it turned.
        let mut placed = Frame::identity();
        let mut l = base;
        while let Some(j) = parent_joint[l] {
            placed = joints[j].origin.compose(&placed);
            l = joints[j].parent;
        }
        // g_base = Rᵀ g_root (+ 0.0 makes −0 zero).
        let g = validate::DEFAULT_GRAVITY;
        let gravity: [f64; 3] = core::array::from_fn(|c| {
            placed.r[0][c] * g[0] + placed.r[1][c] * g[1] + placed.r[2][c] * g[2] + 0.0
        });
        if gravity != g {
            let v = gravity.iter().map(|x| Value::Number(*x, loc)).collect();
            top.push(("gravity".to_string(), loc, Value::Array(v, loc)));
        }
        top.push(("links".to_string(), loc, Value::Array(rows, loc)));
        let table = Table { entries: top, loc };
        // The reader has checked every number of the file; what the validator still rejects
        // is a rule across values (limits in order, friction not negative) or a value the
        // reader derived (origins composed through fixed joints, merged mass properties):
        // named in URDF's terms.
        let model = validate::validate(&table, None).map_err(|e| {
            // Bullet reads `lower > upper` as a joint without limits, and its files use it.
            let hint = if e.field.as_deref() == Some("limits") && e.message.contains("not below") {
                ": write them in order, or leave out lower and upper for a joint without \
                 position limits (Bullet reads lower > upper as no limits; dhgen does not guess)"
            } else {
                ""
            };
            self.err(
                e.loc,
                format!("{}{}{hint}", urdf_terms(&e, &out_joints), e.message),
            )
        })?;
        Ok(UrdfRobot {
            model,
            base: links[base].name.clone(),
            tip: links[tip].name.clone(),
            joints: out_joints,
            locked,
            left_out,
            massless,
            snaps: Vec::new(),
        })
    }

    /// The axis, unit, snapped to a coordinate axis within the tolerance.
    fn snap_axis(&mut self, u: Vector3<f64>, loc: Position, joint: &str) -> [f64; 3] {
        let u = u / u.norm();
        let i = u.iamax();
        let mut e = Vector3::zeros();
        e[i] = u[i].signum();
        let angle = u.cross(&e).norm().atan2(u.dot(&e));
        if u != e && angle <= self.options.snap {
            self.snaps.push(Snap {
                loc,
                what: format!("joint `{joint}` <axis xyz>"),
                from: angle,
                to: 0.0,
            });
            e.into()
        } else {
            u.into()
        }
    }

    fn row(
        &self,
        joint: &Joint,
        origin: &Frame<f64>,
        axis: [f64; 3],
        mass: Option<&Inertial>,
        links: &[Link],
    ) -> Value<Position> {
        let loc = joint.loc;
        let num = |x: f64, l: Position| Value::Number(x, l);
        let vec = |v: &[f64], l: Position| Value::Array(v.iter().map(|x| num(*x, l)).collect(), l);
        let kind = match joint.kind {
            Kind::Prismatic => "prismatic",
            _ => "revolute",
        };
        let mut e = vec![
            ("joint".to_string(), loc, Value::Str(kind.into(), loc)),
            ("origin".to_string(), loc, pose_value(origin, loc)),
            ("axis".to_string(), joint.axis.1, vec(&axis, joint.axis.1)),
        ];
        if let Some(([(lo, _), (hi, _)], lloc)) = joint.limits {
            e.push(("limits".to_string(), lloc, vec(&[lo, hi], lloc)));
        }
        if let Some(m) = mass {
            let mloc = links[joint.child]
                .inertial
                .map_or(links[joint.child].loc, |i| i.1);
            e.push(("mass".to_string(), mloc, num(m.mass, mloc)));
            e.push(("com".to_string(), mloc, vec(&m.com, mloc)));
            let entries = m.inertia_fields();
            e.push((
                "inertia".to_string(),
                mloc,
                Value::Table(Table {
                    entries: entries
                        .iter()
                        .map(|(k, x)| (k.to_string(), mloc, num(*x, mloc)))
                        .collect(),
                    loc: mloc,
                }),
            ));
        }
        if let Some([(damping, dloc), (friction, floc)]) = joint.dynamics
            && (damping != 0.0 || friction != 0.0)
        {
            e.push((
                "friction".to_string(),
                dloc,
                Value::Table(Table {
                    entries: vec![
                        ("viscous".into(), dloc, num(damping, dloc)),
                        ("coulomb".into(), floc, num(friction, floc)),
                    ],
                    loc: dloc,
                }),
            ));
        }
        Value::Table(Table { entries: e, loc })
    }
}

/// Where a validation error of the description built from a URDF file is, in the file's
/// terms (``joint `j1` <dynamics damping>: ``) rather than the description's (`friction.viscous`).
/// The reader has checked every number of the file; what the validator still rejects is a rule
/// across values (limits in order, friction not negative) or a value the reader derived
/// (origins composed through fixed joints, mass properties merged), which this says.
fn urdf_terms(e: &validate::Error<Position>, joints: &[UrdfJoint]) -> String {
    let field = e.field.as_deref().unwrap_or("");
    let Some(joint) = e.link.and_then(|k| joints.get(k - 1)) else {
        return match field.strip_prefix("tool.") {
            Some(xyz) => format!(
                "<origin {xyz}> of the fixed joints after the last joint, composed (the tool \
                 frame): "
            ),
            None if field.is_empty() => String::new(),
            None => format!("{field}: "),
        };
    };
    let name = &joint.name;
    match field {
        "" => format!("joint `{name}`: "),
        "origin.xyz" | "origin.rpy" => format!(
            "joint `{name}` <origin {}> composed with the fixed joints before it: ",
            &field[7..]
        ),
        "axis" => format!("joint `{name}` <axis xyz>: "),
        "limits" => format!("joint `{name}` <limit lower upper>: "),
        "friction.viscous" => format!("joint `{name}` <dynamics damping>: "),
        "friction.coulomb" => format!("joint `{name}` <dynamics friction>: "),
        // The body the joint moves, merged: `mass`, `com`, `inertia`, `inertia.xy`.
        "mass" | "com" | "inertia" | "inertia.xx" | "inertia.yy" | "inertia.zz" | "inertia.xy"
        | "inertia.yz" | "inertia.xz" => format!(
            "joint `{name}`: link `{}` with the links fixed to it, {}: ",
            joint.child,
            field.replace("com", "centre of mass").replace('.', " ")
        ),
        other => format!("joint `{name}`: {other}: "),
    }
}

/// A transform as the description's `{ xyz, rpy }` table.
fn pose_value(t: &Frame<f64>, loc: Position) -> Value<Position> {
    let rpy = crate::model::rpy_of(&t.r);
    let v = |x: &[f64]| Value::Array(x.iter().map(|x| Value::Number(*x, loc)).collect(), loc);
    Value::Table(Table {
        entries: vec![("xyz".into(), loc, v(&t.p)), ("rpy".into(), loc, v(&rpy))],
        loc,
    })
}
