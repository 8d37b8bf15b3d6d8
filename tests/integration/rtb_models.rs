//! Every DH model of Robotics Toolbox for Python 1.5.0 (tests/data/rtb_models.json, made by
//! scripts/rtb_models.py): 23 robots from 2 to 10 joints — industrial arms, 7-joint arms,
//! 10-joint snakes, a PUMA 560 on a two-axis gantry with a rotated base, standard and modified
//! tables, base and tool transforms, joints turning against their DH axis (Jaco and Mico, in
//! the `urdf` convention) — each written as a dhgen description, on the runtime path against the
//! Toolbox's T, J0 and, where the model has dynamics, D, g, C q̇ and τ at 5 seeded states (and
//! the body Jacobian against its `jacobe`, tests/data/rtb_jacobe.json; the kinematic Hessian
//! and manipulability gradient against its `hessian0` and `jacobm`, tests/data/rtb_hessian.json);
//! and
//! the same robots converted to DH tables of both conventions (`convert::to_dh`). The
//! Toolbox's data that is outside the format's ranges (IRB 140: a centre of mass 198 km away)
//! must be rejected with an error naming the field.

use crate::urdf::{matrix as rows, vector as column};
use dhgen::Robot;
use dhgen::model::convert::to_dh;
use dhgen::model::{Convention, RobotModel};
use nalgebra::{DMatrix, DVector};
use serde_json::Value;

fn data() -> Value {
    data_file("rtb_models.json")
}

