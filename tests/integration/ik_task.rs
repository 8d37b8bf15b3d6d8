//! Numeric IK of part of a pose (`NumericIk::task`): the position alone, or the position and
//! the tool's z axis. Arms with fewer than six joints reach what they can (a planar arm and a
//! SCARA their positions, seeded general five-joint arms a position and an approach
//! direction, which the whole pose there is not); checked against the targets directly (the
//! distance between the origins, the tool's z axis against the target's), not through the
//! solver's own error. On a redundant arm the freed constraints are more self-motion for
//! `solve_preferring`. A mask (`Task::Mask`) frees components of the pose error in world
//! axes: checked the same way, the counted components against the target, the free ones left
//! free.

use crate::catalogue::{panda, planar_elbow, puma560, scara};
use crate::support::{allocations_during, random_q};
use dhgen::ik::{IkError, NumericIk, Preference, Task};
use dhgen::model::random::{ArmStyle, random_arm};
use dhgen::nalgebra::{
    DefaultAllocator, Isometry3, OVector, SVector, Translation3, UnitQuaternion, Vector3,
};
use dhgen::velocity::JacobianSvd;
use dhgen::{Arm, ArmAllocator};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};

/// Solves `target` in `task` from `seed` and checks the result against the target directly:
/// the tool's origin within the position tolerance, its z axis within the orientation
/// tolerance of the target's (for the axis), the rotation matrix within it (for the pose),
/// for a mask the counted position components within the tolerance and the turn still to
/// make about the free world axis (if one), the joints within their limits, and the errors
/// reported those of [`Task::errors`].
fn check<A: Arm>(
    arm: &A,
    task: Task,
    target: &Isometry3<f64>,
    seed: &OVector<f64, A::Dof>,
    what: &str,
) -> OVector<f64, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let ik = NumericIk {
        task,
        ..NumericIk::default()
    };
    let s = ik
        .solve(arm, target, seed)
        .unwrap_or_else(|e| panic!("{what}: {e}"));
    let pose = arm.fk(&s.q);
    let dp = target.translation.vector - pose.translation.vector;
    let counted = |k: usize| !matches!(task, Task::Mask(mask) if !mask[k]);
    for k in (0..3).filter(|&k| counted(k)) {
        assert!(
            dp[k].abs() <= ik.position_tolerance,
            "{what}: position {dp}"
        );
    }
    let axis = (pose.rotation * Vector3::new(0.0, 0.0, 1.0)
        - target.rotation * Vector3::new(0.0, 0.0, 1.0))
    .norm();
    // The turn still to make, `R* Rᵀ`: with one world axis free, about that axis.
    let left = target.rotation * pose.rotation.inverse();
    let free: Vec<usize> = (0..3).filter(|&k| !counted(3 + k)).collect();
    match task {
        Task::PositionAndAxis => assert!(axis <= ik.orientation_tolerance, "{what}: {axis:e}"),
        Task::Position => assert_eq!(s.orientation_error, 0.0, "{what}"),
        Task::Mask(_) if free.len() == 3 => assert_eq!(s.orientation_error, 0.0, "{what}"),
        Task::Mask(_) if free.len() == 1 => {
            let u = Vector3::from_fn(|k, _| if k == free[0] { 1.0 } else { 0.0 });
            let moved = (left * u - u).norm();
            assert!(moved <= ik.orientation_tolerance, "{what}: {moved:e}");
        }
        _ => {
            let r = pose.rotation.to_rotation_matrix().into_inner()
                - target.rotation.to_rotation_matrix().into_inner();
            assert!(r.amax() <= ik.orientation_tolerance, "{what}: {r}");
        }
    }
    // The same quantities (the solver's from its residual vector: equal to rounding).
    let (p, r) = task.errors(&pose, target);
    assert!((s.position_error - p).abs() <= 1e-15 + 1e-12 * p, "{what}");
    assert!(
        (s.orientation_error - r).abs() <= 1e-15 + 1e-12 * r,
        "{what}"
    );
    for k in 0..arm.dof() {
        if let Some([lo, hi]) = arm.limits(k) {
            assert!(s.q[k] >= lo && s.q[k] <= hi, "{what}: joint {k}");
        }
    }
    s.q
}

