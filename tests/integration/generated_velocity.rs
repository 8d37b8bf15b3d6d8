//! Generated velocity-kinematics extras: J̇q̇ (also in tool axes), the kinematic Hessian and manipulability
//! gradient, the decoupled singularity determinants and
//! the per-robot closed-form inverse kinematics, against the generic implementations and
//! finite differences.

use crate::catalogue::{cylindrical, odd, panda, puma560, scara, stanford};
use dhgen::ik::DecoupledIk;
use dhgen::nalgebra::{SVector, Vector3};
use dhgen::velocity::{
    Axes, decoupled_determinants, jacobian_dot, jdot_qdot_from_jacobian, kinematic_hessian,
    manipulability, manipulability_gradient, tool_velocity_partial,
};
use proptest::prelude::*;

macro_rules! jdot_matches {
    ($test:ident, $m:ident) => {
        proptest! {
            #![proptest_config(ProptestConfig::with_cases(64))]
            #[test]
            fn $test(
                q in proptest::array::uniform::<_, { $m::DOF }>(-3.0f64..3.0),
                qd in proptest::array::uniform::<_, { $m::DOF }>(-2.0f64..2.0),
            ) {
                let generated = $m::jdot_qdot(&q, &qd);
                let generic = jdot_qdot_from_jacobian(
                    &$m::Robot,
                    &dhgen::Arm::jacobian(&$m::Robot, &SVector::from(q)),
                    &SVector::from(qd),
                );
                // Finite differences of J along q̇, as a check independent of both.
                let h = 1e-6;
                let qp: [f64; $m::DOF] = core::array::from_fn(|i| q[i] + h * qd[i]);
                let qm: [f64; $m::DOF] = core::array::from_fn(|i| q[i] - h * qd[i]);
                let fd = ($m::jacobian(&qp) - $m::jacobian(&qm)) / (2.0 * h) * SVector::from(qd);
                for r in 0..6 {
                    prop_assert!((generated[r] - generic[r]).abs() <= 1e-12 * (1.0 + generic.amax()),
                        "row {r}: generated {}, generic {}", generated[r], generic[r]);
                    prop_assert!((generated[r] - fd[r]).abs() <= 1e-6 * (1.0 + fd.amax()),
                        "row {r}: generated {}, finite differences {}", generated[r], fd[r]);
                }
                // In tool axes: J̇_b q̇ against the differences of the body Jacobian along q̇.
                let body = dhgen::Arm::body_jdot_qdot(&$m::Robot, &SVector::from(q), &SVector::from(qd));
                let fd = ($m::body_jacobian(&qp) - $m::body_jacobian(&qm)) / (2.0 * h) * SVector::from(qd);
                prop_assert!((body - fd).amax() <= 1e-6 * (1.0 + fd.amax()),
                    "J̇_b q̇ {body} against finite differences {fd}");
            }
        }
    };
}

jdot_matches!(puma560_jdot_qdot, puma560);
jdot_matches!(stanford_jdot_qdot, stanford);
jdot_matches!(panda_jdot_qdot, panda);
jdot_matches!(scara_jdot_qdot, scara);
jdot_matches!(odd_jdot_qdot, odd);

