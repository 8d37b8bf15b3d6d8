//! Non-finite and huge input: the rule of docs/conventions.md, "Non-finite input".
//!
//! - Numeric evaluations do not check their input: NaN or ±∞ in an input reaches the outputs
//!   that depend on it, and an output that stays finite does not depend on it; no panic, no
//!   hang. Checked on every catalogue robot, generated and runtime path, by comparing each
//!   finite output with the same output at two finite values of the input.
//! - Forward dynamics answers `None` rather than a non-finite q̈.
//! - Whatever decides or searches (IK, planners, trajectory constructors) returns an error
//!   naming the non-finite argument, and terminates for huge finite input (1e10 rad).
//! - The runtime path panics on a joint vector of the wrong length, naming the function and
//!   the argument.

use crate::catalogue::{cylindrical, panda, planar_elbow, puma560, scara, stanford, ur5};
use crate::support::runtime;
use dhgen::ik::{DecoupledIk, IkError, NumericIk};
use dhgen::nalgebra::{
    DVector, DefaultAllocator, Isometry3, Quaternion, Rotation3, SVector, Translation3, U1,
    UnitQuaternion, Vector3, Vector6,
};
use dhgen::planning::potential::{self, CSpaceField, ConvexCSpaceObstacles, ConvexRegion};
use dhgen::planning::{
    CSpaceGrid, CollisionChecker, DescentParams, Obstacle, PlanError, Prm, PrmConfig, Scene,
    WorkspaceField, WorkspacePlanner,
};
use dhgen::rotation::{EulerZyz, Rpy, axis_angle, rotation_vector, wrap_angle};
use dhgen::trajectory::{
    BlendedSegments, Cubic, CubicSpline, Lspb, MultiProfile, Profile, Quintic, Setpoint,
    SplineEnds, Synchronized, TrajectoryError, bang_bang_duration, sample_times_into,
    velocity_limited_duration,
};
use dhgen::velocity::{
    Damping, JacobianSvd, analytic_jacobian, euler_rate_matrix, inverse_acceleration,
    inverse_velocity, jacobian_dot,
};
use dhgen::{Arm, ArmAllocator, ArmDynamics, JointVector, Robot};
use std::f64::consts::PI;
use std::time::{Duration, Instant};

const NON_FINITE: [f64; 3] = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY];
const HUGE: f64 = 1e10;

/// A configuration inside the joint limits (where given), away from the obvious
/// singularities; `shift` moves every joint.
fn config<A: Arm>(arm: &A, shift: f64) -> JointVector<A>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    JointVector::<A>::from_fn_generic(arm.dim(), U1, |j, _| {
        let f = 0.2 + 0.6 * (0.37 * (j + 1) as f64 + shift).fract();
        match (arm.limits(j), arm.is_prismatic(j)) {
            (Some([lo, hi]), _) => lo + (hi - lo) * f,
            (None, false) => 2.0 * f - 1.0,
            (None, true) => 0.1 + 0.5 * f,
        }
    })
}

/// `v` with entry `j` replaced by `x`.
fn with<A: Arm>(v: &JointVector<A>, j: usize, x: f64) -> JointVector<A>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let mut v = v.clone();
    v[j] = x;
    v
}

/// Named outputs of numeric evaluations; `None` where the function answered `None`.
type Outputs = Vec<(&'static str, Option<Vec<f64>>)>;

/// Every kinematic evaluation of an arm at `(q, q̇)`.
fn kinematics<A: Arm>(arm: &A, q: &JointVector<A>, qd: &JointVector<A>) -> Outputs
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let values = |s: &[f64]| Some(s.to_vec());
    let mut frames = vec![Isometry3::identity(); arm.dof()];
    arm.frames_into(q, &mut frames);
    let j = arm.jacobian(q);
    let svd = JacobianSvd::new(&j);
    let xi = Vector6::new(0.1, -0.2, 0.05, 0.3, 0.0, -0.1);
    vec![
        ("fk", values(arm.fk(q).to_homogeneous().as_slice())),
        (
            "frames_into",
            Some(
                frames
                    .iter()
                    .flat_map(|f| f.to_homogeneous().as_slice().to_vec())
                    .collect(),
            ),
        ),
        ("jacobian", values(j.as_slice())),
        ("body_jacobian", values(arm.body_jacobian(q).as_slice())),
        ("jdot_qdot", values(arm.jdot_qdot(q, qd).as_slice())),
        (
            "body_jdot_qdot",
            values(arm.body_jdot_qdot(q, qd).as_slice()),
        ),
        ("jacobian_dot", values(jacobian_dot(arm, q, qd).as_slice())),
        (
            "inverse_velocity",
            values(inverse_velocity(arm, q, &xi, Some(qd), &Damping::default()).as_slice()),
        ),
        (
            "inverse_acceleration",
            values(inverse_acceleration(arm, q, qd, &xi, None, &Damping::default()).as_slice()),
        ),
        ("singular_values", values(svd.singular_values().as_slice())),
        (
            "manipulability, condition_number",
            Some(vec![svd.manipulability(), svd.condition_number()]),
        ),
        (
            "analytic_jacobian",
            analytic_jacobian(arm, q).map(|a| {
                let mut v = a.jacobian.as_slice().to_vec();
                v.extend(a.euler.to_vector().iter());
                v
            }),
        ),
    ]
}

/// [`dynamics`] for one arm type.
type DynamicsOutputs<A> = fn(&A, &JointVector<A>, &JointVector<A>, &JointVector<A>) -> Outputs;

/// Every dynamic evaluation of an arm at `(q, q̇, x)`, `x` both q̈ and τ.
fn dynamics<A: ArmDynamics>(
    arm: &A,
    q: &JointVector<A>,
    qd: &JointVector<A>,
    x: &JointVector<A>,
) -> Outputs
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let values = |s: &[f64]| Some(s.to_vec());
    let n = arm.dof();
    let mut christoffel = vec![0.0; n * n * n];
    arm.christoffel_into(q, &mut christoffel);
    vec![
        ("mass_matrix", values(arm.mass_matrix(q).as_slice())),
        ("christoffel_into", Some(christoffel)),
        ("coriolis", values(arm.coriolis(q, qd).as_slice())),
        ("gravity", values(arm.gravity(q).as_slice())),
        ("bias", values(arm.bias(q, qd).as_slice())),
        ("kinetic_energy", Some(vec![arm.kinetic_energy(q, qd)])),
        ("potential_energy", Some(vec![arm.potential_energy(q)])),
        (
            "inverse_dynamics",
            values(arm.inverse_dynamics(q, qd, x).as_slice()),
        ),
        (
            "forward_dynamics",
            arm.forward_dynamics(q, qd, x)
                .map(|a| a.as_slice().to_vec()),
        ),
    ]
}

/// The law for one output: every finite entry of `bad` (computed with a non-finite input)
/// equals the entry computed with two finite values of that input, i.e. does not depend on
/// it; `None` (forward dynamics, the analytic Jacobian) is always allowed for `bad`, and a
/// `Some` where a reference is `None` must carry a non-finite entry.
fn check_law(context: &str, bad: &Option<Vec<f64>>, refs: [&Option<Vec<f64>>; 2]) {
    let Some(bad) = bad else {
        return;
    };
    let [Some(a), Some(b)] = refs else {
        assert!(
            bad.iter().any(|x| !x.is_finite()),
            "{context}: finite with a non-finite input where finite inputs give None"
        );
        return;
    };
    assert_eq!(bad.len(), a.len(), "{context}: output length");
    for (i, &x) in bad.iter().enumerate() {
        if !x.is_finite() {
            continue;
        }
        for r in [a[i], b[i]] {
            assert!(
                (x - r).abs() <= 1e-9 * (1.0 + r.abs()),
                "{context}[{i}] = {x} stays finite with a non-finite input, but depends on \
                 that input ({r} at a finite value)"
            );
        }
    }
}

