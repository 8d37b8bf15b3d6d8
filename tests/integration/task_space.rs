//! Task-space (operational-space) dynamics, `dhgen::task_space`:
//! - against Robotics Toolbox 1.5.0 (tests/data/rtb_task_space.json, made by
//!   scripts/rtb_task_space.py from the Toolbox's own D, J, J̇, C and g, and checked there
//!   against its `inertia_x`, `coriolis_x`, `gravload_x` and forward dynamics);
//! - against the law it states, on seeded states of arms with prismatic joints, a modified
//!   table with base, tool and tilted gravity, motors and friction, URDF arms, and seeded
//!   random arms of 8 and 12 joints with oblique axes: under the torques
//!   `Jᵀ F + Nᵀ τ₀`, forward dynamics gives the task acceleration `J q̈ + J̇ q̇ = Λ⁻¹ (F − μ − p)`,
//!   whatever `τ₀`; and `J J̄ = I`;
//! - generated arms against the runtime path, without allocation, and their `tool_terms`
//!   against their five separate quantities;
//! - forward dynamics with the task held (`constrained`): the constraint, the equation of
//!   motion and Gauss's principle on seeded states, and Pinocchio 4.1.0's constrained
//!   `forwardDynamics` (tests/data/derivatives_*.json);
//! - its errors: a task the arm cannot hold, a kinematic singularity, a singular `D`, and
//!   non-finite input.

use crate::catalogue::{odd, panda, planar_elbow, puma560, scara, stanford};
use crate::support::{allocations_during, fixture, runtime};
use crate::urdf::{matrix, vector};
use dhgen::nalgebra::{DMatrix, DVector, DimName, OMatrix, OVector, SVector, U3, U6, Vector6};
use dhgen::task_space::{
    TaskDynamics, TaskSpaceError, ToolTerms, tool, tool_position, tool_with_payload,
};
use dhgen::{Arm, ArmDynamics, Robot};
use serde_json::Value;
use std::f64::consts::PI;

/// `|a − b|_max / max(1, |b|_max)`.
fn relative(a: &[f64], b: &[f64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / scale
}

/// A seeded stream of states: `q` within the joint limits (±π where none), `q̇` in ±2.
fn states(robot: &Robot, count: usize, seed: u64) -> Vec<(DVector<f64>, DVector<f64>)> {
    let mut x = seed | 1;
    let mut uniform = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..count)
        .map(|_| {
            let q = DVector::from_iterator(
                robot.dof(),
                robot.model().links.iter().map(|l| {
                    let [lo, hi] = l.limits.unwrap_or([-PI, PI]);
                    lo + (hi - lo) * uniform()
                }),
            );
            let qd = DVector::from_fn(robot.dof(), |_, _| 4.0 * uniform() - 2.0);
            (q, qd)
        })
        .collect()
}

/// A state `(q, q̇)` of [`states`] as the joint vectors of a generated arm of `N` joints.
fn fixed<const N: usize>(
    q: &DVector<f64>,
    qd: &DVector<f64>,
) -> (SVector<f64, N>, SVector<f64, N>) {
    (
        SVector::from_column_slice(q.as_slice()),
        SVector::from_column_slice(qd.as_slice()),
    )
}

/// The task's Λ, μ, p and J̄ᵀ as row-major plain vectors.
fn parts<M: DimName, D: dhgen::nalgebra::Dim>(t: &TaskDynamics<M, D>) -> [Vec<f64>; 4]
where
    dhgen::nalgebra::DefaultAllocator: dhgen::nalgebra::allocator::Allocator<M, D>
        + dhgen::nalgebra::allocator::Allocator<M, M>
        + dhgen::nalgebra::allocator::Allocator<M>
        + dhgen::nalgebra::allocator::Allocator<D, D>
        + dhgen::nalgebra::allocator::Allocator<D>,
{
    let rows = |m: &[f64], r: usize, c: usize| -> Vec<f64> {
        (0..r * c).map(|k| m[(k % c) * r + k / c]).collect()
    };
    let (m, n) = t.inverse_transpose().shape();
    [
        rows(t.inertia().as_slice(), m, m),
        t.coriolis().as_slice().to_vec(),
        t.gravity().as_slice().to_vec(),
        rows(t.inverse_transpose().as_slice(), m, n),
    ]
}

