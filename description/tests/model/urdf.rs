//! URDF input: the chain a file describes, checked against URDF's own formula evaluated
//! independently here (nalgebra's axis-angle rotations), mass merging by hand, the snapping
//! rule, and one test per kind of bad file.

use dhgen_description::urdf::{UrdfOptions, read};
use dhgen_description::{Convention, JointKind, LoadError, RobotModel};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

/// `<origin>` as an isometry: URDF's `Rz(yaw) Ry(pitch) Rx(roll)` and the translation.
fn origin(xyz: [f64; 3], rpy: [f64; 3]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(xyz[0], xyz[1], xyz[2]),
        UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    )
}

/// An arm exercising what a URDF can say: a world link, fixed joints before, between and
/// after the movable ones, axes along y, −x and an oblique direction, a continuous and a
/// prismatic joint, inertial frames with their own rpy, and an extra fixed child with mass.
const ARM: &str = r#"<?xml version="1.0"?>
<robot name="test_arm">
  <link name="world"/>
  <joint name="mount" type="fixed">
    <parent link="world"/><child link="base"/>
    <origin xyz="0.1 0 0.05" rpy="0 0 0.3"/>
  </joint>
  <link name="base">
    <inertial><mass value="5"/><inertia ixx="1" iyy="1" izz="1" ixy="0" iyz="0" ixz="0"/></inertial>
  </link>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.3" rpy="0 0 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" effort="50" velocity="3"/>
    <dynamics damping="0.5" friction="0.2"/>
  </joint>
  <link name="l1">
    <inertial>
      <origin xyz="0.01 0.02 0.15" rpy="0.1 0.2 0.3"/>
      <mass value="2.5"/>
      <inertia ixx="0.05" iyy="0.04" izz="0.02" ixy="0.001" iyz="-0.002" ixz="0.003"/>
    </inertial>
  </link>
  <joint name="elbow_mount" type="fixed">
    <parent link="l1"/><child link="l1b"/>
    <origin xyz="0 0.05 0.3" rpy="1.5707963267948966 0 0"/>
  </joint>
  <link name="l1b">
    <inertial><origin xyz="0 0 0.02"/><mass value="0.5"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" iyz="0" ixz="0"/></inertial>
  </link>
  <joint name="j2" type="continuous">
    <parent link="l1b"/><child link="l2"/>
    <origin xyz="0.02 0 0.1" rpy="0 -1.5707963267948966 0"/>
    <axis xyz="-1 0 0"/>
  </joint>
  <link name="l2">
    <inertial><origin xyz="0 0 0.1"/><mass value="1.5"/><inertia ixx="0.02" iyy="0.02" izz="0.004" ixy="0" iyz="0" ixz="0"/></inertial>
  </link>
  <joint name="j3" type="prismatic">
    <parent link="l2"/><child link="l3"/>
    <origin xyz="0 0 0.2" rpy="0.4 0 0"/>
    <axis xyz="0 0.6 0.8"/>
    <limit lower="0" upper="0.3" effort="100" velocity="0.5"/>
  </joint>
  <link name="l3">
    <inertial><mass value="0.8"/><inertia ixx="0.003" iyy="0.003" izz="0.001" ixy="0" iyz="0" ixz="0"/></inertial>
  </link>
  <joint name="flange" type="fixed">
    <parent link="l3"/><child link="tool"/>
    <origin xyz="0 0 0.12" rpy="3.141592653589793 0 0"/>
  </joint>
  <link name="tool"/>
</robot>
"#;

/// The tool pose by URDF's definition: `Π origin_i · motion_i(q_i)`.
fn urdf_tool(q: &[f64; 3]) -> Isometry3<f64> {
    let rot = |axis: [f64; 3], a: f64| {
        Isometry3::from_parts(
            Translation3::identity(),
            UnitQuaternion::from_axis_angle(&nalgebra::Unit::new_normalize(Vector3::from(axis)), a),
        )
    };
    let slide = |axis: [f64; 3], d: f64| {
        let u = Vector3::from(axis).normalize() * d;
        Isometry3::translation(u.x, u.y, u.z)
    };
    let fr = core::f64::consts::FRAC_PI_2;
    origin([0.1, 0.0, 0.05], [0.0, 0.0, 0.3])
        * origin([0.0, 0.0, 0.3], [0.0; 3])
        * rot([0.0, 1.0, 0.0], q[0])
        * origin([0.0, 0.05, 0.3], [fr, 0.0, 0.0])
        * origin([0.02, 0.0, 0.1], [0.0, -fr, 0.0])
        * rot([-1.0, 0.0, 0.0], q[1])
        * origin([0.0, 0.0, 0.2], [0.4, 0.0, 0.0])
        * slide([0.0, 0.6, 0.8], q[2])
        * origin([0.0, 0.0, 0.12], [core::f64::consts::PI, 0.0, 0.0])
}

