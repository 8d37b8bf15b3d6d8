//! The inertial parameters and the regressor (`dhgen::parameters`): `Y π = τ` on every
//! robot, the base parameters `Y_b π_b = τ`, their count against an independent rank
//! computation, and the planar elbow's regrouping against the textbook's closed form.

use dhgen::Robot;
use dhgen::parameters::PhysicalConsistency;
use nalgebra::{DMatrix, DVector};

/// Every description of the repository with mass properties, and the URDF fixtures.
fn robots() -> Vec<(String, Robot)> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut out = Vec::new();
    for p in crate::support::description_paths() {
        let r = Robot::from_toml_file(&p).unwrap();
        // The 17-joint snake is covered by the generator tests; here it would only be slow.
        if r.has_dynamics() && r.dof() <= 12 {
            out.push((p.file_stem().unwrap().to_string_lossy().into_owned(), r));
        }
    }
    for (file, tip) in [
        ("panda.urdf", "panda_hand"),
        ("random_2.urdf", "link_7"),
        ("random_3.urdf", "tool"),
    ] {
        let path = root.join("tests/data/urdf").join(file);
        let options = dhgen::model::urdf::UrdfOptions {
            tip: Some(tip.into()),
            ..Default::default()
        };
        let r = dhgen::model::urdf::read_file(&path, &options).unwrap();
        out.push((file.to_string(), Robot::from_model(r.model)));
    }
    out
}

/// A seeded state within the joint limits.
fn state(robot: &Robot, seed: u64) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let mut x = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        (x >> 11) as f64 / (1u64 << 53) as f64
    };
    let q = robot
        .chain()
        .bodies
        .iter()
        .map(|b| match b.limits {
            Some([lo, hi]) => lo + (hi - lo) * next(),
            None => (2.0 * next() - 1.0) * 3.0,
        })
        .collect();
    let n = robot.dof();
    let qd = (0..n).map(|_| 4.0 * next() - 2.0).collect();
    let qdd = (0..n).map(|_| 4.0 * next() - 2.0).collect();
    (q, qd, qdd)
}

fn close(what: &str, got: &DVector<f64>, want: &DVector<f64>, tol: f64) -> f64 {
    let scale = want.amax().max(1.0);
    let err = (got - want).amax() / scale;
    assert!(err <= tol, "{what}: {got} vs {want}: {err:e}");
    err
}

