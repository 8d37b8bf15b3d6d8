//! A Franka Panda drawing a circle with its tool under operational-space control (Khatib),
//! built on `dhgen::task_space` over the generated dynamics, while its redundant seventh
//! degree of freedom holds a posture in the null space of the task.
//!
//! ```sh
//! cargo run --release --example operational_space [plot.svg]
//! ```
//!
//! At 1 kHz the controller forms the tool's task-space dynamics `Λ a + μ + p = F` at the
//! measured state and commands
//!
//! `τ = Jᵀ (Λ (a_d + K_p e + K_d ė) + μ + p) + Nᵀ τ₀`,
//!
//! `e` the tool's position error and orientation error (the rotation vector taking the tool's
//! orientation to the desired one), `τ₀ = K_q (q_rest − q) − D_q q̇` a joint-space pull toward a
//! rest posture, which `Nᵀ` filters so that it does not disturb the tool. The plant is the
//! generated forward dynamics of the same arm, integrated by RK4 at 1 kHz with the torque held
//! between control steps. The example prints the time of one control step, the tracking errors,
//! and how far the joints move from the rest posture, with and without the null-space torque
//! (without it the task is tracked as well, but nothing holds the arm's self-motion), and draws
//! the path and the errors into an SVG (`target/operational_space.svg` unless a path is given).

use dhgen::nalgebra::{Isometry3, SVector, UnitQuaternion, Vector3, Vector6};
use dhgen::task_space::tool;
use plotters::prelude::*;
use std::error::Error;
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};
use std::path::PathBuf;
use std::time::{Duration, Instant};

dhgen::robot!(mod panda = "robots/panda.toml");

type V7 = SVector<f64, 7>;

/// Simulation and control step, s; simulated time, s.
const DT: f64 = 1e-3;
const DURATION: f64 = 4.0;
/// The Panda's "ready" posture: the start and the posture held in the null space.
const Q_REST: [f64; 7] = [
    0.0,
    -FRAC_PI_4,
    0.0,
    -3.0 * FRAC_PI_4,
    0.0,
    FRAC_PI_2,
    FRAC_PI_4,
];
/// The circle: radius (m), and the angular speed it ramps up to (rad/s) with time constant
/// `RAMP` (s), so that the tool starts at rest.
const RADIUS: f64 = 0.1;
const OMEGA: f64 = PI;
const RAMP: f64 = 0.3;
/// Task gains (1/s², 1/s): a critically damped 20 rad/s loop on every task direction.
const KP: f64 = 400.0;
const KD: f64 = 40.0;
/// Null-space posture gains (N·m/rad, N·m·s/rad).
const KQ: f64 = 50.0;
const DQ: f64 = 10.0;

/// The desired tool position, velocity and acceleration at time `t`, on a circle in the
/// horizontal plane through `start`, starting there at rest.
fn circle(start: &Vector3<f64>, t: f64) -> [Vector3<f64>; 3] {
    let decay = (-t / RAMP).exp();
    let (phi, phid, phidd) = (
        OMEGA * (t - RAMP * (1.0 - decay)),
        OMEGA * (1.0 - decay),
        OMEGA / RAMP * decay,
    );
    let centre = start - Vector3::new(RADIUS, 0.0, 0.0);
    let (s, c) = phi.sin_cos();
    let radial = Vector3::new(c, s, 0.0);
    let tangent = Vector3::new(-s, c, 0.0);
    [
        centre + radial * RADIUS,
        tangent * (RADIUS * phid),
        tangent * (RADIUS * phidd) - radial * (RADIUS * phid * phid),
    ]
}

struct Sample {
    t: f64,
    position: Vector3<f64>,
    desired: Vector3<f64>,
    orientation_error: f64,
    posture: f64,
}

