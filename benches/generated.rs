//! Generated code against the runtime path, per catalogue robot with dynamics and per
//! quantity: `{robot}/{quantity}/{generated_f64|generated_f32|runtime}`, plus the
//! controller's combined "all terms at one q" (D, C, g, J), and the task-space dynamics of
//! the tool (`task_space/{robot}/...`) for the PUMA 560 and the Panda. Every call takes the next of 64
//! fixed random states, so the optimiser cannot fold a constant configuration.
//!
//! `cargo bench --bench generated`, then `cargo run --release --example bench_report`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use dhgen::Robot;
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::f64::consts::PI;
use std::hint::black_box;
use std::time::Duration;

const STATES: usize = 64;

dhgen::robot!(mod planar_elbow = "robots/planar_elbow.toml");
dhgen::robot!(mod puma560 = "robots/puma560.toml");
dhgen::robot!(mod stanford = "robots/stanford.toml");
dhgen::robot!(mod panda = "robots/panda.toml");
dhgen::robot!(mod scara = "robots/scara.toml");
dhgen::robot!(mod ur5 = "robots/ur5.toml");

/// One random state in three representations.
struct Sample<const N: usize> {
    q: [f64; N],
    qd: [f64; N],
    qdd: [f64; N],
    tau: [f64; N],
    q32: [f32; N],
    qd32: [f32; N],
    qdd32: [f32; N],
    tau32: [f32; N],
}

fn samples<const N: usize>(robot: &Robot, seed: u64) -> Vec<Sample<N>> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..STATES)
        .map(|_| {
            let q: [f64; N] = core::array::from_fn(|j| {
                let [lo, hi] = robot.model().links[j].limits.unwrap_or([-PI, PI]);
                rng.random_range(lo..hi)
            });
            let qd: [f64; N] = core::array::from_fn(|_| rng.random_range(-2.0..2.0));
            let qdd: [f64; N] = core::array::from_fn(|_| rng.random_range(-5.0..5.0));
            let t = robot.inverse_dynamics(&q, &qd, &qdd);
            let tau: [f64; N] = core::array::from_fn(|j| t[j]);
            let f = |a: [f64; N]| a.map(|x| x as f32);
            Sample {
                q,
                qd,
                qdd,
                tau,
                q32: f(q),
                qd32: f(qd),
                qdd32: f(qdd),
                tau32: f(tau),
            }
        })
        .collect()
}

fn cycle<const N: usize, R>(
    c: &mut Criterion,
    robot: &str,
    quantity: &str,
    variant: &str,
    samples: &[Sample<N>],
    f: impl Fn(&Sample<N>) -> R,
) {
    c.benchmark_group(robot)
        .bench_function(BenchmarkId::new(quantity, variant), |b| {
            let mut i = 0;
            b.iter(|| {
                let s = black_box(&samples[i % STATES]);
                i += 1;
                black_box(f(s))
            })
        });
}

macro_rules! bench_robot {
    ($c:expr, $m:ident) => {{
        use $m as g;
        const N: usize = g::DOF;
        let name = stringify!($m);
        let robot =
            Robot::from_toml_file(format!("{}/robots/{name}.toml", env!("CARGO_MANIFEST_DIR")))
                .unwrap();
        let s = samples::<N>(&robot, 0x5EED_0000 + N as u64);
        let c: &mut Criterion = &mut *$c;
        cycle(c, name, "fk", "generated_f64", &s, |s| g::fk(&s.q));
        cycle(c, name, "fk", "generated_f32", &s, |s| g::fk(&s.q32));
        cycle(c, name, "fk", "runtime", &s, |s| robot.fk(&s.q));
        cycle(c, name, "frames", "generated_f64", &s, |s| g::frames(&s.q));
        cycle(c, name, "frames", "generated_f32", &s, |s| {
            g::frames(&s.q32)
        });
        cycle(c, name, "frames", "runtime", &s, |s| robot.frames(&s.q));
        cycle(c, name, "jacobian", "generated_f64", &s, |s| {
            g::jacobian(&s.q)
        });
        cycle(c, name, "jacobian", "generated_f32", &s, |s| {
            g::jacobian(&s.q32)
        });
        cycle(c, name, "jacobian", "runtime", &s, |s| robot.jacobian(&s.q));
        cycle(c, name, "mass_matrix", "generated_f64", &s, |s| {
            g::mass_matrix(&s.q)
        });
        cycle(c, name, "mass_matrix", "generated_f32", &s, |s| {
            g::mass_matrix(&s.q32)
        });
        cycle(c, name, "mass_matrix", "runtime", &s, |s| {
            robot.mass_matrix(&s.q)
        });
        cycle(c, name, "christoffel", "generated_f64", &s, |s| {
            g::christoffel(&s.q)
        });
        cycle(c, name, "christoffel", "generated_f32", &s, |s| {
            g::christoffel(&s.q32)
        });
        cycle(c, name, "christoffel", "runtime", &s, |s| {
            robot.christoffel(&s.q)
        });
        cycle(c, name, "coriolis", "generated_f64", &s, |s| {
            g::coriolis(&s.q, &s.qd)
        });
        cycle(c, name, "coriolis", "generated_f32", &s, |s| {
            g::coriolis(&s.q32, &s.qd32)
        });
        cycle(c, name, "coriolis", "runtime", &s, |s| {
            robot.coriolis(&s.q, &s.qd)
        });
        cycle(c, name, "center_of_mass", "generated_f64", &s, |s| {
            g::center_of_mass(&s.q)
        });
        cycle(c, name, "center_of_mass", "runtime", &s, |s| {
            robot.center_of_mass(&s.q)
        });
        cycle(
            c,
            name,
            "center_of_mass_jacobian",
            "generated_f64",
            &s,
            |s| g::center_of_mass_jacobian(&s.q),
        );
        cycle(c, name, "center_of_mass_jacobian", "runtime", &s, |s| {
            robot.center_of_mass_jacobian(&s.q)
        });
        cycle(c, name, "gravity", "generated_f64", &s, |s| {
            g::gravity(&s.q)
        });
        cycle(c, name, "gravity", "generated_f32", &s, |s| {
            g::gravity(&s.q32)
        });
        cycle(c, name, "gravity", "runtime", &s, |s| robot.gravity(&s.q));
        cycle(c, name, "inverse_dynamics", "generated_f64", &s, |s| {
            g::inverse_dynamics(&s.q, &s.qd, &s.qdd)
        });
        cycle(c, name, "inverse_dynamics", "generated_f32", &s, |s| {
            g::inverse_dynamics(&s.q32, &s.qd32, &s.qdd32)
        });
        cycle(c, name, "inverse_dynamics", "runtime", &s, |s| {
            robot.inverse_dynamics(&s.q, &s.qd, &s.qdd)
        });
        cycle(c, name, "forward_dynamics", "generated_f64", &s, |s| {
            g::forward_dynamics(&s.q, &s.qd, &s.tau)
        });
        cycle(c, name, "forward_dynamics", "generated_f32", &s, |s| {
            g::forward_dynamics(&s.q32, &s.qd32, &s.tau32)
        });
        cycle(c, name, "forward_dynamics", "runtime", &s, |s| {
            robot.forward_dynamics(&s.q, &s.qd, &s.tau)
        });
        // A controller's needs at one configuration: shared sin/cos versus separate calls.
        cycle(c, name, "all_terms", "generated_f64", &s, |s| {
            g::State::new(&s.q).terms(&s.qd)
        });
        cycle(c, name, "all_terms", "generated_f32", &s, |s| {
            g::State::new(&s.q32).terms(&s.qd32)
        });
        cycle(c, name, "all_terms", "separate_f64", &s, |s| {
            (
                g::mass_matrix(&s.q),
                g::coriolis(&s.q, &s.qd),
                g::gravity(&s.q),
                g::jacobian(&s.q),
            )
        });
        cycle(c, name, "all_terms", "runtime", &s, |s| {
            (
                robot.mass_matrix(&s.q),
                robot.coriolis(&s.q, &s.qd),
                robot.gravity(&s.q),
                robot.jacobian(&s.q),
            )
        });
    }};
}