#[test]
fn urdf_chain_is_urdf_formula() {
    let robot = read(ARM, "arm.urdf", &UrdfOptions::default()).unwrap();
    assert_eq!(robot.base, "world");
    // The end of the movable joints is l3; the fixed `tool` alone below it is the tip.
    assert_eq!(robot.tip, "tool");
    let names: Vec<&str> = robot.joints.iter().map(|j| j.name.as_str()).collect();
    assert_eq!(names, ["j1", "j2", "j3"]);
    assert_eq!(robot.joints[0].velocity, Some(3.0));
    assert_eq!(robot.joints[2].effort, Some(100.0));
    let m = &robot.model;
    assert_eq!(m.convention, Convention::Urdf);
    assert_eq!(
        m.links.iter().map(|l| l.joint).collect::<Vec<_>>(),
        [
            JointKind::Revolute,
            JointKind::Revolute,
            JointKind::Prismatic
        ]
    );
    assert_eq!(m.links[0].limits, Some([-2.0, 2.0]));
    assert_eq!(m.links[1].limits, None, "continuous");
    let f = m.links[0].friction.unwrap();
    assert_eq!((f.viscous, f.coulomb), (0.5, 0.2));
    // With `tip = "l3"`, the chain stops at the last moving link: no tool transform.
    let at_l3 = read(
        ARM,
        "arm.urdf",
        &UrdfOptions {
            tip: Some("l3".into()),
            ..Default::default()
        },
    )
    .unwrap();
    assert!(at_l3.model.tool.is_none());
    assert!(robot.model.tool.is_some());
    let with_tool = robot.clone();
    let chain = with_tool.model.chain();
    for q in [[0.0, 0.0, 0.0], [0.3, -1.2, 0.1], [-1.9, 2.5, 0.29]] {
        let got = chain.view().tool_at(&q);
        let want = urdf_tool(&q).to_homogeneous();
        for i in 0..3 {
            assert!(
                (got.p[i] - want[(i, 3)]).abs() < 1e-14,
                "{q:?} {got:?} {want}"
            );
            for j in 0..3 {
                assert!((got.r[i][j] - want[(i, j)]).abs() < 1e-14, "{q:?}");
            }
        }
    }
    // The description round-trips through its TOML form.
    let text = with_tool.model.to_toml();
    let back = RobotModel::from_toml_str(&text).unwrap();
    assert_eq!(back, with_tool.model, "{text}");
}

#[test]
fn urdf_fixed_links_merge_into_their_body() {
    let robot = read(ARM, "arm.urdf", &UrdfOptions::default()).unwrap();
    // Body 1 = l1 (inertial frame rotated) + l1b fixed to it, in l1's frame.
    let l1_frame = origin([0.01, 0.02, 0.15], [0.1, 0.2, 0.3]);
    let r1 = l1_frame.rotation.to_rotation_matrix().into_inner();
    let i1 = nalgebra::Matrix3::new(0.05, 0.001, 0.003, 0.001, 0.04, -0.002, 0.003, -0.002, 0.02);
    let i1 = r1 * i1 * r1.transpose();
    let c1 = l1_frame.translation.vector;
    let l1b = origin([0.0, 0.05, 0.3], [core::f64::consts::FRAC_PI_2, 0.0, 0.0]);
    let c2 = l1b
        .transform_point(&nalgebra::Point3::new(0.0, 0.0, 0.02))
        .coords;
    let (m1, m2) = (2.5, 0.5);
    let c = (c1 * m1 + c2 * m2) / (m1 + m2);
    let steiner = |d: Vector3<f64>, m: f64| {
        (nalgebra::Matrix3::identity() * d.norm_squared() - d * d.transpose()) * m
    };
    let want =
        i1 + steiner(c1 - c, m1) + nalgebra::Matrix3::identity() * 0.001 + steiner(c2 - c, m2);
    let got = robot.model.links[0].inertial.unwrap();
    assert!((got.mass - 3.0).abs() < 1e-15);
    for i in 0..3 {
        assert!((got.com[i] - c[i]).abs() < 1e-15, "{got:?} {c}");
        for j in 0..3 {
            assert!(
                (got.inertia[i][j] - want[(i, j)]).abs() < 1e-15,
                "{got:?} {want}"
            );
        }
    }
    // The base's 5 kg are the world's, not the robot's.
    let total: f64 = robot
        .model
        .links
        .iter()
        .map(|l| l.inertial.unwrap().mass)
        .sum();
    assert!((total - (3.0 + 1.5 + 0.8)).abs() < 1e-15);
}

