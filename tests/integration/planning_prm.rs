//! The probabilistic roadmap (6.4): success rates over 100 seeds on a narrow passage and on a
//! PUMA 560 scene within a stated budget, every path re-checked at ten times the resolution,
//! reproducibility, and the failures it reports.
//!
//! Budgets (see `tests/integration/planning_support.rs`): the narrow passage at most 1500 nodes, the
//! PUMA 560 at most 600 nodes; both at a local-planner resolution of 0.02 rad, and at most
//! 30 s per query (a debug build needs well under a second for most seeds). Run with
//! `--nocapture` to see the success rates and timings.

use std::time::{Duration, Instant};

use crate::catalogue::{planar_elbow as planar, puma560 as puma};
use crate::planning_support::{
    PUMA_GOAL, PUMA_START, model, narrow_config, narrow_passage, puma_config, puma_obstacles,
};
use dhgen::nalgebra::DefaultAllocator;
use dhgen::nalgebra::{DVector, SVector};
use dhgen::planning::{
    CollisionChecker, Obstacle, PlanError, Prm, PrmConfig, PrmPath, Scene, prm::KD_TREE_DOF,
};
use dhgen::{Arm, ArmAllocator, JointVector, Robot};

const SEEDS: u64 = 100;
const TIME_BUDGET: Duration = Duration::from_secs(30);

/// What one seed gave.
struct Outcome {
    solved: bool,
    time: Duration,
    nodes: usize,
}

/// Plans with every seed, on two threads (the machine's two cores), checking each path:
/// it joins start and goal, every segment passes the local planner, and re-checked at
/// `resolution / 10` with no margin at all, no configuration touches an obstacle.
fn run_seeds<A: Arm + Sync>(
    arm: &A,
    obstacles: fn() -> Vec<Obstacle>,
    config: &PrmConfig,
    start: &JointVector<A>,
    goal: &JointVector<A>,
) -> Vec<Outcome>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
    JointVector<A>: Sync,
{
    let config = PrmConfig {
        time_budget: Some(TIME_BUDGET),
        ..config.clone()
    };
    let run = |seeds: std::ops::Range<u64>| {
        seeds
            .map(|seed| {
                let scene = Scene::new(obstacles()).unwrap();
                let mut checker = CollisionChecker::new(arm, scene).unwrap();
                let started = Instant::now();
                let found = Prm::new(&mut checker, config.clone(), seed)
                    .unwrap()
                    .query(start, goal);
                let time = started.elapsed();
                match found {
                    Ok(path) => {
                        check_path(&mut checker, &path, start, goal, config.resolution);
                        Outcome {
                            solved: true,
                            time,
                            nodes: path.stats.nodes,
                        }
                    }
                    Err(PlanError::NoPath { nodes, .. }) => Outcome {
                        solved: false,
                        time,
                        nodes,
                    },
                    Err(e) => panic!("seed {seed}: {e}"),
                }
            })
            .collect::<Vec<_>>()
    };
    std::thread::scope(|s| {
        let half = s.spawn(|| run(0..SEEDS / 2));
        let mut outcomes = run(SEEDS / 2..SEEDS);
        let mut first = half.join().unwrap();
        first.append(&mut outcomes);
        first
    })
}

fn check_path<A: Arm>(
    checker: &mut CollisionChecker<'_, A>,
    path: &PrmPath<JointVector<A>>,
    start: &JointVector<A>,
    goal: &JointVector<A>,
    resolution: f64,
) where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    assert_eq!(&path.waypoints[0], start);
    assert_eq!(path.waypoints.last().unwrap(), goal);
    assert!(checker.path_is_free(&path.waypoints, resolution));
    assert!(checker.path_touches_nothing(&path.waypoints, resolution / 10.0));
    assert!(path.length <= path.roadmap_length + 1e-9);
}

/// Prints and checks the success rate and the time budget.
fn summarize(name: &str, outcomes: &[Outcome]) {
    let solved = outcomes.iter().filter(|o| o.solved).count();
    let mut times: Vec<f64> = outcomes.iter().map(|o| o.time.as_secs_f64()).collect();
    times.sort_by(f64::total_cmp);
    let mut nodes: Vec<usize> = outcomes
        .iter()
        .filter(|o| o.solved)
        .map(|o| o.nodes)
        .collect();
    nodes.sort_unstable();
    println!(
        "{name}: solved {solved} of {}; time per query median {:.3} s, max {:.3} s; \
         nodes when solved median {}, max {}",
        outcomes.len(),
        times[times.len() / 2],
        times[times.len() - 1],
        nodes.get(nodes.len() / 2).copied().unwrap_or(0),
        nodes.last().copied().unwrap_or(0)
    );
    assert!(
        solved * 100 >= 95 * outcomes.len(),
        "{name}: only {solved} solved"
    );
    assert!(
        times[times.len() - 1] <= TIME_BUDGET.as_secs_f64() + 1.0,
        "{name}: over the time budget"
    );
}

