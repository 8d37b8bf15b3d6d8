//! A payload given at run time (`dhgen::payload`) against the same body written into the
//! description: added to the last link through the description format, τ, D, g, the bias,
//! q̈ and the kinetic and potential energy are the same to 1e-12 (q̈ to 1e-12 times D's
//! condition number), on the runtime path and on generated modules.

use crate::catalogue::{odd, panda, puma560, snake17};
use dhgen::payload::{self, Payload};
use dhgen::{ArmDynamics, Robot, RobotModel};
use nalgebra::{DVector, SVector};

fn box_payload() -> Payload {
    // 1.7 kg, off-centre, with products of inertia (a tilted box).
    Payload::new(
        1.7,
        [0.03, -0.02, 0.06],
        [
            [0.012, 0.001, -0.002],
            [0.001, 0.010, 0.0015],
            [-0.002, 0.0015, 0.008],
        ],
    )
    .unwrap()
}

/// The description with the payload merged into the last link, written through the format
/// (`to_toml` and back), as a user would edit the file.
fn with_payload_in_description(model: &RobotModel, p: &Payload) -> Robot {
    let mut m = model.clone();
    let tool = m
        .tool
        .map_or_else(dhgen::model::Frame::identity, |t| t.frame::<f64>());
    let held = dhgen::model::Inertial {
        mass: p.mass(),
        com: p.com(),
        inertia: p.inertia(),
    }
    .in_frame(&tool);
    let last = m.links.last_mut().unwrap();
    last.inertial = Some(last.inertial.unwrap().combined(&held));
    Robot::from_toml_str(&m.to_toml()).unwrap()
}

fn close(what: &str, got: &[f64], want: &[f64]) {
    close_to(what, got, want, 1e-12);
}

/// `got` and `want` agree to `tol` relative to the largest of `want` (and 1).
fn close_to(what: &str, got: &[f64], want: &[f64], tol: f64) {
    let scale = want.iter().fold(1.0f64, |m, x| m.max(x.abs()));
    for (g, w) in got.iter().zip(want) {
        assert!((g - w).abs() <= tol * scale, "{what}: {got:?} vs {want:?}");
    }
}

fn check<A: ArmDynamics<Dof = nalgebra::Const<N>>, const N: usize>(
    name: &str,
    arm: &A,
    model: &RobotModel,
    generated: impl Fn(&[f64; N], &[f64; N], &[f64; N], &[f64; 10]) -> SVector<f64, N>,
) {
    let p = box_payload();
    let merged = with_payload_in_description(model, &p);
    for s in 0..10 {
        let t = s as f64;
        let q = SVector::<f64, N>::from_fn(|i, _| (0.7 * t + 1.3 * i as f64).sin());
        let qd = SVector::<f64, N>::from_fn(|i, _| (0.3 * t - 0.9 * i as f64).cos());
        let qdd = SVector::<f64, N>::from_fn(|i, _| (1.1 * t + 0.5 * i as f64).sin() * 2.0);
        let (qv, qdv, qddv) = (
            DVector::from_column_slice(q.as_slice()),
            DVector::from_column_slice(qd.as_slice()),
            DVector::from_column_slice(qdd.as_slice()),
        );
        let tau = payload::inverse_dynamics(arm, &p, &q, &qd, &qdd);
        let want = merged.inverse_dynamics(&qv, &qdv, &qddv);
        close(&format!("{name} tau"), tau.as_slice(), want.as_slice());
        // The generated symbolic form: the payload's parameters as inputs of the recursion.
        let symbolic = generated(&q.into(), &qd.into(), &qdd.into(), &p.parameters());
        close(
            &format!("{name} generated tau with payload"),
            symbolic.as_slice(),
            want.as_slice(),
        );
        let d = payload::mass_matrix(arm, &p, &q);
        close(
            &format!("{name} D"),
            d.as_slice(),
            merged.mass_matrix(&qv).as_slice(),
        );
        let g = payload::gravity(arm, &p, &q);
        close(
            &format!("{name} g"),
            g.as_slice(),
            merged.gravity(&qv).as_slice(),
        );
        let b = payload::bias(arm, &p, &q, &qd);
        close(
            &format!("{name} bias"),
            b.as_slice(),
            merged.bias(&qv, &qdv).as_slice(),
        );
        let acc = payload::forward_dynamics(arm, &p, &q, &qd, &tau).unwrap();
        close(&format!("{name} qdd"), acc.as_slice(), qdd.as_slice());
        close(
            &format!("{name} energies"),
            &[
                payload::kinetic_energy(arm, &p, &q, &qd),
                payload::potential_energy(arm, &p, &q),
            ],
            &[
                merged.kinetic_energy(&qv, &qdv),
                merged.potential_energy(&qv),
            ],
        );
        let (mass, centre) = payload::center_of_mass(arm, &p, &q);
        let (want_mass, want_centre) = merged.center_of_mass(&qv);
        close(&format!("{name} mass"), &[mass], &[want_mass]);
        close(
            &format!("{name} centre of mass"),
            centre.coords.as_slice(),
            want_centre.coords.as_slice(),
        );
        close(
            &format!("{name} J_c"),
            payload::center_of_mass_jacobian(arm, &p, &q).as_slice(),
            merged.center_of_mass_jacobian(&qv).as_slice(),
        );
        // No payload is the arm itself.
        let none = payload::inverse_dynamics(arm, &Payload::NONE, &q, &qd, &qdd);
        close(
            &format!("{name} none"),
            none.as_slice(),
            arm.inverse_dynamics(&q, &qd, &qdd).as_slice(),
        );
    }
}

