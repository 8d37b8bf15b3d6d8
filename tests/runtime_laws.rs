//! Laws the runtime path must obey at any configuration, checked on random states of the
//! four reference robots and of robots written here: a prismatic-joint arm with non-quarter
//! angles, a modified-DH arm with a base, a tool and tilted gravity, and an arm with motor
//! inertia and friction. Also the API's errors and panics.
//!
//! Finite differences appear only here, as an independent check of analytic results.
//! Comparisons are norm-relative: `|a − b| ≤ tol · max(1, max |b|)` over the whole quantity.

use dhgen::model::{JointKind, JointValue};
use dhgen::nalgebra::{DMatrix, DVector, Isometry3, Matrix6, Vector3};
use dhgen::{Error, Robot};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use std::f64::consts::PI;

const CASES: u32 = 24;

fn reference(name: &str) -> Robot {
    let root = env!("CARGO_MANIFEST_DIR");
    Robot::from_toml_file(format!("{root}/robots/{name}.toml")).unwrap()
}

/// Prismatic joints, non-quarter-turn twists and offsets, products of inertia.
const PRISMATIC: &str = r#"
name = "rpp_arm"
convention = "standard"
gravity = [0.0, 0.0, -9.81]
[[links]]
joint = "revolute"
a = 0.1
alpha = 0
d = 0.5
theta = 0
mass = 3.0
com = [-0.05, 0.01, -0.1]
inertia = { xx = 0.05, yy = 0.06, zz = 0.04, xy = 0.001 }
[[links]]
joint = "prismatic"
a = 0.0
alpha = "-90deg"
d = 0.2
theta = "90deg"
limits = [0.1, 0.8]
mass = 2.0
com = [0.0, 0.05, -0.2]
inertia = { xx = 0.03, yy = 0.03, zz = 0.01 }
[[links]]
joint = "prismatic"
a = 0.05
alpha = "30deg"
d = 0.1
theta = "10deg"
limits = [0.0, 0.5]
mass = 1.0
com = [0.01, 0.0, -0.1]
inertia = { xx = 0.01, yy = 0.012, zz = 0.005, yz = 0.001 }
[[links]]
joint = "revolute"
a = 0.03
alpha = "75deg"
d = 0.05
theta = "-20deg"
mass = 0.5
com = [0.0, 0.02, 0.03]
inertia = { xx = 0.002, yy = 0.002, zz = 0.001 }
"#;

/// Modified DH with a base pose, a tool pose, a prismatic joint and gravity off every axis.
fn tilted_modified(with_base: bool, gravity: [f64; 3]) -> String {
    let base = if with_base {
        r#"base = { xyz = [0.3, -0.2, 1.0], rpy = ["20deg", "-35deg", "100deg"] }"#
    } else {
        ""
    };
    format!(
        r#"
name = "tilted_modified"
convention = "modified"
gravity = {gravity:?}
{base}
tool = {{ xyz = [0.02, 0.0, 0.15], rpy = [0, "90deg", "-45deg"] }}
[[links]]
joint = "revolute"
a = 0.0
alpha = 0
d = 0.3
theta = "15deg"
mass = 4.0
com = [0.01, 0.02, -0.1]
inertia = {{ xx = 0.1, yy = 0.1, zz = 0.02, xz = 0.003 }}
[[links]]
joint = "revolute"
a = 0.05
alpha = "-90deg"
d = 0.0
theta = 0
mass = 2.5
com = [0.2, 0.0, 0.01]
inertia = {{ xx = 0.01, yy = 0.05, zz = 0.05, xy = -0.002 }}
[[links]]
joint = "prismatic"
a = 0.4
alpha = "60deg"
d = 0.1
theta = "-30deg"
limits = [0.0, 0.3]
mass = 1.5
com = [0.0, -0.03, 0.1]
inertia = {{ xx = 0.02, yy = 0.02, zz = 0.004 }}
[[links]]
joint = "revolute"
a = 0.0
alpha = "90deg"
d = 0.25
theta = 0
mass = 1.0
com = [0.0, 0.0, 0.05]
inertia = {{ xx = 0.004, yy = 0.004, zz = 0.002, yz = 0.0005 }}
[[links]]
joint = "revolute"
a = 0.02
alpha = "-1.1"
d = 0.0
theta = 0
mass = 0.4
com = [0.01, 0.01, 0.02]
inertia = {{ xx = 0.001, yy = 0.0012, zz = 0.0008 }}
"#
    )
}