/// `tests/data/<name>`, parsed.
fn data_file(name: &str) -> Value {
    let path = format!("{}/tests/data/{name}", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The largest difference relative to the reference's largest entry (at least 1).
fn error(ours: &DMatrix<f64>, theirs: &DMatrix<f64>) -> f64 {
    assert_eq!(ours.shape(), theirs.shape());
    (ours - theirs).amax() / theirs.amax().max(1.0)
}

/// The worst errors of `robot` against the references `r`: T, J, D, g, C q̇, τ.
fn worst(robot: &Robot, r: &Value) -> [f64; 6] {
    let n = robot.dof();
    let mut worst = [0.0f64; 6];
    for s in r["samples"].as_array().unwrap() {
        let (q, qd, qdd) = (column(&s["q"]), column(&s["qd"]), column(&s["qdd"]));
        let t = robot.fk(&q[..]).to_homogeneous();
        let t = DMatrix::from_fn(4, 4, |i, j| t[(i, j)]);
        worst[0] = worst[0].max(error(&t, &rows(&s["T"])));
        let j = robot.jacobian(&q[..]);
        let j = DMatrix::from_fn(6, n, |a, b| j[(a, b)]);
        worst[1] = worst[1].max(error(&j, &rows(&s["J0"])));
        if s.get("D").is_none() {
            continue;
        }
        let vector = |v: &[f64]| DMatrix::from_column_slice(n, 1, v);
        worst[2] = worst[2].max(error(&robot.mass_matrix(&q[..]), &rows(&s["D"])));
        let g = robot.gravity(&q[..]);
        worst[3] = worst[3].max(error(&vector(g.as_slice()), &rows(&s["g"])));
        let c = robot.coriolis(&q[..], &qd[..]) * vector(&qd);
        worst[4] = worst[4].max(error(&c, &rows(&s["Cqd"])));
        let tau = robot.inverse_dynamics(&q[..], &qd[..], &qdd[..]);
        worst[5] = worst[5].max(error(&vector(tau.as_slice()), &rows(&s["tau"])));
    }
    worst
}

#[test]
fn toolbox_models_match_on_the_runtime_path() {
    let d = data();
    let robots = d["robots"].as_array().unwrap();
    assert_eq!(robots.len(), 23);
    let mut dynamics = 0;
    let mut flipped = 0;
    for r in robots {
        let name = r["name"].as_str().unwrap();
        let robot = Robot::from_toml_str(r["toml"].as_str().unwrap())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let n = robot.dof();
        assert_eq!(n, r["dof"].as_u64().unwrap() as usize, "{name}");
        if r["samples"][0].get("D").is_some() {
            dynamics += 1;
        }
        if r["flipped"].as_bool().unwrap() {
            assert_eq!(robot.model().convention, Convention::Urdf, "{name}");
            flipped += 1;
        }
        let w = worst(&robot, r);
        for (what, w) in ["T", "J", "D", "g", "Cqd", "tau"].iter().zip(w) {
            println!("{name} ({n} joints) {what}: worst relative error {w:.1e}");
            assert!(w < 1e-12, "{name} {what}: {w:e}");
        }
    }
    assert_eq!(
        (dynamics, flipped),
        (8, 2),
        "the models with dynamics, with flipped joints"
    );
}

/// Calls `each(name, robot, state, reference)` for every sample of every model, with the
/// sample's entry in the reference file `file` (made at the same states, in the same order).
fn with_reference(file: &str, mut each: impl FnMut(&str, &Robot, &Value, &Value)) {
    let (d, reference) = (data(), data_file(file));
    let (robots, references) = (
        d["robots"].as_array().unwrap(),
        reference["robots"].as_array().unwrap(),
    );
    assert_eq!(robots.len(), references.len());
    for (r, reference) in robots.iter().zip(references) {
        let name = r["name"].as_str().unwrap();
        assert_eq!(reference["name"].as_str(), Some(name));
        let robot = Robot::from_toml_str(r["toml"].as_str().unwrap()).unwrap();
        let states = r["samples"].as_array().unwrap();
        let refs = reference["samples"].as_array().unwrap();
        assert_eq!(states.len(), refs.len(), "{name}");
        for (s, e) in states.iter().zip(refs) {
            each(name, &robot, s, e);
        }
    }
}

/// The body Jacobian (`Arm::body_jacobian`) against the Toolbox's `jacobe` at the same states
/// (tests/data/rtb_jacobe.json, made by scripts/rtb_jacobe.py), on all 23 models.
#[test]
fn toolbox_models_body_jacobians_match_jacobe() {
    let mut compared = 0;
    with_reference("rtb_jacobe.json", |name, robot, s, e| {
        let q = column(&s["q"]);
        let jb = dhgen::Arm::body_jacobian(robot, &DVector::from_column_slice(&q));
        let jb = DMatrix::from_fn(6, robot.dof(), |a, b| jb[(a, b)]);
        let w = error(&jb, &rows(&e["Je"]));
        assert!(w < 1e-12, "{name}: body Jacobian off jacobe by {w:e}");
        compared += 1;
    });
    assert_eq!(compared, 5 * 23);
}

/// The kinematic Hessian (`velocity::kinematic_hessian`) against the Toolbox's `hessian0`, and
/// the manipulability and its gradient (`velocity::manipulability_gradient`) against its
/// `manipulability` and `jacobm` for all, translational and rotational axes, at the same states
/// (tests/data/rtb_hessian.json, made by scripts/rtb_hessian.py), on all 23 models. The
/// Toolbox's `jacobm` inverts J Jᵀ, so it is compared where that is well conditioned (the
/// script leaves the others null); there, both measures are the same product of singular
/// values.
#[test]
fn toolbox_models_hessians_and_manipulability_gradients_match() {
    use dhgen::velocity::{Axes, kinematic_hessian, manipulability_gradient};
    let (mut hessians, mut gradients) = (0, 0);
    with_reference("rtb_hessian.json", |name, robot, s, e| {
        let n = robot.dof();
        let q = DVector::from_column_slice(&column(&s["q"]));
        let j = dhgen::Arm::jacobian(robot, &q);
        if let Some(h0) = e.get("H0") {
            let h0 = h0.as_array().unwrap();
            assert_eq!(h0.len(), n, "{name}");
            for (k, (ours, theirs)) in kinematic_hessian(&j).zip(h0).enumerate() {
                let ours = DMatrix::from_fn(6, n, |a, b| ours[(a, b)]);
                let w = error(&ours, &rows(theirs));
                assert!(w < 1e-12, "{name}: ∂J/∂q_{k} off hessian0 by {w:e}");
            }
            hessians += 1;
        }
        for (key, axes) in [
            ("all", Axes::All),
            ("trans", Axes::Translation),
            ("rot", Axes::Rotation),
        ] {
            if e["Jm"][key].is_null() {
                continue;
            }
            let (m, grad) = manipulability_gradient(&j, axes)
                .unwrap_or_else(|| panic!("{name} {key}: no gradient where jacobm has one"));
            let theirs = e["m"][key].as_f64().unwrap();
            assert!(
                (m - theirs).abs() < 1e-12 * theirs.max(1.0),
                "{name} {key}: m {m} vs {theirs}"
            );
            let grad = DMatrix::from_column_slice(n, 1, grad.as_slice());
            let w = error(
                &grad,
                &DMatrix::from_column_slice(n, 1, &column(&e["Jm"][key])),
            );
            assert!(w < 1e-10, "{name} {key}: ∂m/∂q off jacobm by {w:e}");
            gradients += 1;
        }
    });
    // Two states per model, and most states' three measures (not the planar arms').
    assert_eq!(hessians, 2 * 23);
    assert!(gradients > 200, "{gradients} gradients compared");
}

/// Converted to a DH table of either convention (the flipped joints of Jaco and Mico get a z
/// axis along the joint's turning direction, the frames around them change, q does not), each
/// robot still matches the Toolbox.
#[test]
fn toolbox_models_converted_to_dh_still_match() {
    let d = data();
    for r in d["robots"].as_array().unwrap() {
        let name = r["name"].as_str().unwrap();
        let model = RobotModel::from_toml_str(r["toml"].as_str().unwrap()).unwrap();
        for convention in [Convention::Standard, Convention::Modified] {
            let converted = to_dh(&model, convention)
                .unwrap_or_else(|e| panic!("{name} to {convention:?}: {e}"));
            let w = worst(&Robot::from_model(converted), r);
            for (what, w) in ["T", "J", "D", "g", "Cqd", "tau"].iter().zip(w) {
                assert!(w < 1e-12, "{name} as {convention:?} {what}: {w:e}");
            }
        }
    }
}

#[test]
fn toolbox_data_outside_the_ranges_is_rejected_at_the_field() {
    let d = data();
    let rejected = d["rejected"].as_array().unwrap();
    assert!(!rejected.is_empty());
    for r in rejected {
        let name = r["name"].as_str().unwrap();
        let e = match Robot::from_toml_str(r["toml"].as_str().unwrap()) {
            Ok(_) => panic!("{name}: accepted"),
            Err(e) => e.to_string(),
        };
        let field = r["field"].as_str().unwrap();
        let link = r["link"].as_u64().unwrap();
        assert!(
            e.contains(&format!("link {link}, field `{field}`")) && !e.contains('\n'),
            "{name}: {e}"
        );
    }
}
