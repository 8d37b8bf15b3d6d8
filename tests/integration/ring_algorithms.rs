//! The generator's recursions, written once over any `Ring`, evaluated in `f64` on random arms
//! (general and industrial, 2 to 12 joints and 16, 20 and 30, prismatic joints among them)
//! against the runtime path's independent implementations: the algorithm that a generated
//! module emits as straight-line code whenever it is the cheapest candidate, checked on arms
//! where the catalogue would never select it; and, past 12 joints, the symbolic engine's
//! recursions checking the runtime's loops that generated modules call there
//! (`dhgen::recursive`: D, C, c_ijk).

use dhgen::Robot;
use dhgen::model::random::{ArmStyle, random_arm};
use dhgen_codegen::{Coordinates, Numbers, RingChain};

/// A named arm and a state `(q, q̇, q̈)`.
type Case = (String, Robot, Vec<f64>, Vec<f64>, Vec<f64>);

/// Random arms of both styles, and a seeded state for each.
fn arms() -> Vec<Case> {
    let mut out = Vec::new();
    for style in [ArmStyle::General, ArmStyle::Industrial] {
        for n in (2..=12).chain([16, 20, 30]) {
            for seed in 0..if n <= 12 { 3u64 } else { 1 } {
                let robot = Robot::from_model(random_arm(n, style, seed));
                let f = |k: usize, a: f64| {
                    (0..n)
                        .map(|i| a * ((seed as f64 + 1.0) * 0.77 + (i * 3 + k) as f64 * 1.31).sin())
                        .collect::<Vec<f64>>()
                };
                let (q, qd, qdd) = (f(0, 1.2), f(1, 2.0), f(2, 2.0));
                out.push((format!("{style:?} {n} seed {seed}"), robot, q, qd, qdd));
            }
        }
    }
    out
}

/// Asserts that the rows `got` equal `want` entry by entry to 1e-12 relative to max(1, |want|);
/// returns the largest error.
fn matches(what: &str, got: &[Vec<f64>], want: &dhgen::nalgebra::DMatrix<f64>) -> f64 {
    assert_eq!((got.len(), got[0].len()), want.shape(), "{what}: shape");
    let scale = want.amax().max(1.0);
    let mut worst = 0.0f64;
    for (r, row) in got.iter().enumerate() {
        for (c, x) in row.iter().enumerate() {
            let err = (x - want[(r, c)]).abs() / scale;
            assert!(err <= 1e-12, "{what}[{r}][{c}] {x} vs {}", want[(r, c)]);
            worst = worst.max(err);
        }
    }
    worst
}

/// The coordinates the spatial candidates may be built in: the root frame, the first, a
/// middle and the last joint frame.
fn coordinates(n: usize) -> [Coordinates; 4] {
    [
        Coordinates::Root,
        Coordinates::Joint(0),
        Coordinates::Joint(n / 2),
        Coordinates::Joint(n - 1),
    ]
}

#[test]
fn coriolis_recursion_equals_the_runtime() {
    let mut worst = 0.0f64;
    for (name, robot, q, qd, _) in arms() {
        let chain = robot.chain();
        let want = robot.coriolis(&q[..], &qd[..]);
        let rc = RingChain::new(chain, &Numbers(chain, &q));
        for at in coordinates(robot.dof()) {
            let c = rc.coriolis_matrix_in(at, &qd);
            worst = worst.max(matches(&format!("{name} in {at:?}: C"), &c, &want));
        }
        let c = rc.coriolis_matrix_local(&qd);
        worst = worst.max(matches(&format!("{name} in joint frames: C"), &c, &want));
    }
    println!("Echeandia–Wensing over the ring = runtime C to {worst:.1e}");
}

/// The runtime path's Christoffel symbols (the loop generated modules call past 12 joints,
/// `dhgen::recursive::christoffel`) are symmetric in their first two indices and contract to
/// the C of the generator's recursion in joint frames, another algorithm: `Σ_i c_ijk q̇_i =
/// C_kj`, at every size.
#[test]
fn christoffel_symbols_contract_to_the_coriolis_recursion() {
    let mut worst = 0.0f64;
    for (name, robot, q, qd, _) in arms() {
        let n = robot.dof();
        let chain = robot.chain();
        let c = robot.christoffel(&q[..]);
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    assert_eq!(c[i][j][k], c[j][i][k], "{name}: c_{i}{j}{k}");
                }
            }
        }
        let contracted: Vec<Vec<f64>> = (0..n)
            .map(|k| {
                (0..n)
                    .map(|j| (0..n).map(|i| c[i][j][k] * qd[i]).sum())
                    .collect()
            })
            .collect();
        let rc = RingChain::new(chain, &Numbers(chain, &q));
        let want = dhgen::nalgebra::DMatrix::from_fn(n, n, {
            let local = rc.coriolis_matrix_local(&qd);
            move |r, col| local[r][col]
        });
        worst = worst.max(matches(&format!("{name}: Σ c q̇"), &contracted, &want));
    }
    println!("runtime c_ijk contracted = C over the ring to {worst:.1e}");
}