/// The kinematic Hessian and what is built on it, on generated arms (prismatic joints:
/// Stanford, SCARA, the odd fixture's modified table): each ∂J/∂q_k against central
/// differences of the generated Jacobian; the position rows symmetric (Schwarz); contracted with
/// q̇, J̇ of `jacobian_dot` (derived from the axes' motion, not from the Hessian) and the
/// generated `jdot_qdot`; the manipulability gradient against differences of manipulability.
macro_rules! hessian_matches {
    ($test:ident, $m:ident) => {
        proptest! {
            #![proptest_config(ProptestConfig::with_cases(32))]
            #[test]
            fn $test(
                q in proptest::array::uniform::<_, { $m::DOF }>(-3.0f64..3.0),
                qd in proptest::array::uniform::<_, { $m::DOF }>(-2.0f64..2.0),
            ) {
                const N: usize = $m::DOF;
                let (q, qd) = (SVector::<f64, N>::from(q), SVector::<f64, N>::from(qd));
                let j = $m::jacobian(&q);
                let slices: Vec<_> = kinematic_hessian(&j).collect();
                prop_assert_eq!(slices.len(), N);
                let h = 1e-6;
                for (k, hk) in slices.iter().enumerate() {
                    let e = SVector::<f64, N>::from_fn(|i, _| if i == k { h } else { 0.0 });
                    let fd = ($m::jacobian(&(q + e)) - $m::jacobian(&(q - e))) / (2.0 * h);
                    prop_assert!((hk - fd).amax() <= 1e-7 * (1.0 + fd.amax()),
                        "∂J/∂q_{k} off finite differences by {:e}", (hk - fd).amax());
                    for i in 0..N {
                        for r in 0..3 {
                            prop_assert!((hk[(r, i)] - slices[i][(r, k)]).abs() <= 1e-12,
                                "∂v_{i}/∂q_{k} ≠ ∂v_{k}/∂q_{i} in row {r}");
                        }
                    }
                }
                let jdot = slices.iter().zip(qd.iter()).map(|(hk, &v)| hk * v)
                    .fold(j * 0.0, |a, b| a + b);
                let reference = jacobian_dot(&$m::Robot, &q, &qd);
                prop_assert!((jdot - reference).amax() <= 1e-12 * (1.0 + reference.amax()));
                let partial = tool_velocity_partial(&j, &qd);
                let bias = $m::jdot_qdot(&q, &qd);
                prop_assert!((partial * qd - bias).amax() <= 1e-12 * (1.0 + bias.amax()));
                for axes in [Axes::All, Axes::Translation, Axes::Rotation] {
                    let Some((m, grad)) = manipulability_gradient(&j, axes) else { continue };
                    if axes == Axes::All {
                        prop_assert_eq!(m, manipulability(&j));
                    }
                    let m_at = |q: SVector<f64, N>| {
                        manipulability_gradient(&$m::jacobian(&q), axes).map_or(0.0, |(m, _)| m)
                    };
                    for k in 0..N {
                        let e = SVector::<f64, N>::from_fn(|i, _| if i == k { h } else { 0.0 });
                        let fd = (m_at(q + e) - m_at(q - e)) / (2.0 * h);
                        prop_assert!((grad[k] - fd).abs() <= 1e-6 * (1.0 + grad.amax()),
                            "{axes:?}: ∂m/∂q_{k} {} against finite differences {fd}", grad[k]);
                    }
                }
            }
        }
    };
}

hessian_matches!(puma560_kinematic_hessian, puma560);
hessian_matches!(stanford_kinematic_hessian, stanford);
hessian_matches!(panda_kinematic_hessian, panda);
hessian_matches!(scara_kinematic_hessian, scara);
hessian_matches!(odd_kinematic_hessian, odd);
hessian_matches!(cylindrical_kinematic_hessian, cylindrical);