#[test]
fn matches_the_toolbox() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/rtb_task_space.json"
    );
    let data: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let robots = data["robots"].as_array().unwrap();
    let names: Vec<&str> = robots.iter().map(|r| r["name"].as_str().unwrap()).collect();
    assert_eq!(names, ["Panda", "Puma560", "Stanford", "UR10"]);
    for r in robots {
        let robot = Robot::from_toml_str(r["toml"].as_str().unwrap()).unwrap();
        let mut worst = [0.0f64; 4];
        for s in r["samples"].as_array().unwrap() {
            let q = DVector::from_vec(vector(&s["q"]));
            let qd = DVector::from_vec(vector(&s["qd"]));
            let ours = match r["task"].as_str().unwrap() {
                "tool" => parts(&tool(&robot, &q, &qd).unwrap()),
                other => panic!("task {other}"),
            };
            let theirs = [
                matrix(&s["Lambda"]).transpose().as_slice().to_vec(),
                vector(&s["mu"]),
                vector(&s["p"]),
                matrix(&s["JbarT"]).transpose().as_slice().to_vec(),
            ];
            for k in 0..4 {
                worst[k] = worst[k].max(relative(&ours[k], &theirs[k]));
            }
        }
        eprintln!("{}: Λ, μ, p, J̄ᵀ worst relative error {worst:?}", r["name"]);
        assert!(worst.iter().all(|&e| e < 1e-9), "{}: {worst:?}", r["name"]);
    }
}

/// The largest over smallest eigenvalue of a symmetric matrix.
fn condition(m: DMatrix<f64>) -> f64 {
    let e = m.symmetric_eigenvalues();
    e.max() / e.min()
}

/// The law of task-space dynamics on `count` seeded states of `robot`, for the task `$task`
/// (`tool` or `tool_position`) with rows `$m`: returns the worst relative residual, the
/// number of states checked, and the largest null-space torque seen.
macro_rules! law {
    ($robot:expr, $task:ident, $m:ty, $count:expr) => {{
        let rows = <$m as DimName>::DIM;
        let robot: &Robot = $robot;
        let (mut worst, mut checked, mut null) = (0.0f64, 0usize, 0.0f64);
        for (k, (q, qd)) in states(robot, $count, 0x9E37_79B9_7F4A_7C15 ^ robot.dof() as u64)
            .into_iter()
            .enumerate()
        {
            let task = match $task(robot, &q, &qd) {
                Ok(task) => task,
                Err(TaskSpaceError::SingularTask) => continue,
                Err(e) => panic!("{}: {e} at {q}", robot.model().name),
            };
            // Near a singularity Λ grows as 1/σ² and the law loses digits with it.
            let mobility = DMatrix::from_fn(rows, rows, |i, j| task.mobility()[(i, j)]);
            if condition(mobility) > 1e8 {
                continue;
            }
            checked += 1;
            let f = OVector::<f64, $m>::from_fn(|i, _| 10.0 * ((i + k) as f64 * 1.3).sin());
            let tau0 = DVector::from_fn(robot.dof(), |i, _| 5.0 * ((i * 7 + k) as f64).cos());
            let null_torque = task.null_space_torque(&tau0);
            null = null.max(null_torque.amax());
            let tau = task.torque(&f) + null_torque;
            let qdd = ArmDynamics::forward_dynamics(robot, &q, &qd, &tau).unwrap();
            let a = Arm::jacobian(robot, &q) * qdd + Arm::jdot_qdot(robot, &q, &qd);
            let achieved = a.rows(0, rows).into_owned();
            let predicted = task.acceleration(&f);
            worst = worst.max(relative(achieved.as_slice(), predicted.as_slice()));
            // The force for an acceleration gives that acceleration back.
            let back = task.acceleration(&task.force(&predicted));
            worst = worst.max(relative(back.as_slice(), predicted.as_slice()));
            // J J̄ = I and Λ (J D⁻¹ Jᵀ) = I.
            let jjbar = task.jacobian() * task.inverse_transpose().transpose();
            let eye = OMatrix::<f64, $m, $m>::identity();
            worst = worst.max(relative(jjbar.as_slice(), eye.as_slice()));
            let product = task.inertia() * task.mobility();
            worst = worst.max(relative(product.as_slice(), eye.as_slice()));
            let inertia = task.inertia();
            worst = worst.max(relative(inertia.as_slice(), inertia.transpose().as_slice()));
        }
        (worst, checked, null)
    }};
}