/// The propagation law over every input slot (`q`, `q̇`, `x` = q̈ or τ), joint and
/// non-finite value, for the kinematics and, where given, the dynamics of `arm`.
fn propagation<A: Arm>(arm: &A, path: &str, dyn_outputs: Option<DynamicsOutputs<A>>)
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let inputs = [config(arm, 0.0), config(arm, 0.21), config(arm, 0.43)];
    let evaluate = |v: &[JointVector<A>; 3]| {
        let mut out = kinematics(arm, &v[0], &v[1]);
        if let Some(d) = dyn_outputs {
            out.extend(d(arm, &v[0], &v[1], &v[2]));
        }
        out
    };
    let slots = if dyn_outputs.is_some() { 3 } else { 2 };
    for slot in 0..slots {
        for j in 0..arm.dof() {
            let at = |x: f64| {
                let mut v = inputs.clone();
                v[slot] = with::<A>(&v[slot], j, x);
                evaluate(&v)
            };
            let x0 = inputs[slot][j];
            let refs = [at(x0 + 0.3), at(x0 - 0.2)];
            for bad in NON_FINITE {
                let out = at(bad);
                let mut any_non_finite = false;
                for (k, (name, values)) in out.iter().enumerate() {
                    let context = format!(
                        "{path}: {name} with input {slot} (0 q, 1 qd, 2 qdd/tau) entry {j} = {bad}"
                    );
                    check_law(&context, values, [&refs[0][k].1, &refs[1][k].1]);
                    if *name == "forward_dynamics" {
                        // Rule 2: an answer is finite.
                        assert!(
                            values.iter().flatten().all(|x| x.is_finite()),
                            "{context}: Some with a non-finite entry"
                        );
                    }
                    let non_finite = match values {
                        None => true,
                        Some(v) => v.iter().any(|x| !x.is_finite()),
                    };
                    any_non_finite |= non_finite;
                    if slot == 0 && *name == "fk" {
                        assert!(
                            non_finite,
                            "{context}: the tool pose depends on every joint"
                        );
                    }
                }
                assert!(
                    any_non_finite,
                    "{path}: nothing depends on input {slot} entry {j} = {bad}"
                );
            }
        }
    }
}

/// One test per catalogue robot, on the generated and the runtime path.
mod numeric_functions_propagate_non_finite_input_without_panicking {
    use super::*;

    macro_rules! robot {
        ($name:ident, kinematics) => {
            #[test]
            fn $name() {
                propagation(
                    &$name::Robot,
                    concat!(stringify!($name), " (generated)"),
                    None,
                );
                propagation(
                    &runtime(stringify!($name)),
                    concat!(stringify!($name), " (runtime)"),
                    None,
                );
            }
        };
        ($name:ident) => {
            #[test]
            fn $name() {
                propagation(
                    &$name::Robot,
                    concat!(stringify!($name), " (generated)"),
                    Some(dynamics::<$name::Robot>),
                );
                propagation(
                    &runtime(stringify!($name)),
                    concat!(stringify!($name), " (runtime)"),
                    Some(dynamics::<Robot>),
                );
            }
        };
    }

    robot!(cylindrical, kinematics);
    robot!(panda);
    robot!(planar_elbow);
    robot!(puma560);
    robot!(scara);
    robot!(stanford);
    robot!(ur5);
}

#[test]
fn rotation_conversions_propagate_non_finite_input() {
    let angles = [0.3, -1.1, 2.2];
    type Convert = fn([f64; 3]) -> Vec<f64>;
    let conversions: [(&str, Convert); 5] = [
        ("EulerZyz", |a| {
            let e = EulerZyz::new(a[0], a[1], a[2]);
            let r = e.to_rotation();
            let mut out = r.matrix().as_slice().to_vec();
            for b in EulerZyz::from_rotation(&r) {
                out.extend(b.to_vector().iter());
            }
            out.extend(euler_rate_matrix(&e).iter());
            out
        }),
        ("Rpy", |a| {
            let r = Rpy::new(a[0], a[1], a[2]).to_rotation();
            let mut out = r.matrix().as_slice().to_vec();
            for b in Rpy::from_rotation(&r) {
                out.extend([b.roll, b.pitch, b.yaw]);
            }
            out
        }),
        ("axis_angle", |a| {
            let (axis, theta) = axis_angle(&Rotation3::new(Vector3::from(a)));
            vec![axis.x, axis.y, axis.z, theta]
        }),
        ("rotation_vector", |a| {
            rotation_vector(&Rotation3::new(Vector3::from(a)))
                .iter()
                .copied()
                .collect()
        }),
        ("wrap_angle", |a| a.map(wrap_angle).to_vec()),
    ];
    for (name, convert) in conversions {
        for i in 0..3 {
            let at = |x: f64| {
                let mut a = angles;
                a[i] = x;
                Some(convert(a))
            };
            let refs = [at(angles[i] + 0.3), at(angles[i] - 0.2)];
            for bad in NON_FINITE {
                let out = at(bad);
                assert!(
                    out.iter().flatten().any(|x| !x.is_finite()),
                    "{name}: angle {i} = {bad} reaches no output"
                );
                check_law(
                    &format!("{name} with angle {i} = {bad}"),
                    &out,
                    [&refs[0], &refs[1]],
                );
            }
        }
    }
}

/// A profile of each kind, built from finite input.
fn profiles() -> Vec<(&'static str, Box<dyn Profile>)> {
    vec![
        (
            "cubic",
            Box::new(Cubic::new(1.0, 3.0, 0.5, 0.2, -1.0, 0.1).unwrap()),
        ),
        (
            "quintic",
            Box::new(
                Quintic::new(
                    1.0,
                    3.0,
                    Setpoint::new(0.5, 0.2, 0.1),
                    Setpoint::new(-1.0, 0.0, 0.3),
                )
                .unwrap(),
            ),
        ),
        (
            "lspb",
            Box::new(Lspb::with_velocity(1.0, 3.0, 0.5, 2.0, 1.0).unwrap()),
        ),
        (
            "bang-bang",
            Box::new(Lspb::bang_bang(1.0, 0.5, -2.0, 3.0).unwrap()),
        ),
        (
            "trapezoid",
            Box::new(Lspb::velocity_limited(1.0, 0.5, 4.0, 1.0, 3.0).unwrap()),
        ),
        (
            "zero move",
            Box::new(Lspb::with_acceleration(1.0, 3.0, 0.5, 0.5, 1.0).unwrap()),
        ),
    ]
}

#[test]
fn trajectory_sampling_propagates_non_finite_time() {
    // Beyond the ends the joint rests at the nearest end; a NaN time gives NaN.
    let check = |name: &str, eval: &dyn Fn(f64) -> Setpoint, t0: f64, tf: f64| {
        let nan = eval(f64::NAN);
        assert!(
            nan.q.is_nan() && nan.qd.is_nan() && nan.qdd.is_nan(),
            "{name} at t = NaN: {nan:?}"
        );
        assert_eq!(eval(f64::INFINITY), eval(tf + 1.0), "{name} at t = +inf");
        assert_eq!(
            eval(f64::NEG_INFINITY),
            eval(t0 - 1.0),
            "{name} at t = -inf"
        );
    };
    for (name, p) in profiles() {
        check(name, &|t| p.eval(t), p.start_time(), p.end_time());
        let mut out = [Setpoint::default(); 2];
        for bad in NON_FINITE {
            let err = sample_times_into(p.as_ref(), &[1.5, bad], &mut out).unwrap_err();
            assert!(
                matches!(err, TrajectoryError::NonFinite { name: "t", .. }),
                "{name}: {err}"
            );
        }
    }
    let points = [[0.0, 1.0], [2.0, -1.0], [1.0, 0.5], [3.0, 3.0]];
    let times = [0.0, 2.0, 3.0, 5.0];
    let spline = CubicSpline::new(&times, &points, SplineEnds::Natural).unwrap();
    let blended = BlendedSegments::from_times(&times, &points, 0.4).unwrap();
    let limited = BlendedSegments::from_limits(0.0, &points, &[1.0, 2.0], &[3.0, 1.0]).unwrap();
    let paths: [(&str, &dyn MultiProfile); 3] = [
        ("cubic spline", &spline),
        ("blended segments", &blended),
        ("blended segments from limits", &limited),
    ];
    for (name, path) in paths {
        let eval = |t: f64| {
            let mut out = [Setpoint::default(); 2];
            path.eval_into(t, &mut out).unwrap();
            out
        };
        for j in 0..2 {
            check(
                &format!("{name}, joint {j}"),
                &|t| eval(t)[j],
                path.start_time(),
                path.end_time(),
            );
        }
    }
    let sync = Synchronized::bang_bang(0.0, &[0.0, 1.0], &[2.0, -1.0], &[1.0, 3.0]).unwrap();
    for j in 0..2 {
        check(
            &format!("synchronized bang-bang, joint {j}"),
            &|t| sync.eval(t)[j],
            MultiProfile::start_time(&sync),
            MultiProfile::end_time(&sync),
        );
    }
}

