//! Velocity kinematics: the analytic Jacobian against finite differences of Euler angles,
//! J̇ q̇ against finite differences, the SVD and pseudo-inverse identities, singularity
//! detection at known singular configurations, the decoupled determinants, inverse velocity
//! and acceleration, the Jacobians of points on every link, and the body Jacobian against
//! finite differences of the pose in tool axes (and its independence of the base).

use crate::catalogue::{cylindrical, elbow, odd, panda, planar_elbow as planar, puma560, stanford};
use crate::support::runtime;
use dhgen::ik::DecoupledIk;
use dhgen::nalgebra::{
    DMatrix, DVector, DefaultAllocator, Matrix3, OMatrix, OVector, Rotation3, SVector, U6, Vector3,
    Vector6,
};
use dhgen::rotation::{EulerZyz, wrap_angle};
use dhgen::velocity::{
    Damping, JacobianSvd, analytic_jacobian, condition_number, decoupled_determinants,
    euler_rate_matrix, inverse_acceleration, inverse_velocity, is_singular, jacobian_dot,
    manipulability, point_jacobian,
};
use dhgen::{Arm, ArmAllocator};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::f64::consts::FRAC_PI_2;

fn random_q<A: Arm>(arm: &A, rng: &mut StdRng) -> OVector<f64, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    OVector::<f64, A::Dof>::from_fn_generic(arm.dim(), dhgen::nalgebra::U1, |j, _| {
        let [lo, hi] = arm.limits(j).unwrap_or([-2.5, 2.5]);
        rng.random_range(lo..=hi)
    })
}

fn random_qd<A: Arm>(arm: &A, rng: &mut StdRng) -> OVector<f64, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    OVector::<f64, A::Dof>::from_fn_generic(arm.dim(), dhgen::nalgebra::U1, |_, _| {
        rng.random_range(-1.5..1.5)
    })
}

/// `J̇` by central differences of J along q̇, against the analytic one; and `J̇ q̇`
/// against the second difference of the tool position along the same line (q̈ = 0).
fn check_jacobian_dot<A: Arm>(arm: &A, name: &str, samples: usize)
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let mut rng = StdRng::seed_from_u64(17);
    let h = 1e-5;
    let mut worst: f64 = 0.0;
    for _ in 0..samples {
        let q = random_q(arm, &mut rng);
        let qd = random_qd(arm, &mut rng);
        let jd = jacobian_dot(arm, &q, &qd);
        let fd = (arm.jacobian(&(&q + &qd * h)) - arm.jacobian(&(&q - &qd * h))) / (2.0 * h);
        let err = (&jd - &fd).abs().max();
        worst = worst.max(err);
        assert!(
            err < 1e-8,
            "{name}: J̇ differs from finite differences by {err:e}"
        );
        let bias = dhgen::Arm::jdot_qdot(arm, &q, &qd);
        assert!((bias - &jd * &qd).abs().max() < 1e-12, "{name}");
        // Linear part: the tool origin's acceleration along the line q + t q̇.
        let hp = 1e-4;
        let p = |t: f64| arm.fk(&(&q + &qd * t)).translation.vector;
        let acc = (p(hp) - p(0.0) * 2.0 + p(-hp)) / (hp * hp);
        assert!(
            (acc - bias.fixed_rows::<3>(0)).norm() < 1e-5,
            "{name}: {acc:?} vs {bias:?}"
        );
    }
    eprintln!("{name}: J̇ vs central differences, worst entry error {worst:.1e}");
}

#[test]
fn jacobian_dot_matches_finite_differences() {
    check_jacobian_dot(&puma560::Robot, "puma560", 200);
    check_jacobian_dot(&panda::Robot, "panda", 200);
    check_jacobian_dot(&stanford::Robot, "stanford", 200);
    check_jacobian_dot(&cylindrical::Robot, "cylindrical", 200);
    check_jacobian_dot(&odd::Robot, "modified DH, prismatic, base and tool", 200);
    check_jacobian_dot(&runtime("puma560"), "puma560 (runtime)", 50);
    check_jacobian_dot(&runtime("ur5"), "ur5 (runtime)", 50);
}

