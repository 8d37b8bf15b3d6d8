//! Round trips of the rotation parametrisations (ZYZ Euler angles, roll-pitch-yaw,
//! axis-angle) on random rotations and on their singular cases.

use dhgen::nalgebra::{Matrix3, Rotation3, Unit, UnitQuaternion, Vector3};
use dhgen::rotation::{EulerZyz, Rpy, SINGULAR_EPS, axis_angle, rotation_vector, vee, wrap_angle};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

fn rz(a: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Vector3::z_axis(), a)
}
fn ry(a: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Vector3::y_axis(), a)
}
fn rx(a: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Vector3::x_axis(), a)
}

fn dist(a: &Rotation3<f64>, b: &Rotation3<f64>) -> f64 {
    (a.matrix() - b.matrix()).abs().max()
}

/// A uniformly random rotation from a random unit quaternion.
fn rotation() -> impl Strategy<Value = Rotation3<f64>> {
    (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)
        .prop_filter("not too short", |(w, x, y, z)| {
            (w * w + x * x + y * y + z * z) > 1e-3
        })
        .prop_map(|(w, x, y, z)| {
            UnitQuaternion::from_quaternion(dhgen::nalgebra::Quaternion::new(w, x, y, z))
                .to_rotation_matrix()
        })
}

fn angle() -> impl Strategy<Value = f64> {
    -PI..PI
}

#[test]
fn zyz_matches_the_product_of_basic_rotations() {
    let e = EulerZyz::new(0.4, -1.2, 2.5);
    let expected = rz(0.4) * ry(-1.2) * rz(2.5);
    assert!(dist(&e.to_rotation(), &expected) < 1e-15);
}

#[test]
fn rpy_is_the_text_and_nalgebra_convention() {
    let rpy = Rpy::new(0.3, -0.7, 1.9);
    let expected = rz(1.9) * ry(-0.7) * rx(0.3);
    assert!(dist(&rpy.to_rotation(), &expected) < 1e-15);
    let (roll, pitch, yaw) = expected.euler_angles();
    let [first, _] = Rpy::from_rotation(&expected);
    assert!((first.roll - roll).abs() < 1e-14);
    assert!((first.pitch - pitch).abs() < 1e-14);
    assert!((first.yaw - yaw).abs() < 1e-14);
}

#[test]
fn skew_and_vee_are_inverse() {
    let a = Vector3::new(0.3, -1.2, 2.0);
    let s = a.cross_matrix();
    assert_eq!(s + s.transpose(), Matrix3::zeros());
    assert_eq!(vee(&s), a);
    let p = Vector3::new(-0.5, 0.25, 4.0);
    assert!((s * p - a.cross(&p)).norm() < 1e-15);
}

#[test]
fn wrap_angle_lands_in_the_half_open_interval() {
    assert_eq!(wrap_angle(PI), PI);
    assert_eq!(wrap_angle(-PI), PI);
    assert!((wrap_angle(3.0 * PI) - PI).abs() < 1e-15);
    assert!((wrap_angle(7.0) - (7.0 - 2.0 * PI)).abs() < 1e-15);
    assert!((wrap_angle(-7.0) - (-7.0 + 2.0 * PI)).abs() < 1e-15);
    assert_eq!(wrap_angle(0.25), 0.25);
}

#[test]
fn zyz_singular_cases_use_psi_zero() {
    // θ = 0: only φ + ψ is determined.
    let r = rz(0.7) * rz(0.5);
    let [a, b] = EulerZyz::from_rotation(&r);
    assert_eq!(a, b);
    assert_eq!((a.theta, a.psi), (0.0, 0.0));
    assert!((a.phi - 1.2).abs() < 1e-15);
    // θ = π: only φ − ψ is determined.
    let r = rz(0.7) * ry(PI) * rz(0.5);
    let [a, b] = EulerZyz::from_rotation(&r);
    assert_eq!(a, b);
    assert_eq!((a.theta, a.psi), (PI, 0.0));
    assert!((a.phi - 0.2).abs() < 1e-15);
    assert!(dist(&a.to_rotation(), &r) < 1e-15);
    // The identity.
    let [a, _] = EulerZyz::from_rotation(&Rotation3::identity());
    assert_eq!((a.phi, a.theta, a.psi), (0.0, 0.0, 0.0));
}