/// Forward dynamics (rule 2): `None` for a non-finite q̇ or τ (every q̈ depends on both), and
/// never a non-finite q̈, also where a huge input overflows the arithmetic.
#[test]
fn forward_dynamics_answers_none_rather_than_a_non_finite_acceleration() {
    fn check<A: ArmDynamics>(arm: &A, path: &str)
    where
        DefaultAllocator: ArmAllocator<A::Dof>,
    {
        let q = config(arm, 0.1);
        let qd = config(arm, 0.3);
        let tau = arm.gravity(&q);
        let huge = [1e200, -1e200, f64::MAX, f64::MIN];
        for bad in NON_FINITE.into_iter().chain(huge) {
            for j in 0..arm.dof() {
                let found = [
                    ("q", arm.forward_dynamics(&with::<A>(&q, j, bad), &qd, &tau)),
                    (
                        "qd",
                        arm.forward_dynamics(&q, &with::<A>(&qd, j, bad), &tau),
                    ),
                    (
                        "tau",
                        arm.forward_dynamics(&q, &qd, &with::<A>(&tau, j, bad)),
                    ),
                ];
                for (input, qdd) in &found {
                    if let Some(qdd) = qdd {
                        assert!(
                            qdd.iter().all(|x| x.is_finite()),
                            "{path}: {input}[{j}] = {bad} gave {qdd}"
                        );
                    }
                }
                if !bad.is_finite() {
                    for (input, qdd) in &found[1..] {
                        assert!(qdd.is_none(), "{path}: {input}[{j}] = {bad} gave {qdd:?}");
                    }
                }
            }
        }
    }
    check(&panda::Robot, "panda (generated)");
    check(&runtime("panda"), "panda (runtime)");
    check(&puma560::Robot, "puma560 (generated)");
    check(&runtime("puma560"), "puma560 (runtime)");
    check(&scara::Robot, "scara (generated)");
    check(&runtime("scara"), "scara (runtime)");
}

fn pose_with(translation: [f64; 3], rotation: [f64; 4]) -> Isometry3<f64> {
    Isometry3::from_parts(
        Translation3::new(translation[0], translation[1], translation[2]),
        UnitQuaternion::new_unchecked(Quaternion::new(
            rotation[0],
            rotation[1],
            rotation[2],
            rotation[3],
        )),
    )
}

fn numeric_ik_rejects<A: Arm>(arm: &A, path: &str)
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let seed = config(arm, 0.0);
    let target = arm.fk(&config(arm, 0.2));
    let ik = NumericIk::default();
    assert!(
        ik.solve(arm, &target, &seed).is_ok(),
        "{path}: finite input"
    );
    for bad in NON_FINITE {
        for j in 0..arm.dof() {
            let err = ik
                .solve(arm, &target, &with::<A>(&seed, j, bad))
                .unwrap_err();
            assert_eq!(err, IkError::NonFiniteSeed { joint: j }, "{path}: {err}");
            assert!(err.to_string().contains("seed"), "{path}: {err}");
        }
        let t = target.translation.vector;
        let r = target.rotation.coords;
        for k in 0..3 {
            let mut p = [t.x, t.y, t.z];
            p[k] = bad;
            let err = ik
                .solve(arm, &pose_with(p, [r.w, r.x, r.y, r.z]), &seed)
                .unwrap_err();
            assert_eq!(err, IkError::NonFiniteTarget, "{path}: {err}");
        }
        for k in 0..4 {
            let mut w = [r.w, r.x, r.y, r.z];
            w[k] = bad;
            let err = ik
                .solve(arm, &pose_with([t.x, t.y, t.z], w), &seed)
                .unwrap_err();
            assert_eq!(err, IkError::NonFiniteTarget, "{path}: {err}");
            assert!(err.to_string().contains("target"), "{path}: {err}");
        }
        type Set = fn(&mut NumericIk, f64);
        let settings: [(&str, Set); 3] = [
            ("position_tolerance", |s, x| s.position_tolerance = x),
            ("orientation_tolerance", |s, x| s.orientation_tolerance = x),
            ("initial_damping", |s, x| s.initial_damping = x),
        ];
        for (name, set) in settings {
            let mut s = NumericIk::default();
            set(&mut s, bad);
            let err = s.solve(arm, &target, &seed).unwrap_err();
            assert!(
                matches!(err, IkError::InvalidSettings(_))
                    && err.to_string().contains(name)
                    && err.to_string().contains("finite"),
                "{path}: {name} = {bad}: {err}"
            );
        }
    }
}

fn closed_form_rejects(solver: &DecoupledIk, path: &str) {
    let pose = solver.fk(&SVector::from([0.2, -0.4, 0.3, 0.5, 0.7, -0.3]));
    assert!(!solver.solve(&pose).is_empty(), "{path}: finite pose");
    let t = pose.translation.vector;
    let r = pose.rotation.coords;
    for bad in NON_FINITE {
        for k in 0..7 {
            let mut v = [t.x, t.y, t.z, r.w, r.x, r.y, r.z];
            v[k] = bad;
            let bad_pose = pose_with([v[0], v[1], v[2]], [v[3], v[4], v[5], v[6]]);
            assert!(
                solver.solve(&bad_pose).is_empty(),
                "{path}: pose entry {k} = {bad}"
            );
        }
    }
}

#[test]
fn inverse_kinematics_rejects_non_finite_input() {
    numeric_ik_rejects(&cylindrical::Robot, "cylindrical (generated)");
    numeric_ik_rejects(&panda::Robot, "panda (generated)");
    numeric_ik_rejects(&puma560::Robot, "puma560 (generated)");
    numeric_ik_rejects(&scara::Robot, "scara (generated)");
    numeric_ik_rejects(&stanford::Robot, "stanford (generated)");
    numeric_ik_rejects(&ur5::Robot, "ur5 (generated)");
    for name in [
        "cylindrical",
        "panda",
        "puma560",
        "scara",
        "stanford",
        "ur5",
    ] {
        numeric_ik_rejects(&runtime(name), &format!("{name} (runtime)"));
    }
    // Closed form: the generated constant and the runtime model's solver find no solution.
    closed_form_rejects(&puma560::IK, "puma560::IK");
    closed_form_rejects(&stanford::IK, "stanford::IK");
    closed_form_rejects(&ur5::IK, "ur5::IK");
    for name in ["puma560", "stanford", "ur5", "cylindrical"] {
        let solver = DecoupledIk::from_model(runtime(name).model()).unwrap();
        closed_form_rejects(&solver, name);
    }
    assert!(puma560::ik(&pose_with([f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0])).is_empty());
}

