//! Validation: the raw description tree becomes a [`RobotModel`], or an [`Error`] naming
//! the link and the field at fault, located at the offending value.
//!
//! Every rule of the description format lives here, once, for both front ends.

use crate::raw::{Table, Value};
use crate::{
    Angle, Collision, Convention, Friction, Inertial, JointKind, Link, Motor, Placement, Pose,
    RobotModel,
};
use core::fmt;

/// A validation error at location `L` (`()` for files, a token span in the macro); displays as
/// `link N, field NAME: what is wrong`.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("{}{}", Context { link: *link, field: field.as_deref() }, OneLine(message))]
pub struct Error<L> {
    /// Where the offending value (or, for a missing field, its table) is.
    pub loc: L,
    /// 1-based link index, when the error is inside `links`.
    pub link: Option<usize>,
    /// The field, as a dotted path inside the link or the document (`inertia.xy`).
    pub field: Option<String>,
    /// What is wrong, for a person.
    pub message: String,
}

/// Text shown on one line: control characters (a newline in a quoted key or string of the
/// description) appear as escapes, `\n`.
pub struct OneLine<'a>(pub &'a str);

impl fmt::Display for OneLine<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for c in self.0.chars() {
            if c.is_control() {
                write!(f, "{}", c.escape_default())?;
            } else {
                write!(f, "{c}")?;
            }
        }
        Ok(())
    }
}

/// `link N, field NAME: ` (the parts that are known) in front of a validation message.
struct Context<'a> {
    link: Option<usize>,
    field: Option<&'a str>,
}

impl fmt::Display for Context<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.link, self.field) {
            (Some(l), Some(field)) => write!(f, "link {l}, field `{}`: ", OneLine(field)),
            (Some(l), None) => write!(f, "link {l}: "),
            (None, Some(field)) => write!(f, "field `{}`: ", OneLine(field)),
            (None, None) => Ok(()),
        }
    }
}

const TOP_FIELDS: &[&str] = &[
    "name",
    "description",
    "convention",
    "gravity",
    "base",
    "tool",
    "links",
    "allow_nonphysical_inertia",
];
/// A link's fields: `joint`, then those placing it (the DH four, or a `urdf` row's two),
/// then what every row may have.
const DH_FIELDS: &[&str] = &["joint", "a", "alpha", "d", "theta"];
const URDF_ROW_FIELDS: &[&str] = &["joint", "origin", "axis"];
const LINK_COMMON_FIELDS: &[&str] = &[
    "limits",
    "mass",
    "com",
    "inertia",
    "motor",
    "friction",
    "collision",
];
/// The inertia table's field names, those of [`Inertial::FIELDS`].
const INERTIA_FIELDS: [&str; 6] = {
    let mut out = [""; 6];
    let mut k = 0;
    while k < 6 {
        out[k] = Inertial::FIELDS[k].0;
        k += 1;
    }
    out
};

/// Where in the description we are: the link (if any) and the field path.
#[derive(Clone, Copy)]
struct At<'a> {
    link: Option<usize>,
    field: &'a str,
}

impl At<'_> {
    fn err<L: Clone>(&self, loc: &L, message: impl Into<String>) -> Error<L> {
        Error {
            loc: loc.clone(),
            link: self.link,
            field: (!self.field.is_empty()).then(|| self.field.to_string()),
            message: message.into(),
        }
    }
}

/// A table being read: checks for unknown keys up front, then hands out fields.
struct Fields<'t, L> {
    table: &'t Table<L>,
    link: Option<usize>,
    prefix: &'t str,
}