/// A runtime robot seen with a fixed number of joints (the `Arm` of `dhgen::Robot` is
/// dynamically sized; this checks it through the same generic functions).
fn check_runtime(name: &str, robot: &Robot) {
    let p = box_payload();
    let merged = with_payload_in_description(robot.model(), &p);
    let n = robot.dof();
    for s in 0..10 {
        let t = s as f64;
        let q = DVector::from_fn(n, |i, _| (0.7 * t + 1.3 * i as f64).sin());
        let qd = DVector::from_fn(n, |i, _| (0.3 * t - 0.9 * i as f64).cos());
        let qdd = DVector::from_fn(n, |i, _| (1.1 * t + 0.5 * i as f64).sin() * 2.0);
        let tau = payload::inverse_dynamics(robot, &p, &q, &qd, &qdd);
        close(
            name,
            tau.as_slice(),
            merged.inverse_dynamics(&q, &qd, &qdd).as_slice(),
        );
        let d = payload::mass_matrix(robot, &p, &q);
        close(name, d.as_slice(), merged.mass_matrix(&q).as_slice());
        let acc = payload::forward_dynamics(robot, &p, &q, &qd, &tau).unwrap();
        close(name, acc.as_slice(), qdd.as_slice());
        let energies = [merged.kinetic_energy(&q, &qd), merged.potential_energy(&q)];
        close(
            name,
            &[
                payload::kinetic_energy(robot, &p, &q, &qd),
                payload::potential_energy(robot, &p, &q),
            ],
            &energies,
        );
        let (mass, centre) = payload::center_of_mass(robot, &p, &q);
        let (want_mass, want_centre) = merged.center_of_mass(&q);
        close(name, &[mass], &[want_mass]);
        close(
            name,
            centre.coords.as_slice(),
            want_centre.coords.as_slice(),
        );
        close(
            name,
            payload::center_of_mass_jacobian(robot, &p, &q).as_slice(),
            merged.center_of_mass_jacobian(&q).as_slice(),
        );
        // The robot holding it, built without the description's text.
        let holding = robot.with_payload(&p).expect("a robot with dynamics");
        close(
            name,
            holding.inverse_dynamics(&q, &qd, &qdd).as_slice(),
            tau.as_slice(),
        );
        close(
            name,
            &[
                holding.kinetic_energy(&q, &qd),
                holding.potential_energy(&q),
            ],
            &energies,
        );
        let (dq, dqd) = holding.inverse_dynamics_derivatives(&q, &qd, &qdd);
        let (want_q, want_qd) = merged.inverse_dynamics_derivatives(&q, &qd, &qdd);
        close(name, dq.as_slice(), want_q.as_slice());
        close(name, dqd.as_slice(), want_qd.as_slice());
    }
}