/// The Jacobian of a point fixed in each link's frame (and one fixed to the base) against
/// central differences of that point and of the link's orientation; the columns of the joints
/// after the link are exactly zero, and at the last link and the tool origin it is the tool's
/// Jacobian.
fn check_point_jacobian<A: Arm>(arm: &A, name: &str)
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let mut rng = StdRng::seed_from_u64(23);
    let (n, h) = (arm.dof(), 1e-6);
    let local = dhgen::nalgebra::Point3::new(0.13, -0.07, 0.21);
    let frames = |q: &OVector<f64, A::Dof>| {
        let mut out = vec![dhgen::nalgebra::Isometry3::identity(); n];
        arm.frames_into(q, &mut out);
        out
    };
    // Link k's frame (k = 1..n), the base's for k = 0 (fixed).
    let frame = |q: &OVector<f64, A::Dof>, k: usize| {
        if k == 0 {
            dhgen::nalgebra::Isometry3::translation(0.3, -0.2, 0.1)
        } else {
            frames(q)[k - 1]
        }
    };
    let mut worst: f64 = 0.0;
    for _ in 0..20 {
        let q = random_q(arm, &mut rng);
        for k in 0..=n {
            let j = point_jacobian(arm, &q, k, &(frame(&q, k) * local)).unwrap();
            for c in 0..n {
                let mut dq = OVector::<f64, A::Dof>::zeros_generic(arm.dim(), dhgen::nalgebra::U1);
                dq[c] = h;
                let (fp, fm) = (frame(&(&q + &dq), k), frame(&(&q - &dq), k));
                let v = ((fp * local) - (fm * local)) / (2.0 * h);
                let w = (fp.rotation * fm.rotation.inverse()).scaled_axis() / (2.0 * h);
                let column = j.column(c);
                if c >= k {
                    assert!(
                        column.iter().all(|&x| x == 0.0),
                        "{name}: link {k} column {c}"
                    );
                }
                let err = (column.fixed_rows::<3>(0) - v)
                    .norm()
                    .max((column.fixed_rows::<3>(3) - w).norm());
                worst = worst.max(err);
                assert!(err < 1e-8, "{name}: link {k}, column {c}: {err:e}");
            }
        }
        let tool = arm.fk(&q) * dhgen::nalgebra::Point3::origin();
        let at_tool = point_jacobian(arm, &q, n, &tool).unwrap();
        assert!((at_tool - arm.jacobian(&q)).abs().max() < 1e-14, "{name}");
        assert!(point_jacobian(arm, &q, n + 1, &tool).is_none());
    }
    eprintln!("{name}: point Jacobians vs central differences, worst column error {worst:.1e}");
}

#[test]
fn point_jacobians_match_finite_differences_on_every_link() {
    check_point_jacobian(&puma560::Robot, "puma560");
    check_point_jacobian(&panda::Robot, "panda");
    check_point_jacobian(&stanford::Robot, "stanford");
    check_point_jacobian(&odd::Robot, "modified DH, prismatic, base and tool");
    check_point_jacobian(&runtime("panda"), "panda (runtime)");
    check_point_jacobian(&runtime("ur5"), "ur5 (runtime)");
}

/// The body Jacobian against central differences of the pose along `q̇`:
/// `J_b q̇ = [Rᵀ ṗ; (Rᵀ Ṙ)^∨]`, both resolved in the tool frame.
fn check_body_jacobian<A: Arm>(arm: &A, name: &str)
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let mut rng = StdRng::seed_from_u64(29);
    let h = 1e-6;
    for _ in 0..20 {
        let q = random_q(arm, &mut rng);
        let qd = random_qd(arm, &mut rng);
        let (plus, minus, at) = (arm.fk(&(&q + &qd * h)), arm.fk(&(&q - &qd * h)), arm.fk(&q));
        let rt = at.rotation.to_rotation_matrix().into_inner().transpose();
        let p_dot = (plus.translation.vector - minus.translation.vector) / (2.0 * h);
        let r_dot = (plus.rotation.to_rotation_matrix().into_inner()
            - minus.rotation.to_rotation_matrix().into_inner())
            / (2.0 * h);
        let w = rt * r_dot; // skew-symmetric: [ω]× in tool axes
        let v = rt * p_dot;
        let expected = Vector6::new(v.x, v.y, v.z, w[(2, 1)], w[(0, 2)], w[(1, 0)]);
        let got = arm.body_jacobian(&q) * &qd;
        let scale = expected.norm().max(1.0);
        assert!(
            (got - expected).norm() < 1e-7 * scale,
            "{name}: body Jacobian off finite differences by {:e}",
            (got - expected).norm()
        );
        // Its norm per column is the world Jacobian's: only the axes differ.
        let j = arm.jacobian(&q);
        let jb = arm.body_jacobian(&q);
        for c in 0..arm.dof() {
            let (a, b) = (j.column(c), jb.column(c));
            assert!(
                (a.fixed_rows::<3>(0).norm() - b.fixed_rows::<3>(0).norm()).abs() < 1e-12
                    && (a.fixed_rows::<3>(3).norm() - b.fixed_rows::<3>(3).norm()).abs() < 1e-12,
                "{name}: column {c}"
            );
        }
    }
}