/// The control law at `(q, q̇)` and time `t`: the torques, the tool pose it measured, and the
/// time the step took.
fn control(
    q: &V7,
    qd: &V7,
    t: f64,
    start: &Vector3<f64>,
    goal: &UnitQuaternion<f64>,
    null_space: bool,
) -> Result<(V7, Isometry3<f64>, Duration), Box<dyn Error>> {
    let clock = Instant::now();
    let task = tool(&panda::Robot, q, qd)?;
    let pose = panda::fk(q);
    let [p_d, v_d, a_d] = circle(start, t);
    let twist = task.jacobian() * qd;
    // The rotation vector from the tool's orientation to the desired one, world axes.
    let orientation = (goal * pose.rotation.inverse()).scaled_axis();
    let position = p_d - pose.translation.vector;
    let error = Vector6::new(
        position.x,
        position.y,
        position.z,
        orientation.x,
        orientation.y,
        orientation.z,
    );
    let rate = Vector6::new(v_d.x, v_d.y, v_d.z, 0.0, 0.0, 0.0) - twist;
    let a = Vector6::new(a_d.x, a_d.y, a_d.z, 0.0, 0.0, 0.0) + error * KP + rate * KD;
    let mut tau = task.torque(&task.force(&a));
    if null_space {
        let pull = (V7::from(Q_REST) - q) * KQ - qd * DQ;
        tau += task.null_space_torque(&pull);
    }
    Ok((tau, pose, clock.elapsed()))
}

/// Simulates the circle; returns the samples and the control steps' times.
fn run(null_space: bool) -> Result<(Vec<Sample>, Vec<Duration>), Box<dyn Error>> {
    let (mut q, mut qd) = (V7::from(Q_REST), V7::zeros());
    let start_pose = panda::fk(&q);
    let (start, goal) = (start_pose.translation.vector, start_pose.rotation);
    let mut samples = Vec::new();
    let mut times = Vec::new();
    for step in 0..(DURATION / DT).round() as usize {
        let t = step as f64 * DT;
        // The pose the controller measured, recorded.
        let (tau, pose, took) = control(&q, &qd, t, &start, &goal, null_space)?;
        times.push(took);
        samples.push(Sample {
            t,
            position: pose.translation.vector,
            desired: circle(&start, t)[0],
            orientation_error: (goal * pose.rotation.inverse()).angle(),
            posture: (q - V7::from(Q_REST)).norm(),
        });
        (q, qd) = dhgen::simulate::rk4_step(&panda::Robot, &q, &qd, &tau, DT)
            .ok_or("the plant's inertia matrix became singular")?;
    }
    Ok((samples, times))
}

fn main() -> Result<(), Box<dyn Error>> {
    let svg = std::env::args_os().nth(1).map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/operational_space.svg"),
        PathBuf::from,
    );
    let (samples, mut times) = run(true)?;
    let (without, _) = run(false)?;
    times.sort();
    let micros = |d: Duration| d.as_secs_f64() * 1e6;
    // After the ramp-in (one time constant), the tracking errors.
    let settled = |s: &&Sample| s.t > RAMP;
    let path_error = |s: &[Sample]| {
        s.iter()
            .filter(settled)
            .map(|s| (s.position - s.desired).norm())
            .fold(0.0, f64::max)
    };
    let position = path_error(&samples);
    let orientation = samples
        .iter()
        .filter(settled)
        .map(|s| s.orientation_error)
        .fold(0.0, f64::max);
    let posture = |s: &[Sample]| s.iter().map(|s| s.posture).fold(0.0, f64::max);
    println!(
        "Panda drawing a {RADIUS} m circle at up to {:.2} m/s for {DURATION} s: operational-space control on the generated dynamics",
        RADIUS * OMEGA
    );
    println!(
        "control step (task-space dynamics Λ, J̄, μ, p from the generated D, J, J̇q̇, bias and g, and the law): median {:.2} µs, 99th percentile {:.2} µs over {} steps",
        micros(times[times.len() / 2]),
        micros(times[times.len() * 99 / 100]),
        times.len()
    );
    println!(
        "tracking error after the ramp-in: position max {:.3} mm, orientation max {:.3} mrad",
        position * 1e3,
        orientation * 1e3
    );
    println!(
        "joints away from the rest posture, max |q − q_rest|: {:.3} rad with the null-space torque (the circle needs it), {:.3} rad without (the self-motion left to itself; the tool still within {:.3} mm of its path)",
        posture(&samples),
        posture(&without),
        path_error(&without) * 1e3
    );
    plot(&svg, &samples, &without)?;
    println!("wrote {}", svg.display());
    if position > 1e-3 || orientation > 1e-2 {
        return Err(format!(
            "the tool left its path: {:.3} mm, {:.3} mrad",
            position * 1e3,
            orientation * 1e3
        )
        .into());
    }
    Ok(())
}

