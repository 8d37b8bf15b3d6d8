//! The quick start: PUMA 560 generated at compile time by `robot!`, and the same robot
//! loaded at run time, evaluated at one configuration.
//!
//! `cargo run --release --example quickstart`

use dhgen::Robot;

// Everything in `puma560` is straight-line code derived symbolically from the DH table.
dhgen::robot!(pub mod puma560 = "robots/puma560.toml");

fn main() -> Result<(), dhgen::Error> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/robots/puma560.toml");
    let robot = Robot::from_toml_file(path)?;
    let model = robot.model();
    println!(
        "{} — {} DOF, {:?} DH",
        model.name,
        robot.dof(),
        model.convention
    );
    println!(
        "{:>4} {:>10} {:>10} {:>10} {:>10} {:>8}",
        "j", "a", "alpha", "d", "theta", "mass"
    );
    for (j, l) in model.links.iter().enumerate() {
        println!(
            "{:>4} {:>10.4} {:>10.4} {:>10.4} {:>10.4} {:>8.3}",
            j + 1,
            l.a,
            l.alpha.radians(),
            l.d,
            l.theta.radians(),
            l.inertial.map_or(0.0, |i| i.mass)
        );
    }

    let q = [0.1, -0.6, 0.4, 0.3, 0.8, -0.2];
    let state = puma560::State::new(&q);
    println!("\nq = {q:?}");
    println!("pose (generated): {}", state.fk().to_homogeneous());
    println!("Jacobian (generated): {}", state.jacobian());
    println!("D(q) (generated): {}", state.mass_matrix());

    // The runtime path computes the same quantities for any robot loaded at run time.
    let worst = (robot.mass_matrix(&q) - state.mass_matrix().fixed_view::<6, 6>(0, 0))
        .abs()
        .max();
    println!("largest |D_runtime - D_generated| = {worst:.1e}");
    Ok(())
}
