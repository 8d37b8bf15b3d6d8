//! A PUMA 560 reaching a target under torque limits with a short-horizon linearised controller
//! built on the generated derivatives of the dynamics (`robot!(..., derivatives)`).
//!
//! ```sh
//! cargo run --release --example mpc [plot.svg]
//! ```
//!
//! Every 10 ms the controller linearises the arm about its current state and the torque that
//! would hold it there, u₀ = C(q, q̇) q̇ + g(q) (so q̈ = 0 at u₀):
//! q̈ ≈ ∂q̈/∂q (q − q₀) + ∂q̈/∂q̇ (q̇ − q̇₀) + D⁻¹ (u − u₀), all three matrices from one call of
//! the generated `forward_dynamics_derivatives`. On that model, discretised over a 0.5 s
//! horizon of 25 steps, it solves the finite-horizon LQR problem (a backward Riccati recursion
//! on the error state with an affine term, augmented by a constant) and applies the first
//! torque, clipped to the motors' limits, until the next replan: receding-horizon control,
//! i.e. linear MPC whose only constraint handling is saturation of the applied torque.
//!
//! The plant is the generated forward dynamics itself, integrated by RK4 at 1 kHz. The example
//! prints the time of one replan (linearisation and Riccati recursion), the final error and the
//! largest torque per joint against its limit, and draws joint angles and torques into an SVG
//! (`target/mpc.svg` unless a path is given).

use dhgen::nalgebra::{SMatrix, SVector};
use plotters::prelude::*;
use std::error::Error;
use std::path::PathBuf;
use std::time::{Duration, Instant};

dhgen::robot!(mod puma560 = "robots/puma560.toml", derivatives);

type V6 = SVector<f64, 6>;
/// The error state `[q − q_target; q̇]` augmented by a constant 1 (for the affine term).
type X = SVector<f64, 13>;
type A = SMatrix<f64, 13, 13>;
type B = SMatrix<f64, 13, 6>;

/// Simulation step (plant, 1 kHz) and control period (replan, 100 Hz), s.
const DT: f64 = 1e-3;
const CONTROL_EVERY: usize = 10;
/// Horizon: steps of `H` seconds.
const STEPS: usize = 25;
const H: f64 = 0.02;
/// Simulated time, s.
const DURATION: f64 = 3.0;
/// Start and target, rad (inside the joint limits, away from the wrist singularity).
const Q0: [f64; 6] = [0.0, 0.3, -0.6, 0.0, 0.6, 0.0];
const QF: [f64; 6] = [1.2, 0.9, -1.4, 1.0, -0.5, 1.5];
/// Torque limits, N·m (the PUMA 560's motor limits as Robotics Toolbox lists them).
const LIMITS: [f64; 6] = [97.6, 186.4, 89.4, 24.2, 20.1, 21.3];
/// Weights: position error, velocity, torque (per N·m²), terminal factor.
const W_POSITION: f64 = 400.0;
const W_VELOCITY: f64 = 4.0;
const W_TORQUE: f64 = 1e-3;
const W_TERMINAL: f64 = 10.0;

/// The first torque of the finite-horizon LQR solution at `(q, q̇)`, before clipping.
fn replan(q: &[f64; 6], qd: &[f64; 6]) -> Option<[f64; 6]> {
    let u0 = puma560::bias(q, qd);
    let (fq, fv, minv) = puma560::forward_dynamics_derivatives(q, qd, &u0)?;
    let (qv, qdv) = (V6::from(*q), V6::from(*qd));
    let e0 = qv - V6::from(QF);
    // Error dynamics over one step of H (semi-implicit Euler):
    //   q̇' = q̇ + H (Fq (e − e0) + Fv (q̇ − q̇0) + D⁻¹ δu),  e' = e + H q̇'.
    let mut a = A::identity();
    let mut b = B::zeros();
    let affine = -(fq * e0 + fv * qdv) * H;
    for r in 0..6 {
        for c in 0..6 {
            let dv_de = H * fq[(r, c)];
            let dv_dv = H * fv[(r, c)] + if r == c { 1.0 } else { 0.0 };
            a[(6 + r, c)] += dv_de;
            a[(6 + r, 6 + c)] = dv_dv;
            b[(6 + r, c)] = H * minv[(r, c)];
        }
        a[(6 + r, 12)] = affine[r];
    }
    // e' = e + H q̇' (the row of q̇' times H).
    for r in 0..6 {
        for c in 0..13 {
            a[(r, c)] += H * a[(6 + r, c)];
        }
        for c in 0..6 {
            b[(r, c)] = H * b[(6 + r, c)];
        }
    }
    let mut q_cost = A::zeros();
    for i in 0..6 {
        q_cost[(i, i)] = W_POSITION;
        q_cost[(6 + i, 6 + i)] = W_VELOCITY;
    }
    let r_cost = SMatrix::<f64, 6, 6>::identity() * W_TORQUE;
    // Backward Riccati recursion; the first step's gain is the one applied.
    let mut p = q_cost * W_TERMINAL;
    let mut gain = SMatrix::<f64, 6, 13>::zeros();
    for _ in 0..STEPS {
        let bt_p = b.transpose() * p;
        gain = (r_cost + bt_p * b).cholesky()?.solve(&(bt_p * a));
        p = q_cost + a.transpose() * p * (a - b * gain);
        p = (p + p.transpose()) * 0.5;
    }
    let mut x = X::zeros();
    x.fixed_rows_mut::<6>(0).copy_from(&e0);
    x.fixed_rows_mut::<6>(6).copy_from(&qdv);
    x[12] = 1.0;
    Some((u0 - gain * x).into())
}

struct Sample {
    t: f64,
    q: [f64; 6],
    tau: [f64; 6],
}