#[test]
fn generated_payload_equals_the_body_in_the_description() {
    let model = |f: &str| {
        RobotModel::from_toml_file(format!("{}/{f}", env!("CARGO_MANIFEST_DIR"))).unwrap()
    };
    check::<_, 6>(
        "puma560",
        &puma560::Robot,
        &model("robots/puma560.toml"),
        puma560::inverse_dynamics_with_payload,
    );
    check::<_, 7>(
        "panda",
        &panda::Robot,
        &model("robots/panda.toml"),
        panda::inverse_dynamics_with_payload,
    );
    check::<_, { odd::DOF }>(
        "odd",
        &odd::Robot,
        &model("tests/fixtures/odd.toml"),
        odd::inverse_dynamics_with_payload,
    );
}

/// Generated ∂τ/∂q and ∂τ/∂q̇ with a payload against the runtime's analytic derivatives of the
/// description holding the same body (to 1e-12) and against central differences of the
/// generated τ with the payload (to 1e-6); with no payload, the plain derivatives. The PUMA
/// 560's last link is symmetric about its axis, so its plain derivations drop joint 6: the
/// payload must bring it back. Forward dynamics' derivatives with the payload, at the τ of
/// that state, against the runtime's of the same description (to 1e-14 of D's condition
/// number, and at least 1e-12: D⁻¹ amplifies the rounding of D by it).
#[test]
fn generated_payload_derivatives_equal_the_body_in_the_description() {
    macro_rules! check_derivatives {
        ($m:ident, $file:expr) => {{
            use crate::catalogue::$m as m;
            const N: usize = m::DOF;
            let name = stringify!($m);
            let model = RobotModel::from_toml_file(concat!(env!("CARGO_MANIFEST_DIR"), "/", $file))
                .unwrap();
            let p = box_payload();
            let merged = with_payload_in_description(&model, &p);
            let (params, none) = (p.parameters(), Payload::NONE.parameters());
            let tau = |q: &[f64; N], qd: &[f64; N], qdd: &[f64; N]| {
                m::inverse_dynamics_with_payload(q, qd, qdd, &params)
            };
            for s in 0..6 {
                let t = s as f64;
                let q: [f64; N] = std::array::from_fn(|i| (0.7 * t + 1.3 * i as f64).sin());
                let qd: [f64; N] = std::array::from_fn(|i| (0.3 * t - 0.9 * i as f64).cos());
                let qdd: [f64; N] = std::array::from_fn(|i| (1.1 * t + 0.5 * i as f64).sin() * 2.0);
                let (dq, dqd) =
                    m::inverse_dynamics_derivatives_with_payload(&q, &qd, &qdd, &params);
                let (want_q, want_qd) = merged.inverse_dynamics_derivatives(&q, &qd, &qdd);
                close(&format!("{name} ∂τ/∂q"), dq.as_slice(), want_q.as_slice());
                close(&format!("{name} ∂τ/∂q̇"), dqd.as_slice(), want_qd.as_slice());
                let h = 1e-6;
                for j in 0..N {
                    let step = |x: &[f64; N], by: f64| {
                        let mut y = *x;
                        y[j] += by;
                        y
                    };
                    let along_q =
                        (tau(&step(&q, h), &qd, &qdd) - tau(&step(&q, -h), &qd, &qdd)) / (2.0 * h);
                    let along_qd =
                        (tau(&q, &step(&qd, h), &qdd) - tau(&q, &step(&qd, -h), &qdd)) / (2.0 * h);
                    let what = format!("{name} column {j} by differences");
                    close_to(&what, dq.column(j).as_slice(), along_q.as_slice(), 1e-6);
                    close_to(&what, dqd.column(j).as_slice(), along_qd.as_slice(), 1e-6);
                }
                let torque = tau(&q, &qd, &qdd);
                let (fq, fqd, inverse) =
                    m::forward_dynamics_derivatives_with_payload(&q, &qd, &torque, &params)
                        .expect("D is regular");
                let (want_fq, want_fqd, want_inverse) = merged
                    .forward_dynamics_derivatives(&q, &qd, torque.as_slice())
                    .expect("D is regular");
                let eigen = merged.mass_matrix(&q).symmetric_eigenvalues();
                let tol = (1e-14 * eigen.max() / eigen.min()).max(1e-12);
                close_to(
                    &format!("{name} ∂q̈/∂q"),
                    fq.as_slice(),
                    want_fq.as_slice(),
                    tol,
                );
                close_to(
                    &format!("{name} ∂q̈/∂q̇"),
                    fqd.as_slice(),
                    want_fqd.as_slice(),
                    tol,
                );
                close_to(
                    &format!("{name} D⁻¹"),
                    inverse.as_slice(),
                    want_inverse.as_slice(),
                    tol,
                );
                let (dq0, dqd0) =
                    m::inverse_dynamics_derivatives_with_payload(&q, &qd, &qdd, &none);
                let (plain_q, plain_qd) = m::inverse_dynamics_derivatives(&q, &qd, &qdd);
                close(
                    &format!("{name} no payload"),
                    dq0.as_slice(),
                    plain_q.as_slice(),
                );
                close(
                    &format!("{name} no payload"),
                    dqd0.as_slice(),
                    plain_qd.as_slice(),
                );
            }
        }};
    }
    check_derivatives!(puma560_derivatives, "robots/puma560.toml");
    check_derivatives!(panda_derivatives, "robots/panda.toml");
    check_derivatives!(odd_derivatives, "tests/fixtures/odd.toml");
    check_derivatives!(scara_derivatives, "robots/scara.toml");
    check_derivatives!(stanford_derivatives, "robots/stanford.toml");
}