#[test]
fn narrow_passage_is_solved_for_95_of_100_seeds() {
    let scene = narrow_passage();
    let (start, goal) = (SVector::from(scene.start), SVector::from(scene.goal));
    let outcomes = run_seeds(
        &planar::Robot,
        || narrow_passage().obstacles,
        &narrow_config(),
        &start,
        &goal,
    );
    summarize("narrow passage (planar 2-link)", &outcomes);
}

#[test]
fn puma560_scene_is_solved_for_95_of_100_seeds() {
    let (start, goal) = (SVector::from(PUMA_START), SVector::from(PUMA_GOAL));
    // The direct motion is blocked: the roadmap is needed.
    let mut checker =
        CollisionChecker::new(&puma::Robot, Scene::new(puma_obstacles()).unwrap()).unwrap();
    assert!(!checker.motion_is_free(&start, &goal, puma_config().resolution));
    let outcomes = run_seeds(&puma::Robot, puma_obstacles, &puma_config(), &start, &goal);
    summarize("PUMA 560 scene", &outcomes);
}

fn narrow_checker<A: Arm>(arm: &A) -> CollisionChecker<'_, A>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    CollisionChecker::new(arm, Scene::new(narrow_passage().obstacles).unwrap()).unwrap()
}

#[test]
fn a_seed_fixes_the_roadmap_and_the_path() {
    let scene = narrow_passage();
    let (start, goal) = (SVector::from(scene.start), SVector::from(scene.goal));
    let plan = |seed| {
        let mut checker = narrow_checker(&planar::Robot);
        let mut prm = Prm::new(&mut checker, narrow_config(), seed).unwrap();
        let path = prm.query(&start, &goal).unwrap();
        let edges: Vec<(usize, usize)> = prm.edges().collect();
        (prm.nodes().to_vec(), edges, path)
    };
    let (nodes_a, edges_a, path_a) = plan(3);
    let (nodes_b, edges_b, path_b) = plan(3);
    assert_eq!(nodes_a, nodes_b);
    assert_eq!(edges_a, edges_b);
    assert_eq!(path_a.waypoints, path_b.waypoints);
    assert_eq!(path_a.stats.collision_checks, path_b.stats.collision_checks);
    let (nodes_c, _, path_c) = plan(4);
    assert_ne!(nodes_a, nodes_c);
    assert_ne!(path_a.waypoints, path_c.waypoints);

    // The runtime robot draws the same samples and makes the same decisions.
    let robot = Robot::from_model(model("planar_elbow.toml"));
    let mut checker = narrow_checker(&robot);
    let mut prm = Prm::new(&mut checker, narrow_config(), 3).unwrap();
    let path = prm
        .query(
            &DVector::from_column_slice(&scene.start),
            &DVector::from_column_slice(&scene.goal),
        )
        .unwrap();
    assert_eq!(prm.nodes().len(), nodes_a.len());
    assert_eq!(path.waypoints.len(), path_a.waypoints.len());
    for (a, b) in path.waypoints.iter().zip(&path_a.waypoints) {
        assert!((a - DVector::from_column_slice(b.as_slice())).norm() < 1e-9);
    }
}

#[test]
fn every_roadmap_edge_is_free() {
    let scene = narrow_passage();
    let mut checker = narrow_checker(&planar::Robot);
    let config = narrow_config();
    let mut prm = Prm::new(&mut checker, config.clone(), 9).unwrap();
    prm.query(&SVector::from(scene.start), &SVector::from(scene.goal))
        .unwrap();
    let stats = prm.stats();
    let nodes = prm.nodes().to_vec();
    let edges: Vec<(usize, usize)> = prm.edges().collect();
    assert_eq!(stats.nodes, nodes.len());
    assert_eq!(stats.edges, edges.len());
    let mut labels = prm.component_labels();
    labels.sort_unstable();
    labels.dedup();
    assert_eq!(stats.components, labels.len());
    assert!(stats.samples >= stats.nodes - 2 && stats.rejected_samples < stats.samples);
    for (a, b) in edges {
        assert!(
            checker.path_touches_nothing(&[nodes[a], nodes[b]], config.resolution / 10.0),
            "edge {a}-{b}"
        );
    }
}

#[test]
fn an_unreachable_goal_is_reported() {
    // Two balls within reach of link 1 block q1 = ±π/2 whatever q2 is: the configuration
    // space falls apart into q1 ∈ (−π/2, π/2) and the rest.
    let scene = Scene::new(vec![
        Obstacle::sphere([0.0, 0.7, 0.0], 0.15),
        Obstacle::sphere([0.0, -0.7, 0.0], 0.15),
    ])
    .unwrap();
    let mut checker = CollisionChecker::new(&planar::Robot, scene).unwrap();
    let config = PrmConfig {
        max_nodes: 300,
        ..narrow_config()
    };
    let mut prm = Prm::new(&mut checker, config, 1).unwrap();
    let err = prm
        .query(&SVector::from([0.0, 0.5]), &SVector::from([3.0, 0.5]))
        .unwrap_err();
    match &err {
        PlanError::NoPath {
            nodes, components, ..
        } => {
            assert_eq!(*nodes, 300);
            assert!(*components >= 2);
        }
        other => panic!("expected no path, got {other}"),
    }
    assert!(
        err.to_string().contains("node budget of 300 reached"),
        "{err}"
    );
}

