//! Closed-form inverse kinematics on random arms of every kind it solves: Pieper arms at any
//! twist angles (axes 1 and 2 intersecting, parallel, or skew with an offset; revolute or
//! prismatic joint 3; wrists with oblique axes) and arms with three parallel axes (UR type).
//! On each, poses made from random joint vectors: every solution reproduces the pose to
//! `VERIFY_TOLERANCE` (by the runtime path's forward kinematics, independently of the solver's
//! own check), and the generating joint vector is among the solutions.

use dhgen::Robot;
use dhgen::ik::{ArmKind, DecoupledIk, VERIFY_TOLERANCE, pose_error};
use dhgen::nalgebra::SVector;
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::f64::consts::PI;

/// A twist in (−π, π) at least 0.2 rad from 0 and ±π (so axes are not parallel).
fn oblique(rng: &mut StdRng) -> f64 {
    let x: f64 = rng.random_range(0.2..PI - 0.2);
    if rng.random_bool(0.5) { x } else { -x }
}

/// One row of a standard DH table.
fn row(joint: &str, a: f64, alpha: f64, d: f64, theta: f64) -> String {
    format!(
        "[[links]]\njoint = \"{joint}\"\na = {a:?}\nalpha = {alpha:?}\nd = {d:?}\ntheta = {theta:?}\n"
    )
}

fn robot(rows: &[String]) -> Robot {
    let text = format!(
        "name = \"random\"\nconvention = \"standard\"\n{}",
        rows.concat()
    );
    Robot::from_toml_str(&text).unwrap()
}

/// A Pieper arm: joints 1–3 of the given shoulder, a spherical wrist with oblique axes
/// (a4 = a5 = d5 = 0 puts axes 4, 5, 6 through one point), offsets everywhere else.
fn pieper(rng: &mut StdRng, shoulder: ArmKind, prismatic3: bool) -> Robot {
    let mut s = StdRng::seed_from_u64(rng.random_range(0..u64::MAX));
    let (a1, alpha1) = match shoulder {
        // Axes 1 and 2 meet at an oblique angle.
        ArmKind::IntersectingShoulder => (0.0, oblique(&mut s)),
        // Parallel (or anti-parallel), apart.
        ArmKind::ParallelShoulder => (
            s.random_range(0.1..0.4),
            if s.random_bool(0.5) { 0.0 } else { PI },
        ),
        // Skew: apart and oblique.
        _ => (s.random_range(0.1..0.4), oblique(&mut s)),
    };
    let mut r = |lo: f64, hi: f64| rng.random_range(lo..hi);
    let joint3 = if prismatic3 { "prismatic" } else { "revolute" };
    robot(&[
        row("revolute", a1, alpha1, r(0.2, 0.5), r(-PI, PI)),
        row(
            "revolute",
            r(0.2, 0.6),
            oblique(&mut s),
            r(-0.2, 0.2),
            r(-PI, PI),
        ),
        row(
            joint3,
            r(0.0, 0.1),
            oblique(&mut s),
            r(0.1, 0.3),
            r(-PI, PI),
        ),
        row("revolute", 0.0, oblique(&mut s), r(0.2, 0.5), r(-PI, PI)),
        row("revolute", 0.0, oblique(&mut s), 0.0, r(-PI, PI)),
        row(
            "revolute",
            r(0.0, 0.1),
            r(-PI, PI),
            r(0.05, 0.2),
            r(-PI, PI),
        ),
    ])
}

