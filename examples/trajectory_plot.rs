//! Plots joint trajectories like Figure 4 of the reference text: position, velocity and
//! acceleration against time, one panel each, one curve per joint.
//!
//! ```text
//! cargo run --example trajectory_plot [output-directory]
//! ```
//!
//! Writes into `target/plots/` of the package unless a directory is given:
//! - `figure4_cubic.svg`: the text's Figure 4 (cubic, q0 = 10°, qf = -20°, tf = 1 s);
//! - `quintic.svg`: a 6-joint rest-to-rest quintic (`jtraj`);
//! - `lspb.svg`: the same move, velocity-limited minimum time, synchronized to the slowest joint;
//! - `bang_bang.svg`: the same move, bang-bang minimum time (a straight line in joint space);
//! - `via_spline.svg`: a 6-joint cubic spline through four via points, at rest at both ends;
//! - `via_blend.svg`: linear segments with parabolic blends through the same via points, timed
//!   from velocity and acceleration limits (`mstraj`).

use std::error::Error;
use std::path::{Path, PathBuf};

use dhgen::trajectory::{
    BlendedSegments, Cubic, CubicSpline, Lspb, MultiProfile, SplineEnds, Synchronized, sample_multi,
};
use plotters::prelude::*;

/// Start and goal of the 6-joint move, in radians.
const Q0: [f64; 6] = [0.0, -0.5, 1.0, 0.0, 0.3, 0.0];
const QF: [f64; 6] = [1.2, 0.4, -0.6, 2.0, -0.8, 1.5];
/// Per-joint limits for the minimum-time and via-point moves (rad/s, rad/s²).
const VMAX: [f64; 6] = [1.0, 1.0, 1.2, 2.0, 2.0, 2.5];
const AMAX: [f64; 6] = [2.0, 2.0, 3.0, 5.0, 5.0, 6.0];
/// Samples per curve: dense enough that acceleration jumps draw as near-vertical lines.
const SAMPLES: usize = 1200;
/// One clearly distinguishable colour per joint.
const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(23, 190, 207),
];

/// Via points for the via-point examples (the first and last are the move's ends).
fn via_points() -> [[f64; 6]; 4] {
    [
        Q0,
        [0.8, 0.3, 0.3, 1.0, -0.4, 0.9],
        [1.8, 0.9, -0.1, 1.4, -1.0, 1.2],
        QF,
    ]
}

/// What one plot shows.
struct Figure<'a> {
    file: &'a str,
    title: &'a str,
    /// Unit of position; velocity and acceleration get `/s` and `/s²`.
    unit: &'a str,
    /// Legend label of joint `j`.
    labels: Vec<String>,
    /// Via points to mark on the position panel: `(time, positions)`.
    marks: Vec<(f64, Vec<f64>)>,
}

fn main() -> Result<(), Box<dyn Error>> {
    let dir = match std::env::args_os().nth(1) {
        Some(dir) => PathBuf::from(dir),
        None => Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("target")
            .join("plots"),
    };
    std::fs::create_dir_all(&dir)?;
    let joints: Vec<String> = (1..=6).map(|j| format!("joint {j}")).collect();
    let plain = |file, title, unit| Figure {
        file,
        title,
        unit,
        labels: joints.clone(),
        marks: Vec::new(),
    };

    let figure4 = Synchronized::new([Cubic::rest_to_rest(0.0, 1.0, 10.0, -20.0)?])?;
    let figure = Figure {
        file: "figure4_cubic.svg",
        title: "Figure 4: cubic, q0 = 10°, qf = -20°, tf = 1 s",
        unit: "°",
        labels: vec!["q(t) = 10 - 90 t² + 60 t³".into()],
        marks: Vec::new(),
    };
    plot(&dir, &figure, &figure4)?;

    let quintic = Synchronized::quintic_rest_to_rest(0.0, 2.0, &Q0, &QF)?;
    plot(
        &dir,
        &plain("quintic.svg", "Quintic, rest to rest, tf = 2 s", "rad"),
        &quintic,
    )?;

    let lspb = Synchronized::<Lspb, 6>::velocity_limited(0.0, &Q0, &QF, &VMAX, &AMAX)?;
    let title = format!(
        "LSPB, minimum time under vmax and amax, synchronized: tf = {:.3} s",
        lspb.duration()
    );
    plot(&dir, &plain("lspb.svg", &title, "rad"), &lspb)?;

    let bang = Synchronized::<Lspb, 6>::bang_bang(0.0, &Q0, &QF, &AMAX)?;
    let title = format!(
        "Bang-bang, minimum time under amax, synchronized: tf = {:.3} s",
        bang.duration()
    );
    plot(&dir, &plain("bang_bang.svg", &title, "rad"), &bang)?;

    let points = via_points();
    let times = [0.0, 1.0, 2.2, 3.5];
    let spline = CubicSpline::new(&times, &points, SplineEnds::AtRest)?;
    let marks = times
        .iter()
        .zip(&points)
        .map(|(&t, p)| (t, p.to_vec()))
        .collect();
    let figure = Figure {
        marks,
        ..plain(
            "via_spline.svg",
            "Cubic spline through 4 via points (dots), at rest at the ends",
            "rad",
        )
    };
    plot(&dir, &figure, &spline)?;

    let blend = BlendedSegments::from_limits(0.0, &points, &VMAX, &AMAX)?;
    let marks = blend
        .times()
        .iter()
        .zip(&points)
        .map(|(&t, p)| (t, p.to_vec()))
        .collect();
    let title = format!(
        "Linear segments, parabolic blends (mstraj) from vmax, amax: tacc = {:.3} s, tf = {:.3} s",
        blend.blend_time(),
        blend.duration()
    );
    let figure = Figure {
        marks,
        ..plain("via_blend.svg", &title, "rad")
    };
    plot(&dir, &figure, &blend)?;

    println!("wrote 6 plots to {}", dir.display());
    Ok(())
}

