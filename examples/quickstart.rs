//! The quick start: PUMA 560 generated at compile time by `robot!`, and the same robot
//! loaded at run time, evaluated at one configuration and printed side by side.
//!
//! `cargo run --release --example quickstart`

use dhgen::Robot;
use dhgen::nalgebra::DMatrix;

// Everything in `puma560` is straight-line code derived symbolically from the DH table.
dhgen::robot!(pub mod puma560 = "robots/puma560.toml");

/// Prints `generated` and `runtime` side by side (four decimals, small values in scientific
/// notation) and the largest difference.
fn side_by_side(title: &str, generated: &DMatrix<f64>, runtime: &DMatrix<f64>) {
    let width = 9 * generated.ncols();
    println!("\n{title}");
    println!(
        "  {:<width$}    {:<width$}",
        "generated (robot!)", "runtime (dhgen::Robot)"
    );
    for r in 0..generated.nrows() {
        let row = |m: &DMatrix<f64>| -> String {
            m.row(r)
                .iter()
                .map(|x| match x.abs() {
                    // Rounding residue is 0; small values keep their digits.
                    a if a < 1e-12 => format!("{:>9.4}", 0.0),
                    a if a < 1e-3 => format!("{x:>9.1e}"),
                    _ => format!("{x:>9.4}"),
                })
                .collect()
        };
        println!("  {}    {}", row(generated), row(runtime));
    }
    println!(
        "  largest difference: {:.1e}",
        (generated - runtime).abs().max()
    );
}

/// Any nalgebra matrix as a dynamically sized one, for printing.
fn dynamic<R: dhgen::nalgebra::Dim, C: dhgen::nalgebra::Dim, S>(
    m: &dhgen::nalgebra::Matrix<f64, R, C, S>,
) -> DMatrix<f64>
where
    S: dhgen::nalgebra::RawStorage<f64, R, C>,
{
    DMatrix::from_fn(m.nrows(), m.ncols(), |i, j| m[(i, j)])
}

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
        "j", "a [m]", "alpha [°]", "d [m]", "theta [°]", "mass [kg]"
    );
    for (j, l) in model.links.iter().enumerate() {
        println!(
            "{:>4} {:>10.4} {:>10.1} {:>10.4} {:>10.1} {:>8.3}",
            j + 1,
            l.a,
            l.alpha.radians().to_degrees(),
            l.d,
            l.theta.radians().to_degrees(),
            l.inertial.map_or(0.0, |i| i.mass)
        );
    }

    let q = [0.1, -0.6, 0.4, 0.3, 0.8, -0.2];
    let qd = [0.2, 0.1, -0.3, 0.0, 0.5, 0.1];
    println!("\nq = {q:?} rad, q̇ = {qd:?} rad/s");
    let state = puma560::State::new(&q);
    side_by_side(
        "pose T (4×4)",
        &dynamic(&state.fk_matrix()),
        &dynamic(&robot.fk(&q).to_homogeneous()),
    );
    side_by_side(
        "Jacobian J (rows vx vy vz ωx ωy ωz)",
        &dynamic(&state.jacobian()),
        &dynamic(&robot.jacobian(&q)),
    );
    side_by_side(
        "inertia matrix D(q) [kg·m²]",
        &dynamic(&state.mass_matrix()),
        &dynamic(&robot.mass_matrix(&q)),
    );
    side_by_side(
        "gravity g(q) [N·m], transposed",
        &dynamic(&state.gravity().transpose()),
        &dynamic(&robot.gravity(&q).transpose()),
    );
    side_by_side(
        "inverse dynamics τ at q̈ = 0.5 rad/s² [N·m], transposed",
        &dynamic(&puma560::inverse_dynamics(&q, &qd, &[0.5; 6]).transpose()),
        &dynamic(&robot.inverse_dynamics(&q, &qd, &[0.5; 6]).transpose()),
    );
    Ok(())
}