#[test]
fn body_jacobian_matches_finite_differences_in_tool_axes() {
    // Generated arms (a prismatic joint in the cylindrical and Stanford arms; odd: modified DH,
    // base and tool at inexact angles) and the runtime path.
    check_body_jacobian(&puma560::Robot, "puma560");
    check_body_jacobian(&panda::Robot, "panda");
    check_body_jacobian(&stanford::Robot, "stanford");
    check_body_jacobian(&cylindrical::Robot, "cylindrical");
    check_body_jacobian(&odd::Robot, "odd");
    check_body_jacobian(&runtime("panda"), "panda (runtime)");
    check_body_jacobian(&crate::support::fixture("odd"), "odd (runtime)");
}

#[test]
fn runtime_body_jdot_qdot_matches_finite_differences_and_the_trait_formula() {
    // `Robot::body_jdot_qdot` walks the chain once; checked against central differences of
    // `J_b q̇` along q(t) = q + t q̇, and against the trait's default formula from `fk`,
    // `J q̇` and `J̇ q̇` computed separately. Fixtures with prismatic joints (gantry, odd),
    // modified DH, base and tool (odd), and the Panda.
    let mut rng = StdRng::seed_from_u64(31);
    let h = 1e-5;
    for (name, arm) in [
        ("odd", crate::support::fixture("odd")),
        ("gantry", crate::support::fixture("gantry")),
        ("panda", runtime("panda")),
    ] {
        for _ in 0..20 {
            let (q, qd) = (random_q(&arm, &mut rng), random_qd(&arm, &mut rng));
            let got = arm.body_jdot_qdot(&q, &qd);
            let fd = (arm.body_jacobian(&(&q + &qd * h)) - arm.body_jacobian(&(&q - &qd * h)))
                * &qd
                / (2.0 * h);
            let scale = fd.norm().max(1.0);
            assert!(
                (got - fd).norm() < 1e-7 * scale,
                "{name}: J̇_b q̇ off central differences by {:e}",
                (got - fd).norm()
            );
            let formula = dhgen::velocity::body_jdot_qdot_from(
                &arm.fk(&q),
                &(arm.jacobian(&q) * &qd),
                &Arm::jdot_qdot(&arm, &q, &qd),
            );
            assert!(
                (got - formula).norm() < 1e-12 * scale,
                "{name}: one walk and the trait's formula differ by {:e}",
                (got - formula).norm()
            );
            let jb = dhgen::velocity::body_jacobian_from_jacobian(&arm.fk(&q), arm.jacobian(&q));
            assert!((arm.body_jacobian(&q) - jb).amax() < 1e-13, "{name}: J_b");
        }
    }
}

#[test]
fn body_jacobian_does_not_depend_on_the_base() {
    // The odd fixture with the base of another fixture: world Jacobians differ, body
    // Jacobians agree.
    let arm = crate::support::fixture("odd");
    let mut model = arm.model().clone();
    model.base = crate::support::fixture("puma_offsets").model().base;
    assert_ne!(model.base, arm.model().base);
    let moved = dhgen::Robot::from_model(model);
    let mut rng = StdRng::seed_from_u64(31);
    for _ in 0..20 {
        let q = random_q(&arm, &mut rng);
        let (a, b) = (arm.body_jacobian(&q), moved.body_jacobian(&q));
        assert!((&a - &b).abs().max() < 1e-12, "{}", (&a - &b).abs().max());
        assert!((arm.jacobian(&q) - moved.jacobian(&q)).abs().max() > 1e-3);
        // Generated: the same.
        let sq = SVector::<f64, { odd::DOF }>::from_column_slice(q.as_slice());
        let g = odd::Robot.body_jacobian(&sq);
        assert!(
            (DMatrix::from_column_slice(6, odd::DOF, g.as_slice()) - &a)
                .abs()
                .max()
                < 1e-12
        );
    }
}