#[test]
// `1.5708` is the decimal a URDF file writes for π/2, which the test is about.
#[allow(clippy::approx_constant)]
fn urdf_quarter_turns_snap_within_tolerance_only() {
    let robot = read(ARM, "arm.urdf", &UrdfOptions::default()).unwrap();
    // 1.5707963267948966 is π/2 as an f64 already: nothing to snap, and it is exact.
    assert!(robot.snaps.is_empty(), "{:?}", robot.snaps);
    let short = ARM.replace("1.5707963267948966", "1.5708");
    let loose = read(&short, "arm.urdf", &UrdfOptions::default()).unwrap();
    assert!(loose.snaps.is_empty());
    let snapped = read(
        &short,
        "arm.urdf",
        &UrdfOptions {
            snap: 1e-4,
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(snapped.snaps.len(), 2, "{:?}", snapped.snaps);
    assert_eq!(snapped.snaps[0].from, 1.5708);
    assert_eq!(snapped.snaps[0].to, core::f64::consts::FRAC_PI_2);
    assert!(
        snapped.snaps[0].what.contains("elbow_mount"),
        "{:?}",
        snapped.snaps
    );
    // Snapped, the model equals the exact file's.
    assert_eq!(snapped.model, robot.model);
    // 10 digits snap at the default 1e-9; an axis 1e-10 off z snaps to z.
    let ten = ARM
        .replace("1.5707963267948966", "1.5707963268")
        .replace("<axis xyz=\"0 1 0\"/>", "<axis xyz=\"1e-10 1 0\"/>");
    let r = read(&ten, "arm.urdf", &UrdfOptions::default()).unwrap();
    assert_eq!(r.snaps.len(), 3, "{:?}", r.snaps);
    assert_eq!(r.model, robot.model);
}

/// The snapping tolerance is an option of the reader, checked by it: 10 rad or ∞ would snap
/// every angle to a quarter turn (a different robot), NaN or a negative one would silently
/// snap nothing.
#[test]
// `1.5708` is the decimal a URDF file writes for π/2.
#[allow(clippy::approx_constant)]
fn urdf_snap_outside_its_range_is_an_error() {
    let with = |snap| UrdfOptions {
        snap,
        ..Default::default()
    };
    for snap in [
        10.0,
        f64::INFINITY,
        f64::NAN,
        -1.0,
        -1e-12,
        0.1000001,
        f64::NEG_INFINITY,
    ] {
        let e = error(ARM, &with(snap));
        assert!(
            e.starts_with("bad.urdf:1:1: snap = ") && e.contains("from 0 to 0.1"),
            "{snap}: {e}"
        );
    }
    // Even on text that is not URDF: the options are checked first.
    let e = error("not xml", &with(f64::NAN));
    assert!(e.contains("snap = NaN"), "{e}");
    // The ends of the range are accepted: 0 snaps nothing.
    let exact = read(ARM, "arm.urdf", &with(0.0)).unwrap();
    assert!(exact.snaps.is_empty());
    let short = ARM.replace("1.5707963267948966", "1.5708");
    let wide = read(&short, "arm.urdf", &with(UrdfOptions::MAX_SNAP)).unwrap();
    assert!(
        wide.snaps.iter().filter(|s| s.from.abs() == 1.5708).count() == 2,
        "{:?}",
        wide.snaps
    );
}

fn error(text: &str, options: &UrdfOptions) -> String {
    match read(text, "bad.urdf", options) {
        Ok(r) => panic!("accepted: {:?}", r.model),
        Err(e) => {
            assert!(matches!(e, LoadError::Urdf { .. }), "{e:?}");
            e.to_string()
        }
    }
}

fn bad(text: &str) -> String {
    error(text, &UrdfOptions::default())
}

#[test]
fn urdf_malformed_xml_is_located() {
    let e = bad("<robot name=\"x\">\n  <link name=\"a\">\n</robot>\n");
    assert!(e.starts_with("bad.urdf:3:"), "{e}");
    assert!(e.contains("invalid XML"), "{e}");
}

#[test]
fn urdf_missing_inertial_on_a_moving_link_is_massless_and_listed() {
    let text = ARM.replace(
        "<inertial><origin xyz=\"0 0 0.1\"/><mass value=\"1.5\"/><inertia ixx=\"0.02\" iyy=\"0.02\" izz=\"0.004\" ixy=\"0\" iyz=\"0\" ixz=\"0\"/></inertial>",
        "",
    );
    assert_ne!(text, ARM);
    let r = read(&text, "m.urdf", &UrdfOptions::default()).unwrap();
    assert_eq!(r.massless, ["l2"]);
    assert!(r.model.has_dynamics());
    let full = read(ARM, "arm.urdf", &UrdfOptions::default()).unwrap();
    assert!(full.massless.is_empty());
    let (a, b) = (&r.model.links[1], &full.model.links[1]);
    assert_eq!(a.inertial.as_ref().map(|i| i.mass), Some(0.0));
    assert_eq!(b.inertial.as_ref().map(|i| i.mass), Some(1.5));
    // A file with no inertial at all is a kinematics-only robot.
    let kin: String = ARM
        .lines()
        .filter(|l| !l.contains("inertia") && !l.contains("mass"))
        .collect::<Vec<_>>()
        .join("\n")
        .replace("<inertial>", "")
        .replace("</inertial>", "")
        .replace("<origin xyz=\"0.01 0.02 0.15\" rpy=\"0.1 0.2 0.3\"/>", "");
    let r = read(&kin, "k.urdf", &UrdfOptions::default()).unwrap();
    assert!(!r.model.has_dynamics());
}

#[test]
fn urdf_unknown_tip_names_the_links() {
    let e = error(
        ARM,
        &UrdfOptions {
            tip: Some("hand".into()),
            ..Default::default()
        },
    );
    assert!(
        e.contains("the tip `hand` is not a link") && e.contains("`l3`"),
        "{e}"
    );
}

#[test]
fn urdf_tree_without_tip_lists_the_ends() {
    let text = ARM.replace(
        "  <link name=\"tool\"/>",
        "  <link name=\"tool\"/>\n  <joint name=\"finger\" type=\"prismatic\"><parent link=\"l2\"/><child link=\"f\"/><axis xyz=\"1 0 0\"/><limit lower=\"0\" upper=\"0.04\"/></joint>\n  <link name=\"f\"><inertial><mass value=\"0.1\"/><inertia ixx=\"1e-5\" iyy=\"1e-5\" izz=\"1e-5\" ixy=\"0\" iyz=\"0\" ixz=\"0\"/></inertial></link>",
    );
    let e = bad(&text);
    assert!(
        e.contains("2 ends") && e.contains("`f`") && e.contains("`l3`"),
        "{e}"
    );
    assert!(e.contains("tip"), "{e}");
    // Naming the tip reads the chain, the finger held at zero and its mass merged into l2.
    let r = read(
        &text,
        "t.urdf",
        &UrdfOptions {
            tip: Some("l3".into()),
            ..Default::default()
        },
    )
    .unwrap();
    assert_eq!(r.locked, ["finger"]);
    assert!((r.model.links[1].inertial.unwrap().mass - 1.6).abs() < 1e-15);
}

#[test]
fn urdf_mimic_joint_on_the_chain() {
    let text = ARM.replace(
        "<axis xyz=\"-1 0 0\"/>",
        "<axis xyz=\"-1 0 0\"/><mimic joint=\"j1\" multiplier=\"2\"/>",
    );
    let e = bad(&text);
    assert!(e.contains("joint `j2`") && e.contains("mimic"), "{e}");
}

/// A fixed joint has no value to follow: a `<mimic>` on it (some published files carry one)
/// changes nothing.
#[test]
fn urdf_mimic_on_a_fixed_joint_is_read_as_fixed() {
    let text = edit(
        ARM,
        "<origin xyz=\"0 0.05 0.3\"",
        "<mimic joint=\"j1\"/><origin xyz=\"0 0.05 0.3\"",
    );
    let with = read(&text, "arm.urdf", &UrdfOptions::default()).unwrap();
    let without = read(ARM, "arm.urdf", &UrdfOptions::default()).unwrap();
    assert_eq!(with.model, without.model);
}

/// Limits hold a joint of the chain to the description format's ranges; a joint off the chain
/// is held at 0, so its limits play no part (±1e16, as some files write "unlimited", is read).
#[test]
fn urdf_limits_are_checked_on_the_chain_only() {
    let rotor = "  <link name=\"tool\"/>\n  <joint name=\"rotor\" type=\"revolute\"><parent link=\"l1\"/><child link=\"r\"/><limit lower=\"-1e16\" upper=\"1e16\" effort=\"1\" velocity=\"1\"/></joint>\n  <link name=\"r\"/>";
    let text = edit(ARM, "  <link name=\"tool\"/>", rotor);
    let options = UrdfOptions {
        tip: Some("tool".into()),
        ..Default::default()
    };
    let off = read(&text, "arm.urdf", &options).unwrap();
    assert_eq!(off.locked, ["rotor"]);
    assert_eq!(
        off.model,
        read(ARM, "arm.urdf", &UrdfOptions::default())
            .unwrap()
            .model
    );
    let on = UrdfOptions {
        tip: Some("r".into()),
        ..Default::default()
    };
    let e = error(&text, &on);
    assert!(
        e.starts_with(&format!(
            "{}joint `rotor` <limit lower>: angle -1e16 rad is outside the range of any robot",
            at(&text, "lower=\"-1e16\"")
        )),
        "{e}"
    );
    assert!(
        e.ends_with("(a joint that turns without limits is `continuous`)"),
        "{e}"
    );
}

#[test]
fn urdf_floating_joint_on_the_chain() {
    let text = ARM.replace(
        "<joint name=\"j2\" type=\"continuous\">",
        "<joint name=\"j2\" type=\"floating\">",
    );
    let e = bad(&text);
    assert!(e.contains("joint `j2`") && e.contains("floating"), "{e}");
}

#[test]
fn urdf_zero_axis() {
    let text = ARM.replace("<axis xyz=\"0 1 0\"/>", "<axis xyz=\"0 0 0\"/>");
    let e = bad(&text);
    assert!(
        e.contains("joint `j1` <axis xyz>") && e.contains("no direction"),
        "{e}"
    );
    assert!(e.starts_with("bad.urdf:14:"), "{e}");
}

#[test]
fn urdf_negative_mass() {
    let text = ARM.replace("<mass value=\"1.5\"/>", "<mass value=\"-1.5\"/>");
    let e = bad(&text);
    assert!(e.contains("link `l2`") && e.contains("negative"), "{e}");
}

#[test]
fn urdf_inertia_not_positive_semidefinite() {
    let text = ARM.replace(
        "ixx=\"0.02\" iyy=\"0.02\" izz=\"0.004\"",
        "ixx=\"0.02\" iyy=\"-0.02\" izz=\"0.004\"",
    );
    let e = bad(&text);
    assert!(
        e.contains("link `l2`") && e.contains("positive semi-definite"),
        "{e}"
    );
}

#[test]
fn urdf_cycle_is_a_closed_chain() {
    let text = ARM.replace(
        "  <link name=\"tool\"/>",
        "  <link name=\"tool\"/>\n  <joint name=\"loop\" type=\"fixed\"><parent link=\"l3\"/><child link=\"l1\"/></joint>",
    );
    let e = bad(&text);
    assert!(
        e.contains("joint `loop`") && e.contains("closed chain"),
        "{e}"
    );
}

#[test]
fn urdf_unknown_link_and_bad_numbers_are_located() {
    let text = ARM.replace("<child link=\"l2\"/>", "<child link=\"l9\"/>");
    let e = bad(&text);
    assert!(e.contains("there is no link `l9`"), "{e}");
    let text = ARM.replace("xyz=\"0 0 0.3\"", "xyz=\"0 zero 0.3\"");
    let e = bad(&text);
    assert!(
        e.contains("joint `j1` <origin xyz>: expected 3 numbers"),
        "{e}"
    );
    assert!(e.starts_with("bad.urdf:13:"), "{e}");
    let text = ARM.replace(
        "<origin xyz=\"0 0 0.2\" rpy=\"0.4 0 0\"/>",
        "<origin xyz=\"0 0 2e3\" rpy=\"0.4 0 0\"/>",
    );
    let e = bad(&text);
    assert!(e.contains("joint `j3`") && e.contains("length"), "{e}");
}

#[test]
fn urdf_convention_rows_take_origin_and_axis_only() {
    let row = |fields: &str| {
        format!("name = \"x\"\nconvention = \"urdf\"\n[[links]]\njoint = \"revolute\"\n{fields}\n")
    };
    let m = RobotModel::from_toml_str(&row("origin = { xyz = [0, 0, 0.3] }\naxis = [0, 2, 0]"))
        .unwrap();
    let p = m.links[0].placement.unwrap();
    assert_eq!(p.axis, [0.0, 1.0, 0.0], "scaled to unit length, exactly");
    // The DH fields belong to the DH conventions.
    let e = RobotModel::from_toml_str(&row("a = 0.5"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("<string>:5:1: link 1, field `a`: unknown field `a`")
            && e.contains("origin, axis"),
        "{e}"
    );
    let e = RobotModel::from_toml_str(&row("axis = [0, 0, 0]"))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("field `axis`") && e.contains("no direction"),
        "{e}"
    );
    // And `origin` to the urdf convention.
    let dh = "name = \"x\"\nconvention = \"standard\"\n[[links]]\njoint = \"revolute\"\na = 0\nalpha = 0\nd = 0\ntheta = 0\norigin = { xyz = [0, 0, 1] }\n";
    let e = RobotModel::from_toml_str(dh).unwrap_err().to_string();
    assert!(e.contains("unknown field `origin`"), "{e}");
}

#[test]
fn urdf_turns_about_the_joint_axis_become_offsets() {
    // UR5's shoulder, elbow and first wrist axes are parallel (y in the file), their frames a
    // quarter turn apart about that axis: the chain sees parallel axes with nothing but a
    // translation between them, as from UR's DH table, so the engine adds their angles.
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/urdf/ur5.urdf");
    let ur5 = dhgen_description::urdf::read_file(path, &UrdfOptions::default()).unwrap();
    let chain = ur5.model.chain();
    let view = chain.view();
    assert!(view.parallel_to_previous(2), "elbow after shoulder");
    assert!(view.parallel_to_previous(3), "wrist 1 after elbow");
    let offsets: Vec<f64> = view.bodies.iter().map(|b| b.offset).collect();
    assert_eq!(offsets[3], core::f64::consts::FRAC_PI_2, "{offsets:?}");
    // The frames are unchanged: the tool pose is URDF's at any q.
    let q = [0.3, -1.1, 0.8, 0.4, -0.6, 1.2];
    let t = view.tool_at(&q);
    let mut m = nalgebra::Matrix4::<f64>::identity();
    for (k, l) in ur5.model.links.iter().enumerate() {
        let p = l.placement.unwrap();
        let rpy = p.origin.rpy.map(|a| a.radians());
        m *= origin(p.origin.xyz, rpy).to_homogeneous()
            * nalgebra::Rotation3::from_axis_angle(
                &nalgebra::Unit::new_normalize(Vector3::from(p.axis)),
                q[k],
            )
            .to_homogeneous();
    }
    for i in 0..3 {
        assert!((t.p[i] - m[(i, 3)]).abs() < 1e-14);
        for j in 0..3 {
            assert!((t.r[i][j] - m[(i, j)]).abs() < 1e-14);
        }
    }
}

#[test]
fn urdf_base_starts_the_chain_below_the_root() {
    // From l1b: the chain is j2, j3 and the fixed tool; l1b's own mass stays with the fixed
    // base, j1 is above the chain.
    let r = read(
        ARM,
        "arm.urdf",
        &UrdfOptions {
            base: Some("l1b".into()),
            ..Default::default()
        },
    )
    .unwrap();
    let names: Vec<&str> = r.joints.iter().map(|j| j.name.as_str()).collect();
    assert_eq!(names, ["j2", "j3"]);
    assert_eq!((r.base.as_str(), r.tip.as_str()), ("l1b", "tool"));
    let full = read(ARM, "arm.urdf", &UrdfOptions::default()).unwrap();
    // The pose of `tool` relative to l1b, with j1 at zero, equals the full chain's at q1 = 0
    // seen from l1b's pose.
    let q = [0.7, 0.2];
    let sub = r.model.chain().view().tool_at(&q);
    let l1b = origin([0.1, 0.0, 0.05], [0.0, 0.0, 0.3])
        * origin([0.0, 0.0, 0.3], [0.0; 3])
        * origin([0.0, 0.05, 0.3], [core::f64::consts::FRAC_PI_2, 0.0, 0.0]);
    let whole = full.model.chain().view().tool_at(&[0.0, q[0], q[1]]);
    let want = l1b.inverse().to_homogeneous()
        * nalgebra::Matrix4::from_fn(|i, j| match (i, j) {
            (3, 3) => 1.0,
            (3, _) => 0.0,
            (i, 3) => whole.p[i],
            (i, j) => whole.r[i][j],
        });
    for i in 0..3 {
        assert!((sub.p[i] - want[(i, 3)]).abs() < 1e-14, "{sub:?} {want}");
        for j in 0..3 {
            assert!((sub.r[i][j] - want[(i, j)]).abs() < 1e-14);
        }
    }
    assert!((r.model.links[0].inertial.unwrap().mass - 1.5).abs() < 1e-15);
    // Gravity stays URDF's [0, 0, −9.81] in the root link's frame: seen from l1b (rolled a
    // quarter turn and yawed 0.3 rad against the root), it is turned; from the root, not.
    let g = l1b.rotation.inverse() * Vector3::new(0.0, 0.0, -9.81);
    for i in 0..3 {
        // (The reference turns through quaternions: a few ulps of 9.81.)
        assert!(
            (r.model.gravity[i] - g[i]).abs() < 1e-13,
            "{:?} {g}",
            r.model.gravity
        );
    }
    assert!(g.z.abs() < 1e-12, "the test turns gravity: {g}");
    assert_eq!(full.model.gravity, [0.0, 0.0, -9.81]);
    // A tip that is not below the base.
    let e = error(
        ARM,
        &UrdfOptions {
            base: Some("l2".into()),
            tip: Some("l1".into()),
            ..Default::default()
        },
    );
    assert!(e.contains("the tip `l1` is not below the base `l2`"), "{e}");
}

/// A one-joint arm: a fixed base and a moving link with mass, the joint with every element.
const ONE: &str = r#"<?xml version="1.0"?>
<robot name="r">
<link name="base"/>
<link name="l1"><inertial><origin xyz="0 0 0.1" rpy="0 0 0"/><mass value="1.0"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
<joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0.2" rpy="0 0 0"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="1"/><dynamics damping="0.1" friction="0.2"/></joint>
</robot>
"#;

/// `bad.urdf:line:column: ` of the first occurrence of `needle` in `text`: where an error
/// must point.
fn at(text: &str, needle: &str) -> String {
    let offset = text
        .find(needle)
        .unwrap_or_else(|| panic!("{needle:?} is not in\n{text}"));
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let column = before.rsplit('\n').next().unwrap_or("").chars().count() + 1;
    format!("bad.urdf:{line}:{column}: ")
}

/// `text` with `from` replaced by `to`, which must change it.
fn edit(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "{from:?} is not in\n{text}");
    text.replacen(from, to, 1)
}

/// The message the TOML validator gives a `urdf`-convention row with this `origin`.
fn toml_origin_message(origin: &str) -> String {
    let text = format!(
        "name = \"x\"\nconvention = \"urdf\"\n[[links]]\njoint = \"revolute\"\norigin = {origin}\n"
    );
    match RobotModel::from_toml_str(&text) {
        Err(LoadError::Invalid { error, .. }) => error.message,
        other => panic!("expected a validation error, got {other:?}"),
    }
}

#[test]
fn urdf_angles_outside_the_range_are_errors_as_in_toml() {
    assert!(read(ONE, "one.urdf", &UrdfOptions::default()).is_ok());
    for big in ["1e10", "1e308", "-1000.5"] {
        // The joint's origin: the TOML rule, word for word, at the attribute.
        let text = edit(
            ONE,
            "rpy=\"0 0 0\"/><axis",
            &format!("rpy=\"0 {big} 0\"/><axis"),
        );
        let e = bad(&text);
        let want = format!(
            "{}joint `j1` <origin rpy>: {}",
            at(&text, &format!("rpy=\"0 {big}")),
            toml_origin_message(&format!("{{ rpy = [0, {big}, 0] }}"))
        );
        assert_eq!(e, want);
        assert!(
            e.contains(&format!("angle {big} rad is outside the range")),
            "{e}"
        );
        // The inertial's origin, on the moving link.
        let text = edit(
            ONE,
            "rpy=\"0 0 0\"/><mass",
            &format!("rpy=\"{big} 0 0\"/><mass"),
        );
        let e = bad(&text);
        assert!(
            e.starts_with(&format!(
                "{}link `l1` <inertial> <origin rpy>: angle {big} rad is outside the range",
                at(&text, &format!("rpy=\"{big}"))
            )),
            "{e}"
        );
    }
    // The edge of the range is accepted, as in TOML.
    let text = edit(ONE, "rpy=\"0 0 0\"/><axis", "rpy=\"1000 0 -1000\"/><axis");
    assert!(read(&text, "edge.urdf", &UrdfOptions::default()).is_ok());
}

#[test]
fn urdf_free_bodies_off_the_chain_are_left_out() {
    let full = read(ARM, "arm.urdf", &UrdfOptions::default()).unwrap();
    // A 10 kg object on a floating joint below l2: not attached, so neither merged nor held.
    let object = "  <link name=\"tool\"/>\n  <joint name=\"grasped\" type=\"floating\"><parent link=\"l2\"/><child link=\"object\"/><origin xyz=\"0 0 0.5\"/></joint>\n  <link name=\"object\"><inertial><mass value=\"10\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" iyz=\"0\" ixz=\"0\"/></inertial></link>";
    let text = edit(ARM, "  <link name=\"tool\"/>", object);
    let r = read(&text, "free.urdf", &UrdfOptions::default()).unwrap();
    assert_eq!(r.left_out, ["grasped"]);
    assert!(r.locked.is_empty(), "{:?}", r.locked);
    assert_eq!(r.model, full.model, "the object's mass is not the arm's");
    // A planar joint with a movable joint of its own below it: the whole subtree is left out.
    let cart = "  <link name=\"tool\"/>\n  <joint name=\"cart\" type=\"planar\"><parent link=\"l1\"/><child link=\"c\"/><axis xyz=\"0 0 1\"/></joint>\n  <link name=\"c\"><inertial><mass value=\"3\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" iyz=\"0\" ixz=\"0\"/></inertial></link>\n  <joint name=\"wheel\" type=\"continuous\"><parent link=\"c\"/><child link=\"w\"/></joint>\n  <link name=\"w\"><inertial><mass value=\"1\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" iyz=\"0\" ixz=\"0\"/></inertial></link>";
    let text = edit(ARM, "  <link name=\"tool\"/>", cart);
    let options = UrdfOptions {
        tip: Some("tool".into()),
        ..Default::default()
    };
    let r = read(&text, "cart.urdf", &options).unwrap();
    assert_eq!(r.left_out, ["cart"]);
    assert!(r.locked.is_empty(), "{:?}", r.locked);
    assert_eq!(r.model, full.model);
    // On the chain it stays an error (`urdf_floating_joint_on_the_chain`); so does a planar one.
    let text = edit(
        ARM,
        "<joint name=\"j2\" type=\"continuous\">",
        "<joint name=\"j2\" type=\"planar\">",
    );
    let e = bad(&text);
    assert!(e.contains("joint `j2`") && e.contains("planar"), "{e}");
}

/// A serial chain of `n` revolute joints, one line per link and joint.
fn long_chain(n: usize) -> String {
    let mut text =
        String::from("<?xml version=\"1.0\"?>\n<robot name=\"long\">\n<link name=\"l0\"/>\n");
    for i in 1..=n {
        text.push_str(&format!(
            "<link name=\"l{i}\"/>\n<joint name=\"j{i}\" type=\"revolute\"><parent link=\"l{}\"/><child link=\"l{i}\"/><origin xyz=\"0 0 0.2\" rpy=\"0 0 0\"/><axis xyz=\"0 {} 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"1\"/></joint>\n",
            i - 1,
            i % 2
        ));
    }
    text.push_str("</robot>\n");
    text
}

/// Reading is linear in the size of the file: 20,000 joints took 51 s (release build) when
/// every position was found by scanning the text from its start and every link looked below
/// itself for movable joints; now a fraction of a second, in the debug build too.
#[test]
fn urdf_long_chains_read_in_linear_time() {
    let n = 20_000;
    let text = long_chain(n);
    let start = std::time::Instant::now();
    let r = read(&text, "long.urdf", &UrdfOptions::default()).unwrap();
    let seconds = start.elapsed().as_secs_f64();
    assert_eq!(r.joints.len(), n);
    assert_eq!(r.tip, format!("l{n}"));
    assert!(seconds < 20.0, "{n} joints took {seconds} s");
    // Positions at the end of the file are still exact: an error in the last joint.
    let text = edit(
        &text,
        &format!("<joint name=\"j{n}\" type=\"revolute\">"),
        &format!("<joint name=\"j{n}\" type=\"spherical\">"),
    );
    let e = bad(&text);
    assert!(e.starts_with(&at(&text, "type=\"spherical\"")), "{e}");
}

/// Errors name URDF's elements and attributes, at the attribute, not the description's fields
/// (`origin.xyz`, `friction.viscous`, `limits`) at the joint.
#[test]
fn urdf_errors_name_the_attribute_where_it_is() {
    let range = "is outside the range of any robot";
    let cases = [
        (
            "xyz=\"0 0 0.2\"",
            "xyz=\"0 1e308 0.2\"",
            "joint `j1` <origin xyz>: length 1e308 m",
        ),
        (
            "damping=\"0.1\"",
            "damping=\"1e308\"",
            "joint `j1` <dynamics damping>: friction coefficient 1e308",
        ),
        (
            "friction=\"0.2\"",
            "friction=\"1e7\"",
            "joint `j1` <dynamics friction>: friction coefficient 1e7",
        ),
        (
            "lower=\"-1\"",
            "lower=\"-1e6\"",
            "joint `j1` <limit lower>: angle -1e6 rad",
        ),
        (
            "upper=\"1\"",
            "upper=\"1000.0000001\"",
            "joint `j1` <limit upper>: angle 1000.0000001 rad",
        ),
        (
            "ixx=\"0.01\"",
            "ixx=\"1e308\"",
            "link `l1` <inertial> <inertia ixx>: inertia 1e308 kg·m²",
        ),
        (
            "iyz=\"0\"",
            "iyz=\"-2e9\"",
            "link `l1` <inertial> <inertia iyz>: inertia -2e9 kg·m²",
        ),
        (
            "value=\"1.0\"",
            "value=\"1e308\"",
            "link `l1` <inertial> <mass value>: mass 1e308 kg",
        ),
    ];
    for (from, to, what) in cases {
        let text = edit(ONE, from, to);
        let e = bad(&text);
        assert!(
            e.starts_with(&format!("{}{what} {range}", at(&text, to))),
            "{e}\nshould start with {}{what}",
            at(&text, to)
        );
    }
    // A prismatic joint's limits are lengths.
    let text = edit(ONE, "type=\"revolute\"", "type=\"prismatic\"");
    let text = edit(&text, "upper=\"1\"", "upper=\"2e3\"");
    let e = bad(&text);
    assert!(
        e.starts_with(&format!(
            "{}joint `j1` <limit upper>: length 2000 m {range}",
            at(&text, "upper=\"2e3\"")
        )),
        "{e}"
    );
    // Rules across values, checked by the validator, in the file's terms too.
    let text = edit(ONE, "damping=\"0.1\"", "damping=\"-0.1\"");
    assert_eq!(
        bad(&text),
        format!(
            "{}joint `j1` <dynamics damping>: friction coefficient -0.1 is negative",
            at(&text, "damping=")
        )
    );
    let text = edit(ONE, "lower=\"-1\" upper=\"1\"", "lower=\"1\" upper=\"-1\"");
    assert_eq!(
        bad(&text),
        format!(
            "{}joint `j1` <limit lower upper>: lower limit 1 rad (57.2958°) is not below upper \
             limit -1 rad (-57.2958°): write them in order, or leave out lower and upper for a \
             joint without position limits (Bullet reads lower > upper as no limits; dhgen does \
             not guess)",
            at(&text, "lower=")
        )
    );
    // What the reader derives: an origin composed through fixed joints, merged masses.
    let fixed = "<link name=\"base\"/>\n<link name=\"mount\"><inertial><mass value=\"6e5\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" iyz=\"0\" ixz=\"0\"/></inertial></link>\n<joint name=\"m\" type=\"fixed\"><parent link=\"base\"/><child link=\"mount\"/><origin xyz=\"600 0 0\"/></joint>";
    let text = edit(ONE, "<link name=\"base\"/>", fixed);
    let text = edit(
        &text,
        "<parent link=\"base\"/><child link=\"l1\"/><origin xyz=\"0 0 0.2\"",
        "<parent link=\"mount\"/><child link=\"l1\"/><origin xyz=\"600 0 0.2\"",
    );
    let e = bad(&text);
    assert!(
        e.contains(
            "joint `j1` <origin xyz> composed with the fixed joints before it: length 1200 m"
        ),
        "{e}"
    );
    let flange = "<link name=\"f1\"/><link name=\"f2\"/>\n<joint name=\"a\" type=\"fixed\"><parent link=\"l1\"/><child link=\"f1\"/><origin xyz=\"0 0 600\"/></joint>\n<joint name=\"b\" type=\"fixed\"><parent link=\"f1\"/><child link=\"f2\"/><origin xyz=\"0 0 600\"/></joint>\n</robot>";
    let e = bad(&edit(ONE, "</robot>", flange));
    assert!(
        e.contains(
            "<origin xyz> of the fixed joints after the last joint, composed (the tool frame): \
             length 1200 m"
        ),
        "{e}"
    );
    let fixed_below = "</robot>";
    let text = edit(
        ONE,
        fixed_below,
        "<link name=\"weight\"><inertial><mass value=\"6e5\"/><inertia ixx=\"1\" iyy=\"1\" izz=\"1\" ixy=\"0\" iyz=\"0\" ixz=\"0\"/></inertial></link>\n<joint name=\"w\" type=\"fixed\"><parent link=\"l1\"/><child link=\"weight\"/></joint>\n</robot>",
    );
    let text = edit(&text, "value=\"1.0\"", "value=\"6e5\"");
    let e = bad(&text);
    assert!(
        e.contains("joint `j1`: link `l1` with the links fixed to it, mass: mass 1.2e6 kg"),
        "{e}"
    );
}

/// URDF requires all six entries of `<inertia>` (ROS's urdfdom rejects the element
/// otherwise): a missing one is an error naming it, not a silent 0.
#[test]
fn urdf_inertia_needs_all_six_entries() {
    for key in ["ixx", "iyy", "izz", "ixy", "iyz", "ixz"] {
        let text = edit(ONE, &format!(" {key}=\""), &format!(" {key}_=\""));
        let e = bad(&text);
        assert_eq!(
            e,
            format!(
                "{}link `l1` <inertial> <inertia> has no `{key}`; URDF requires all six of ixx, \
                 ixy, ixz, iyy, iyz, izz (write 0 for a zero)",
                at(&text, "<inertia ")
            )
        );
    }
}

/// A URDF file read as TOML (named `.toml`, or with no extension) says what it looks like.
#[test]
fn urdf_text_read_as_toml_gets_a_hint() {
    let hint = "this looks like XML (URDF): name the file .urdf";
    for text in [ONE.to_string(), format!("\u{feff}\n  {ONE}")] {
        let e = RobotModel::from_toml_named(&text, "arm.toml").unwrap_err();
        assert!(matches!(e, LoadError::Syntax { .. }), "{e:?}");
        let e = e.to_string();
        assert!(
            e.starts_with("arm.toml:") && e.contains("invalid TOML"),
            "{e}"
        );
        assert!(e.ends_with(hint), "{e}");
    }
    let e = RobotModel::from_toml_str("name = \n")
        .unwrap_err()
        .to_string();
    assert!(!e.contains("XML"), "{e}");
}