/// [`law!`] on `$count` states, asserted: at least three in four states away from
/// singularities, the law to 1e-8, and null-space torques only where the arm is redundant.
macro_rules! check_law {
    ($robot:expr, $task:ident, $m:ty, $count:expr) => {{
        let robot: &Robot = $robot;
        let (worst, checked, null) = law!(robot, $task, $m, $count);
        let name = &robot.model().name;
        let what = stringify!($task);
        eprintln!(
            "{name} {what}: {checked} states, worst {worst:.1e}, null-space torque {null:.1e}"
        );
        assert!(checked >= $count * 3 / 4, "{name} {what}: {checked} states");
        assert!(worst < 1e-8, "{name} {what}: {worst:e}");
        if robot.dof() > <$m as DimName>::DIM {
            assert!(null > 1e-2, "{name} {what}: {null:e}");
        } else {
            assert!(null < 1e-8, "{name} {what}: {null:e}");
        }
    }};
}

#[test]
fn forward_dynamics_obeys_the_task_space_equation() {
    let count = 40;
    let mut six: Vec<Robot> = ["puma560", "stanford", "panda"].map(runtime).into();
    six.extend(["ur5_urdf", "snake17"].map(fixture));
    // URDF arms as read from their files: xArm7 (7 joints) and Kinova's six.
    let urdf = |file: &str| {
        let path = format!("{}/tests/data/urdf/{file}", env!("CARGO_MANIFEST_DIR"));
        Robot::from_urdf_file(path).unwrap()
    };
    six.extend([urdf("xarm7.urdf"), urdf("kinova.urdf")]);
    // Seeded random arms with no structure (`dhgen random --style general`): oblique axes,
    // offsets everywhere, full inertias.
    for n in [8, 12] {
        let path = format!(
            "{}/benches/arms/general_{n}.toml",
            env!("CARGO_MANIFEST_DIR")
        );
        six.push(Robot::from_toml_file(path).unwrap());
    }
    for robot in &six {
        check_law!(robot, tool, U6, count);
    }
    let mut three: Vec<Robot> = ["scara", "panda"].map(runtime).into();
    three.extend(["driven", "odd", "tilted_modified", "rpp_arm", "snake17"].map(fixture));
    for robot in &three {
        check_law!(robot, tool_position, U3, count);
    }
}

