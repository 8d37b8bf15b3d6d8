//! The configuration-space potential field (6.2) and gradient descent (6.2.3): the forces
//! are the gradients of the potentials, the planner reaches the goal with no obstacles and
//! around a simple one, and reports a local minimum in a trap instead of failing silently.

use crate::catalogue::planar_elbow as planar;
use crate::planning_support::figure3;
use dhgen::nalgebra::SVector;
use dhgen::planning::potential::{self, ConvexCSpaceObstacles, ConvexRegion};
use dhgen::planning::{CSpaceField, CSpaceGrid, CollisionChecker, DescentParams, PlanError, Scene};

const FIELD: CSpaceField = CSpaceField {
    zeta: 1.0,
    d: 0.5,
    eta: 0.01,
    rho0: 0.3,
};

fn obstacles(regions: Vec<ConvexRegion>) -> ConvexCSpaceObstacles {
    ConvexCSpaceObstacles::new(2, regions).unwrap()
}

fn ball(c: [f64; 2], r: f64) -> ConvexRegion {
    ConvexRegion::Ball {
        center: c.to_vec(),
        radius: r,
    }
}

fn cbox(lower: [f64; 2], upper: [f64; 2]) -> ConvexRegion {
    ConvexRegion::Box {
        lower: lower.to_vec(),
        upper: upper.to_vec(),
    }
}

