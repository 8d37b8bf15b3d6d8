//! Generated code on SIMD packs (`dhgen::batch`): every configuration of a batch gets what the
//! scalar function returns for it, in `f32` (eight lanes) bit for bit, in `f64` (four lanes) bit
//! for bit where the target has AVX ([`dhgen::sincos::PACKED`]: scalar code then takes its sines
//! and cosines from packs too) and otherwise to 1e-12 of the output's largest entry (the pack's
//! sine and cosine are dhgen's branch-free ones, scalar `f64` keeps `libm`'s; both within one
//! ulp), with the same `None`s; on every
//! catalogue robot and the fixtures that exercise prismatic joints, modified DH, base and
//! tool, motors, Coulomb friction (at q̇ = 0 too) and a singular inertia matrix. The slices
//! are of 11 configurations: full packs and a partial one.

use crate::catalogue::*;
use dhgen::batch::LengthMismatch;

/// A seeded stream in [-2, 2), with exact zeros now and then (Coulomb friction's sign(0)).
struct Stream(dhgen::model::random::Stream);

impl Stream {
    fn new(seed: u64) -> Self {
        Stream(dhgen::model::random::Stream(seed))
    }

    fn next(&mut self) -> f64 {
        let u = self.0.uniform(0.0, 1.0);
        if u < 1.0 / 7.0 {
            0.0
        } else {
            self.0.uniform(-2.0, 2.0)
        }
    }

    fn states<const N: usize>(&mut self, count: usize) -> Vec<[f64; N]> {
        (0..count)
            .map(|_| std::array::from_fn(|_| self.next()))
            .collect()
    }
}

/// Exact equality, NaN and the sign of zero included: `Debug` prints the shortest string that
/// reads back to the same bits.
fn same<A: std::fmt::Debug, B: std::fmt::Debug>(what: &str, c: usize, batch: &A, scalar: &B) {
    let (a, b) = (format!("{batch:?}"), format!("{scalar:?}"));
    assert_eq!(a, b, "{what}, configuration {c}: batch differs from scalar");
}

/// The input a name stands for, one per configuration, from `(q̇, q̈, τ, payload)` (the
/// payload is the same for every configuration).
macro_rules! pick {
    (qd, $s:ident) => {
        $s.0
    };
    (qdd, $s:ident) => {
        $s.1
    };
    (tau, $s:ident) => {
        $s.2
    };
    (payload, $s:ident) => {
        $s.3
    };
}

/// The argument of a batch function a name stands for: a slice of joint vectors, or the one
/// payload of every configuration.
macro_rules! batch_arg {
    (payload, $s:ident) => {
        &$s.3[0]
    };
    ($x:ident, $s:ident) => {
        &pick!($x, $s)
    };
}

/// The numbers of a value's `Debug` text and the text around them.
fn numbers(text: &str) -> (String, Vec<f64>) {
    let mut skeleton = String::new();
    let mut values = Vec::new();
    for token in text.split_inclusive(|c: char| " ,()[]{}:;".contains(c)) {
        let (body, sep) = token
            .split_at(token.len() - token.ends_with(|c: char| " ,()[]{}:;".contains(c)) as usize);
        match body.parse::<f64>() {
            Ok(v) => {
                values.push(v);
                skeleton.push('#');
            }
            Err(_) => skeleton.push_str(body),
        }
        skeleton.push_str(sep);
    }
    (skeleton, values)
}

/// Equal up to 1e-12 of the largest magnitude, with the same structure (`Some`/`None`).
fn close<A: std::fmt::Debug, B: std::fmt::Debug>(what: &str, c: usize, batch: &A, scalar: &B) {
    let (sa, a) = numbers(&format!("{batch:?}"));
    let (sb, b) = numbers(&format!("{scalar:?}"));
    assert_eq!(sa, sb, "{what}, configuration {c}: structure");
    let scale = b.iter().fold(
        1.0f64,
        |m, x| if x.is_finite() { m.max(x.abs()) } else { m },
    );
    for (x, y) in a.iter().zip(&b) {
        let ok = (x.is_nan() && y.is_nan()) || x == y || (x - y).abs() <= 1e-12 * scale;
        assert!(ok, "{what}, configuration {c}: {x} against {y}");
    }
}

/// Bit for bit in `f32`, and in `f64` where its scalar sines and cosines come from packs.
trait Agree {
    const BITWISE: bool;
}

impl Agree for f32 {
    const BITWISE: bool = true;
}

impl Agree for f64 {
    // Where scalar `f64` takes its sines and cosines from packs too (AVX), bit for bit.
    const BITWISE: bool = dhgen::sincos::PACKED;
}