/// Forward dynamics with the task held (`TaskDynamics::constrained`) on `count` seeded states:
/// the worst relative residual of the constraint `J q̈ + J̇ q̇ = a` (relative to the free
/// motion's task acceleration), of the equation of motion
/// `D q̈ + b = τ + Jᵀ F` (through inverse dynamics), and of Gauss's principle (moving `q̈`
/// along a direction the constraint allows raises `(q̈ − q̈_free)ᵀ D (q̈ − q̈_free)`).
macro_rules! constrained_law {
    ($robot:expr, $task:ident, $m:ty, $count:expr) => {{
        let robot: &Robot = $robot;
        let (mut worst, mut checked) = (0.0f64, 0usize);
        for (k, (q, qd)) in states(robot, $count, 0xC0FF_EE00 ^ robot.dof() as u64)
            .into_iter()
            .enumerate()
        {
            let Ok(task) = $task(robot, &q, &qd) else {
                continue;
            };
            let rows = <$m as DimName>::DIM;
            checked += 1;
            let n = robot.dof();
            let tau = DVector::from_fn(n, |i, _| 8.0 * ((i * 5 + k) as f64 * 0.7).sin());
            let qdd_free = ArmDynamics::forward_dynamics(robot, &q, &qd, &tau).unwrap();
            // Held still (a = 0), then driven along a given acceleration.
            let driven = OVector::<f64, $m>::from_fn(|i, _| ((i + k) as f64 * 0.9).cos());
            for a in [OVector::<f64, $m>::zeros(), driven] {
                let (qdd, force) = task.constrained(&qdd_free, &a);
                let reached = (Arm::jacobian(robot, &q) * &qdd + Arm::jdot_qdot(robot, &q, &qd))
                    .rows(0, rows)
                    .into_owned();
                // J q̈ + J̇ q̇ = a is the difference of J q̈_free + J̇ q̇ and of J D⁻¹ Jᵀ F, which
                // cancel: its rounding is relative to their size (the PUMA 560's light wrist
                // under these torques: 1e5 rad/s²).
                let drift = (Arm::jacobian(robot, &q) * &qdd_free + Arm::jdot_qdot(robot, &q, &qd))
                    .rows(0, rows)
                    .amax();
                let e1 = (reached - &a).amax() / drift.max(a.amax()).max(1.0);
                let needed = ArmDynamics::inverse_dynamics(robot, &q, &qd, &qdd);
                let applied = &tau + task.torque(&force);
                let e2 = relative(needed.as_slice(), applied.as_slice());
                                worst = worst.max(e1).max(e2);
                // A direction the constraint allows: z − J̄ J z, for which J δ = 0.
                let z = DVector::from_fn(n, |i, _| ((i * 3 + k) as f64).sin());
                let delta = &z - task.inverse_transpose().tr_mul(&(task.jacobian() * &z));
                let d = ArmDynamics::mass_matrix(robot, &q);
                let cost = |x: &DVector<f64>| {
                    let e = x - &qdd_free;
                    e.dot(&(&d * &e))
                };
                let step = 1e-3 * (1.0 + qdd.amax()) / (1e-12 + delta.amax());
                let best = cost(&qdd);
                if delta.amax() > 1e-9 {
                    assert!(
                        cost(&(&qdd + &delta * step)) > best
                            && cost(&(&qdd - &delta * step)) > best,
                        "{}: q̈ is not the least constrained",
                        robot.model().name
                    );
                }
            }
        }
        (worst, checked)
    }};
}

#[test]
fn a_held_task_obeys_the_constrained_equation_of_motion() {
    let mut six: Vec<Robot> = ["puma560", "panda"].map(runtime).into();
    six.push(fixture("snake17"));
    let general = format!("{}/benches/arms/general_8.toml", env!("CARGO_MANIFEST_DIR"));
    six.push(Robot::from_toml_file(general).unwrap());
    for robot in &six {
        let (worst, checked) = constrained_law!(robot, tool, U6, 30);
        eprintln!(
            "{} tool held: {checked} states, worst {worst:.1e}",
            robot.model().name
        );
        assert!(
            checked >= 20 && worst < 1e-8,
            "{}: {worst:e}",
            robot.model().name
        );
    }
    let mut three: Vec<Robot> = ["scara"].map(runtime).into();
    three.extend(["driven", "odd", "tilted_modified"].map(fixture));
    for robot in &three {
        let (worst, checked) = constrained_law!(robot, tool_position, U3, 30);
        eprintln!(
            "{} tool position held: {checked} states, worst {worst:.1e}",
            robot.model().name
        );
        assert!(
            checked >= 20 && worst < 1e-8,
            "{}: {worst:e}",
            robot.model().name
        );
    }
}

