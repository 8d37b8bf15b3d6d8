//! Path planning (sections 6.1 to 6.4 of the reference text) on two robots.
//!
//! ```text
//! cargo run --release --example planning [output-directory]
//! ```
//!
//! A planar 2-link arm (`robots/planar_elbow.toml`, links as capsules of radius 5 cm) among
//! a sphere, a box and a capsule, like Figure 3 of the text. Writes into
//! `target/plots/` of the package unless a directory is given:
//! - `planar_cspace.svg`: the configuration-space obstacle region QO on a grid over (q1, q2)
//!   of one cell per pixel, the roadmap, the PRM path, and the paths of the C-space and
//!   workspace potential fields (a cross where a field got stuck in a local minimum instead);
//! - `planar_workspace.svg`: the obstacles and the arm along the PRM path;
//! - `narrow_cspace.svg`, `narrow_workspace.svg`: the same for a scene whose free space has a
//!   narrow passage (a ring of capsules around the arm with a door that link 2 must pass
//!   through to turn the elbow over).
//!
//! Then a PUMA 560 among a table, a panel and a ball, solved by PRM; prints the roadmap's
//! statistics and the path, and writes `puma_views.svg` (the arm along the path, from the
//! side and from above).
//!
//! Every picture has its title and its legend in strips of their own above the charts, so
//! that neither covers any data.
//!
//! The scenes and budgets are those of the tests, in `tests/integration/planning_support.rs`.

use std::error::Error;
use std::path::{Path, PathBuf};
use std::time::Instant;

use dhgen::nalgebra::{SVector, Vector3};
use dhgen::planning::collision::LinkCapsule;
use dhgen::planning::{
    CSpaceField, CSpaceGrid, CollisionChecker, DescentParams, Obstacle, PlanError, Prm, Scene,
    WorkspaceField, WorkspacePlanner,
};
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

#[path = "../tests/integration/planning_support.rs"]
pub mod scenes;
use scenes::PlanarScene;

dhgen::robot!(mod planar = "robots/planar_elbow.toml");
dhgen::robot!(mod puma = "robots/puma560.toml");

type Q2 = SVector<f64, 2>;
type Q6 = SVector<f64, 6>;

const OBSTACLE: RGBColor = RGBColor(120, 120, 120);
const ROADMAP: RGBColor = RGBColor(100, 150, 220);
const PRM_PATH: RGBColor = RGBColor(214, 39, 40);
const CSPACE_PATH: RGBColor = RGBColor(44, 160, 44);
const WORKSPACE_PATH: RGBColor = RGBColor(255, 127, 14);
/// The goal: its marker in C-space, the arm's last pose in the workspace.
const GOAL: RGBColor = RGBColor(20, 40, 160);
/// Radius of the start's disc and half the side of the goal's square, in pixels.
const START_RADIUS: i32 = 7;
const GOAL_HALF: i32 = 6;
/// Size of the cross where a potential field got stuck, and its line width, in pixels.
const STUCK_SIZE: i32 = 9;
const STUCK_WIDTH: u32 = 4;

fn main() -> Result<(), Box<dyn Error>> {
    let dir = match std::env::args_os().nth(1) {
        Some(dir) => PathBuf::from(dir),
        None => Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("target")
            .join("plots"),
    };
    std::fs::create_dir_all(&dir)?;
    for scene in [scenes::figure3(), scenes::narrow_passage()] {
        planar(&dir, &scene)?;
    }
    puma560(&dir)?;
    Ok(())
}

