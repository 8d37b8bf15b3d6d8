//! Forward dynamics on singular and nearly singular inertia matrices: `None` exactly where
//! `D(q)` is singular to working precision, by the one rule both paths follow
//! (`dhgen::cholesky_pivot_floor`), and a correct solve everywhere else.

use crate::catalogue::{stiff_wrist, ur5, weightless_wrist};
use crate::support::{fixture, runtime};
use dhgen::nalgebra::SVector;
use dhgen::{Robot, cholesky_pivot_floor};

/// A fixed stream of configurations in [−π, π).
fn configurations<const N: usize>(count: usize) -> Vec<[f64; N]> {
    let mut x = 0x2545_F491_4F6C_DD1D_u64;
    (0..count)
        .map(|_| {
            core::array::from_fn(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 11) as f64 / (1u64 << 53) as f64 * std::f64::consts::TAU
                    - std::f64::consts::PI
            })
        })
        .collect()
}

#[test]
fn ur5_without_inertias_has_no_forward_dynamics_anywhere() {
    // UR publish no inertia tensors; link 6's centre of mass is on joint 6's axis, so D is
    // singular at every configuration. Rounding leaves a tiny positive pivot, which must not
    // be taken for inertia.
    let robot = runtime("ur5");
    for q in configurations::<6>(300) {
        let qd = q.map(|x| 0.3 * x);
        let tau = [1.0, -2.0, 0.5, 0.1, -0.2, 0.05];
        assert_eq!(
            ur5::forward_dynamics(&q, &qd, &tau),
            None,
            "generated at {q:?}"
        );
        assert_eq!(
            robot.forward_dynamics(&q, &qd, &tau),
            None,
            "runtime at {q:?}"
        );
    }
}

#[test]
fn an_exactly_singular_inertia_matrix_gives_none_on_both_paths() {
    let robot = fixture("weightless_wrist");
    for q in configurations::<2>(50) {
        assert_eq!(robot.mass_matrix(&q)[(1, 1)], 0.0);
        let tau = [1.0, 0.0];
        assert_eq!(robot.forward_dynamics(&q, &[0.0; 2], &tau), None);
        assert_eq!(
            weightless_wrist::forward_dynamics(&q, &[0.0; 2], &tau),
            None
        );
        assert_eq!(
            weightless_wrist::forward_dynamics(&q.map(|x| x as f32), &[0.0; 2], &[1.0, 0.0]),
            None
        );
    }
}

#[test]
fn a_nearly_singular_inertia_matrix_is_still_solved() {
    // D22 = 1e-9 against D11 ≈ 0.33: a condition number near 1e9, far above the f64 floor.
    let robot = fixture("stiff_wrist");
    for q in configurations::<2>(50) {
        let qd = [0.4, -0.7];
        let qdd = [1.5, -3.0];
        let tau = robot.inverse_dynamics(&q, &qd, &qdd);
        let runtime = robot.forward_dynamics(&q, &qd, &tau).expect("regular D");
        let tau = SVector::<f64, 2>::from_column_slice(tau.as_slice());
        let generated = stiff_wrist::forward_dynamics(&q, &qd, &tau).expect("regular D");
        for (i, want) in qdd.iter().enumerate() {
            // The solve amplifies rounding by the condition number: 1e9 · 1e-16.
            assert!(
                (runtime[i] - want).abs() < 1e-5,
                "runtime {runtime} at {q:?}"
            );
            assert!(
                (generated[i] - want).abs() < 1e-5,
                "generated {generated} at {q:?}"
            );
        }
    }
}

#[test]
fn both_paths_draw_the_line_at_the_same_pivot() {
    // A diagonal inertia matrix diag(1, ε_k): the pivot of joint 2 is ε_k itself. Walking ε
    // down through the floor, forward dynamics answers `Some` above it and `None` at or
    // below it, on the runtime path built with that inertia.
    let floor = cholesky_pivot_floor(2, 1.0_f64);
    assert!(floor > 0.0 && floor < 1e-12);
    for scale in [1e3, 10.0, 2.0, 1.0, 0.5, 1e-3] {
        let pivot = floor * scale;
        let robot = weightless_with_inertia(pivot);
        let d = robot.mass_matrix(&[0.0; 2]);
        let result = robot.forward_dynamics(&[0.0; 2], &[0.0; 2], &[0.0, 0.0]);
        // D11 = 1 by construction (joint 1 carries unit inertia about its axis).
        assert_eq!(d[(1, 1)], pivot);
        assert_eq!(d[(0, 0)], 1.0 + pivot);
        let floor = cholesky_pivot_floor(2, d[(0, 0)]);
        assert_eq!(
            result.is_some(),
            pivot > floor,
            "pivot {pivot:e}, floor {floor:e}"
        );
    }
    // The rule itself: relative to the largest diagonal entry, and to the scalar's precision.
    assert_eq!(
        cholesky_pivot_floor(4, 2.0_f64),
        2.0 * cholesky_pivot_floor(2, 2.0_f64)
    );
    assert!(cholesky_pivot_floor(2, 1.0_f32) > 1e-6);
}

/// Two joints on one axis at the origin: link 1 a unit inertia about z, link 2 a point-free
/// body with inertia `zz` about z.
fn weightless_with_inertia(zz: f64) -> Robot {
    Robot::from_toml_str(&format!(
        r#"
name = "coaxial"
convention = "standard"
[[links]]
joint = "revolute"
a = 0
alpha = 0
d = 0
theta = 0
mass = 1.0
com = [0, 0, 0]
inertia = {{ xx = 1.0, yy = 1.0, zz = 1.0 }}
[[links]]
joint = "revolute"
a = 0
alpha = 0
d = 0
theta = 0
mass = 0.0
com = [0, 0, 0]
inertia = {{ xx = {zz:e}, yy = {zz:e}, zz = {zz:e} }}
"#
    ))
    .unwrap()
}

#[test]
fn generated_and_runtime_agree_on_regular_arms() {
    // The floor must not reject a healthy arm: the PUMA 560 everywhere.
    let robot = runtime("puma560");
    for q in configurations::<6>(100) {
        let tau = SVector::<f64, 6>::from([1.0, 2.0, -1.0, 0.1, 0.2, -0.1]);
        assert!(crate::catalogue::puma560::forward_dynamics(&q, &[0.0; 6], &tau).is_some());
        assert!(robot.forward_dynamics(&q, &[0.0; 6], &tau).is_some());
    }
}