impl<'t, L: Clone> Fields<'t, L> {
    fn new(
        table: &'t Table<L>,
        link: Option<usize>,
        prefix: &'t str,
        allowed: &[&str],
    ) -> Result<Self, Error<L>> {
        for (i, (key, key_loc, _)) in table.entries.iter().enumerate() {
            let path = join(prefix, key);
            let at = At { link, field: &path };
            if !allowed.contains(&key.as_str()) {
                return Err(at.err(
                    key_loc,
                    format!(
                        "unknown field `{key}`{}; expected one of: {}",
                        suggestion(key, allowed),
                        allowed.join(", ")
                    ),
                ));
            }
            if table.entries[..i].iter().any(|(k, _, _)| k == key) {
                return Err(at.err(key_loc, format!("field `{key}` is given twice")));
            }
        }
        Ok(Fields {
            table,
            link,
            prefix,
        })
    }

    fn get(&self, key: &str) -> Option<&'t Value<L>> {
        self.table
            .entries
            .iter()
            .find(|(k, _, _)| k == key)
            .map(|(_, _, v)| v)
    }

    fn path(&self, key: &str) -> String {
        join(self.prefix, key)
    }

    fn required(&self, key: &str) -> Result<&'t Value<L>, Error<L>> {
        self.get(key).ok_or_else(|| {
            let path = self.path(key);
            At {
                link: self.link,
                field: &path,
            }
            .err(&self.table.loc, format!("missing required field `{key}`"))
        })
    }

    fn with<T>(
        &self,
        key: &str,
        read: impl FnOnce(At<'_>, &'t Value<L>) -> Result<T, Error<L>>,
    ) -> Result<Option<T>, Error<L>> {
        let path = self.path(key);
        let at = At {
            link: self.link,
            field: &path,
        };
        self.get(key).map(|v| read(at, v)).transpose()
    }

    fn with_required<T>(
        &self,
        key: &str,
        read: impl FnOnce(At<'_>, &'t Value<L>) -> Result<T, Error<L>>,
    ) -> Result<T, Error<L>> {
        let v = self.required(key)?;
        let path = self.path(key);
        read(
            At {
                link: self.link,
                field: &path,
            },
            v,
        )
    }
}

/// A value in a message: the shortest text that reads back as `x` (so that a value just past
/// a limit never prints as the limit), in scientific notation below 1e-4 and from 1e6 on
/// (`1e308`, not 309 digits). Every message that shows a number of the description, or one
/// computed from it, shows it this way.
pub(crate) fn short(x: f64) -> String {
    if x != 0.0 && x.is_finite() && !(1e-4..1e6).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// An angle in degrees to 6 significant digits, shown beside the exact radians for
/// orientation (`57.2958°`, not `57.29577951308232°`).
fn degrees(rad: f64) -> f64 {
    let deg = rad.to_degrees();
    format!("{deg:.5e}").parse().unwrap_or(deg)
}

/// " (did you mean `x`?)" when an allowed name is one or two edits away from `key`.
fn suggestion(key: &str, allowed: &[&str]) -> String {
    allowed
        .iter()
        .map(|name| (edit_distance(key, name), name))
        .filter(|(d, name)| *d <= 2 && *d < name.len())
        .min_by_key(|(d, _)| *d)
        .map(|(_, name)| format!(" (did you mean `{name}`?)"))
        .unwrap_or_default()
}

/// Levenshtein distance, by characters.
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let substitute = diagonal + usize::from(ca != *cb);
            diagonal = row[j + 1];
            row[j + 1] = substitute.min(row[j] + 1).min(diagonal + 1);
        }
    }
    row[b.len()]
}

fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

fn number<L: Clone>(at: At<'_>, v: &Value<L>) -> Result<f64, Error<L>> {
    match v {
        Value::Number(x, loc) if x.is_nan() => {
            Err(at.err(loc, "the value is NaN; give a finite number"))
        }
        Value::Number(x, loc) if x.is_infinite() => Err(at.err(
            loc,
            format!("the value is {}; give a finite number", short(*x)),
        )),
        Value::Number(x, _) => Ok(*x),
        Value::Expr(text, loc) => Err(at.err(
            loc,
            format!(
                "expected a number, found the expression `{text}`; write the number itself \
                 (only angles may be expressions, such as `PI / 2` or `90 deg`)"
            ),
        )),
        other => Err(at.err(
            other.loc(),
            format!("expected a number, found {}", other.kind()),
        )),
    }
}