const TILTED_GRAVITY: [f64; 3] = [1.2, -2.0, -9.5];

/// A three-joint arm; `drives` adds motor inertia and friction to every joint.
fn driven(drives: bool) -> String {
    let joint = |motor: &str, friction: &str| {
        if drives {
            format!("motor = {{ {motor} }}\nfriction = {{ {friction} }}")
        } else {
            String::new()
        }
    };
    format!(
        r#"
name = "driven"
convention = "standard"
[[links]]
joint = "revolute"
a = 0.0
alpha = "90deg"
d = 0.4
theta = 0
mass = 5.0
com = [0.0, -0.1, 0.0]
inertia = {{ xx = 0.1, yy = 0.05, zz = 0.1 }}
{}
[[links]]
joint = "revolute"
a = 0.5
alpha = 0
d = 0.0
theta = 0
mass = 3.0
com = [-0.25, 0.0, 0.05]
inertia = {{ xx = 0.01, yy = 0.07, zz = 0.07 }}
{}
[[links]]
joint = "prismatic"
a = 0.0
alpha = 0
d = 0.1
theta = "90deg"
mass = 1.0
com = [0.0, 0.0, -0.1]
inertia = {{ xx = 0.01, yy = 0.01, zz = 0.002 }}
{}
"#,
        joint(
            "inertia = 2.0e-4, gear = 62.6",
            "viscous = 1.5, coulomb = 0.4"
        ),
        joint(
            "inertia = 2.0e-4, gear = 107.8",
            "viscous = 0.8, coulomb = 0.7"
        ),
        joint(
            "inertia = 3.3e-5, gear = -76.0",
            "viscous = 20.0, coulomb = 3.0"
        ),
    )
}

/// Every robot the laws run on.
fn robots() -> Vec<Robot> {
    let mut robots: Vec<Robot> = ["planar_elbow", "puma560", "stanford", "panda"]
        .into_iter()
        .map(reference)
        .collect();
    robots.push(Robot::from_toml_str(PRISMATIC).unwrap());
    robots.push(Robot::from_toml_str(&tilted_modified(true, TILTED_GRAVITY)).unwrap());
    robots.push(Robot::from_toml_str(&driven(true)).unwrap());
    robots
}

/// A random state: q within the joint limits (±π where none are given), qd, qdd.
fn state(robot: &Robot) -> impl Strategy<Value = (Vec<f64>, Vec<f64>, Vec<f64>)> + use<> {
    let q: Vec<_> = robot
        .model()
        .links
        .iter()
        .map(|l| {
            let [lo, hi] = l.limits.unwrap_or([-PI, PI]);
            lo..hi
        })
        .collect();
    let n = robot.dof();
    (
        q,
        prop::collection::vec(-2.0..2.0f64, n),
        prop::collection::vec(-5.0..5.0f64, n),
    )
}

/// Few cases, so that the suite stays fast in debug builds; failures are reported with
/// their shrunk input rather than saved to a file.
fn config() -> Config {
    Config {
        cases: CASES,
        failure_persistence: None,
        ..Config::default()
    }
}

/// Runs `law` on random states of every robot.
fn for_all_states(law: impl Fn(&Robot, &[f64], &[f64], &[f64]) -> Result<(), TestCaseError>) {
    for robot in robots() {
        let mut runner = TestRunner::new(config());
        runner
            .run(&state(&robot), |(q, qd, qdd)| law(&robot, &q, &qd, &qdd))
            .unwrap_or_else(|e| panic!("{}: {e}", robot.model().name));
    }
}

/// `max |a − b| ≤ tol · max(1, max |b|)`.
fn close(a: &[f64], b: &[f64], tol: f64) -> bool {
    let scale = b.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    a.iter().zip(b).all(|(x, y)| (x - y).abs() <= tol * scale)
}

fn ensure_close(what: &str, a: &[f64], b: &[f64], tol: f64) -> Result<(), TestCaseError> {
    prop_assert!(close(a, b, tol), "{what}:\n got {a:?}\n expected {b:?}");
    Ok(())
}

/// `x ± h` in coordinate `i`.
fn nudged(x: &[f64], i: usize, h: f64) -> Vec<f64> {
    let mut y = x.to_vec();
    y[i] += h;
    y
}