/// Asserts that `result` is the [`TrajectoryError::NonFinite`] naming `name`.
fn names<T: std::fmt::Debug>(result: Result<T, TrajectoryError>, name: &str, case: &str) {
    match result {
        Err(TrajectoryError::NonFinite { name: n, .. }) if n == name => {}
        other => panic!("{case}: expected NonFinite naming `{name}`, got {other:?}"),
    }
}

#[test]
fn trajectory_constructors_reject_non_finite_input_naming_it() {
    fn ok<T>(r: Result<T, TrajectoryError>) -> Result<(), TrajectoryError> {
        r.map(drop)
    }
    type Build = Box<dyn Fn(f64) -> Result<(), TrajectoryError>>;
    // (case, the argument's name in the error, the constructor with `x` for the argument)
    macro_rules! cases {
        ($x:ident; $($case:literal, $name:literal => $build:expr;)*) => {
            vec![$(($case, $name, Box::new(move |$x: f64| ok($build)) as Build)),*]
        };
    }
    let rest = Setpoint::rest;
    let cases = cases! { x;
        "Cubic::new t0", "t0" => Cubic::new(x, 1.0, 0.0, 0.0, 1.0, 0.0);
        "Cubic::new tf", "tf" => Cubic::new(0.0, x, 0.0, 0.0, 1.0, 0.0);
        "Cubic::new q0", "q0" => Cubic::new(0.0, 1.0, x, 0.0, 1.0, 0.0);
        "Cubic::new v0", "v0" => Cubic::new(0.0, 1.0, 0.0, x, 1.0, 0.0);
        "Cubic::new qf", "qf" => Cubic::new(0.0, 1.0, 0.0, 0.0, x, 0.0);
        "Cubic::new vf", "vf" => Cubic::new(0.0, 1.0, 0.0, 0.0, 1.0, x);
        "Cubic::rest_to_rest qf", "qf" => Cubic::rest_to_rest(0.0, 1.0, 0.0, x);
        "Quintic::new t0", "t0" => Quintic::new(x, 1.0, rest(0.0), rest(1.0));
        "Quintic::new tf", "tf" => Quintic::new(0.0, x, rest(0.0), rest(1.0));
        "Quintic::new q0", "q0" => Quintic::new(0.0, 1.0, rest(x), rest(1.0));
        "Quintic::new v0", "v0" => Quintic::new(0.0, 1.0, Setpoint::new(0.0, x, 0.0), rest(1.0));
        "Quintic::new a0", "a0" => Quintic::new(0.0, 1.0, Setpoint::new(0.0, 0.0, x), rest(1.0));
        "Quintic::new qf", "qf" => Quintic::new(0.0, 1.0, rest(0.0), rest(x));
        "Quintic::new vf", "vf" => Quintic::new(0.0, 1.0, rest(0.0), Setpoint::new(1.0, x, 0.0));
        "Quintic::new af", "af" => Quintic::new(0.0, 1.0, rest(0.0), Setpoint::new(1.0, 0.0, x));
        "Lspb::with_velocity t0", "t0" => Lspb::with_velocity(x, 1.0, 0.0, 1.0, 1.5);
        "Lspb::with_velocity tf", "tf" => Lspb::with_velocity(0.0, x, 0.0, 1.0, 1.5);
        "Lspb::with_velocity q0", "q0" => Lspb::with_velocity(0.0, 1.0, x, 1.0, 1.5);
        "Lspb::with_velocity qf", "qf" => Lspb::with_velocity(0.0, 1.0, 0.0, x, 1.5);
        "Lspb::with_velocity V", "V" => Lspb::with_velocity(0.0, 1.0, 0.0, 1.0, x);
        "Lspb::with_acceleration alpha", "alpha" => Lspb::with_acceleration(0.0, 1.0, 0.0, 1.0, x);
        "Lspb::with_acceleration q0", "q0" => Lspb::with_acceleration(0.0, 1.0, x, 1.0, 5.0);
        "Lspb::bang_bang t0", "t0" => Lspb::bang_bang(x, 0.0, 1.0, 2.0);
        "Lspb::bang_bang q0", "q0" => Lspb::bang_bang(0.0, x, 1.0, 2.0);
        "Lspb::bang_bang qf", "qf" => Lspb::bang_bang(0.0, 0.0, x, 2.0);
        "Lspb::bang_bang amax", "amax" => Lspb::bang_bang(0.0, 0.0, 1.0, x);
        "Lspb::velocity_limited t0", "t0" => Lspb::velocity_limited(x, 0.0, 1.0, 1.0, 2.0);
        "Lspb::velocity_limited vmax", "vmax" => Lspb::velocity_limited(0.0, 0.0, 1.0, x, 2.0);
        "Lspb::velocity_limited amax", "amax" => Lspb::velocity_limited(0.0, 0.0, 1.0, 1.0, x);
        "bang_bang_duration q0", "q0" => bang_bang_duration(x, 1.0, 2.0);
        "bang_bang_duration amax", "amax" => bang_bang_duration(0.0, 1.0, x);
        "velocity_limited_duration qf", "qf" => velocity_limited_duration(0.0, x, 1.0, 2.0);
        "velocity_limited_duration vmax", "vmax" => velocity_limited_duration(0.0, 1.0, x, 2.0);
        "velocity_limited_duration amax", "amax" => velocity_limited_duration(0.0, 1.0, 1.0, x);
        "Synchronized::cubic vf", "vf" =>
            Synchronized::cubic(0.0, 1.0, &[0.0; 2], &[0.0; 2], &[1.0; 2], &[0.0, x]);
        "Synchronized::quintic af", "af" => Synchronized::quintic(
            0.0, 1.0, &[rest(0.0); 2], &[rest(1.0), Setpoint::new(1.0, 0.0, x)]);
        "Synchronized::quintic_rest_to_rest tf", "tf" =>
            Synchronized::quintic_rest_to_rest(0.0, x, &[0.0; 2], &[1.0; 2]);
        "Synchronized::lspb_velocity V", "V" =>
            Synchronized::lspb_velocity(0.0, 1.0, &[0.0; 2], &[1.0; 2], &[1.5, x]);
        "Synchronized::lspb_acceleration alpha", "alpha" =>
            Synchronized::lspb_acceleration(0.0, 1.0, &[0.0; 2], &[1.0; 2], &[5.0, x]);
        "Synchronized::bang_bang t0", "t0" =>
            Synchronized::bang_bang(x, &[0.0; 2], &[1.0; 2], &[2.0; 2]);
        "Synchronized::bang_bang q0", "q0" =>
            Synchronized::bang_bang(0.0, &[0.0, x], &[1.0; 2], &[2.0; 2]);
        "Synchronized::bang_bang amax", "amax" =>
            Synchronized::bang_bang(0.0, &[0.0; 2], &[1.0; 2], &[x, 2.0]);
        "Synchronized::velocity_limited vmax", "vmax" =>
            Synchronized::velocity_limited(0.0, &[0.0; 2], &[1.0; 2], &[1.0, x], &[2.0; 2]);
        "Synchronized::velocity_limited qf", "qf" =>
            Synchronized::velocity_limited(0.0, &[0.0; 2], &[x, 1.0], &[1.0; 2], &[2.0; 2]);
        "CubicSpline::new times", "time" =>
            CubicSpline::new(&[0.0, x, 2.0], &[[0.0], [1.0], [0.0]], SplineEnds::Natural);
        "CubicSpline::new points", "q" =>
            CubicSpline::new(&[0.0, 1.0, 2.0], &[[0.0], [x], [0.0]], SplineEnds::AtRest);
        "CubicSpline::new start velocities", "start velocities" => CubicSpline::new(
            &[0.0, 1.0], &[[0.0], [1.0]], SplineEnds::Clamped { start: &[x], end: &[0.0] });
        "CubicSpline::new end velocities", "end velocities" => CubicSpline::new(
            &[0.0, 1.0], &[[0.0], [1.0]], SplineEnds::Clamped { start: &[0.0], end: &[x] });
        "BlendedSegments::from_times times", "time" =>
            BlendedSegments::from_times(&[0.0, 2.0, x], &[[0.0], [1.0], [0.0]], 0.2);
        "BlendedSegments::from_times points", "q" =>
            BlendedSegments::from_times(&[0.0, 2.0, 4.0], &[[0.0], [1.0], [x]], 0.2);
        "BlendedSegments::from_times tacc", "tacc" =>
            BlendedSegments::from_times(&[0.0, 2.0, 4.0], &[[0.0], [1.0], [0.0]], x);
        "BlendedSegments::from_limits t0", "t0" =>
            BlendedSegments::from_limits(x, &[[0.0], [1.0]], &[1.0], &[1.0]);
        "BlendedSegments::from_limits points", "q" =>
            BlendedSegments::from_limits(0.0, &[[0.0], [x]], &[1.0], &[1.0]);
        "BlendedSegments::from_limits vmax", "vmax" =>
            BlendedSegments::from_limits(0.0, &[[0.0], [1.0]], &[x], &[1.0]);
        "BlendedSegments::from_limits amax", "amax" =>
            BlendedSegments::from_limits(0.0, &[[0.0], [1.0]], &[1.0], &[x]);
    };
    for (case, name, build) in &cases {
        assert!(
            [0.0, 0.5, 1.0, 1.5, 2.0, 3.0, 5.0]
                .into_iter()
                .any(|x| build(x).is_ok()),
            "{case}: some finite value works"
        );
        for bad in NON_FINITE {
            names(build(bad), name, &format!("{case} = {bad}"));
        }
    }
}