#[test]
fn zyz_is_accurate_next_to_the_singularity() {
    for theta in [
        1e-13,
        1e-11,
        1e-9,
        1e-7,
        1e-5,
        PI - 1e-9,
        PI - 1e-7,
        PI - 1e-13,
    ] {
        for (phi, psi) in [(0.3, -2.0), (3.0, 3.0), (-1.0, 0.5)] {
            let r = EulerZyz::new(phi, theta, psi).to_rotation();
            for e in EulerZyz::from_rotation(&r) {
                let err = dist(&e.to_rotation(), &r);
                // Inside the singular band θ is set to 0 or π: an error of at most θ.
                let allowed = 2e-15
                    + if theta.sin() < SINGULAR_EPS {
                        theta.sin()
                    } else {
                        0.0
                    };
                assert!(err < allowed, "θ = {theta}: {err}");
            }
        }
    }
}

#[test]
fn rpy_singular_cases_use_yaw_zero() {
    let r = rz(0.4) * ry(FRAC_PI_2) * rx(1.0);
    let [a, b] = Rpy::from_rotation(&r);
    assert_eq!(a, b);
    assert_eq!((a.pitch, a.yaw), (FRAC_PI_2, 0.0));
    assert!((a.roll - 0.6).abs() < 1e-15);
    assert!(dist(&a.to_rotation(), &r) < 1e-15);
    let r = rz(0.4) * ry(-FRAC_PI_2) * rx(1.0);
    let [a, _] = Rpy::from_rotation(&r);
    assert_eq!((a.pitch, a.yaw), (-FRAC_PI_2, 0.0));
    assert!((a.roll - 1.4).abs() < 1e-15);
    assert!(dist(&a.to_rotation(), &r) < 1e-15);
}

#[test]
fn rpy_is_accurate_next_to_the_singularity() {
    for pitch in [
        FRAC_PI_2 - 1e-13,
        FRAC_PI_2 - 1e-9,
        FRAC_PI_2 - 1e-6,
        -FRAC_PI_2 + 1e-10,
        -FRAC_PI_2 + 1e-7,
    ] {
        let r = Rpy::new(0.8, pitch, -2.9).to_rotation();
        for e in Rpy::from_rotation(&r) {
            let err = dist(&e.to_rotation(), &r);
            let allowed = 1e-15
                + if pitch.cos() < SINGULAR_EPS {
                    pitch.cos()
                } else {
                    0.0
                };
            assert!(err < allowed, "pitch = {pitch}: {err}");
        }
        // Pitch itself is accurate, where asin would lose half the digits.
        let allowed = 1e-15
            + if pitch.cos() < SINGULAR_EPS {
                pitch.cos()
            } else {
                0.0
            };
        assert!((Rpy::from_rotation(&r)[0].pitch - pitch).abs() < allowed);
        let (_, nalgebra_pitch, _) = r.euler_angles();
        if pitch.cos() > 1e-9 {
            assert!(
                (nalgebra_pitch - pitch).abs() > 1e-12,
                "asin was accurate at {pitch}"
            );
        }
    }
}

#[test]
fn axis_angle_at_zero_and_half_turns() {
    let (axis, theta) = axis_angle(&Rotation3::<f64>::identity());
    assert_eq!((axis.into_inner(), theta), (Vector3::z(), 0.0));
    assert_eq!(
        rotation_vector(&Rotation3::<f64>::identity()),
        Vector3::zeros()
    );
    // nalgebra gives no axis at θ = π; this does. For an exactly symmetric half turn
    // R = 2kkᵀ − I the axis is the one with its largest component positive.
    for k in [
        Vector3::new(1.0, 2.0, -3.0),
        Vector3::new(-1.0, 0.0, 0.0),
        Vector3::new(0.0, -2.0, 1.0),
    ] {
        let k = Unit::new_normalize(k);
        let half_turn = k.into_inner() * k.transpose() * 2.0 - Matrix3::identity();
        let r = Rotation3::from_matrix_unchecked(half_turn);
        assert!(r.axis().is_none());
        let (axis, theta) = axis_angle(&r);
        assert_eq!(theta, PI);
        let i = k.iamax();
        let expected = if k[i] > 0.0 {
            k.into_inner()
        } else {
            -k.into_inner()
        };
        assert!(
            (axis.into_inner() - expected).norm() < 1e-15,
            "{axis:?} vs {expected:?}"
        );
        assert!(dist(&Rotation3::from_axis_angle(&axis, theta), &r) < 1e-15);
        // Rounded half turns: the skew part, however small, picks the sign.
        let r = Rotation3::from_axis_angle(&k, PI);
        let (axis, theta) = axis_angle(&r);
        assert!((theta - PI).abs() < 1e-15);
        assert!((axis.into_inner().dot(&k).abs() - 1.0).abs() < 1e-15);
        assert!(dist(&Rotation3::from_axis_angle(&axis, theta), &r) < 1e-15);
    }
}