fn planar(dir: &Path, scene: &PlanarScene) -> Result<(), Box<dyn Error>> {
    let mut checker = CollisionChecker::new(&planar::Robot, Scene::new(scene.obstacles.clone())?)?;
    let (start, goal) = (Q2::from(scene.start), Q2::from(scene.goal));
    let config = scenes::narrow_config();
    let resolution = config.resolution;

    let t = Instant::now();
    let grid = CSpaceGrid::compute(&mut checker, [240, 240])?;
    println!(
        "{}: QO grid 240 x 240 in {:.1?}: {:.1}% occupied, {} components",
        scene.name,
        t.elapsed(),
        100.0 * grid.occupied_fraction(),
        grid.components()
    );

    let mut prm = Prm::new(&mut checker, config, 1)?;
    let path = match prm.query(&start, &goal) {
        Ok(path) => path,
        Err(e) => {
            println!("{}: PRM failed: {e}", scene.name);
            let nodes: Vec<Q2> = prm.nodes().to_vec();
            let edges: Vec<(usize, usize)> = prm.edges().collect();
            drop(prm);
            draw_cspace(
                &dir.join(format!("{}_cspace.svg", scene.name)),
                scene,
                &mut checker,
                &nodes,
                &edges,
                &[],
            )?;
            return Ok(());
        }
    };
    println!(
        "{}: PRM {} nodes, {} edges, {} components, {} enhancement rounds, {} collision checks, {:.1?}; \
         path {} waypoints, length {:.3} (roadmap {:.3}, {} shortcuts)",
        scene.name,
        path.stats.nodes,
        path.stats.edges,
        path.stats.components,
        path.stats.enhancement_rounds,
        path.stats.collision_checks,
        path.stats.time,
        path.waypoints.len(),
        path.length,
        path.roadmap_length,
        path.shortcuts
    );
    let nodes: Vec<Q2> = prm.nodes().to_vec();
    let edges: Vec<(usize, usize)> = prm.edges().collect();
    drop(prm);

    // The C-space potential of 6.2 over the grid's obstacle region.
    let cspace = dhgen::planning::potential::plan(
        &CSpaceField {
            zeta: 1.0,
            d: 1.0,
            eta: 0.05,
            rho0: 0.5,
        },
        grid.obstacles(&mut checker, resolution).unwrap(),
        start.as_slice(),
        goal.as_slice(),
        &DescentParams {
            step: 0.02,
            tolerance: 0.02,
            ..DescentParams::default()
        },
    );
    let cspace_path: Vec<Q2> = match &cspace {
        Ok(p) => {
            println!(
                "{}: C-space potential field: {} iterations, {} random walks",
                scene.name, p.iterations, p.random_walks
            );
            p.waypoints
                .iter()
                .map(|q| Q2::from_column_slice(q))
                .collect()
        }
        Err(e) => {
            println!("{}: C-space potential field failed: {e}", scene.name);
            stuck_at(e)
        }
    };
    // The workspace potential of 6.3.
    let mut planner = WorkspacePlanner::new(
        &mut checker,
        WorkspaceField {
            zeta: vec![1.0, 2.0],
            d: 0.5,
            eta: 0.002,
            rho0: 0.3,
        },
        resolution,
    )?;
    let workspace = planner.plan(
        &start,
        &goal,
        &DescentParams {
            step: 0.02,
            tolerance: 0.02,
            ..DescentParams::default()
        },
    );
    let workspace_path: Vec<Q2> = match &workspace {
        Ok(p) => {
            println!(
                "{}: workspace potential field: {} iterations, {} random walks",
                scene.name, p.iterations, p.random_walks
            );
            p.waypoints.clone()
        }
        Err(e) => {
            println!("{}: workspace potential field failed: {e}", scene.name);
            stuck_at(e)
        }
    };

    draw_cspace(
        &dir.join(format!("{}_cspace.svg", scene.name)),
        scene,
        &mut checker,
        &nodes,
        &edges,
        &[
            (&path.waypoints, PRM_PATH, "PRM path (smoothed)"),
            (&cspace_path, CSPACE_PATH, "C-space potential field (6.2)"),
            (
                &workspace_path,
                WORKSPACE_PATH,
                "workspace potential field (6.3)",
            ),
        ],
    )?;
    let poses: Vec<Vec<LinkCapsule>> = resample(&path.waypoints, 0.15)
        .iter()
        .map(|q| checker.capsules(q))
        .collect();
    draw_workspace(
        &dir.join(format!("{}_workspace.svg", scene.name)),
        scene,
        &poses,
    )?;
    Ok(())
}

