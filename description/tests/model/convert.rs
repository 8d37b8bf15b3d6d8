//! Conversions between descriptions (`dhgen_description::convert`): every catalogue robot, URDF
//! fixture, random arm and hand-made awkward chain keeps its tool pose and the world-frame
//! mass properties of every body at random configurations, through `to_dh` in each
//! convention and through `to_urdf` and the URDF reader; exact quarter turns and zeros stay
//! exact.
//!
//! The comparison uses only the DH formula (`Link::transform`, via `support::dh_frames`) and
//! each row's mass properties in its link frame, not the chain the conversion starts from.

use crate::catalogue::CATALOGUE;
use crate::support::{dh_frames, load};
use dhgen_description::convert::{ConvertError, to_dh, to_urdf};
use dhgen_description::random::{ArmStyle, random_arm};
use dhgen_description::urdf::{UrdfOptions, read};
use dhgen_description::{Convention, Frame, Friction, JointKind, RobotModel};

const CONVENTIONS: [Convention; 3] = [Convention::Standard, Convention::Modified, Convention::Urdf];

/// The URDF fixtures and the tip each is read to.
const FIXTURES: &[(&str, &str)] = &[
    ("panda", "panda_hand"),
    ("ur5", "wrist_3_link"),
    ("kinova", "j2s6s200_end_effector"),
    ("double_pendulum_continuous", "link2"),
    ("baxter", "left_gripper"),
];

fn fixture(stem: &str, tip: &str) -> RobotModel {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../tests/data/urdf/");
    let text = std::fs::read_to_string(format!("{path}{stem}.urdf")).unwrap();
    read(
        &text,
        stem,
        &UrdfOptions {
            tip: Some(tip.into()),
            ..Default::default()
        },
    )
    .unwrap_or_else(|e| panic!("{e}"))
    .model
}

/// Reads a document written by `to_urdf`, to its `tool` link when it has one.
fn read_back(text: &str, dof: usize) -> RobotModel {
    let tip = if text.contains("<link name=\"tool\"/>") {
        "tool".to_string()
    } else {
        format!("link{dof}")
    };
    read(
        text,
        "written.urdf",
        &UrdfOptions {
            tip: Some(tip),
            ..Default::default()
        },
    )
    .unwrap_or_else(|e| panic!("{e}\n{text}"))
    .model
}

/// SplitMix64, for reproducible configurations.
struct Stream(u64);

