//! The no_std build's functions compute what they should: forward dynamics undoes inverse
//! dynamics, and `f32` agrees with `f64` to `f32` precision.

use dhgen_nostd_check::{panda_f32, panda_f64, puma560_f32, puma560_f64};

/// A state away from singularities, with every joint moving.
const Q: [f64; 7] = [0.3, -0.7, 0.5, -1.9, 0.4, 1.1, -0.6];
const QD: [f64; 7] = [0.5, -0.2, 0.8, 0.1, -0.6, 0.3, 0.9];
const QDD: [f64; 7] = [1.0, -0.5, 0.25, 0.75, -1.25, 0.5, -0.3];

fn first<const N: usize>(x: &[f64; 7]) -> [f64; N] {
    core::array::from_fn(|i| x[i])
}

fn narrow<const N: usize>(x: &[f64; N]) -> [f32; N] {
    x.map(|v| v as f32)
}

/// Largest |a - b| relative to max(1, |b|).
fn worst<'a>(a: impl IntoIterator<Item = &'a f32>, b: impl IntoIterator<Item = &'a f64>) -> f64 {
    a.into_iter()
        .zip(b)
        .map(|(x, y)| (f64::from(*x) - y).abs() / y.abs().max(1.0))
        .fold(0.0, f64::max)
}

macro_rules! check {
    ($test:ident, $f64:ident, $f32:ident, $n:literal) => {
        #[test]
        fn $test() {
            let (q, qd, qdd) = (first::<$n>(&Q), first::<$n>(&QD), first::<$n>(&QDD));
            let e = $f64(&q, &qd, &qdd);
            let back = e.acceleration.expect("D(q) is positive definite");
            for i in 0..$n {
                assert!(
                    (back[i] - qdd[i]).abs() <= 1e-9,
                    "joint {i}: forward dynamics gives {}, want {}",
                    back[i],
                    qdd[i]
                );
            }
            let s = $f32(&narrow(&q), &narrow(&qd), &narrow(&qdd));
            let pose = (s.pose.to_homogeneous(), e.pose.to_homogeneous());
            // f32 carries 7 digits; a few hundred roundings in each quantity cost up to
            // about two of them.
            let tol = 1e-5;
            for (what, err) in [
                ("pose", worst(pose.0.iter(), pose.1.iter())),
                ("jacobian", worst(s.jacobian.iter(), e.jacobian.iter())),
                (
                    "mass matrix",
                    worst(s.mass_matrix.iter(), e.mass_matrix.iter()),
                ),
                ("gravity", worst(s.gravity.iter(), e.gravity.iter())),
                ("torque", worst(s.torque.iter(), e.torque.iter())),
            ] {
                assert!(err <= tol, "{what}: f32 differs from f64 by {err:e}");
            }
            // Solving with D(q) costs a further factor of its condition number (~10² here).
            let back = s
                .acceleration
                .expect("D(q) is positive definite in f32 too");
            let err = worst(back.iter(), qdd.iter());
            assert!(err <= 1e-4, "f32 forward dynamics misses q̈ by {err:e}");
        }
    };
}

check!(puma560_in_f64_and_f32, puma560_f64, puma560_f32, 6);
check!(panda_in_f64_and_f32, panda_f64, panda_f32, 7);

/// Every other generated function (derivatives, regressor, payload, batch) runs in the
/// no_std build, in `f64` and `f32`, and the two agree: the sum of one entry of each, to
/// `f32` precision and the conditioning of D(q) that the solved quantities carry.
#[test]
fn everything_else_runs_and_f32_agrees_with_f64() {
    use dhgen_nostd_check::{puma560_everything_f32, puma560_everything_f64};
    let (q, qd, qdd) = (first::<6>(&Q), first::<6>(&QD), first::<6>(&QDD));
    let payload = [
        0.8, 0.01, -0.02, 0.05, 0.004, 0.0001, 0.005, 0.0002, -0.0001, 0.003,
    ];
    let e = puma560_everything_f64(&q, &qd, &qdd, &payload);
    let s = puma560_everything_f32(&narrow(&q), &narrow(&qd), &narrow(&qdd), &narrow(&payload));
    assert!(e.is_finite() && s.is_finite(), "f64 {e}, f32 {s}");
    let err = (f64::from(s) - e).abs() / e.abs().max(1.0);
    assert!(err <= 1e-5, "f32 {s} differs from f64 {e} by {err:e}");
}