/// The composite-rigid-body algorithm in one frame's coordinates (with each joint's armature
/// added, as the generated candidates do) and in joint frames against the runtime's CRBA.
#[test]
fn mass_matrix_recursions_equal_the_runtime() {
    let mut worst = 0.0f64;
    for (name, robot, q, _, _) in arms() {
        let chain = robot.chain();
        let want = robot.mass_matrix(&q[..]);
        let rc = RingChain::new(chain, &Numbers(chain, &q));
        let with_armature = |mut d: Vec<Vec<f64>>| {
            for (i, b) in chain.bodies.iter().enumerate() {
                d[i][i] += b.armature;
            }
            d
        };
        let d = with_armature(rc.mass_matrix());
        worst = worst.max(matches(&format!("{name} in joint frames: D"), &d, &want));
        for at in coordinates(robot.dof()) {
            let d = with_armature(rc.mass_matrix_in(at));
            worst = worst.max(matches(&format!("{name} in {at:?}: D"), &d, &want));
        }
    }
    println!("composite-rigid-body recursions over the ring = runtime D to {worst:.1e}");
}

/// The closed-form ∂τ/∂q (Carpentier–Mansard in one frame's coordinates and in joint frames)
/// against the runtime's forward-mode tangents of Newton–Euler, a different algorithm; and the
/// C it returns with it.
#[test]
fn inverse_dynamics_derivatives_in_closed_form_equal_the_runtime() {
    let mut worst = 0.0f64;
    for (name, robot, q, qd, qdd) in arms() {
        let chain = robot.chain();
        let (want_dq, _) = robot.inverse_dynamics_derivatives(&q[..], &qd[..], &qdd[..]);
        let want_c = robot.coriolis(&q[..], &qd[..]);
        for at in coordinates(robot.dof()) {
            let [dq, c] = RingChain::new(chain, &Numbers(chain, &q))
                .inverse_dynamics_derivatives(at, &qd, &qdd);
            worst = worst.max(matches(
                &format!("{name} in {at:?}: dtau/dq"),
                &dq,
                &want_dq,
            ));
            worst = worst.max(matches(&format!("{name} in {at:?}: C"), &c, &want_c));
        }
        let [dq, c] = RingChain::new(chain, &Numbers(chain, &q))
            .inverse_dynamics_derivatives_local(&qd, &qdd);
        let at = "in joint frames";
        worst = worst.max(matches(&format!("{name} {at}: dtau/dq"), &dq, &want_dq));
        worst = worst.max(matches(&format!("{name} {at}: C"), &c, &want_c));
    }
    println!("closed-form dtau/dq over the ring = runtime tangents to {worst:.1e}");
}

#[test]
fn regressor_recursion_equals_the_runtime() {
    let mut worst = 0.0f64;
    for (name, robot, q, qd, qdd) in arms() {
        let chain = robot.chain();
        let y = RingChain::new(chain, &Numbers(chain, &q)).regressor(&qd, &qdd);
        let want = robot.regressor(&q[..], &qd[..], &qdd[..]);
        worst = worst.max(matches(&format!("{name}: Y"), &y, &want));
    }
    println!("regressor recursion over the ring = runtime Y to {worst:.1e}");
}

/// The arms of `benches/random_arms.rs` are the seeded ones (`dhgen random --dof N --style
/// STYLE --seed 1`), so the benchmark measures what the generator of random arms makes.
#[test]
fn bench_arms_are_the_seeded_ones() {
    for (style, word) in [
        (ArmStyle::General, "general"),
        (ArmStyle::Industrial, "industrial"),
    ] {
        for n in [6, 8, 10, 12] {
            let path = format!(
                "{}/benches/arms/{word}_{n}.toml",
                env!("CARGO_MANIFEST_DIR")
            );
            let checked_in = dhgen::RobotModel::from_toml_file(&path).unwrap();
            assert!(
                checked_in == random_arm(n, style, 1),
                "{path} is not the seeded arm"
            );
        }
    }
}
