//! Many configurations per call (`dhgen::batch`, SIMD packs) against one at a time, and the
//! branch-free sine and cosine against `libm`'s.
//!
//! `{robot}/{quantity}/{scalar_f64|batch_f64x4|packs_f64x4}` evaluates the same 64 seeded configurations
//! (`scalar`: a loop of the generated function; `batch`: the module's `batch` function over
//! the slice; `packs`: the generated function called on the 16 packs themselves, the
//! values left as packs): divide by 64 for the time per configuration;
//! `{scalar_f32|batch_f32x8|packs_f32x8}` the same configurations in `f32` (8 packs of 8).
//! `sincos/{dhgen|dhgen_f64x4|libm|dhgen_f32x8|libm_f32}`: 64 angles in [−π, π], one at a
//! time or four (eight) per pack.
//!
//! `cargo bench --bench batch`.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use std::hint::black_box;
use std::time::Duration;

dhgen::robot!(mod puma560 = "robots/puma560.toml");
dhgen::robot!(mod panda = "robots/panda.toml");

const STATES: usize = 64;

fn states<const N: usize>(seed: u64) -> Vec<[f64; N]> {
    let mut s = seed;
    let mut next = move || {
        s = s
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((s >> 11) as f64 / (1u64 << 53) as f64) * 2.0 * std::f64::consts::PI - std::f64::consts::PI
    };
    (0..STATES)
        .map(|_| std::array::from_fn(|_| next()))
        .collect()
}

/// The seed of the states an input name stands for (q uses 1).
macro_rules! seed {
    (qd) => {
        2
    };
    (qdd) => {
        3
    };
}

/// Four configurations per pack.
fn packs<const N: usize>(v: &[[f64; N]]) -> Vec<[dhgen::batch::WideF64x4; N]> {
    v.chunks(4)
        .map(|c| {
            std::array::from_fn(|j| {
                dhgen::batch::WideF64x4([c[0][j], c[1][j], c[2][j], c[3][j]].into())
            })
        })
        .collect()
}

/// The same configurations in `f32`.
fn narrow<const N: usize>(v: &[[f64; N]]) -> Vec<[f32; N]> {
    v.iter().map(|x| x.map(|e| e as f32)).collect()
}

/// Eight `f32` configurations per pack.
fn packs8<const N: usize>(v: &[[f32; N]]) -> Vec<[dhgen::batch::WideF32x8; N]> {
    v.chunks(8)
        .map(|c| {
            std::array::from_fn(|j| {
                dhgen::batch::WideF32x8(std::array::from_fn::<f32, 8, _>(|l| c[l][j]).into())
            })
        })
        .collect()
}

macro_rules! pair {
    ($c:expr, $m:ident, $name:literal, $f:ident($($x:ident),*)) => {
        pair!($c, $m, $name, $f($($x),*), $f)
    };
    ($c:expr, $m:ident, $name:literal, $f:ident($($x:ident),*), $packed:ident) => {{
        use $m as g;
        const N: usize = g::DOF;
        // q and each input the function takes (q̇, q̈), under their own names.
        let q = states::<N>(1);
        $(let $x = states::<N>(seed!($x));)*
        let mut group = $c.benchmark_group(stringify!($m));
        rows!(group, g, $name, $f($($x),*), $packed, q, packs, 4, ["scalar_f64", "batch_f64x4", "packs_f64x4"]);
        // The same configurations in f32: one at a time, by the batch function, by packs of 8.
        let q = narrow(&q);
        $(let $x = narrow(&$x);)*
        rows!(group, g, $name, $f($($x),*), $packed, q, packs8, 8, ["scalar_f32", "batch_f32x8", "packs_f32x8"]);
        group.finish();
    }};
}