#[test]
fn euler_rate_matrix_maps_euler_rates_to_angular_velocity() {
    let mut rng = StdRng::seed_from_u64(3);
    for _ in 0..200 {
        let e = EulerZyz::new(
            rng.random_range(-3.0..3.0),
            rng.random_range(0.1..3.0),
            rng.random_range(-3.0..3.0),
        );
        let rate = Vector3::new(
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
            rng.random_range(-1.0..1.0),
        );
        let h = 1e-6;
        let at = |t: f64| {
            EulerZyz::new(e.phi + rate.x * t, e.theta + rate.y * t, e.psi + rate.z * t)
                .to_rotation()
        };
        // Ṙ Rᵀ = S(ω).
        let r_dot = (at(h).matrix() - at(-h).matrix()) / (2.0 * h);
        let s = r_dot * at(0.0).matrix().transpose();
        let omega = Vector3::new(s[(2, 1)], s[(0, 2)], s[(1, 0)]);
        assert!((euler_rate_matrix(&e) * rate - omega).norm() < 1e-8);
        assert!((euler_rate_matrix(&e).determinant() + e.theta.sin()).abs() < 1e-14);
    }
}

/// The angular rows of J_a against central differences of the ZYZ angles of fk(q).
fn check_analytic_jacobian<A: Arm>(arm: &A, name: &str)
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let mut rng = StdRng::seed_from_u64(23);
    let h = 1e-6;
    let mut checked = 0;
    while checked < 200 {
        let q = random_q(arm, &mut rng);
        let Some(dhgen::velocity::AnalyticJacobian {
            jacobian: ja,
            euler: e,
        }) = analytic_jacobian(arm, &q)
        else {
            continue;
        };
        if e.theta.sin() < 0.05 {
            continue; // close to the representation singularity the differences lose accuracy
        }
        checked += 1;
        let euler = |q: &OVector<f64, A::Dof>| {
            EulerZyz::from_rotation(&arm.fk(q).rotation.to_rotation_matrix())[0]
        };
        let j = arm.jacobian(&q);
        for c in 0..arm.dof() {
            let mut dq = OVector::<f64, A::Dof>::zeros_generic(arm.dim(), dhgen::nalgebra::U1);
            dq[c] = h;
            let (a, b) = (euler(&(&q + &dq)), euler(&(&q - &dq)));
            let fd = Vector3::new(
                wrap_angle(a.phi - b.phi),
                wrap_angle(a.theta - b.theta),
                wrap_angle(a.psi - b.psi),
            ) / (2.0 * h);
            let col = Vector3::new(ja[(3, c)], ja[(4, c)], ja[(5, c)]);
            assert!(
                (fd - col).norm() < 1e-6 * (1.0 + col.norm()),
                "{name}: column {c}: {fd:?} vs {col:?}"
            );
            // The linear rows are J's.
            for r in 0..3 {
                assert_eq!(ja[(r, c)], j[(r, c)]);
            }
        }
        // J = [I 0; 0 B] J_a.
        let b = euler_rate_matrix(&e);
        for c in 0..arm.dof() {
            let w = b * Vector3::new(ja[(3, c)], ja[(4, c)], ja[(5, c)]);
            assert!((w - Vector3::new(j[(3, c)], j[(4, c)], j[(5, c)])).norm() < 1e-12);
        }
    }
}

#[test]
fn analytic_jacobian_matches_finite_differences_of_euler_angles() {
    check_analytic_jacobian(&puma560::Robot, "puma560");
    check_analytic_jacobian(&panda::Robot, "panda");
    check_analytic_jacobian(&runtime("stanford"), "stanford (runtime)");
}

