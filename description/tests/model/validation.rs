//! Every rule of the description format: one test per kind of error, each checking that
//! the message names the file, the line and column, the link (1-based) and the field.

use dhgen_description::raw::{Position, Table, Value};
use dhgen_description::{LoadError, RobotModel, validate};

const FILE: &str = "robots/bad.toml";

/// A valid kinematic link.
const LINK: &str = r#"joint = "revolute"
a = 0.5
alpha = "90deg"
d = 0.1
theta = 0
"#;

/// Valid mass properties of a slender rod along x.
const MASS: &str = r#"mass = 2.0
com = [-0.25, 0.0, 0.0]
inertia = { xx = 0.001, yy = 0.04, zz = 0.04 }
"#;

/// A robot: `top` lines after the required top-level fields, then one table per link.
fn robot(top: &str, links: &[&str]) -> String {
    let mut text = format!("name = \"bad\"\nconvention = \"standard\"\n{top}");
    for link in links {
        text.push_str("\n[[links]]\n");
        text.push_str(link);
    }
    text
}

/// A link with mass properties, plus `extra` lines.
fn massive(extra: &str) -> String {
    format!("{LINK}{MASS}{extra}")
}

/// `line:column` (1-based, columns in characters) of the `nth` (1-based) occurrence of
/// `needle` in `text`: where the error must point.
fn position_of(text: &str, needle: &str, nth: usize) -> String {
    let (offset, _) = text
        .match_indices(needle)
        .nth(nth - 1)
        .unwrap_or_else(|| panic!("{needle:?} does not occur {nth} times in\n{text}"));
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().unwrap_or("").chars().count() + 1;
    format!("{line}:{column}")
}

/// The rule violation `text` must be rejected with.
fn rejection(text: &str) -> (validate::Error<Position>, String) {
    match RobotModel::from_toml_named(text, FILE) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => match &e {
            LoadError::Invalid { error, .. } => (error.clone(), e.to_string()),
            other => panic!("expected a validation error, got {other:?}:\n{e}"),
        },
    }
}

/// Asserts that `text` is rejected at the `nth` occurrence of `needle`, in `link`, naming
/// `field`, with a message containing `what`.
fn check(text: &str, needle: &str, nth: usize, link: Option<usize>, field: &str, what: &str) {
    let (error, shown) = rejection(text);
    let place = match link {
        Some(n) => format!("link {n}, field `{field}`: "),
        None => format!("field `{field}`: "),
    };
    let expected = format!("{FILE}:{}: {place}", position_of(text, needle, nth));
    assert!(
        shown.starts_with(&expected),
        "message {shown:?} should start with {expected:?}; text:\n{text}"
    );
    assert!(
        shown.contains(what),
        "message {shown:?} should say {what:?}"
    );
    assert_eq!(error.link, link, "{shown}");
    assert_eq!(error.field.as_deref(), Some(field), "{shown}");
}

#[test]
fn the_helpers_build_a_valid_robot() {
    let text = robot("", &[LINK, LINK, LINK]);
    let model = RobotModel::from_toml_named(&text, FILE).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(model.dof(), 3);
    let link = massive("");
    let text = robot("", &[&link, &link, &link]);
    let model = RobotModel::from_toml_named(&text, FILE).unwrap_or_else(|e| panic!("{e}"));
    assert!(model.has_dynamics());
}

#[test]
fn missing_required_top_level_field() {
    let full = robot("", &[LINK]);
    for (line, field) in [
        ("name = \"bad\"\n", "name"),
        ("convention = \"standard\"\n", "convention"),
    ] {
        let text = full.replacen(line, "", 1);
        // A missing field has no place of its own: the error points at its table, here
        // the document, which starts at 1:1.
        check(
            &text,
            "",
            1,
            None,
            field,
            &format!("missing required field `{field}`"),
        );
    }
    let text = "name = \"bad\"\nconvention = \"standard\"\n";
    check(text, "", 1, None, "links", "missing required field `links`");
}