/// The range of one kind of quantity: magnitudes beyond `max` belong to no robot, and
/// accepting them would only let arithmetic overflow later (1e308 squared is infinite).
/// The ranges are generous by orders of magnitude and listed in docs/robot-description.md.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Range {
    /// What the quantity is, for messages ("length").
    pub what: &'static str,
    /// Its unit ("m").
    pub unit: &'static str,
    /// The largest magnitude accepted.
    pub max: f64,
    /// The smallest non-zero magnitude accepted (0 when any is).
    pub min: f64,
}

impl Range {
    /// Magnitudes from 0 to `max`.
    const fn up_to(what: &'static str, unit: &'static str, max: f64) -> Range {
        Range {
            what,
            unit,
            max,
            min: 0.0,
        }
    }

    fn check<L: Clone>(self, at: At<'_>, loc: &L, x: f64) -> Result<f64, Error<L>> {
        self.check_value(x).map_err(|message| at.err(loc, message))
    }

    /// The range rule on a value `x`, as a message: `x`, or why it is outside the range (NaN
    /// is). The validator, the URDF reader and run-time values held to the description's
    /// ranges (`dhgen::payload::Payload::new`) apply it through here.
    pub fn check_value(self, x: f64) -> Result<f64, String> {
        let m = x.abs();
        if m.is_nan() || m > self.max || (m < self.min && m != 0.0) {
            let unit = if self.unit.is_empty() {
                String::new()
            } else {
                format!(" {}", self.unit)
            };
            let bounds = if self.min > 0.0 {
                format!("{:e} to {:e}", self.min, self.max)
            } else {
                format!("at most {:e}", self.max)
            };
            return Err(format!(
                "{} {}{unit} is outside the range of any robot (magnitude {bounds}{unit}; \
                 see \"Ranges\" in docs/robot-description.md)",
                self.what,
                short(x),
            ));
        }
        Ok(x)
    }
}

/// Lengths: `a`, `d`, `com`, `xyz`, prismatic limits, collision radii.
pub const LENGTH: Range = Range::up_to("length", "m", 1e3);
/// Angles: `alpha`, `theta`, `rpy`, revolute limits (1000 rad is 159 turns).
pub const ANGLE: Range = Range::up_to("angle", "rad", 1e3);
/// Link masses.
pub const MASS: Range = Range::up_to("mass", "kg", 1e6);
/// Entries of an inertia tensor.
pub const INERTIA: Range = Range::up_to("inertia", "kg·m²", 1e9);
/// `gravity` where a description gives none: 9.81 m/s² down the world frame's z axis (also
/// URDF's, which has no gravity of its own, in the root link's frame).
pub const DEFAULT_GRAVITY: [f64; 3] = [0.0, 0.0, -9.81];

/// Components of `gravity`.
pub const GRAVITY: Range = Range::up_to("gravity component", "m/s²", 1e3);
/// Rotor inertias of motors.
pub const ROTOR_INERTIA: Range = Range::up_to("rotor inertia", "kg·m²", 1e3);
/// Gear ratios (non-zero; a ratio below 1e-6 or above 1e6 is a typing error).
pub const GEAR_RATIO: Range = Range {
    what: "gear ratio",
    unit: "",
    max: 1e6,
    min: 1e-6,
};
/// Friction coefficients (N·m·s/rad and N·m, or N·s/m and N).
pub const FRICTION: Range = Range::up_to("friction coefficient", "", 1e6);

/// A finite number within `range`.
fn quantity<L: Clone>(at: At<'_>, v: &Value<L>, range: Range) -> Result<f64, Error<L>> {
    let x = number(at, v)?;
    range.check(at, v.loc(), x)
}