/// Where a potential field got stuck, as a one-point "path" that the picture marks with a
/// cross; nothing for other failures.
fn stuck_at(e: &PlanError) -> Vec<Q2> {
    match e {
        PlanError::LocalMinimum { q, .. } => vec![Q2::from_column_slice(q)],
        _ => Vec::new(),
    }
}

/// Points along the polyline through `path`, at most `spacing` apart.
fn resample<const N: usize>(path: &[SVector<f64, N>], spacing: f64) -> Vec<SVector<f64, N>> {
    let mut out = vec![path[0]];
    for w in path.windows(2) {
        let steps = ((w[1] - w[0]).norm() / spacing).ceil().max(1.0) as usize;
        out.extend((1..=steps).map(|k| w[0].lerp(&w[1], k as f64 / steps as f64)));
    }
    out
}

type Series<'p> = (&'p [Q2], RGBColor, &'p str);

/// Line width of the paths in C-space, in pixels.
const PATH_WIDTH: u32 = 2;
/// Blank margin around the joint ranges in the C-space pictures, in pixels: more than any
/// marker reaches from its configuration, so that a marker on a joint limit (where a
/// potential field may get stuck) stays inside the plotting area.
const CSPACE_PAD: i32 = 16;
const _: () = assert!(
    CSPACE_PAD > STUCK_SIZE + STUCK_WIDTH as i32 / 2
        && CSPACE_PAD > START_RADIUS
        && CSPACE_PAD > GOAL_HALF
);

