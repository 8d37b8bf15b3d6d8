//! Path planning (sections 6.1 to 6.4 of the reference text) on two robots.
//!
//! ```text
//! cargo run --release --example planning [output-directory]
//! ```
//!
//! A planar 2-link arm (`robots/planar_elbow.toml`, links as capsules of radius 5 cm) among
//! a sphere, a box and a capsule, like Figure 3 of the text. Writes into
//! `target/plots/` of the package unless a directory is given:
//! - `planar_cspace.svg`: the configuration-space obstacle region QO on a grid over (q1, q2),
//!   the roadmap, the PRM path, and the paths of the C-space and workspace potential fields
//!   (a cross where a field got stuck in a local minimum instead);
//! - `planar_workspace.svg`: the obstacles and the arm along the PRM path;
//! - `narrow_cspace.svg`, `narrow_workspace.svg`: the same for a scene whose free space has a
//!   narrow passage (a ring of capsules around the arm with a door that link 2 must pass
//!   through to turn the elbow over).
//!
//! Then a PUMA 560 among a table, a panel and a ball, solved by PRM; prints the roadmap's
//! statistics and the path, and writes `puma_views.svg` (the arm along the path, from the
//! side and from above).
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
use plotters::prelude::*;

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
                &grid,
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
        &grid,
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

fn draw_cspace(
    file: &Path,
    scene: &PlanarScene,
    grid: &CSpaceGrid,
    nodes: &[Q2],
    edges: &[(usize, usize)],
    paths: &[Series<'_>],
) -> Result<(), Box<dyn Error>> {
    let [[x0, x1], [y0, y1]] = grid.bounds();
    let root = SVGBackend::new(file, (900, 900)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("{}: configuration space", scene.title),
            ("sans-serif", 20),
        )
        .margin(15)
        .x_label_area_size(40)
        .y_label_area_size(50)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc("q1 (rad)")
        .y_desc("q2 (rad)")
        .disable_mesh()
        .draw()?;
    // QO: runs of occupied cells along q2, one rectangle each.
    let [ni, nj] = grid.cells();
    let [dx, dy] = grid.cell_size();
    let mut runs = Vec::new();
    for i in 0..ni {
        let mut j = 0;
        while j < nj {
            if grid.is_occupied(i, j) {
                let start = j;
                while j < nj && grid.is_occupied(i, j) {
                    j += 1;
                }
                let xa = x0 + i as f64 * dx;
                runs.push([(xa, y0 + start as f64 * dy), (xa + dx, y0 + j as f64 * dy)]);
            } else {
                j += 1;
            }
        }
    }
    chart
        .draw_series(
            runs.into_iter()
                .map(|r| Rectangle::new(r, OBSTACLE.mix(0.45).filled())),
        )?
        .label("QO (arm in collision)")
        .legend(|(x, y)| {
            Rectangle::new([(x, y - 5), (x + 12, y + 5)], OBSTACLE.mix(0.45).filled())
        });
    chart
        .draw_series(edges.iter().map(|&(a, b)| {
            PathElement::new(
                vec![(nodes[a][0], nodes[a][1]), (nodes[b][0], nodes[b][1])],
                ROADMAP.mix(0.5).stroke_width(1),
            )
        }))?
        .label("roadmap")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 12, y)], ROADMAP.stroke_width(2)));
    chart.draw_series(
        nodes
            .iter()
            .map(|q| Circle::new((q[0], q[1]), 2, ROADMAP.filled())),
    )?;
    for (path, color, label) in paths {
        if path.is_empty() {
            continue;
        }
        if let [q] = path {
            chart
                .draw_series([Cross::new((q[0], q[1]), 9, color.stroke_width(4))])?
                .label(format!("{label}: stuck in a local minimum"))
                .legend(move |(x, y)| Cross::new((x + 6, y), 5, color.stroke_width(3)));
            continue;
        }
        chart
            .draw_series(LineSeries::new(
                path.iter().map(|q| (q[0], q[1])),
                color.stroke_width(3),
            ))?
            .label(*label)
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 12, y)], color.stroke_width(3))
            });
    }
    for (q, label) in [(scene.start, "start"), (scene.goal, "goal")] {
        chart.draw_series([Circle::new((q[0], q[1]), 7, BLACK.filled())])?;
        chart.draw_series([Text::new(
            label,
            (q[0] + 0.08, q[1] + 0.08),
            ("sans-serif", 18).into_font(),
        )])?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 15))
        .draw()?;
    root.present()?;
    println!("wrote {}", file.display());
    Ok(())
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
        RGBColor(20, 40, 160).mix(0.9)
    } else {
        PRM_PATH.mix(0.15 + 0.6 * k as f64 / count as f64)
    }
}

fn draw_workspace(
    file: &Path,
    scene: &PlanarScene,
    poses: &[Vec<LinkCapsule>],
) -> Result<(), Box<dyn Error>> {
    let root = SVGBackend::new(file, (800, 800)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            format!("{}: workspace, PRM path", scene.title),
            ("sans-serif", 18),
        )
        .margin(15)
        .x_label_area_size(35)
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
        chart.draw_series([Polygon::new(outline, OBSTACLE.mix(0.6).filled())])?;
    }
    for (k, pose) in poses.iter().enumerate() {
        let color = pose_color(k, poses.len());
        for c in pose {
            chart.draw_series([PathElement::new(
                capsule_outline((c.a.x, c.a.y), (c.b.x, c.b.y), c.radius),
                color.stroke_width(1),
            )])?;
        }
    }
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
    // 220 pixels per metre on both axes of both views, so that circles stay round.
    let root = SVGBackend::new(file, (1000, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let areas = root.split_evenly((1, 2));
    for (area, (name, axis)) in areas
        .iter()
        .zip([("x-z, from the side", 0usize), ("x-y, from above", 1)])
    {
        let mut chart = ChartBuilder::on(area)
            .caption(format!("PUMA 560, PRM path: {name}"), ("sans-serif", 16))
            .margin(10)
            .x_label_area_size(30)
            .y_label_area_size(40)
            .build_cartesian_2d(-0.9..1.1, if axis == 0 { -0.1..1.7 } else { -0.9..0.9 })?;
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
            chart.draw_series([Polygon::new(outline, OBSTACLE.mix(0.5).filled())])?;
        }
        for (k, pose) in poses.iter().enumerate() {
            let color = pose_color(k, poses.len());
            for c in pose {
                chart.draw_series([PathElement::new(
                    capsule_outline(project(&c.a), project(&c.b), c.radius),
                    color.stroke_width(1),
                )])?;
            }
        }
    }
    root.present()?;
    println!("wrote {}", file.display());
    Ok(())
}