#[test]
fn missing_required_link_field() {
    for field in ["joint", "a", "alpha", "d", "theta"] {
        let prefix = format!("{field} = ");
        let without: String = LINK
            .lines()
            .filter(|l| !l.starts_with(&prefix))
            .map(|l| format!("{l}\n"))
            .collect();
        let text = robot("", &[LINK, LINK, &without]);
        check(
            &text,
            "[[links]]",
            3,
            Some(3),
            field,
            &format!("missing required field `{field}`"),
        );
    }
    // Inside a link's table: the motor needs both numbers.
    let text = robot(
        "",
        &[LINK, &format!("{LINK}motor = {{ inertia = 1e-4 }}\n")],
    );
    check(
        &text,
        "{ inertia",
        1,
        Some(2),
        "motor.gear",
        "missing required field `gear`",
    );
}

#[test]
fn unknown_top_level_field() {
    let text = robot("colour = \"red\"\n", &[LINK]);
    check(
        &text,
        "colour",
        1,
        None,
        "colour",
        "unknown field `colour`; expected one of: name,",
    );
    // `link` for `links` is the likely typo.
    let text = robot("", &[LINK]).replace("[[links]]", "[[link]]");
    check(&text, "link]]", 1, None, "link", "unknown field `link`");
}

#[test]
fn unknown_link_field() {
    // Of two unknown fields the first in the text is reported, not the first in
    // alphabetical order.
    let text = robot("", &[LINK, &format!("{LINK}weight = 1\ncolour = 2\n")]);
    check(
        &text,
        "weight",
        1,
        Some(2),
        "weight",
        "unknown field `weight`; expected one of: joint, a, alpha, d, theta, limits, mass, com, inertia, motor, friction, collision",
    );
    // A near miss of a known name is pointed out.
    let text = robot("", &[&format!("{LINK}frction = {{ viscous = 0.1 }}\n")]);
    check(
        &text,
        "frction",
        1,
        Some(1),
        "frction",
        "unknown field `frction` (did you mean `friction`?); expected one of:",
    );
}

#[test]
fn unknown_field_in_nested_tables() {
    let link = format!("{LINK}inertia = {{ xx = 1.0, ixy = 0.0 }}\nmass = 1.0\ncom = [0, 0, 0]\n");
    let text = robot("", &[&link]);
    check(
        &text,
        "ixy",
        1,
        Some(1),
        "inertia.ixy",
        "unknown field `ixy` (did you mean `xy`?); expected one of: xx, yy, zz, xy, yz, xz",
    );

    let text = robot("base = { xyz = [0, 0, 0], rot = [0, 0, 0] }\n", &[LINK]);
    check(
        &text,
        "rot",
        1,
        None,
        "base.rot",
        "unknown field `rot` (did you mean `rpy`?); expected one of: xyz, rpy",
    );
    let text = robot("tool = { z = 0.1 }\n", &[LINK]);
    check(&text, "z = 0.1", 1, None, "tool.z", "unknown field `z`");

    let text = robot(
        "",
        &[
            LINK,
            &format!("{LINK}motor = {{ inertia = 1e-4, gear = 50, ratio = 2 }}\n"),
        ],
    );
    check(
        &text,
        "ratio",
        1,
        Some(2),
        "motor.ratio",
        "unknown field `ratio`; expected one of: inertia, gear",
    );
    let text = robot(
        "",
        &[&format!(
            "{LINK}friction = {{ viscous = 0.1, static = 0.2 }}\n"
        )],
    );
    check(
        &text,
        "static",
        1,
        Some(1),
        "friction.static",
        "unknown field `static`; expected one of: viscous, coulomb",
    );
}

#[test]
fn unknown_joint_type() {
    let text = robot("", &[LINK, &LINK.replace("\"revolute\"", "\"spherical\"")]);
    check(
        &text,
        "\"spherical\"",
        1,
        Some(2),
        "joint",
        "unknown joint type `spherical`; expected `revolute` or `prismatic`",
    );
}

#[test]
fn number_is_nan() {
    let cases = [
        (LINK.replace("a = 0.5", "a = nan"), "nan", "a"),
        (LINK.replace("d = 0.1", "d = -nan"), "-nan", "d"),
        (
            LINK.replace("alpha = \"90deg\"", "alpha = nan"),
            "nan",
            "alpha",
        ),
        (format!("{LINK}limits = [nan, 1.0]\n"), "nan", "limits"),
    ];
    for (link, needle, field) in &cases {
        let text = robot("", &[LINK, LINK, link]);
        check(&text, needle, 1, Some(3), field, "the value is NaN");
    }
    let link = massive("").replace("com = [-0.25, 0.0, 0.0]", "com = [-0.25, nan, 0.0]");
    let text = robot("", &[&link]);
    check(&text, "nan", 1, Some(1), "com", "the value is NaN");
    let link = massive("").replace("xx = 0.001", "xx = nan");
    let text = robot("", &[&link]);
    check(&text, "nan", 1, Some(1), "inertia.xx", "the value is NaN");
    let text = robot("gravity = [0, 0, nan]\n", &[LINK]);
    check(&text, "nan", 1, None, "gravity", "the value is NaN");
}