/// The target `fk(q)` with its orientation replaced by one drawn at random: its position is
/// reachable, its orientation in general not by an arm of fewer than six joints.
fn position_of<A: Arm>(arm: &A, q: &OVector<f64, A::Dof>, rng: &mut StdRng) -> Isometry3<f64>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let p = arm.fk(q).translation;
    let r = UnitQuaternion::from_euler_angles(
        rng.random_range(-3.0..3.0),
        rng.random_range(-1.5..1.5),
        rng.random_range(-3.0..3.0),
    );
    Isometry3::from_parts(p, r)
}

/// A planar two-joint arm and a four-joint SCARA reach positions whatever orientation the
/// target asks for; the whole pose they do not (the same targets as poses fail).
/// A random position target (`position_of`) solved from a random seed as a position, checked;
/// whether the same target as a whole pose fails.
fn position_case<A: Arm>(arm: &A, rng: &mut StdRng, what: &str) -> bool
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let target = position_of(arm, &random_q(arm, rng), rng);
    let seed = random_q(arm, rng);
    check(arm, Task::Position, &target, &seed, what);
    NumericIk::default().solve(arm, &target, &seed).is_err()
}

#[test]
fn arms_of_fewer_than_six_joints_reach_positions() {
    let mut rng = StdRng::seed_from_u64(61);
    let mut whole_pose_failures = 0;
    for case in 0..30 {
        position_case(&planar_elbow::Robot, &mut rng, &format!("planar {case}"));
        let fails = position_case(&scara::Robot, &mut rng, &format!("scara {case}"));
        whole_pose_failures += usize::from(fails);
    }
    assert_eq!(whole_pose_failures, 30);
}

/// `pose` turned about its own z axis by `angle`: the same position and z axis.
fn turned(pose: &Isometry3<f64>, angle: f64) -> Isometry3<f64> {
    pose * Isometry3::from_parts(
        Translation3::identity(),
        UnitQuaternion::from_axis_angle(&Vector3::z_axis(), angle),
    )
}

/// Seeded general five-joint arms (oblique axes, offsets everywhere; runtime path) and the
/// SCARA, whose tool axis is always vertical: a position and an approach direction taken from
/// one configuration, the tool turned about that axis by a random angle (so the whole pose is
/// out of reach), are reached from random seeds.
#[test]
fn five_joint_arms_reach_a_position_and_an_axis() {
    let mut rng = StdRng::seed_from_u64(55);
    for seed_arm in 0..4 {
        let arm = dhgen::Robot::from_model(random_arm(5, ArmStyle::General, 50 + seed_arm));
        for case in 0..10 {
            let pose = Arm::fk(&arm, &random_q(&arm, &mut rng));
            let target = turned(&pose, rng.random_range(0.5..3.0));
            let seed = random_q(&arm, &mut rng);
            let what = format!("general 5 arm {seed_arm} case {case}");
            check(&arm, Task::PositionAndAxis, &target, &seed, &what);
            assert!(
                NumericIk::default().solve(&arm, &target, &seed).is_err(),
                "{what}: the turned pose is out of a five-joint arm's reach"
            );
        }
    }
    let arm = scara::Robot;
    for case in 0..10 {
        let pose = arm.fk(&random_q(&arm, &mut rng));
        let target = turned(&pose, rng.random_range(-3.0..3.0));
        let seed = random_q(&arm, &mut rng);
        check(
            &arm,
            Task::PositionAndAxis,
            &target,
            &seed,
            &format!("scara {case}"),
        );
    }
}

