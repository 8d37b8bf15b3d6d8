//! Laws the runtime path must obey at any configuration, checked on random states of the
//! four reference robots and of three fixtures (tests/fixtures): a prismatic-joint arm with
//! non-quarter angles (`rpp_arm`), a modified-DH arm with a base, a tool and tilted gravity
//! (`tilted_modified`), and an arm with motor inertia and friction (`driven`). Also the API's
//! errors and panics.
//!
//! Finite differences appear only here, as an independent check of analytic results.
//! Comparisons are norm-relative: `|a − b| ≤ tol · max(1, max |b|)` over the whole quantity.

use crate::support::{fixture, fixture_path, runtime};
use dhgen::model::{JointKind, JointValue};
use dhgen::nalgebra::{DMatrix, DVector, Isometry3, Matrix6, Vector3};
use dhgen::{Error, Robot};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use std::f64::consts::PI;

const CASES: u32 = 24;

/// Every robot the laws run on.
fn robots() -> Vec<Robot> {
    let mut robots: Vec<Robot> = ["planar_elbow", "puma560", "stanford", "panda"]
        .into_iter()
        .map(runtime)
        .collect();
    robots.extend(["rpp_arm", "tilted_modified", "driven"].map(fixture));
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

/// The potential energy `P = −Σ m_i gravity · c_i` (world frame), from the description's
/// link frames and centres of mass (not the joint frames the runtime path walks).
fn potential_energy_of_the_links(robot: &Robot, q: &[f64]) -> f64 {
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
fn potential_energy_is_the_weight_times_the_height_of_each_centre_of_mass() {
    for_all_states(|robot, q, _, _| {
        ensure_close(
            "P",
            &[robot.potential_energy(q)],
            &[potential_energy_of_the_links(robot, q)],
            1e-12,
        )
    });
}

#[test]
fn gravity_is_the_gradient_of_the_potential_energy() {
    for_all_states(|robot, q, _, _| {
        let expected: Vec<f64> = (0..robot.dof())
            .map(|i| {
                (robot.potential_energy(&nudged(q, i, H))
                    - robot.potential_energy(&nudged(q, i, -H)))
                    / (2.0 * H)
            })
            .collect();
        ensure_close("g", robot.gravity(q).as_slice(), &expected, FD_TOL)
    });
}

/// The centre of mass carries the potential energy, `P = −M gravity · c` with `M` the links'
/// masses summed, and its Jacobian is its derivative and gives gravity, `g = −M J_cᵀ gravity`.
#[test]
fn centre_of_mass_carries_the_potential_energy_and_gravity() {
    for_all_states(|robot, q, qd, _| {
        let (mass, c) = robot.center_of_mass(q);
        let links: f64 = robot
            .model()
            .links
            .iter()
            .map(|l| l.inertial.unwrap().mass)
            .sum();
        ensure_close("M", &[mass], &[links], 1e-14)?;
        let gravity = Vector3::from(robot.model().gravity);
        ensure_close(
            "P",
            &[-mass * gravity.dot(&c.coords)],
            &[robot.potential_energy(q)],
            1e-12,
        )?;
        let jc = robot.center_of_mass_jacobian(q);
        let rate = (robot.center_of_mass(&along(q, qd, H)).1
            - robot.center_of_mass(&along(q, qd, -H)).1)
            / (2.0 * H);
        ensure_close(
            "ċ",
            (&jc * DVector::from_column_slice(qd)).as_slice(),
            rate.as_slice(),
            FD_TOL,
        )?;
        let g = -(jc.transpose() * gravity) * mass;
        ensure_close("g", g.as_slice(), robot.gravity(q).as_slice(), 1e-12)
    });
}

/// Generated arms take the trait's centre of mass from their own pose and Jacobian: the
/// runtime path's numbers.
#[test]
fn generated_arms_have_the_runtime_centre_of_mass() {
    use crate::catalogue::{panda, puma560};
    use dhgen::ArmDynamics;
    macro_rules! check {
        ($m:ident) => {{
            let name = stringify!($m);
            let q = dhgen::nalgebra::SVector::<f64, { $m::DOF }>::from_fn(|i, _| {
                (0.9 * i as f64 + 0.2).sin()
            });
            let robot = runtime(name);
            let (mass, c) = $m::Robot.center_of_mass(&q);
            let (want_mass, want_c) = robot.center_of_mass(q.as_slice());
            assert!(close(&[mass], &[want_mass], 1e-14), "{name} M");
            assert!(
                close(c.coords.as_slice(), want_c.coords.as_slice(), 1e-14),
                "{name} c"
            );
            let jc = $m::Robot.center_of_mass_jacobian(&q);
            let want = robot.center_of_mass_jacobian(q.as_slice());
            assert!(close(jc.as_slice(), want.as_slice(), 1e-13), "{name} J_c");
        }};
    }
    check!(puma560);
    check!(panda);
}

/// Along the motion through (q, q̇) with acceleration q̈, the energy `T + P` changes at the
/// power the joint torques put in, friction's share taken out: `d(T + P)/dt = q̇ᵀ (τ − f)`
/// with `τ = τ(q, q̇, q̈)` (what makes `Ḋ − 2C` skew-symmetric physical).
#[test]
fn energy_changes_by_the_power_of_the_torques() {
    for_all_states(|robot, q, qd, qdd| {
        let energy = |t: f64| {
            let q_t: Vec<f64> = q
                .iter()
                .zip(qd)
                .zip(qdd)
                .map(|((x, v), a)| x + t * v + 0.5 * t * t * a)
                .collect();
            let qd_t = along(qd, qdd, t);
            robot.kinetic_energy(&q_t, &qd_t) + robot.potential_energy(&q_t)
        };
        // Central differences err by E‴h²/6, and along fast motions E‴ reaches 10⁴ (the
        // Stanford arm, 7,600 at a state proptest found: 1.3e-7 at h = H, above FD_TOL), so
        // Richardson's extrapolation of two of them, whose error is O(h⁴): 6e-11 there at
        // h = 1e-3, where rounding (energies of ~10² J) costs about as much.
        let central = |h: f64| (energy(h) - energy(-h)) / (2.0 * h);
        let h = 1e-3;
        let rate = (4.0 * central(h / 2.0) - central(h)) / 3.0;
        let work = robot.inverse_dynamics(q, qd, qdd) - friction(robot, qd);
        let power = DVector::from_column_slice(qd).dot(&work);
        ensure_close("d(T + P)/dt", &[rate], &[power], FD_TOL)
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
    let robot = fixture("driven");
    // The same arm without its motors and friction.
    let mut bare_model = robot.model().clone();
    for link in &mut bare_model.links {
        link.motor = None;
        link.friction = None;
    }
    let plain = Robot::from_model(bare_model);
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
    let robot = fixture("tilted_modified");
    let base = robot.model().base.unwrap().frame::<f64>();
    let base_r = dhgen::nalgebra::Matrix3::from_fn(|r, c| base.r[r][c]);
    let local_gravity = base_r.transpose() * Vector3::from(robot.model().gravity);
    let mut unmoved_model = robot.model().clone();
    unmoved_model.base = None;
    unmoved_model.gravity = local_gravity.into();
    let unmoved = Robot::from_model(unmoved_model);
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
    let bad = std::fs::read_to_string(fixture_path("rpp_arm"))
        .unwrap()
        .replacen("mass = 2.0", "mass = -2.0", 1);
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
    let panda = runtime("panda");
    assert_eq!(panda.dof(), 7);
    assert_eq!(panda.model().convention, dhgen::Convention::Modified);
    assert!(panda.has_dynamics());
    let model = panda.model().clone();
    let rebuilt = Robot::from_model(model);
    let q = [0.1, -0.4, 0.3, -2.0, 0.2, 1.8, 0.5];
    assert_eq!(rebuilt.fk(&q), panda.fk(&q));
    assert_eq!(panda.frames(&q).len(), 7);
}

#[test]
fn kinematics_only_robot_has_kinematics() {
    let robot = fixture("bare");
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
    fixture("bare").mass_matrix(&[0.0, 0.0]);
}

#[test]
#[should_panic(expected = "dhgen::Robot::inverse_dynamics: robot `bare` has no mass properties")]
fn inverse_dynamics_of_kinematics_only_robot_panics() {
    fixture("bare").inverse_dynamics(&[0.0; 2], &[0.0; 2], &[0.0; 2]);
}

#[test]
#[should_panic(expected = "dhgen::Robot::fk: `q` has length 5, expected 6 (one entry per joint)")]
fn fk_rejects_short_q() {
    runtime("puma560").fk(&[0.0; 5]);
}

#[test]
#[should_panic(expected = "dhgen::Robot::jacobian: `q` has length 8, expected 7")]
fn jacobian_rejects_long_q() {
    runtime("panda").jacobian(&[0.0; 8]);
}

#[test]
#[should_panic(expected = "dhgen::Robot::inverse_dynamics: `qdd` has length 1, expected 2")]
fn inverse_dynamics_rejects_wrong_qdd() {
    runtime("planar_elbow").inverse_dynamics(&[0.0; 2], &[0.0; 2], &[0.0; 1]);
}

#[test]
#[should_panic(expected = "dhgen::Robot::coriolis: `qd` has length 3, expected 2")]
fn coriolis_rejects_wrong_qd() {
    runtime("planar_elbow").coriolis(&[0.0; 2], &[0.0; 3]);
}

#[test]
#[should_panic(expected = "dhgen::Robot::forward_dynamics: `tau` has length 0, expected 2")]
fn forward_dynamics_rejects_wrong_tau() {
    runtime("planar_elbow").forward_dynamics(&[0.0; 2], &[0.0; 2], &[]);
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
