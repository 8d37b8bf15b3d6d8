//! Timings of inverse kinematics and velocity kinematics on generated robots: the closed
//! form by kinematic decoupling (all solutions, each verified by forward kinematics; the
//! bar to beat is IKFast's published ~4 µs per solve), the numeric solver from nearby and
//! from random seeds, redundancy resolution (`solve_preferring`), and the velocity-kinematics
//! helpers. Every call takes the next of 64
//! fixed random poses (seeded, from joint vectors within the limits).
//!
//! `cargo bench --bench ik -- --warm-up-time 1 --measurement-time 2`

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use dhgen::Arm;
use dhgen::ik::{DecoupledIk, NumericIk, Preference};
use dhgen::nalgebra::{Isometry3, SVector, Vector6};
use dhgen::velocity::{Damping, JacobianSvd, inverse_velocity};
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::hint::black_box;

dhgen::robot!(mod puma560 = "robots/puma560.toml");
dhgen::robot!(mod stanford = "robots/stanford.toml");
dhgen::robot!(mod panda = "robots/panda.toml");
dhgen::robot!(mod snake17 = "tests/fixtures/snake17.toml");

const STATES: usize = 64;

struct Case<const N: usize> {
    q: SVector<f64, N>,
    pose: Isometry3<f64>,
    near: SVector<f64, N>,
    random: SVector<f64, N>,
}

fn cases<const N: usize, A: Arm<Dof = dhgen::nalgebra::Const<N>>>(
    arm: &A,
    seed: u64,
) -> Vec<Case<N>> {
    let mut rng = StdRng::seed_from_u64(seed);
    let within = |rng: &mut StdRng| {
        SVector::<f64, N>::from_fn(|j, _| {
            let [lo, hi] = arm.limits(j).unwrap_or([-3.0, 3.0]);
            rng.random_range(lo..hi)
        })
    };
    (0..STATES)
        .map(|_| {
            let q = within(&mut rng);
            let random = within(&mut rng);
            let near = q + SVector::<f64, N>::from_fn(|_, _| rng.random_range(-0.1..0.1));
            Case {
                pose: arm.fk(&q),
                q,
                near,
                random,
            }
        })
        .collect()
}

fn cycle<const N: usize, R>(
    c: &mut Criterion,
    group: &str,
    name: &str,
    variant: &str,
    cases: &[Case<N>],
    f: impl Fn(&Case<N>) -> R,
) {
    c.benchmark_group(group)
        .bench_function(BenchmarkId::new(name, variant), |b| {
            let mut i = 0;
            b.iter(|| {
                let s = black_box(&cases[i % STATES]);
                i += 1;
                black_box(f(s))
            })
        });
}

fn closed_form(c: &mut Criterion) {
    let puma = cases::<6, _>(&puma560::Robot, 560);
    let ik = DecoupledIk::from_chain(puma560::CHAIN).unwrap();
    cycle(
        c,
        "puma560",
        "ik_closed_form",
        "all_solutions",
        &puma,
        |s| ik.solve(&s.pose),
    );
    let st = cases::<6, _>(&stanford::Robot, 1969);
    let ik = DecoupledIk::from_chain(stanford::CHAIN).unwrap();
    cycle(c, "stanford", "ik_closed_form", "all_solutions", &st, |s| {
        ik.solve(&s.pose)
    });
}

fn numeric(c: &mut Criterion) {
    let solver = NumericIk::default();
    let puma = cases::<6, _>(&puma560::Robot, 560);
    cycle(c, "puma560", "ik_numeric", "near_seed", &puma, |s| {
        solver.solve(&puma560::Robot, &s.pose, &s.near)
    });
    cycle(c, "puma560", "ik_numeric", "random_seed", &puma, |s| {
        solver.solve(&puma560::Robot, &s.pose, &s.random)
    });
    let pd = cases::<7, _>(&panda::Robot, 7);
    cycle(c, "panda", "ik_numeric", "near_seed", &pd, |s| {
        solver.solve(&panda::Robot, &s.pose, &s.near)
    });
    cycle(c, "panda", "ik_numeric", "random_seed", &pd, |s| {
        solver.solve(&panda::Robot, &s.pose, &s.random)
    });
}

/// Redundancy resolution: from a random seed, the solution nearest the middle of the limits
/// (the 7-joint Panda, and the 17-joint snake whose limits the active set holds joints on).
fn preferring(c: &mut Criterion) {
    fn middle<const N: usize, A: Arm<Dof = dhgen::nalgebra::Const<N>>>(arm: &A) -> SVector<f64, N> {
        SVector::from_fn(|j, _| {
            let [lo, hi] = arm.limits(j).unwrap_or([0.0, 0.0]);
            0.5 * (lo + hi)
        })
    }
    let solver = NumericIk::default();
    let pd = cases::<7, _>(&panda::Robot, 7);
    let posture = middle::<7, _>(&panda::Robot);
    cycle(c, "panda", "ik_preferring", "nearest_middle", &pd, |s| {
        solver.solve_preferring(
            &panda::Robot,
            &s.pose,
            &s.random,
            Preference::Posture(&posture),
        )
    });
    let snake = cases::<17, _>(&snake17::Robot, 17);
    let posture = middle::<17, _>(&snake17::Robot);
    cycle(
        c,
        "snake17",
        "ik_preferring",
        "nearest_middle",
        &snake,
        |s| {
            solver.solve_preferring(
                &snake17::Robot,
                &s.pose,
                &s.random,
                Preference::Posture(&posture),
            )
        },
    );
}

fn velocity(c: &mut Criterion) {
    let puma = cases::<6, _>(&puma560::Robot, 560);
    let xi = Vector6::new(0.1, -0.2, 0.05, 0.3, 0.0, -0.1);
    cycle(c, "puma560", "svd", "jacobian", &puma, |s| {
        JacobianSvd::new(&puma560::Robot.jacobian(&s.q))
    });
    cycle(c, "puma560", "inverse_velocity", "damped", &puma, |s| {
        inverse_velocity(&puma560::Robot, &s.q, &xi, None, &Damping::default())
    });
    cycle(c, "puma560", "jdot_qdot", "analytic", &puma, |s| {
        dhgen::Arm::jdot_qdot(&puma560::Robot, &s.q, &s.near)
    });
}

criterion_group!(benches, closed_form, numeric, preferring, velocity);
criterion_main!(benches);