/// On the Panda, each task from random seeds: the position, the position and axis, and the
/// whole pose, all reached; the axis task leaves the turn about the axis free.
#[test]
fn panda_reaches_each_task() {
    let arm = panda::Robot;
    let mut rng = StdRng::seed_from_u64(77);
    for case in 0..20 {
        let q = random_q(&arm, &mut rng);
        let target = position_of(&arm, &q, &mut rng);
        let seed = random_q(&arm, &mut rng);
        check(
            &arm,
            Task::Position,
            &target,
            &seed,
            &format!("position {case}"),
        );
        let pose = arm.fk(&q);
        let target = turned(&pose, rng.random_range(-3.0..3.0));
        check(
            &arm,
            Task::PositionAndAxis,
            &target,
            &seed,
            &format!("axis {case}"),
        );
        check(&arm, Task::Pose, &target, &seed, &format!("pose {case}"));
    }
}

/// A position alone leaves the Panda four dimensions of self-motion: the solution nearest a
/// posture, started from the one that also holds the orientation, is at least as near (and
/// in these cases nearer), and stationary on
/// that larger self-motion (the posture's pull has no part in the null space of the position
/// rows, where no joint is on a limit).
#[test]
fn a_position_alone_frees_more_self_motion() {
    let (checked, nearer) = frees_more_self_motion(Task::Position, 3..6, 78, 20);
    assert!(checked >= 10, "{checked}");
    assert_eq!(nearer, 20);
}

/// On `cases` random targets, posture and seeds for the Panda: the solution of `task` nearest
/// a posture, started from the whole pose's, reaches the task, is at least as near as the
/// whole pose's, and where no joint is on a limit is stationary on the self-motion of the
/// Jacobian with the rows `free` zeroed (the posture's pull has no part in its null space).
/// Returns how many were checked for stationarity and how many were nearer.
fn frees_more_self_motion(
    task: Task,
    free: core::ops::Range<usize>,
    seed: u64,
    cases: usize,
) -> (usize, usize) {
    let arm = panda::Robot;
    let mut rng = StdRng::seed_from_u64(seed);
    let (mut checked, mut nearer) = (0, 0);
    for case in 0..cases {
        let target = arm.fk(&random_q(&arm, &mut rng));
        let seed = random_q(&arm, &mut rng);
        let posture = random_q(&arm, &mut rng);
        let solve = |task, seed: &SVector<f64, 7>| {
            let ik = NumericIk {
                task,
                ..NumericIk::default()
            };
            ik.solve_preferring(&arm, &target, seed, Preference::Posture(&posture))
                .unwrap_or_else(|e| panic!("case {case}: {e}"))
                .q
        };
        // From the whole pose's nearest solution, which already reaches the task.
        let whole = solve(Task::Pose, &seed);
        let freer = solve(task, &whole);
        let (dp, dr) = task.errors(&arm.fk(&freer), &target);
        assert!(dp <= 1e-10 && dr <= 1e-10, "case {case}: {dp:e} {dr:e}");
        let distance = |q: &SVector<f64, 7>| (posture - q).norm();
        nearer += usize::from(distance(&freer) < distance(&whole) - 1e-6);
        assert!(
            distance(&freer) <= distance(&whole) + 1e-9,
            "case {case}: {} > {}",
            distance(&freer),
            distance(&whole)
        );
        let on_limit = (0..7).any(|k| {
            let [lo, hi] = arm.limits(k).unwrap();
            freer[k] <= lo + 1e-9 || freer[k] >= hi - 1e-9
        });
        if on_limit {
            continue;
        }
        let mut j = arm.jacobian(&freer);
        for r in free.clone() {
            j.row_mut(r).fill(0.0);
        }
        let pull = posture - freer;
        let moves = JacobianSvd::new(&j).null_space_projection(&pull);
        assert!(
            moves.amax() <= 1e-7 * (1.0 + pull.amax()),
            "case {case}: {:e}",
            moves.amax()
        );
        checked += 1;
    }
    (checked, nearer)
}