/// Asserts that `err` names `name` and says what is wrong with a non-finite value.
fn rejects(err: PlanError, name: &str, case: &str) {
    let text = err.to_string();
    assert!(
        text.contains(name) && (text.contains("finite") || text.contains("NaN")),
        "{case}: expected an error naming `{name}` as not finite, got: {text}"
    );
}

fn planar_checker(obstacles: Vec<Obstacle>) -> CollisionChecker<'static, planar_elbow::Robot> {
    CollisionChecker::new(&planar_elbow::Robot, Scene::new(obstacles).unwrap()).unwrap()
}

#[test]
fn planners_reject_non_finite_input_naming_it() {
    for bad in NON_FINITE {
        // Scenes.
        let obstacles: [(&str, Obstacle); 9] = [
            ("centre", Obstacle::sphere([1.0, bad, 0.0], 0.1)),
            ("radius", Obstacle::sphere([1.0, 0.0, 0.0], bad)),
            ("position", Obstacle::cuboid([bad, 0.0, 0.0], [0.1; 3])),
            (
                "half extent",
                Obstacle::cuboid([1.0, 0.0, 0.0], [0.1, bad, 0.1]),
            ),
            (
                "orientation",
                Obstacle::Box {
                    pose: pose_with([1.0, 0.0, 0.0], [bad, 0.0, 0.0, 0.0]),
                    half_extents: [0.1; 3],
                },
            ),
            (
                "end",
                Obstacle::capsule([bad, 0.0, 0.0], [1.0, 0.0, 0.0], 0.1),
            ),
            (
                "end",
                Obstacle::capsule([0.0, 0.0, 0.0], [1.0, 0.0, bad], 0.1),
            ),
            ("radius", Obstacle::capsule([0.0; 3], [1.0, 0.0, 0.0], bad)),
            ("radius", Obstacle::capsule([0.0; 3], [0.0; 3], bad)),
        ];
        for (name, obstacle) in obstacles {
            let err =
                Scene::new(vec![Obstacle::sphere([5.0, 0.0, 0.0], 0.1), obstacle]).unwrap_err();
            assert!(matches!(err, PlanError::InvalidObstacle { index: 1, .. }));
            rejects(err, name, &format!("obstacle {name} = {bad}"));
        }

        // The roadmap.
        let mut checker = planar_checker(vec![Obstacle::sphere([0.0, 1.6, 0.0], 0.2)]);
        type SetPrm = fn(&mut PrmConfig, f64);
        let settings: [(&str, SetPrm); 2] = [
            ("resolution", |c, x| c.resolution = x),
            ("resample_radius", |c, x| c.resample_radius = x),
        ];
        for (name, set) in settings {
            let mut config = PrmConfig::default();
            set(&mut config, bad);
            let err = Prm::new(&mut checker, config, 1).err().unwrap();
            rejects(err, name, &format!("PrmConfig::{name} = {bad}"));
        }
        let (start, goal) = (SVector::from([0.3, 0.2]), SVector::from([2.8, -0.2]));
        for j in 0..2 {
            let mut prm = Prm::new(&mut checker, PrmConfig::default(), 1).unwrap();
            let err = prm.query(&with::<planar_elbow::Robot>(&start, j, bad), &goal);
            rejects(
                err.unwrap_err(),
                "start",
                &format!("Prm::query start[{j}] = {bad}"),
            );
            let err = prm.query(&start, &with::<planar_elbow::Robot>(&goal, j, bad));
            rejects(
                err.unwrap_err(),
                "goal",
                &format!("Prm::query goal[{j}] = {bad}"),
            );
        }
        let err = checker.check_configuration(&[0.1, bad]).unwrap_err();
        assert!(err.contains("joint 2") && err.contains("finite"), "{err}");

        // The workspace field.
        let field = WorkspaceField::uniform(2, 1.0, 0.5, 0.01, 0.3);
        type SetField = fn(&mut WorkspaceField, f64);
        let gains: [(&str, SetField); 4] = [
            ("zeta", |f, x| f.zeta[1] = x),
            ("d", |f, x| f.d = x),
            ("eta", |f, x| f.eta = x),
            ("rho0", |f, x| f.rho0 = x),
        ];
        for (name, set) in gains {
            let mut f = field.clone();
            set(&mut f, bad);
            let err = WorkspacePlanner::new(&mut checker, f, 0.02).err().unwrap();
            rejects(err, name, &format!("WorkspaceField::{name} = {bad}"));
        }
        let err = WorkspacePlanner::new(&mut checker, field.clone(), bad)
            .err()
            .unwrap();
        rejects(
            err,
            "resolution",
            &format!("WorkspacePlanner resolution = {bad}"),
        );
        let mut planner = WorkspacePlanner::new(&mut checker, field.clone(), 0.02).unwrap();
        for j in 0..2 {
            let err = planner.plan(
                &with::<planar_elbow::Robot>(&start, j, bad),
                &goal,
                &DescentParams::default(),
            );
            rejects(
                err.unwrap_err(),
                "start",
                &format!("workspace plan start[{j}] = {bad}"),
            );
            let err = planner.plan(
                &start,
                &with::<planar_elbow::Robot>(&goal, j, bad),
                &DescentParams::default(),
            );
            rejects(
                err.unwrap_err(),
                "goal",
                &format!("workspace plan goal[{j}] = {bad}"),
            );
        }
        type SetParams = fn(&mut DescentParams, f64);
        let params: [(&str, SetParams); 4] = [
            ("step", |p, x| p.step = x),
            ("tolerance", |p, x| p.tolerance = x),
            ("min_decrease", |p, x| p.min_decrease = x),
            ("walk_step", |p, x| p.walk_step = x),
        ];
        for (name, set) in params {
            let mut p = DescentParams::default();
            set(&mut p, bad);
            let err = planner.plan(&start, &goal, &p).unwrap_err();
            rejects(
                err,
                name,
                &format!("DescentParams::{name} = {bad} (workspace)"),
            );
        }

        // The configuration-space field, unbounded and bounded.
        let regions = || {
            vec![ConvexRegion::Ball {
                center: vec![0.5, 0.05],
                radius: 0.15,
            }]
        };
        let cspace = CSpaceField {
            zeta: 1.0,
            d: 0.5,
            eta: 1e-3,
            rho0: 0.2,
        };
        let plan = |field: &CSpaceField, start: &[f64], goal: &[f64], p: &DescentParams| {
            potential::plan(
                field,
                ConvexCSpaceObstacles::new(2, regions()).unwrap(),
                start,
                goal,
                p,
            )
        };
        let p = DescentParams::default();
        assert!(plan(&cspace, &[0.0, 0.0], &[1.0, 0.0], &p).is_ok());
        type SetCSpace = fn(&mut CSpaceField, f64);
        let gains: [(&str, SetCSpace); 4] = [
            ("zeta", |f, x| f.zeta = x),
            ("d", |f, x| f.d = x),
            ("eta", |f, x| f.eta = x),
            ("rho0", |f, x| f.rho0 = x),
        ];
        for (name, set) in gains {
            let mut f = cspace;
            set(&mut f, bad);
            let err = plan(&f, &[0.0, 0.0], &[1.0, 0.0], &p).unwrap_err();
            rejects(err, name, &format!("CSpaceField::{name} = {bad}"));
        }
        for j in 0..2 {
            let mut q = [0.0, 0.0];
            q[j] = bad;
            rejects(
                plan(&cspace, &q, &[1.0, 0.0], &p).unwrap_err(),
                "start",
                &format!("potential::plan start[{j}] = {bad}"),
            );
            rejects(
                plan(&cspace, &[0.0, 0.0], &q, &p).unwrap_err(),
                "goal",
                &format!("potential::plan goal[{j}] = {bad}"),
            );
        }
        for (name, set) in params {
            let mut p = DescentParams::default();
            set(&mut p, bad);
            let err = plan(&cspace, &[0.0, 0.0], &[1.0, 0.0], &p).unwrap_err();
            rejects(
                err,
                name,
                &format!("DescentParams::{name} = {bad} (C-space)"),
            );
        }
        let bad_regions = [
            ConvexRegion::Ball {
                center: vec![bad, 0.0],
                radius: 0.1,
            },
            ConvexRegion::Ball {
                center: vec![0.5, 0.0],
                radius: bad,
            },
            ConvexRegion::Box {
                lower: vec![0.0, bad],
                upper: vec![1.0, 1.0],
            },
            ConvexRegion::Box {
                lower: vec![0.0, 0.0],
                upper: vec![bad, 1.0],
            },
        ];
        for region in bad_regions {
            let err = ConvexCSpaceObstacles::new(2, vec![region.clone()]).unwrap_err();
            assert!(err.to_string().contains("finite"), "{region:?}: {err}");
        }
        let err = ConvexCSpaceObstacles::new(2, regions())
            .unwrap()
            .with_bounds(vec![[-1.0, 1.0], [f64::NAN, 1.0]])
            .unwrap_err();
        rejects(err, "bounds", "bounds NaN");

        // The C-space grid as obstacles.
        let grid = CSpaceGrid::compute(&mut checker, [8, 8]).unwrap();
        let err = grid.obstacles(&mut checker, bad).err().unwrap();
        rejects(
            err,
            "resolution",
            &format!("CSpaceGrid::obstacles resolution = {bad}"),
        );
    }
}