/// Pinocchio 4.1.0's tool-frame kinematics on the PUMA 560 and the Panda
/// (tests/data/pinocchio_kinematics.json, made by scripts/pinocchio_kinematics.py): the body
/// Jacobian (`LOCAL` frame Jacobian), ∂(J q̇)/∂q and the kinematic Hessian (assembled by the
/// script from `getFrameVelocityDerivatives`), and J̇_b q̇ (`getFrameJacobianTimeVariation(LOCAL)`
/// times q̇), generated and runtime, to 1e-12.
#[test]
fn tool_kinematics_match_pinocchio() {
    use crate::support::runtime;
    use crate::urdf::{matrix, vector};
    use dhgen::Arm;
    use dhgen::nalgebra::{DMatrix, DVector, Dim, OMatrix, U6};
    fn dynamic<C: Dim>(m: &OMatrix<f64, U6, C>) -> DMatrix<f64>
    where
        dhgen::nalgebra::DefaultAllocator: dhgen::nalgebra::allocator::Allocator<U6, C>,
    {
        DMatrix::from_fn(6, m.ncols(), |r, c| m[(r, c)])
    }
    /// Each of `ours` (body Jacobian, ∂(J q̇)/∂q, then ∂J/∂q_k, then J̇_b q̇ as a column)
    /// against the sample.
    fn compare(what: &str, ours: &[DMatrix<f64>], s: &serde_json::Value) {
        let mut theirs = vec![matrix(&s["Jb"]), matrix(&s["dv_dq"])];
        theirs.extend(s["H0"].as_array().unwrap().iter().map(matrix));
        theirs.push(DMatrix::from_vec(6, 1, vector(&s["Jb_dot_qd"])));
        assert_eq!(ours.len(), theirs.len(), "{what}");
        for (i, (a, b)) in ours.iter().zip(&theirs).enumerate() {
            let e = (a - b).amax() / b.amax().max(1.0);
            assert!(e < 1e-12, "{what}: matrix {i} off Pinocchio by {e:e}");
        }
    }
    let path = format!(
        "{}/tests/data/pinocchio_kinematics.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let data: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let mut compared = 0;
    for name in ["puma560", "panda"] {
        let robot = runtime(name);
        let samples = data["robots"][name].as_array().unwrap();
        assert_eq!(samples.len(), 10);
        for s in samples {
            let (q, qd) = (
                DVector::from_vec(vector(&s["q"])),
                DVector::from_vec(vector(&s["qd"])),
            );
            let j = robot.jacobian(q.as_slice());
            let mut ours = vec![
                dynamic(&robot.body_jacobian(&q)),
                dynamic(&tool_velocity_partial(&j, &qd)),
            ];
            ours.extend(kinematic_hessian(&j).map(|h| dynamic(&h)));
            ours.push(DMatrix::from_column_slice(
                6,
                1,
                robot.body_jdot_qdot(&q, &qd).as_slice(),
            ));
            compare(&format!("{name}, runtime"), &ours, s);
            macro_rules! generated {
                ($m:ident) => {{
                    const N: usize = $m::DOF;
                    let q = SVector::<f64, N>::from_column_slice(q.as_slice());
                    let qd = SVector::<f64, N>::from_column_slice(qd.as_slice());
                    let j = $m::jacobian(&q);
                    let mut ours = vec![
                        dynamic(&$m::body_jacobian(&q)),
                        dynamic(&tool_velocity_partial(&j, &qd)),
                    ];
                    ours.extend(kinematic_hessian(&j).map(|h| dynamic(&h)));
                    let body = $m::Robot.body_jdot_qdot(&q, &qd);
                    ours.push(DMatrix::from_column_slice(6, 1, body.as_slice()));
                    compare(&format!("{name}, generated"), &ours, s);
                }};
            }
            if name == "puma560" {
                generated!(puma560);
            } else {
                generated!(panda);
            }
            compared += 1;
        }
    }
    assert_eq!(compared, 20);
}

macro_rules! determinants_match {
    ($test:ident, $m:ident) => {
        proptest! {
            #![proptest_config(ProptestConfig::with_cases(64))]
            #[test]
            fn $test(q in proptest::array::uniform::<_, 6>(-3.0f64..3.0)) {
                let centre: Vector3<f64> = DecoupledIk::from_chain($m::CHAIN).unwrap().wrist_centre_in_tool().expect("a spherical wrist");
                let d = decoupled_determinants(&$m::Robot, &SVector::from(q), &centre).unwrap();
                let (arm, wrist) = ($m::det_j11(&q), $m::det_j22(&q));
                prop_assert!((arm - d.arm).abs() <= 1e-12 * (1.0 + d.arm.abs()), "det J11 {arm} vs {}", d.arm);
                prop_assert!((wrist - d.wrist).abs() <= 1e-12, "det J22 {wrist} vs {}", d.wrist);
                // det J = det J11 · det J22, whatever the reference point.
                let full = $m::jacobian(&q).determinant();
                prop_assert!((arm * wrist - full).abs() <= 1e-10 * (1.0 + full.abs()), "{} vs {full}", arm * wrist);
            }
        }
    };
}

determinants_match!(puma560_decoupled_determinants, puma560);
determinants_match!(stanford_decoupled_determinants, stanford);
determinants_match!(cylindrical_decoupled_determinants, cylindrical);

#[test]
fn spherical_wrists_are_detected() {
    // Checked while compiling: a wrong detection fails the build of this test.
    const {
        assert!(
            puma560::SPHERICAL_WRIST && stanford::SPHERICAL_WRIST && cylindrical::SPHERICAL_WRIST
        );
        assert!(!panda::SPHERICAL_WRIST && !scara::SPHERICAL_WRIST);
    }
}

#[test]
fn puma_wrist_singularity_is_sin_theta5() {
    // θ5 = 0 aligns z3 and z5: det J22 vanishes; elsewhere it is ±sin θ5.
    for t5 in [-2.0f64, -0.5, 0.0, 0.3, 1.4] {
        let q = [0.2, -0.3, 0.4, 0.5, t5, 0.7];
        assert!((puma560::det_j22(&q).abs() - f64::sin(t5).abs()).abs() < 1e-14);
    }
}

#[test]
fn generated_ik_recovers_the_configuration() {
    let q = [0.3, -0.4, 0.2, 0.5, -0.7, 1.1];
    let solutions = puma560::ik(&puma560::fk(&q));
    assert_eq!(solutions.len(), 8);
    assert!(
        solutions
            .iter()
            .any(|s| (s - SVector::from(q)).norm() < 1e-9)
    );
    // Unreachable: empty, not NaN.
    let far = dhgen::nalgebra::Isometry3::translation(5.0, 0.0, 0.0);
    assert!(puma560::ik(&far).is_empty());
}
