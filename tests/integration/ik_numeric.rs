//! Numeric inverse kinematics (damped least squares / Levenberg–Marquardt): convergence rate
//! from random seeds on random reachable poses (PUMA 560, Panda), prismatic joints, the
//! runtime robot, limits, and every error reason.

use crate::catalogue::{cylindrical, panda, puma560, stanford};
use crate::support::{allocations_during, runtime, scaled};
use dhgen::ik::{DecoupledIk, IkError, NumericIk, pose_error};
use dhgen::nalgebra::{
    DVector, DefaultAllocator, Isometry3, OVector, SVector, Translation3, UnitQuaternion, Vector6,
};
use dhgen::velocity::{Damping, inverse_acceleration, inverse_velocity};
use dhgen::{Arm, ArmAllocator};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};

fn random_q<A: Arm>(arm: &A, rng: &mut StdRng) -> OVector<f64, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    OVector::<f64, A::Dof>::from_fn_generic(arm.dim(), dhgen::nalgebra::U1, |j, _| {
        let [lo, hi] = arm.limits(j).unwrap_or([-3.0, 3.0]);
        rng.random_range(lo..=hi)
    })
}

struct Rate {
    poses: usize,
    converged: usize,
    iterations: Vec<usize>,
    worst_position: f64,
    worst_orientation: f64,
}

impl Rate {
    fn rate(&self) -> f64 {
        self.converged as f64 / self.poses as f64
    }
    fn report(&self, name: &str, cap: usize) {
        if self.iterations.is_empty() {
            eprintln!(
                "{name}: converged on 0/{} poses within {cap} iterations",
                self.poses
            );
            return;
        }
        let mut it = self.iterations.clone();
        it.sort_unstable();
        let mean = it.iter().sum::<usize>() as f64 / it.len().max(1) as f64;
        let pct = |p: f64| it[((it.len() - 1) as f64 * p) as usize];
        eprintln!(
            "{name}: converged on {}/{} poses ({:.2}%) from random seeds within {cap} iterations; \
             iterations mean {mean:.1}, median {}, 99th percentile {}, max {}; worst final error \
             {:.1e} m / {:.1e} rad",
            self.converged,
            self.poses,
            100.0 * self.rate(),
            pct(0.5),
            pct(0.99),
            it.last().unwrap(),
            self.worst_position,
            self.worst_orientation
        );
    }
}

/// Random reachable poses (from random q within limits), each solved once from a random
/// seed within limits.
fn convergence<A: Arm>(arm: &A, solver: &NumericIk, poses: usize, seed: u64) -> Rate
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let mut rng = StdRng::seed_from_u64(seed);
    let mut r = Rate {
        poses,
        converged: 0,
        iterations: Vec::new(),
        worst_position: 0.0,
        worst_orientation: 0.0,
    };
    for _ in 0..poses {
        let q = random_q(arm, &mut rng);
        let target = arm.fk(&q);
        let seed = random_q(arm, &mut rng);
        if let Ok(s) = solver.solve(arm, &target, &seed) {
            let (dp, dr) = pose_error(&arm.fk(&s.q), &target);
            assert!(dp <= solver.position_tolerance && dr <= solver.orientation_tolerance);
            assert!((dp - s.position_error).abs() < 1e-15);
            assert!((dr - s.orientation_error).abs() < 1e-14);
            for j in 0..arm.dof() {
                if let Some([lo, hi]) = arm.limits(j) {
                    assert!(s.q[j] >= lo && s.q[j] <= hi, "joint {j} outside its limits");
                }
            }
            r.converged += 1;
            r.iterations.push(s.iterations);
            r.worst_position = r.worst_position.max(dp);
            r.worst_orientation = r.worst_orientation.max(dr);
        }
    }
    r
}

/// The acceptance count (10,000 poses) under `cargo test --release`; 2,000 in debug builds,
/// where each solve is about 20 times slower.
const POSES: usize = if cfg!(debug_assertions) {
    2_000
} else {
    10_000
};

#[test]
fn puma560_converges_from_random_seeds() {
    let solver = NumericIk::default();
    let r = convergence(&puma560::Robot, &solver, POSES, 560);
    r.report("puma560", solver.max_iterations);
    assert!(r.rate() >= 0.99, "{}", r.rate());
}

#[test]
fn panda_converges_from_random_seeds() {
    let solver = NumericIk::default();
    let r = convergence(&panda::Robot, &solver, POSES, 7);
    r.report("panda", solver.max_iterations);
    assert!(r.rate() >= 0.99, "{}", r.rate());
}

#[test]
fn runtime_robots_converge_too() {
    let solver = NumericIk::default();
    for name in ["puma560", "panda"] {
        let robot = runtime(name);
        let r = convergence(&robot, &solver, 150, 5);
        r.report(&format!("{name} (runtime)"), solver.max_iterations);
        assert!(r.rate() >= 0.98, "{name}: {}", r.rate());
    }
}

