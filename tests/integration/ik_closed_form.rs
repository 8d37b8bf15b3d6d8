//! Closed-form inverse kinematics by kinematic decoupling: acceptance on 10,000 random
//! reachable poses per applicable catalogue robot, structure detection, base/tool/offsets,
//! singular and unreachable poses.

use crate::catalogue::{
    craig, cylindrical, offset_elbow, panda, puma_offsets, puma560, stanford, ur5,
};
use crate::support::fixture_path;
use dhgen::Arm;
use dhgen::ik::{ArmKind, DecoupledIk, Solutions, StructureError, VERIFY_TOLERANCE, pose_error};
use dhgen::model::NotSpherical;
use dhgen::nalgebra::{Isometry3, SVector, Translation3, UnitQuaternion, Vector3};
use dhgen::rotation::wrap_angle;
use dhgen::{Robot, RobotModel};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::f64::consts::PI;

fn model(name: &str) -> RobotModel {
    RobotModel::from_toml_file(format!("{}/robots/{name}.toml", env!("CARGO_MANIFEST_DIR")))
        .unwrap()
}

fn fixture_model(name: &str) -> RobotModel {
    RobotModel::from_toml_file(fixture_path(name)).unwrap()
}

fn random_q<A: Arm<Dof = dhgen::nalgebra::Const<6>>>(arm: &A, rng: &mut StdRng) -> SVector<f64, 6> {
    SVector::from_fn(|j, _| {
        let [lo, hi] = arm.limits(j).unwrap_or([-PI, PI]);
        rng.random_range(lo..=hi)
    })
}

fn same_joints(a: &SVector<f64, 6>, b: &SVector<f64, 6>, prismatic: &[bool; 6], tol: f64) -> bool {
    (0..6).all(|j| {
        let d = a[j] - b[j];
        let d = if prismatic[j] { d } else { wrap_angle(d) };
        d.abs() < tol
    })
}

struct Figures {
    poses: usize,
    solutions: usize,
    histogram: [usize; 9],
    worst_position: f64,
    worst_orientation: f64,
    worst_generating_distance: f64,
}

/// Solves `count` poses made from random joint vectors within the limits; every solution
/// must reproduce the pose (checked with the arm's own forward kinematics) and the generating
/// joint vector must be among them.
fn acceptance<A: Arm<Dof = dhgen::nalgebra::Const<6>>>(
    arm: &A,
    ik: &DecoupledIk,
    count: usize,
    seed: u64,
) -> Figures {
    let mut rng = StdRng::seed_from_u64(seed);
    let prismatic = ik.prismatic();
    let mut f = Figures {
        poses: count,
        solutions: 0,
        histogram: [0; 9],
        worst_position: 0.0,
        worst_orientation: 0.0,
        worst_generating_distance: 0.0,
    };
    for _ in 0..count {
        let q = random_q(arm, &mut rng);
        let pose = arm.fk(&q);
        let solutions = ik.solve(&pose);
        f.solutions += solutions.len();
        f.histogram[solutions.len()] += 1;
        for s in &solutions {
            assert!(s.iter().all(|x| x.is_finite()));
            let (dp, dr) = pose_error(&arm.fk(s), &pose);
            assert!(
                dp <= VERIFY_TOLERANCE && dr <= VERIFY_TOLERANCE,
                "q = {q:?}: solution {s:?} misses the pose by {dp:e} m, {dr:e} rad"
            );
            f.worst_position = f.worst_position.max(dp);
            f.worst_orientation = f.worst_orientation.max(dr);
        }
        let nearest = solutions
            .iter()
            .map(|s| {
                (0..6)
                    .map(|j| {
                        let d = s[j] - q[j];
                        if prismatic[j] {
                            d.abs()
                        } else {
                            wrap_angle(d).abs()
                        }
                    })
                    .fold(0.0, f64::max)
            })
            .fold(f64::INFINITY, f64::min);
        assert!(
            nearest < 1e-7,
            "q = {q:?} is not among the {} solutions {:?} (nearest {nearest:e})",
            solutions.len(),
            solutions.as_slice()
        );
        f.worst_generating_distance = f.worst_generating_distance.max(nearest);
    }
    f
}

