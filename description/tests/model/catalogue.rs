//! Every robot of the catalogue loads and validates, with the joints and dynamics it is
//! meant to have; the hand-written ones are checked against their geometry.

use crate::support::{dh_frames, dir, load};
use dhgen_description::{Convention, Frame, JointKind, RobotModel};

/// `(file stem, convention, joint kinds as R/P, has dynamics)` of every catalogue robot.
pub const CATALOGUE: &[(&str, Convention, &str, bool)] = &[
    ("cylindrical", Convention::Standard, "RPPRRR", false),
    ("panda", Convention::Modified, "RRRRRRR", true),
    ("planar_elbow", Convention::Standard, "RR", true),
    ("puma560", Convention::Standard, "RRRRRR", true),
    ("scara", Convention::Standard, "RRPR", true),
    ("stanford", Convention::Standard, "RRPRRR", true),
    ("ur5", Convention::Standard, "RRRRRR", true),
];

fn kinds(robot: &RobotModel) -> String {
    robot
        .links
        .iter()
        .map(|l| match l.joint {
            JointKind::Revolute => 'R',
            JointKind::Prismatic => 'P',
        })
        .collect()
}

#[test]
fn every_file_is_listed_and_every_listed_file_exists() {
    let mut stems: Vec<String> = std::fs::read_dir(dir())
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "toml"))
        .map(|path| path.file_stem().unwrap().to_string_lossy().into_owned())
        .collect();
    stems.sort();
    let listed: Vec<&str> = CATALOGUE.iter().map(|(stem, ..)| *stem).collect();
    assert_eq!(stems, listed, "robots/*.toml and CATALOGUE differ");
}

#[test]
fn catalogue_robots_have_their_expected_shape() {
    for &(stem, convention, joints, dynamics) in CATALOGUE {
        let robot = load(stem);
        assert_eq!(robot.name, stem, "the name is the file's stem");
        assert_eq!(robot.convention, convention, "{stem}");
        assert_eq!(robot.dof(), joints.len(), "{stem}");
        assert_eq!(kinds(&robot), joints, "{stem}");
        assert_eq!(robot.has_dynamics(), dynamics, "{stem}");
        assert!(robot.description.is_some(), "{stem} has a description");
    }
}

/// Frames 0..=n of a standard or modified DH chain at `q` ([`dh_frames`]); base and tool
/// poses left out: the robots checked here have none.
fn frames(robot: &RobotModel, q: &[f64]) -> Vec<Frame<f64>> {
    assert_eq!(robot.base, None);
    assert_eq!(robot.tool, None);
    dh_frames(robot, q)
}

fn assert_close(actual: [f64; 3], expected: [f64; 3], what: &str) {
    for (a, e) in actual.iter().zip(expected) {
        assert!((a - e).abs() < 1e-12, "{what}: {actual:?} != {expected:?}");
    }
}

#[test]
fn cylindrical_arm_is_the_text_dh_table() {
    let robot = load("cylindrical");
    // The text's table: a = 0 throughout; alpha = 0, -90, 0, -90, 90, 0 degrees; theta
    // offsets 0; d1 and d6 constant.
    let alphas: Vec<_> = robot.links.iter().map(|l| l.alpha.quarter_turn()).collect();
    let quarter = |c, s| Some((c, s));
    assert_eq!(
        alphas,
        [
            quarter(1, 0),
            quarter(0, -1),
            quarter(1, 0),
            quarter(0, -1),
            quarter(0, 1),
            quarter(1, 0)
        ]
    );
    assert!(robot.links.iter().all(|l| l.a == 0.0));
    assert!(robot.links.iter().all(|l| l.theta.radians() == 0.0));
    let d: Vec<f64> = robot.links.iter().map(|l| l.d).collect();
    assert_eq!(d, [0.5, 0.0, 0.0, 0.0, 0.0, 0.1]);

    // Cylindrical geometry: with the column turned by 90deg, the lift q2 adds to the height
    // d1 and the reach q3 (plus d6, the wrist pointing along the reach) runs along -x0.
    let f = frames(&robot, &[90f64.to_radians(), 0.2, 0.3, 0.0, 0.0, 0.0]);
    assert_close(f[6].p, [-(0.3 + 0.1), 0.0, 0.5 + 0.2], "flange");

    // Spherical wrist: o3 = o4 = o5 (the wrist centre) whatever the wrist angles, and the
    // flange is d6 along z5.
    let f = frames(&robot, &[0.3, 0.1, 0.4, 0.7, -1.1, 2.0]);
    assert_close(f[4].p, f[3].p, "o4 = o3");
    assert_close(f[5].p, f[3].p, "o5 = o3");
    let z5 = f[5].z_axis();
    let expected = core::array::from_fn(|i| f[5].p[i] + 0.1 * z5[i]);
    assert_close(f[6].p, expected, "o6 = o5 + d6 z5");
}