fn dist(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// The potential and force of the field at `q`, as the planner sees them.
fn potential_and_force(
    field: &CSpaceField,
    obstacles: &mut ConvexCSpaceObstacles,
    q: &[f64],
    goal: &[f64],
) -> (f64, Vec<f64>) {
    use dhgen::planning::CSpaceObstacles;
    let mut force = vec![0.0; q.len()];
    let mut u = field.attractive(q, goal, &mut force);
    obstacles.nearest(q, field.rho0, &mut |rho, b| {
        u += field.repulsive(q, rho, b, &mut force)
    });
    (u, force)
}

#[test]
fn forces_are_minus_the_gradients() {
    let mut obs = obstacles(vec![ball([0.5, 0.1], 0.2), cbox([-0.6, -0.5], [-0.3, 0.4])]);
    let goal = [1.0, -0.2];
    let h = 1e-6;
    let mut checked = [0; 3];
    for i in 0..40 {
        for j in 0..40 {
            // Off the planes of the box's faces, where the distance's second derivative
            // jumps and a central difference straddling them is off by O(h·η/ρ³).
            let q = [-1.0123 + 0.055 * i as f64, -1.0077 + 0.05 * j as f64];
            let (u, f) = potential_and_force(&FIELD, &mut obs, &q, &goal);
            if !u.is_finite() || obs.distance(&q) < 1e-3 {
                continue;
            }
            let rho_goal = ((q[0] - goal[0]).powi(2) + (q[1] - goal[1]).powi(2)).sqrt();
            if (rho_goal - FIELD.d).abs() < 1e-4 {
                continue;
            }
            for k in 0..2 {
                let (mut plus, mut minus) = (q, q);
                plus[k] += h;
                minus[k] -= h;
                let du = (potential_and_force(&FIELD, &mut obs, &plus, &goal).0
                    - potential_and_force(&FIELD, &mut obs, &minus, &goal).0)
                    / (2.0 * h);
                assert!(
                    (f[k] + du).abs() < 1e-5 * (1.0 + du.abs()),
                    "q = {q:?}: F[{k}] = {}, -dU/dq = {}",
                    f[k],
                    -du
                );
            }
            let near = obs.distance(&q) < FIELD.rho0;
            checked[usize::from(rho_goal > FIELD.d) + usize::from(near)] += 1;
        }
    }
    // The quadratic and conic attraction, with and without repulsion, were all checked.
    assert!(checked.iter().all(|&c| c > 20), "{checked:?}");
}

#[test]
fn attraction_is_quadratic_then_conic_and_continuous() {
    let goal = [0.0, 0.0];
    let mut f = [0.0; 2];
    // Quadratic inside d: ½ζρ², force −ζ(q − q_f).
    let u = FIELD.attractive(&[0.3, 0.0], &goal, &mut f);
    assert!((u - 0.5 * 0.09).abs() < 1e-15 && (f[0] + 0.3).abs() < 1e-15);
    // Conic beyond: dζρ − ½ζd², force of constant magnitude dζ.
    let mut f = [0.0; 2];
    let u = FIELD.attractive(&[3.0, 4.0], &goal, &mut f);
    assert!((u - (0.5 * 5.0 - 0.125)).abs() < 1e-12);
    assert!(((f[0] * f[0] + f[1] * f[1]).sqrt() - 0.5).abs() < 1e-12);
    // Continuous at ρ = d, value and force.
    let (mut fa, mut fb) = ([0.0; 2], [0.0; 2]);
    let ua = FIELD.attractive(&[0.5 - 1e-12, 0.0], &goal, &mut fa);
    let ub = FIELD.attractive(&[0.5 + 1e-12, 0.0], &goal, &mut fb);
    assert!((ua - ub).abs() < 1e-11 && (fa[0] - fb[0]).abs() < 1e-11);
}

fn params() -> DescentParams {
    DescentParams {
        step: 0.01,
        tolerance: 0.005,
        ..DescentParams::default()
    }
}

#[test]
fn reaches_the_goal_without_obstacles() {
    let (start, goal) = ([-1.0, 0.5], [1.2, -0.4]);
    let path = potential::plan(&FIELD, obstacles(vec![]), &start, &goal, &params()).unwrap();
    assert!(path.ends_at_goal);
    assert_eq!(path.waypoints.last().unwrap(), &goal.to_vec());
    assert_eq!(path.random_walks, 0);
    // Straight down the attractive field: every step of length α along the line, so the
    // path is as long as the distance (to rounding) and takes ⌈distance/α⌉ steps.
    let distance = dist(&start, &goal);
    let length: f64 = path.waypoints.windows(2).map(|w| dist(&w[0], &w[1])).sum();
    assert!((length - distance).abs() < 1e-9, "{length} vs {distance}");
    assert_eq!(path.waypoints.len() - 1, (distance / 0.01).ceil() as usize);
}

#[test]
fn goes_around_a_simple_obstacle() {
    let mut obs = obstacles(vec![ball([0.0, 0.05], 0.3)]);
    let (start, goal) = ([-1.0, 0.0], [1.0, 0.0]);
    let path = potential::plan(&FIELD, obs.clone(), &start, &goal, &params()).unwrap();
    assert!(path.ends_at_goal);
    assert_eq!(path.waypoints.last().unwrap(), &goal.to_vec());
    // Never inside the obstacle; the path bends around it (below, the obstacle is off
    // centre upwards).
    let mut lowest: f64 = 0.0;
    for w in &path.waypoints {
        assert!(obs.distance(w) > 0.0, "{w:?} is inside the obstacle");
        lowest = lowest.min(w[1]);
    }
    assert!(lowest < -0.25, "did not go around: lowest q2 = {lowest}");
}

#[test]
fn reports_a_local_minimum_in_a_trap() {
    // A cup open towards the start: the attraction pulls into it, the walls repel, and the
    // bottom sits between the descent and the goal.
    let trap = vec![
        cbox([0.0, -0.6], [0.1, 0.6]),
        cbox([-0.6, 0.5], [0.1, 0.6]),
        cbox([-0.6, -0.6], [0.1, -0.5]),
    ];
    let (start, goal) = ([-0.4, 0.0], [1.0, 0.0]);
    let walks = DescentParams {
        random_walks: 3,
        walk_steps: 10,
        walk_step: 0.02,
        ..params()
    };
    let err = potential::plan(&FIELD, obstacles(trap), &start, &goal, &walks).unwrap_err();
    match &err {
        PlanError::LocalMinimum {
            q,
            random_walks,
            distance_to_goal,
            ..
        } => {
            assert_eq!(*random_walks, 3);
            // Stuck inside the cup, in front of its bottom.
            assert!(q[0] < 0.0 && q[0] > -0.5 && q[1].abs() < 0.45, "{q:?}");
            assert!(*distance_to_goal > 1.0);
        }
        other => panic!("expected a local minimum, got {other}"),
    }
    assert!(err.to_string().contains("local minimum"), "{err}");
}

#[test]
fn bad_input_is_an_error() {
    let obs = || obstacles(vec![ball([0.0, 0.0], 0.3)]);
    let err = potential::plan(&FIELD, obs(), &[0.1, 0.0], &[1.0, 0.0], &params()).unwrap_err();
    assert!(
        matches!(err, PlanError::InvalidConfiguration { which: "start", .. }),
        "{err}"
    );
    let err = potential::plan(&FIELD, obs(), &[1.0, 0.0, 0.0], &[1.0, 0.0], &params()).unwrap_err();
    assert!(
        err.to_string().contains("3 coordinates, expected 2"),
        "{err}"
    );
    let bad = CSpaceField { rho0: 0.0, ..FIELD };
    let err = potential::plan(&bad, obs(), &[1.0, 0.0], &[-1.0, 0.5], &params()).unwrap_err();
    assert!(
        matches!(err, PlanError::InvalidParameter { name: "rho0", .. }),
        "{err}"
    );
    let bounded = obs().with_bounds(vec![[-1.0, 1.0], [-1.0, 1.0]]).unwrap();
    let err = potential::plan(&FIELD, bounded, &[1.0, 0.0], &[2.0, 0.5], &params()).unwrap_err();
    assert!(err.to_string().contains("outside"), "{err}");
    let err = ConvexCSpaceObstacles::new(2, vec![cbox([0.0, 0.0], [0.0, 1.0])]).unwrap_err();
    assert!(
        matches!(err, PlanError::InvalidObstacle { index: 0, .. }),
        "{err}"
    );
}

#[test]
fn planar_arm_descends_over_its_obstacle_grid() {
    // The C-space field of a real arm: QO sampled on a grid, motions checked on the arm.
    let scene = figure3();
    let mut checker =
        CollisionChecker::new(&planar::Robot, Scene::new(scene.obstacles.clone()).unwrap())
            .unwrap();
    let grid = CSpaceGrid::compute(&mut checker, [120, 120]).unwrap();
    assert!(grid.components() >= 3);
    // The grid is the checker's verdict at the cell centres.
    for (i, j) in [(10, 10), (60, 40), (30, 100), (100, 70)] {
        let c = grid.cell_center(i, j);
        assert_eq!(
            grid.is_occupied(i, j),
            checker.in_collision(&SVector::from(c)),
            "cell {i}, {j}"
        );
    }
    let field = CSpaceField {
        zeta: 1.0,
        d: 1.0,
        eta: 0.05,
        rho0: 0.5,
    };
    let resolution = 0.02;
    let path = potential::plan(
        &field,
        grid.obstacles(&mut checker, resolution).unwrap(),
        &scene.start,
        &scene.goal,
        &DescentParams {
            step: 0.02,
            tolerance: 0.02,
            ..DescentParams::default()
        },
    )
    .unwrap();
    assert!(path.ends_at_goal);
    let waypoints: Vec<SVector<f64, 2>> = path
        .waypoints
        .iter()
        .map(|q| SVector::from_column_slice(q))
        .collect();
    // Re-checked at ten times the resolution, without the margin: nothing touches.
    assert!(checker.path_touches_nothing(&waypoints, resolution / 10.0));
    // The straight motion is blocked: the field found a way around.
    assert!(!checker.motion_is_free(
        &SVector::from(scene.start),
        &SVector::from(scene.goal),
        resolution
    ));
}