#[test]
fn the_task_errors_are_what_they_say() {
    let a = Isometry3::new(Vector3::new(0.1, 0.2, 0.3), Vector3::new(0.4, -0.2, 0.1));
    // Turned about its own z axis by 0.7 and moved by (0, 0.3, 0.4): the axis is unchanged.
    let b = Translation3::new(0.0, 0.3, 0.4)
        * a
        * UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.7);
    let (dp, dr) = Task::PositionAndAxis.errors(&b, &a);
    assert!((dp - 0.5).abs() < 1e-15 && dr < 1e-15, "{dp} {dr:e}");
    assert!((Task::Pose.errors(&b, &a).1 - 0.7).abs() < 1e-14);
    assert_eq!(Task::Position.errors(&b, &a).1, 0.0);
    // The axis reversed: a half turn; tilted by 0.25 about x: 0.25.
    let flip = a * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), core::f64::consts::PI);
    assert!((Task::PositionAndAxis.errors(&flip, &a).1 - core::f64::consts::PI).abs() < 1e-15);
    let tilt = a * UnitQuaternion::from_axis_angle(&Vector3::x_axis(), 0.25);
    assert!((Task::PositionAndAxis.errors(&tilt, &a).1 - 0.25).abs() < 1e-15);
    assert_eq!(
        [Task::Pose, Task::Position, Task::PositionAndAxis].map(Task::constraints),
        [6, 3, 5]
    );
}

/// A target whose axis points opposite the tool's at the seed (the shortest turn is not
/// unique there) is still reached.
#[test]
fn an_opposite_axis_is_reached() {
    let arm = panda::Robot;
    let seed = SVector::<f64, 7>::from([0.0, -0.3, 0.0, -2.0, 0.0, 1.7, 0.8]);
    let at_seed = arm.fk(&seed);
    let flip = UnitQuaternion::from_axis_angle(&Vector3::x_axis(), core::f64::consts::PI);
    let target = Isometry3::from_parts(at_seed.translation, at_seed.rotation * flip);
    let ik = NumericIk {
        task: Task::PositionAndAxis,
        ..NumericIk::default()
    };
    let (_, dr) = Task::PositionAndAxis.errors(&at_seed, &target);
    assert!((dr - core::f64::consts::PI).abs() < 1e-12);
    check(&arm, Task::PositionAndAxis, &target, &seed, "opposite axis");
    assert!(ik.solve(&arm, &target, &seed).unwrap().iterations > 1);
}

#[test]
fn a_task_solve_allocates_nothing_for_a_generated_arm() {
    let arm = planar_elbow::Robot;
    let target = Isometry3::translation(0.5, 0.4, 0.0);
    let seed = SVector::<f64, 2>::new(0.3, 0.3);
    let ik = NumericIk {
        task: Task::Position,
        ..NumericIk::default()
    };
    let mut result: Option<Result<_, IkError>> = None;
    assert_eq!(
        allocations_during(|| result = Some(ik.solve(&arm, &target, &seed))),
        0
    );
    assert!(result.unwrap().unwrap().position_error <= 1e-10);
}

/// `pose` turned about the world's vertical through its origin by `angle`.
fn yawed(pose: &Isometry3<f64>, angle: f64) -> Isometry3<f64> {
    let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), angle);
    Isometry3::from_parts(pose.translation, turn * pose.rotation)
}

/// A SCARA told only x and y reaches them at heights its prismatic joint cannot (the same
/// targets as positions fail); a mask counting one rotation component is refused.
#[test]
fn a_mask_frees_what_it_leaves_out_on_a_scara() {
    let arm = scara::Robot;
    let mut rng = StdRng::seed_from_u64(91);
    for case in 0..20 {
        let mut target = position_of(&arm, &random_q(&arm, &mut rng), &mut rng);
        target.translation.vector.z += rng.random_range(1.0..5.0);
        let seed = random_q(&arm, &mut rng);
        let what = format!("scara xy {case}");
        let mask = Task::Mask([true, true, false, false, false, false]);
        check(&arm, mask, &target, &seed, &what);
        let position = NumericIk {
            task: Task::Position,
            ..NumericIk::default()
        };
        assert!(position.solve(&arm, &target, &seed).is_err(), "{what}");
    }
    for rotation in [
        [true, false, false],
        [false, true, false],
        [false, false, true],
    ] {
        let mask = [true, true, true, rotation[0], rotation[1], rotation[2]];
        let ik = NumericIk {
            task: Task::Mask(mask),
            ..NumericIk::default()
        };
        let seed = random_q(&arm, &mut rng);
        let target = arm.fk(&seed);
        match ik.solve(&arm, &target, &seed) {
            Err(IkError::InvalidSettings(why)) => assert!(why.contains("mask"), "{why}"),
            other => panic!("{mask:?}: {other:?}"),
        }
    }
}

