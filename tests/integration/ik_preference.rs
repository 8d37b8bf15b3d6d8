//! Redundancy resolution (`NumericIk::solve_preferring`): the solution nearest a posture is a
//! minimum of the distance along the self-motion, the most manipulable one a maximum of the
//! manipulability (first order: the objective's gradient has no part in the Jacobian's null
//! space; second order: moving along the self-motion either way and back onto the pose makes
//! it no better), both never worse than the first solution; on the Panda, on general arms of
//! 8 and 9 joints with oblique axes (runtime), on a 17-joint arm; nothing moves on a
//! non-redundant arm; no allocation for a generated arm; bad postures are errors.

use crate::catalogue::{panda, puma560, snake17};
use crate::support::{allocations_during, random_q, runtime};
use dhgen::ik::{IkError, NumericIk, Preference, pose_error};
use dhgen::model::random::{ArmStyle, random_arm};
use dhgen::nalgebra::{DVector, DefaultAllocator, Isometry3, OVector, SVector, U1};
use dhgen::velocity::{Axes, JacobianSvd, manipulability, manipulability_gradient};
use dhgen::{Arm, ArmAllocator};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};

fn cost<A: Arm>(arm: &A, q: &OVector<f64, A::Dof>, preference: &Preference<'_, A::Dof>) -> f64
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    match preference {
        Preference::Posture(p) => 0.5 * (*p - q).norm_squared(),
        Preference::Manipulability(_) => -manipulability(&arm.jacobian(q)),
        Preference::Cost(f) => f(q).0,
    }
}

/// The objective's descent direction at `q` (towards the posture; up ∂m/∂q).
fn descent<A: Arm>(
    arm: &A,
    q: &OVector<f64, A::Dof>,
    preference: &Preference<'_, A::Dof>,
) -> OVector<f64, A::Dof>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    match preference {
        Preference::Posture(p) => *p - q,
        Preference::Manipulability(axes) => {
            manipulability_gradient(&arm.jacobian(q), *axes).unwrap().1
        }
        Preference::Cost(f) => -f(q).1,
    }
}

/// What one preferred solve shows: the pose reached, no worse than the first solution,
/// stationary (with the joints on limits held, which the objective pushes out) and, off the
/// limits, optimal along the self-motion. Returns whether that second-order check ran (no
/// joint on a limit).
fn check_preferred<A: Arm>(
    arm: &A,
    target: &Isometry3<f64>,
    seed: &OVector<f64, A::Dof>,
    preference: Preference<'_, A::Dof>,
    what: &str,
) -> bool
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let ik = NumericIk::default();
    let first = ik.solve(arm, target, seed).unwrap();
    let best = ik.solve_preferring(arm, target, seed, preference).unwrap();
    let (dp, dr) = pose_error(&arm.fk(&best.q), target);
    assert!(
        dp <= ik.position_tolerance && dr <= ik.orientation_tolerance,
        "{what}: {dp:e} {dr:e}"
    );
    for k in 0..arm.dof() {
        if let Some([lo, hi]) = arm.limits(k) {
            assert!(
                best.q[k] >= lo && best.q[k] <= hi,
                "{what}: joint {k} outside its limits"
            );
        }
    }
    let c = cost(arm, &best.q, &preference);
    assert!(
        c <= cost(arm, &first.q, &preference),
        "{what}: worse than the first solution"
    );
    assert!(best.iterations <= ik.max_iterations);
    // First order (Karush–Kuhn–Tucker): with the joints on a limit held, (I − J⁺J) g = 0 to
    // the square root of the rounding of the objective; releasing any one of them, the
    // objective would push it out of its limits, not in.
    let q = &best.q;
    let on_limit: Vec<(usize, f64)> = (0..arm.dof())
        .filter_map(|k| {
            let [lo, hi] = arm.limits(k)?;
            (q[k] <= lo + 1e-9)
                .then_some((k, -1.0))
                .or((q[k] >= hi - 1e-9).then_some((k, 1.0)))
        })
        .collect();
    let g = descent(arm, q, &preference);
    let j = arm.jacobian(q);
    let on_face = |released: Option<usize>| {
        let (mut jr, mut gr) = (j.clone(), g.clone());
        for &(k, _) in on_limit.iter().filter(|&&(k, _)| Some(k) != released) {
            jr.column_mut(k).fill(0.0);
            gr[k] = 0.0;
        }
        JacobianSvd::new(&jr).null_space_projection(&gr)
    };
    let bound = 1e-7 * (1.0 + g.amax());
    let d = on_face(None);
    assert!(
        d.amax() <= bound,
        "{what}: projected gradient {:e} (gradient {:e}, {} joints on limits), {} iterations",
        d.amax(),
        g.amax(),
        on_limit.len(),
        best.iterations
    );
    for &(k, outward) in &on_limit {
        let push = outward * on_face(Some(k))[k];
        assert!(
            push >= -bound,
            "{what}: joint {k} on its limit is pulled in ({push:e})"
        );
    }
    if !on_limit.is_empty() {
        return false;
    }
    let svd = JacobianSvd::new(&j);
    // Second order: 1e-3 along each of a few null-space directions, either way, and back on
    // the pose, is no better.
    let mut rng = StdRng::seed_from_u64(17);
    let correct = NumericIk { restarts: 0, ..ik };
    for _ in 0..3 {
        let b = OVector::<f64, A::Dof>::from_fn_generic(arm.dim(), U1, |_, _| {
            rng.random_range(-1.0..1.0)
        });
        let n = svd.null_space_projection(&b).normalize();
        for sign in [-1.0, 1.0] {
            let moved = correct
                .solve(arm, target, &(&best.q + &n * (sign * 1e-3)))
                .unwrap();
            let cm = cost(arm, &moved.q, &preference);
            assert!(
                cm >= c - 1e-12 * c.abs().max(1e-3),
                "{what}: {cm:e} beside the optimum {c:e} along the self-motion"
            );
        }
    }
    true
}