/// A UR-type arm: axes 2, 3, 4 parallel (α2 = α3 = 0), axes 5 and 6 meeting (a5 = 0),
/// everything else random.
fn three_parallel(rng: &mut StdRng) -> Robot {
    let mut s = StdRng::seed_from_u64(rng.random_range(0..u64::MAX));
    let mut r = |lo: f64, hi: f64| rng.random_range(lo..hi);
    robot(&[
        row(
            "revolute",
            r(0.0, 0.1),
            oblique(&mut s),
            r(0.05, 0.2),
            r(-PI, PI),
        ),
        row("revolute", r(-0.6, -0.2), 0.0, r(-0.1, 0.1), r(-PI, PI)),
        row("revolute", r(-0.5, -0.2), 0.0, r(-0.1, 0.1), r(-PI, PI)),
        row(
            "revolute",
            r(0.0, 0.1),
            oblique(&mut s),
            r(0.05, 0.2),
            r(-PI, PI),
        ),
        row("revolute", 0.0, oblique(&mut s), r(0.05, 0.15), r(-PI, PI)),
        row(
            "revolute",
            r(0.0, 0.05),
            r(-PI, PI),
            r(0.05, 0.15),
            r(-PI, PI),
        ),
    ])
}

/// A random joint vector: angles in (−π, π), displacements in (0.1, 0.5) m.
fn random_joints(prismatic: &[bool; 6], rng: &mut StdRng) -> SVector<f64, 6> {
    SVector::from_fn(|j, _| {
        if prismatic[j] {
            rng.random_range(0.1..0.5)
        } else {
            rng.random_range(-PI..PI)
        }
    })
}

/// Solves `poses` poses of `robot` from random joint vectors; returns how many solutions
/// there were in all.
fn check(robot: &Robot, kind: ArmKind, poses: usize, rng: &mut StdRng) -> usize {
    let ik = DecoupledIk::from_chain(robot.chain()).unwrap();
    assert_eq!(ik.arm_kind(), kind, "{}", robot.model().to_toml());
    let prismatic = ik.prismatic();
    let mut total = 0;
    for _ in 0..poses {
        let q = random_joints(&prismatic, rng);
        let pose = robot.fk(&q);
        let solutions = ik.solve(&pose);
        total += solutions.len();
        for s in &solutions {
            let (dp, dr) = pose_error(&robot.fk(s), &pose);
            assert!(
                dp <= VERIFY_TOLERANCE && dr <= VERIFY_TOLERANCE,
                "{kind:?}: solution {s} misses the pose by {dp:e} m, {dr:e} rad"
            );
        }
        let found = solutions.iter().any(|s| {
            (0..6).all(|j| {
                let d = s[j] - q[j];
                let d = if prismatic[j] {
                    d
                } else {
                    d - (2.0 * PI) * (d / (2.0 * PI)).round()
                };
                d.abs() < 1e-7
            })
        });
        assert!(
            found,
            "{kind:?}: q = {q} is not among {:?}\n{}",
            solutions.as_slice(),
            robot.model().to_toml()
        );
    }
    total
}

#[test]
fn pieper_arms_with_intersecting_shoulders_at_any_angle() {
    let mut rng = StdRng::seed_from_u64(101);
    for prismatic in [false, true] {
        for _ in 0..10 {
            let arm = pieper(&mut rng, ArmKind::IntersectingShoulder, prismatic);
            check(&arm, ArmKind::IntersectingShoulder, 100, &mut rng);
        }
    }
}

#[test]
fn pieper_arms_with_parallel_shoulders() {
    let mut rng = StdRng::seed_from_u64(102);
    for prismatic in [false, true] {
        for _ in 0..10 {
            let arm = pieper(&mut rng, ArmKind::ParallelShoulder, prismatic);
            check(&arm, ArmKind::ParallelShoulder, 100, &mut rng);
        }
    }
}

#[test]
fn pieper_arms_with_skew_shoulders_solve_the_quartic() {
    let mut rng = StdRng::seed_from_u64(103);
    let mut solutions = 0;
    for prismatic in [false, true] {
        for _ in 0..10 {
            let arm = pieper(&mut rng, ArmKind::OffsetShoulder, prismatic);
            solutions += check(&arm, ArmKind::OffsetShoulder, 100, &mut rng);
        }
    }
    // Up to 4 arm solutions times the wrist flip: more than the 2 of a single branch.
    assert!(solutions > 2 * 2000, "{solutions}");
}

