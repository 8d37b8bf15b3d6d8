//! The kinematic structure ([`JointChain`]) against the one DH formula it factors, and the
//! structural questions it answers, on every catalogue robot and on tables with what the
//! catalogue lacks (modified DH with a base and a tool, offsets, prismatic joints).

use crate::catalogue::CATALOGUE;
use crate::support::{dh_frames, load};
use dhgen_description::{Convention, Frame, NotSpherical, RobotModel};

/// A modified-DH arm with every constant non-zero, a base and a tool, and a prismatic joint.
const OFFSETS: &str = r#"
    name = "offsets"
    convention = "modified"
    base = { xyz = [0.1, -0.2, 0.3], rpy = [0.2, -0.4, 1.1] }
    tool = { xyz = [0.01, 0.02, 0.15], rpy = ["90deg", 0.3, -0.2] }
    [[links]]
    joint = "revolute"
    a = 0.05
    alpha = 0.3
    d = 0.2
    theta = 0.4
    [[links]]
    joint = "prismatic"
    a = 0.1
    alpha = "-90deg"
    d = 0.3
    theta = 0.7
    limits = [0.0, 0.5]
    [[links]]
    joint = "revolute"
    a = 0.4
    alpha = "90deg"
    d = -0.1
    theta = "-pi/2"
"#;

/// The same chain in standard DH.
fn standard_twin() -> RobotModel {
    RobotModel::from_toml_str(&OFFSETS.replace("modified", "standard")).unwrap()
}

/// SplitMix64 in [lo, hi): a fixed stream, no dependency.
struct Stream(u64);

impl Stream {
    fn next(&mut self, lo: f64, hi: f64) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        lo + (hi - lo) * ((z >> 11) as f64 / (1u64 << 53) as f64)
    }
}

fn assert_frames_close(a: &Frame<f64>, b: &Frame<f64>, what: &str) {
    let err =
        a.r.iter()
            .flatten()
            .zip(b.r.iter().flatten())
            .chain(a.p.iter().zip(&b.p))
            .map(|(x, y)| (x - y).abs())
            .fold(0.0, f64::max);
    assert!(err < 1e-12, "{what}: {a:?} vs {b:?} ({err:e})");
}

fn robots() -> Vec<RobotModel> {
    let mut all: Vec<RobotModel> = CATALOGUE.iter().map(|(stem, ..)| load(stem)).collect();
    all.push(RobotModel::from_toml_str(OFFSETS).unwrap());
    all.push(standard_twin());
    all
}

#[test]
fn the_chain_reproduces_the_dh_product() {
    let mut rng = Stream(7);
    for robot in robots() {
        let structure = robot.chain();
        let chain = structure.view();
        assert_eq!(chain.dof(), robot.dof());
        assert_eq!(chain.placements.len(), robot.dof() + 1);
        for _ in 0..50 {
            let q: Vec<f64> = (0..robot.dof()).map(|_| rng.next(-3.0, 3.0)).collect();
            let dh = dh_frames(&robot, &q);
            let tool = robot
                .tool
                .map_or_else(Frame::identity, |p| p.frame::<f64>());
            let name = &robot.name;
            assert_frames_close(
                &chain.tool_at(&q),
                &dh[robot.dof()].compose(&tool),
                &format!("{name}: tool at {q:?}"),
            );
            // Joint frame k carries joint k: its z axis and origin are those of DH frame
            // k − 1 (standard) or k (modified), and the link frame sits in it.
            chain.walk(
                chain.placements[0],
                |k| chain.bodies[k].motion(q[k]),
                |k, joint_frame| {
                    let link = joint_frame.compose(&chain.bodies[k].link);
                    assert_frames_close(&link, &dh[k + 1], &format!("{name}: link frame {k}"));
                    let carrier = &dh[robot.convention.joint_frame(k)];
                    let (z, zc) = (joint_frame.z_axis(), carrier.z_axis());
                    let gap = (0..3).map(|i| (z[i] - zc[i]).abs()).fold(0.0, f64::max);
                    assert!(gap < 1e-12, "{name}: axis {k}");
                    // The origins lie on the same axis line.
                    let d: [f64; 3] = core::array::from_fn(|i| joint_frame.p[i] - carrier.p[i]);
                    let along = d[0] * z[0] + d[1] * z[1] + d[2] * z[2];
                    let off = (0..3)
                        .map(|i| (d[i] - along * z[i]).abs())
                        .fold(0.0, f64::max);
                    assert!(off < 1e-12, "{name}: axis {k} is displaced by {off}");
                },
            );
        }
    }
}