#[test]
fn panda_nearest_posture_is_a_minimum_along_the_self_motion() {
    let arm = panda::Robot;
    let mut rng = StdRng::seed_from_u64(70);
    let mut checked = 0;
    for case in 0..40 {
        let target = arm.fk(&random_q(&arm, &mut rng));
        let seed = random_q(&arm, &mut rng);
        let posture = random_q(&arm, &mut rng);
        let what = format!("panda posture case {case}");
        checked +=
            check_preferred(&arm, &target, &seed, Preference::Posture(&posture), &what) as usize;
    }
    assert!(
        checked >= 10,
        "only {checked} of 40 solutions off the limits"
    );
}

#[test]
fn panda_most_manipulable_is_a_maximum_along_the_self_motion() {
    let arm = panda::Robot;
    let mut rng = StdRng::seed_from_u64(71);
    let mut checked = 0;
    for case in 0..40 {
        let target = arm.fk(&random_q(&arm, &mut rng));
        let seed = random_q(&arm, &mut rng);
        let what = format!("panda manipulability case {case}");
        let preference = Preference::Manipulability(Axes::All);
        checked += check_preferred(&arm, &target, &seed, preference, &what) as usize;
    }
    assert!(
        checked >= 10,
        "only {checked} of 40 solutions off the limits"
    );
}

/// Arms the tests have not seen: seeded general arms (oblique axes, offsets everywhere) of 8
/// and 9 joints on the runtime path, where the self-motion has two and three dimensions.
#[test]
fn general_arms_prefer_on_a_self_motion_of_several_dimensions() {
    for (dof, seed) in [(8, 3), (9, 4)] {
        let arm = dhgen::Robot::from_model(random_arm(dof, ArmStyle::General, seed));
        let mut rng = StdRng::seed_from_u64(seed);
        for case in 0..8 {
            let target = Arm::fk(&arm, &random_q(&arm, &mut rng));
            let start = random_q(&arm, &mut rng);
            let posture = random_q(&arm, &mut rng);
            let what = format!("general {dof} case {case}");
            check_preferred(&arm, &target, &start, Preference::Posture(&posture), &what);
            let preference = Preference::Manipulability(Axes::All);
            check_preferred(&arm, &target, &start, preference, &what);
        }
    }
}

