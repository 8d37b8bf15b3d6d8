//! Redundancy resolution on a 7-joint arm: one tool pose, three of the infinitely many
//! configurations that reach it (where the seed leads, the nearest to a rest posture, the most
//! manipulable), and how each sits against the joint limits.
//!
//! `cargo run --release --example redundancy`

use dhgen::Arm;
use dhgen::ik::{NumericIk, Preference, Solution, pose_error};
use dhgen::nalgebra::{Const, Isometry3, SVector};
use dhgen::velocity::{Axes, JacobianSvd};
use std::time::Instant;

dhgen::robot!(mod panda = "robots/panda.toml");

type Q = SVector<f64, 7>;

fn show(title: &str, target: &Isometry3<f64>, s: &Solution<Const<7>>, rest: &Q, micros: f64) {
    let arm = panda::Robot;
    let (dp, dr) = pose_error(&arm.fk(&s.q), target);
    let svd = JacobianSvd::new(&arm.jacobian(&s.q));
    // The distance to the nearest limit, as a fraction of each joint's range.
    let margin = (0..7)
        .map(|k| {
            let [lo, hi] = arm.limits(k).unwrap();
            (s.q[k] - lo).min(hi - s.q[k]) / (hi - lo)
        })
        .fold(f64::INFINITY, f64::min);
    println!("\n{title}");
    println!(
        "  q = [{}]",
        s.q.iter()
            .map(|x| format!("{x:7.3}"))
            .collect::<Vec<_>>()
            .join(",")
    );
    println!(
        "  |q − rest| {:.3} rad, manipulability {:.4}, smallest singular value {:.3}, nearest \
         limit at {:.1} % of its range",
        (s.q - rest).norm(),
        svd.manipulability(),
        svd.min_singular_value(),
        100.0 * margin
    );
    println!(
        "  pose error {dp:.1e} m / {dr:.1e} rad, {} iterations, {micros:.0} µs",
        s.iterations
    );
}

fn main() {
    let arm = panda::Robot;
    // Franka's "ready" posture, and a pose the arm reaches with its elbow swung out of it.
    let rest = Q::from([0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785]);
    let target = arm.fk(&(rest + Q::from([0.5, 0.3, -0.9, 0.4, 0.6, -0.3, 0.2])));
    let seed = Q::from([-0.8, 0.2, 1.2, -1.6, -0.9, 2.2, 0.1]);
    let ik = NumericIk::default();
    let timed = |preference: Option<Preference<'_, Const<7>>>| {
        let start = Instant::now();
        let runs = 200;
        let mut out = None;
        for _ in 0..runs {
            out = Some(match preference {
                None => ik.solve(&arm, &target, &seed),
                Some(p) => ik.solve_preferring(&arm, &target, &seed, p),
            });
        }
        let micros = start.elapsed().as_secs_f64() * 1e6 / runs as f64;
        (out.unwrap().expect("the pose is reachable"), micros)
    };
    println!(
        "Panda, one tool pose at ({:.3}, {:.3}, {:.3}) m, from the same seed:",
        target.translation.x, target.translation.y, target.translation.z
    );
    let (first, t) = timed(None);
    show(
        "where the seed leads (NumericIk::solve)",
        &target,
        &first,
        &rest,
        t,
    );
    let (near, t) = timed(Some(Preference::Posture(&rest)));
    show(
        "nearest the rest posture (Preference::Posture)",
        &target,
        &near,
        &rest,
        t,
    );
    let (most, t) = timed(Some(Preference::Manipulability(Axes::All)));
    show(
        "most manipulable (Preference::Manipulability)",
        &target,
        &most,
        &rest,
        t,
    );
    assert!((near.q - rest).norm() <= (first.q - rest).norm());
    assert!(
        JacobianSvd::new(&arm.jacobian(&most.q)).manipulability()
            >= JacobianSvd::new(&arm.jacobian(&first.q)).manipulability()
    );
}