#[test]
fn number_is_infinite() {
    let cases = [
        (
            LINK.replace("a = 0.5", "a = inf"),
            "inf",
            "a",
            "the value is inf",
        ),
        (
            LINK.replace("d = 0.1", "d = -inf"),
            "-inf",
            "d",
            "the value is -inf",
        ),
        (
            LINK.replace("theta = 0", "theta = +inf"),
            "+inf",
            "theta",
            "the value is inf",
        ),
        // Too large for f64: TOML accepts the literal, the value is infinite.
        (
            LINK.replace("d = 0.1", "d = 1e400"),
            "1e400",
            "d",
            "the value is inf",
        ),
    ];
    for (link, needle, field, what) in &cases {
        let text = robot("", &[LINK, link]);
        check(&text, needle, 1, Some(2), field, what);
    }
    let text = robot("", &[&massive("").replace("mass = 2.0", "mass = inf")]);
    check(&text, "inf", 1, Some(1), "mass", "the value is inf");
    let text = robot("", &[&massive("motor = { inertia = 1e-4, gear = -inf }\n")]);
    check(&text, "-inf", 1, Some(1), "motor.gear", "the value is -inf");
}

#[test]
fn unparsable_angle_string() {
    let cases = [
        ("alpha = \"ninety\"", "\"ninety\"", "alpha"),
        ("alpha = \"2pi\"", "\"2pi\"", "alpha"),
        ("alpha = \"pi/0\"", "\"pi/0\"", "alpha"),
        ("alpha = \"90 degrees\"", "\"90 degrees\"", "alpha"),
    ];
    for (line, needle, field) in cases {
        let link = LINK.replace("alpha = \"90deg\"", line);
        let text = robot("", &[LINK, LINK, &link]);
        check(&text, needle, 1, Some(3), field, "cannot parse angle");
    }
    let text = robot("", &[&LINK.replace("theta = 0", "theta = \"nandeg\"")]);
    check(
        &text,
        "\"nandeg\"",
        1,
        Some(1),
        "theta",
        "cannot parse angle \"nandeg\"",
    );
    let text = robot("", &[&format!("{LINK}limits = [\"-90deg\", \"half\"]\n")]);
    check(
        &text,
        "\"half\"",
        1,
        Some(1),
        "limits",
        "cannot parse angle \"half\"",
    );
    // Columns count characters: `°` is two bytes but one column.
    let text = robot("tool = { rpy = [\"90°\", \"nïnety\", 0] }\n", &[LINK]);
    check(
        &text,
        "\"nïnety\"",
        1,
        None,
        "tool.rpy",
        "cannot parse angle \"nïnety\"",
    );
    assert!(rejection(&text).1.starts_with(&format!("{FILE}:3:24: ")));
}

#[test]
fn zero_links() {
    let text = "name = \"bad\"\nconvention = \"standard\"\nlinks = []\n";
    check(
        text,
        "[]",
        1,
        None,
        "links",
        "the robot has zero links; give at least one",
    );
}

#[test]
fn negative_mass() {
    let link = massive("").replace("mass = 2.0", "mass = -2.0");
    let text = robot("", &[&massive(""), &link]);
    check(&text, "-2.0", 1, Some(2), "mass", "mass -2 is negative");
    // Zero is allowed: the PUMA 560's first link is published with mass 0.
    let link = massive("").replace("mass = 2.0", "mass = 0");
    let text = robot("", &[&massive(""), &link]);
    assert!(RobotModel::from_toml_named(&text, FILE).is_ok());
}