#[test]
fn samples_piling_up_at_a_joint_limit_are_planned_around() {
    // One joint limited to ±0.5 rad, its link blocked at q = 0: the roadmap cannot join the
    // two sides, and asking for many nodes near each sparse one clamps hundreds of samples
    // to exactly ±0.5. The kd-tree holds at most 32 items at one point: the 33rd panicked.
    let robot = Robot::from_toml_str(
        "name = \"one\"\nconvention = \"standard\"\n[[links]]\njoint = \"revolute\"\n\
         a = 1.0\nalpha = 0\nd = 0\ntheta = 0\nlimits = [-0.5, 0.5]\n\
         collision = { radius = 0.05 }\n",
    )
    .unwrap();
    let scene = Scene::new(vec![Obstacle::sphere([1.0, 0.0, 0.0], 0.02)]).unwrap();
    let mut checker = CollisionChecker::new(&robot, scene).unwrap();
    let config = PrmConfig {
        few_neighbours: 1000,
        ..PrmConfig::default()
    };
    let err = Prm::new(&mut checker, config, 3)
        .unwrap()
        .query(
            &DVector::from_vec(vec![-0.45]),
            &DVector::from_vec(vec![0.45]),
        )
        .unwrap_err();
    assert!(matches!(err, PlanError::NoPath { .. }), "{err}");
    // As many neighbours as a usize holds: all the nodes there are (`neighbours + 1`
    // overflowed).
    let config = PrmConfig {
        neighbours: usize::MAX,
        ..PrmConfig::default()
    };
    let path = Prm::new(&mut checker, config, 1)
        .unwrap()
        .query(
            &DVector::from_vec(vec![0.1]),
            &DVector::from_vec(vec![0.45]),
        )
        .unwrap();
    assert!(path.waypoints.len() >= 2);
}

#[test]
fn bad_queries_are_errors() {
    let mut checker = narrow_checker(&planar::Robot);
    let mut prm = Prm::new(&mut checker, narrow_config(), 0).unwrap();
    // Link 2 pointing outwards hits the ring.
    let err = prm
        .query(&SVector::from([0.0, 0.0]), &SVector::from([0.0, 2.2]))
        .unwrap_err();
    assert!(
        matches!(err, PlanError::InvalidConfiguration { which: "start", .. }),
        "{err}"
    );
    let err = prm
        .query(&SVector::from([0.0, 2.2]), &SVector::from([0.0, 3.5]))
        .unwrap_err();
    assert!(
        err.to_string()
            .contains("joint 2 = 3.5 is outside its range"),
        "{err}"
    );
    drop(prm);
    let config = PrmConfig {
        resolution: 0.0,
        ..narrow_config()
    };
    let err = Prm::new(&mut checker, config, 0).err().unwrap();
    assert!(
        matches!(
            err,
            PlanError::InvalidParameter {
                name: "resolution",
                ..
            }
        ),
        "{err}"
    );
}

/// More joints than the roadmap's kd-trees have (`KD_TREE_DOF`): the roadmap scans its
/// nodes instead, and plans as well. A planar snake of 12 links, 1.2 m long, swings from
/// lying along x to pointing up (q1 = 1.3) past a sphere its straight-line motion would
/// sweep through; every seed finds a path, re-checked ten times finer.
#[test]
fn a_twelve_joint_snake_is_planned_around_an_obstacle() {
    // More joints than any kd-tree: the roadmap scans.
    const { assert!(12 > KD_TREE_DOF) };
    let link = "[[links]]\njoint = \"revolute\"\na = 0.1\nalpha = 0\nd = 0\ntheta = 0\n\
                limits = [-2.5, 2.5]\ncollision = { radius = 0.01 }\n";
    let text = format!(
        "name = \"snake\"\nconvention = \"standard\"\n{}",
        link.repeat(12)
    );
    let snake = Robot::from_toml_str(&text).unwrap();
    let start = DVector::zeros(12);
    let mut goal = DVector::zeros(12);
    goal[0] = 1.3;
    let config = PrmConfig {
        time_budget: Some(TIME_BUDGET),
        ..PrmConfig::default()
    };
    for seed in 0..4 {
        let scene = Scene::new(vec![Obstacle::sphere([0.6, 0.35, 0.0], 0.12)]).unwrap();
        let mut checker = CollisionChecker::new(&snake, scene).unwrap();
        assert!(!checker.motion_is_free(&start, &goal, config.resolution));
        let path = Prm::new(&mut checker, config.clone(), seed)
            .unwrap()
            .query(&start, &goal)
            .unwrap_or_else(|e| panic!("seed {seed}: {e}"));
        check_path(&mut checker, &path, &start, &goal, config.resolution);
    }
}