fn length<L: Clone>(at: At<'_>, v: &Value<L>) -> Result<f64, Error<L>> {
    quantity(at, v, LENGTH)
}

fn angle<L: Clone>(at: At<'_>, v: &Value<L>) -> Result<Angle, Error<L>> {
    let a = angle_value(at, v)?;
    ANGLE.check(at, v.loc(), a.radians())?;
    Ok(a)
}

fn angle_value<L: Clone>(at: At<'_>, v: &Value<L>) -> Result<Angle, Error<L>> {
    match v {
        Value::Str(s, loc) | Value::Expr(s, loc) => Angle::parse(s).map_err(|m| at.err(loc, m)),
        Value::Number(..) => number(at, v).map(Angle::from_radians),
        other => Err(at.err(
            other.loc(),
            format!(
                "expected an angle (a number in radians or a string like \"90deg\"), found {}",
                other.kind()
            ),
        )),
    }
}

fn string<L: Clone>(at: At<'_>, v: &Value<L>) -> Result<String, Error<L>> {
    match v {
        Value::Str(s, _) => Ok(s.clone()),
        other => Err(at.err(
            other.loc(),
            format!("expected a string, found {}", other.kind()),
        )),
    }
}

/// One of a fixed set of keywords (`what`, e.g. "joint type"): a string in TOML, a bare
/// word in the macro. Returns the index of the keyword in `choices`.
fn keyword<L: Clone>(
    at: At<'_>,
    v: &Value<L>,
    what: &str,
    choices: &[&str],
) -> Result<usize, Error<L>> {
    let expected = choices
        .iter()
        .map(|c| format!("`{c}`"))
        .collect::<Vec<_>>()
        .join(" or ");
    match v {
        Value::Str(s, loc) | Value::Word(s, loc) => choices
            .iter()
            .position(|c| c == s)
            .ok_or_else(|| at.err(loc, format!("unknown {what} `{s}`; expected {expected}"))),
        other => Err(at.err(
            other.loc(),
            format!("expected the {what} ({expected}), found {}", other.kind()),
        )),
    }
}

fn array<'v, L: Clone>(
    at: At<'_>,
    v: &'v Value<L>,
    len: usize,
) -> Result<&'v [Value<L>], Error<L>> {
    match v {
        Value::Array(items, _) if items.len() == len => Ok(items),
        Value::Array(items, loc) => Err(at.err(
            loc,
            format!("expected {len} elements, found {}", items.len()),
        )),
        other => Err(at.err(
            other.loc(),
            format!(
                "expected an array of {len} elements, found {}",
                other.kind()
            ),
        )),
    }
}

fn vec3<L: Clone>(at: At<'_>, v: &Value<L>, range: Range) -> Result<[f64; 3], Error<L>> {
    let items = array(at, v, 3)?;
    Ok([
        quantity(at, &items[0], range)?,
        quantity(at, &items[1], range)?,
        quantity(at, &items[2], range)?,
    ])
}

fn table<'v, L: Clone>(at: At<'_>, v: &'v Value<L>) -> Result<&'v Table<L>, Error<L>> {
    match v {
        Value::Table(t) => Ok(t),
        other => Err(at.err(
            other.loc(),
            format!("expected a table, found {}", other.kind()),
        )),
    }
}

fn boolean<L: Clone>(at: At<'_>, v: &Value<L>) -> Result<bool, Error<L>> {
    match v {
        Value::Bool(b, _) => Ok(*b),
        other => Err(at.err(
            other.loc(),
            format!("expected true or false, found {}", other.kind()),
        )),
    }
}