#[test]
fn inertia_not_positive_semi_definite() {
    // A negative principal moment on the diagonal...
    let link = massive("").replace("xx = 0.001", "xx = -0.001");
    let text = robot("", &[&massive(""), &massive(""), &link]);
    check(
        &text,
        "{ xx = -0.001",
        1,
        Some(3),
        "inertia",
        "inertia tensor is not positive semi-definite",
    );
    // ...and one hidden by a product of inertia: diagonal 1, 1, 1 with xy = 2 has
    // eigenvalues -1, 1, 3.
    let link = massive("").replace(
        "inertia = { xx = 0.001, yy = 0.04, zz = 0.04 }",
        "inertia = { xx = 1, yy = 1, zz = 1, xy = 2 }",
    );
    let text = robot("", &[&massive(""), &link]);
    check(
        &text,
        "{ xx = 1,",
        1,
        Some(2),
        "inertia",
        "not positive semi-definite (principal moments -1",
    );
}

#[test]
fn inertia_violates_triangle_inequality() {
    // The published PUMA 560 link 3 inertia: 0.066 + 0.0125 < 0.086.
    let published = "inertia = { xx = 0.066, yy = 0.086, zz = 0.0125 }";
    let link = massive("").replace("inertia = { xx = 0.001, yy = 0.04, zz = 0.04 }", published);
    let text = robot("", &[&massive(""), &massive(""), &link]);
    check(
        &text,
        "{ xx = 0.066",
        1,
        Some(3),
        "inertia",
        "violate the triangle inequality",
    );
    assert!(
        rejection(&text)
            .1
            .contains("allow_nonphysical_inertia = true")
    );

    // The extension accepts it as published...
    let allowed = text.replacen(
        "convention = \"standard\"\n",
        "convention = \"standard\"\nallow_nonphysical_inertia = true\n",
        1,
    );
    let model = RobotModel::from_toml_named(&allowed, FILE).unwrap_or_else(|e| panic!("{e}"));
    let inertia = model.links[2].inertial.map(|i| i.inertia);
    assert_eq!(
        inertia.map(|i| [i[0][0], i[1][1], i[2][2]]),
        Some([0.066, 0.086, 0.0125])
    );

    // ...but never a tensor with a negative principal moment.
    let negative = allowed.replace("xx = 0.066", "xx = -0.066");
    check(
        &negative,
        "{ xx = -0.066",
        1,
        Some(3),
        "inertia",
        "not positive semi-definite",
    );
}

#[test]
fn limits_lower_not_below_upper() {
    let cases = [
        (
            "[1.0, -1.0]",
            "lower limit 1 rad (57.2958°) is not below upper limit -1 rad (-57.2958°)",
        ),
        (
            "[0.5, 0.5]",
            "lower limit 0.5 rad (28.6479°) is not below upper limit 0.5 rad (28.6479°)",
        ),
        (
            "[\"90deg\", \"pi/2\"]",
            "lower limit 1.5707963267948966 rad (90°) is not below upper limit 1.5707963267948966 rad (90°)",
        ),
    ];
    for (limits, what) in cases {
        let text = robot("", &[LINK, &format!("{LINK}limits = {limits}\n")]);
        check(&text, limits, 1, Some(2), "limits", what);
    }
    let prismatic = LINK.replace("revolute", "prismatic");
    let text = robot("", &[&format!("{prismatic}limits = [0.3, 0.1]\n")]);
    check(
        &text,
        "[0.3",
        1,
        Some(1),
        "limits",
        "lower limit 0.3 m is not below upper limit 0.1 m",
    );
}

#[test]
fn mass_without_com_and_inertia() {
    let text = robot("", &[LINK, &format!("{LINK}mass = 2.0\n")]);
    check(
        &text,
        "2.0",
        1,
        Some(2),
        "com",
        "`mass` is given but `com` is missing: mass, com and inertia go together",
    );
    let text = robot("", &[&format!("{LINK}mass = 2.0\ncom = [0, 0, 0]\n")]);
    check(
        &text,
        "2.0",
        1,
        Some(1),
        "inertia",
        "`mass`, `com` is given but `inertia` is missing",
    );
}

#[test]
fn com_or_inertia_without_mass() {
    let text = robot("", &[LINK, &format!("{LINK}com = [0, 0, 0]\n")]);
    check(
        &text,
        "[0, 0, 0]",
        1,
        Some(2),
        "mass",
        "`com` is given but `mass` is missing",
    );
    let text = robot(
        "",
        &[&format!(
            "{LINK}inertia = {{ xx = 1, yy = 1, zz = 1 }}\ncom = [0, 0, 0]\n"
        )],
    );
    check(
        &text,
        "[0, 0, 0]",
        1,
        Some(1),
        "mass",
        "`com`, `inertia` is given but `mass` is missing",
    );
}