#[test]
fn a_held_tool_matches_pinocchio() {
    // Pinocchio 4.1.0's constrained forwardDynamics with the tool frame held still, at the
    // states of tests/data/derivatives_*.json (scripts/pinocchio_derivatives.py).
    for name in ["puma560", "panda"] {
        let data = crate::support::pinocchio_reference(name);
        let robot = runtime(name);
        let (mut worst_qdd, mut worst_force, mut held) = (0.0f64, 0.0f64, 0);
        for s in data["samples"].as_array().unwrap() {
            let [q, qd, tau] = ["q", "qd", "tau"].map(|k| DVector::from_vec(vector(&s[k])));
            let task = tool(&robot, &q, &qd).unwrap();
            let free = ArmDynamics::forward_dynamics(&robot, &q, &qd, &tau).unwrap();
            let (qdd, force) = task.constrained(&free, &Vector6::zeros());
            worst_qdd = worst_qdd.max(relative(qdd.as_slice(), &vector(&s["held_qdd"])));
            worst_force = worst_force.max(relative(force.as_slice(), &vector(&s["held_force"])));
            held += 1;
        }
        eprintln!("{name}: {held} states, q̈ {worst_qdd:.1e}, force {worst_force:.1e}");
        assert!(
            held == 10 && worst_qdd < 1e-9 && worst_force < 1e-9,
            "{name}"
        );
    }
}

#[test]
fn generated_arms_agree_with_the_runtime_path_without_allocating() {
    fn check<const N: usize, A: ArmDynamics<Dof = dhgen::nalgebra::Const<N>>>(arm: &A, name: &str) {
        let robot = runtime(name);
        let mut worst = [0.0f64; 4];
        for (q, qd) in states(&robot, 20, 7) {
            let (sq, sqd) = fixed::<N>(&q, &qd);
            let Ok(runtime) = tool(&robot, &q, &qd) else {
                continue;
            };
            let mut generated = None;
            let allocations = allocations_during(|| generated = Some(tool(arm, &sq, &sqd)));
            assert_eq!(allocations, 0, "{name}");
            let generated = generated.unwrap().unwrap();
            for (k, (a, b)) in parts(&generated).iter().zip(parts(&runtime)).enumerate() {
                worst[k] = worst[k].max(relative(a, &b));
            }
            let position = tool_position(arm, &sq, &sqd).unwrap();
            let full = tool_position(&robot, &q, &qd).unwrap();
            worst[0] = worst[0].max(relative(
                position.inertia().as_slice(),
                full.inertia().as_slice(),
            ));
        }
        eprintln!("{name}: generated vs runtime Λ, μ, p, J̄ᵀ {worst:?}");
        assert!(worst.iter().all(|&e| e < 1e-9), "{name}: {worst:?}");
    }
    check(&puma560::Robot, "puma560");
    check(&stanford::Robot, "stanford");
    check(&panda::Robot, "panda");
}

/// A generated arm's `tool_terms` (one state's sines and cosines) are its five separate
/// quantities bit for bit, and the runtime path's default (five calls) agrees with them: on
/// arms with Coulomb and viscous friction, a prismatic joint and modified DH (odd), a
/// prismatic joint (SCARA, Stanford) and seven joints (Panda).
#[test]
fn tool_terms_are_the_five_quantities_at_once() {
    fn check<const N: usize, A: ArmDynamics<Dof = dhgen::nalgebra::Const<N>>>(
        arm: &A,
        robot: &Robot,
        name: &str,
    ) {
        for (q, qd) in states(robot, 10, 11) {
            let (sq, sqd) = fixed::<N>(&q, &qd);
            let t = arm.tool_terms(&sq, &sqd);
            assert_eq!(t.mass_matrix, arm.mass_matrix(&sq), "{name}");
            assert_eq!(t.jacobian, arm.jacobian(&sq), "{name}");
            assert_eq!(t.jdot_qdot, arm.jdot_qdot(&sq, &sqd), "{name}");
            assert_eq!(t.bias, arm.bias(&sq, &sqd), "{name}");
            assert_eq!(t.gravity, arm.gravity(&sq), "{name}");
            let r = robot.tool_terms(&q, &qd);
            let pairs: [(&[f64], &[f64]); 5] = [
                (t.mass_matrix.as_slice(), r.mass_matrix.as_slice()),
                (t.jacobian.as_slice(), r.jacobian.as_slice()),
                (t.jdot_qdot.as_slice(), r.jdot_qdot.as_slice()),
                (t.bias.as_slice(), r.bias.as_slice()),
                (t.gravity.as_slice(), r.gravity.as_slice()),
            ];
            for (k, (a, b)) in pairs.iter().enumerate() {
                assert!(
                    relative(a, b) < 1e-12,
                    "{name}: term {k}, {}",
                    relative(a, b)
                );
            }
        }
    }
    check(&odd::Robot, &fixture("odd"), "odd");
    check(&scara::Robot, &runtime("scara"), "scara");
    check(&stanford::Robot, &runtime("stanford"), "stanford");
    check(&panda::Robot, &runtime("panda"), "panda");
}