/// The same arms scaled to a tenth of a millimetre and to 300 times their size (lengths,
/// prismatic limits, base and tool) converge as the originals do, with the default settings:
/// positions are measured in the arm's length scale. In metres, the 0.1 mm PUMA 560 had
/// converged on none of these 100 poses (the damping swamped its Jacobian).
#[test]
fn scaled_arms_converge_as_the_originals() {
    let solver = NumericIk::default();
    for name in ["puma560", "panda", "stanford"] {
        for scale in [1e-4, 300.0] {
            let model = scaled(runtime(name).model().clone(), scale, 1.0);
            let robot = dhgen::Robot::from_model(model);
            let r = convergence(&robot, &solver, 100, 11);
            r.report(&format!("{name} ×{scale:e}"), solver.max_iterations);
            assert!(r.rate() >= 0.97, "{name} ×{scale:e}: {}", r.rate());
        }
    }
}

#[test]
fn prismatic_joints_converge() {
    let solver = NumericIk::default();
    let r = convergence(&stanford::Robot, &solver, 300, 9);
    r.report("stanford", solver.max_iterations);
    assert!(r.rate() >= 0.99, "{}", r.rate());
    let r = convergence(&cylindrical::Robot, &solver, 300, 10);
    r.report("cylindrical", solver.max_iterations);
    assert!(r.rate() >= 0.99, "{}", r.rate());
}

#[test]
fn near_seed_converges_quadratically_without_restarts() {
    let solver = NumericIk::default();
    let q = SVector::<f64, 7>::from([0.1, -0.4, 0.2, -1.8, 0.3, 1.5, 0.4]);
    let target = panda::Robot.fk(&q);
    let seed = q + SVector::repeat(0.05);
    let s = solver.solve(&panda::Robot, &target, &seed).unwrap();
    assert_eq!(s.restarts, 0);
    assert!(s.iterations <= 6, "{}", s.iterations);
    // At the solution itself: no iteration.
    let s = solver.solve(&panda::Robot, &target, &q).unwrap();
    assert_eq!((s.iterations, s.restarts), (0, 0));
}

#[test]
fn same_call_same_answer() {
    let solver = NumericIk::default();
    let mut rng = StdRng::seed_from_u64(1);
    let q = random_q(&puma560::Robot, &mut rng);
    let seed = random_q(&puma560::Robot, &mut rng);
    let target = puma560::Robot.fk(&q);
    assert_eq!(
        solver.solve(&puma560::Robot, &target, &seed),
        solver.solve(&puma560::Robot, &target, &seed)
    );
}

#[test]
fn invalid_input_is_an_error_naming_it() {
    let robot = runtime("puma560");
    let solver = NumericIk::default();
    let target = robot.fk(&[0.0; 6]);
    let err = solver
        .solve(&robot, &target, &DVector::zeros(5))
        .unwrap_err();
    assert_eq!(
        err,
        IkError::SeedLength {
            len: 5,
            expected: 6
        }
    );
    assert!(err.to_string().contains("length 5, expected 6"), "{err}");
    let mut seed = SVector::<f64, 6>::zeros();
    seed[3] = f64::NAN;
    let err = solver.solve(&puma560::Robot, &target, &seed).unwrap_err();
    assert_eq!(err, IkError::NonFiniteSeed { joint: 3 });
    assert!(err.to_string().contains("seed entry 3"), "{err}");
    let bad = Isometry3::from_parts(
        Translation3::new(0.0, f64::NAN, 0.0),
        UnitQuaternion::identity(),
    );
    let err = solver
        .solve(&puma560::Robot, &bad, &SVector::zeros())
        .unwrap_err();
    assert_eq!(err, IkError::NonFiniteTarget);
    for (settings, what) in [
        (
            NumericIk {
                position_tolerance: 0.0,
                ..solver
            },
            "position_tolerance",
        ),
        (
            NumericIk {
                orientation_tolerance: f64::NAN,
                ..solver
            },
            "orientation_tolerance",
        ),
        (
            NumericIk {
                max_iterations: 0,
                ..solver
            },
            "max_iterations",
        ),
        (
            NumericIk {
                initial_damping: -1.0,
                ..solver
            },
            "initial_damping",
        ),
    ] {
        let err = settings
            .solve(&puma560::Robot, &target, &SVector::zeros())
            .unwrap_err();
        assert!(matches!(err, IkError::InvalidSettings(_)), "{err}");
        assert!(err.to_string().contains(what), "{err}");
    }
}

#[test]
fn iteration_cap_reports_not_converged_with_the_error() {
    let solver = NumericIk {
        max_iterations: 2,
        ..NumericIk::default()
    };
    let q = SVector::<f64, 6>::new(0.5, 0.3, -0.8, 0.2, 0.9, -0.4);
    let target = puma560::Robot.fk(&q);
    let err = solver
        .solve(&puma560::Robot, &target, &SVector::zeros())
        .unwrap_err();
    let IkError::NotConverged {
        iterations,
        position_error,
        orientation_error,
    } = err
    else {
        panic!("{err}");
    };
    assert_eq!(iterations, 2);
    assert!(position_error > 1e-6 && position_error.is_finite());
    assert!(orientation_error.is_finite());
    assert!(
        err.to_string().contains("did not converge in 2 iterations"),
        "{err}"
    );
}