/// The configuration space of the planar arm: QO, the roadmap, `paths` (a one-point path is
/// where a potential field got stuck), start and goal.
///
/// QO is drawn from a grid of its own, of one cell per pixel, rather than from the potential
/// field's grid, and the paths are drawn 2 pixels wide. A cell is occupied when the arm
/// collides at the cell's centre ([`CSpaceGrid`]), so a drawn cell can stick out of the true
/// QO by up to half its diagonal. The field's 240 × 240 cells are 0.026 rad (3.4 pixels)
/// wide, coarser than the 0.02 rad the planners check motions at, and drawn from them, the
/// smoothed PRM path of the narrow passage ran over an occupied cell although no
/// configuration on it collides: from (1.005, 1.273) to (1.477, 0.244) it stays 0.02 m clear
/// of the ring, yet crosses the free corner of cell (165, 151), whose centre (1.191, 0.825)
/// collides (and elsewhere it passed within 1.7 pixels of occupied cells, hardly more than
/// the half width of the 3-pixel line it was drawn with). With one-pixel cells (0.008 rad)
/// the overhang is at most 0.7 pixel, and the path keeps 1.3 pixels off every occupied cell.
fn draw_cspace(
    file: &Path,
    scene: &PlanarScene,
    checker: &mut CollisionChecker<'_, planar::Robot>,
    nodes: &[Q2],
    edges: &[(usize, usize)],
    paths: &[Series<'_>],
) -> Result<(), Box<dyn Error>> {
    let qo = OBSTACLE.mix(0.45).filled();
    let mut legend = vec![
        (Mark::Start, "start".to_string()),
        (Mark::Goal, "goal".to_string()),
    ];
    for &(path, color, label) in paths {
        match path {
            [] => {}
            [_] => legend.push((
                Mark::Cross(color.stroke_width(3)),
                format!("{label}: stuck in a local minimum"),
            )),
            _ => legend.push((
                Mark::Line(color.stroke_width(PATH_WIDTH)),
                label.to_string(),
            )),
        }
    }
    if !nodes.is_empty() {
        legend.push((Mark::Roadmap, "roadmap (nodes and edges)".to_string()));
    }
    legend.push((
        Mark::Area(qo),
        "QO: the arm collides at the centre of the cell (one-pixel cells)".to_string(),
    ));
    legend.push((
        Mark::Frame(BLACK.stroke_width(1)),
        "joint limits".to_string(),
    ));
    let (root, body) = picture(
        file,
        (900, 900),
        &format!("{}: configuration space", scene.title),
        &legend,
    )?;

    let mut builder = ChartBuilder::on(&body);
    builder
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(50);
    // The plotting area's size does not depend on the ranges: find it first, then make the
    // joint ranges span a whole number of pixels, one grid cell each, with CSPACE_PAD
    // pixels to spare on every side.
    let (w, h) = builder
        .build_cartesian_2d(0.0..1.0, 0.0..1.0)?
        .plotting_area()
        .dim_in_pixel();
    let cells = [w, h].map(|n| (n as i32 - 2 * CSPACE_PAD) as usize);
    let bounds = [checker.joint_range(0), checker.joint_range(1)];
    let padded = |[lo, hi]: [f64; 2], n: usize| {
        let pad = (hi - lo) * CSPACE_PAD as f64 / n as f64;
        (lo - pad)..(hi + pad)
    };
    let mut chart =
        builder.build_cartesian_2d(padded(bounds[0], cells[0]), padded(bounds[1], cells[1]))?;
    chart
        .configure_mesh()
        .x_desc("q1 (rad)")
        .y_desc("q2 (rad)")
        .disable_mesh()
        .draw()?;

    let t = Instant::now();
    let grid = CSpaceGrid::compute(checker, cells)?;
    let [dx, dy] = grid.cell_size();
    println!(
        "{}: QO drawn on {} x {} cells of {dx:.4} x {dy:.4} rad in {:.1?}",
        scene.name,
        cells[0],
        cells[1],
        t.elapsed()
    );
    // QO: runs of occupied cells along q2, one rectangle each.
    let [[x0, x1], [y0, y1]] = grid.bounds();
    let mut runs = Vec::new();
    for i in 0..cells[0] {
        let mut j = 0;
        while j < cells[1] {
            if grid.is_occupied(i, j) {
                let start = j;
                while j < cells[1] && grid.is_occupied(i, j) {
                    j += 1;
                }
                let xa = x0 + i as f64 * dx;
                runs.push([(xa, y0 + start as f64 * dy), (xa + dx, y0 + j as f64 * dy)]);
            } else {
                j += 1;
            }
        }
    }
    chart.draw_series(runs.into_iter().map(|r| Rectangle::new(r, qo)))?;
    chart.draw_series([Rectangle::new([(x0, y0), (x1, y1)], BLACK.stroke_width(1))])?;
    chart.draw_series(edges.iter().map(|&(a, b)| {
        PathElement::new(
            vec![(nodes[a][0], nodes[a][1]), (nodes[b][0], nodes[b][1])],
            ROADMAP.mix(0.5).stroke_width(1),
        )
    }))?;
    chart.draw_series(
        nodes
            .iter()
            .map(|q| Circle::new((q[0], q[1]), 2, ROADMAP.filled())),
    )?;
    // Markers last, over the paths. Every marked configuration is within the joint ranges,
    // so CSPACE_PAD keeps its marker inside the plotting area.
    let within = |q: &[f64]| (0..2).all(|a| (bounds[a][0]..=bounds[a][1]).contains(&q[a]));
    let mut stuck = Vec::new();
    for &(path, color, _) in paths {
        match path {
            [] => {}
            [q] => stuck.push((*q, color)),
            _ => {
                chart.draw_series(LineSeries::new(
                    path.iter().map(|q| (q[0], q[1])),
                    color.stroke_width(PATH_WIDTH),
                ))?;
            }
        }
    }
    for (q, color) in stuck {
        if !within(q.as_slice()) {
            return Err(format!("stuck at {q:?}, outside the joint ranges").into());
        }
        chart.draw_series([Cross::new(
            (q[0], q[1]),
            STUCK_SIZE,
            color.stroke_width(STUCK_WIDTH),
        )])?;
    }
    for q in [scene.start, scene.goal] {
        if !within(&q) {
            return Err(format!("{q:?} is outside the joint ranges").into());
        }
    }
    chart.draw_series([Circle::new(
        (scene.start[0], scene.start[1]),
        START_RADIUS,
        BLACK.filled(),
    )])?;
    chart.draw_series([EmptyElement::at((scene.goal[0], scene.goal[1]))
        + Rectangle::new(
            [(-GOAL_HALF, -GOAL_HALF), (GOAL_HALF, GOAL_HALF)],
            GOAL.filled(),
        )])?;
    root.present()?;
    println!("wrote {}", file.display());
    Ok(())
}

/// What a legend entry shows in front of its text.
enum Mark {
    /// A line, for a path.
    Line(ShapeStyle),
    /// A filled square, for a region.
    Area(ShapeStyle),
    /// An empty square, for a boundary.
    Frame(ShapeStyle),
    /// A roadmap edge between two nodes.
    Roadmap,
    /// The start's disc.
    Start,
    /// The goal's square.
    Goal,
    /// A cross, where a potential field got stuck.
    Cross(ShapeStyle),
    /// Outlines of the arm's links, side by side.
    Links(Vec<ShapeStyle>),
}

/// A legend entry: its mark and its text.
type Entry = (Mark, String);

/// A part of an SVG picture, in pixels.
type Area<'f> = DrawingArea<SVGBackend<'f>, Shift>;

const TITLE_FONT: u32 = 20;
const TITLE_HEIGHT: u32 = 34;
const LEGEND_FONT: u32 = 15;
/// Height of a row of the legend, and the width of a mark, in pixels.
const LEGEND_ROW: i32 = 24;
const MARK_WIDTH: i32 = 28;
/// A generous width of a character of the legend's font, in pixels: the SVG backend writes
/// ("sans-serif", 15) as 12.1-pixel text, whose characters are about 7 pixels wide.
const LEGEND_CHAR: i32 = 8;

impl Mark {
    /// Draws the mark on `area` from `x` to `x + MARK_WIDTH`, centred on the line `y`.
    fn draw(&self, area: &Area<'_>, x: i32, y: i32) -> Result<(), Box<dyn Error>> {
        let square = |half: i32| [(x + 14 - half, y - half), (x + 14 + half, y + half)];
        match self {
            Mark::Line(style) => {
                area.draw(&PathElement::new([(x, y), (x + MARK_WIDTH, y)], *style))?
            }
            Mark::Area(style) | Mark::Frame(style) => {
                area.draw(&Rectangle::new(square(7), *style))?
            }
            Mark::Roadmap => {
                let ends = [(x + 4, y + 4), (x + 24, y - 4)];
                area.draw(&PathElement::new(ends, ROADMAP.mix(0.5).stroke_width(1)))?;
                for end in ends {
                    area.draw(&Circle::new(end, 2, ROADMAP.filled()))?;
                }
            }
            Mark::Start => area.draw(&Circle::new((x + 14, y), START_RADIUS, BLACK.filled()))?,
            Mark::Goal => area.draw(&Rectangle::new(square(GOAL_HALF), GOAL.filled()))?,
            Mark::Cross(style) => area.draw(&Cross::new((x + 14, y), 6, *style))?,
            Mark::Links(styles) => {
                let n = styles.len().max(2) - 1;
                for (k, style) in styles.iter().enumerate() {
                    // Slanted links of radius 3, spread over the mark's width.
                    let cx = if styles.len() == 1 {
                        14.0
                    } else {
                        5.0 + 18.0 * k as f64 / n as f64
                    };
                    let outline = capsule_outline(
                        (x as f64 + cx - 3.0, y as f64 + 6.0),
                        (x as f64 + cx + 3.0, y as f64 - 6.0),
                        3.0,
                    );
                    let points: Vec<(i32, i32)> = outline
                        .iter()
                        .map(|&(px, py)| (px.round() as i32, py.round() as i32))
                        .collect();
                    area.draw(&PathElement::new(points, *style))?;
                }
            }
        }
        Ok(())
    }
}

/// Where the entries of a legend go in a strip `width` pixels wide: the left end and the
/// middle line of each, row after row; and the strip's height.
fn legend_layout(width: i32, legend: &[Entry]) -> (Vec<(i32, i32)>, u32) {
    let (left, right) = (16, width - 16);
    let (mut x, mut row) = (left, 0);
    let mut places = Vec::with_capacity(legend.len());
    for (_, label) in legend {
        let entry = MARK_WIDTH + 6 + LEGEND_CHAR * label.chars().count() as i32;
        if x > left && x + entry > right {
            (x, row) = (left, row + 1);
        }
        places.push((x, 4 + LEGEND_ROW * row + LEGEND_ROW / 2));
        x += entry + 24;
    }
    let rows = if legend.is_empty() { 0 } else { row + 1 };
    (places, (8 + LEGEND_ROW * rows) as u32)
}

/// An SVG picture of `body` pixels for the charts, under a strip with the title and a strip
/// with the legend, so that neither covers any data; the root (to present) and the body.
fn picture<'f>(
    file: &'f Path,
    body: (u32, u32),
    title: &str,
    legend: &[Entry],
) -> Result<(Area<'f>, Area<'f>), Box<dyn Error>> {
    let (places, legend_height) = legend_layout(body.0 as i32, legend);
    let root =
        SVGBackend::new(file, (body.0, TITLE_HEIGHT + legend_height + body.1)).into_drawing_area();
    root.fill(&WHITE)?;
    let (title_strip, rest) = root.split_vertically(TITLE_HEIGHT);
    title_strip.draw(&Text::new(
        title,
        (body.0 as i32 / 2, TITLE_HEIGHT as i32 / 2),
        ("sans-serif", TITLE_FONT)
            .into_font()
            .into_text_style(&title_strip)
            .pos(Pos::new(HPos::Center, VPos::Center)),
    ))?;
    let (legend_strip, body) = rest.split_vertically(legend_height);
    let font = ("sans-serif", LEGEND_FONT)
        .into_font()
        .into_text_style(&legend_strip)
        .pos(Pos::new(HPos::Left, VPos::Center));
    for ((mark, label), &(x, y)) in legend.iter().zip(&places) {
        mark.draw(&legend_strip, x, y)?;
        legend_strip.draw(&Text::new(
            label.as_str(),
            (x + MARK_WIDTH + 6, y),
            font.clone(),
        ))?;
    }
    Ok((root, body))
}