#[test]
fn ur5_zero_pose_is_the_published_geometry() {
    // At q = 0 the UR5 lies stretched along -x0: x = a2 + a3, the wrist offsets d4 and d6
    // along -y0, and z = d1 - d5.
    let robot = load("ur5");
    let f = frames(&robot, &[0.0; 6]);
    assert_close(
        f[6].p,
        [-0.425 - 0.39225, -(0.10915 + 0.0823), 0.089159 - 0.09465],
        "flange",
    );
    assert_close(f[6].z_axis(), [0.0, -1.0, 0.0], "tool axis");
}

#[test]
fn scara_geometry_and_actuators() {
    let robot = load("scara");
    // Stretched out along x0 at the arm-plane height, the quill pointing down.
    let f = frames(&robot, &[0.0, 0.0, 0.1, 0.0]);
    assert_close(f[4].p, [0.325 + 0.225, 0.0, 0.4 - 0.1 - 0.05], "flange");
    assert_close(f[4].z_axis(), [0.0, 0.0, -1.0], "quill axis");
    // Elbow at 90deg: the forearm points along y1.
    let f = frames(&robot, &[0.0, 90f64.to_radians(), 0.0, 0.0]);
    assert_close(f[4].p, [0.325, 0.225, 0.35], "flange, elbow bent");

    // The catalogue's motor and friction fields are exercised here.
    let motors = robot.links.iter().filter(|l| l.motor.is_some()).count();
    let frictions = robot.links.iter().filter(|l| l.friction.is_some()).count();
    assert_eq!((motors, frictions), (3, 4));
    let prismatic = &robot.links[2];
    assert_eq!(prismatic.limits, Some([0.0, 0.15]));
    assert!(prismatic.friction.is_some_and(|f| f.viscous > 0.0));
}

#[test]
fn descriptions_written_back_read_back_equal() {
    use dhgen_description::random::{ArmStyle, random_arm};
    let mut models: Vec<RobotModel> = CATALOGUE.iter().map(|(stem, ..)| load(stem)).collect();
    for dof in [1, 2, 6, 7, 17, 30] {
        for style in [ArmStyle::General, ArmStyle::Industrial] {
            for seed in 0..3 {
                models.push(random_arm(dof, style, seed));
            }
        }
    }
    for model in models {
        let text = model.to_toml();
        let back = RobotModel::from_toml_str(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
        assert_eq!(back, model, "{text}");
    }
}

#[test]
fn random_arms_are_reproducible_and_of_their_style() {
    use dhgen_description::random::{ArmStyle, random_arm};
    assert_eq!(
        random_arm(9, ArmStyle::General, 4),
        random_arm(9, ArmStyle::General, 4)
    );
    assert_ne!(
        random_arm(9, ArmStyle::General, 4),
        random_arm(9, ArmStyle::General, 5)
    );
    for seed in 0..20 {
        let general = random_arm(12, ArmStyle::General, seed);
        assert!(general.has_dynamics());
        assert!(
            general
                .links
                .iter()
                .all(|l| l.alpha.quarter_turn().is_none() && l.a != 0.0)
        );
        let industrial = random_arm(12, ArmStyle::Industrial, seed);
        assert!(
            industrial
                .links
                .iter()
                .all(|l| l.alpha.quarter_turn().is_some() && l.theta.quarter_turn().is_some())
        );
    }
}