#[test]
fn analytic_jacobian_is_undefined_where_b_is_singular() {
    // Tool z axis along the world z axis: θ = 0 in the Euler angles.
    let q = SVector::<f64, 2>::new(0.4, -0.3);
    assert!(analytic_jacobian(&planar::Robot, &q).is_none());
}

/// Checks the Penrose identities and compares the singular values with nalgebra's SVD.
fn check_svd<D: dhgen::nalgebra::Dim>(j: &OMatrix<f64, U6, D>)
where
    DefaultAllocator: dhgen::nalgebra::allocator::Allocator<U6, D>
        + dhgen::nalgebra::allocator::Allocator<D, U6>
        + dhgen::nalgebra::allocator::Allocator<D>,
{
    let svd = JacobianSvd::new(j);
    let dj = DMatrix::from_fn(6, j.ncols(), |r, c| j[(r, c)]);
    let reference = dj.clone().svd(false, false).singular_values;
    let mut reference: Vec<f64> = reference.iter().copied().collect();
    reference.sort_by(|a, b| b.partial_cmp(a).unwrap());
    let sigma = svd.singular_values();
    for (i, s) in reference.iter().enumerate() {
        assert!(
            (sigma[i] - s).abs() < 1e-12 * (1.0 + reference[0]),
            "σ{i}: {} vs {s}",
            sigma[i]
        );
    }
    for w in sigma.as_slice().windows(2) {
        assert!(w[0] >= w[1]);
    }
    let u = svd.u();
    assert!(
        (u.transpose() * u - dhgen::nalgebra::Matrix6::identity())
            .abs()
            .max()
            < 1e-13
    );
    let pinv = svd.pseudo_inverse(0.0);
    let p = DMatrix::from_fn(j.ncols(), 6, |r, c| pinv[(r, c)]);
    let tol = 1e-10 * (1.0 + dj.abs().max()) * (1.0 + p.abs().max());
    assert!((&dj * &p * &dj - &dj).abs().max() < tol, "J J⁺ J = J");
    assert!((&p * &dj * &p - &p).abs().max() < tol, "J⁺ J J⁺ = J⁺");
    let jp = &dj * &p;
    assert!((&jp - jp.transpose()).abs().max() < tol, "J J⁺ symmetric");
    let pj = &p * &dj;
    assert!((&pj - pj.transpose()).abs().max() < tol, "J⁺ J symmetric");
    // The damped inverse is Jᵀ (J Jᵀ + λ² I)⁻¹.
    let lambda = 0.3;
    let damped = svd.pseudo_inverse(lambda);
    let expected = dj.transpose()
        * (&dj * dj.transpose() + DMatrix::identity(6, 6) * (lambda * lambda))
            .try_inverse()
            .unwrap();
    for r in 0..j.ncols() {
        for c in 0..6 {
            assert!((damped[(r, c)] - expected[(r, c)]).abs() < 1e-10);
        }
    }
    // solve and null_space_projection agree with the matrices.
    let xi = Vector6::new(0.3, -0.1, 0.2, 0.5, -0.4, 0.1);
    let x = svd.solve(&xi, 0.0);
    let px = &p * DVector::from_column_slice(xi.as_slice());
    for r in 0..j.ncols() {
        assert!((x[r] - px[r]).abs() < 1e-10);
    }
    let b = OVector::<f64, D>::from_fn_generic(j.shape_generic().1, dhgen::nalgebra::U1, |r, _| {
        (r as f64 * 0.7).sin()
    });
    let nb = svd.null_space_projection(&b);
    assert!((j * &nb).norm() < 1e-10 * (1.0 + b.norm()));
}

#[test]
fn svd_and_pseudo_inverse_identities() {
    let mut rng = StdRng::seed_from_u64(8);
    for _ in 0..50 {
        check_svd(&puma560::Robot.jacobian(&random_q(&puma560::Robot, &mut rng)));
        check_svd(&panda::Robot.jacobian(&random_q(&panda::Robot, &mut rng)));
        check_svd(&planar::Robot.jacobian(&random_q(&planar::Robot, &mut rng)));
        let robot = runtime("panda");
        check_svd(&Arm::jacobian(&robot, &random_q(&robot, &mut rng)));
    }
    // Singular Jacobians: the wrist of the PUMA at θ5 = 0 (rank 5).
    let q = SVector::<f64, 6>::new(0.3, 0.2, -0.9, 0.4, 0.0, 0.1);
    check_svd(&puma560::Robot.jacobian(&q));
}