#[test]
fn three_parallel_axes_ur_type() {
    let mut rng = StdRng::seed_from_u64(104);
    let mut solutions = 0;
    for _ in 0..20 {
        let arm = three_parallel(&mut rng);
        solutions += check(&arm, ArmKind::ThreeParallel, 100, &mut rng);
    }
    assert!(solutions > 2 * 2000, "{solutions}");
}

#[test]
fn ur5_gets_eight_solutions() {
    let ur5 = crate::support::runtime("ur5");
    let mut rng = StdRng::seed_from_u64(105);
    let total = check(&ur5, ArmKind::ThreeParallel, 500, &mut rng);
    // Generic poses of a UR have 8 solutions.
    assert!(total > 500 * 7, "{total}");
    // The generated module carries the same solver, precomputed.
    let q = [0.3, -1.2, 1.0, -0.5, 1.1, 0.7];
    let pose = crate::catalogue::ur5::fk(&q);
    assert_eq!(crate::catalogue::ur5::ik(&pose).len(), 8);
    assert_eq!(
        crate::catalogue::ur5::IK,
        DecoupledIk::from_chain(ur5.chain()).unwrap()
    );
}

/// Whatever structure the solver accepts, it solves: arms drawn from the special values
/// catalogues are made of (twists in {0, ±90°} or oblique, lengths and offsets zero, tens of
/// micrometres (CAD's roundings of zero) or not, some prismatic joints, wrists with parallel
/// axes among them), so that many are degenerate or nearly so.
/// Every arm `DecoupledIk` accepts gives, for poses made from random joint vectors, solutions
/// that reproduce the pose, never an empty list; the rest are refused with a reason.
#[test]
fn accepted_structures_solve_every_reachable_pose() {
    let mut rng = StdRng::seed_from_u64(20_261_201);
    let (mut accepted, mut refused) = (0, 0);
    for _ in 0..3000 {
        let twist = |rng: &mut StdRng| match rng.random_range(0..4) {
            0 => 0.0,
            1 => PI / 2.0,
            2 => -PI / 2.0,
            _ => oblique(rng),
        };
        let length = |rng: &mut StdRng| {
            let sign = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
            match rng.random_range(0..8) {
                0..4 => 0.0,
                // A rounding of zero from CAD: tens of micrometres.
                4 => sign * rng.random_range(1e-6..1e-4),
                _ => sign * rng.random_range(0.0..0.5),
            }
        };
        let ur_type = rng.random_bool(0.3);
        let rows: Vec<String> = (0..6)
            .map(|j| {
                let prismatic = j > 0 && j < 3 && rng.random_bool(0.15);
                let joint = if prismatic { "prismatic" } else { "revolute" };
                let (a, d) = if !ur_type && (j == 3 || j == 4) {
                    // A wrist through one point: a4 = a5 = d5 = 0.
                    (0.0, if j == 3 { length(&mut rng) } else { 0.0 })
                } else {
                    (length(&mut rng), length(&mut rng))
                };
                let alpha = twist(&mut rng);
                let offset = if prismatic { 0.2 } else { 0.0 };
                row(joint, a, alpha, d + offset, 0.0)
            })
            .collect();
        let robot = robot(&rows);
        let Ok(ik) = DecoupledIk::from_chain(robot.chain()) else {
            refused += 1;
            continue;
        };
        accepted += 1;
        let prismatic = ik.prismatic();
        for _ in 0..5 {
            let q = random_joints(&prismatic, &mut rng);
            let pose = robot.fk(&q);
            let solutions = ik.solve(&pose);
            assert!(
                !solutions.is_empty(),
                "{:?}: no solution for the pose of q = {q}\n{}",
                ik.arm_kind(),
                robot.model().to_toml()
            );
            for s in &solutions {
                let (dp, dr) = pose_error(&robot.fk(s), &pose);
                assert!(dp <= VERIFY_TOLERANCE && dr <= VERIFY_TOLERANCE);
            }
        }
    }
    assert!(
        accepted > 300 && refused > 300,
        "{accepted} accepted, {refused} refused"
    );
}