#[test]
fn payload_tool_terms_are_the_payload_quantities_at_once() {
    use dhgen::payload::{self, Payload};
    // Off-centre, with products of inertia.
    let part = Payload::new(
        1.7,
        [0.03, -0.02, 0.07],
        [[3e-3, 2e-4, -1e-4], [2e-4, 4e-3, 3e-4], [-1e-4, 3e-4, 2e-3]],
    )
    .unwrap();
    fn check<const N: usize, A: ArmDynamics<Dof = dhgen::nalgebra::Const<N>>>(
        arm: &A,
        robot: &Robot,
        part: &Payload,
        name: &str,
    ) {
        for (q, qd) in states(robot, 10, 5) {
            let (sq, sqd) = fixed::<N>(&q, &qd);
            for (r, t) in [
                (
                    robot.tool_terms(&q, &qd),
                    payload::tool_terms(robot, part, &q, &qd),
                ),
                {
                    let t = payload::tool_terms(arm, part, &sq, &sqd);
                    let r = arm.tool_terms(&sq, &sqd);
                    (to_dynamic(r), to_dynamic(t))
                },
            ] {
                // Against the separate functions of `payload` (runtime arm) ...
                let pairs: [(&[f64], DVector<f64>); 5] = [
                    (
                        t.mass_matrix.as_slice(),
                        DVector::from_column_slice(
                            payload::mass_matrix(robot, part, &q).as_slice(),
                        ),
                    ),
                    (
                        t.jacobian.as_slice(),
                        DVector::from_column_slice(r.jacobian.as_slice()),
                    ),
                    (
                        t.jdot_qdot.as_slice(),
                        DVector::from_column_slice(r.jdot_qdot.as_slice()),
                    ),
                    (t.bias.as_slice(), payload::bias(robot, part, &q, &qd)),
                    (t.gravity.as_slice(), payload::gravity(robot, part, &q)),
                ];
                for (k, (a, b)) in pairs.iter().enumerate() {
                    assert!(
                        relative(a, b.as_slice()) < 1e-12,
                        "{name}: term {k}, {}",
                        relative(a, b.as_slice())
                    );
                }
                // ... and the payload changes D, the bias and g (the test could fail).
                assert!(relative(t.mass_matrix.as_slice(), r.mass_matrix.as_slice()) > 1e-6);
                assert!(relative(t.gravity.as_slice(), r.gravity.as_slice()) > 1e-6);
            }
        }
    }
    check(&odd::Robot, &fixture("odd"), &part, "odd");
    check(&scara::Robot, &runtime("scara"), &part, "scara");
    check(&stanford::Robot, &runtime("stanford"), &part, "stanford");
    check(&panda::Robot, &runtime("panda"), &part, "panda");
}

/// A generated arm's `ToolTerms` in the runtime path's dynamic sizes.
fn to_dynamic<const N: usize>(
    t: ToolTerms<f64, dhgen::nalgebra::Const<N>>,
) -> ToolTerms<f64, dhgen::nalgebra::Dyn> {
    ToolTerms {
        mass_matrix: DMatrix::from_column_slice(N, N, t.mass_matrix.as_slice()),
        jacobian: DMatrix::from_column_slice(6, N, t.jacobian.as_slice())
            .fixed_rows::<6>(0)
            .into_owned(),
        jdot_qdot: t.jdot_qdot,
        bias: DVector::from_column_slice(t.bias.as_slice()),
        gravity: DVector::from_column_slice(t.gravity.as_slice()),
    }
}

