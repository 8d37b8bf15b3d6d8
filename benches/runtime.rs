//! Timings of the generic runtime path `dhgen::Robot`: the baseline the generated code is
//! measured against. Every call takes the next of 64 fixed random states (seeded, within
//! the joint limits), so that no single configuration's branch pattern or cache is timed.
//!
//! `cargo bench --bench runtime -- --warm-up-time 1 --measurement-time 2`

use criterion::{Criterion, criterion_group, criterion_main};
use dhgen::nalgebra::DVector;
use dhgen::{Arm, Robot};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::f64::consts::PI;
use std::hint::black_box;

const STATES: usize = 64;

/// A joint state: position, velocity, acceleration and the torque producing it.
struct State {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    tau: Vec<f64>,
    /// `q` and `qd` as the `Arm` trait takes them.
    q_vector: DVector<f64>,
    qd_vector: DVector<f64>,
}

fn states(robot: &Robot, seed: u64) -> Vec<State> {
    let mut rng = StdRng::seed_from_u64(seed);
    (0..STATES)
        .map(|_| {
            let q: Vec<f64> = robot
                .model()
                .links
                .iter()
                .map(|l| {
                    let [lo, hi] = l.limits.unwrap_or([-PI, PI]);
                    rng.random_range(lo..hi)
                })
                .collect();
            let qd: Vec<f64> = (0..robot.dof())
                .map(|_| rng.random_range(-2.0..2.0))
                .collect();
            let qdd: Vec<f64> = (0..robot.dof())
                .map(|_| rng.random_range(-5.0..5.0))
                .collect();
            let tau = robot.inverse_dynamics(&q, &qd, &qdd).as_slice().to_vec();
            let (q_vector, qd_vector) =
                (DVector::from_vec(q.clone()), DVector::from_vec(qd.clone()));
            State {
                q,
                qd,
                qdd,
                tau,
                q_vector,
                qd_vector,
            }
        })
        .collect()
}

/// Times `f` on the states in turn.
fn cycle<R>(c: &mut Criterion, group: &str, name: &str, states: &[State], f: impl Fn(&State) -> R) {
    c.benchmark_group(group).bench_function(name, |b| {
        let mut i = 0;
        b.iter(|| {
            let state = black_box(&states[i % STATES]);
            i += 1;
            black_box(f(state))
        })
    });
}

fn bench_robot(c: &mut Criterion, name: &str) {
    let path = format!("{}/robots/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let robot = Robot::from_toml_file(path).unwrap();
    let states = states(&robot, 0x5EED_0000 + robot.dof() as u64);
    cycle(c, name, "fk", &states, |s| robot.fk(&s.q));
    cycle(c, name, "frames", &states, |s| robot.frames(&s.q));
    cycle(c, name, "jacobian", &states, |s| robot.jacobian(&s.q));
    cycle(c, name, "body_jacobian", &states, |s| {
        Arm::body_jacobian(&robot, &s.q_vector)
    });
    cycle(c, name, "body_jdot_qdot", &states, |s| {
        Arm::body_jdot_qdot(&robot, &s.q_vector, &s.qd_vector)
    });
    cycle(c, name, "mass_matrix", &states, |s| robot.mass_matrix(&s.q));
    cycle(c, name, "christoffel", &states, |s| robot.christoffel(&s.q));
    cycle(c, name, "coriolis", &states, |s| {
        robot.coriolis(&s.q, &s.qd)
    });
    cycle(c, name, "gravity", &states, |s| robot.gravity(&s.q));
    cycle(c, name, "inverse_dynamics", &states, |s| {
        robot.inverse_dynamics(&s.q, &s.qd, &s.qdd)
    });
    cycle(c, name, "forward_dynamics", &states, |s| {
        robot.forward_dynamics(&s.q, &s.qd, &s.tau)
    });
}

fn runtime(c: &mut Criterion) {
    bench_robot(c, "puma560");
    bench_robot(c, "panda");
}

criterion_group!(benches, runtime);
criterion_main!(benches);