/// The outline of a capsule around `a`–`b` in the x-y plane.
fn capsule_outline(a: (f64, f64), b: (f64, f64), r: f64) -> Vec<(f64, f64)> {
    let heading = (b.1 - a.1).atan2(b.0 - a.0);
    let arc = |c: (f64, f64), from: f64| {
        (0..=16).map(move |k| {
            let t = from + std::f64::consts::PI * k as f64 / 16.0;
            (c.0 + r * t.cos(), c.1 + r * t.sin())
        })
    };
    let half = std::f64::consts::FRAC_PI_2;
    let mut outline: Vec<(f64, f64)> = arc(b, heading - half)
        .chain(arc(a, heading + half))
        .collect();
    // Closed, so that it also draws as a path.
    outline.push(outline[0]);
    outline
}

/// The colour of the arm at pose `k` of `count`: the start black, the goal dark blue, the
/// poses between from light to dark red.
fn pose_color(k: usize, count: usize) -> RGBAColor {
    if k == 0 {
        BLACK.mix(0.9)
    } else if k + 1 == count {
        GOAL.mix(0.9)
    } else {
        along_path(k as f64 / count as f64)
    }
}

/// The colour of the arm at the fraction `f` of the way along the path.
fn along_path(f: f64) -> RGBAColor {
    PRM_PATH.mix(0.15 + 0.6 * f)
}