fn report(name: &str, f: &Figures) {
    eprintln!(
        "{name}: {} poses, {:.3} solutions per pose (histogram by count 0..8: {:?}), worst pose \
         error {:.2e} m / {:.2e} rad, generating q found to {:.2e}",
        f.poses,
        f.solutions as f64 / f.poses as f64,
        f.histogram,
        f.worst_position,
        f.worst_orientation,
        f.worst_generating_distance
    );
}

#[test]
fn puma560_ten_thousand_poses() {
    let ik = DecoupledIk::from_chain(puma560::CHAIN).unwrap();
    assert_eq!(ik.arm_kind(), ArmKind::IntersectingShoulder);
    let f = acceptance(&puma560::Robot, &ik, 10_000, 560);
    report("puma560", &f);
    // The PUMA has 8 solutions at almost every pose (4 arm configurations × wrist flip).
    assert!(f.histogram[8] > 9_900, "{:?}", f.histogram);
}

#[test]
fn stanford_ten_thousand_poses() {
    let ik = DecoupledIk::from_chain(stanford::CHAIN).unwrap();
    assert_eq!(ik.arm_kind(), ArmKind::IntersectingShoulder);
    let f = acceptance(&stanford::Robot, &ik, 10_000, 1969);
    report("stanford", &f);
    assert!(f.histogram[8] > 9_900, "{:?}", f.histogram);
}

#[test]
fn cylindrical_ten_thousand_poses() {
    let ik = DecoupledIk::from_chain(cylindrical::CHAIN).unwrap();
    assert_eq!(ik.arm_kind(), ArmKind::Cylindrical);
    let f = acceptance(&cylindrical::Robot, &ik, 10_000, 42);
    report("cylindrical", &f);
    // Reach ±d3 with q1 and q1 + π, times the wrist flip.
    assert_eq!(f.histogram[4], 10_000, "{:?}", f.histogram);
}

#[test]
fn offsets_base_and_tool_are_honoured() {
    let ik = DecoupledIk::from_chain(puma_offsets::CHAIN).unwrap();
    let f = acceptance(&puma_offsets::Robot, &ik, 2_000, 7);
    report("puma with offsets, base, tool", &f);
    assert!(f.histogram[8] > 1_950, "{:?}", f.histogram);
}

#[test]
fn elbow_with_shoulder_offset_a1() {
    let ik = DecoupledIk::from_chain(offset_elbow::CHAIN).unwrap();
    // Axes 1 and 2 are skew (offset a1): the quartic case.
    assert_eq!(ik.arm_kind(), ArmKind::OffsetShoulder);
    let f = acceptance(&offset_elbow::Robot, &ik, 2_000, 11);
    report("elbow arm with a1 offset", &f);
    assert!(f.solutions >= 2_000 * 4);
}

#[test]
fn modified_dh_arm() {
    let ik = DecoupledIk::from_chain(craig::CHAIN).unwrap();
    let f = acceptance(&craig::Robot, &ik, 2_000, 13);
    report("modified DH PUMA", &f);
    assert!(f.histogram[8] > 1_950, "{:?}", f.histogram);
}

#[test]
fn from_model_and_from_arm_agree_for_generated_and_runtime_robots() {
    for name in ["puma560", "stanford", "cylindrical"] {
        let m = model(name);
        let robot = Robot::from_model(m.clone());
        let from_model = DecoupledIk::from_model(&m).unwrap();
        let from_runtime = DecoupledIk::from_chain(robot.chain()).unwrap();
        assert_eq!(from_model.arm_kind(), from_runtime.arm_kind());
        let mut rng = StdRng::seed_from_u64(3);
        for _ in 0..200 {
            let q: Vec<f64> = m
                .links
                .iter()
                .map(|l| {
                    let [lo, hi] = l.limits.unwrap();
                    rng.random_range(lo..=hi)
                })
                .collect();
            let pose = robot.fk(&q);
            let a = from_model.solve(&pose);
            let b = from_runtime.solve(&pose);
            assert_eq!(a.len(), b.len(), "{name}");
            for (x, y) in a.iter().zip(&b) {
                assert!(
                    same_joints(x, y, &from_model.prismatic(), 1e-9),
                    "{name}: {x:?} vs {y:?}"
                );
            }
        }
    }
}