/// `x + h·v`.
fn along(x: &[f64], v: &[f64], h: f64) -> Vec<f64> {
    x.iter().zip(v).map(|(a, b)| a + h * b).collect()
}

/// Step of the central differences: truncation error ~h², rounding ~1e-16/h.
const H: f64 = 1e-5;
/// What central differences with step `H` can resolve.
const FD_TOL: f64 = 1e-7;

#[test]
fn link_frames_compose_the_model_transforms() {
    // The runtime path splits each A_i into constants and a pure joint motion; composing
    // the model's own Link::transform must give the same frames.
    for_all_states(|robot, q, _, _| {
        let model = robot.model();
        let mut frame = model
            .base
            .map_or(dhgen::model::Frame::identity(), |b| b.frame());
        let frames = robot.frames(q);
        for (i, link) in model.links.iter().enumerate() {
            let value = match link.joint {
                JointKind::Revolute => JointValue::Revolute {
                    cos: q[i].cos(),
                    sin: q[i].sin(),
                },
                JointKind::Prismatic => JointValue::Prismatic(q[i]),
            };
            frame = frame.compose(&link.transform(model.convention, value));
            let ours = frames[i].to_homogeneous();
            for r in 0..3 {
                ensure_close(
                    "rotation",
                    &[ours[(r, 0)], ours[(r, 1)], ours[(r, 2)]],
                    &frame.r[r],
                    1e-13,
                )?;
            }
            ensure_close(
                "origin",
                frames[i].translation.vector.as_slice(),
                &frame.p,
                1e-13,
            )?;
        }
        let tool = model.tool.map_or(Isometry3::identity(), |t| {
            let f = t.frame::<f64>();
            let m = dhgen::nalgebra::Matrix3::from_fn(|r, c| f.r[r][c]);
            Isometry3::from_parts(
                Vector3::from(f.p).into(),
                dhgen::nalgebra::UnitQuaternion::from_matrix(&m),
            )
        });
        let expected = (frames[frames.len() - 1] * tool).to_homogeneous();
        ensure_close(
            "fk",
            robot.fk(q).to_homogeneous().as_slice(),
            expected.as_slice(),
            1e-13,
        )
    });
}

#[test]
fn jacobian_is_the_derivative_of_fk() {
    for_all_states(|robot, q, _, _| {
        let j = robot.jacobian(q);
        for i in 0..robot.dof() {
            let plus = robot.fk(&nudged(q, i, H));
            let minus = robot.fk(&nudged(q, i, -H));
            let v = (plus.translation.vector - minus.translation.vector) / (2.0 * H);
            let w = (plus.rotation * minus.rotation.inverse()).scaled_axis() / (2.0 * H);
            let column: Vec<f64> = j.column(i).iter().copied().collect();
            let expected: Vec<f64> = v.iter().chain(w.iter()).copied().collect();
            ensure_close("Jacobian column", &column, &expected, FD_TOL)?;
        }
        Ok(())
    });
}

#[test]
fn mass_matrix_is_symmetric_positive_definite() {
    for_all_states(|robot, q, _, _| {
        let d = robot.mass_matrix(q);
        prop_assert_eq!(&d, &d.transpose());
        let smallest = d.clone().symmetric_eigenvalues().min();
        prop_assert!(smallest > 0.0, "smallest eigenvalue {smallest}");
        prop_assert!(d.cholesky().is_some());
        Ok(())
    });
}

#[test]
fn christoffel_symbols_are_derivatives_of_the_mass_matrix() {
    for_all_states(|robot, q, _, _| {
        let n = robot.dof();
        let c = robot.christoffel(q);
        let dd: Vec<DMatrix<f64>> = (0..n)
            .map(|l| {
                (robot.mass_matrix(&nudged(q, l, H)) - robot.mass_matrix(&nudged(q, l, -H)))
                    / (2.0 * H)
            })
            .collect();
        let mut ours = Vec::new();
        let mut expected = Vec::new();
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    prop_assert_eq!(c[i][j][k], c[j][i][k], "c_ijk symmetric in i, j");
                    ours.push(c.get(i, j, k));
                    expected.push(0.5 * (dd[i][(k, j)] + dd[j][(k, i)] - dd[k][(i, j)]));
                }
            }
        }
        ensure_close("c_ijk", &ours, &expected, FD_TOL)
    });
}