/// The legend of a picture of the arm along a path among obstacles filled with `obstacle`.
fn arm_legend(obstacle: ShapeStyle) -> Vec<Entry> {
    let links =
        |colors: &[RGBAColor]| Mark::Links(colors.iter().map(|c| c.stroke_width(1)).collect());
    vec![
        (links(&[BLACK.mix(0.9)]), "arm at the start".to_string()),
        (
            links(&[along_path(0.2), along_path(0.5), along_path(0.8)]),
            "arm along the PRM path (smoothed), light to dark".to_string(),
        ),
        (links(&[GOAL.mix(0.9)]), "arm at the goal".to_string()),
        (Mark::Area(obstacle), "obstacles".to_string()),
    ]
}

/// The outlines of the links along the path, from the start to the goal (see [`pose_color`]).
fn draw_poses<F: Fn(&LinkCapsule) -> ((f64, f64), (f64, f64))>(
    chart: &mut ChartContext<'_, SVGBackend<'_>, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    poses: &[Vec<LinkCapsule>],
    project: F,
) -> Result<(), Box<dyn Error>> {
    for (k, pose) in poses.iter().enumerate() {
        let color = pose_color(k, poses.len());
        for c in pose {
            let (a, b) = project(c);
            chart.draw_series([PathElement::new(
                capsule_outline(a, b, c.radius),
                color.stroke_width(1),
            )])?;
        }
    }
    Ok(())
}