/// Collision queries decide: a configuration that is not finite is never free, and never
/// has a finite clearance.
fn collision_queries<A: Arm>(arm: &A, obstacles: Vec<Obstacle>, path: &str)
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let mut checker = CollisionChecker::new(arm, Scene::new(obstacles).unwrap()).unwrap();
    let (a, b) = (config(arm, 0.0), config(arm, 0.05));
    assert!(
        checker.is_free(&a, 0.0),
        "{path}: the finite configuration is free"
    );
    assert!(
        checker.motion_is_free(&a, &b, 0.02),
        "{path}: the finite motion is free"
    );
    assert!(checker.clearance(&a).is_finite(), "{path}");
    for bad in NON_FINITE {
        for j in 0..arm.dof() {
            let q = with::<A>(&a, j, bad);
            let case = format!("{path}: q[{j}] = {bad}");
            assert!(!checker.is_free(&q, 0.0), "{case}: is_free");
            assert!(checker.in_collision(&q), "{case}: in_collision");
            assert!(checker.clearance(&q).is_nan(), "{case}: clearance");
            assert!(
                !checker.motion_is_free(&a, &q, 0.02),
                "{case}: motion to it"
            );
            assert!(
                !checker.motion_is_free(&q, &b, 0.02),
                "{case}: motion from it"
            );
            let polyline = [a.clone(), b.clone(), q.clone()];
            assert!(
                !checker.path_is_free(&polyline, 0.02),
                "{case}: path_is_free"
            );
            assert!(
                !checker.path_touches_nothing(&polyline, 0.02),
                "{case}: path_touches_nothing"
            );
        }
        assert!(
            !checker.motion_is_free(&a, &b, bad),
            "{path}: resolution {bad}"
        );
        assert!(
            !checker.path_touches_nothing(&[a.clone(), b.clone()], bad),
            "{path}: {bad}"
        );
        let p = dhgen::nalgebra::Point3::new(bad, 0.0, 0.0);
        let distance = checker.scene().distance_to_segment(&p, &p);
        assert!(
            distance.is_nan(),
            "{path}: distance_to_segment from {bad}: {distance}"
        );
    }
    for resolution in [0.0, -0.02] {
        assert!(
            !checker.motion_is_free(&a, &b, resolution),
            "{path}: resolution {resolution}"
        );
    }
    // The workspace potential is a numeric evaluation: the propagation law.
    let n = arm.dof();
    let field = WorkspaceField::uniform(n, 1.0, 0.5, 0.01, 0.3);
    let mut planner = WorkspacePlanner::new(&mut checker, field, 0.02).unwrap();
    let mut potential = |q: &JointVector<A>| {
        let mut out = vec![0.0; n + 1];
        out[n] = planner.potential_towards(q, &b, &mut out[..n]);
        Some(out)
    };
    assert!(
        potential(&a).iter().flatten().all(|x| x.is_finite()),
        "{path}"
    );
    for j in 0..n {
        let refs = [
            potential(&with::<A>(&a, j, a[j] + 0.1)),
            potential(&with::<A>(&a, j, a[j] - 0.1)),
        ];
        for bad in NON_FINITE {
            let out = potential(&with::<A>(&a, j, bad));
            let context = format!("{path}: workspace torques and potential at q[{j}] = {bad}");
            check_law(&context, &out, [&refs[0], &refs[1]]);
        }
    }
}

#[test]
fn collision_queries_never_call_a_non_finite_configuration_free() {
    let far = || {
        vec![
            Obstacle::sphere([4.0, 4.0, 0.0], 0.3),
            Obstacle::cuboid([-4.0, 0.0, 0.0], [0.2, 0.3, 0.4]),
            Obstacle::capsule([0.0, -4.0, -1.0], [0.0, -4.0, 1.0], 0.1),
        ]
    };
    collision_queries(&planar_elbow::Robot, far(), "planar_elbow (generated)");
    collision_queries(&runtime("planar_elbow"), far(), "planar_elbow (runtime)");
    collision_queries(&puma560::Robot, far(), "puma560 (generated)");
    collision_queries(&runtime("puma560"), far(), "puma560 (runtime)");
}

/// Numeric IK from a seed 1e10 rad (or m) away, and towards a target 1e10 m away: an answer
/// or an error within the iteration cap, never a hang.
fn numeric_ik_terminates<A: Arm>(arm: &A, path: &str)
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    let ik = NumericIk::default();
    let target = arm.fk(&config(arm, 0.3));
    let huge = JointVector::<A>::from_element_generic(arm.dim(), U1, HUGE);
    for (seed, target) in [
        (huge, target),
        (
            config(arm, 0.0),
            pose_with([HUGE, 0.0, -HUGE], [1.0, 0.0, 0.0, 0.0]),
        ),
    ] {
        match ik.solve(arm, &target, &seed) {
            Ok(s) => {
                let (dp, dr) = dhgen::ik::pose_error(&arm.fk(&s.q), &target);
                assert!(dp <= 1e-9 && dr <= 1e-9, "{path}: a wrong solution");
                assert!(s.iterations <= ik.max_iterations, "{path}");
            }
            Err(
                IkError::NotConverged { iterations, .. }
                | IkError::Singular { iterations, .. }
                | IkError::LocalMinimum { iterations, .. },
            ) => assert!(iterations <= ik.max_iterations, "{path}"),
            Err(e) => panic!("{path}: {e}"),
        }
    }
}