#[test]
fn unreachable_pose_stalls_with_the_best_error() {
    // 2 m beyond the base: the PUMA reaches about 0.9 m; no restart can help.
    let far = Isometry3::from_parts(Translation3::new(2.0, 0.0, 0.7), UnitQuaternion::identity());
    let solver = NumericIk {
        restarts: 3,
        ..NumericIk::default()
    };
    let err = solver
        .solve(&puma560::Robot, &far, &SVector::zeros())
        .unwrap_err();
    let (IkError::LocalMinimum { position_error, .. } | IkError::Singular { position_error, .. }) =
        err
    else {
        panic!("{err}");
    };
    // The best the arm can do is to stretch towards the target: about 1.1 m short.
    assert!(
        position_error > 1.0 && position_error < 1.3,
        "{position_error}"
    );
}

#[test]
fn stalling_at_a_singular_configuration_is_reported_as_singular() {
    use dhgen::velocity::JacobianSvd;
    // The PUMA with its elbow stretched (θ3 = −90° + atan2(a3, d4)): J has rank 5. Ask for a
    // pose displaced along the one twist it cannot produce, outwards: unreachable, and no
    // step helps.
    let q = SVector::<f64, 6>::new(
        0.3,
        0.4,
        -std::f64::consts::FRAC_PI_2 + 0.0203f64.atan2(0.4318),
        0.2,
        0.6,
        -0.1,
    );
    let svd = JacobianSvd::new(&puma560::Robot.jacobian(&q));
    assert!(svd.min_singular_value() < 1e-12);
    let mut lost: Vector6<f64> = svd.u().column(5).into_owned();
    let pose = puma560::Robot.fk(&q);
    if lost.fixed_rows::<3>(0).dot(&pose.translation.vector) < 0.0 {
        lost = -lost;
    }
    let twist = lost * 0.1;
    let target = Isometry3::from_parts(
        Translation3::from(pose.translation.vector + twist.fixed_rows::<3>(0)),
        UnitQuaternion::from_scaled_axis(twist.fixed_rows::<3>(3).into_owned()) * pose.rotation,
    );
    let solver = NumericIk {
        restarts: 0,
        ..NumericIk::default()
    };
    let err = solver.solve(&puma560::Robot, &target, &q).unwrap_err();
    let IkError::Singular { sigma_min, .. } = err else {
        panic!("{err}");
    };
    assert!(sigma_min < 1e-6);
    assert!(err.to_string().contains("singular"), "{err}");
}

#[test]
fn limits_can_be_ignored() {
    // A pose whose only solutions need joint 2 beyond its upper limit of the PUMA's.
    let solver = NumericIk {
        respect_limits: false,
        ..NumericIk::default()
    };
    let q = SVector::<f64, 6>::new(0.2, 4.2, -0.5, 0.1, 0.4, 0.2);
    let target = puma560::Robot.fk(&q);
    let s = solver.solve(&puma560::Robot, &target, &(q * 0.9)).unwrap();
    assert!(s.position_error <= 1e-10);
}

#[test]
fn generated_robots_allocate_nothing() {
    let q = SVector::<f64, 7>::from([0.1, -0.4, 0.2, -1.8, 0.3, 1.5, 0.4]);
    let target = panda::Robot.fk(&q);
    let seed = q + SVector::repeat(0.3);
    let solver = NumericIk::default();
    let mut result = None;
    assert_eq!(
        allocations_during(|| result = Some(solver.solve(&panda::Robot, &target, &seed))),
        0
    );
    assert!(result.take().unwrap().is_ok());
    // With restarts (a far seed).
    let far_seed = SVector::<f64, 7>::from([2.5, 1.5, -2.5, -0.2, 2.5, 3.5, -2.5]);
    assert_eq!(
        allocations_during(|| result = Some(solver.solve(&panda::Robot, &target, &far_seed))),
        0
    );
    let solution = result.take().unwrap().unwrap();
    assert!(
        solution.restarts > 0,
        "the far seed converged without a restart"
    );

    let ik = DecoupledIk::from_chain(puma560::CHAIN).unwrap();
    let q6 = SVector::<f64, 6>::new(0.3, -0.2, 0.4, 0.5, 0.6, 0.7);
    let pose = puma560::Robot.fk(&q6);
    let mut count = 0;
    assert_eq!(allocations_during(|| count = ik.solve(&pose).len()), 0);
    assert_eq!(count, 8);
    assert_eq!(
        allocations_during(|| {
            DecoupledIk::from_chain(puma560::CHAIN).unwrap();
        }),
        0
    );

    let xi = Vector6::new(0.1, -0.2, 0.05, 0.3, 0.0, -0.1);
    let mut out = SVector::<f64, 6>::zeros();
    assert_eq!(
        allocations_during(|| {
            out = inverse_velocity(&puma560::Robot, &q6, &xi, None, &Damping::default());
            out += inverse_acceleration(
                &puma560::Robot,
                &q6,
                &out.clone(),
                &xi,
                Some(&out.clone()),
                &Damping::default(),
            );
            let _ = dhgen::Arm::jdot_qdot(&puma560::Robot, &q6, &out);
        }),
        0
    );
}