#[test]
fn exact_quarter_turns_stay_exact() {
    // PUMA 560: twists of ±90° and 0 give placements of exact zeros and ones.
    let puma = load("puma560");
    let structure = puma.chain();
    for p in structure.view().placements {
        for x in p.r.iter().flatten() {
            assert!([0.0, 1.0, -1.0].contains(x), "{x} in {p:?}");
        }
    }
}

#[test]
fn spherical_wrists_are_found_with_their_centre() {
    for stem in ["puma560", "stanford", "cylindrical"] {
        let robot = load(stem);
        let structure = robot.chain();
        let wrist = structure
            .view()
            .spherical_wrist()
            .unwrap_or_else(|e| panic!("{stem}: {e}"));
        assert_eq!(wrist.first, 3);
        // These tables put the wrist centre at the origins of DH frames 4 and 5.
        let frames = dh_frames(&robot, &[0.0; 6]);
        for (a, b) in wrist.centre_at_zero.iter().zip(frames[5].p) {
            assert!((a - b).abs() < 1e-12, "{stem}: {wrist:?}");
        }
        // The centre stays put in joint frame 4 whatever the joints do.
        let q = [0.3, -0.2, 0.1, 0.7, -1.1, 2.0];
        let chain = structure.view();
        let mut at_q = None;
        chain.walk(
            chain.placements[0],
            |k| chain.bodies[k].motion(q[k]),
            |k, f| {
                if k == 3 {
                    at_q = Some(f.point(&wrist.centre));
                }
            },
        );
        let frames = dh_frames(&robot, &q);
        for (a, b) in at_q.unwrap().iter().zip(frames[5].p) {
            assert!((a - b).abs() < 1e-12, "{stem} at {q:?}");
        }
    }
    let why = |stem: &str| load(stem).chain().view().spherical_wrist().unwrap_err();
    assert!(matches!(
        why("panda"),
        NotSpherical::AxesApart { axis: 6, .. }
    ));
    assert!(matches!(why("ur5"), NotSpherical::AxesApart { .. }));
    assert_eq!(why("planar_elbow"), NotSpherical::TooFewJoints { dof: 2 });
    assert_eq!(why("scara"), NotSpherical::PrismaticJoint { joint: 2 });
}

#[test]
fn twists_are_the_tables_common_normals() {
    for robot in robots() {
        let structure = robot.chain();
        let chain = structure.view();
        for k in 0..robot.dof() - 1 {
            // The common normal of axes k and k+1 is row k's (standard) or row k+1's
            // (modified) a and α.
            let row = match robot.convention {
                Convention::Standard => &robot.links[k],
                Convention::Modified => &robot.links[k + 1],
                Convention::Urdf => unreachable!("the catalogue is DH tables"),
            };
            let t = chain.twist(k);
            let alpha = row.alpha.radians().rem_euclid(std::f64::consts::TAU);
            let alpha = alpha.min(std::f64::consts::TAU - alpha);
            assert!(
                (t.distance - row.a.abs()).abs() < 1e-12,
                "{}: {k}",
                robot.name
            );
            assert!((t.angle - alpha).abs() < 1e-12, "{}: {k}", robot.name);
        }
    }
}

#[test]
fn parallel_runs_are_exact() {
    let parallel = |stem: &str| -> Vec<usize> {
        let structure = load(stem).chain();
        let chain = structure.view();
        (0..chain.dof())
            .filter(|&k| chain.parallel_to_previous(k))
            .collect()
    };
    assert_eq!(parallel("puma560"), [2]);
    assert_eq!(parallel("planar_elbow"), [1]);
    assert_eq!(parallel("ur5"), [2, 3]);
    assert_eq!(parallel("panda"), Vec::<usize>::new());
    // SCARA: joints 1 and 2 turn about parallel axes; joint 3 is prismatic.
    assert_eq!(parallel("scara"), [1]);
}