#[test]
fn a_payload_joins_the_task_space_inertia() {
    use dhgen::payload::{self, Payload};
    let (mass, com, inertia) = (
        2.5,
        [0.02, -0.01, 0.08],
        [[4e-3, 1e-4, 0.0], [1e-4, 5e-3, 0.0], [0.0, 0.0, 3e-3]],
    );
    let part = Payload::new(mass, com, inertia).unwrap();
    let robot = runtime("panda");
    let held = robot.with_payload(&part).unwrap();
    let mut worst = [0.0f64; 5];
    let mut added = 0.0f64;
    for (q, qd) in states(&robot, 20, 11) {
        let Ok(task) = tool_with_payload(&robot, &part, &q, &qd) else {
            continue;
        };
        // As the runtime arm with the payload written into its last body ...
        let whole = tool(&held, &q, &qd).unwrap();
        for (k, (a, b)) in parts(&task).iter().zip(parts(&whole)).enumerate() {
            worst[k] = worst[k].max(relative(a, &b));
        }
        // ... and as the generated arm with it.
        let (sq, sqd) = fixed::<7>(&q, &qd);
        let generated = tool_with_payload(&panda::Robot, &part, &sq, &sqd).unwrap();
        worst[4] = worst[4].max(relative(&parts(&generated)[0], &parts(&task)[0]));
        // Under the torques Jᵀ F the arm holding it accelerates its tool as predicted.
        let f = Vector6::new(5.0, -3.0, 8.0, 0.4, -0.2, 0.3);
        let qdd = payload::forward_dynamics(&robot, &part, &q, &qd, &task.torque(&f)).unwrap();
        let a = Arm::jacobian(&robot, &q) * qdd + Arm::jdot_qdot(&robot, &q, &qd);
        worst[4] = worst[4].max(relative(a.as_slice(), task.acceleration(&f).as_slice()));
        // The task-space inertia grows by exactly the payload's spatial inertia at the tool
        // origin (world axes; the Woodbury identity, J of full row rank): [m, −h×; h×, I_o]
        // with h = m R c and I_o = R (I_c + m (|c|² − c cᵀ)) Rᵀ.
        let r = Arm::fk(&robot, &q)
            .rotation
            .to_rotation_matrix()
            .into_inner();
        let c = dhgen::nalgebra::Vector3::from(com);
        let i_c = dhgen::nalgebra::Matrix3::from_fn(|i, j| inertia[i][j]);
        let h = r * c * mass;
        let i_o = r
            * (i_c
                + (dhgen::nalgebra::Matrix3::identity() * c.norm_squared() - c * c.transpose())
                    * mass)
            * r.transpose();
        let mut spatial = dhgen::nalgebra::Matrix6::zeros();
        spatial.fixed_view_mut::<3, 3>(0, 0).fill_with_identity();
        spatial.fixed_view_mut::<3, 3>(0, 0).scale_mut(mass);
        spatial
            .fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&-h.cross_matrix());
        spatial
            .fixed_view_mut::<3, 3>(3, 0)
            .copy_from(&h.cross_matrix());
        spatial.fixed_view_mut::<3, 3>(3, 3).copy_from(&i_o);
        let bare = tool(&robot, &q, &qd).unwrap();
        let growth = task.inertia() - bare.inertia();
        added = added.max((growth - spatial).amax() / bare.inertia().amax());
    }
    eprintln!("Panda with a payload: {worst:?}, Λ − Λ_bare − M_payload {added:.1e} of Λ");
    assert!(worst.iter().all(|&e| e < 1e-9), "{worst:?}");
    assert!(added < 1e-10, "{added:e}");
}

#[test]
#[should_panic(
    expected = "dhgen::task_space::TaskDynamics::new: `d` is 3×3, `bias` has length 3 \
                           and `gravity` 3, expected 2×2 and 2"
)]
fn sizes_that_disagree_are_named() {
    let _ = TaskDynamics::<U3, dhgen::nalgebra::Dyn>::new(
        DMatrix::identity(3, 3),
        OMatrix::<f64, U3, dhgen::nalgebra::Dyn>::zeros(2),
        &OVector::<f64, U3>::zeros(),
        &DVector::zeros(3),
        &DVector::zeros(3),
    );
}