#[test]
fn from_model_honours_offsets_base_tool_and_modified_dh() {
    // The descriptions the generated modules were made from, read at run time.
    let offsets = fixture_model("puma_offsets");
    let modified = fixture_model("craig");
    let mut rng = StdRng::seed_from_u64(21);
    for (model, fk) in [
        (
            offsets,
            puma_offsets::fk::<f64> as fn(&[f64; 6]) -> Isometry3<f64>,
        ),
        (modified, craig::fk::<f64>),
    ] {
        let ik = DecoupledIk::from_model(&model).unwrap();
        for _ in 0..300 {
            let q = SVector::<f64, 6>::from_fn(|_, _| rng.random_range(-2.0..2.0));
            let pose = fk(&q.into());
            let solutions = ik.solve(&pose);
            assert!(solutions.len() >= 2, "{}: {q:?}", model.name);
            assert!(
                solutions
                    .iter()
                    .any(|s| same_joints(s, &q, &[false; 6], 1e-7)),
                "{}: {q:?}",
                model.name
            );
            for s in &solutions {
                let (dp, dr) = pose_error(&fk(&(*s).into()), &pose);
                assert!(dp <= VERIFY_TOLERANCE && dr <= VERIFY_TOLERANCE);
            }
        }
    }
}

#[test]
fn wrist_singularity_sets_q4_to_zero() {
    let ik = DecoupledIk::from_chain(puma560::CHAIN).unwrap();
    for (q4, q6) in [(0.7, -0.2), (-1.0, 2.0), (0.0, 0.5)] {
        let q = SVector::<f64, 6>::new(0.3, 0.2, -0.9, q4, 0.0, q6);
        let pose = puma560::fk(&q);
        let solutions = ik.solve(&pose);
        // 4 arm solutions; for the one that generated the pose the wrist is singular.
        let singular: Vec<_> = solutions
            .iter()
            .filter(|s| (0..3).all(|j| wrap_angle(s[j] - q[j]).abs() < 1e-9))
            .collect();
        assert_eq!(singular.len(), 1, "{:?}", solutions.as_slice());
        let s = singular[0];
        assert_eq!(s[3], 0.0);
        assert!(s[4].abs() < 1e-9);
        assert!(wrap_angle(s[5] - (q4 + q6)).abs() < 1e-9);
        let (dp, dr) = pose_error(&puma560::fk(s), &pose);
        assert!(dp < 1e-12 && dr < 1e-12);
    }
}

#[test]
fn shoulder_singularity_sets_q1_to_zero() {
    // An elbow arm without shoulder offset: its wrist centre can sit on axis 1.
    use crate::catalogue::shoulder_singular_elbow as elbow;
    let ik = DecoupledIk::from_chain(elbow::CHAIN).unwrap();
    // With q2 = 60°, q3 = −90° puts the wrist centre straight above the base: on axis 1.
    let q = SVector::<f64, 6>::new(1.1, PI / 3.0, -PI / 2.0, 0.4, 0.9, -0.3);
    let pose = elbow::fk(&q);
    let centre =
        pose * dhgen::nalgebra::Point3::from(ik.wrist_centre_in_tool().expect("a spherical wrist"));
    assert!(centre.coords.xy().norm() < 1e-12, "{centre:?}");
    let solutions = ik.solve(&pose);
    assert!(!solutions.is_empty());
    for s in &solutions {
        assert_eq!(s[0], 0.0);
        let (dp, dr) = pose_error(&elbow::fk(s), &pose);
        assert!(dp < 1e-9 && dr < 1e-9);
    }
}

#[test]
fn unreachable_poses_give_no_solution_and_no_nan() {
    let ik = DecoupledIk::from_chain(puma560::CHAIN).unwrap();
    let far = Isometry3::from_parts(Translation3::new(3.0, 0.0, 0.5), UnitQuaternion::identity());
    assert!(ik.solve(&far).is_empty());
    let nan = Isometry3::from_parts(
        Translation3::new(f64::NAN, 0.0, 0.5),
        UnitQuaternion::identity(),
    );
    assert!(ik.solve(&nan).is_empty());
    // Every wrist centre of the cylindrical arm has a solution for some real d2, d3: beyond
    // its reach is a matter of the joint limits.
    let ik = DecoupledIk::from_chain(cylindrical::CHAIN).unwrap();
    let inf = Isometry3::from_parts(
        Translation3::new(0.3, f64::INFINITY, 0.5),
        UnitQuaternion::identity(),
    );
    assert!(ik.solve(&inf).is_empty());
    // Within the limits, a radius beyond the reach has no solution.
    let out = Isometry3::from_parts(Translation3::new(2.0, 0.0, 0.5), UnitQuaternion::identity());
    assert!(ik.solve_within_limits(&out).is_empty());
    // The stretched PUMA (elbow singular) is on the boundary: solutions exist and are exact.
    let ik = DecoupledIk::from_chain(puma560::CHAIN).unwrap();
    let q = SVector::<f64, 6>::new(
        0.2,
        0.5,
        -std::f64::consts::FRAC_PI_2 + (0.0203f64).atan2(0.4318),
        0.3,
        0.7,
        0.1,
    );
    let pose = puma560::fk(&q);
    let solutions = ik.solve(&pose);
    assert!(!solutions.is_empty());
    assert!(
        solutions
            .iter()
            .any(|s| same_joints(s, &q, &[false; 6], 1e-6))
    );
}

