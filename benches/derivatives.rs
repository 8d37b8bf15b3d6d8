//! The derivatives of the dynamics, generated (`robot!(..., derivatives)`) against the runtime
//! path's analytic O(n²) recursion, next to inverse dynamics itself for scale:
//! `{robot}/{quantity}/{generated|generated_f32|runtime}`. Every call takes the next of 64 fixed random
//! states.
//!
//! `cargo bench --bench derivatives`
//!
//! Pinocchio 4.1.0 on the same models and machine, each side built for the same target
//! (`scripts/pinocchio_bench.sh --time ""` for baseline x86-64, `--time -march=x86-64-v3`;
//! two rounds alternating with this benchmark, 2026-12-01, the day's last session; ratios
//! within a round). Default x86-64: PUMA 560 `computeRNEADerivatives` 2.13–2.26 µs against
//! generated ∂τ 189–191 ns (11–12×), `computeABADerivatives` 2.54–2.57 µs against ∂q̈ 344–353
//! ns (7.2–7.5×); Panda 2.48–2.49 µs against 592–615 ns (4.0–4.2×), 3.10–3.11 µs against
//! 848–878 ns (3.5–3.7×). x86-64-v3 (`RUSTFLAGS="-C target-cpu=x86-64-v3"` here): PUMA 560
//! 2.15–2.18 µs against 160–163 ns (13×), 2.43–2.48 µs against 260–265 ns (9.2–9.5×); Panda
//! 2.49–2.54 µs against 430–431 ns (5.8–5.9×), 2.94 µs against 648–652 ns (4.5×). Pinocchio
//! built `-march=native` (AVX-512 on this host) was no faster in an earlier session (Panda
//! 2.52–2.58 and 3.32–3.70 µs). (These large functions move with code layout: the same code
//! took 598 and 877 ns for the Panda on the default target in another build; the PUMA 560's
//! ∂q̈ 411 to 567 ns in three builds of a session with the same instructions.)
//! Instructions per call (`scripts/pinocchio_bench.sh --callgrind`,
//! `examples/instructions.rs`): Pinocchio 24,364 and 33,754 (PUMA 560), 29,094 and 40,623
//! (Panda); generated 3,783 and 5,747, 7,459 and 10,328. Both for x86-64-v3 (`--callgrind
//! -march=x86-64-v3`): Pinocchio 20,431 and 29,907, 24,394 and 35,002; generated 2,692 and
//! 3,806, 5,353 and 6,979. Ḋ and Cᵀq̇ (default target, an earlier session): PUMA 560 77 and
//! 52 ns (runtime 575 and 615), Panda 163 and 142 ns (705 and 696).

use criterion::{Criterion, criterion_group, criterion_main};
use dhgen::Robot;
use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::hint::black_box;
use std::time::Duration;

dhgen::robot!(mod puma560 = "robots/puma560.toml", derivatives);
dhgen::robot!(mod panda = "robots/panda.toml", derivatives);

const STATES: usize = 64;

/// `(q, q̇, q̈, τ)` with τ the inverse dynamics at the others.
type State<const N: usize> = ([f64; N], [f64; N], [f64; N], [f64; N]);
/// The same in `f32`.
type State32<const N: usize> = ([f32; N], [f32; N], [f32; N], [f32; N]);

fn states<const N: usize>(robot: &Robot) -> Vec<State<N>> {
    let mut rng = StdRng::seed_from_u64(21);
    (0..STATES)
        .map(|_| {
            let q: [f64; N] = core::array::from_fn(|_| rng.random_range(-1.5..1.5));
            let qd: [f64; N] = core::array::from_fn(|_| rng.random_range(-2.0..2.0));
            let qdd: [f64; N] = core::array::from_fn(|_| rng.random_range(-5.0..5.0));
            let t = robot.inverse_dynamics(&q, &qd, &qdd);
            (q, qd, qdd, core::array::from_fn(|j| t[j]))
        })
        .collect()
}