#[test]
fn runtime_payload_equals_the_body_in_the_description() {
    for f in [
        "robots/stanford.toml",
        "robots/scara.toml",
        "tests/fixtures/tilted_modified.toml",
    ] {
        let robot = Robot::from_toml_file(format!("{}/{f}", env!("CARGO_MANIFEST_DIR"))).unwrap();
        check_runtime(f, &robot);
    }
    let urdf = dhgen::model::urdf::read_file(
        concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/urdf/ur5.urdf"),
        &Default::default(),
    )
    .unwrap();
    check_runtime("ur5.urdf", &Robot::from_model(urdf.model));
    // Without mass properties there is nothing to add the payload to.
    let kinematic = Robot::from_toml_file(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/robots/cylindrical.toml"
    ))
    .unwrap();
    assert!(kinematic.with_payload(&box_payload()).is_none());
}

#[test]
fn bad_payloads_are_refused_at_construction() {
    let i = [[0.01, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.01]];
    let e = Payload::new(-1.0, [0.0; 3], i).unwrap_err().to_string();
    assert!(e.contains("negative"), "{e}");
    let e = Payload::new(f64::NAN, [0.0; 3], i).unwrap_err().to_string();
    assert!(e.contains("finite"), "{e}");
    let e = Payload::new(1.0, [0.0, f64::INFINITY, 0.0], i)
        .unwrap_err()
        .to_string();
    assert!(e.contains("not finite"), "{e}");
    let not_psd = [[0.01, 0.0, 0.0], [0.0, -0.01, 0.0], [0.0, 0.0, 0.01]];
    let e = Payload::new(1.0, [0.0; 3], not_psd)
        .unwrap_err()
        .to_string();
    assert!(e.contains("positive semi-definite"), "{e}");
    let thin = [[0.01, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.05]];
    let e = Payload::new(1.0, [0.0; 3], thin).unwrap_err().to_string();
    assert!(e.contains("triangle"), "{e}");
    let skew = [[0.01, 0.001, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.01]];
    let e = Payload::new(1.0, [0.0; 3], skew).unwrap_err().to_string();
    assert!(e.contains("symmetric"), "{e}");
}

/// A centre of mass beyond the description format's length range (10³ m, a link's `com`) is
/// refused: 1e300 m made the parameters m·c·c infinite and NaN. At the edge of every range
/// (10⁶ kg at 10³ m, inertia entries of 10⁹ kg·m²) the parameters are finite.
#[test]
fn payload_centre_of_mass_is_held_to_the_length_range() {
    let i = [[0.01, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0, 0.0, 0.01]];
    for com in [[1e300, 0.0, 0.0], [0.0, -1e200, 0.0], [0.0, 0.0, 1000.5]] {
        let e = Payload::new(1.0, com, i).unwrap_err().to_string();
        assert!(
            e.contains("outside the range of any robot") && e.contains("at most 1e3 m"),
            "{e}"
        );
    }
    let e = Payload::new(1e6, [0.0, 1e303, 0.0], i)
        .unwrap_err()
        .to_string();
    assert!(e.contains("y: length 1e303 m"), "{e}");
    let big = [[1e9, 0.0, 0.0], [0.0, 1e9, 0.0], [0.0, 0.0, 1e9]];
    let p = Payload::new(1e6, [1e3, -1e3, 1e3], big).unwrap();
    assert!(
        p.parameters().iter().all(|x| x.is_finite()),
        "{:?}",
        p.parameters()
    );
    let p = Payload::new(1.0, [-1e3, 0.0, 0.0], i).unwrap();
    assert_eq!(p.parameters()[1], -1e3);
}

