//! The output of `dhgen emit robots/puma560.toml`, checked in as `emitted/puma560.rs`
//! (`commands.rs` checks that it is current), compiles against `dhgen` and computes the same
//! numbers as `dhgen::robot!` on the same file.

use dhgen::Arm;
use dhgen::nalgebra::SVector;

// Public, as in a firmware crate that checks the file in: what this test does not call is
// still part of the crate's interface, not dead code.
/// The checked-in output of `dhgen emit`.
pub mod emitted {
    include!("emitted/puma560.rs");
}

/// A one-joint arm emitted with every option: functions that read none of some inputs (its
/// C(q, q̇) is zero) and friction-free bias terms, checked to compile without a warning.
#[deny(warnings)]
pub mod emitted_one_joint {
    include!("emitted/one_joint.rs");
}

dhgen::robot!(mod generated = "../robots/puma560.toml");

use emitted::puma560 as emitted_puma;

/// Pseudo-random configurations in [-π, π) (a fixed sequence, no dependency needed).
fn configurations() -> Vec<[f64; 6]> {
    let mut x = 0x2545_F491_4F6C_DD1D_u64;
    (0..20)
        .map(|_| {
            core::array::from_fn(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                ((x >> 11) as f64 / (1u64 << 53) as f64 - 0.5) * 2.0 * core::f64::consts::PI
            })
        })
        .collect()
}

fn assert_close(name: &str, a: &[f64], b: &[f64]) {
    assert_eq!(a.len(), b.len(), "{name}");
    let scale = b.iter().fold(1.0_f64, |m, x| m.max(x.abs()));
    for (i, (x, y)) in a.iter().zip(b).enumerate() {
        assert!((x - y).abs() <= 1e-12 * scale, "{name}[{i}]: {x} vs {y}");
    }
}

#[test]
fn emitted_module_matches_the_macro() {
    assert_eq!(emitted_puma::DOF, generated::DOF);
    assert_eq!(emitted_puma::NAME, "puma560");
    assert_eq!(emitted_puma::CHAIN, generated::CHAIN);
    let configs = configurations();
    for (n, q) in configs.iter().enumerate() {
        let qd = configs[(n + 1) % configs.len()].map(|x| x * 0.5);
        let qdd = configs[(n + 2) % configs.len()];
        let (e, g) = (emitted_puma::State::new(q), generated::State::new(q));
        assert_close(
            "fk",
            e.fk().to_homogeneous().as_slice(),
            g.fk().to_homogeneous().as_slice(),
        );
        assert_close("jacobian", e.jacobian().as_slice(), g.jacobian().as_slice());
        assert_close("D", e.mass_matrix().as_slice(), g.mass_matrix().as_slice());
        let flat =
            |c: [[[f64; 6]; 6]; 6]| -> Vec<f64> { c.iter().flatten().flatten().copied().collect() };
        assert_close("c_ijk", &flat(e.christoffel()), &flat(g.christoffel()));
        assert_close("C", e.coriolis(&qd).as_slice(), g.coriolis(&qd).as_slice());
        assert_close("g", e.gravity().as_slice(), g.gravity().as_slice());
        assert_close(
            "tau",
            e.inverse_dynamics(&qd, &qdd).as_slice(),
            g.inverse_dynamics(&qd, &qdd).as_slice(),
        );
        let tau = g.inverse_dynamics(&qd, &qdd);
        let fd = e
            .forward_dynamics(&qd, &tau)
            .expect("D is positive definite");
        // Forward dynamics inverts inverse dynamics.
        assert_close("forward dynamics", fd.as_slice(), &qdd);
    }
}

#[test]
fn emitted_module_implements_arm() {
    let q = SVector::<f64, 6>::from([0.3, -0.2, 0.5, 1.0, -0.7, 0.1]);
    let a = Arm::fk(&emitted_puma::Robot, &q);
    let b = Arm::fk(&generated::Robot, &q);
    assert_close(
        "Arm::fk",
        a.to_homogeneous().as_slice(),
        b.to_homogeneous().as_slice(),
    );
    assert_eq!(Arm::dof(&emitted_puma::Robot), 6);
}

#[test]
fn one_joint_module_is_a_pendulum() {
    use emitted_one_joint::one_joint as pendulum;
    // A rod of 1 kg with its centre of mass 0.5 m from the axis (the link frame sits at the
    // rod's far end, a = 1 m), gravity along −z of the base, the axis along z: no torque
    // from gravity, inertia zz + m·0.5² about the axis, no Coriolis term.
    for q in [-2.0_f64, -0.3, 0.0, 1.1, 3.0] {
        let d = pendulum::mass_matrix(&[q]);
        assert!((d[(0, 0)] - (0.1 + 0.25)).abs() < 1e-15, "D = {d}");
        assert_eq!(pendulum::gravity(&[q])[0], 0.0);
        assert_eq!(pendulum::coriolis(&[q], &[0.7])[(0, 0)], 0.0);
        let (dq, dqd) = pendulum::inverse_dynamics_derivatives(&[q], &[0.7], &[0.2]);
        assert_eq!((dq[(0, 0)], dqd[(0, 0)]), (0.0, 0.0));
        let (_, _, inverse) =
            pendulum::forward_dynamics_derivatives(&[q], &[0.7], &[1.0]).expect("D > 0");
        assert!((inverse[(0, 0)] * d[(0, 0)] - 1.0_f64).abs() < 1e-15);
    }
}