#[test]
fn axis_angle_is_accurate_near_zero_and_pi() {
    let k = Unit::new_normalize(Vector3::new(0.3, -0.4, 0.8));
    for theta in [1e-12, 1e-8, 1e-4, PI - 1e-4, PI - 1e-8, PI - 1e-12] {
        let r = Rotation3::from_axis_angle(&k, theta);
        let (axis, t) = axis_angle(&r);
        assert!(
            (t - theta).abs() < 4e-16 * (1.0 + theta),
            "θ = {theta}: got {t}"
        );
        // Near θ = 0 only k θ is determined to rounding error, not k itself.
        let axis_error = (axis.into_inner() - k.into_inner()).norm();
        assert!(
            axis_error * theta < 1e-15 && axis_error < 1e-3,
            "θ = {theta}: {axis_error}"
        );
        assert!(dist(&Rotation3::from_axis_angle(&axis, t), &r) < 1e-15);
    }
}

proptest! {
    #[test]
    fn zyz_round_trip(r in rotation()) {
        let [a, b] = EulerZyz::from_rotation(&r);
        prop_assert!(a.theta >= 0.0 && b.theta <= 0.0);
        for e in [a, b] {
            prop_assert!(dist(&e.to_rotation(), &r) < 2e-15);
            for x in [e.phi, e.theta, e.psi] {
                prop_assert!(x > -PI && x <= PI);
            }
        }
    }

    #[test]
    fn zyz_angles_round_trip(phi in angle(), theta in 1e-6f64..PI - 1e-6, psi in angle()) {
        let [a, b] = EulerZyz::from_rotation(&EulerZyz::new(phi, theta, psi).to_rotation());
        prop_assert!((wrap_angle(a.phi - phi)).abs() < 1e-9);
        prop_assert!((a.theta - theta).abs() < 1e-14);
        prop_assert!((wrap_angle(a.psi - psi)).abs() < 1e-9);
        prop_assert!((b.theta + theta).abs() < 1e-14);
    }

    #[test]
    fn rpy_round_trip(r in rotation()) {
        let [a, b] = Rpy::from_rotation(&r);
        prop_assert!(a.pitch.abs() <= FRAC_PI_2);
        prop_assert!(b.pitch.abs() >= FRAC_PI_2);
        for e in [a, b] {
            prop_assert!(dist(&e.to_rotation(), &r) < 2e-15);
        }
    }

    #[test]
    fn rpy_angles_round_trip(roll in angle(), pitch in -FRAC_PI_2 + 1e-6..FRAC_PI_2 - 1e-6, yaw in angle()) {
        let [a, _] = Rpy::from_rotation(&Rpy::new(roll, pitch, yaw).to_rotation());
        prop_assert!((wrap_angle(a.roll - roll)).abs() < 1e-9);
        prop_assert!((a.pitch - pitch).abs() < 1e-14);
        prop_assert!((wrap_angle(a.yaw - yaw)).abs() < 1e-9);
    }

    #[test]
    fn axis_angle_round_trip(r in rotation()) {
        let (axis, theta) = axis_angle(&r);
        prop_assert!((0.0..=PI).contains(&theta));
        prop_assert!(dist(&Rotation3::from_axis_angle(&axis, theta), &r) < 2e-15);
        let v = rotation_vector(&r);
        prop_assert!(dist(&Rotation3::new(v), &r) < 2e-15);
        // Agrees with nalgebra's quaternion route.
        let q = UnitQuaternion::from_rotation_matrix(&r);
        prop_assert!((q.angle() - theta).abs() < 1e-14);
    }
}