#[test]
fn coriolis_matrix_contracts_the_christoffel_symbols() {
    for_all_states(|robot, q, qd, _| {
        let n = robot.dof();
        let c = robot.christoffel(q);
        let expected = DMatrix::from_fn(n, n, |k, j| (0..n).map(|i| c[i][j][k] * qd[i]).sum());
        ensure_close(
            "C",
            robot.coriolis(q, qd).as_slice(),
            expected.as_slice(),
            1e-13,
        )
    });
}

#[test]
fn mass_matrix_rate_minus_twice_coriolis_is_skew_symmetric() {
    for_all_states(|robot, q, qd, _| {
        let d_rate = (robot.mass_matrix(&along(q, qd, H)) - robot.mass_matrix(&along(q, qd, -H)))
            / (2.0 * H);
        // N = Ḋ − 2C is skew-symmetric exactly when Ḋ = C + Cᵀ; compared that way the
        // finite-difference error is measured against the size of Ḋ.
        let c = robot.coriolis(q, qd);
        ensure_close(
            "C + Cᵀ",
            (&c + c.transpose()).as_slice(),
            d_rate.as_slice(),
            FD_TOL,
        )
    });
}

/// The potential energy `P = −Σ m_i gravity · c_i` (world frame).
fn potential_energy(robot: &Robot, q: &[f64]) -> f64 {
    let gravity = Vector3::from(robot.model().gravity);
    robot
        .frames(q)
        .iter()
        .zip(&robot.model().links)
        .map(|(frame, link)| {
            let inertial = link.inertial.unwrap();
            let com = frame * dhgen::nalgebra::Point3::from(inertial.com);
            -inertial.mass * gravity.dot(&com.coords)
        })
        .sum()
}

#[test]
fn gravity_is_the_gradient_of_the_potential_energy() {
    for_all_states(|robot, q, _, _| {
        let expected: Vec<f64> = (0..robot.dof())
            .map(|i| {
                (potential_energy(robot, &nudged(q, i, H))
                    - potential_energy(robot, &nudged(q, i, -H)))
                    / (2.0 * H)
            })
            .collect();
        ensure_close("g", robot.gravity(q).as_slice(), &expected, FD_TOL)
    });
}

/// `viscous·q̇ + coulomb·sign(q̇)` from the description.
fn friction(robot: &Robot, qd: &[f64]) -> DVector<f64> {
    DVector::from_fn(robot.dof(), |i, _| {
        robot.model().links[i].friction.map_or(0.0, |f| {
            let sign = if qd[i] > 0.0 {
                1.0
            } else if qd[i] < 0.0 {
                -1.0
            } else {
                0.0
            };
            f.viscous * qd[i] + f.coulomb * sign
        })
    })
}

#[test]
fn inverse_dynamics_is_the_equation_of_motion() {
    for_all_states(|robot, q, qd, qdd| {
        let (qd_v, qdd_v) = (
            DVector::from_column_slice(qd),
            DVector::from_column_slice(qdd),
        );
        let expected = robot.mass_matrix(q) * qdd_v
            + robot.coriolis(q, qd) * qd_v
            + robot.gravity(q)
            + friction(robot, qd);
        ensure_close(
            "tau",
            robot.inverse_dynamics(q, qd, qdd).as_slice(),
            expected.as_slice(),
            1e-12,
        )
    });
}

#[test]
fn forward_dynamics_inverts_inverse_dynamics() {
    for_all_states(|robot, q, qd, qdd| {
        let tau = robot.inverse_dynamics(q, qd, qdd);
        let back = robot
            .forward_dynamics(q, qd, tau.as_slice())
            .expect("D is positive definite");
        ensure_close("qdd", back.as_slice(), qdd, 1e-9)
    });
}