#[test]
fn solutions_within_limits_respect_them() {
    let ik = DecoupledIk::from_chain(puma560::CHAIN).unwrap();
    let mut rng = StdRng::seed_from_u64(99);
    for _ in 0..500 {
        let q = random_q(&puma560::Robot, &mut rng);
        let pose = puma560::fk(&q);
        let inside = ik.solve_within_limits(&pose);
        assert!(!inside.is_empty());
        assert!(inside.len() <= ik.solve(&pose).len());
        for s in &inside {
            for j in 0..6 {
                let [lo, hi] = puma560::CHAIN.bodies[j].limits.unwrap();
                assert!(s[j] >= lo - 1e-12 && s[j] <= hi + 1e-12);
            }
        }
        let near = inside.nearest(&q, &[false; 6]).unwrap();
        assert!(same_joints(&near, &q, &[false; 6], 1e-7));
    }
}

#[test]
fn structures_without_a_closed_form_are_rejected_with_the_reason() {
    assert_eq!(
        DecoupledIk::from_chain(panda::CHAIN).unwrap_err(),
        StructureError::NotSixJoints { dof: 7 }
    );
    // A general six-joint arm: no spherical wrist, no parallel axes.
    let general = dhgen::model::random::random_arm(6, dhgen::model::random::ArmStyle::General, 1);
    let err = DecoupledIk::from_model(&general).unwrap_err();
    assert!(matches!(err, StructureError::NoDecoupling(_)), "{err}");
    assert!(err.to_string().contains("no spherical wrist"), "{err}");
    // Axes 4, 5, 6 apart (here: joint 4 prismatic) is said in the reason.
    assert_eq!(
        err,
        StructureError::NoDecoupling(NotSpherical::PrismaticJoint { joint: 3 })
    );
    // The UR5 decouples the other way: axes 2, 3, 4 parallel, 5 and 6 meeting.
    assert_eq!(
        DecoupledIk::from_chain(ur5::CHAIN).unwrap().arm_kind(),
        ArmKind::ThreeParallel
    );
}