fn draw_workspace(
    file: &Path,
    scene: &PlanarScene,
    poses: &[Vec<LinkCapsule>],
) -> Result<(), Box<dyn Error>> {
    let obstacle = OBSTACLE.mix(0.6).filled();
    let (root, body) = picture(
        file,
        (800, 800),
        &format!("{}: workspace, PRM path", scene.title),
        &arm_legend(obstacle),
    )?;
    // Label areas of equal size make the plotting area square, so that circles stay round.
    let mut chart = ChartBuilder::on(&body)
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(45)
        .build_cartesian_2d(-2.0..2.0, -2.0..2.0)?;
    chart
        .configure_mesh()
        .x_desc("x (m)")
        .y_desc("y (m)")
        .light_line_style(WHITE)
        .draw()?;
    for o in &scene.obstacles {
        let outline = match o {
            Obstacle::Sphere { center, radius } => {
                capsule_outline((center[0], center[1]), (center[0], center[1]), *radius)
            }
            Obstacle::Box { pose, half_extents } => {
                let c = pose.translation.vector;
                let [hx, hy, _] = *half_extents;
                [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                    .iter()
                    .map(|(sx, sy)| {
                        let p = pose.rotation * Vector3::new(sx * hx, sy * hy, 0.0);
                        (c[0] + p[0], c[1] + p[1])
                    })
                    .collect()
            }
            Obstacle::Capsule { a, b, radius } => {
                capsule_outline((a[0], a[1]), (b[0], b[1]), *radius)
            }
        };
        chart.draw_series([Polygon::new(outline, obstacle)])?;
    }
    draw_poses(&mut chart, poses, |c| ((c.a.x, c.a.y), (c.b.x, c.b.y)))?;
    root.present()?;
    println!("wrote {}", file.display());
    Ok(())
}

fn puma560(dir: &Path) -> Result<(), Box<dyn Error>> {
    let scene = Scene::new(scenes::puma_obstacles())?;
    let mut checker = CollisionChecker::new(&puma::Robot, scene)?;
    let (start, goal) = (Q6::from(scenes::PUMA_START), Q6::from(scenes::PUMA_GOAL));
    let mut prm = Prm::new(&mut checker, scenes::puma_config(), 1)?;
    let path = prm.query(&start, &goal)?;
    let s = path.stats;
    println!(
        "puma560: PRM {} nodes ({} samples, {} rejected), {} edges ({} local-planner calls), \
         {} components, {} enhancement rounds, {} collision checks in {:.1?} ({:.0} checks/s)",
        s.nodes,
        s.samples,
        s.rejected_samples,
        s.edges,
        s.edge_attempts,
        s.components,
        s.enhancement_rounds,
        s.collision_checks,
        s.time,
        s.collision_checks as f64 / s.time.as_secs_f64()
    );
    println!(
        "puma560: path of {} waypoints, length {:.3} rad (roadmap path {:.3}, {} shortcuts)",
        path.waypoints.len(),
        path.length,
        path.roadmap_length,
        path.shortcuts
    );
    for q in &path.waypoints {
        println!(
            "  q = {:?}",
            q.as_slice()
                .iter()
                .map(|x| (x * 1e3).round() / 1e3)
                .collect::<Vec<_>>()
        );
    }
    drop(prm);
    let poses: Vec<Vec<LinkCapsule>> = resample(&path.waypoints, 0.25)
        .iter()
        .map(|q| checker.capsules(q))
        .collect();
    draw_side(&dir.join("puma_views.svg"), checker.scene(), &poses)?;
    Ok(())
}

fn draw_side(file: &Path, scene: &Scene, poses: &[Vec<LinkCapsule>]) -> Result<(), Box<dyn Error>> {
    let obstacle = OBSTACLE.mix(0.5).filled();
    let (root, body) = picture(
        file,
        (1000, 480),
        "PUMA 560 among a table, a panel and a ball: PRM path",
        &arm_legend(obstacle),
    )?;
    let areas = body.split_evenly((1, 2));
    for (area, (name, axis)) in areas
        .iter()
        .zip([("x-z, from the side", 0usize), ("x-y, from above", 1)])
    {
        let area = area.titled(name, ("sans-serif", 16))?;
        let mut builder = ChartBuilder::on(&area);
        builder
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(40);
        // The same scale on both axes, so that circles stay round: x over 2 m, and y over
        // what the plotting area's height gives at that scale, centred as before. (The
        // plotting area's size does not depend on the ranges.)
        let (w, h) = builder
            .build_cartesian_2d(0.0..1.0, 0.0..1.0)?
            .plotting_area()
            .dim_in_pixel();
        let (x, y_mid) = (-0.9..1.1, if axis == 0 { 0.8 } else { 0.0 });
        let half = 0.5 * h as f64 * (x.end - x.start) / w as f64;
        let mut chart = builder.build_cartesian_2d(x, y_mid - half..y_mid + half)?;
        chart
            .configure_mesh()
            .x_desc("x (m)")
            .y_desc(if axis == 0 { "z (m)" } else { "y (m)" })
            .light_line_style(WHITE)
            .draw()?;
        let project = |p: &dhgen::nalgebra::Point3<f64>| {
            if axis == 0 { (p.x, p.z) } else { (p.x, p.y) }
        };
        for o in scene.obstacles() {
            let outline = match o {
                Obstacle::Sphere { center, radius } => {
                    let c = dhgen::nalgebra::Point3::from(*center);
                    capsule_outline(project(&c), project(&c), *radius)
                }
                Obstacle::Box { pose, half_extents } => {
                    let c = dhgen::nalgebra::Point3::from(pose.translation.vector);
                    let (cx, cy) = project(&c);
                    let (hx, hy) = if axis == 0 {
                        (half_extents[0], half_extents[2])
                    } else {
                        (half_extents[0], half_extents[1])
                    };
                    vec![
                        (cx - hx, cy - hy),
                        (cx + hx, cy - hy),
                        (cx + hx, cy + hy),
                        (cx - hx, cy + hy),
                    ]
                }
                Obstacle::Capsule { a, b, radius } => {
                    let (a, b) = (
                        dhgen::nalgebra::Point3::from(*a),
                        dhgen::nalgebra::Point3::from(*b),
                    );
                    capsule_outline(project(&a), project(&b), *radius)
                }
            };
            chart.draw_series([Polygon::new(outline, obstacle)])?;
        }
        draw_poses(&mut chart, poses, |c| (project(&c.a), project(&c.b)))?;
    }
    root.present()?;
    println!("wrote {}", file.display());
    Ok(())
}