fn main() -> Result<(), Box<dyn Error>> {
    let svg = std::env::args_os().nth(1).map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/mpc.svg"),
        PathBuf::from,
    );
    let (mut q, mut qd) = (V6::from(Q0), V6::zeros());
    let mut tau = [0.0; 6];
    let mut samples = Vec::new();
    let mut replans = Vec::new();
    let mut peak = [0.0_f64; 6];
    let mut saturated_steps = 0;
    let steps = (DURATION / DT).round() as usize;
    for step in 0..steps {
        if step % CONTROL_EVERY == 0 {
            let (qa, qda): ([f64; 6], [f64; 6]) = (q.into(), qd.into());
            let start = Instant::now();
            let u = replan(&qa, &qda).ok_or("the inertia matrix became singular")?;
            replans.push(start.elapsed());
            let mut clipped = false;
            for j in 0..6 {
                tau[j] = u[j].clamp(-LIMITS[j], LIMITS[j]);
                clipped |= tau[j] != u[j];
            }
            saturated_steps += usize::from(clipped);
        }
        for j in 0..6 {
            peak[j] = peak[j].max(tau[j].abs());
        }
        samples.push(Sample {
            t: step as f64 * DT,
            q: q.into(),
            tau,
        });
        (q, qd) = dhgen::simulate::rk4_step(&puma560::Robot, &q, &qd, &V6::from(tau), DT)
            .ok_or("the plant's inertia matrix became singular")?;
    }
    replans.sort();
    let micros = |d: Duration| d.as_secs_f64() * 1e6;
    let error = q - V6::from(QF);
    println!(
        "PUMA 560 from {Q0:?} to {QF:?} rad in {DURATION} s: linear MPC on the generated derivatives"
    );
    println!(
        "replan (∂q̈/∂q, ∂q̈/∂q̇, D⁻¹ at (q, q̇, u₀) and a {STEPS}-step Riccati recursion): median {:.1} µs, 99th percentile {:.1} µs over {} replans",
        micros(replans[replans.len() / 2]),
        micros(replans[replans.len() * 99 / 100]),
        replans.len()
    );
    println!(
        "final position error: max {:.2e} rad; final speed: max {:.2e} rad/s",
        error.amax(),
        qd.amax()
    );
    println!(
        "torque limits reached in {saturated_steps} of {} replans",
        replans.len()
    );
    for j in 0..6 {
        println!(
            "  joint {}: peak |τ| {:7.2} N·m of {:6.1} ({:3.0} %)",
            j + 1,
            peak[j],
            LIMITS[j],
            100.0 * peak[j] / LIMITS[j]
        );
    }
    if error.amax() > 1e-2 {
        return Err(format!(
            "the arm did not reach the target: error {:.3} rad",
            error.amax()
        )
        .into());
    }
    plot(&svg, &samples)?;
    println!("wrote {}", svg.display());
    Ok(())
}

/// Joint angles against their targets (top) and torques as a fraction of their limits
/// (bottom).
fn plot(path: &PathBuf, samples: &[Sample]) -> Result<(), Box<dyn Error>> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let colors = [
        RGBColor(31, 119, 180),
        RGBColor(255, 127, 14),
        RGBColor(44, 160, 44),
        RGBColor(214, 39, 40),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
    ];
    let root = SVGBackend::new(path, (1000, 800)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "PUMA 560 reaching a target: receding-horizon LQR on the generated derivatives, 100 Hz",
        ("sans-serif", 20),
    )?;
    let (legend, body) = root.split_vertically(34);
    for (j, color) in colors.iter().enumerate() {
        let x = 60 + 140 * j as i32;
        legend.draw(&PathElement::new(
            [(x, 17), (x + 28, 17)],
            color.stroke_width(3),
        ))?;
        legend.draw(&Text::new(
            format!("joint {}", j + 1),
            (x + 34, 9),
            ("sans-serif", 16),
        ))?;
    }
    legend.draw(&Text::new(
        "dashed: target",
        (60 + 140 * 6, 9),
        ("sans-serif", 16),
    ))?;
    let panels = body.split_evenly((2, 1));
    let tf = samples.last().map_or(1.0, |s| s.t);
    let mut top = ChartBuilder::on(&panels[0])
        .caption("joint angles", ("sans-serif", 16))
        .margin(10)
        .x_label_area_size(30)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..tf, -100.0..100.0)?;
    top.configure_mesh()
        .x_desc("t [s]")
        .y_desc("q [deg]")
        .draw()?;
    for j in 0..6 {
        top.draw_series(LineSeries::new(
            samples.iter().map(|s| (s.t, s.q[j].to_degrees())),
            colors[j].stroke_width(2),
        ))?;
        let target = QF[j].to_degrees();
        for k in (0..20).step_by(2) {
            let (a, b) = (tf * k as f64 / 20.0, tf * (k + 1) as f64 / 20.0);
            top.draw_series(LineSeries::new([(a, target), (b, target)], colors[j]))?;
        }
    }
    let mut bottom = ChartBuilder::on(&panels[1])
        .caption("torque / limit", ("sans-serif", 16))
        .margin(10)
        .x_label_area_size(30)
        .y_label_area_size(50)
        .build_cartesian_2d(0.0..tf, -1.05..1.05)?;
    bottom
        .configure_mesh()
        .x_desc("t [s]")
        .y_desc("τ / τmax")
        .draw()?;
    for j in 0..6 {
        bottom.draw_series(LineSeries::new(
            samples.iter().map(|s| (s.t, s.tau[j] / LIMITS[j])),
            colors[j].stroke_width(1),
        ))?;
    }
    root.present()?;
    Ok(())
}