#[test]
#[should_panic(expected = "null_space_torque: `tau0` has length 6, expected 7")]
fn a_wrong_length_posture_torque_is_named() {
    let panda = runtime("panda");
    let task = tool(&panda, &DVector::from_element(7, 0.3), &DVector::zeros(7)).unwrap();
    let _ = task.null_space_torque(&DVector::zeros(6));
}

#[test]
fn errors_say_why() {
    // Two joints cannot hold six task directions, nor three.
    let (q, qd) = (SVector::<f64, 2>::new(0.3, 0.4), SVector::<f64, 2>::zeros());
    assert_eq!(
        tool(&planar_elbow::Robot, &q, &qd).unwrap_err(),
        TaskSpaceError::SingularTask
    );
    assert_eq!(
        tool_position(&planar_elbow::Robot, &q, &qd).unwrap_err(),
        TaskSpaceError::SingularTask
    );
    // Four joints hold the position (SCARA), not the orientation.
    let (q, qd) = (
        SVector::<f64, 4>::new(0.3, 0.8, 0.1, 0.2),
        SVector::<f64, 4>::zeros(),
    );
    assert!(tool_position(&scara::Robot, &q, &qd).is_ok());
    assert_eq!(
        tool(&scara::Robot, &q, &qd).unwrap_err(),
        TaskSpaceError::SingularTask
    );
    // The gantry's revolute joint turns about the world's x axis, its two prismatic joints
    // slide along y and z: its tool moves in a plane, everywhere.
    let gantry = fixture("gantry");
    for (q, qd) in states(&gantry, 20, 3) {
        assert_eq!(
            tool_position(&gantry, &q, &qd).unwrap_err(),
            TaskSpaceError::SingularTask,
            "{q}"
        );
    }
    // The wrist singularity of the PUMA 560 and of the Stanford arm (θ5 = 0: joints 4 and 6
    // aligned), on both paths; with θ5 = 0.9 instead, the tool's task is held.
    let qd = SVector::<f64, 6>::zeros();
    for theta5 in [0.0, 0.9] {
        let q = SVector::from([0.2, -0.5, 0.4, 0.3, theta5, -0.2]);
        let dq = DVector::from_column_slice(q.as_slice());
        let results = [
            tool(&puma560::Robot, &q, &qd).err(),
            tool(&stanford::Robot, &q, &qd).err(),
            tool(&runtime("puma560"), &dq, &DVector::zeros(6)).err(),
            tool(&runtime("stanford"), &dq, &DVector::zeros(6)).err(),
        ];
        let expected = (theta5 == 0.0).then_some(TaskSpaceError::SingularTask);
        assert_eq!(results, [expected; 4], "θ5 = {theta5}");
    }
    // UR5's published data has no inertia tensors: D(q) is singular everywhere.
    let ur5 = runtime("ur5");
    let q = DVector::from_column_slice(&[0.1, -1.0, 1.2, 0.3, 0.9, 0.2]);
    assert_eq!(
        tool(&ur5, &q, &DVector::zeros(6)).unwrap_err(),
        TaskSpaceError::SingularInertia
    );
    // Non-finite input.
    let q = SVector::from([0.2, f64::NAN, 0.4, 0.3, 0.9, -0.2]);
    assert_eq!(
        tool(&puma560::Robot, &q, &qd).unwrap_err(),
        TaskSpaceError::NotFinite
    );
    let qd = SVector::from([0.0, 0.0, f64::INFINITY, 0.0, 0.0, 0.0]);
    assert_eq!(
        tool(
            &puma560::Robot,
            &SVector::from([0.2, -0.5, 0.4, 0.3, 0.9, -0.2]),
            &qd
        )
        .unwrap_err(),
        TaskSpaceError::NotFinite
    );
    assert_eq!(
        TaskSpaceError::SingularTask.to_string(),
        "task space: the task Jacobian has lost rank (J D⁻¹ Jᵀ is singular)"
    );
}