/// Finite values no robot has (1e308 m, 1e200 gear ratios) would overflow inside the
/// symbolic engine; each kind of quantity has a documented range.
#[test]
fn magnitudes_outside_the_physical_ranges() {
    let out = "is outside the range of any robot";
    let cases = [
        (
            LINK.replace("a = 0.5", "a = 1e308"),
            "1e308",
            "a",
            "length 1e308 m",
        ),
        (
            LINK.replace("a = 0.5", "a = -1e308"),
            "-1e308",
            "a",
            "length -1e308 m",
        ),
        (
            LINK.replace("d = 0.1", "d = 1001.0"),
            "1001.0",
            "d",
            "length 1001 m",
        ),
        (
            LINK.replace("theta = 0", "theta = 1e308"),
            "1e308",
            "theta",
            "angle 1e308 rad",
        ),
        (
            LINK.replace("alpha = \"90deg\"", "alpha = \"1e300deg\""),
            "\"1e300deg\"",
            "alpha",
            "angle",
        ),
        (
            LINK.replace("theta = 0", "theta = \"1e308*pi\""),
            "\"1e308*pi\"",
            "theta",
            "give an angle of finite size",
        ),
        (
            LINK.replace("theta = 0", "theta = \"pi/1e-320\""),
            "\"pi/1e-320\"",
            "theta",
            "give an angle of finite size",
        ),
        (
            format!("{LINK}limits = [-1e10, 1e10]\n"),
            "-1e10",
            "limits",
            "angle -1e10 rad",
        ),
        (
            format!("{LINK}motor = {{ inertia = 1e-4, gear = 1e200 }}\n"),
            "1e200",
            "motor.gear",
            "gear ratio 1e200",
        ),
        (
            format!("{LINK}motor = {{ inertia = 1e-4, gear = 1e-9 }}\n"),
            "1e-9",
            "motor.gear",
            "gear ratio 1e-9",
        ),
        (
            format!("{LINK}motor = {{ inertia = 1e4, gear = 1 }}\n"),
            "1e4",
            "motor.inertia",
            "rotor inertia 10000",
        ),
        (
            format!("{LINK}friction = {{ viscous = 1e7 }}\n"),
            "1e7",
            "friction.viscous",
            "friction coefficient 1e7",
        ),
        (
            format!("{LINK}collision = {{ radius = 1e5 }}\n"),
            "1e5",
            "collision.radius",
            "length 100000 m",
        ),
    ];
    for (link, needle, field, what) in &cases {
        let text = robot("", &[LINK, link]);
        check(&text, needle, 1, Some(2), field, what);
        if !what.contains("finite") {
            check(&text, needle, 1, Some(2), field, out);
        }
    }
    let mass_cases = [
        ("mass = 2.0", "mass = 1e7", "1e7", "mass", "mass 1e7 kg"),
        (
            "com = [-0.25",
            "com = [-1e308",
            "-1e308",
            "com",
            "length -1e308 m",
        ),
        (
            "xx = 0.001",
            "xx = 1e308",
            "1e308",
            "inertia.xx",
            "inertia 1e308 kg·m²",
        ),
    ];
    for (from, to, needle, field, what) in mass_cases {
        let text = robot("", &[&massive("").replace(from, to)]);
        check(&text, needle, 1, Some(1), field, what);
    }
    let text = robot("gravity = [0, 0, -1e5]\n", &[LINK]);
    check(
        &text,
        "-1e5",
        1,
        None,
        "gravity",
        "gravity component -100000 m/s²",
    );
    let text = robot("tool = { xyz = [0, 0, 2e3] }\n", &[LINK]);
    check(&text, "2e3", 1, None, "tool.xyz", "length 2000 m");
    // The edges of the ranges are accepted; so are exact zeros and tiny lengths.
    let text = robot(
        "gravity = [0, 0, -1e3]\n",
        &[
            &massive("motor = { inertia = 1e3, gear = 1e6 }\nfriction = { viscous = 1e6 }\n")
                .replace("a = 0.5", "a = 1e3")
                .replace("d = 0.1", "d = 1e-300")
                .replace("mass = 2.0", "mass = 1e6"),
        ],
    );
    if let Err(e) = RobotModel::from_toml_named(&text, FILE) {
        panic!("rejected a description at the edges of the ranges: {e}\n{text}");
    }
}