macro_rules! bench_robot {
    ($c:expr, $name:literal, $module:ident, $n:literal) => {{
        let robot = Robot::from_toml_file(concat!("robots/", $name, ".toml")).unwrap();
        let s = states::<$n>(&robot);
        let mut g = $c.benchmark_group($name);
        let mut i = 0;
        let mut next = || {
            i = (i + 1) % STATES;
            &s[i]
        };
        g.bench_function("inverse_dynamics/generated", |b| {
            b.iter(|| {
                let (q, qd, qdd, _) = next();
                $module::inverse_dynamics(black_box(q), black_box(qd), black_box(qdd))
            })
        });
        g.bench_function("inverse_dynamics_derivatives/generated", |b| {
            b.iter(|| {
                let (q, qd, qdd, _) = next();
                $module::inverse_dynamics_derivatives(black_box(q), black_box(qd), black_box(qdd))
            })
        });
        let s32: Vec<State32<$n>> = s
            .iter()
            .map(|(q, qd, qdd, tau)| {
                let f = |a: &[f64; $n]| a.map(|x| x as f32);
                (f(q), f(qd), f(qdd), f(tau))
            })
            .collect();
        let mut j = 0;
        let mut next32 = || {
            j = (j + 1) % STATES;
            &s32[j]
        };
        g.bench_function("inverse_dynamics_derivatives/generated_f32", |b| {
            b.iter(|| {
                let (q, qd, qdd, _) = next32();
                $module::inverse_dynamics_derivatives(black_box(q), black_box(qd), black_box(qdd))
            })
        });
        g.bench_function("forward_dynamics_derivatives/generated_f32", |b| {
            b.iter(|| {
                let (q, qd, _, tau) = next32();
                $module::forward_dynamics_derivatives(black_box(q), black_box(qd), black_box(tau))
            })
        });
        g.bench_function("inverse_dynamics_derivatives/runtime", |b| {
            b.iter(|| {
                let (q, qd, qdd, _) = next();
                robot.inverse_dynamics_derivatives(black_box(q), black_box(qd), black_box(qdd))
            })
        });
        g.bench_function("forward_dynamics_derivatives/generated", |b| {
            b.iter(|| {
                let (q, qd, _, tau) = next();
                $module::forward_dynamics_derivatives(black_box(q), black_box(qd), black_box(tau))
            })
        });
        g.bench_function("forward_dynamics_derivatives/runtime", |b| {
            b.iter(|| {
                let (q, qd, _, tau) = next();
                robot.forward_dynamics_derivatives(black_box(q), black_box(qd), black_box(tau))
            })
        });
        g.bench_function("mass_matrix_rate/generated", |b| {
            b.iter(|| {
                let (q, qd, _, _) = next();
                $module::mass_matrix_rate(black_box(q), black_box(qd))
            })
        });
        g.bench_function("mass_matrix_rate/runtime", |b| {
            b.iter(|| {
                let (q, qd, _, _) = next();
                robot.mass_matrix_rate(black_box(q), black_box(qd))
            })
        });
        g.bench_function("coriolis_transpose_qd/generated", |b| {
            b.iter(|| {
                let (q, qd, _, _) = next();
                $module::coriolis_transpose_qd(black_box(q), black_box(qd))
            })
        });
        g.bench_function("coriolis_transpose_qd/runtime", |b| {
            b.iter(|| {
                let (q, qd, _, _) = next();
                robot.coriolis_transpose_qd(black_box(q), black_box(qd))
            })
        });
        g.finish();
    }};
}

fn derivatives(c: &mut Criterion) {
    bench_robot!(c, "puma560", puma560, 6);
    bench_robot!(c, "panda", panda, 7);
}

criterion_group! {
    name = benches;
    config = Criterion::default()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2));
    targets = derivatives
}
criterion_main!(benches);