/// With the turn about the world's vertical left free, the PUMA 560 (five constraints, six
/// joints) and the Panda reach targets turned about the vertical from random seeds, and the
/// turn they leave is free: the PUMA 560's solutions mostly keep some of it.
#[test]
fn a_mask_leaves_the_turn_about_the_vertical_free() {
    let mask = Task::Mask([true, true, true, true, true, false]);
    let mut rng = StdRng::seed_from_u64(92);
    let mut kept = 0;
    for case in 0..20 {
        let arm = puma560::Robot;
        let pose = arm.fk(&random_q(&arm, &mut rng));
        let target = yawed(&pose, rng.random_range(-3.0..3.0));
        let seed = random_q(&arm, &mut rng);
        let q = check(&arm, mask, &target, &seed, &format!("puma {case}"));
        let left = target.rotation * arm.fk(&q).rotation.inverse();
        kept += usize::from(left.angle() > 1e-3);
        let arm = panda::Robot;
        let pose = arm.fk(&random_q(&arm, &mut rng));
        let target = yawed(&pose, rng.random_range(-3.0..3.0));
        let seed = random_q(&arm, &mut rng);
        check(&arm, mask, &target, &seed, &format!("panda {case}"));
    }
    assert!(kept >= 10, "{kept}");
}

/// The turn about the vertical, left free, is one more dimension of the Panda's self-motion:
/// the solution nearest a posture, started from the whole pose's, is at least as near (here
/// nearer in all but a few cases), and stationary on that larger self-motion (where no joint is
/// on a limit: the yaw freedom pushes more of them there, so more cases).
#[test]
fn a_mask_frees_more_self_motion() {
    let mask = Task::Mask([true, true, true, true, true, false]);
    let (checked, nearer) = frees_more_self_motion(mask, 5..6, 93, 40);
    assert!(checked >= 10, "{checked}");
    assert!(nearer >= 35, "{nearer}");
}

#[test]
fn mask_errors_and_constraints_are_what_they_say() {
    let a = Isometry3::new(Vector3::new(0.1, 0.2, 0.3), Vector3::new(0.4, -0.2, 0.1));
    // Moved by (0.3, 0, 0.4) and turned by 0.7 about the world's vertical.
    let b = Translation3::new(0.3, 0.0, 0.4) * yawed(&a, 0.7);
    let all = Task::Mask([true; 6]);
    let (dp, dr) = all.errors(&b, &a);
    assert!(
        (dp - 0.5).abs() < 1e-15 && (dr - 0.7).abs() < 1e-14,
        "{dp} {dr}"
    );
    // As the whole pose's.
    let (p, r) = Task::Pose.errors(&b, &a);
    assert!((dp - p).abs() < 1e-15 && (dr - r).abs() < 1e-14);
    let (dp, dr) = Task::Mask([false, true, true, true, true, false]).errors(&b, &a);
    assert!((dp - 0.4).abs() < 1e-15 && dr < 1e-15, "{dp} {dr:e}");
    let (dp, dr) = Task::Mask([false; 6]).errors(&b, &a);
    assert_eq!((dp, dr), (0.0, 0.0));
    assert_eq!(
        [
            [true; 6],
            [false; 6],
            [true, false, true, true, false, true]
        ]
        .map(|m| Task::Mask(m).constraints()),
        [6, 0, 4]
    );
}