fn pose<L: Clone>(at: At<'_>, v: &Value<L>) -> Result<Pose, Error<L>> {
    let t = table(at, v)?;
    let f = Fields::new(t, at.link, at.field, &["xyz", "rpy"])?;
    let xyz = f
        .with("xyz", |at, v| vec3(at, v, LENGTH))?
        .unwrap_or([0.0; 3]);
    let rpy = f
        .with("rpy", |at, v| {
            let items = array(at, v, 3)?;
            Ok([
                angle(at, &items[0])?,
                angle(at, &items[1])?,
                angle(at, &items[2])?,
            ])
        })?
        .unwrap_or([Angle::ZERO; 3]);
    Ok(Pose { xyz, rpy })
}

/// Builds and validates a robot from its description tree.
///
/// `default_name` stands in for a missing `name` (the macro passes the module's name).
pub fn validate<L: Clone>(
    root: &Table<L>,
    default_name: Option<&str>,
) -> Result<RobotModel, Error<L>> {
    let f = Fields::new(root, None, "", TOP_FIELDS)?;
    let name = match (f.with("name", string)?, default_name) {
        (Some(n), _) => n,
        (None, Some(d)) => d.to_string(),
        (None, None) => f.with_required("name", string)?,
    };
    let description = f.with("description", string)?;
    let convention = f.with_required("convention", |at, v| {
        let conventions = [Convention::Standard, Convention::Modified, Convention::Urdf];
        keyword(at, v, "convention", &["standard", "modified", "urdf"]).map(|i| conventions[i])
    })?;
    let gravity = f
        .with("gravity", |at, v| vec3(at, v, GRAVITY))?
        .unwrap_or(DEFAULT_GRAVITY);
    let base = f.with("base", pose)?;
    let tool = f.with("tool", pose)?;
    let allow_nonphysical = f
        .with("allow_nonphysical_inertia", boolean)?
        .unwrap_or(false);
    let links = f.with_required("links", |at, v| match v {
        Value::Array(items, loc) => {
            if items.is_empty() {
                return Err(at.err(loc, "the robot has zero links; give at least one"));
            }
            items
                .iter()
                .enumerate()
                .map(|(i, item)| link(i + 1, item, convention, allow_nonphysical))
                .collect::<Result<Vec<_>, _>>()
        }
        other => Err(at.err(
            other.loc(),
            format!("expected an array of link tables, found {}", other.kind()),
        )),
    })?;
    // Dynamics are all or nothing: a link silently treated as massless would be a bug.
    if let Some(with) = links.iter().position(|l| l.inertial.is_some())
        && let Some(without) = links.iter().position(|l| l.inertial.is_none())
    {
        let Value::Array(items, _) = f.required("links")? else {
            unreachable!("links was read as an array above")
        };
        return Err(Error {
            loc: items[without].loc().clone(),
            link: Some(without + 1),
            field: Some("mass".into()),
            message: format!(
                "this link has no `mass`, `com` and `inertia` but link {} has them; \
                     give every link its mass properties, or none",
                with + 1
            ),
        });
    }
    Ok(RobotModel {
        name,
        description,
        convention,
        gravity,
        base,
        tool,
        links,
    })
}