/// Seventeen joints (a prismatic one among them), eleven dimensions of self-motion: the
/// posture's projected Newton steps reach its nearest solution.
#[test]
fn snake17_nearest_posture() {
    let arm = snake17::Robot;
    let mut rng = StdRng::seed_from_u64(171);
    for case in 0..5 {
        let target = arm.fk(&random_q(&arm, &mut rng));
        let seed = random_q(&arm, &mut rng);
        let posture = random_q(&arm, &mut rng);
        let what = format!("snake17 case {case}");
        check_preferred(&arm, &target, &seed, Preference::Posture(&posture), &what);
    }
}

/// Joint-limit avoidance, a cost of the user's: Σ ((q_k − mid_k) / range_k)⁴, which grows
/// steeply towards either limit (Liégeois' criterion, with a fourth power). Its optimum on the
/// self-motion meets the same conditions as the built-in objectives', on the Panda (generated)
/// and on a general 9-joint arm given limits (runtime).
#[test]
fn a_cost_of_ones_own_is_minimised_along_the_self_motion() {
    fn limit_avoidance<A: Arm>(arm: &A, q: &OVector<f64, A::Dof>) -> (f64, OVector<f64, A::Dof>)
    where
        DefaultAllocator: ArmAllocator<A::Dof>,
    {
        let mut grad = q.clone();
        let mut cost = 0.0;
        for k in 0..arm.dof() {
            let [lo, hi] = arm.limits(k).unwrap();
            let (mid, range) = ((lo + hi) / 2.0, hi - lo);
            let x = (q[k] - mid) / range;
            cost += x.powi(4);
            grad[k] = 4.0 * x.powi(3) / range;
        }
        (cost, grad)
    }
    let arm = panda::Robot;
    let cost = |q: &SVector<f64, 7>| limit_avoidance(&arm, q);
    let mut rng = StdRng::seed_from_u64(72);
    for case in 0..20 {
        let target = arm.fk(&random_q(&arm, &mut rng));
        let seed = random_q(&arm, &mut rng);
        let what = format!("panda limit avoidance case {case}");
        check_preferred(&arm, &target, &seed, Preference::Cost(&cost), &what);
    }
    let mut model = random_arm(9, ArmStyle::General, 5);
    for link in &mut model.links {
        link.limits = Some([-2.5, 2.0]);
    }
    let arm = dhgen::Robot::from_model(model);
    let cost = |q: &DVector<f64>| limit_avoidance(&arm, q);
    for case in 0..8 {
        let target = Arm::fk(&arm, &random_q(&arm, &mut rng));
        let seed = random_q(&arm, &mut rng);
        let what = format!("general 9 limit avoidance case {case}");
        check_preferred(&arm, &target, &seed, Preference::Cost(&cost), &what);
    }
}

/// A cost that is not finite ends the iteration at once: the first solution, polished.
#[test]
fn a_cost_that_is_not_finite_keeps_the_first_solution() {
    let arm = panda::Robot;
    let q = SVector::<f64, 7>::from([0.1, -0.4, 0.2, -1.8, 0.3, 1.5, 0.4]);
    let target = arm.fk(&q);
    let seed = SVector::<f64, 7>::from([0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0]);
    let ik = NumericIk::default();
    let first = ik.solve(&arm, &target, &seed).unwrap();
    let nan = |q: &SVector<f64, 7>| (f64::NAN, *q);
    let s = ik
        .solve_preferring(&arm, &target, &seed, Preference::Cost(&nan))
        .unwrap();
    assert!((s.q - first.q).amax() < 1e-8);
    let (dp, dr) = pose_error(&arm.fk(&s.q), &target);
    assert!(dp <= 1e-10 && dr <= 1e-10);
}

#[test]
fn a_non_redundant_arm_keeps_its_first_solution() {
    let arm = puma560::Robot;
    let mut rng = StdRng::seed_from_u64(6);
    let ik = NumericIk::default();
    for _ in 0..10 {
        let target = arm.fk(&random_q(&arm, &mut rng));
        let seed = random_q(&arm, &mut rng);
        let posture = random_q(&arm, &mut rng);
        let first = ik.solve(&arm, &target, &seed).unwrap();
        for preference in [
            Preference::Posture(&posture),
            Preference::Manipulability(Axes::All),
        ] {
            let s = ik
                .solve_preferring(&arm, &target, &seed, preference)
                .unwrap();
            // Only polished: moved by no more than the pose's tolerances allow.
            assert!((s.q - first.q).amax() < 1e-8, "{}", (s.q - first.q).amax());
            assert!(s.position_error <= first.position_error.max(1e-15));
            assert!(s.orientation_error <= first.orientation_error.max(1e-15));
        }
    }
}

