//! Scenes and budgets shared by the planning tests (`tests/integration/planning_*.rs`), the
//! example (`examples/planning.rs`) and the benchmark (`benches/planning.rs`).

use dhgen::model::RobotModel;
use dhgen::planning::{Obstacle, PrmConfig};
use std::f64::consts::{FRAC_PI_2, PI};
use std::path::Path;

/// A description from `robots/`.
pub fn model(file: &str) -> RobotModel {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("robots")
        .join(file);
    RobotModel::from_toml_file(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// A planar scene for the 2-link arm of `robots/planar_elbow.toml`.
pub struct PlanarScene {
    /// File-name stem of its pictures.
    pub name: &'static str,
    /// Caption of its pictures.
    pub title: &'static str,
    /// Obstacles, in the plane z = 0 of the arm.
    pub obstacles: Vec<Obstacle>,
    /// Start configuration.
    pub start: [f64; 2],
    /// Goal configuration.
    pub goal: [f64; 2],
}

/// Like Figure 3 of the text: a sphere, a box and a capsule, all beyond the reach of link 1
/// (1 m plus its radius), so that only link 2 can hit them and QO is a few islands.
pub fn figure3() -> PlanarScene {
    PlanarScene {
        name: "planar",
        title: "Planar 2-link arm among a sphere, a box and a capsule",
        obstacles: vec![
            Obstacle::sphere([1.1, 0.8, 0.0], 0.2),
            Obstacle::cuboid([-1.3, 0.3, 0.0], [0.15, 0.25, 0.2]),
            Obstacle::capsule([0.2, -1.5, 0.0], [1.0, -1.2, 0.0], 0.1),
        ],
        start: [-0.4, 1.2],
        goal: [2.4, -0.9],
    }
}

/// A narrow passage: a ring of twelve capsules (radius 0.1) at 1.5 m around the robot with a
/// door 0.35 m wide (between the capsules' surfaces) on the +y axis. Link 2 cannot point
/// outwards (|q2| < 1.46) except through the door, and the joint ranges end at ±π, so
/// turning the elbow from one side (q2 > 0) to the other must pass through a corridor of
/// the configuration space about 0.1 rad wide.
pub fn narrow_passage() -> PlanarScene {
    let radius = 1.5;
    let half_door = (0.275f64 / radius).asin();
    let (first, last) = (FRAC_PI_2 + half_door, FRAC_PI_2 + 2.0 * PI - half_door);
    let pieces = 12;
    let angle = |k: usize| first + (last - first) * k as f64 / pieces as f64;
    PlanarScene {
        name: "narrow",
        title: "Narrow passage: link 2 must pass the door in a ring",
        obstacles: (0..pieces)
            .map(|k| {
                let (a, b) = (angle(k), angle(k + 1));
                Obstacle::capsule(
                    [radius * a.cos(), radius * a.sin(), 0.0],
                    [radius * b.cos(), radius * b.sin(), 0.0],
                    0.1,
                )
            })
            .collect(),
        start: [0.0, 2.2],
        goal: [0.0, -2.2],
    }
}

/// The roadmap budget of the narrow-passage scene: at most 1500 nodes, local planner at
/// 0.02 rad.
pub fn narrow_config() -> PrmConfig {
    PrmConfig {
        initial_nodes: 100,
        max_nodes: 1500,
        resolution: 0.02,
        ..PrmConfig::default()
    }
}

/// The PUMA 560 scene: a table in front of the robot, a tall panel on its left that the
/// straight joint-space motion from start to goal runs into, and a ball over the table.
pub fn puma_obstacles() -> Vec<Obstacle> {
    vec![
        Obstacle::cuboid([0.65, 0.0, 0.30], [0.30, 0.60, 0.03]),
        Obstacle::cuboid([0.5, 0.45, 0.95], [0.45, 0.03, 0.5]),
        Obstacle::sphere([0.55, -0.35, 0.6], 0.1),
    ]
}

/// Start: the wrist above the table, front right. Goal: the wrist low behind the panel, to
/// the left (joint 1 turns by 2.5 rad).
pub const PUMA_START: [f64; 6] = [-0.3, 0.6, -2.0, 0.0, 0.5, 0.0];
/// See [`PUMA_START`].
pub const PUMA_GOAL: [f64; 6] = [2.2, 0.3, -2.6, 0.0, 0.5, 0.0];

/// The roadmap budget of the PUMA 560 scene: at most 600 nodes, local planner at 0.02 rad.
pub fn puma_config() -> PrmConfig {
    PrmConfig {
        initial_nodes: 30,
        max_nodes: 600,
        resolution: 0.02,
        ..PrmConfig::default()
    }
}