#[test]
fn huge_angles_terminate() {
    let started = Instant::now();
    // Numeric evaluations stay finite, and the two paths agree to the digits that 1e10 keeps.
    fn finite_and_agree<A: ArmDynamics>(arm: &A, robot: &Robot, path: &str)
    where
        DefaultAllocator: ArmAllocator<A::Dof>,
    {
        let q = JointVector::<A>::from_fn_generic(arm.dim(), U1, |j, _| {
            HUGE * if j % 2 == 0 { 1.0 } else { -1.0 } + j as f64
        });
        let qr = DVector::from_column_slice(q.as_slice());
        let pairs: [(&str, Vec<f64>, Vec<f64>); 3] = [
            (
                "fk",
                arm.fk(&q).to_homogeneous().as_slice().to_vec(),
                robot.fk(&qr).to_homogeneous().as_slice().to_vec(),
            ),
            (
                "jacobian",
                arm.jacobian(&q).as_slice().to_vec(),
                robot.jacobian(&qr).as_slice().to_vec(),
            ),
            (
                "gravity",
                arm.gravity(&q).as_slice().to_vec(),
                robot.gravity(&qr).as_slice().to_vec(),
            ),
        ];
        for (name, generated, runtime) in pairs {
            for (g, r) in generated.iter().zip(&runtime) {
                assert!(g.is_finite() && r.is_finite(), "{path}: {name}");
                assert!(
                    (g - r).abs() <= 1e-4 * (1.0 + r.abs()),
                    "{path}: {name} {g} vs {r}"
                );
            }
        }
    }
    finite_and_agree(&panda::Robot, &runtime("panda"), "panda");
    finite_and_agree(&puma560::Robot, &runtime("puma560"), "puma560");
    finite_and_agree(&stanford::Robot, &runtime("stanford"), "stanford");
    finite_and_agree(&ur5::Robot, &runtime("ur5"), "ur5");

    // Angles wrap into (−π, π], however large (exactly modulo the f64 nearest 2π).
    for x in [HUGE, -HUGE, 1e17, 1e300, -1e300, f64::MAX] {
        let y = wrap_angle(x);
        assert!(-PI < y && y <= PI, "wrap_angle({x}) = {y}");
    }

    // Inverse kinematics.
    numeric_ik_terminates(&puma560::Robot, "puma560 (generated)");
    numeric_ik_terminates(&runtime("puma560"), "puma560 (runtime)");
    numeric_ik_terminates(&panda::Robot, "panda (generated)");
    numeric_ik_terminates(&runtime("panda"), "panda (runtime)");
    numeric_ik_terminates(&stanford::Robot, "stanford (generated)");
    numeric_ik_terminates(&cylindrical::Robot, "cylindrical (generated)");
    let q = SVector::from([HUGE, -HUGE, HUGE, 1.0, -HUGE, HUGE]);
    let pose = puma560::fk(&q);
    let solutions = puma560::ik(&pose);
    assert!(
        !solutions.is_empty(),
        "the pose of a 1e10 rad configuration is reachable"
    );
    for s in &solutions {
        let (dp, dr) = dhgen::ik::pose_error(&puma560::fk(s), &pose);
        assert!(dp < 1e-9 && dr < 1e-9);
    }
    assert!(puma560::ik(&pose_with([HUGE, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0])).is_empty());

    // Collision checking: a motion of 1e10 rad is not checked sample by sample.
    let mut checker = planar_checker(vec![Obstacle::sphere([0.0, 1.6, 0.0], 0.2)]);
    let a = SVector::from([0.3, 0.2]);
    for j in 0..2 {
        let b = with::<planar_elbow::Robot>(&a, j, HUGE);
        // More samples than MAX_MOTION_SAMPLES: not free, unchecked.
        assert!(!checker.motion_is_free(&a, &b, 0.02));
        assert!(!checker.path_touches_nothing(&[a, b], 0.02));
        // The configuration itself is an ordinary one.
        assert_eq!(
            checker.is_free(&b, 0.0),
            checker.is_free(&b.map(wrap_angle), 0.0)
        );
    }
    assert!(!checker.motion_is_free(&a, &SVector::from([0.4, 0.1]), 1e-300));
    assert!(checker.motion_is_free(&a, &SVector::from([0.4, 0.1]), 0.02));
    let mut puma_checker = CollisionChecker::new(
        &puma560::Robot,
        Scene::new(vec![Obstacle::sphere([0.6, 0.0, 0.3], 0.1)]).unwrap(),
    )
    .unwrap();
    let p = config(&puma560::Robot, 0.0);
    assert!(!puma_checker.motion_is_free(&p, &p.map(|x| x + HUGE), 0.02));

    // Planners: 1e10 is outside every joint range; in an unbounded C-space the descent
    // runs out of iterations.
    let goal = SVector::from([2.8, -0.2]);
    let mut prm = Prm::new(&mut checker, PrmConfig::default(), 1).unwrap();
    for j in 0..2 {
        let err = prm
            .query(&with::<planar_elbow::Robot>(&a, j, HUGE), &goal)
            .unwrap_err();
        assert!(
            matches!(err, PlanError::InvalidConfiguration { which: "start", .. }),
            "{err}"
        );
    }
    let mut planner = WorkspacePlanner::new(
        &mut checker,
        WorkspaceField::uniform(2, 1.0, 0.5, 0.01, 0.3),
        0.02,
    )
    .unwrap();
    let err = planner
        .plan(
            &SVector::from([HUGE, 0.0]),
            &goal,
            &DescentParams::default(),
        )
        .unwrap_err();
    assert!(
        matches!(err, PlanError::InvalidConfiguration { which: "start", .. }),
        "{err}"
    );
    let field = CSpaceField {
        zeta: 1.0,
        d: 0.5,
        eta: 1e-3,
        rho0: 0.2,
    };
    let obstacles = || {
        ConvexCSpaceObstacles::new(
            2,
            vec![ConvexRegion::Ball {
                center: vec![0.5, 0.05],
                radius: 0.15,
            }],
        )
        .unwrap()
    };
    let found = potential::plan(
        &field,
        obstacles(),
        &[HUGE, 0.0],
        &[0.0, 0.0],
        &DescentParams::default(),
    );
    assert!(
        matches!(
            found,
            Err(PlanError::IterationLimit { .. } | PlanError::LocalMinimum { .. })
        ),
        "{found:?}"
    );
    let found = potential::plan(
        &field,
        obstacles(),
        &[0.0, 0.0],
        &[1.0, -HUGE],
        &DescentParams::default(),
    );
    assert!(
        matches!(
            found,
            Err(PlanError::IterationLimit { .. } | PlanError::LocalMinimum { .. })
        ),
        "{found:?}"
    );

    // Trajectories over 1e10 rad, and for 1e10 s.
    let cubic = Cubic::rest_to_rest(0.0, 1.0, -HUGE, HUGE).unwrap();
    assert_eq!(cubic.eval(1.0).q, HUGE);
    let trapezoid = Lspb::velocity_limited(0.0, 0.0, HUGE, 1.0, 2.0).unwrap();
    assert!((trapezoid.duration() - (HUGE + 0.5)).abs() < 1e-3);
    assert_eq!(trapezoid.eval(trapezoid.end_time()).q, HUGE);
    let sync =
        Synchronized::velocity_limited(0.0, &[0.0, 1.0], &[HUGE, -HUGE], &[1.0; 2], &[1.0; 2])
            .unwrap();
    assert!(
        sync.eval(0.5 * MultiProfile::end_time(&sync))
            .iter()
            .all(|s| s.q.is_finite())
    );
    let spline = CubicSpline::new(
        &[0.0, 1.0, HUGE],
        &[[0.0], [HUGE], [-HUGE]],
        SplineEnds::AtRest,
    )
    .unwrap();
    let mut out = [Setpoint::default()];
    spline.eval_into(0.5 * HUGE, &mut out).unwrap();
    assert!(out[0].q.is_finite());
    let segments = BlendedSegments::from_limits(
        0.0,
        &[[0.0, HUGE], [HUGE, 0.0], [-HUGE, 1.0]],
        &[1.0, 2.0],
        &[1.0, 1.0],
    )
    .unwrap();
    segments
        .eval_into(
            MultiProfile::end_time(&segments),
            &mut [Setpoint::default(); 2],
        )
        .unwrap();
    assert!(started.elapsed() < Duration::from_secs(10));
}