/// The generated D, C, g, bias and q̈ with the payload's parameters as inputs equal the same
/// body written into the description.
macro_rules! generated_terms {
    ($test:ident, $m:ident, $file:literal) => {
        #[test]
        fn $test() {
            const N: usize = $m::DOF;
            let model = RobotModel::from_toml_file(concat!(env!("CARGO_MANIFEST_DIR"), "/", $file))
                .unwrap();
            let p = box_payload();
            let pp = p.parameters();
            let merged = with_payload_in_description(&model, &p);
            for s in 0..10 {
                let t = s as f64;
                let q: [f64; N] = core::array::from_fn(|i| (0.7 * t + 1.3 * i as f64).sin());
                let qd: [f64; N] = core::array::from_fn(|i| (0.3 * t - 0.9 * i as f64).cos());
                let (qv, qdv) = (DVector::from_row_slice(&q), DVector::from_row_slice(&qd));
                let d = $m::mass_matrix_with_payload(&q, &pp);
                close("D", d.as_slice(), merged.mass_matrix(&qv).as_slice());
                let g = $m::gravity_with_payload(&q, &pp);
                close("g", g.as_slice(), merged.gravity(&qv).as_slice());
                let b = $m::bias_with_payload(&q, &qd, &pp);
                close("bias", b.as_slice(), merged.bias(&qv, &qdv).as_slice());
                let c = $m::coriolis_with_payload(&q, &qd, &pp);
                close("C", c.as_slice(), merged.coriolis(&qv, &qdv).as_slice());
                close(
                    "energies",
                    &[
                        $m::kinetic_energy_with_payload(&q, &qd, &pp),
                        $m::potential_energy_with_payload(&q, &pp),
                    ],
                    &[
                        merged.kinetic_energy(&qv, &qdv),
                        merged.potential_energy(&qv),
                    ],
                );
                let tau: [f64; N] = core::array::from_fn(|i| 5.0 * (0.4 * t + i as f64).cos());
                let qdd = $m::forward_dynamics_with_payload(&q, &qd, &tau, &pp).unwrap();
                let want = merged
                    .forward_dynamics(&qv, &qdv, &DVector::from_row_slice(&tau))
                    .unwrap();
                // q̈ solves the merged arm's equations of motion to rounding: the residual
                // is rounding times the size of the terms summed, |D| |q̈| + |h| (which is
                // what a backward-stable solve bounds, and can be well above |τ|), and so q̈
                // agrees with the merged arm's to rounding times D's condition number (above
                // 3·10⁴ for the 17-joint snake here, 10² to 10⁴ for the Panda and PUMA 560).
                let qddv = DVector::from_row_slice(qdd.as_slice());
                let residual = merged.inverse_dynamics(&qv, &qdv, &qddv);
                let dm = merged.mass_matrix(&qv);
                let terms = dm.abs() * qddv.abs() + merged.bias(&qv, &qdv).abs();
                let size = terms.iter().fold(1.0f64, |m, x| m.max(*x));
                for (r, t) in residual.iter().zip(&tau) {
                    assert!(
                        (r - t).abs() <= 1e-12 * size,
                        "D q̈ + h: {residual:?} vs {tau:?} (terms up to {size:e})"
                    );
                }
                let eigen = dm.symmetric_eigenvalues();
                let condition = eigen.max() / eigen.min();
                close_to(
                    "q̈",
                    qdd.as_slice(),
                    want.as_slice(),
                    1e-12 * condition.max(1.0),
                );
            }
        }
    };
}

generated_terms!(
    puma560_generated_terms_with_payload,
    puma560,
    "robots/puma560.toml"
);
generated_terms!(
    panda_generated_terms_with_payload,
    panda,
    "robots/panda.toml"
);
generated_terms!(
    odd_generated_terms_with_payload,
    odd,
    "tests/fixtures/odd.toml"
);
// Past 12 joints: D and C with the payload from the runtime path's loops.
generated_terms!(
    snake17_generated_terms_with_payload,
    snake17,
    "tests/fixtures/snake17.toml"
);