fn link<L: Clone>(
    index: usize,
    v: &Value<L>,
    convention: Convention,
    allow_nonphysical: bool,
) -> Result<Link, Error<L>> {
    let at = At {
        link: Some(index),
        field: "",
    };
    let t = table(at, v)?;
    let urdf = convention == Convention::Urdf;
    let placing = if urdf { URDF_ROW_FIELDS } else { DH_FIELDS };
    let allowed: Vec<&str> = placing.iter().chain(LINK_COMMON_FIELDS).copied().collect();
    let f = Fields::new(t, Some(index), "", &allowed)?;
    let joint = f.with_required("joint", |at, v| {
        let kinds = [JointKind::Revolute, JointKind::Prismatic];
        keyword(at, v, "joint type", &["revolute", "prismatic"]).map(|i| kinds[i])
    })?;
    let (a, alpha, d, theta, placement) = if urdf {
        let origin = f.with("origin", pose)?.unwrap_or(Pose {
            xyz: [0.0; 3],
            rpy: [Angle::ZERO; 3],
        });
        let axis = f
            .with("axis", |at, v| unit_axis(at, v))?
            .unwrap_or([0.0, 0.0, 1.0]);
        (
            0.0,
            Angle::ZERO,
            0.0,
            Angle::ZERO,
            Some(Placement { origin, axis }),
        )
    } else {
        (
            f.with_required("a", length)?,
            f.with_required("alpha", angle)?,
            f.with_required("d", length)?,
            f.with_required("theta", angle)?,
            None,
        )
    };
    let limits = f.with("limits", |at, v| {
        let items = array(at, v, 2)?;
        let bound = |item: &Value<L>| match joint {
            JointKind::Revolute => angle(at, item).map(Angle::radians),
            JointKind::Prismatic => length(at, item),
        };
        let (lo, hi) = (bound(&items[0])?, bound(&items[1])?);
        if lo >= hi {
            return Err(at.err(
                v.loc(),
                match joint {
                    JointKind::Revolute => format!(
                        "lower limit {} rad ({}°) is not below upper limit {} rad ({}°)",
                        short(lo),
                        short(degrees(lo)),
                        short(hi),
                        short(degrees(hi))
                    ),
                    JointKind::Prismatic => format!(
                        "lower limit {} m is not below upper limit {} m",
                        short(lo),
                        short(hi)
                    ),
                },
            ));
        }
        Ok([lo, hi])
    })?;
    let inertial = inertial(&f, allow_nonphysical)?;
    let motor = f.with("motor", |at, v| {
        let m = Fields::new(table(at, v)?, at.link, at.field, &["inertia", "gear"])?;
        let inertia = m.with_required("inertia", |at, v| {
            let x = quantity(at, v, ROTOR_INERTIA)?;
            if x < 0.0 {
                return Err(at.err(v.loc(), format!("rotor inertia {} is negative", short(x))));
            }
            Ok(x)
        })?;
        let gear = m.with_required("gear", |at, v| {
            let g = number(at, v)?;
            if g == 0.0 {
                return Err(at.err(v.loc(), "gear ratio is 0; it must be non-zero"));
            }
            GEAR_RATIO.check(at, v.loc(), g)
        })?;
        Ok(Motor { inertia, gear })
    })?;
    let friction = f.with("friction", |at, v| {
        let m = Fields::new(table(at, v)?, at.link, at.field, &["viscous", "coulomb"])?;
        let coefficient = |at: At<'_>, v: &Value<L>| {
            let x = quantity(at, v, FRICTION)?;
            if x < 0.0 {
                return Err(at.err(
                    v.loc(),
                    format!("friction coefficient {} is negative", short(x)),
                ));
            }
            Ok(x)
        };
        Ok(Friction {
            viscous: m.with("viscous", coefficient)?.unwrap_or(0.0),
            coulomb: m.with("coulomb", coefficient)?.unwrap_or(0.0),
        })
    })?;
    let collision = f.with("collision", |at, v| {
        let c = Fields::new(table(at, v)?, at.link, at.field, &["radius"])?;
        let radius = c.with_required("radius", |at, v| {
            let r = length(at, v)?;
            if r <= 0.0 {
                return Err(at.err(
                    v.loc(),
                    format!(
                        "collision radius {} is not positive; give a radius > 0 in m",
                        short(r)
                    ),
                ));
            }
            Ok(r)
        })?;
        Ok(Collision { radius })
    })?;
    Ok(Link {
        joint,
        a,
        alpha,
        d,
        theta,
        limits,
        inertial,
        motor,
        friction,
        collision,
        placement,
    })
}

/// The shortest joint axis read as a direction: a shorter one is taken for a zero written
/// with round-off (the description's `axis`, URDF's `<axis xyz>`).
pub const MIN_AXIS_LENGTH: f64 = 1e-9;