/// A value just past its limit is shown as written (the shortest text that reads back as the
/// value), not rounded onto the limit: the message must show why the value failed. Beyond 1e6
/// and below 1e-4 in scientific notation.
#[test]
fn values_just_past_a_limit_show_why_they_fail() {
    let cases = [
        (
            LINK.replace("a = 0.5", "a = 1000.0000001"),
            "1000.0000001",
            "a",
            "length 1000.0000001 m is outside",
        ),
        (
            LINK.replace("alpha = \"90deg\"", "alpha = -1000.0000001"),
            "-1000.0000001",
            "alpha",
            "angle -1000.0000001 rad is outside",
        ),
        (
            format!("{LINK}limits = [-1000.0000001, 0]\n"),
            "-1000.0000001",
            "limits",
            "angle -1000.0000001 rad is outside",
        ),
        (
            format!("{LINK}motor = {{ inertia = 1e-4, gear = 9.99999999e-7 }}\n"),
            "9.99999999e-7",
            "motor.gear",
            "gear ratio 9.99999999e-7 is outside",
        ),
    ];
    for (link, needle, field, what) in &cases {
        let text = robot("", &[LINK, link]);
        check(&text, needle, 1, Some(2), field, what);
    }
    let mass_cases = [
        (
            "mass = 2.0",
            "mass = 1000000.0000000002",
            "1000000.0000000002",
            "mass",
            "mass 1.0000000000000002e6 kg is outside",
        ),
        (
            "xx = 0.001",
            "xx = 1000000000.0000002",
            "1000000000.0000002",
            "inertia.xx",
            "inertia 1.0000000000000002e9 kg·m² is outside",
        ),
        (
            "inertia = { xx = 0.001, yy = 0.04, zz = 0.04 }",
            "inertia = { xx = 0.5, yy = 0.5, zz = 1.0000001 }",
            "{ xx = 0.5",
            "inertia",
            "principal moments 0.5, 0.5, 1.0000001 violate the triangle inequality \
             (0.5 + 0.5 < 1.0000001)",
        ),
    ];
    for (from, to, needle, field, what) in mass_cases {
        let text = robot("", &[&massive("").replace(from, to)]);
        check(&text, needle, 1, Some(1), field, what);
    }
    let text = robot("gravity = [0, 0, -1000.0000000001]\n", &[LINK]);
    check(
        &text,
        "-1000.0000000001",
        1,
        None,
        "gravity",
        "gravity component -1000.0000000001 m/s² is outside",
    );
}

#[test]
fn gear_ratio_zero() {
    let text = robot(
        "",
        &[
            LINK,
            &format!("{LINK}motor = {{ inertia = 1e-4, gear = 0 }}\n"),
        ],
    );
    check(
        &text,
        "0 }",
        1,
        Some(2),
        "motor.gear",
        "gear ratio is 0; it must be non-zero",
    );
    // A negative ratio (a reversing transmission) is fine.
    let text = robot(
        "",
        &[&format!("{LINK}motor = {{ inertia = 1e-4, gear = -50 }}\n")],
    );
    assert!(RobotModel::from_toml_named(&text, FILE).is_ok());
}

#[test]
fn unknown_convention() {
    let text = robot("", &[LINK]).replace("\"standard\"", "\"craig\"");
    check(
        &text,
        "\"craig\"",
        1,
        None,
        "convention",
        "unknown convention `craig`; expected `standard` or `modified` or `urdf`",
    );
}

#[test]
fn mixed_dynamics_across_links() {
    let text = robot("", &[&massive(""), LINK, &massive("")]);
    check(
        &text,
        "[[links]]",
        2,
        Some(2),
        "mass",
        "this link has no `mass`, `com` and `inertia` but link 1 has them",
    );
}