#[test]
fn manipulability_and_condition_number() {
    let mut rng = StdRng::seed_from_u64(12);
    for _ in 0..50 {
        let j = panda::Robot.jacobian(&random_q(&panda::Robot, &mut rng));
        let yoshikawa = (j * j.transpose()).determinant().sqrt();
        assert!((manipulability(&j) - yoshikawa).abs() < 1e-12 * (1.0 + yoshikawa));
        let j = puma560::Robot.jacobian(&random_q(&puma560::Robot, &mut rng));
        assert!((manipulability(&j) - j.determinant().abs()).abs() < 1e-12);
        let s = j.svd(false, false).singular_values;
        assert!((condition_number(&j) - s.max() / s.min()).abs() < 1e-8 * condition_number(&j));
    }
    // n < 6: the product of the n singular values, √det(Jᵀ J).
    let j = planar::Robot.jacobian(&SVector::<f64, 2>::new(0.3, 1.1));
    assert!((manipulability(&j) - (j.transpose() * j).determinant().sqrt()).abs() < 1e-12);
}

#[test]
fn singular_configurations_are_detected() {
    let threshold = 1e-9;
    // Elbow stretched: the forearm (a3, d4) in line with the upper arm.
    let elbow = -FRAC_PI_2 + 0.0203f64.atan2(0.4318);
    let stretched = SVector::<f64, 6>::new(0.3, -0.4, elbow, 0.5, 0.7, 0.2);
    assert!(is_singular(&puma560::Robot.jacobian(&stretched), threshold));
    // Wrist: θ5 = 0 aligns axes 4 and 6.
    let wrist = SVector::<f64, 6>::new(0.3, -0.4, 0.3, 0.5, 0.0, 0.2);
    assert!(is_singular(&puma560::Robot.jacobian(&wrist), threshold));
    // A regular configuration.
    let regular = SVector::<f64, 6>::new(0.3, -0.4, 0.3, 0.5, 0.7, 0.2);
    let svd = JacobianSvd::new(&puma560::Robot.jacobian(&regular));
    assert!(svd.min_singular_value() > 1e-2);
    assert!(!is_singular(&puma560::Robot.jacobian(&regular), threshold));
    assert_eq!(svd.rank(threshold), 6);
    assert_eq!(
        JacobianSvd::new(&puma560::Robot.jacobian(&wrist)).rank(threshold),
        5
    );
    // Near (not at) the singularity: small but non-zero, proportional to the distance.
    let near = SVector::<f64, 6>::new(0.3, -0.4, 0.3, 0.5, 1e-4, 0.2);
    let s = JacobianSvd::new(&puma560::Robot.jacobian(&near)).min_singular_value();
    assert!(s > 1e-6 && s < 1e-3, "{s}");
}

#[test]
fn decoupled_determinants_separate_arm_and_wrist() {
    let ik = DecoupledIk::from_chain(puma560::CHAIN).unwrap();
    let centre = ik.wrist_centre_in_tool().expect("a spherical wrist");
    let mut rng = StdRng::seed_from_u64(4);
    for _ in 0..200 {
        let q = random_q(&puma560::Robot, &mut rng);
        let d = decoupled_determinants(&puma560::Robot, &q, &centre).unwrap();
        let det = puma560::Robot.jacobian(&q).determinant();
        assert!(
            (d.arm * d.wrist - det).abs() < 1e-12,
            "{} vs {det}",
            d.arm * d.wrist
        );
        // det J22 = det[z3 z4 z5] = ± sin θ5.
        assert!((d.wrist.abs() - q[4].sin().abs()).abs() < 1e-12);
    }
    let elbow = -FRAC_PI_2 + 0.0203f64.atan2(0.4318);
    let stretched = SVector::<f64, 6>::new(0.3, -0.4, elbow, 0.5, 0.7, 0.2);
    let d = decoupled_determinants(&puma560::Robot, &stretched, &centre).unwrap();
    assert!(d.arm.abs() < 1e-12 && d.wrist.abs() > 0.5);
    let wrist = SVector::<f64, 6>::new(0.3, -0.4, 0.3, 0.5, 0.0, 0.2);
    let d = decoupled_determinants(&puma560::Robot, &wrist, &centre).unwrap();
    assert!(d.wrist.abs() < 1e-15 && d.arm.abs() > 1e-3);
    // Not six joints.
    assert!(decoupled_determinants(&panda::Robot, &SVector::zeros(), &centre).is_none());
}