/// A joint axis: three numbers longer than [`MIN_AXIS_LENGTH`], scaled to unit length (a
/// signed coordinate axis stays exact).
fn unit_axis<L: Clone>(at: At<'_>, v: &Value<L>) -> Result<[f64; 3], Error<L>> {
    let u = vec3(at, v, LENGTH)?;
    let norm = (u[0] * u[0] + u[1] * u[1] + u[2] * u[2]).sqrt();
    // The components are finite (checked by `vec3`).
    if norm <= MIN_AXIS_LENGTH {
        return Err(at.err(
            v.loc(),
            format!(
                "the axis [{}, {}, {}] has no direction (its length {} is at most {:e}); give \
                 a direction such as [0, 0, 1]",
                short(u[0]),
                short(u[1]),
                short(u[2]),
                short(norm),
                MIN_AXIS_LENGTH
            ),
        ));
    }
    Ok(u.map(|x| x / norm))
}

fn inertial<L: Clone>(
    f: &Fields<'_, L>,
    allow_nonphysical: bool,
) -> Result<Option<Inertial>, Error<L>> {
    let mass = f.with("mass", |at, v| {
        let m = quantity(at, v, MASS)?;
        check_mass(m).map_err(|message| at.err(v.loc(), message))?;
        Ok(m)
    })?;
    let com = f.with("com", |at, v| vec3(at, v, LENGTH))?;
    let inertia = f.with("inertia", |at, v| {
        let t = table(at, v)?;
        let fields = Fields::new(t, at.link, at.field, &INERTIA_FIELDS)?;
        let mut tensor = [[0.0; 3]; 3];
        for (key, [a, b]) in Inertial::FIELDS {
            let x = fields
                .with(key, |at, v| quantity(at, v, INERTIA))?
                .unwrap_or(0.0);
            tensor[a][b] = x;
            tensor[b][a] = x;
        }
        check_inertia(
            at,
            t.loc.clone(),
            &tensor,
            mass.unwrap_or(0.0),
            allow_nonphysical,
        )?;
        Ok(tensor)
    })?;
    let group = ["mass", "com", "inertia"];
    let present = [mass.is_some(), com.is_some(), inertia.is_some()];
    match (mass, com, inertia) {
        (Some(mass), Some(com), Some(inertia)) => Ok(Some(Inertial { mass, com, inertia })),
        (None, None, None) => Ok(None),
        _ => {
            let given = group
                .iter()
                .zip(present)
                .filter(|(_, p)| *p)
                .map(|(g, _)| *g)
                .collect::<Vec<_>>();
            let missing = group
                .iter()
                .zip(present)
                .find(|(_, p)| !*p)
                .map(|(g, _)| *g)
                .unwrap_or("mass");
            let loc = f
                .get(given[0])
                .map(|v| v.loc().clone())
                .unwrap_or_else(|| f.table.loc.clone());
            Err(Error {
                loc,
                link: f.link,
                field: Some(missing.to_string()),
                message: format!(
                    "`{}` is given but `{missing}` is missing: mass, com and inertia go together",
                    given.join("`, `")
                ),
            })
        }
    }
}

/// The principal moments of the tensor of a body of mass `mass`, ascending, and the tolerance
/// the checks use: a billionth of the largest moment, and at least the moment of `mass` at a
/// micrometre (exporters write round-off such as `ixx="-5.42101e-20"` for a zero moment of a
/// half-kilogram link; a real moment that small is below anything a robot can resolve).
fn principal_moments(tensor: &[[f64; 3]; 3], mass: f64) -> ([f64; 3], f64) {
    let m = nalgebra::Matrix3::from_fn(|i, j| tensor[i][j]);
    let mut e = m.symmetric_eigenvalues();
    e.as_mut_slice().sort_by(f64::total_cmp);
    let scale = e.amax().max(f64::MIN_POSITIVE);
    ([e[0], e[1], e[2]], (1e-9 * scale).max(mass * 1e-12))
}