#[test]
fn motor_inertia_and_friction_add_exactly_their_terms() {
    let plain = Robot::from_toml_str(&driven(false)).unwrap();
    let robot = Robot::from_toml_str(&driven(true)).unwrap();
    let mut runner = TestRunner::new(config());
    runner
        .run(&state(&robot), |(q, mut qd, qdd)| {
            qd[1] = 0.0; // sign(0) = 0: no Coulomb friction at rest
            let armature: Vec<f64> = robot
                .model()
                .links
                .iter()
                .map(|l| l.motor.unwrap().armature())
                .collect();
            prop_assert_eq!(armature[2], 3.3e-5 * 76.0 * 76.0);
            let extra = DVector::from_fn(3, |i, _| armature[i] * qdd[i]) + friction(&robot, &qd);
            let tau = robot.inverse_dynamics(&q, &qd, &qdd) - plain.inverse_dynamics(&q, &qd, &qdd);
            ensure_close("τ difference", tau.as_slice(), extra.as_slice(), 1e-12)?;
            let d = robot.mass_matrix(&q) - plain.mass_matrix(&q);
            ensure_close(
                "D difference",
                d.as_slice(),
                DMatrix::from_diagonal(&DVector::from_vec(armature)).as_slice(),
                1e-12,
            )?;
            prop_assert_eq!(robot.coriolis(&q, &qd), plain.coriolis(&q, &qd));
            prop_assert_eq!(robot.gravity(&q), plain.gravity(&q));
            prop_assert_eq!(robot.christoffel(&q), plain.christoffel(&q));
            Ok(())
        })
        .unwrap();
}

#[test]
fn gravity_is_given_in_the_world_frame() {
    // Moving the base moves the arm, not gravity: the robot with a base behaves like the
    // same robot without one under gravity rotated into its base frame.
    let robot = Robot::from_toml_str(&tilted_modified(true, TILTED_GRAVITY)).unwrap();
    let base = robot.model().base.unwrap().frame::<f64>();
    let base_r = dhgen::nalgebra::Matrix3::from_fn(|r, c| base.r[r][c]);
    let local_gravity = base_r.transpose() * Vector3::from(TILTED_GRAVITY);
    let unmoved = Robot::from_toml_str(&tilted_modified(false, local_gravity.into())).unwrap();
    let base_iso = Isometry3::from_parts(
        Vector3::from(base.p).into(),
        dhgen::nalgebra::UnitQuaternion::from_matrix(&base_r),
    );
    let mut rotate = Matrix6::zeros();
    rotate.fixed_view_mut::<3, 3>(0, 0).copy_from(&base_r);
    rotate.fixed_view_mut::<3, 3>(3, 3).copy_from(&base_r);
    let mut runner = TestRunner::new(config());
    runner
        .run(&state(&robot), |(q, qd, qdd)| {
            let pose = (base_iso * unmoved.fk(&q)).to_homogeneous();
            ensure_close(
                "fk",
                robot.fk(&q).to_homogeneous().as_slice(),
                pose.as_slice(),
                1e-13,
            )?;
            let j = rotate * unmoved.jacobian(&q);
            ensure_close(
                "jacobian",
                robot.jacobian(&q).as_slice(),
                j.as_slice(),
                1e-13,
            )?;
            ensure_close(
                "g",
                robot.gravity(&q).as_slice(),
                unmoved.gravity(&q).as_slice(),
                1e-12,
            )?;
            ensure_close(
                "D",
                robot.mass_matrix(&q).as_slice(),
                unmoved.mass_matrix(&q).as_slice(),
                1e-12,
            )?;
            let tau = robot.inverse_dynamics(&q, &qd, &qdd);
            ensure_close(
                "tau",
                tau.as_slice(),
                unmoved.inverse_dynamics(&q, &qd, &qdd).as_slice(),
                1e-12,
            )?;
            let c = robot.coriolis(&q, &qd);
            ensure_close(
                "C",
                c.as_slice(),
                unmoved.coriolis(&q, &qd).as_slice(),
                1e-12,
            )
        })
        .unwrap();
}

#[test]
fn errors_name_the_file_link_and_field() {
    let bad = PRISMATIC.replacen("mass = 2.0", "mass = -2.0", 1);
    let err = Robot::from_toml_str(&bad).unwrap_err();
    assert!(matches!(err, Error::Load(_)));
    let message = err.to_string();
    assert!(
        message.contains("<string>") && message.contains("link 2") && message.contains("mass"),
        "{message}"
    );
    let missing = "/nonexistent/dir/arm.toml";
    let message = Robot::from_toml_file(missing).unwrap_err().to_string();
    assert!(message.contains(missing), "{message}");
}