/// Draws position, velocity and acceleration panels, stacked, for every joint of `profile`.
fn plot(dir: &Path, figure: &Figure<'_>, profile: &dyn MultiProfile) -> Result<(), Box<dyn Error>> {
    let samples = sample_multi(profile, SAMPLES)?;
    let path = dir.join(figure.file);
    let root = SVGBackend::new(&path, (1000, 1050)).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(figure.title, ("sans-serif", 22))?;
    // The legend gets its own strip so that it never hides a curve.
    let (legend, body) = root.split_vertically(36);
    for (joint, label) in figure.labels.iter().enumerate() {
        let x = 90 + 150 * joint as i32;
        legend.draw(&PathElement::new(
            [(x, 18), (x + 28, 18)],
            COLORS[joint].stroke_width(3),
        ))?;
        legend.draw(&Text::new(label.as_str(), (x + 34, 10), ("sans-serif", 16)))?;
    }
    let panels = body.split_evenly((3, 1));
    let names = ["(a) position", "(b) velocity", "(c) acceleration"];
    let units = [
        figure.unit.to_string(),
        format!("{}/s", figure.unit),
        format!("{}/s²", figure.unit),
    ];
    let (t0, tf) = (profile.start_time(), profile.end_time());

    for (panel_index, panel) in panels.iter().enumerate() {
        let value = |s: dhgen::trajectory::Setpoint| [s.q, s.qd, s.qdd][panel_index];
        let (mut lo, mut hi) = samples
            .setpoints
            .iter()
            .map(|&s| value(s))
            .fold((0.0f64, 0.0f64), |(lo, hi), v| (lo.min(v), hi.max(v)));
        let pad = 0.08 * (hi - lo).max(1e-9);
        (lo, hi) = (lo - pad, hi + pad);
        let mut chart = ChartBuilder::on(panel)
            .caption(names[panel_index], ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(38)
            .y_label_area_size(70)
            .build_cartesian_2d(t0..tf, lo..hi)?;
        chart
            .configure_mesh()
            .x_desc("t [s]")
            .y_desc(units[panel_index].as_str())
            .axis_desc_style(("sans-serif", 15))
            .light_line_style(WHITE.mix(0.0))
            .draw()?;
        // The zero line, as in the text's figures.
        chart.draw_series(LineSeries::new([(t0, 0.0), (tf, 0.0)], BLACK.mix(0.4)))?;
        for (joint, color) in COLORS.iter().enumerate().take(samples.dof) {
            chart.draw_series(LineSeries::new(
                samples.joint(joint).map(|(t, s)| (t, value(s))),
                color.stroke_width(2),
            ))?;
        }
        if panel_index == 0 {
            for (t, positions) in &figure.marks {
                chart.draw_series(
                    positions
                        .iter()
                        .enumerate()
                        .map(|(joint, &q)| Circle::new((*t, q), 4, COLORS[joint].filled())),
                )?;
            }
        }
    }
    root.present()?;
    Ok(())
}