#[test]
fn a_posture_out_of_the_limits_leaves_the_solution_within_them() {
    let arm = panda::Robot;
    let q = SVector::<f64, 7>::from([0.1, -0.4, 0.2, -1.8, 0.3, 1.5, 0.4]);
    let target = arm.fk(&q);
    // Joint 3's posture 1 rad beyond its lower limit pulls it onto the limit; the others
    // make up for it.
    let [lo, _] = arm.limits(3).unwrap();
    let mut posture = q;
    posture[3] = lo - 1.0;
    let ik = NumericIk::default();
    let s = ik
        .solve_preferring(&arm, &target, &q, Preference::Posture(&posture))
        .unwrap();
    assert!(s.q[3] >= lo && s.q[3] < q[3], "{} (from {})", s.q[3], q[3]);
    let (dp, dr) = pose_error(&arm.fk(&s.q), &target);
    assert!(dp <= 1e-10 && dr <= 1e-10);
    assert!((s.q - posture).norm() < (q - posture).norm());
}

/// A posture at 1e300 rad (finite: accepted) overflows the squared distance: the iteration
/// still ends within its budget, at a solution of the pose within the limits.
#[test]
fn a_huge_posture_ends_within_the_budget() {
    let arm = panda::Robot;
    let q = SVector::<f64, 7>::from([0.1, -0.4, 0.2, -1.8, 0.3, 1.5, 0.4]);
    let target = arm.fk(&q);
    let posture = SVector::<f64, 7>::repeat(1e300);
    let ik = NumericIk::default();
    let s = ik
        .solve_preferring(&arm, &target, &q, Preference::Posture(&posture))
        .unwrap();
    assert!(s.iterations <= ik.max_iterations);
    let (dp, dr) = pose_error(&arm.fk(&s.q), &target);
    assert!(dp <= 1e-10 && dr <= 1e-10);
    for k in 0..7 {
        let [lo, hi] = arm.limits(k).unwrap();
        assert!(s.q[k] >= lo && s.q[k] <= hi);
    }
}

#[test]
fn preferring_allocates_nothing_for_a_generated_arm() {
    let arm = panda::Robot;
    let q = SVector::<f64, 7>::from([0.1, -0.4, 0.2, -1.8, 0.3, 1.5, 0.4]);
    let target = arm.fk(&q);
    let seed = SVector::<f64, 7>::from([0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0]);
    let posture = SVector::<f64, 7>::zeros();
    let ik = NumericIk::default();
    for preference in [
        Preference::Posture(&posture),
        Preference::Manipulability(Axes::All),
    ] {
        let mut result = None;
        let allocations = allocations_during(|| {
            result = Some(ik.solve_preferring(&arm, &target, &seed, preference))
        });
        assert_eq!(allocations, 0);
        assert!(result.unwrap().unwrap().iterations > 0);
    }
}

#[test]
fn a_bad_posture_is_an_error_naming_it() {
    let robot = runtime("panda");
    let ik = NumericIk::default();
    let target = robot.fk(&[0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0]);
    let seed = DVector::from_vec(vec![0.1, 0.0, 0.0, -1.4, 0.0, 1.5, 0.0]);
    let short = DVector::zeros(6);
    assert_eq!(
        ik.solve_preferring(&robot, &target, &seed, Preference::Posture(&short)),
        Err(IkError::PostureLength {
            len: 6,
            expected: 7
        })
    );
    let mut nan = DVector::zeros(7);
    nan[4] = f64::NAN;
    let err = ik.solve_preferring(&robot, &target, &seed, Preference::Posture(&nan));
    assert_eq!(err, Err(IkError::NonFinitePosture { joint: 4 }));
    assert_eq!(
        err.unwrap_err().to_string(),
        "numeric IK: posture entry 4 is not finite"
    );
}