#[test]
fn accessors_describe_the_robot() {
    let panda = reference("panda");
    assert_eq!(panda.dof(), 7);
    assert_eq!(panda.model().convention, dhgen::Convention::Modified);
    assert!(panda.has_dynamics());
    let model = panda.model().clone();
    let rebuilt = Robot::from_model(model);
    let q = [0.1, -0.4, 0.3, -2.0, 0.2, 1.8, 0.5];
    assert_eq!(rebuilt.fk(&q), panda.fk(&q));
    assert_eq!(panda.frames(&q).len(), 7);
}

const KINEMATICS_ONLY: &str = r#"
name = "bare"
convention = "standard"
[[links]]
joint = "revolute"
a = 1.0
alpha = 0
d = 0
theta = 0
[[links]]
joint = "prismatic"
a = 0.0
alpha = 0
d = 0
theta = 0
"#;

#[test]
fn kinematics_only_robot_has_kinematics() {
    let robot = Robot::from_toml_str(KINEMATICS_ONLY).unwrap();
    assert!(!robot.has_dynamics());
    let t = robot.fk(&[std::f64::consts::FRAC_PI_2, 0.5]);
    assert!(close(
        t.translation.vector.as_slice(),
        &[0.0, 1.0, 0.5],
        1e-15
    ));
    let j = robot.jacobian(&[0.0, 0.5]);
    assert!(close(
        j.as_slice(),
        &[0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0],
        1e-15
    ));
}

#[test]
#[should_panic(expected = "dhgen::Robot::mass_matrix: robot `bare` has no mass properties")]
fn dynamics_of_kinematics_only_robot_panics() {
    Robot::from_toml_str(KINEMATICS_ONLY)
        .unwrap()
        .mass_matrix(&[0.0, 0.0]);
}

#[test]
#[should_panic(expected = "dhgen::Robot::inverse_dynamics: robot `bare` has no mass properties")]
fn inverse_dynamics_of_kinematics_only_robot_panics() {
    Robot::from_toml_str(KINEMATICS_ONLY)
        .unwrap()
        .inverse_dynamics(&[0.0; 2], &[0.0; 2], &[0.0; 2]);
}

#[test]
#[should_panic(expected = "dhgen::Robot::fk: `q` has length 5, expected 6 (one entry per joint)")]
fn fk_rejects_short_q() {
    reference("puma560").fk(&[0.0; 5]);
}

#[test]
#[should_panic(expected = "dhgen::Robot::jacobian: `q` has length 8, expected 7")]
fn jacobian_rejects_long_q() {
    reference("panda").jacobian(&[0.0; 8]);
}

#[test]
#[should_panic(expected = "dhgen::Robot::inverse_dynamics: `qdd` has length 1, expected 2")]
fn inverse_dynamics_rejects_wrong_qdd() {
    reference("planar_elbow").inverse_dynamics(&[0.0; 2], &[0.0; 2], &[0.0; 1]);
}

#[test]
#[should_panic(expected = "dhgen::Robot::coriolis: `qd` has length 3, expected 2")]
fn coriolis_rejects_wrong_qd() {
    reference("planar_elbow").coriolis(&[0.0; 2], &[0.0; 3]);
}

#[test]
#[should_panic(expected = "dhgen::Robot::forward_dynamics: `tau` has length 0, expected 2")]
fn forward_dynamics_rejects_wrong_tau() {
    reference("planar_elbow").forward_dynamics(&[0.0; 2], &[0.0; 2], &[]);
}

#[test]
fn forward_dynamics_is_none_for_a_singular_mass_matrix() {
    // The second joint moves a body with no mass and no inertia: D is singular.
    let text = r#"
name = "weightless_wrist"
convention = "standard"
[[links]]
joint = "revolute"
a = 0.5
alpha = 0
d = 0
theta = 0
mass = 1.0
com = [-0.25, 0, 0]
inertia = { yy = 0.02, zz = 0.02 }
[[links]]
joint = "revolute"
a = 0.0
alpha = 0
d = 0
theta = 0
mass = 0.0
com = [0, 0, 0]
inertia = { xx = 0.0 }
"#;
    let robot = Robot::from_toml_str(text).unwrap();
    assert_eq!(robot.mass_matrix(&[0.3, 0.1])[(1, 1)], 0.0);
    assert_eq!(
        robot.forward_dynamics(&[0.3, 0.1], &[0.0; 2], &[1.0, 0.0]),
        None
    );
}