fn agree<T: Agree, A: std::fmt::Debug, B: std::fmt::Debug>(
    what: &str,
    c: usize,
    batch: &A,
    scalar: &B,
) {
    if T::BITWISE {
        same(what, c, batch, scalar);
    } else {
        close(what, c, batch, scalar);
    }
}

/// Checks every listed batch function of module `$m` against its scalar function, for `$t`.
macro_rules! check {
    ($m:ident, $t:ty, [$($f:ident($($x:ident),*)),* $(,)?]) => {{
        use $m as m;
        const N: usize = m::DOF;
        let mut s = Stream::new(0x5EED ^ N as u64);
        let cast = |v: Vec<[f64; N]>| -> Vec<[$t; N]> {
            v.into_iter().map(|x| x.map(|e| e as $t)).collect()
        };
        let q = cast(s.states::<N>(11));
        let qd = cast(s.states::<N>(11));
        let qdd = cast(s.states::<N>(11));
        let tau = cast(s.states::<N>(11));
        // A payload off the tool's axis, with products of inertia.
        let payload = dhgen::payload::Payload::new(
            2.5,
            [0.02, -0.03, 0.06],
            [[4e-3, 2e-4, -1e-4], [2e-4, 5e-3, 3e-4], [-1e-4, 3e-4, 6e-3]],
        )
        .expect("a physical payload")
        .parameters()
        .map(|x| x as $t);
        let inputs = (qd, qdd, tau, vec![payload; q.len()]);
        let _ = &inputs;
        $(
            // Any value of the right type to overwrite: configuration 0's.
            let mut out = vec![m::$f(&q[0], $(&pick!($x, inputs)[0]),*); q.len()];
            m::batch::$f(&q, $(batch_arg!($x, inputs),)* &mut out).expect("lengths agree");
            for (c, o) in out.iter().enumerate() {
                agree::<$t, _, _>(
                    concat!(stringify!($m), "::", stringify!($f), " ", stringify!($t)),
                    c,
                    o,
                    &m::$f(&q[c], $(&pick!($x, inputs)[c]),*),
                );
            }
        )*
    }};
}

macro_rules! kinematics {
    ($m:ident, $t:ty) => {
        check!(
            $m,
            $t,
            [
                fk_matrix(),
                fk(),
                frames_matrix(),
                jacobian(),
                body_jacobian(),
                jdot_qdot(qd),
                body_jdot_qdot(qd)
            ]
        )
    };
}

macro_rules! dynamics {
    ($m:ident, $t:ty) => {{
        kinematics!($m, $t);
        check!(
            $m,
            $t,
            [
                mass_matrix(),
                christoffel(),
                coriolis(qd),
                gravity(),
                inverse_dynamics(qd, qdd),
                bias(qd),
                forward_dynamics(qd, tau),
                kinetic_energy(qd),
                potential_energy(),
                center_of_mass(),
                center_of_mass_jacobian(),
                inverse_dynamics_with_payload(qd, qdd, payload),
                bias_with_payload(qd, payload),
                mass_matrix_with_payload(payload),
                gravity_with_payload(payload),
                coriolis_with_payload(qd, payload),
                forward_dynamics_with_payload(qd, tau, payload),
            ]
        )
    }};
}

#[test]
fn batch_lanes_equal_scalar_f64() {
    dynamics!(puma560, f64);
    dynamics!(panda, f64);
    dynamics!(stanford, f64);
    dynamics!(scara, f64);
    dynamics!(ur5, f64);
    dynamics!(planar_elbow, f64);
    dynamics!(odd, f64);
    // D and C by the runtime's loops (`dhgen::recursive`), past 12 joints.
    check!(
        snake17,
        f64,
        [mass_matrix(), coriolis(qd), forward_dynamics(qd, tau)]
    );
    kinematics!(craig, f64);
    dynamics!(weightless_wrist, f64);
    dynamics!(kinova_urdf, f64);
    dynamics!(random_urdf_3, f64);
    kinematics!(cylindrical, f64);
    kinematics!(gantry, f64);
}

#[test]
fn batch_lanes_equal_scalar_f32() {
    dynamics!(puma560, f32);
    dynamics!(panda, f32);
    dynamics!(odd, f32);
    check!(snake17, f32, [mass_matrix(), coriolis(qd)]);
    dynamics!(weightless_wrist, f32);
    kinematics!(gantry, f32);
}