/// The three ways of one scalar type: a loop of the scalar function, the batch function, the
/// function on packs of `$width` (made by `$pack`), on `$q` and the inputs named `$x`.
macro_rules! rows {
    ($group:ident, $g:ident, $name:literal, $f:ident($($x:ident),*), $packed:ident, $q:ident, $pack:ident, $width:literal, [$scalar:literal, $batch:literal, $packs:literal]) => {{
        $group.bench_function(BenchmarkId::new($name, $scalar), |b| {
            b.iter(|| {
                let q = black_box(&$q);
                for c in 0..STATES {
                    black_box($g::$f(&q[c], $(&$x[c]),*));
                }
            })
        });
        let mut out = vec![$g::$f(&$q[0], $(&$x[0]),*); STATES];
        $group.bench_function(BenchmarkId::new($name, $batch), |b| {
            b.iter(|| {
                $g::batch::$f(black_box(&$q), $(black_box(&$x),)* &mut out).unwrap();
                black_box(&out);
            })
        });
        let q = $pack(&$q);
        $(let $x = $pack(&$x);)*
        $group.bench_function(BenchmarkId::new($name, $packs), |b| {
            b.iter(|| {
                let q = black_box(&q);
                for c in 0..STATES / $width {
                    black_box($g::$packed(&q[c], $(&$x[c]),*));
                }
            })
        });
    }};
}

macro_rules! robot {
    ($c:expr, $m:ident) => {{
        pair!($c, $m, "fk", fk());
        pair!($c, $m, "fk_matrix", fk_matrix());
        pair!($c, $m, "jacobian", jacobian());
        pair!($c, $m, "mass_matrix", mass_matrix());
        pair!($c, $m, "christoffel", christoffel());
        pair!($c, $m, "coriolis", coriolis(qd));
        pair!($c, $m, "gravity", gravity());
        pair!($c, $m, "inverse_dynamics", inverse_dynamics(qd, qdd));
        pair!(
            $c,
            $m,
            "forward_dynamics",
            forward_dynamics(qd, qdd),
            forward_dynamics_lanes
        );
    }};
}

fn batch(c: &mut Criterion) {
    let angles: Vec<f64> = states::<1>(9).into_iter().map(|a| a[0]).collect();
    let mut group = c.benchmark_group("sincos");
    group.bench_function("dhgen", |b| {
        b.iter(|| {
            for &x in black_box(&angles) {
                black_box(dhgen::sincos::sincos(x));
            }
        })
    });
    let angle_packs: Vec<dhgen::batch::WideF64x4> = angles
        .chunks(4)
        .map(|a| dhgen::batch::WideF64x4([a[0], a[1], a[2], a[3]].into()))
        .collect();
    group.bench_function("dhgen_f64x4", |b| {
        b.iter(|| {
            for &x in black_box(&angle_packs) {
                black_box(dhgen::Real::sincos(x));
            }
        })
    });
    group.bench_function("libm", |b| {
        b.iter(|| {
            for &x in black_box(&angles) {
                black_box(libm::sincos(x));
            }
        })
    });
    let angles32: Vec<f32> = angles.iter().map(|&a| a as f32).collect();
    let angle_packs8: Vec<dhgen::batch::WideF32x8> = angles32
        .chunks(8)
        .map(|a| dhgen::batch::WideF32x8(std::array::from_fn::<f32, 8, _>(|l| a[l]).into()))
        .collect();
    group.bench_function("dhgen_f32x8", |b| {
        b.iter(|| {
            for &x in black_box(&angle_packs8) {
                black_box(dhgen::Real::sincos(x));
            }
        })
    });
    group.bench_function("libm_f32", |b| {
        b.iter(|| {
            for &x in black_box(&angles32) {
                black_box(libm::sincosf(x));
            }
        })
    });
    group.finish();
    // Every joint's sine and cosine (`State::new`), one configuration at a time and by packs.
    let q = states::<7>(1);
    let qp = packs(&q);
    let mut group = c.benchmark_group("panda");
    group.bench_function(BenchmarkId::new("state", "scalar_f64"), |b| {
        b.iter(|| {
            for x in black_box(&q) {
                black_box(panda::State::new(x));
            }
        })
    });
    group.bench_function(BenchmarkId::new("state", "packs_f64x4"), |b| {
        b.iter(|| {
            for x in black_box(&qp) {
                black_box(panda::State::new(x));
            }
        })
    });
    group.finish();
    robot!(c, puma560);
    robot!(c, panda);
}

criterion_group! {
    name = benches;
    config = Criterion::default().warm_up_time(Duration::from_millis(300)).measurement_time(Duration::from_millis(1000)).sample_size(30);
    targets = batch
}
criterion_main!(benches);