#[test]
fn elbow_arm_det_j11_is_the_texts_expression() {
    let (a2, a3) = (0.7, 0.6);
    let centre = DecoupledIk::from_chain(elbow::CHAIN)
        .unwrap()
        .wrist_centre_in_tool()
        .expect("a spherical wrist");
    let mut rng = StdRng::seed_from_u64(6);
    for _ in 0..200 {
        let q = random_q(&elbow::Robot, &mut rng);
        let d = decoupled_determinants(&elbow::Robot, &q, &centre).unwrap();
        let (c2, s3, c23) = (q[1].cos(), q[2].sin(), (q[1] + q[2]).cos());
        let text = a2 * a3 * s3 * (a2 * c2 + a3 * c23);
        assert!((d.arm + text).abs() < 1e-12, "{} vs −{text}", d.arm);
    }
    // Zero at θ3 = 0 (stretched) and with the wrist centre on axis 1.
    let d = decoupled_determinants(
        &elbow::Robot,
        &SVector::<f64, 6>::new(0.2, 0.5, 0.0, 0.1, 0.4, 0.3),
        &centre,
    )
    .unwrap();
    assert!(d.arm.abs() < 1e-15);
    let q2: f64 = 1.2;
    let q3 = (-(a2 * q2.cos()) / a3).acos() - q2; // a2 c2 + a3 c23 = 0
    let d = decoupled_determinants(
        &elbow::Robot,
        &SVector::<f64, 6>::new(0.2, q2, q3, 0.1, 0.4, 0.3),
        &centre,
    )
    .unwrap();
    assert!(d.arm.abs() < 1e-12);
}

#[test]
fn inverse_velocity_reproduces_the_twist_away_from_singularities() {
    let mut rng = StdRng::seed_from_u64(10);
    let damping = Damping::default();
    let mut worst: f64 = 0.0;
    let mut checked = 0;
    while checked < 500 {
        let q = random_q(&puma560::Robot, &mut rng);
        let j = puma560::Robot.jacobian(&q);
        if JacobianSvd::new(&j).min_singular_value() < damping.threshold {
            continue;
        }
        checked += 1;
        let xi = Vector6::from_fn(|_, _| rng.random_range(-1.0..1.0));
        let qd = inverse_velocity(&puma560::Robot, &q, &xi, None, &damping);
        let err = (j * qd - xi).norm();
        worst = worst.max(err);
        assert!(err < 1e-9, "{err:e}");
    }
    // Redundant: the null-space term changes q̇ but not the twist.
    for _ in 0..200 {
        let q = random_q(&panda::Robot, &mut rng);
        let j = panda::Robot.jacobian(&q);
        if JacobianSvd::new(&j).min_singular_value() < damping.threshold {
            continue;
        }
        let xi = Vector6::from_fn(|_, _| rng.random_range(-1.0..1.0));
        let b = SVector::<f64, 7>::from_fn(|_, _| rng.random_range(-1.0..1.0));
        let least = inverse_velocity(&panda::Robot, &q, &xi, None, &damping);
        let with_b = inverse_velocity(&panda::Robot, &q, &xi, Some(&b), &damping);
        assert!((j * least - xi).norm() < 1e-9);
        assert!((j * with_b - xi).norm() < 1e-9);
        assert!((with_b - least).norm() > 1e-6);
        // The least-norm solution is orthogonal to the null-space part.
        assert!(least.dot(&(with_b - least)).abs() < 1e-9);
        worst = worst.max((j * with_b - xi).norm());
    }
    // The runtime robot gives the same joint rates.
    let robot = runtime("puma560");
    let q = SVector::<f64, 6>::new(0.1, -0.5, 0.3, 0.2, 0.8, -0.4);
    let xi = Vector6::new(0.1, 0.2, -0.1, 0.3, -0.2, 0.1);
    let a = inverse_velocity(&puma560::Robot, &q, &xi, None, &damping);
    let b = inverse_velocity(
        &robot,
        &DVector::from_column_slice(q.as_slice()),
        &xi,
        None,
        &damping,
    );
    assert!((a - SVector::<f64, 6>::from_column_slice(b.as_slice())).norm() < 1e-10);
    eprintln!("inverse velocity: worst |J q̇ − ξ| = {worst:.1e} away from singularities");
}