#[test]
fn batch_derivatives_and_regressor_equal_scalar() {
    check!(
        odd_derivatives,
        f64,
        [
            inverse_dynamics_derivatives(qd, qdd),
            inverse_dynamics_derivatives_with_payload(qd, qdd, payload),
            forward_dynamics_derivatives_with_payload(qd, tau, payload),
            mass_matrix_rate(qd),
            coriolis_transpose_qd(qd),
            regressor(qd, qdd),
            base_regressor(qd, qdd),
            mass_matrix_inverse(),
            forward_dynamics_derivatives(qd, tau),
        ]
    );
    check!(
        puma560_derivatives,
        f64,
        [
            inverse_dynamics_derivatives(qd, qdd),
            inverse_dynamics_derivatives_with_payload(qd, qdd, payload),
            forward_dynamics_derivatives_with_payload(qd, tau, payload),
            mass_matrix_inverse(),
            forward_dynamics_derivatives(qd, tau),
        ]
    );
    // D beside ∂τ in one derivation (`forward_dynamics_terms`), factored between its stages.
    check!(
        panda_derivatives,
        f64,
        [forward_dynamics_derivatives(qd, tau)]
    );
    // The looped Cholesky factorisation (past the joints it is unrolled for).
    check!(
        snake17_derivatives,
        f64,
        [
            forward_dynamics(qd, tau),
            mass_matrix_inverse(),
            forward_dynamics_derivatives(qd, tau),
        ]
    );
}

/// Forward dynamics of a pack is lane by lane: a lane with a singular or non-finite case is
/// `None` and does not disturb its neighbours.
#[test]
fn forward_dynamics_lanes_are_independent() {
    use dhgen::batch::WideF64x4;
    let mut s = Stream::new(7);
    let q = s.states::<6>(4);
    let qd = s.states::<6>(4);
    let mut tau = s.states::<6>(4);
    tau[2][3] = f64::NAN;
    let mut out = vec![None; 4];
    puma560::batch::forward_dynamics(&q, &qd, &tau, &mut out).unwrap();
    assert!(out[2].is_none());
    for c in [0, 1, 3] {
        close(
            "forward_dynamics",
            c,
            &out[c],
            &puma560::forward_dynamics(&q[c], &qd[c], &tau[c]),
        );
        assert!(out[c].is_some());
    }
    // The pack itself: `Option` only when every lane has an answer.
    let pack = |v: &[[f64; 6]]| -> [WideF64x4; 6] {
        std::array::from_fn(|j| WideF64x4([v[0][j], v[1][j], v[2][j], v[3][j]].into()))
    };
    assert!(puma560::forward_dynamics(&pack(&q), &pack(&qd), &pack(&tau)).is_none());
    let (_, ok) = puma560::forward_dynamics_lanes(&pack(&q), &pack(&qd), &pack(&tau));
    assert_eq!(dhgen::nalgebra::SimdBool::bitmask(ok), 0b1011);
    tau[2][3] = 0.5;
    assert!(puma560::forward_dynamics(&pack(&q), &pack(&qd), &pack(&tau)).is_some());
}

/// The derivatives of forward dynamics too: a lane whose q̈ is not finite is `None`, its
/// neighbours get the scalar answers.
#[test]
fn forward_dynamics_derivative_lanes_are_independent() {
    let mut s = Stream::new(8);
    let q = s.states::<6>(4);
    let qd = s.states::<6>(4);
    let mut tau = s.states::<6>(4);
    tau[1][0] = f64::INFINITY;
    let mut out = vec![None; 4];
    puma560_derivatives::batch::forward_dynamics_derivatives(&q, &qd, &tau, &mut out).unwrap();
    assert!(out[1].is_none());
    for c in [0, 2, 3] {
        let scalar = puma560_derivatives::forward_dynamics_derivatives(&q[c], &qd[c], &tau[c]);
        assert!(out[c].is_some() && scalar.is_some());
        close("forward_dynamics_derivatives", c, &out[c], &scalar);
    }
}

#[test]
fn batch_lengths_must_agree() {
    let q = vec![[0.0; 6]; 3];
    let qd = vec![[0.0; 6]; 2];
    let mut out = vec![Default::default(); 3];
    assert_eq!(
        puma560::batch::coriolis(&q, &qd, &mut out),
        Err(LengthMismatch {
            inputs: 2,
            outputs: 3
        })
    );
    assert!(
        out.iter()
            .all(|m: &dhgen::nalgebra::SMatrix<f64, 6, 6>| m.iter().all(|&x| x == 0.0))
    );
    let mut none: Vec<dhgen::nalgebra::SMatrix<f64, 6, 6>> = Vec::new();
    assert_eq!(puma560::batch::mass_matrix(&[], &mut none), Ok(()));
}