/// Task-space dynamics of the tool (`dhgen::task_space::tool`: Λ, J̄, μ, p) from the generated
/// arm's D, J, J̇ q̇, bias and g, against the same function on the runtime path, without and
/// with a payload (`tool_with_payload`):
/// `task_space/{robot}/{generated_f64|runtime|with_payload_generated_f64|with_payload_runtime}`.
macro_rules! bench_task_space {
    ($c:expr, $m:ident) => {{
        use dhgen::nalgebra::{DVector, SVector};
        const N: usize = $m::DOF;
        let name = stringify!($m);
        let robot =
            Robot::from_toml_file(format!("{}/robots/{name}.toml", env!("CARGO_MANIFEST_DIR")))
                .unwrap();
        let s = samples::<N>(&robot, 0x5EED_0000 + N as u64);
        let fixed: Vec<_> = s
            .iter()
            .map(|s| (SVector::from(s.q), SVector::from(s.qd)))
            .collect();
        let dynamic: Vec<_> = s
            .iter()
            .map(|s| {
                (
                    DVector::from_column_slice(&s.q),
                    DVector::from_column_slice(&s.qd),
                )
            })
            .collect();
        let c: &mut Criterion = &mut *$c;
        let mut group = c.benchmark_group("task_space");
        let mut i = 0;
        group.bench_function(BenchmarkId::new(name, "generated_f64"), |b| {
            b.iter(|| {
                let (q, qd) = black_box(&fixed[i % STATES]);
                i += 1;
                black_box(dhgen::task_space::tool(&$m::Robot, q, qd).ok())
            })
        });
        group.bench_function(BenchmarkId::new(name, "runtime"), |b| {
            b.iter(|| {
                let (q, qd) = black_box(&dynamic[i % STATES]);
                i += 1;
                black_box(dhgen::task_space::tool(&robot, q, qd).ok())
            })
        });
        // The same holding a payload (1.7 kg, off-centre, products of inertia).
        let part = dhgen::payload::Payload::new(
            1.7,
            [0.03, -0.02, 0.07],
            [[3e-3, 2e-4, -1e-4], [2e-4, 4e-3, 3e-4], [-1e-4, 3e-4, 2e-3]],
        )
        .unwrap();
        group.bench_function(BenchmarkId::new(name, "with_payload_generated_f64"), |b| {
            b.iter(|| {
                let (q, qd) = black_box(&fixed[i % STATES]);
                i += 1;
                black_box(dhgen::task_space::tool_with_payload(&$m::Robot, &part, q, qd).ok())
            })
        });
        group.bench_function(BenchmarkId::new(name, "with_payload_runtime"), |b| {
            b.iter(|| {
                let (q, qd) = black_box(&dynamic[i % STATES]);
                i += 1;
                black_box(dhgen::task_space::tool_with_payload(&robot, &part, q, qd).ok())
            })
        });
    }};
}

fn generated(c: &mut Criterion) {
    bench_task_space!(c, puma560);
    bench_task_space!(c, panda);
    bench_robot!(c, puma560);
    bench_robot!(c, panda);
    bench_robot!(c, planar_elbow);
    bench_robot!(c, stanford);
    bench_robot!(c, scara);
    bench_robot!(c, ur5);
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_millis(1200)).sample_size(50);
    targets = generated
}
criterion_main!(benches);