/// Finite parameters large enough to overflow the arithmetic inside a planner are rejected
/// or handled, never a panic.
#[test]
fn huge_parameters_are_rejected_or_handled() {
    let mut checker = planar_checker(vec![Obstacle::sphere([0.0, 1.6, 0.0], 0.2)]);
    let (start, goal) = (SVector::from([0.3, 0.2]), SVector::from([0.6, -0.2]));
    // A time budget no clock can reach is no budget.
    let config = PrmConfig {
        initial_nodes: 20,
        time_budget: Some(Duration::MAX),
        ..PrmConfig::default()
    };
    let mut prm = Prm::new(&mut checker, config, 3).unwrap();
    assert!(prm.query(&start, &goal).is_ok());
    // A resampling box or random walk wider than f64 can span.
    let config = PrmConfig {
        resample_radius: f64::MAX,
        ..PrmConfig::default()
    };
    rejects_large(Prm::new(&mut checker, config, 3).err(), "resample_radius");
    let params = DescentParams {
        walk_step: f64::MAX,
        ..DescentParams::default()
    };
    let mut planner = WorkspacePlanner::new(
        &mut checker,
        WorkspaceField::uniform(2, 1.0, 0.5, 0.01, 0.3),
        0.02,
    )
    .unwrap();
    rejects_large(planner.plan(&start, &goal, &params).err(), "walk_step");
    // A grid too large to count.
    let err = CSpaceGrid::compute(&mut checker, [usize::MAX, 2]).unwrap_err();
    assert!(err.to_string().contains("cells"), "{err}");
    // One a usize counts but memory does not hold (2⁴⁰ cells aborted the process).
    let err = CSpaceGrid::compute(&mut checker, [1 << 20, 1 << 20]).unwrap_err();
    assert!(err.to_string().contains("MAX_CELLS"), "{err}");
}

fn rejects_large(err: Option<PlanError>, name: &str) {
    let err = err.unwrap_or_else(|| panic!("{name} = f64::MAX was accepted"));
    assert!(
        matches!(err, PlanError::InvalidParameter { name: n, .. } if n == name),
        "{err}"
    );
}

/// The runtime path panics on a joint vector of the wrong length, naming the function and
/// the argument (and both lengths).
mod wrong_length_panics_naming_function_and_argument {
    use crate::support::runtime;
    use dhgen::Arm;
    use dhgen::nalgebra::{DVector, Vector6};
    use dhgen::velocity::{Damping, inverse_acceleration, inverse_velocity, jacobian_dot};

    fn zeros(n: usize) -> DVector<f64> {
        DVector::zeros(n)
    }

    // Each case on the 6-joint PUMA 560: test name, the start of the message, the call.
    macro_rules! panics {
        ($($test:ident, $expected:literal, |$r:ident| $call:expr;)*) => {$(
            #[test]
            #[should_panic(expected = $expected)]
            fn $test() {
                let $r = runtime("puma560");
                let _ = $call;
            }
        )*};
    }

    panics! {
        fk_q, "dhgen::Robot::fk: `q` has length 5, expected 6",
            |r| r.fk(&[0.0; 5]);
        frames_q, "dhgen::Robot::frames: `q` has length 7, expected 6",
            |r| r.frames(&[0.0; 7]);
        jacobian_q, "dhgen::Robot::jacobian: `q` has length 0, expected 6",
            |r| r.jacobian(&[0.0; 0]);
        mass_matrix_q, "dhgen::Robot::mass_matrix: `q` has length 5",
            |r| r.mass_matrix(&[0.0; 5]);
        christoffel_q, "dhgen::Robot::christoffel: `q` has length 5",
            |r| r.christoffel(&[0.0; 5]);
        gravity_q, "dhgen::Robot::gravity: `q` has length 5",
            |r| r.gravity(&vec![0.0; 5]);
        coriolis_q, "dhgen::Robot::coriolis: `q` has length 5",
            |r| r.coriolis(&[0.0; 5], &[0.0; 6]);
        coriolis_qd, "dhgen::Robot::coriolis: `qd` has length 5",
            |r| r.coriolis(&[0.0; 6], &[0.0; 5]);
        inverse_dynamics_q, "dhgen::Robot::inverse_dynamics: `q` has length 5",
            |r| r.inverse_dynamics(&[0.0; 5], &[0.0; 6], &[0.0; 6]);
        inverse_dynamics_qd, "dhgen::Robot::inverse_dynamics: `qd` has length 5",
            |r| r.inverse_dynamics(&[0.0; 6], &[0.0; 5], &[0.0; 6]);
        inverse_dynamics_qdd, "dhgen::Robot::inverse_dynamics: `qdd` has length 5",
            |r| r.inverse_dynamics(&[0.0; 6], &[0.0; 6], &[0.0; 5]);
        bias_q, "dhgen::Robot::bias: `q` has length 5",
            |r| r.bias(&[0.0; 5], &[0.0; 6]);
        bias_qd, "dhgen::Robot::bias: `qd` has length 7",
            |r| r.bias(&[0.0; 6], &[0.0; 7]);
        forward_dynamics_q, "dhgen::Robot::forward_dynamics: `q` has length 5",
            |r| r.forward_dynamics(&[0.0; 5], &[0.0; 6], &[0.0; 6]);
        forward_dynamics_qd, "dhgen::Robot::forward_dynamics: `qd` has length 5",
            |r| r.forward_dynamics(&[0.0; 6], &[0.0; 5], &[0.0; 6]);
        forward_dynamics_tau, "dhgen::Robot::forward_dynamics: `tau` has length 5",
            |r| r.forward_dynamics(&[0.0; 6], &[0.0; 6], &[0.0; 5]);
        arm_trait_fk_q, "dhgen::Robot::fk: `q` has length 5, expected 6",
            |r| Arm::fk(&r, &zeros(5));
        arm_trait_jdot_qdot_qd,
            "dhgen::velocity::jdot_qdot_from_jacobian: `qd` has length 5, expected 6",
            |r| r.jdot_qdot(&zeros(6), &zeros(5));
        jacobian_dot_qd, "dhgen::velocity::jacobian_dot: `qd` has length 7, expected 6",
            |r| jacobian_dot(&r, &zeros(6), &zeros(7));
        inverse_acceleration_qd,
            "dhgen::velocity::inverse_acceleration: `qd` has length 5, expected 6",
            |r| inverse_acceleration(
                &r, &zeros(6), &zeros(5), &Vector6::zeros(), None, &Damping::default());
        inverse_velocity_null, "dhgen::velocity::inverse_velocity: `null` has length 5, expected 6",
            |r| inverse_velocity(
                &r, &zeros(6), &Vector6::zeros(), Some(&zeros(5)), &Damping::default());
    }
}