#[test]
fn wrong_value_types() {
    let link = |from: &str, to: &str| robot("", &[LINK, &LINK.replace(from, to)]);
    check(
        &link("a = 0.5", "a = \"0.5\""),
        "\"0.5\"",
        1,
        Some(2),
        "a",
        "expected a number, found a string",
    );
    check(
        &link("\"revolute\"", "1"),
        "1\na",
        1,
        Some(2),
        "joint",
        "expected the joint type (`revolute` or `prismatic`), found a number",
    );
    check(
        &link("alpha = \"90deg\"", "alpha = true"),
        "true",
        1,
        Some(2),
        "alpha",
        "expected an angle (a number in radians or a string like \"90deg\"), found a boolean",
    );
    check(
        &robot("", &[&format!("{LINK}motor = 55\n")]),
        "55",
        1,
        Some(1),
        "motor",
        "expected a table, found a number",
    );
    check(
        &robot("", &[&format!("{LINK}limits = 11\n")]),
        "11",
        1,
        Some(1),
        "limits",
        "expected an array of 2 elements, found a number",
    );
    let top = |line: &str| robot(line, &[LINK]);
    check(
        &top("description = 33\n"),
        "33",
        1,
        None,
        "description",
        "expected a string, found a number",
    );
    check(
        &top("allow_nonphysical_inertia = \"yes\"\n"),
        "\"yes\"",
        1,
        None,
        "allow_nonphysical_inertia",
        "expected true or false, found a string",
    );
    check(
        &top("base = [0, 0, 0]\n"),
        "[0, 0, 0]",
        1,
        None,
        "base",
        "expected a table, found an array",
    );
    check(
        "name = 5\nconvention = \"standard\"\nlinks = []\n",
        "5",
        1,
        None,
        "name",
        "expected a string, found a number",
    );
    check(
        "name = \"bad\"\nconvention = \"standard\"\nlinks = 3\n",
        "3",
        1,
        None,
        "links",
        "expected an array of link tables, found a number",
    );
    // An element of `links` that is not a table has no field to name: only the link.
    let text = "name = \"bad\"\nconvention = \"standard\"\nlinks = [1]\n";
    let (error, shown) = rejection(text);
    assert_eq!((error.link, error.field), (Some(1), None));
    assert_eq!(
        shown,
        "robots/bad.toml:3:10: link 1: expected a table, found a number"
    );
}

#[test]
fn wrong_array_lengths() {
    check(
        &robot(
            "",
            &[&massive("").replace("[-0.25, 0.0, 0.0]", "[-0.25, 0.0]")],
        ),
        "[-0.25",
        1,
        Some(1),
        "com",
        "expected 3 elements, found 2",
    );
    check(
        &robot("gravity = [0, 0, -9.81, 0]\n", &[LINK]),
        "[0, 0, -9.81",
        1,
        None,
        "gravity",
        "expected 3 elements, found 4",
    );
    check(
        &robot("", &[LINK, &format!("{LINK}limits = [-1, 0, 1]\n")]),
        "[-1",
        1,
        Some(2),
        "limits",
        "expected 2 elements, found 3",
    );
    check(
        &robot("base = { xyz = [0, 0] }\n", &[LINK]),
        "[0, 0]",
        1,
        None,
        "base.xyz",
        "expected 3 elements, found 2",
    );
    check(
        &robot("tool = { rpy = [0, 0, 0, 0] }\n", &[LINK]),
        "[0, 0, 0, 0]",
        1,
        None,
        "tool.rpy",
        "expected 3 elements, found 4",
    );
}

#[test]
fn negative_rotor_inertia() {
    let text = robot(
        "",
        &[
            LINK,
            LINK,
            &format!("{LINK}motor = {{ inertia = -1e-4, gear = 50 }}\n"),
        ],
    );
    check(
        &text,
        "-1e-4",
        1,
        Some(3),
        "motor.inertia",
        "rotor inertia -0.0001 is negative",
    );
}

#[test]
fn negative_friction() {
    for (key, needle) in [("viscous", "-0.5"), ("coulomb", "-2")] {
        let friction = format!("friction = {{ {key} = {needle} }}\n");
        let text = robot("", &[LINK, &format!("{LINK}{friction}")]);
        check(
            &text,
            needle,
            1,
            Some(2),
            &format!("friction.{key}"),
            &format!("friction coefficient {needle} is negative"),
        );
    }
}