/// A seeded stream of standard normal numbers (xorshift, Box–Muller).
fn gaussians(seed: u64) -> impl FnMut() -> f64 {
    let mut x = seed;
    let mut uniform = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        ((x >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    move || {
        let (u, v) = (uniform(), uniform());
        (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
    }
}

#[test]
fn regressor_times_parameters_is_inverse_dynamics() {
    for (name, robot) in robots() {
        let pi = robot.parameters();
        assert_eq!(pi.len(), robot.parameter_count());
        assert_eq!(robot.parameter_names().len(), pi.len());
        let base = robot.base_parameters();
        let pi_b = base.reduce(&pi);
        let (mut worst, mut worst_b) = (0.0f64, 0.0f64);
        for seed in 0..20 {
            let (q, qd, qdd) = state(&robot, seed);
            let tau = robot.inverse_dynamics(&q[..], &qd[..], &qdd[..]);
            let y = robot.regressor(&q[..], &qd[..], &qdd[..]);
            worst = worst.max(close(&name, &(&y * &pi), &tau, 1e-12));
            let yb = base.base_regressor(&y);
            worst_b = worst_b.max(close(&name, &(&yb * &pi_b), &tau, 1e-12));
        }
        println!(
            "{name}: {} parameters, {} base; Y π = τ to {worst:.1e}, Y_b π_b = τ to {worst_b:.1e}",
            pi.len(),
            base.count()
        );
    }
}

/// Identification (`dhgen::identification`) on every robot, from its own inverse dynamics at
/// seeded states: without noise the least-squares estimate is its base parameters; with
/// Gaussian torque noise of known σ_j on joint j, rows weighted by 1/σ_j, every parameter is
/// within five predicted standard deviations of them, and the residual variance within five of
/// its standard deviations of 1 (what weights of the true noise give).
#[test]
fn identification_recovers_the_base_parameters() {
    use dhgen::identification::LeastSquares;
    let mut gaussian = gaussians(0x5EED_1DE4);
    for (name, robot) in robots() {
        let base = robot.base_parameters();
        let truth = base.reduce(&robot.parameters());
        let (b, n) = (base.count(), robot.dof());
        let sigma: Vec<f64> = (0..n).map(|j| 0.02 * (j + 1) as f64).collect();
        let weights: Vec<f64> = sigma.iter().map(|s| 1.0 / s).collect();
        let (mut exact, mut noisy) = (LeastSquares::new(b), LeastSquares::new(b));
        let samples = (10 * b).div_ceil(n) as u64;
        for seed in 0..samples {
            let (q, qd, qdd) = state(&robot, 1_000 + seed);
            let y = base.base_regressor(&robot.regressor(&q[..], &qd[..], &qdd[..]));
            let tau = robot.inverse_dynamics(&q[..], &qd[..], &qdd[..]);
            exact.add(&y, &tau).unwrap();
            let measured = DVector::from_fn(n, |j, _| tau[j] + sigma[j] * gaussian());
            noisy.add_weighted(&y, &measured, &weights).unwrap();
        }
        let e = exact.estimate().unwrap();
        let scale = truth.amax();
        let err = (&e.parameters - &truth).amax() / scale;
        assert!(
            err < 1e-9,
            "{name}: {err:e} (condition number {:.1})",
            e.condition_number
        );
        let e = noisy.estimate().unwrap();
        let worst = (0..b)
            .map(|k| (e.parameters[k] - truth[k]).abs() / e.standard_deviations[k])
            .fold(0.0, f64::max);
        assert!(
            worst < 5.0,
            "{name}: an estimate {worst:.2} standard deviations off"
        );
        // σ̂² (rows − b) is χ² with rows − b degrees of freedom: σ̂² has mean 1 and standard
        // deviation √(2 / (rows − b)).
        let spread = (2.0 / (e.rows - b) as f64).sqrt();
        assert!(
            (e.residual_variance - 1.0).abs() < 5.0 * spread,
            "{name}: residual variance {} (its standard deviation {spread:.3})",
            e.residual_variance
        );
        println!(
            "{name}: {b} base parameters from {} rows, condition number {:.1}: exact to {err:.1e}; \
             with noise, within {worst:.2} σ, residual variance {:.3}",
            e.rows, e.condition_number, e.residual_variance
        );
    }
}

/// The rank of the regressor stacked over `states` seeded states, by Householder QR of
/// blocks (no pivoting) and a singular value decomposition of the triangular factor: a
/// computation that shares nothing with the pivoted reduction but the regressor.
fn stacked_rank(robot: &Robot, states: u64) -> usize {
    let p = robot.parameter_count();
    let mut r = DMatrix::<f64>::zeros(0, p);
    for seed in 1000..1000 + states {
        let (q, qd, qdd) = state(robot, seed);
        let y = robot.regressor(&q[..], &qd[..], &qdd[..]);
        let mut block = DMatrix::zeros(r.nrows() + y.nrows(), p);
        block.rows_mut(0, r.nrows()).copy_from(&r);
        block.rows_mut(r.nrows(), y.nrows()).copy_from(&y);
        let rr = block.qr().r();
        r = rr.rows(0, rr.nrows().min(p)).into_owned();
    }
    let s = r.singular_values();
    let top = s.amax();
    s.iter().filter(|&&x| x > 1e-9 * top).count()
}

#[test]
fn base_parameter_count_is_the_rank() {
    for (name, robot) in robots() {
        let count = robot.base_parameters().count();
        let rank = stacked_rank(&robot, 1000);
        println!("{name}: {count} base parameters, rank over 1,000 states {rank}");
        assert_eq!(count, rank, "{name}");
    }
}

#[test]
fn planar_elbow_base_parameters_are_the_textbooks() {
    // Spong, Hutchinson and Vidyasagar's planar elbow (§7.4): with the centres of mass on the
    // links' x axes, τ = Y_text(q, q̇, q̈) θ with
    // θ = [m1 lc1² + m2 (l1² + lc2²) + I1 + I2, m2 l1 lc2, m2 lc2² + I2, m1 lc1 + m2 l1, m2 lc2].
    let robot = Robot::from_toml_file(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/robots/planar_elbow.toml"
    ))
    .unwrap();
    let links = &robot.model().links;
    let (l1, m1, m2) = (
        links[0].a,
        links[0].inertial.unwrap().mass,
        links[1].inertial.unwrap().mass,
    );
    // The centre of mass sits at com.x from the far end (standard DH frames).
    let lc1 = l1 + links[0].inertial.unwrap().com[0];
    let lc2 = links[1].a + links[1].inertial.unwrap().com[0];
    let (i1, i2) = (
        links[0].inertial.unwrap().inertia[2][2],
        links[1].inertial.unwrap().inertia[2][2],
    );
    let theta = DVector::from_vec(vec![
        m1 * lc1 * lc1 + m2 * (l1 * l1 + lc2 * lc2) + i1 + i2,
        m2 * l1 * lc2,
        m2 * lc2 * lc2 + i2,
        m1 * lc1 + m2 * l1,
        m2 * lc2,
    ]);
    let g = 9.81;
    let y_text = |q: &[f64], qd: &[f64], qdd: &[f64]| {
        let (c1, c2, s2, c12) = (q[0].cos(), q[1].cos(), q[1].sin(), (q[0] + q[1]).cos());
        DMatrix::from_row_slice(
            2,
            5,
            &[
                qdd[0],
                2.0 * c2 * qdd[0] + c2 * qdd[1] - s2 * qd[1] * qd[1] - 2.0 * s2 * qd[0] * qd[1],
                qdd[1],
                g * c1,
                g * c12,
                0.0,
                c2 * qdd[0] + s2 * qd[0] * qd[0],
                qdd[0] + qdd[1],
                0.0,
                g * c12,
            ],
        )
    };
    let base = robot.base_parameters();
    let pi_b = base.reduce(&robot.parameters());
    let b = base.count();
    let samples = 40;
    let mut yb = DMatrix::zeros(2 * samples, b);
    let mut yt = DMatrix::zeros(2 * samples, 5);
    for s in 0..samples {
        let (q, qd, qdd) = state(&robot, s as u64);
        let y = robot.regressor(&q[..], &qd[..], &qdd[..]);
        yb.rows_mut(2 * s, 2).copy_from(&base.base_regressor(&y));
        yt.rows_mut(2 * s, 2).copy_from(&y_text(&q, &qd, &qdd));
        // The textbook's closed form is this robot's dynamics.
        let tau = robot.inverse_dynamics(&q[..], &qd[..], &qdd[..]);
        close("textbook τ", &(y_text(&q, &qd, &qdd) * &theta), &tau, 1e-12);
    }
    // The textbook's five are not independent: θ2 = m2 l1 lc2 = l1 θ5 with l1 a constant of
    // the geometry, so its columns 1 and 4 enter the dynamics only as l1·Y1 + Y4: neither alone
    // is a combination of base columns, their sum is.
    let merged = DMatrix::from_columns(&[
        yt.column(0).into_owned(),
        yt.column(2).into_owned(),
        yt.column(3).into_owned(),
        yt.column(1) * l1 + yt.column(4),
    ]);
    let theta_merged = DVector::from_vec(vec![theta[0], theta[2], theta[3], theta[4]]);
    let svd = yb.clone().svd(true, true);
    let residual_of = |target: &DMatrix<f64>| {
        let m = svd.solve(target, 1e-12).unwrap();
        ((&yb * &m - target).amax(), m)
    };
    for c in [1, 4] {
        let (r, _) = residual_of(&yt.columns(c, 1).into_owned());
        assert!(
            r > 1e-3,
            "textbook column {c} alone is a base combination ({r:e})"
        );
    }
    // Every merged textbook column is a fixed combination of base columns: Y_text = Y_b M ...
    let (residual, m) = residual_of(&merged);
    assert!(residual < 1e-10, "residual {residual:e}");
    // ... so Y_b (π_b − M θ) = 0, and Y_b has full column rank: π_b = M θ. The base
    // parameters beyond the textbook's are the first moments along y, zero here.
    close("π_b = M θ", &(&m * &theta_merged), &pi_b, 1e-12);
    let names = robot.parameter_names();
    let rules = base.rules(&names);
    println!("planar elbow: {b} base parameters: {rules:?}; π_b = {pi_b}");
    assert_eq!(b, 6, "{rules:?}");
    assert_eq!(
        (0..b).filter(|&k| pi_b[k].abs() > 1e-12).count(),
        4,
        "four non-zero base parameters (θ1, θ3, θ4 and θ5 = θ2 / l1): {rules:?} = {pi_b}"
    );
}

/// The generated regressor equals the runtime one entry by entry; `Y π = τ` with the generated
/// τ; the generated module's parameters, base columns and regrouping are the runtime's; and
/// `Y_b base_parameters(π) = τ` for the robot's own π and for a perturbed one.
macro_rules! generated_regressor {
    ($test:ident, $m:ident, $robot:expr) => {
        #[test]
        fn $test() {
            use $m as m;
            const N: usize = m::DOF;
            let robot: Robot = $robot;
            assert_eq!(m::PARAMETERS, robot.parameter_count());
            assert_eq!(
                m::PARAMETER_NAMES.to_vec(),
                robot.parameter_names(),
                "names"
            );
            let pi = robot.parameters();
            assert_eq!(m::PARAMETER_VALUES.as_slice(), pi.as_slice(), "π");
            let base = robot.base_parameters();
            assert_eq!(m::BASE_COLUMNS.to_vec(), base.independent, "base columns");
            // A π that is not the robot's, so no term cancels by accident.
            let perturbed: [f64; m::PARAMETERS] =
                core::array::from_fn(|k| pi[k] * (1.0 + 0.2 * (k as f64).sin()) + 0.01);
            let pv = DVector::from_row_slice(&perturbed);
            let pi_b = m::base_parameters(&perturbed);
            close(
                "π_b",
                &DVector::from_row_slice(&pi_b),
                &base.reduce(&pv),
                1e-12,
            );
            let (mut worst, mut worst_b) = (0.0f64, 0.0f64);
            for seed in 0..20 {
                let (q, qd, qdd) = state(&robot, seed);
                let (q, qd, qdd): ([f64; N], [f64; N], [f64; N]) = (
                    q.try_into().unwrap(),
                    qd.try_into().unwrap(),
                    qdd.try_into().unwrap(),
                );
                let y = m::regressor(&q, &qd, &qdd);
                let yr = robot.regressor(&q[..], &qd[..], &qdd[..]);
                let scale = yr.amax().max(1.0);
                let err = (0..N)
                    .flat_map(|r| (0..m::PARAMETERS).map(move |c| (r, c)))
                    .map(|(r, c)| (y[(r, c)] - yr[(r, c)]).abs())
                    .fold(0.0, f64::max)
                    / scale;
                assert!(err <= 1e-12, "{}: Y generated vs runtime {err:e}", m::NAME);
                let y_own = DVector::from_iterator(
                    N,
                    (0..N).map(|r| (0..m::PARAMETERS).map(|c| y[(r, c)] * pi[c]).sum::<f64>()),
                );
                let tau = DVector::from_row_slice(m::inverse_dynamics(&q, &qd, &qdd).as_slice());
                worst = worst.max(close("Y π", &y_own, &tau, 1e-12));
                let yb = m::base_regressor(&q, &qd, &qdd);
                let tau_p = &yr * &pv;
                let yb_pb = DVector::from_iterator(
                    N,
                    (0..N).map(|r| {
                        (0..m::BASE_PARAMETERS)
                            .map(|c| yb[(r, c)] * pi_b[c])
                            .sum::<f64>()
                    }),
                );
                worst_b = worst_b.max(close("Y_b π_b", &yb_pb, &tau_p, 1e-12));
            }
            println!(
                "{}: generated Y π = τ to {worst:.1e}, Y_b π_b = Y π to {worst_b:.1e}",
                m::NAME
            );
        }
    };
}

use crate::catalogue::{
    oblique9, odd_derivatives, panda_regressor, planar_elbow, puma560_derivatives,
    scara_derivatives, stanford_regressor, ur5,
};
use crate::support::{fixture, runtime};

generated_regressor!(
    puma560_generated_regressor,
    puma560_derivatives,
    runtime("puma560")
);
generated_regressor!(panda_generated_regressor, panda_regressor, runtime("panda"));
generated_regressor!(
    stanford_generated_regressor,
    stanford_regressor,
    runtime("stanford")
);
generated_regressor!(
    scara_generated_regressor,
    scara_derivatives,
    runtime("scara")
);
generated_regressor!(odd_generated_regressor, odd_derivatives, fixture("odd"));
generated_regressor!(oblique9_generated_regressor, oblique9, fixture("oblique9"));
generated_regressor!(ur5_generated_regressor, ur5, runtime("ur5"));
generated_regressor!(
    planar_elbow_generated_regressor,
    planar_elbow,
    runtime("planar_elbow")
);

/// The regrouping does not depend on units. Seeded general arms in metres and kilograms, in
/// millimetres and tenths of grams (lengths ×1e-3, masses ×1e-4), and thirty times larger and
/// a thousand times heavier, have the same number of base parameters, and `Y_b π_b = τ` to
/// rounding relative to τ itself. (A threshold on the coefficients β in the parameters' units,
/// 1e-10, had dropped the small arms' real ones: τ off by 3e-8 of its size.)
#[test]
fn base_parameters_hold_in_any_units() {
    use dhgen::model::random::{ArmStyle, random_arm};
    for (dof, seed) in [(4, 2), (9, 3), (7, 5)] {
        let mut counts = Vec::new();
        for (length, mass) in [(1.0, 1.0), (1e-3, 1e-4), (30.0, 1e3)] {
            let model =
                crate::support::scaled(random_arm(dof, ArmStyle::General, seed), length, mass);
            let pi = DVector::from_vec(dhgen::model::parameters::values(&model).unwrap());
            let robot = Robot::from_model(model);
            let base = robot.base_parameters();
            let pi_b = base.reduce(&pi);
            let mut worst: f64 = 0.0;
            for s in 0..20 {
                let (q, qd, qdd) = state(&robot, 500 + s);
                let y = robot.regressor(&q[..], &qd[..], &qdd[..]);
                let tau = robot.inverse_dynamics(&q[..], &qd[..], &qdd[..]);
                let err = (base.base_regressor(&y) * &pi_b - &tau).amax() / tau.amax();
                worst = worst.max(err);
            }
            println!(
                "general {dof} (seed {seed}) ×{length:e} m ×{mass:e} kg: {} base parameters, \
                 Y_b π_b − τ {worst:.1e} of |τ|",
                base.count()
            );
            assert!(worst <= 1e-12, "{dof} joints ×{length:e} m: {worst:e}");
            counts.push(base.count());
        }
        assert!(counts.iter().all(|&c| c == counts[0]), "{counts:?}");
    }
}

/// `with_values` is the inverse of `values` on every robot: the same parameters back (to
/// rounding: the centre of mass and the inertia about it are recomputed), the same torques.
#[test]
fn a_model_from_its_own_parameters_is_the_same_robot() {
    use dhgen::parameters::{Links, values, with_values};
    for (name, robot) in robots() {
        let pi = values(robot.model()).unwrap();
        let rebuilt = Robot::from_model(with_values(robot.model(), &pi, Links::Physical).unwrap());
        let back = DVector::from_vec(values(rebuilt.model()).unwrap());
        close(&name, &back, &DVector::from_vec(pi), 1e-14);
        for seed in 0..5 {
            let (q, qd, qdd) = state(&robot, 50 + seed);
            close(
                &name,
                &rebuilt.inverse_dynamics(&q[..], &qd[..], &qdd[..]),
                &robot.inverse_dynamics(&q[..], &qd[..], &qdd[..]),
                1e-12,
            );
        }
    }
}

/// Base parameters expanded over a reference (`BaseParameters::expand`) reduce back to
/// themselves, and the model of the expansion moves exactly as the robot they came from,
/// though its links differ (and are rarely all physical, which `Links::Physical` reports): on
/// every robot, the base parameters of a heavier copy (every mass and inertia ×1.15, centres
/// of mass ×0.95, motors and friction ×1.1) expanded over the original's values give that
/// copy's torques, mass matrix and forward dynamics.
#[test]
fn expanded_base_parameters_give_the_robot_they_came_from() {
    use dhgen::parameters::{Links, ParameterError, values, with_values};
    let (mut unphysical, mut count) = (0, 0);
    for (name, robot) in robots() {
        let truth = heavier_copy(&robot);
        count += 1;
        let base = robot.base_parameters();
        let pi_b = base.reduce(&truth.parameters());
        let reference = values(robot.model()).unwrap();
        let expanded = base.expand(pi_b.as_slice(), &reference).unwrap();
        close(&name, &base.reduce(&expanded), &pi_b, 1e-13);
        if let Err(e) = with_values(robot.model(), expanded.as_slice(), Links::Physical) {
            println!("{name}: the expansion is not physical: {e}");
            assert!(matches!(e, ParameterError::Value { .. }), "{e}");
            unphysical += 1;
        }
        let model = with_values(robot.model(), expanded.as_slice(), Links::AsGiven).unwrap();
        let identified = Robot::from_model(model);
        for seed in 0..5 {
            let (q, qd, qdd) = state(&robot, 70 + seed);
            let tau = truth.inverse_dynamics(&q[..], &qd[..], &qdd[..]);
            close(
                &name,
                &identified.inverse_dynamics(&q[..], &qd[..], &qdd[..]),
                &tau,
                1e-11,
            );
            let (d, e) = (identified.mass_matrix(&q[..]), truth.mass_matrix(&q[..]));
            assert!((&d - &e).amax() <= 1e-11 * e.amax(), "{name}: D");
            // Robots whose D is singular by construction (Robotics Toolbox's UR5 moves no
            // inertia about its last axis, the weightless_wrist fixture none at its wrist): both.
            match (
                identified.forward_dynamics(&q[..], &qd[..], &tau),
                truth.forward_dynamics(&q[..], &qd[..], &tau),
            ) {
                (Some(a), Some(b)) => drop(close(&name, &a, &b, 1e-8)),
                (None, None) => {}
                (a, b) => panic!("{name}: forward dynamics {a:?} against {b:?}"),
            }
        }
        println!("{name}: a model of the expanded base parameters moves as the heavier copy");
    }
    // What `Links::AsGiven` documents: most (17 of 18 when it was written).
    assert!(2 * unphysical > count, "{unphysical} of {count}");
}

/// The heavier copy of `robot` of [`expanded_base_parameters_give_the_robot_they_came_from`]:
/// every mass and inertia ×1.15, centres of mass ×0.95, motors and friction ×1.1.
fn heavier_copy(robot: &Robot) -> Robot {
    let mut heavier = robot.model().clone();
    for link in &mut heavier.links {
        let i = link.inertial.as_mut().unwrap();
        i.mass *= 1.15;
        i.com = i.com.map(|x| 0.95 * x);
        i.inertia = i.inertia.map(|row| row.map(|x| 1.15 * x));
        if let Some(m) = link.motor.as_mut() {
            m.inertia *= 1.1;
        }
        if let Some(f) = link.friction.as_mut() {
            f.viscous *= 1.1;
            f.coulomb *= 1.1;
        }
    }
    Robot::from_model(heavier)
}

/// The distance `BaseParameters::expand_physical` documents between two parameter vectors:
/// over the dependent parameters, each difference in its scale (the mean link mass `M` for a
/// mass, `M L` for a first moment, `M L²` for an inertia, `L² = Σ ∫|r|² dm / Σ m`; a
/// joint-side term's own reference value), squared and summed.
pub(crate) fn physical_distance(
    model: &dhgen::RobotModel,
    base: &dhgen::parameters::BaseParameters,
    a: &[f64],
    reference: &[f64],
) -> f64 {
    let scale = physical_scales(model, reference);
    base.dependent
        .iter()
        .map(|&j| ((a[j] - reference[j]) / scale[j]).powi(2))
        .sum()
}

/// Every parameter's scale in [`physical_distance`]: `M`, `M L` or `M L²` for a link's mass,
/// first moment or inertia, a joint-side term's own reference value (1 where zero).
fn physical_scales(model: &dhgen::RobotModel, reference: &[f64]) -> Vec<f64> {
    let n = model.dof();
    let mass: f64 = (0..n).map(|i| reference[10 * i]).sum();
    let second: f64 = (0..n)
        .map(|i| 0.5 * (reference[10 * i + 4] + reference[10 * i + 6] + reference[10 * i + 9]))
        .sum();
    let (big_m, big_l) = (mass / n as f64, (second / mass).sqrt());
    reference
        .iter()
        .enumerate()
        .map(|(j, r)| match (j < 10 * n, j % 10) {
            (true, 0) => big_m,
            (true, 1..=3) => big_m * big_l,
            (true, _) => big_m * big_l * big_l,
            (false, _) if *r != 0.0 => r.abs(),
            (false, _) => 1.0,
        })
        .collect()
}

/// `BaseParameters::expand_physical` on every robot. The base parameters of its heavier copy
/// (a physical robot has them) come back as physical links (`Links::Physical` accepts them)
/// with the same base parameters, which move as the copy, and at least as near the
/// original's values as the copy itself is (the nearest physical vector is no farther than
/// any physical one); a robot's own base parameters come back as its own values.
#[test]
fn physical_expansion_finds_the_nearest_physical_links() {
    use dhgen::parameters::{Links, values, with_values};
    for (name, robot) in robots() {
        let truth = heavier_copy(&robot);
        let base = robot.base_parameters();
        let pi_b = base.reduce(&truth.parameters());
        let reference = values(robot.model()).unwrap();
        let expanded = base
            .expand_physical(pi_b.as_slice(), robot.model())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        close(&name, &base.reduce(&expanded), &pi_b, 1e-12);
        let model = with_values(robot.model(), expanded.as_slice(), Links::Physical)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let identified = Robot::from_model(model);
        for seed in 0..3 {
            let (q, qd, qdd) = state(&robot, 90 + seed);
            let tau = truth.inverse_dynamics(&q[..], &qd[..], &qdd[..]);
            let got = identified.inverse_dynamics(&q[..], &qd[..], &qdd[..]);
            close(&name, &got, &tau, 1e-11);
        }
        let model = robot.model();
        let found = physical_distance(model, &base, expanded.as_slice(), &reference);
        let copy = physical_distance(model, &base, truth.parameters().as_slice(), &reference);
        println!("{name}: distance {found:.4e}, the heavier copy's {copy:.4e}");
        assert!(found <= copy + 1e-9, "{name}: {found} against {copy}");
        let own = DVector::from_vec(reference.clone());
        let again = base
            .expand_physical(base.reduce(&own).as_slice(), model)
            .unwrap();
        close(&name, &again, &own, 1e-12);
    }
}

/// `expand_physical` finds the optimum of the problem it documents, as an independent conic
/// solver does: tests/data/physical_reference.json, made by scripts/physical_reference.py
/// (cvxpy and Clarabel, with the inertial parameters of the description and of its heavier
/// copy computed there from the TOML files, and the pseudo-inertia constraints written there),
/// for the PUMA 560 (two of whose links break the triangle inequality) and the Panda. The
/// distance found is the solver's optimum to 1e-6 of it, and so are the parameters, each to
/// 1e-4 of its scale: a search that stopped short, or a constraint stricter or looser than
/// documented, would differ.
#[test]
fn physical_expansion_is_the_optimum_an_independent_solver_finds() {
    use dhgen::parameters::values;
    let path = format!(
        "{}/tests/data/physical_reference.json",
        env!("CARGO_MANIFEST_DIR")
    );
    let data: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    let entries = data["robots"].as_array().unwrap();
    assert_eq!(entries.len(), 2);
    for entry in entries {
        let file = entry["robot"].as_str().unwrap();
        let robot =
            Robot::from_toml_file(format!("{}/{file}", env!("CARGO_MANIFEST_DIR"))).unwrap();
        let model = robot.model();
        let truth = heavier_copy(&robot);
        let base = robot.base_parameters();
        let reference = values(model).unwrap();
        // The same problem: the copy lies as far from the description there as here.
        let copy = physical_distance(model, &base, truth.parameters().as_slice(), &reference);
        let theirs_copy = entry["copy_objective"].as_f64().unwrap();
        assert!(
            (copy - theirs_copy).abs() <= 1e-12 * theirs_copy,
            "{file}: {copy} against {theirs_copy}"
        );
        let pi_b = base.reduce(&truth.parameters());
        let expanded = base
            .expand_physical(pi_b.as_slice(), model)
            .unwrap_or_else(|e| panic!("{file}: {e}"));
        let ours = physical_distance(model, &base, expanded.as_slice(), &reference);
        let theirs = entry["objective"].as_f64().unwrap();
        println!("{file}: distance {ours:.10e}, the conic solver's {theirs:.10e}");
        assert!(
            (ours - theirs).abs() <= 1e-6 * theirs,
            "{file}: {ours} against {theirs}"
        );
        // Each parameter in its scale (the search's: M, M L, M L²).
        let solution: Vec<f64> = entry["parameters"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect();
        assert_eq!(solution.len(), expanded.len(), "{file}");
        let scales = physical_scales(model, &reference);
        for (j, ((a, b), scale)) in expanded.iter().zip(&solution).zip(&scales).enumerate() {
            assert!(
                (a - b).abs() <= 1e-4 * scale,
                "{file}: parameter {j}: {a} against {b} (scale {scale})"
            );
        }
    }
}

/// Identification constrained to physical links (`Estimate::physical`): on every robot, a
/// heavier copy's torques with 2 % noise, identified over the original's regrouping. The
/// result has physical links (`Links::Physical` accepts them) and minimizes the documented
/// objective, the base parameters' distance from the estimate in the metric of its inverse
/// covariance plus 1e-6 times the distance from the description: it is no larger there than
/// at the copy itself, which is physical; and its base parameters are no farther from the
/// copy's than the estimate's, in that metric, by more than the few σ noise allows.
#[test]
fn physically_consistent_identification_is_the_constrained_fit() {
    use dhgen::identification::LeastSquares;
    use dhgen::parameters::{Links, values, with_values};
    let mut gaussian = gaussians(0x0C05_157E);
    let mut searched = 0;
    for (name, robot) in robots() {
        let truth = heavier_copy(&robot);
        let base = robot.base_parameters();
        let (b, n) = (base.count(), robot.dof());
        let samples = (10 * b).div_ceil(n) as u64;
        let states: Vec<_> = (0..samples).map(|s| state(&robot, 2_000 + s)).collect();
        let torques: Vec<DVector<f64>> = states
            .iter()
            .map(|(q, qd, qdd)| truth.inverse_dynamics(&q[..], &qd[..], &qdd[..]))
            .collect();
        let sigma: Vec<f64> = (0..n)
            .map(|j| {
                let rms = torques.iter().map(|t| t[j] * t[j]).sum::<f64>() / samples as f64;
                0.02 * rms.sqrt().max(1e-3)
            })
            .collect();
        let weights: Vec<f64> = sigma.iter().map(|s| 1.0 / s).collect();
        let mut fit = LeastSquares::new(b);
        for ((q, qd, qdd), tau) in states.iter().zip(&torques) {
            let y = base.base_regressor(&robot.regressor(&q[..], &qd[..], &qdd[..]));
            let measured = DVector::from_fn(n, |j, _| tau[j] + sigma[j] * gaussian());
            fit.add_weighted(&y, &measured, &weights).unwrap();
        }
        let estimate = fit.estimate().unwrap();
        let reference = values(robot.model()).unwrap();
        let plain = base
            .expand(estimate.parameters.as_slice(), &reference)
            .unwrap();
        let own_physical = with_values(robot.model(), plain.as_slice(), Links::Physical).is_ok();
        if !own_physical {
            searched += 1;
        }
        let pi = estimate
            .physical(&base, robot.model())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        with_values(robot.model(), pi.as_slice(), Links::Physical)
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let information = estimate.covariance.clone().try_inverse().unwrap();
        let fit_distance = |pi: &DVector<f64>| {
            let e = base.reduce(pi) - &estimate.parameters;
            e.dot(&(&information * &e))
        };
        let objective = |pi: &DVector<f64>| {
            fit_distance(pi)
                + 1e-6 * physical_distance(robot.model(), &base, pi.as_slice(), &reference)
        };
        let copy = truth.parameters();
        let (found, at_copy) = (objective(&pi), objective(&copy));
        println!(
            "{name}: objective {found:.4} against {at_copy:.4} at the heavier copy; the estimate's \
             own expansion {}",
            if own_physical {
                "is physical"
            } else {
                "is not physical"
            }
        );
        assert!(
            found <= at_copy + 1e-8 * (1.0 + at_copy),
            "{name}: {found} against {at_copy}"
        );
        // In the metric, the copy lies about √b from the estimate (χ² with b degrees of
        // freedom); the physical estimate no farther.
        assert!(fit_distance(&pi) <= fit_distance(&copy) + 1e-8, "{name}");
    }
    // Most estimates' own expansions are not physical: the search ran.
    assert!(2 * searched > robots().len(), "{searched}");
}

/// Whatever base parameters it is given, `expand_physical` and `nearest_physical` answer:
/// physical links (`Links::Physical` accepts them) with the given base parameters (expand) or
/// an `Infeasible` error naming a link or term, never a panic: on every robot, base parameters
/// perturbed at random by up to their own size (and some by a hundred times it).
#[test]
fn physical_expansion_answers_any_base_parameters() {
    use dhgen::parameters::{Links, ParameterError, with_values};
    let mut gaussian = gaussians(0x0BAD_5EED);
    let (mut found, mut refused) = (0, 0);
    for (name, robot) in robots() {
        let base = robot.base_parameters();
        let b = base.count();
        let truth = base.reduce(&robot.parameters());
        let scale = truth.amax();
        for case in 0..4 {
            let size = if case < 3 { 1.0 } else { 100.0 };
            let pi_b = DVector::from_fn(b, |k, _| {
                truth[k] + size * gaussian() * truth[k].abs().max(1e-3 * scale)
            });
            let information =
                DMatrix::from_fn(b, b, |r, c| if r == c { 1.0 + case as f64 } else { 0.0 });
            let results = [
                base.expand_physical(pi_b.as_slice(), robot.model()),
                base.nearest_physical(pi_b.as_slice(), &information, robot.model()),
            ];
            for (expanded, result) in [true, false].into_iter().zip(results) {
                match result {
                    Ok(pi) => {
                        with_values(robot.model(), pi.as_slice(), Links::Physical)
                            .unwrap_or_else(|e| panic!("{name} case {case}: {e}"));
                        if expanded {
                            close(&name, &base.reduce(&pi), &pi_b, 1e-12);
                        }
                        found += 1;
                    }
                    Err(ParameterError::Infeasible {
                        name: what,
                        message,
                    }) => {
                        assert!(!what.is_empty() && !message.is_empty(), "{name}");
                        refused += 1;
                    }
                    Err(e) => panic!("{name} case {case}: {e}"),
                }
            }
        }
    }
    println!("{found} physical, {refused} refused");
}

/// Base parameters no physical robot has are refused, naming the link: a last link's lumped
/// mass made negative, or a lumped inertia below what the masses beyond it already carry; a
/// reference without mass properties and a wrong count are refused too.
#[test]
fn physical_expansion_refuses_base_parameters_no_body_has() {
    use dhgen::parameters::{ParameterError, names};
    for (name, robot) in robots() {
        let base = robot.base_parameters();
        let names = names(robot.model());
        let pi_b = base.reduce(&robot.parameters());
        let n = robot.dof();
        // The last link's mass as a base parameter of its own (nothing regrouped into it).
        let mass = |k: usize| {
            names[base.independent[k]] == format!("m{n}")
                && base.beta.row(k).iter().all(|b| *b == 0.0)
        };
        if let Some(k) = (0..base.count()).find(|&k| mass(k)) {
            let mut b = pi_b.clone();
            b[k] = -0.1;
            match base.expand_physical(b.as_slice(), robot.model()) {
                Err(ParameterError::Infeasible {
                    name: what,
                    message,
                }) => {
                    println!("{name}: m{n} = -0.1: {what}: {message}");
                    assert!(what.starts_with("link "), "{name}: {what}");
                }
                other => panic!("{name}: m{n} = -0.1 gave {other:?}"),
            }
        }
    }
    let planar = robots()
        .into_iter()
        .find(|(name, _)| name == "planar_elbow")
        .unwrap()
        .1;
    let base = planar.base_parameters();
    let names = names(planar.model());
    let mut pi_b = base.reduce(&planar.parameters());
    // The lumped ZZ of link 1 (Izz1 + ...), far below zero.
    let k = (0..base.count())
        .find(|&k| names[base.independent[k]] == "Izz1")
        .expect("Izz1 is a base parameter of the planar elbow");
    pi_b[k] = -10.0;
    let e = base
        .expand_physical(pi_b.as_slice(), planar.model())
        .unwrap_err();
    assert!(
        matches!(&e, ParameterError::Infeasible { name, .. } if name.starts_with("link ")),
        "{e}"
    );
    assert!(e.to_string().contains("cannot be made physical"), "{e}");
    let mut bare = planar.model().clone();
    bare.links[1].inertial = None;
    assert_eq!(
        base.expand_physical(pi_b.as_slice(), &bare).unwrap_err(),
        ParameterError::NoMassProperties { link: 2 }
    );
    assert!(matches!(
        base.expand_physical(&pi_b.as_slice()[1..], planar.model()),
        Err(ParameterError::Count { .. })
    ));
    pi_b[1] = f64::NAN;
    let e = base
        .expand_physical(pi_b.as_slice(), planar.model())
        .unwrap_err();
    assert!(
        matches!(&e, ParameterError::Value { name, index: 1, .. } if name == "base parameter 2"),
        "{e}"
    );
    let information = DMatrix::identity(base.count(), base.count());
    let e = base
        .nearest_physical(pi_b.as_slice(), &information, planar.model())
        .unwrap_err();
    assert!(matches!(&e, ParameterError::Value { index: 1, .. }), "{e}");
    pi_b[1] = 0.0;
    assert!(matches!(
        base.nearest_physical(pi_b.as_slice(), &information.remove_row(0), planar.model()),
        Err(ParameterError::Count { .. })
    ));
}

/// Values no link can have are refused, naming the parameter.
#[test]
fn unphysical_parameter_values_are_refused_by_name() {
    use dhgen::parameters::{Links, ParameterError, values, with_values};
    let model = dhgen::RobotModel::from_toml_str(
        r#"
        name = "two"
        convention = "standard"
        [[links]]
        joint = "revolute"
        a = 0.5
        alpha = 0.0
        d = 0.0
        theta = 0.0
        mass = 2.0
        com = [-0.25, 0.0, 0.0]
        inertia = { xx = 0.01, yy = 0.05, zz = 0.05 }
        motor = { inertia = 1e-4, gear = 50.0 }
        friction = { viscous = 0.1, coulomb = 0.2 }
        [[links]]
        joint = "revolute"
        a = 0.4
        alpha = 0.0
        d = 0.0
        theta = 0.0
        mass = 1.0
        com = [-0.2, 0.0, 0.0]
        inertia = { xx = 0.01, yy = 0.02, zz = 0.02 }
        "#,
    )
    .unwrap();
    let pi = values(&model).unwrap();
    assert_eq!(pi.len(), 23);
    let rebuilt = with_values(&model, &pi, Links::Physical).unwrap();
    assert!((rebuilt.links[0].motor.unwrap().inertia - 1e-4).abs() < 1e-18);
    let refused = |index: usize, value: f64| {
        let mut p = pi.clone();
        p[index] = value;
        with_values(&model, &p, Links::Physical).unwrap_err()
    };
    let as_given = |index: usize, value: f64| {
        let mut p = pi.clone();
        p[index] = value;
        with_values(&model, &p, Links::AsGiven)
    };
    let named = |e: ParameterError, name: &str, index: usize, words: &str| {
        let message = e.to_string();
        assert!(
            matches!(&e, ParameterError::Value { name: n, index: i, .. } if n == name && *i == index),
            "{message}"
        );
        assert!(message.contains(words), "{message}");
    };
    named(refused(10, -1.0), "m2", 10, "negative");
    named(refused(3, f64::NAN), "mz1", 3, "not a finite number");
    // A massless link with a first moment.
    named(refused(10, 0.0), "mx2", 11, "massless");
    // A centre of mass 10 km away.
    named(refused(11, -1e4), "mx2", 11, "centre of mass");
    // Izz about the origin below what the mass at its distance takes.
    named(refused(19, 0.01), "Ixx2", 14, "positive semi-definite");
    // Ixx far above Iyy + Izz.
    named(refused(14, 1.0), "Ixx2", 14, "triangle");
    named(refused(20, -1e-3), "Ia1", 20, "negative");
    named(refused(22, -0.2), "fc1", 22, "negative");
    // As given: what no equation of motion can take, still refused; the rest accepted.
    assert!(as_given(10, -1.0).is_ok() && as_given(19, 0.01).is_ok() && as_given(22, -0.2).is_ok());
    named(
        as_given(3, f64::NAN).unwrap_err(),
        "mz1",
        3,
        "not a finite number",
    );
    named(as_given(10, 0.0).unwrap_err(), "mx2", 11, "massless");
    named(as_given(11, -1e4).unwrap_err(), "mx2", 11, "centre of mass");
    named(as_given(10, -1e7).unwrap_err(), "m2", 10, "mass");
    assert_eq!(
        with_values(&model, &pi[..22], Links::AsGiven).unwrap_err(),
        ParameterError::Count {
            what: "parameter values",
            given: 22,
            expected: 23
        }
    );
    let base = dhgen::Robot::from_model(model.clone()).base_parameters();
    assert!(matches!(
        base.expand(&[1.0], &pi),
        Err(ParameterError::Count { .. })
    ));
    assert!(matches!(
        base.expand(
            base.reduce(&DVector::from_vec(pi.clone())).as_slice(),
            &pi[1..]
        ),
        Err(ParameterError::Count { .. })
    ));
}
