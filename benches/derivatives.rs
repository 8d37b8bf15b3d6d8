//! The derivatives of the dynamics, generated (`robot!(..., derivatives)`) against the runtime
//! path's analytic O(n²) recursion, next to inverse dynamics itself for scale:
//! `{robot}/{quantity}/{generated|generated_f32|runtime}`. Every call takes the next of 64 fixed random
//! states.
//!
//! `cargo bench --bench derivatives`
//!
//! Pinocchio 4.1.0 on the same models and machine (`scripts/pinocchio_bench.sh`: its templates
//! compiled with `-O3 -march=native`, which includes AVX-512 on this host; two rounds alternating
//! with this benchmark, 2026-12-01, a later session): PUMA 560 `rnea` 0.58–0.61 µs,
//! `computeRNEADerivatives` 2.03–2.05 µs, `computeABADerivatives` 2.57–2.60 µs; Panda
//! 0.69–0.71, 2.41–2.43 and 3.13–3.21 µs. Generated here, the same rounds, default target:
//! PUMA 560 ∂τ 183–185 and ∂q̈ 398–416 ns; Panda 704–720 and 951–960 ns; built with
//! `RUSTFLAGS="-C target-cpu=x86-64-v3"`: PUMA 560 159–162 and 277–279 ns, Panda 416–417 and
//! 649–652 ns. (These large functions move with code layout: the same code took 598 and 877 ns
//! for the Panda on the default target in another build the same session; the PUMA 560's ∂q̈
//! 411 to 567 ns in three builds of an earlier session with the same instructions.)
//! Instructions per call (`scripts/pinocchio_bench.sh --callgrind`,
//! `examples/instructions.rs`): Pinocchio 24,364 and 33,754 (PUMA 560), 29,094 and 40,623
//! (Panda); generated 3,783 and 6,021, 7,459 and 10,656. Both for x86-64-v3 (`--callgrind
//! -march=x86-64-v3`): Pinocchio 20,431 and 29,907, 24,394 and 35,002; generated 2,692 and
//! 4,012, 5,353 and 7,197. Ḋ and Cᵀq̇ (default target, an earlier session): PUMA 560 77 and
//! 52 ns (runtime 575 and 615), Panda 163 and 142 ns (705 and 696).

use criterion::{Criterion, criterion_group, criterion_main};
use dhgen::Robot;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
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