/// TOML itself rejects a key given twice, so this rule is only reachable from the macro
/// front end: checked on a hand-built tree whose locations are token numbers.
#[test]
fn field_given_twice() {
    let num = |x: f64, token: u32| Value::Number(x, token);
    let link = Table {
        entries: vec![
            ("joint".into(), 10, Value::Word("revolute".into(), 11)),
            ("a".into(), 12, num(0.5, 13)),
            ("alpha".into(), 14, num(0.0, 15)),
            ("a".into(), 16, num(0.7, 17)),
            ("d".into(), 18, num(0.0, 19)),
            ("theta".into(), 20, num(0.0, 21)),
        ],
        loc: 9,
    };
    let root = Table {
        entries: vec![
            ("convention".into(), 1, Value::Word("standard".into(), 2)),
            ("links".into(), 3, Value::Array(vec![Value::Table(link)], 4)),
        ],
        loc: 0,
    };
    let error = validate::validate(&root, Some("arm")).unwrap_err();
    assert_eq!(error.loc, 16, "at the second key");
    assert_eq!(error.link, Some(1));
    assert_eq!(error.field.as_deref(), Some("a"));
    assert_eq!(
        error.to_string(),
        "link 1, field `a`: field `a` is given twice"
    );
}

/// Syntax errors are located like rule violations (`file:line:column:`), on one line, with
/// the TOML parser's message.
#[test]
fn toml_syntax_error_names_the_line() {
    let text = robot("", &[LINK, "joint = \"revolute\"\na = 0.5\na = 0.6\n"]);
    let error = RobotModel::from_toml_named(&text, FILE).unwrap_err();
    assert!(matches!(error, LoadError::Syntax { .. }), "{error}");
    let shown = error.to_string();
    assert!(
        shown.starts_with(&format!(
            "{FILE}:{}: invalid TOML: ",
            position_of(&text, "a = 0.6", 1)
        )),
        "{shown}"
    );
    assert!(shown.contains("duplicate key"), "{shown}");
    assert!(!shown.contains('\n'), "{shown}");
}

#[test]
fn collision_radius_not_positive() {
    for needle in ["0", "-0.05"] {
        let text = robot(
            "",
            &[
                LINK,
                &format!("{LINK}collision = {{ radius = {needle} }}\n"),
            ],
        );
        check(
            &text,
            &format!("{needle} }}"),
            1,
            Some(2),
            "collision.radius",
            &format!("collision radius {needle} is not positive"),
        );
    }
    let text = robot("", &[&format!("{LINK}collision = {{ radius = nan }}\n")]);
    check(
        &text,
        "nan",
        1,
        Some(1),
        "collision.radius",
        "the value is NaN",
    );
    let text = robot("", &[&format!("{LINK}collision = {{ radius = inf }}\n")]);
    check(
        &text,
        "inf",
        1,
        Some(1),
        "collision.radius",
        "the value is inf",
    );
}

#[test]
fn collision_table_fields() {
    let text = robot(
        "",
        &[&format!(
            "{LINK}collision = {{ radius = 0.05, length = 1 }}\n"
        )],
    );
    check(
        &text,
        "length",
        1,
        Some(1),
        "collision.length",
        "unknown field `length`; expected one of: radius",
    );
    let text = robot("", &[LINK, &format!("{LINK}collision = {{ }}\n")]);
    check(
        &text,
        "{ }",
        1,
        Some(2),
        "collision.radius",
        "missing required field `radius`",
    );
    let text = robot("", &[&format!("{LINK}collision = 0.05\n")]);
    check(
        &text,
        "0.05",
        1,
        Some(1),
        "collision",
        "expected a table, found a number",
    );
    // A valid capsule is kept on its link; links without one have none.
    let text = robot(
        "",
        &[LINK, &format!("{LINK}collision = {{ radius = 0.05 }}\n")],
    );
    let model = RobotModel::from_toml_named(&text, FILE).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(model.links[0].collision, None);
    assert_eq!(
        model.links[1].collision,
        Some(dhgen_description::Collision { radius: 0.05 })
    );
}

/// Every message is one line: a control character from the description (a newline in a
/// quoted key or string) is shown escaped.
#[test]
fn messages_are_one_line_whatever_the_text_holds() {
    let text = "name = \"x\"\nconvention = \"st\\nandard\"\n";
    let (_, shown) = rejection(text);
    assert_eq!(
        shown,
        "robots/bad.toml:2:14: field `convention`: unknown convention `st\\nandard`; expected `standard` or `modified` or `urdf`"
    );
    let text = "name = \"x\"\nconvention = \"standard\"\n\"bad\\nkey\" = 1\n[[links]]\n";
    let (_, shown) = rejection(text);
    assert!(
        shown.starts_with("robots/bad.toml:3:1: field `bad\\nkey`: unknown field `bad\\nkey`"),
        "{shown}"
    );
}
