//! Inertial parameters: the payload's cost over plain inverse dynamics (generated and
//! runtime), the payload's C and q̈ against the plain ones, and the regressor `Y` and base
//! regressor (generated and runtime), for the PUMA 560 and the Panda:
//! `{robot}/{quantity}/{variant}`. Every call takes the next of 64 fixed random states.
//! Then identified parameters back to physical links (`{robot}/physical/...`): the base
//! parameters of a 15 % heavier copy expanded by `BaseParameters::expand_physical`, and a
//! noisy least-squares estimate of them made physically consistent by `Estimate::physical`
//! (`BaseParameters::nearest_physical` in its inverse covariance), each the search the
//! identify example runs once.
//!
//! `cargo bench --bench parameters`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use dhgen::parameters::PhysicalConsistency;
use dhgen::payload::{self, Payload};
use dhgen::{ArmDynamics, Robot};
use nalgebra::{DVector, SVector};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::hint::black_box;
use std::time::Duration;

const STATES: usize = 64;

dhgen::robot!(mod puma560 = "robots/puma560.toml", regressor);
dhgen::robot!(mod panda = "robots/panda.toml", regressor);

fn states<const N: usize>(seed: u64) -> Vec<[SVector<f64, N>; 3]> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..STATES)
        .map(|_| {
            [
                SVector::from_fn(|_, _| rng.random_range(-2.5..2.5)),
                SVector::from_fn(|_, _| rng.random_range(-2.0..2.0)),
                SVector::from_fn(|_, _| rng.random_range(-5.0..5.0)),
            ]
        })
        .collect()
}

fn run<S, R>(
    c: &mut Criterion,
    robot: &str,
    what: &str,
    variant: &str,
    s: &[S],
    f: impl Fn(&S) -> R,
) {
    c.benchmark_group(robot)
        .bench_function(BenchmarkId::new(what, variant), |b| {
            let mut i = 0;
            b.iter(|| {
                let x = black_box(&s[i % STATES]);
                i += 1;
                black_box(f(x))
            })
        });
}

macro_rules! bench_robot {
    ($c:expr, $m:ident, $file:literal) => {{
        const N: usize = $m::DOF;
        let name = stringify!($m);
        let s = states::<N>(7);
        let p = Payload::new(
            1.7,
            [0.03, -0.02, 0.06],
            [
                [0.012, 0.001, -0.002],
                [0.001, 0.010, 0.0015],
                [-0.002, 0.0015, 0.008],
            ],
        )
        .unwrap();
        run($c, name, "tau", "generated", &s, |[q, qd, qdd]| {
            $m::Robot.inverse_dynamics(q, qd, qdd)
        });
        run(
            $c,
            name,
            "tau_payload",
            "generated_jt_w",
            &s,
            |[q, qd, qdd]| payload::inverse_dynamics(&$m::Robot, &p, q, qd, qdd),
        );
        let pp = p.parameters();
        run($c, name, "tau_payload", "generated", &s, |[q, qd, qdd]| {
            $m::inverse_dynamics_with_payload(q, qd, qdd, &pp)
        });
        run($c, name, "coriolis", "generated", &s, |[q, qd, _]| {
            $m::coriolis(q, qd)
        });
        run(
            $c,
            name,
            "coriolis_payload",
            "generated",
            &s,
            |[q, qd, _]| $m::coriolis_with_payload(q, qd, &pp),
        );
        run($c, name, "qdd", "generated", &s, |[q, qd, tau]| {
            $m::forward_dynamics(q, qd, tau)
        });
        run($c, name, "qdd_payload", "generated", &s, |[q, qd, tau]| {
            $m::forward_dynamics_with_payload(q, qd, tau, &pp)
        });
        run($c, name, "regressor", "generated", &s, |[q, qd, qdd]| {
            $m::regressor(q, qd, qdd)
        });
        run(
            $c,
            name,
            "base_regressor",
            "generated",
            &s,
            |[q, qd, qdd]| $m::base_regressor(q, qd, qdd),
        );
        let robot = Robot::from_toml_file(concat!(env!("CARGO_MANIFEST_DIR"), "/", $file)).unwrap();
        let d: Vec<[DVector<f64>; 3]> = s
            .iter()
            .map(|x| x.clone().map(|v| DVector::from_column_slice(v.as_slice())))
            .collect();
        run($c, name, "tau", "runtime", &d, |[q, qd, qdd]| {
            robot.inverse_dynamics(q, qd, qdd)
        });
        run($c, name, "tau_payload", "runtime", &d, |[q, qd, qdd]| {
            payload::inverse_dynamics(&robot, &p, q, qd, qdd)
        });
        run($c, name, "regressor", "runtime", &d, |[q, qd, qdd]| {
            robot.regressor(q, qd, qdd)
        });
        let base = robot.base_parameters();
        run($c, name, "base_regressor", "runtime", &d, |[q, qd, qdd]| {
            base.base_regressor(&robot.regressor(q, qd, qdd))
        });
        physical($c, name, &robot, &d);
    }};
}

/// The identified parameters' way back to physical links, on a 15 % heavier copy of `robot`
/// (masses and inertias ×1.15, centres ×0.95): `expand_physical` of its exact base parameters,
/// and `Estimate::physical` of an estimate from its torques at `states` with 2 % noise
/// (deterministic), whose own expansion has unphysical links.
fn physical(c: &mut Criterion, name: &str, robot: &Robot, states: &[[DVector<f64>; 3]]) {
    use dhgen::identification::LeastSquares;
    use dhgen::parameters::{Links, values, with_values};
    let mut heavier = robot.model().clone();
    for link in &mut heavier.links {
        let i = link
            .inertial
            .as_mut()
            .expect("the catalogue's links have mass");
        i.mass *= 1.15;
        i.com = i.com.map(|x| 0.95 * x);
        i.inertia = i.inertia.map(|row| row.map(|x| 1.15 * x));
    }
    let truth = Robot::from_model(heavier);
    let base = robot.base_parameters();
    let exact = base.reduce(&truth.parameters());
    let mut rng = StdRng::seed_from_u64(0x9415);
    let mut fit = LeastSquares::new(base.count());
    for [q, qd, qdd] in states {
        let tau = truth.inverse_dynamics(q, qd, qdd);
        let noisy = tau.map(|t| t * (1.0 + rng.random_range(-0.02..0.02)));
        let y = base.base_regressor(&robot.regressor(q, qd, qdd));
        fit.add(&y, &noisy).expect("one row per joint");
    }
    let estimate = fit
        .estimate()
        .expect("the states excite every base parameter");
    let reference = values(robot.model()).expect("the catalogue's links have mass");
    let plain = base
        .expand(estimate.parameters.as_slice(), &reference)
        .expect("counts match");
    assert!(
        with_values(robot.model(), plain.as_slice(), Links::Physical).is_err(),
        "{name}: the estimate's own expansion is physical; the search would not run"
    );
    let mut group = c.benchmark_group(name);
    // Milliseconds per call: ten samples.
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(3));
    group.bench_function(BenchmarkId::new("physical", "expand_physical"), |b| {
        b.iter(|| base.expand_physical(black_box(exact.as_slice()), robot.model()))
    });
    group.bench_function(BenchmarkId::new("physical", "estimate_physical"), |b| {
        b.iter(|| black_box(&estimate).physical(&base, robot.model()))
    });
}

fn parameters(c: &mut Criterion) {
    bench_robot!(c, puma560, "robots/puma560.toml");
    bench_robot!(c, panda, "robots/panda.toml");
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_millis(1200)).sample_size(50);
    targets = parameters
}
criterion_main!(benches);