/// Arms that lose a direction at every configuration (a pose has a continuum of solutions or
/// none) are refused, not solved into an empty list for reachable poses: joints 1–3 that
/// cannot place a spherical wrist's centre, wrist axes 5 and 6 parallel, coincident axes among
/// the parallel axes 2–4 of a UR-type arm.
#[test]
fn degenerate_structures_are_rejected() {
    // Six revolute joints (a, alpha in degrees, d), the last three a spherical wrist.
    let arm = |first: [(f64, f64, f64); 3]| {
        let rows: String = first
            .iter()
            .chain(&[(0.0, 90.0, 0.3), (0.0, -90.0, 0.0), (0.0, 0.0, 0.1)])
            .map(|(a, alpha, d)| {
                format!(
                    "[[links]]\njoint = \"revolute\"\na = {a}\nalpha = \"{alpha}deg\"\n\
                     d = {d}\ntheta = 0\n"
                )
            })
            .collect();
        RobotModel::from_toml_str(&format!("name = \"x\"\nconvention = \"standard\"\n{rows}"))
            .unwrap()
    };
    // The control: an elbow arm (a2 = 0.4) is solved.
    let elbow = arm([(0.0, -90.0, 0.3), (0.4, 0.0, 0.0), (0.0, -90.0, 0.0)]);
    assert!(DecoupledIk::from_model(&elbow).is_ok());
    // Joints 2 and 3 coaxial (a2 = 0, alpha2 = 0): only q2 + q3 moves the wrist centre.
    let coaxial = arm([(0.0, -90.0, 0.3), (0.0, 0.0, 0.2), (0.4, -90.0, 0.0)]);
    // Axes 1, 2, 3 parallel: the wrist centre stays in a plane.
    let planar = arm([(0.4, 0.0, 0.0), (0.3, 0.0, 0.0), (0.0, -90.0, 0.0)]);
    for (what, model) in [("coaxial 2, 3", coaxial), ("parallel 1, 2, 3", planar)] {
        let err = DecoupledIk::from_model(&model).unwrap_err();
        assert!(
            matches!(err, StructureError::UnsupportedArm { .. })
                && err.to_string().contains("three independent directions"),
            "{what}: {err}"
        );
    }
    let edited = |robot: &str, from: &str, to: &str| {
        let text = std::fs::read_to_string(format!(
            "{}/robots/{robot}.toml",
            env!("CARGO_MANIFEST_DIR")
        ))
        .unwrap();
        assert!(text.contains(from), "{from}");
        RobotModel::from_toml_str(&text.replacen(from, to, 1)).unwrap()
    };
    // The PUMA 560 with alpha5 = 0: axes 5 and 6 coincide.
    let err = DecoupledIk::from_model(&edited(
        "puma560",
        "alpha = \"-90deg\"\nd = 0.0",
        "alpha = 0.0\nd = 0.0",
    ))
    .unwrap_err();
    assert_eq!(
        err,
        StructureError::NoDecoupling(NotSpherical::ParallelAxes { axis: 4 })
    );
    // The UR5 with alpha4 = 0: axes 2, 3, 4 and 5 parallel.
    let err = DecoupledIk::from_model(&edited(
        "ur5",
        "alpha = \"90deg\"\nd = 0.10915",
        "alpha = 0.0\nd = 0.10915",
    ))
    .unwrap_err();
    assert!(
        err.to_string().contains("2, 3, 4 and 5 are parallel"),
        "{err}"
    );
    // The UR5 with a2 = 0 or a3 = 0: axes 2 and 3, or 3 and 4, coincide.
    for from in ["a = -0.425", "a = -0.39225"] {
        let err = DecoupledIk::from_model(&edited("ur5", from, "a = 0.0")).unwrap_err();
        assert!(
            matches!(err, StructureError::UnsupportedArm { .. })
                && err.to_string().contains("two of them coincide"),
            "{from}: {err}"
        );
    }
}

#[test]
fn the_solution_list_is_fixed_capacity() {
    assert_eq!(Solutions::CAPACITY, 8);
    assert!(std::mem::size_of::<Solutions>() <= 8 * 6 * 8 + 16);
    let _: Vector3<f64> = DecoupledIk::from_chain(puma560::CHAIN)
        .unwrap()
        .wrist_centre_in_tool()
        .expect("a spherical wrist");
}

/// Issue 62's reproducer: at q5 = 0 the q5 equation's right-hand side came out one rounding
/// below its range's end, split the double root into ±1.49e-8, and both candidates missed the
/// pose, losing the whole arm branch that made it, on every path alike.
#[test]
fn wrist_singular_pose_keeps_its_arm_branch() {
    let q = SVector::<f64, 6>::from([
        -1.9999943780643115,
        1.1207482993556654,
        0.23217305068068805,
        1.2849776776310398,
        0.0,
        1.9293003123472254,
    ]);
    let pose = puma560::fk(&q);
    let runtime = Robot::from_model(model("puma560"));
    let solutions = puma560::ik(&pose);
    assert_eq!(
        solutions,
        DecoupledIk::from_model(runtime.model())
            .unwrap()
            .solve(&pose)
    );
    let same_arm: Vec<_> = solutions
        .iter()
        .filter(|s| (0..3).all(|j| wrap_angle(s[j] - q[j]).abs() < 1e-7))
        .collect();
    assert_eq!(same_arm.len(), 1, "{:?}", solutions.as_slice());
    // The singular family's representative: q4 = 0, q6 = q4 + q6.
    let s = same_arm[0];
    assert_eq!(s[3], 0.0);
    assert!(s[4].abs() < 1e-12 && wrap_angle(s[5] - (q[3] + q[5])).abs() < 1e-12);
    let (dp, dr) = pose_error(&puma560::fk(s), &pose);
    assert!(dp < 1e-14 && dr < 1e-14, "{dp:e} {dr:e}");
}
