//! Generated code against the runtime path on random arms, the sizes and styles where the
//! symbolic engine has the least structure to exploit: general arms (twists and offsets
//! anywhere, full inertia tensors) and industrial-style arms (twists in {0, ±90°}) at 6, 8, 10
//! and 12 joints, `{style}_{n}/{quantity}/{generated|runtime}`. The arms are
//! `benches/arms/*.toml`, written by `dhgen random --dof N --style STYLE --seed 1` (the test
//! `random_arms::bench_arms_are_the_seeded_ones` checks that they still are). Every call
//! takes the next of 64 fixed random states.
//!
//! `cargo bench --bench random_arms`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use dhgen::{Arm, ArmDynamics, Robot};
use nalgebra::{DVector, SVector};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::hint::black_box;
use std::time::Duration;

const STATES: usize = 64;

dhgen::robot!(mod general_6 = "benches/arms/general_6.toml");
dhgen::robot!(mod general_8 = "benches/arms/general_8.toml");
dhgen::robot!(mod general_10 = "benches/arms/general_10.toml");
dhgen::robot!(mod general_12 = "benches/arms/general_12.toml");
dhgen::robot!(mod industrial_6 = "benches/arms/industrial_6.toml");
dhgen::robot!(mod industrial_8 = "benches/arms/industrial_8.toml");
dhgen::robot!(mod industrial_10 = "benches/arms/industrial_10.toml");
dhgen::robot!(mod industrial_12 = "benches/arms/industrial_12.toml");

fn run<S, R>(c: &mut Criterion, arm: &str, what: &str, path: &str, s: &[S], f: impl Fn(&S) -> R) {
    c.benchmark_group(arm)
        .bench_function(BenchmarkId::new(what, path), |b| {
            let mut i = 0;
            b.iter(|| {
                let x = black_box(&s[i % STATES]);
                i += 1;
                black_box(f(x))
            })
        });
}

macro_rules! bench_arm {
    ($c:expr, $m:ident) => {{
        const N: usize = $m::DOF;
        let name = stringify!($m);
        let file = format!("{}/benches/arms/{name}.toml", env!("CARGO_MANIFEST_DIR"));
        let robot = Robot::from_toml_file(&file).expect("a checked-in arm");
        let mut rng = StdRng::seed_from_u64(11);
        let s: Vec<[SVector<f64, N>; 3]> = (0..STATES)
            .map(|_| {
                [
                    SVector::from_fn(|_, _| rng.random_range(-0.5..0.5)),
                    SVector::from_fn(|_, _| rng.random_range(-2.0..2.0)),
                    SVector::from_fn(|_, _| rng.random_range(-5.0..5.0)),
                ]
            })
            .collect();
        let d: Vec<[DVector<f64>; 3]> = s
            .iter()
            .map(|x| x.clone().map(|v| DVector::from_column_slice(v.as_slice())))
            .collect();
        let g = $m::Robot;
        run($c, name, "fk", "generated", &s, |[q, _, _]| g.fk(q));
        run($c, name, "fk", "runtime", &d, |[q, _, _]| robot.fk(q));
        run($c, name, "jacobian", "generated", &s, |[q, _, _]| {
            g.jacobian(q)
        });
        run($c, name, "jacobian", "runtime", &d, |[q, _, _]| {
            robot.jacobian(q)
        });
        run($c, name, "mass_matrix", "generated", &s, |[q, _, _]| {
            g.mass_matrix(q)
        });
        run($c, name, "mass_matrix", "runtime", &d, |[q, _, _]| {
            robot.mass_matrix(q)
        });
        run($c, name, "coriolis", "generated", &s, |[q, qd, _]| {
            g.coriolis(q, qd)
        });
        run($c, name, "coriolis", "runtime", &d, |[q, qd, _]| {
            robot.coriolis(q, qd)
        });
        run($c, name, "gravity", "generated", &s, |[q, _, _]| {
            g.gravity(q)
        });
        run($c, name, "gravity", "runtime", &d, |[q, _, _]| {
            robot.gravity(q)
        });
        run($c, name, "kinetic_energy", "generated", &s, |[q, qd, _]| {
            g.kinetic_energy(q, qd)
        });
        run($c, name, "kinetic_energy", "runtime", &d, |[q, qd, _]| {
            robot.kinetic_energy(q, qd)
        });
        run(
            $c,
            name,
            "potential_energy",
            "generated",
            &s,
            |[q, _, _]| g.potential_energy(q),
        );
        run($c, name, "potential_energy", "runtime", &d, |[q, _, _]| {
            robot.potential_energy(q)
        });
        run(
            $c,
            name,
            "inverse_dynamics",
            "generated",
            &s,
            |[q, qd, qdd]| g.inverse_dynamics(q, qd, qdd),
        );
        run(
            $c,
            name,
            "inverse_dynamics",
            "runtime",
            &d,
            |[q, qd, qdd]| robot.inverse_dynamics(q, qd, qdd),
        );
        run(
            $c,
            name,
            "forward_dynamics",
            "generated",
            &s,
            |[q, qd, tau]| g.forward_dynamics(q, qd, tau),
        );
        run(
            $c,
            name,
            "forward_dynamics",
            "runtime",
            &d,
            |[q, qd, tau]| robot.forward_dynamics(q, qd, tau),
        );
    }};
}

fn random_arms(c: &mut Criterion) {
    bench_arm!(c, general_6);
    bench_arm!(c, general_8);
    bench_arm!(c, general_10);
    bench_arm!(c, general_12);
    bench_arm!(c, industrial_6);
    bench_arm!(c, industrial_8);
    bench_arm!(c, industrial_10);
    bench_arm!(c, industrial_12);
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(200)).measurement_time(Duration::from_millis(700)).sample_size(30);
    targets = random_arms
}
criterion_main!(benches);
