//! The planar elbow arm (robots/planar_elbow.toml) against the closed forms of the textbook,
//! section 7.4.1, as corrected by the errata in docs/references.md: l1 = 1, l2 = 0.8, lc_i = l_i / 2, m1 = 2,
//! m2 = 1.5, I_i the links' zz inertia, gravity 9.81 along −y of the base frame.
//! Both paths are checked: the runtime `Robot` and the code `robot!` generates.

use crate::catalogue::planar_elbow as generated;
use crate::support::runtime;
use dhgen::Robot;

const L1: f64 = 1.0;
const LC1: f64 = 0.5;
const LC2: f64 = 0.4;
const M1: f64 = 2.0;
const M2: f64 = 1.5;
const G: f64 = 9.81;

fn robot() -> Robot {
    runtime("planar_elbow")
}

/// Configurations spread over the joint range, including the stretched and folded arm.
fn configurations() -> impl Iterator<Item = [f64; 2]> {
    let angles = [
        -3.0,
        -1.7,
        -0.4,
        0.0,
        0.9,
        std::f64::consts::FRAC_PI_2,
        2.6,
        3.1,
    ];
    angles
        .into_iter()
        .flat_map(move |a| angles.into_iter().map(move |b| [a, 0.37 * a + b]))
}

fn assert_close(what: &str, q: &[f64; 2], actual: f64, expected: f64) {
    assert!(
        (actual - expected).abs() <= 1e-12 * expected.abs().max(1.0),
        "{what} at q = {q:?}: got {actual}, expected {expected}"
    );
}

/// The links' moments of inertia about z through the centre of mass, from the description.
fn inertias(robot: &Robot) -> (f64, f64) {
    let zz = |i: usize| robot.model().links[i].inertial.unwrap().inertia[2][2];
    (zz(0), zz(1))
}

#[test]
fn description_holds_uniform_rods() {
    let robot = robot();
    let (i1, i2) = inertias(&robot);
    assert!((i1 - M1 * L1 * L1 / 12.0).abs() < 1e-15);
    assert!((i2 - M2 * 0.8 * 0.8 / 12.0).abs() < 1e-15);
    assert_eq!(robot.model().gravity, [0.0, -G, 0.0]);
}

#[test]
fn mass_matrix_matches_closed_form() {
    let robot = robot();
    let (i1, i2) = inertias(&robot);
    for q in configurations() {
        let runtime = robot.mass_matrix(&q);
        let symbolic = generated::mass_matrix(&q);
        let c2 = q[1].cos();
        let d11 = M1 * LC1 * LC1 + M2 * (L1 * L1 + LC2 * LC2 + 2.0 * L1 * LC2 * c2) + i1 + i2;
        let d12 = M2 * (LC2 * LC2 + L1 * LC2 * c2) + i2;
        let d22 = M2 * LC2 * LC2 + i2;
        for d in [runtime.fixed_view::<2, 2>(0, 0).into_owned(), symbolic] {
            assert_close("d11", &q, d[(0, 0)], d11);
            assert_close("d12", &q, d[(0, 1)], d12);
            assert_close("d21", &q, d[(1, 0)], d12);
            assert_close("d22", &q, d[(1, 1)], d22);
        }
    }
}

#[test]
fn christoffel_symbols_match_closed_form() {
    let robot = robot();
    for q in configurations() {
        let c = robot.christoffel(&q);
        let symbolic = generated::christoffel(&q);
        let h = -M2 * L1 * LC2 * q[1].sin();
        // Textbook indices are 1-based: c_121 is c[0][1][0].
        let mut expected = [[[0.0; 2]; 2]; 2];
        expected[0][1][0] = h; // c121
        expected[1][0][0] = h; // c211
        expected[1][1][0] = h; // c221
        expected[0][0][1] = -h; // c112
        for (i, plane) in expected.iter().enumerate() {
            for (j, row) in plane.iter().enumerate() {
                for (k, value) in row.iter().enumerate() {
                    let name = format!("c{}{}{}", i + 1, j + 1, k + 1);
                    assert_close(&name, &q, c[i][j][k], *value);
                    assert_close(&name, &q, symbolic[i][j][k], *value);
                }
            }
        }
    }
}

#[test]
fn coriolis_matrix_matches_closed_form() {
    let robot = robot();
    for q in configurations() {
        let qd = [0.8 - q[0] * 0.3, 1.1 + q[1] * 0.5];
        let h = -M2 * L1 * LC2 * q[1].sin();
        let runtime = robot
            .coriolis(&q, &qd)
            .fixed_view::<2, 2>(0, 0)
            .into_owned();
        for c in [runtime, generated::coriolis(&q, &qd)] {
            assert_close("C11", &q, c[(0, 0)], h * qd[1]);
            assert_close("C12", &q, c[(0, 1)], h * (qd[0] + qd[1]));
            assert_close("C21", &q, c[(1, 0)], -h * qd[0]);
            assert_close("C22", &q, c[(1, 1)], 0.0);
        }
    }
}

#[test]
fn gravity_matches_closed_form() {
    let robot = robot();
    for q in configurations() {
        let runtime = robot.gravity(&q);
        let symbolic = generated::gravity(&q);
        let c1 = q[0].cos();
        let c12 = (q[0] + q[1]).cos();
        let phi1 = (M1 * LC1 + M2 * L1) * G * c1 + M2 * LC2 * G * c12;
        let phi2 = M2 * LC2 * G * c12;
        for g in [[runtime[0], runtime[1]], [symbolic[0], symbolic[1]]] {
            assert_close("phi1", &q, g[0], phi1);
            assert_close("phi2", &q, g[1], phi2);
        }
    }
}