#[test]
fn inverse_velocity_stays_bounded_near_singularities() {
    let damping = Damping::default();
    let xi = Vector6::new(0.0, 0.0, 0.0, 1.0, 1.0, 1.0) / 3f64.sqrt();
    let elbow = -FRAC_PI_2 + 0.0203f64.atan2(0.4318);
    let mut largest: f64 = 0.0;
    for offset in [0.0, 1e-12, 1e-9, 1e-6, 1e-4, 1e-3, 5e-3] {
        for q in [
            SVector::<f64, 6>::new(0.3, -0.4, 0.3, 0.5, offset, 0.2),
            SVector::<f64, 6>::new(0.3, -0.4, elbow + offset, 0.5, 0.7, 0.2),
        ] {
            let qd = inverse_velocity(&puma560::Robot, &q, &xi, None, &damping);
            assert!(qd.iter().all(|x| x.is_finite()));
            largest = largest.max(qd.norm());
            // σ/(σ² + λ²) ≤ 1/threshold while damped, whatever σ.
            assert!(
                qd.norm() <= xi.norm() / damping.threshold + 1e-9,
                "{offset}: {}",
                qd.norm()
            );
        }
    }
    // Undamped, the joint rates grow like 1/σ there.
    let q = SVector::<f64, 6>::new(0.3, -0.4, 0.3, 0.5, 1e-6, 0.2);
    let undamped = inverse_velocity(&puma560::Robot, &q, &xi, None, &Damping::NONE);
    assert!(undamped.norm() > 1e4, "{}", undamped.norm());
    eprintln!("inverse velocity near singularities: largest |q̇| = {largest:.1} for |ξ| = 1");
}

#[test]
fn inverse_acceleration_reproduces_the_tool_acceleration() {
    let mut rng = StdRng::seed_from_u64(14);
    let damping = Damping::default();
    let mut checked = 0;
    while checked < 200 {
        let q = random_q(&puma560::Robot, &mut rng);
        let j = puma560::Robot.jacobian(&q);
        if JacobianSvd::new(&j).min_singular_value() < damping.threshold {
            continue;
        }
        checked += 1;
        let qd = random_qd(&puma560::Robot, &mut rng);
        let xdd = Vector6::from_fn(|_, _| rng.random_range(-2.0..2.0));
        let qdd = inverse_acceleration(&puma560::Robot, &q, &qd, &xdd, None, &damping);
        let achieved = j * qdd + dhgen::Arm::jdot_qdot(&puma560::Robot, &q, &qd);
        assert!((achieved - xdd).norm() < 1e-9);
    }
}

#[test]
fn rotation_of_the_tool_under_analytic_rates() {
    // ḋ and α̇ from J_a integrate to the pose: one small Euler step in q.
    let q = SVector::<f64, 6>::new(0.2, -0.3, 0.4, 0.5, 0.6, 0.7);
    let qd = SVector::<f64, 6>::new(0.3, -0.2, 0.1, 0.4, -0.5, 0.6);
    let analytic = analytic_jacobian(&puma560::Robot, &q).unwrap();
    let (ja, e) = (analytic.jacobian, analytic.euler);
    let h = 1e-7;
    let rates = ja * qd;
    let predicted = EulerZyz::new(
        e.phi + rates[3] * h,
        e.theta + rates[4] * h,
        e.psi + rates[5] * h,
    )
    .to_rotation();
    let actual: Rotation3<f64> = puma560::Robot
        .fk(&(q + qd * h))
        .rotation
        .to_rotation_matrix();
    assert!((predicted.matrix() - actual.matrix()).abs().max() < 1e-12);
    let _: Matrix3<f64> = euler_rate_matrix(&e);
}