/// The path seen from above, desired and actual (left); position error and posture drift
/// against time, with and without the null-space torque (right).
fn plot(path: &PathBuf, samples: &[Sample], without: &[Sample]) -> Result<(), Box<dyn Error>> {
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let blue = RGBColor(31, 119, 180);
    let orange = RGBColor(255, 127, 14);
    let root = SVGBackend::new(path, (1100, 520)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        "Panda: operational-space control on the generated dynamics, 1 kHz",
        ("sans-serif", 20),
    )?;
    let (left, right) = root.split_horizontally(520);
    let centre = samples[0].desired - Vector3::new(RADIUS, 0.0, 0.0);
    let span = 1.3 * RADIUS;
    let mut top = ChartBuilder::on(&left)
        .caption("tool path seen from above [m]", ("sans-serif", 16))
        .margin(10)
        .x_label_area_size(30)
        .y_label_area_size(50)
        .build_cartesian_2d(
            (centre.x - span)..(centre.x + span),
            (centre.y - span)..(centre.y + span),
        )?;
    top.configure_mesh().x_desc("x").y_desc("y").draw()?;
    top.draw_series(LineSeries::new(
        samples.iter().map(|s| (s.desired.x, s.desired.y)),
        orange.stroke_width(4),
    ))?
    .label("desired")
    .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], orange.stroke_width(4)));
    top.draw_series(LineSeries::new(
        samples.iter().map(|s| (s.position.x, s.position.y)),
        blue.stroke_width(1),
    ))?
    .label("actual")
    .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], blue));
    top.configure_series_labels()
        .border_style(BLACK)
        .background_style(WHITE)
        .draw()?;
    let panels = right.split_evenly((2, 1));
    let tf = samples.last().map_or(1.0, |s| s.t);
    let error_mm = |s: &Sample| (s.position - s.desired).norm() * 1e3;
    let peak = samples.iter().map(error_mm).fold(1e-3, f64::max);
    let mut errors = ChartBuilder::on(&panels[0])
        .caption("position error [mm]", ("sans-serif", 16))
        .margin(10)
        .x_label_area_size(30)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..tf, 0.0..peak * 1.1)?;
    errors.configure_mesh().x_desc("t [s]").draw()?;
    errors.draw_series(LineSeries::new(
        samples.iter().map(|s| (s.t, error_mm(s))),
        blue.stroke_width(2),
    ))?;
    let drift = without
        .iter()
        .chain(samples)
        .map(|s| s.posture)
        .fold(1e-3, f64::max);
    let mut posture = ChartBuilder::on(&panels[1])
        .caption("posture drift |q − q_rest| [rad]", ("sans-serif", 16))
        .margin(10)
        .x_label_area_size(30)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..tf, 0.0..drift * 1.1)?;
    posture.configure_mesh().x_desc("t [s]").draw()?;
    posture
        .draw_series(LineSeries::new(
            samples.iter().map(|s| (s.t, s.posture)),
            blue.stroke_width(2),
        ))?
        .label("with the null-space torque")
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], blue.stroke_width(2)));
    posture
        .draw_series(LineSeries::new(
            without.iter().map(|s| (s.t, s.posture)),
            orange.stroke_width(2),
        ))?
        .label("without")
        .legend(move |(x, y)| PathElement::new([(x, y), (x + 20, y)], orange.stroke_width(2)));
    posture
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperLeft)
        .border_style(BLACK)
        .background_style(WHITE)
        .draw()?;
    root.present()?;
    Ok(())
}