impl Stream {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// `count` configurations: revolute joints in (−π, π), prismatic in (−0.5, 0.5) m; the first
/// is q = 0.
fn configurations(model: &RobotModel, count: usize, seed: u64) -> Vec<Vec<f64>> {
    let mut s = Stream(seed);
    let mut out = vec![vec![0.0; model.dof()]];
    while out.len() < count {
        out.push(
            model
                .links
                .iter()
                .map(|l| match l.joint {
                    JointKind::Revolute => std::f64::consts::PI * (2.0 * s.next() - 1.0),
                    JointKind::Prismatic => s.next() - 0.5,
                })
                .collect(),
        );
    }
    out
}

type Mass = (f64, [f64; 3], [[f64; 3]; 3]);

/// The tool pose and each body's mass, centre of mass and inertia about it in world axes,
/// by the DH formula (or the `urdf` rows' origin and axis) alone.
fn world(model: &RobotModel, q: &[f64]) -> (Frame<f64>, Vec<Option<Mass>>) {
    let frames = dh_frames(model, q);
    let n = model.dof();
    let tool = model
        .tool
        .map_or(frames[n], |t| frames[n].compose(&t.frame::<f64>()));
    let bodies = model
        .links
        .iter()
        .enumerate()
        .map(|(k, l)| {
            l.inertial.map(|i| {
                let f = &frames[k + 1];
                let r = &f.r;
                let inertia = core::array::from_fn(|a| {
                    core::array::from_fn(|b| {
                        (0..3)
                            .map(|c| {
                                r[a][c] * (0..3).map(|d| i.inertia[c][d] * r[b][d]).sum::<f64>()
                            })
                            .sum()
                    })
                });
                (i.mass, f.point(&i.com), inertia)
            })
        })
        .collect();
    (tool, bodies)
}

/// The worst differences seen: tool pose (relative to the arm's size), centre of mass
/// (relative), inertia (relative to the robot's largest entry).
#[derive(Clone, Copy, Debug, Default)]
struct Worst {
    tool: f64,
    com: f64,
    inertia: f64,
}

impl Worst {
    fn max(self, o: Worst) -> Worst {
        Worst {
            tool: self.tool.max(o.tool),
            com: self.com.max(o.com),
            inertia: self.inertia.max(o.inertia),
        }
    }
}

const TOLERANCE: f64 = 1e-12;

/// Asserts that `b` is the robot `a`: the same joints, limits and (unless a URDF lies between
/// them) gravity, motors and friction; the same tool pose and world-frame mass properties at
/// 20 configurations, to 1e-12 of the arm's size and of the largest inertia entry.
fn same_robot(a: &RobotModel, b: &RobotModel, through_urdf: bool, what: &str) -> Worst {
    assert_eq!(a.dof(), b.dof(), "{what}: dof");
    assert_eq!(a.has_dynamics(), b.has_dynamics(), "{what}: dynamics");
    for (k, (la, lb)) in a.links.iter().zip(&b.links).enumerate() {
        assert_eq!(la.joint, lb.joint, "{what}: joint {}", k + 1);
        assert_eq!(la.limits, lb.limits, "{what}: limits of joint {}", k + 1);
        assert_eq!(
            la.friction.unwrap_or_default(),
            lb.friction.unwrap_or_default(),
            "{what}: friction of joint {}",
            k + 1
        );
        if !through_urdf {
            assert_eq!(la.motor, lb.motor, "{what}: motor of joint {}", k + 1);
        }
    }
    if !through_urdf {
        assert_eq!(a.gravity, b.gravity, "{what}: gravity");
        assert_eq!(a.name, b.name, "{what}: name");
        assert_eq!(a.description, b.description, "{what}: description");
    }
    let scale = a.chain().view().length_scale();
    let big = a
        .links
        .iter()
        .filter_map(|l| l.inertial)
        .flat_map(|i| i.inertia.into_iter().flatten())
        .fold(0.0f64, |m, x| m.max(x.abs()))
        .max(1e-9);
    let mut worst = Worst::default();
    for q in configurations(a, 20, 17 + a.dof() as u64) {
        let (ta, ma) = world(a, &q);
        let (tb, mb) = world(b, &q);
        for i in 0..3 {
            worst.tool = worst.tool.max((ta.p[i] - tb.p[i]).abs() / scale);
            for j in 0..3 {
                worst.tool = worst.tool.max((ta.r[i][j] - tb.r[i][j]).abs());
            }
        }
        for (k, (x, y)) in ma.iter().zip(&mb).enumerate() {
            let (Some(x), Some(y)) = (x, y) else {
                assert!(x.is_none() && y.is_none(), "{what}: body {}", k + 1);
                continue;
            };
            assert_eq!(x.0, y.0, "{what}: mass of body {}", k + 1);
            for i in 0..3 {
                worst.com = worst.com.max((x.1[i] - y.1[i]).abs() / scale);
                for j in 0..3 {
                    worst.inertia = worst.inertia.max((x.2[i][j] - y.2[i][j]).abs() / big);
                }
            }
        }
    }
    assert!(
        worst.tool <= TOLERANCE && worst.com <= TOLERANCE && worst.inertia <= TOLERANCE,
        "{what}: {worst:?}"
    );
    worst
}

#[test]
fn catalogue_to_dh_keeps_the_robot() {
    let mut worst = Worst::default();
    for &(stem, ..) in CATALOGUE {
        let robot = load(stem);
        for convention in CONVENTIONS {
            let what = format!("{stem} -> {convention:?}");
            let converted = to_dh(&robot, convention).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert_eq!(converted.convention, convention, "{what}");
            worst = worst.max(same_robot(&robot, &converted, false, &what));
            // And back.
            let back = to_dh(&converted, robot.convention).unwrap();
            worst = worst.max(same_robot(&robot, &back, false, &format!("{what} -> back")));
        }
    }
    eprintln!("catalogue to_dh: worst {worst:?}");
}

#[test]
fn catalogue_to_dh_in_its_own_convention_gives_the_same_table() {
    for &(stem, ..) in CATALOGUE {
        let robot = load(stem);
        let same = to_dh(&robot, robot.convention).unwrap();
        let scale = robot.chain().view().length_scale();
        let close = |x: f64, y: f64| (x - y).abs() <= 1e-15 * scale;
        for (k, (a, b)) in robot.links.iter().zip(&same.links).enumerate() {
            let at = format!("{stem} row {}", k + 1);
            assert!(close(a.a, b.a) && close(a.d, b.d), "{at}: {a:?} vs {b:?}");
            for (x, y) in [(a.alpha, b.alpha), (a.theta, b.theta)] {
                assert_eq!(x.quarter_turn(), y.quarter_turn(), "{at}");
                assert!(
                    (x.radians() - y.radians()).abs() <= 1e-15,
                    "{at}: {x:?} vs {y:?}"
                );
            }
            // Exact zeros stay exact zeros.
            assert_eq!(a.a == 0.0, b.a == 0.0, "{at}: a");
            assert_eq!(a.d == 0.0, b.d == 0.0, "{at}: d");
            assert_eq!(a.collision, b.collision, "{at}: the capsule is kept");
        }
        for (x, y) in [
            (robot.base_pose(), same.base_pose()),
            (robot.tool_pose(), same.tool_pose()),
        ] {
            match (x, y) {
                (None, None) => {}
                (Some(x), Some(y)) => {
                    for i in 0..3 {
                        assert!(close(x.xyz[i], y.xyz[i]), "{stem}: {x:?} vs {y:?}");
                        assert!((x.rpy[i].radians() - y.rpy[i].radians()).abs() <= 1e-15);
                    }
                }
                _ => panic!("{stem}: base or tool {x:?} became {y:?}"),
            }
        }
    }
}

#[test]
fn catalogue_to_urdf_reads_back_as_the_same_robot() {
    let mut worst = Worst::default();
    for &(stem, ..) in CATALOGUE {
        let robot = load(stem);
        let text = to_urdf(&robot);
        let back = read_back(&text, robot.dof());
        worst = worst.max(same_robot(&robot, &back, true, &format!("{stem} -> URDF")));
        // Through the `urdf` convention model too.
        let model = to_dh(&robot, Convention::Urdf).unwrap();
        let back = read_back(&to_urdf(&model), robot.dof());
        worst = worst.max(same_robot(
            &robot,
            &back,
            true,
            &format!("{stem} -> urdf -> URDF"),
        ));
    }
    eprintln!("catalogue to_urdf: worst {worst:?}");
}

#[test]
fn urdf_fixtures_to_dh_keep_the_robot() {
    let mut worst = Worst::default();
    for &(stem, tip) in FIXTURES {
        let robot = fixture(stem, tip);
        for convention in [Convention::Standard, Convention::Modified] {
            let what = format!("{stem}.urdf -> {convention:?}");
            let dh = to_dh(&robot, convention).unwrap_or_else(|e| panic!("{what}: {e}"));
            worst = worst.max(same_robot(&robot, &dh, false, &what));
            // URDF → DH → URDF.
            let back = read_back(&to_urdf(&dh), robot.dof());
            worst = worst.max(same_robot(&robot, &back, true, &format!("{what} -> URDF")));
        }
        // A `urdf` model stays as it is; its document reads back as the same robot.
        assert_eq!(to_dh(&robot, Convention::Urdf).unwrap(), robot, "{stem}");
        let back = read_back(&to_urdf(&robot), robot.dof());
        worst = worst.max(same_robot(
            &robot,
            &back,
            true,
            &format!("{stem}.urdf -> URDF"),
        ));
    }
    eprintln!("URDF fixtures: worst {worst:?}");
}

#[test]
fn random_arms_convert_in_both_conventions() {
    let mut worst = Worst::default();
    for style in [ArmStyle::General, ArmStyle::Industrial] {
        for dof in 1..=8 {
            for seed in 0..4 {
                let arm = random_arm(dof, style, seed);
                let what = arm.name.clone();
                let modified = to_dh(&arm, Convention::Modified).unwrap();
                worst = worst.max(same_robot(
                    &arm,
                    &modified,
                    false,
                    &format!("{what} -> modified"),
                ));
                let standard = to_dh(&modified, Convention::Standard).unwrap();
                worst = worst.max(same_robot(
                    &arm,
                    &standard,
                    false,
                    &format!("{what} -> back"),
                ));
                let urdf = to_dh(&modified, Convention::Urdf).unwrap();
                worst = worst.max(same_robot(&arm, &urdf, false, &format!("{what} -> urdf")));
                let standard = to_dh(&urdf, Convention::Standard).unwrap();
                worst = worst.max(same_robot(
                    &arm,
                    &standard,
                    false,
                    &format!("{what} -> urdf -> standard"),
                ));
                let back = read_back(&to_urdf(&modified), dof);
                worst = worst.max(same_robot(&arm, &back, true, &format!("{what} -> URDF")));
                if style == ArmStyle::Industrial {
                    // Quarter-turn twists stay exact quarter turns.
                    for l in modified.links.iter().chain(&standard.links) {
                        assert!(l.alpha.quarter_turn().is_some(), "{what}: {l:?}");
                    }
                }
            }
        }
    }
    eprintln!("random arms: worst {worst:?}");
}

#[test]
fn puma560_in_modified_dh_is_exact() {
    let puma = load("puma560");
    let m = to_dh(&puma, Convention::Modified).unwrap();
    assert_eq!(m.base, None);
    assert_eq!(m.tool, None);
    // Modified row i + 1 holds the common normal of axes i and i + 1: standard row i's a and
    // α, exactly; the d and θ of both are measured between the same normals.
    assert_eq!(m.links[0].a, 0.0);
    assert_eq!(m.links[0].alpha.quarter_turn(), Some((1, 0)));
    for i in 1..6 {
        let (s, t) = (&puma.links[i - 1], &m.links[i]);
        assert_eq!(t.a, s.a, "a_{i}");
        assert_eq!(t.alpha.quarter_turn(), s.alpha.quarter_turn(), "alpha_{i}");
        assert!(t.alpha.quarter_turn().is_some());
    }
    for i in 0..6 {
        let (s, t) = (&puma.links[i], &m.links[i]);
        assert_eq!(t.d, s.d, "d_{}", i + 1);
        assert_eq!(t.theta.quarter_turn(), Some((1, 0)), "theta_{}", i + 1);
    }
    // The twists (Craig's table has −90° for α_1: his x_1 points the other way; ours follows
    // the standard table's x_1, so θ stays 0).
    let alphas: Vec<_> = m.links.iter().map(|l| l.alpha.quarter_turn()).collect();
    assert_eq!(
        alphas,
        [(1, 0), (0, 1), (1, 0), (0, -1), (0, 1), (0, -1)].map(Some),
    );
    // And back: the published standard table.
    let s = to_dh(&m, Convention::Standard).unwrap();
    for (a, b) in puma.links.iter().zip(&s.links) {
        assert_eq!((a.a, a.d), (b.a, b.d));
        assert_eq!(a.alpha.quarter_turn(), b.alpha.quarter_turn());
        assert_eq!(b.theta.quarter_turn(), Some((1, 0)));
    }
    assert_eq!((s.base, s.tool), (None, None));
}

#[test]
fn panda_urdf_gives_exact_quarter_turn_twists_and_franka_table() {
    let urdf = fixture("panda", "panda_hand");
    let catalogue = load("panda");
    for convention in [Convention::Standard, Convention::Modified] {
        let dh = to_dh(&urdf, convention).unwrap();
        for (k, l) in dh.links.iter().enumerate() {
            assert!(
                l.alpha.quarter_turn().is_some(),
                "{convention:?} row {}: {l:?}",
                k + 1
            );
            assert!(
                l.theta.quarter_turn().is_some(),
                "{convention:?} row {}: {l:?}",
                k + 1
            );
        }
        assert_eq!(dh.base, None, "{convention:?}");
    }
    // The URDF's link frames are Franka's modified DH frames: the same table comes out,
    // except that the URDF's link 7 frame is at joint 7, not at the flange 0.107 m further
    // (the catalogue's d_7), so the flange is in the tool.
    let dh = to_dh(&urdf, Convention::Modified).unwrap();
    for (k, (a, b)) in catalogue.links.iter().zip(&dh.links).enumerate() {
        let d = if k == 6 { a.d - 0.107 } else { a.d };
        assert!(
            (a.a - b.a).abs() < 1e-15 && (d - b.d).abs() < 1e-15,
            "row {}: {b:?}",
            k + 1
        );
        assert_eq!(
            a.alpha.quarter_turn(),
            b.alpha.quarter_turn(),
            "row {}",
            k + 1
        );
        assert_eq!(b.theta.quarter_turn(), Some((1, 0)), "row {}", k + 1);
    }
    let tool = dh.tool.unwrap();
    assert_eq!(tool.xyz, [0.0, 0.0, 0.107]);
    assert_eq!(
        tool.rpy.map(|a| a.radians()),
        [0.0, 0.0, -std::f64::consts::FRAC_PI_4]
    );
}

/// Awkward chains: a base and a tool, joint offsets, prismatic joints first and last,
/// coincident, antiparallel, intersecting and oblique axes, one joint.
const AWKWARD: &[&str] = &[
    r#"
    name = "offsets"
    description = "modified, every constant non-zero"
    convention = "modified"
    gravity = [0.5, -1.0, -9.0]
    base = { xyz = [0.1, -0.2, 0.3], rpy = [0.2, -0.4, 1.1] }
    tool = { xyz = [0.01, 0.02, 0.15], rpy = ["90deg", 0.3, -0.2] }
    [[links]]
    joint = "prismatic"
    a = 0.05
    alpha = 0.3
    d = 0.2
    theta = 0.4
    limits = [-0.1, 0.4]
    mass = 1.0
    com = [0.01, 0.02, 0.03]
    inertia = { xx = 0.02, yy = 0.03, zz = 0.04, xy = 0.001, yz = -0.002, xz = 0.003 }
    motor = { inertia = 1e-4, gear = -50 }
    friction = { viscous = 0.3, coulomb = 0.1 }
    [[links]]
    joint = "revolute"
    a = 0.3
    alpha = "180deg"
    d = -0.1
    theta = "-90deg"
    mass = 2.0
    com = [0.1, 0.0, -0.02]
    inertia = { xx = 0.05, yy = 0.06, zz = 0.07 }
    collision = { radius = 0.05 }
    [[links]]
    joint = "revolute"
    a = 0.0
    alpha = 0.0
    d = 0.0
    theta = 1.0
    mass = 0.5
    com = [0.0, 0.0, 0.1]
    inertia = { xx = 0.01, yy = 0.01, zz = 0.002 }
    [[links]]
    joint = "prismatic"
    a = 0.0
    alpha = 0.0
    d = 0.1
    theta = 0.0
    mass = 0.5
    com = [0.0, 0.0, 0.1]
    inertia = { xx = 0.01, yy = 0.01, zz = 0.002 }
    "#,
    r#"
    name = "one"
    convention = "standard"
    base = { xyz = [1.0, 2.0, 0.5], rpy = [0.0, "90deg", 0.0] }
    tool = { xyz = [0.3, 0.0, 0.1], rpy = [0.0, 0.0, "180deg"] }
    [[links]]
    joint = "revolute"
    a = 0.4
    alpha = "-90deg"
    d = 0.2
    theta = 0.7
    mass = 3.0
    com = [-0.2, 0.0, 0.0]
    inertia = { xx = 0.01, yy = 0.05, zz = 0.05 }
    "#,
    r#"
    name = "one_prismatic"
    convention = "modified"
    [[links]]
    joint = "prismatic"
    a = 0.0
    alpha = 0.0
    d = 0.0
    theta = 0.0
    "#,
    r#"
    name = "oblique"
    convention = "urdf"
    base = { xyz = [0.0, 0.1, 0.2], rpy = [0.1, 0.0, 0.0] }
    tool = { xyz = [0.0, 0.0, 0.12], rpy = [3.141592653589793, 0.0, 0.0] }
    [[links]]
    joint = "revolute"
    origin = { xyz = [0.0, 0.0, 0.3] }
    axis = [0.0, 1.0, 0.0]
    mass = 2.5
    com = [0.01, 0.02, 0.15]
    inertia = { xx = 0.05, yy = 0.04, zz = 0.02, xy = 0.001, yz = -0.002, xz = 0.003 }
    [[links]]
    joint = "revolute"
    origin = { xyz = [0.02, 0.05, 0.4], rpy = ["90deg", "-90deg", 0.0] }
    axis = [-1.0, 0.0, 0.0]
    mass = 1.5
    com = [0.0, 0.0, 0.1]
    inertia = { xx = 0.02, yy = 0.02, zz = 0.004 }
    [[links]]
    joint = "prismatic"
    origin = { xyz = [0.0, 0.0, 0.2], rpy = [0.4, 0.0, 0.0] }
    axis = [0.0, 0.6, 0.8]
    limits = [0.0, 0.3]
    mass = 0.8
    com = [0.0, 0.0, 0.0]
    inertia = { xx = 0.003, yy = 0.003, zz = 0.001 }
    [[links]]
    joint = "revolute"
    origin = { xyz = [0.1, 0.0, 0.0] }
    axis = [0.0, 0.6, 0.8]
    mass = 0.3
    com = [0.0, 0.0, 0.0]
    inertia = { xx = 0.001, yy = 0.001, zz = 0.001 }
    [[links]]
    joint = "revolute"
    origin = { xyz = [0.0, 0.0, 0.0], rpy = [0.0, 0.0, 0.5] }
    axis = [0.0, -0.6, -0.8]
    mass = 0.3
    com = [0.0, 0.0, 0.0]
    inertia = { xx = 0.001, yy = 0.001, zz = 0.001 }
    "#,
];

#[test]
fn awkward_chains_convert_every_way() {
    let mut worst = Worst::default();
    for text in AWKWARD {
        let robot = RobotModel::from_toml_str(text).unwrap_or_else(|e| panic!("{e}"));
        for convention in CONVENTIONS {
            let what = format!("{} -> {convention:?}", robot.name);
            let converted = to_dh(&robot, convention).unwrap_or_else(|e| panic!("{what}: {e}"));
            worst = worst.max(same_robot(&robot, &converted, false, &what));
            for next in CONVENTIONS {
                let again = to_dh(&converted, next).unwrap();
                worst = worst.max(same_robot(
                    &robot,
                    &again,
                    false,
                    &format!("{what} -> {next:?}"),
                ));
            }
            let back = read_back(&to_urdf(&converted), robot.dof());
            worst = worst.max(same_robot(&robot, &back, true, &format!("{what} -> URDF")));
        }
    }
    eprintln!("awkward chains: worst {worst:?}");
}

#[test]
fn nearly_parallel_axes_apart_leave_the_range() {
    // Axis 2 is 1e-7 rad off axis 1 and 5 cm to its side: the common normal is 500 km away.
    let robot = RobotModel::from_toml_str(
        r#"
        name = "nearly_parallel"
        convention = "urdf"
        [[links]]
        joint = "revolute"
        [[links]]
        joint = "revolute"
        origin = { xyz = [0.1, 0.05, 0.0], rpy = [1e-7, 0.0, 0.0] }
        "#,
    )
    .unwrap();
    for convention in [Convention::Standard, Convention::Modified] {
        let e = to_dh(&robot, convention).unwrap_err();
        let ConvertError::Invalid { joint, field, .. } = &e else {
            panic!("{e:?}")
        };
        assert!(joint.is_some() && field.is_some(), "{e}");
        let text = e.to_string();
        assert!(
            text.starts_with("joint ") && text.contains("outside the range"),
            "{text}"
        );
    }
}

#[test]
fn to_urdf_writes_what_urdf_can_hold_and_says_what_it_cannot() {
    let scara = load("scara");
    let text = to_urdf(&scara);
    assert!(text.contains("<robot name=\"scara\">"), "{text}");
    assert!(
        text.contains("<joint name=\"joint3\" type=\"prismatic\">"),
        "{text}"
    );
    assert!(text.contains("<!-- motor:"), "{text}");
    assert!(text.contains("<dynamics damping="), "{text}");
    assert!(text.contains("URDF has no gravity"), "{text}");
    let back = read(&text, "scara.urdf", &UrdfOptions::default())
        .unwrap()
        .model;
    assert_eq!(back.dof(), 4);
    for (a, b) in scara.links.iter().zip(&back.links) {
        assert_eq!(
            a.friction.unwrap_or_default(),
            b.friction.unwrap_or(Friction::default())
        );
        assert_eq!(a.limits, b.limits);
        assert_eq!(b.motor, None);
    }
    // Revolute joints without limits are continuous; a prismatic one keeps a <limit>.
    let free = RobotModel::from_toml_str(
        r#"
        name = "free"
        description = "a -- b"
        convention = "standard"
        tool = { xyz = [0.0, 0.0, 0.1] }
        [[links]]
        joint = "revolute"
        a = 1.0
        alpha = 0
        d = 0
        theta = 0.5
        [[links]]
        joint = "prismatic"
        a = 0
        alpha = 0
        d = 0.25
        theta = 0
        "#,
    )
    .unwrap();
    let text = to_urdf(&free);
    assert!(text.contains("type=\"continuous\""), "{text}");
    assert!(
        text.contains("<limit effort=\"0\" velocity=\"0\"/>"),
        "{text}"
    );
    assert!(text.contains("<link name=\"tool\"/>"), "{text}");
    assert!(text.contains("a - - b"), "{text}");
    let back = read_back(&text, 2);
    same_robot(&free, &back, true, "free -> URDF");
    assert_eq!(back.links[0].limits, None);
    assert_eq!(back.links[1].limits, None);
}

/// The example of the module docs (`dhgen_description::convert`), run here too.
#[test]
fn module_docs_example() {
    let elbow = RobotModel::from_toml_str(
        r#"
        name = "elbow"
        convention = "standard"
        [[links]]
        joint = "revolute"
        a = 1.0
        alpha = 0
        d = 0
        theta = 0
        [[links]]
        joint = "revolute"
        a = 0.8
        alpha = 0
        d = 0
        theta = 0
        "#,
    )
    .unwrap();
    let craig = to_dh(&elbow, Convention::Modified).unwrap();
    assert_eq!([craig.links[0].a, craig.links[1].a], [0.0, 1.0]);
    assert_eq!(craig.tool.unwrap().xyz, [0.8, 0.0, 0.0]);
    let q = [0.3, -1.2];
    let (a, b) = (
        elbow.chain().view().tool_at(&q),
        craig.chain().view().tool_at(&q),
    );
    assert!((0..3).all(|i| (a.p[i] - b.p[i]).abs() < 1e-12));
}

#[test]
fn ur5_urdf_gives_the_published_table() {
    // The URDF's offsets along the three parallel axes (0.13585, −0.1197, 0.093) add up into
    // d_4 = 0.10915, as in Universal Robots' table; twists are exact quarter turns. (The
    // URDF's tip is at joint 6: the table's d_6 = 0.0823 is not in it.)
    let dh = to_dh(&fixture("ur5", "wrist_3_link"), Convention::Standard).unwrap();
    let catalogue = load("ur5");
    assert_eq!(dh.base, None);
    for (k, (a, b)) in catalogue.links.iter().zip(&dh.links).enumerate() {
        let d = if k == 5 { 0.0 } else { a.d };
        assert!((d - b.d).abs() < 1e-15, "row {}: {b:?}", k + 1);
        assert!(
            (a.a.abs() - b.a.abs()).abs() < 1e-15,
            "row {}: {b:?}",
            k + 1
        );
        let (ca, sa) = a.alpha.cos_sin();
        let (cb, sb) = b.alpha.cos_sin();
        assert!(b.alpha.quarter_turn().is_some(), "row {}", k + 1);
        if k < 5 {
            // Frame 6 takes the z axis of the URDF's wrist_3_link frame (its joint turns about
            // that frame's y axis): α_6 = 90°.
            assert_eq!((ca, sa.abs()), (cb, sb.abs()), "row {}", k + 1);
        }
        assert!(b.theta.quarter_turn().is_some(), "row {}", k + 1);
    }
}