/// Whether the principal moments of a body of mass `mass` obey the triangle inequality (the
/// rule `allow_nonphysical_inertia` lifts).
pub fn obeys_triangle_inequality(tensor: &[[f64; 3]; 3], mass: f64) -> bool {
    let (e, tol) = principal_moments(tensor, mass);
    e[0] + e[1] >= e[2] - tol
}

/// The rule for a mass: in [`MASS`]'s range and not negative (zero is a massless link).
pub fn check_mass(m: f64) -> Result<(), String> {
    if !m.is_finite() {
        return Err(format!("mass {} is not a finite number", short(m)));
    }
    if m < 0.0 {
        return Err(format!("mass {} is negative", short(m)));
    }
    MASS.check_value(m).map(drop)
}

/// Principal moments must be non-negative (positive semi-definite) and obey the triangle
/// inequality, unless the description explicitly allows published non-physical values.
fn check_inertia<L: Clone>(
    at: At<'_>,
    loc: L,
    tensor: &[[f64; 3]; 3],
    mass: f64,
    allow_nonphysical: bool,
) -> Result<(), Error<L>> {
    check_inertia_tensor(tensor, mass, allow_nonphysical).map_err(|message| {
        let hint = if message.contains("triangle") {
            "; set `allow_nonphysical_inertia = true` at the top level to accept published values like these"
        } else {
            ""
        };
        at.err(&loc, format!("{message}{hint}"))
    })
}

/// The rule for the inertia tensor of a body of mass `mass` about its centre of mass, as a
/// message: finite entries, positive semi-definite, and (unless `allow_nonphysical`) the
/// triangle inequality, each to a billionth of the largest principal moment and at least to
/// the moment of `mass` at a micrometre (round-off such as `-5.42101e-20` in an exported file
/// passes; a negative moment a robot could feel does not).
///
/// ```
/// use dhgen_description::validate::check_inertia_tensor;
/// let rod = [[0.02, 0.0, 0.0], [0.0, 0.02, 0.0], [0.0, 0.0, 0.0]];
/// assert!(check_inertia_tensor(&rod, 1.0, false).is_ok());
/// let round_off = [[-5.42101e-20, 0.0, 0.0], [0.0, -5.42101e-20, 0.0], [0.0, 0.0, 0.0]];
/// assert!(check_inertia_tensor(&round_off, 0.526, false).is_ok());
/// let impossible = [[-1e-4, 0.0, 0.0], [0.0, 0.02, 0.0], [0.0, 0.0, 0.02]];
/// assert!(check_inertia_tensor(&impossible, 1.0, true).is_err());
/// ```
pub fn check_inertia_tensor(
    tensor: &[[f64; 3]; 3],
    mass: f64,
    allow_nonphysical: bool,
) -> Result<(), String> {
    for (key, [a, b]) in Inertial::FIELDS {
        for x in [tensor[a][b], tensor[b][a]] {
            if !x.is_finite() {
                return Err(format!(
                    "inertia entry `{key}` is {}; give a finite number",
                    short(x)
                ));
            }
            INERTIA
                .check_value(x)
                .map_err(|message| format!("inertia entry `{key}`: {message}"))?;
        }
    }
    let (e, tol) = principal_moments(tensor, mass);
    if e[0] < -tol {
        return Err(format!(
            "inertia tensor is not positive semi-definite (principal moments {}, {}, {})",
            short(e[0]),
            short(e[1]),
            short(e[2])
        ));
    }
    if !allow_nonphysical && !obeys_triangle_inequality(tensor, mass) {
        return Err(format!(
            "principal moments {a}, {b}, {c} violate the triangle inequality ({a} + {b} < {c})",
            a = short(e[0]),
            b = short(e[1]),
            c = short(e[2])
        ));
    }
    Ok(())
}
