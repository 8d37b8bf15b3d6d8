//! Collision geometry: distances against independent closed forms, the capsule segments of
//! both DH conventions, the motion bound that makes the local planner sound, and the
//! errors for bad geometry.

use crate::catalogue::{planar_elbow as planar, puma560 as puma};
use crate::planning_support::{model, puma_obstacles};
use dhgen::Robot;
use dhgen::model::{Collision, RobotModel};
use dhgen::nalgebra::{DVector, Isometry3, Point3, SVector, Translation3, UnitQuaternion, Vector3};
use dhgen::planning::{CollisionChecker, CollisionModel, Obstacle, PlanError, Scene};
use rand::{RngExt, SeedableRng, rngs::StdRng};

/// Distance from point `p` to the segment `a`–`b`, by projection.
fn point_segment(p: &Point3<f64>, a: &Point3<f64>, b: &Point3<f64>) -> f64 {
    let ab = b - a;
    if ab.norm_squared() == 0.0 {
        return (p - a).norm();
    }
    let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
    (a + ab * t - p).norm()
}

/// The minimum over `t ∈ [0, 1]` of a convex function, by golden-section search.
fn convex_min(f: impl Fn(f64) -> f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let g = 0.5 * (5f64.sqrt() - 1.0);
    for _ in 0..200 {
        let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        if f(x1) < f(x2) {
            hi = x2;
        } else {
            lo = x1;
        }
    }
    f(0.5 * (lo + hi)).min(f(0.0)).min(f(1.0))
}

/// Distance from point `p` to a box, in the box's frame: the clamped point is the nearest.
fn point_box(p: &Point3<f64>, pose: &Isometry3<f64>, half: &[f64; 3]) -> f64 {
    let local = pose.inverse_transform_point(p);
    let clamped = Point3::new(
        local.x.clamp(-half[0], half[0]),
        local.y.clamp(-half[1], half[1]),
        local.z.clamp(-half[2], half[2]),
    );
    (local - clamped).norm()
}

/// Segment-to-obstacle distances from independent formulas: the distance from a point of
/// the segment to a convex obstacle is convex along the segment, so its minimum is found
/// by golden-section search.
fn reference_distance(o: &Obstacle, a: &Point3<f64>, b: &Point3<f64>) -> f64 {
    let at = |t: f64| a + (b - a) * t;
    let d = match o {
        Obstacle::Sphere { center, radius } => point_segment(&Point3::from(*center), a, b) - radius,
        Obstacle::Box { pose, half_extents } => {
            convex_min(|t| point_box(&at(t), pose, half_extents))
        }
        Obstacle::Capsule { a: c, b: e, radius } => {
            let (c, e) = (Point3::from(*c), Point3::from(*e));
            convex_min(|t| point_segment(&at(t), &c, &e)) - radius
        }
    };
    d.max(0.0)
}

fn random_point(rng: &mut StdRng, scale: f64) -> Point3<f64> {
    Point3::new(
        rng.random_range(-scale..scale),
        rng.random_range(-scale..scale),
        rng.random_range(-scale..scale),
    )
}

#[test]
fn segment_distances_match_independent_formulas() {
    let mut rng = StdRng::seed_from_u64(1);
    let tilted = Isometry3::from_parts(
        Translation3::new(0.2, -0.3, 0.1),
        UnitQuaternion::from_euler_angles(0.4, -0.7, 1.1),
    );
    let obstacles = [
        Obstacle::sphere([0.3, 0.2, -0.1], 0.25),
        Obstacle::cuboid([-0.4, 0.1, 0.3], [0.2, 0.1, 0.3]),
        Obstacle::Box {
            pose: tilted,
            half_extents: [0.3, 0.05, 0.15],
        },
        Obstacle::capsule([0.1, -0.5, 0.0], [0.6, 0.4, 0.2], 0.1),
    ];
    let mut touching = 0;
    for o in &obstacles {
        let scene = Scene::new(vec![o.clone()]).unwrap();
        for _ in 0..300 {
            let (a, b) = (random_point(&mut rng, 1.0), random_point(&mut rng, 1.0));
            let got = scene.distance_to_segment(&a, &b);
            let want = reference_distance(o, &a, &b);
            assert!(
                (got - want).abs() < 1e-7,
                "{o:?}, segment {a} to {b}: got {got}, want {want}"
            );
            touching += usize::from(want == 0.0);
            // A point (a zero-length segment) too.
            let got = scene.distance_to_segment(&a, &a);
            let want = reference_distance(o, &a, &a);
            assert!(
                (got - want).abs() < 1e-7,
                "{o:?}, point {a}: {got} vs {want}"
            );
        }
    }
    // Both cases occur: segments that touch and segments that do not.
    assert!(touching > 50 && touching < 1100, "{touching} touching");
}

#[test]
fn nearest_points_lie_on_segment_and_surface() {
    let mut rng = StdRng::seed_from_u64(2);
    let scene = Scene::new(vec![
        Obstacle::sphere([0.3, 0.2, -0.1], 0.25),
        Obstacle::cuboid([-0.6, 0.1, 0.3], [0.2, 0.1, 0.3]),
        Obstacle::capsule([0.1, -0.9, 0.0], [0.6, -0.4, 0.2], 0.1),
    ])
    .unwrap();
    let mut found = 0;
    for _ in 0..500 {
        let (a, b) = (random_point(&mut rng, 1.2), random_point(&mut rng, 1.2));
        let distance = scene.distance_to_segment(&a, &b);
        match scene.nearest_to_segment(&a, &b, 0.3) {
            Some(p) if distance > 0.0 => {
                found += 1;
                assert!((p.distance - distance).abs() < 1e-7, "{p:?} vs {distance}");
                assert!(((p.on_robot - p.on_obstacle).norm() - p.distance).abs() < 1e-7);
                assert!(
                    point_segment(&p.on_robot, &a, &b) < 1e-9,
                    "{p:?} not on the segment"
                );
                // On the obstacle's surface: the obstacle is 0 away from it, and a point just
                // outside it along the normal is as far as it was moved.
                let o = &scene.obstacles()[p.obstacle];
                let normal = (p.on_robot - p.on_obstacle) / p.distance;
                let out = p.on_obstacle + normal * 1e-3;
                assert!(reference_distance(o, &p.on_obstacle, &p.on_obstacle) < 1e-7);
                assert!((reference_distance(o, &out, &out) - 1e-3).abs() < 1e-6);
            }
            Some(p) => assert!(p.distance <= 0.0),
            None => assert!(
                distance >= 0.3,
                "nothing within 0.3 but distance {distance}"
            ),
        }
    }
    assert!(
        found > 50,
        "only {found} segments had an obstacle within 0.3"
    );
}

fn planar_checker(obstacles: Vec<Obstacle>) -> CollisionChecker<'static, planar::Robot> {
    CollisionChecker::new(&planar::Robot, Scene::new(obstacles).unwrap()).unwrap()
}

#[test]
fn planar_clearance_is_the_capsule_distance() {
    // Spheres only: the clearance has the closed form min over links and spheres of
    // (distance from centre to link axis) − sphere radius − link radius.
    let spheres = [
        ([1.1, 0.8, 0.0], 0.2),
        ([-1.2, -0.3, 0.0], 0.3),
        ([0.2, -1.4, 0.0], 0.15),
    ];
    let mut checker = planar_checker(
        spheres
            .iter()
            .map(|(c, r)| Obstacle::sphere(*c, *r))
            .collect(),
    );
    let mut rng = StdRng::seed_from_u64(3);
    for _ in 0..500 {
        let q = SVector::<f64, 2>::new(rng.random_range(-3.1..3.1), rng.random_range(-3.1..3.1));
        let elbow = Point3::new(q[0].cos(), q[0].sin(), 0.0);
        let tip = elbow + 0.8 * Vector3::new((q[0] + q[1]).cos(), (q[0] + q[1]).sin(), 0.0);
        let want = spheres
            .iter()
            .flat_map(|(c, r)| {
                let c = Point3::from(*c);
                [
                    point_segment(&c, &Point3::origin(), &elbow) - r - 0.05,
                    point_segment(&c, &elbow, &tip) - r - 0.05,
                ]
            })
            .fold(f64::INFINITY, f64::min)
            .max(0.0);
        let got = checker.clearance(&q);
        assert!((got - want).abs() < 1e-9, "q = {q}: {got} vs {want}");
        assert_eq!(checker.in_collision(&q), want == 0.0, "q = {q}");
        assert_eq!(checker.is_free(&q, 0.02), want > 0.02, "q = {q}");
    }
    // Every query above counted.
    assert_eq!(checker.checks(), 1500);
}

#[test]
fn generated_and_runtime_arms_agree() {
    let model = model("puma560.toml");
    let robot = Robot::from_model(model.clone());
    let scene = || Scene::new(puma_obstacles()).unwrap();
    let mut generated = CollisionChecker::new(&puma::Robot, scene()).unwrap();
    let mut runtime = CollisionChecker::new(&robot, scene()).unwrap();
    assert_eq!(generated.model(), runtime.model());
    let mut rng = StdRng::seed_from_u64(4);
    let mut hits = 0;
    for _ in 0..300 {
        let q: Vec<f64> = (0..6)
            .map(|j| {
                let [lo, hi] = generated.joint_range(j);
                rng.random_range(lo..hi)
            })
            .collect();
        let a = generated.clearance(&SVector::<f64, 6>::from_column_slice(&q));
        let b = runtime.clearance(&DVector::from_column_slice(&q));
        assert!((a - b).abs() < 1e-9, "q = {q:?}: {a} vs {b}");
        hits += usize::from(a == 0.0);
    }
    assert!(hits > 10 && hits < 290, "{hits} of 300 in collision");
}

#[test]
fn capsules_join_frame_origins_in_both_conventions() {
    // Standard DH with a base pose: link 1's capsule starts at the base origin.
    let text = r#"
        name = "based"
        convention = "standard"
        base = { xyz = [0.5, -0.2, 0.3], rpy = [0, 0, "90deg"] }
        [[links]]
        joint = "revolute"
        a = 1.0
        alpha = 0
        d = 0.2
        theta = 0
        collision = { radius = 0.1 }
        [[links]]
        joint = "prismatic"
        a = 0.0
        alpha = 0
        d = 0.1
        theta = 0
        limits = [0.0, 0.5]
        collision = { radius = 0.05 }
    "#;
    let model = RobotModel::from_toml_str(text).unwrap();
    let robot = Robot::from_model(model.clone());
    let mut checker = CollisionChecker::new(&robot, Scene::default()).unwrap();
    let q = DVector::from_vec(vec![0.3, 0.25]);
    let capsules = checker.capsules(&q);
    assert_eq!(capsules.len(), 2);
    assert_eq!(capsules[0].a, Point3::new(0.5, -0.2, 0.3));
    // Base turned by 90° about z: the link points along +y rotated by q1.
    let elbow = Point3::new(0.5 - 0.3f64.sin(), -0.2 + 0.3f64.cos(), 0.5);
    assert!((capsules[0].b - elbow).norm() < 1e-12, "{}", capsules[0].b);
    // The prismatic row's segment stretches with q2: d = 0.1 + 0.25 along z.
    assert!((capsules[1].b - (elbow + Vector3::new(0.0, 0.0, 0.35))).norm() < 1e-12);
    assert_eq!((capsules[0].radius, capsules[1].radius), (0.1, 0.05));

    // Modified DH: row i's capsule joins the origins of frames i−1 and i. For this planar
    // arm, row 1 (a0 = 0) is a sphere at the base and row 2 (a1 = 1) runs from joint 1 to
    // joint 2; the last link, beyond joint 2, is not covered.
    let text = r#"
        name = "craig"
        convention = "modified"
        [[links]]
        joint = "revolute"
        a = 0.0
        alpha = 0
        d = 0
        theta = 0
        collision = { radius = 0.1 }
        [[links]]
        joint = "revolute"
        a = 1.0
        alpha = 0
        d = 0
        theta = 0
        collision = { radius = 0.05 }
    "#;
    let model = RobotModel::from_toml_str(text).unwrap();
    let robot = Robot::from_model(model.clone());
    let obstacle = Obstacle::sphere([0.0, 1.5, 0.0], 0.2);
    let mut checker = CollisionChecker::new(&robot, Scene::new(vec![obstacle]).unwrap()).unwrap();
    let q = DVector::from_vec(vec![std::f64::consts::FRAC_PI_2, 0.4]);
    let capsules = checker.capsules(&q);
    assert_eq!(capsules[0].a, capsules[0].b);
    assert_eq!(capsules[0].a, Point3::origin());
    assert!((capsules[1].b - Point3::new(0.0, 1.0, 0.0)).norm() < 1e-12);
    // The sphere is 0.5 − 0.2 − 0.05 from the end of row 2's segment, whatever q2 does.
    for q2 in [-2.0, 0.0, 2.0] {
        let q = DVector::from_vec(vec![std::f64::consts::FRAC_PI_2, q2]);
        assert!((checker.clearance(&q) - 0.25).abs() < 1e-12);
    }
}

/// Copies of catalogue robots with a capsule on every link.
fn with_capsules(file: &str) -> RobotModel {
    let mut m = model(file);
    for l in &mut m.links {
        l.collision = Some(Collision { radius: 0.05 });
    }
    m
}

#[test]
fn no_point_moves_farther_than_the_sweep_bound() {
    // The soundness of the local planner rests on this: along a straight joint-space
    // motion, no point of any capsule axis moves farther than `sweep` (standard and
    // modified DH, revolute and prismatic joints).
    let mut rng = StdRng::seed_from_u64(5);
    for file in [
        "puma560.toml",
        "panda.toml",
        "stanford.toml",
        "scara.toml",
        "cylindrical.toml",
    ] {
        let model = with_capsules(file);
        let robot = Robot::from_model(model.clone());
        let geometry = CollisionModel::from_chain(robot.chain()).unwrap();
        let mut checker = CollisionChecker::new(&robot, Scene::default()).unwrap();
        let n = robot.dof();
        let mut tightest: f64 = 0.0;
        for _ in 0..200 {
            let sample = |rng: &mut StdRng| {
                DVector::from_fn(n, |j, _| {
                    let [lo, hi] = checker.joint_range(j);
                    rng.random_range(lo..hi)
                })
            };
            let a = sample(&mut rng);
            let b = a.lerp(&sample(&mut rng), rng.random_range(0.0..0.3));
            let start = checker.capsules(&a);
            for k in 1..=10 {
                let q = a.lerp(&b, k as f64 / 10.0);
                let bound = geometry.sweep(a.as_slice(), q.as_slice());
                for (c0, c) in start.iter().zip(checker.capsules(&q)) {
                    for (p0, p) in [(c0.a, c.a), (c0.b, c.b)] {
                        let moved = (p - p0).norm();
                        assert!(
                            moved <= bound + 1e-12,
                            "{file}: a point moved {moved} > bound {bound} from {a} to {q}"
                        );
                        tightest = tightest.max(moved / bound.max(1e-300));
                    }
                }
            }
        }
        // The bound is not vacuous: some motions come within a factor 2 of it.
        assert!(tightest > 0.5, "{file}: the bound is loose ({tightest})");
    }
}

#[test]
fn motions_checked_at_a_resolution_are_free_in_between() {
    // A thin wall that a coarse sampling would step over: the margin catches it.
    let mut checker = planar_checker(vec![Obstacle::cuboid([1.5, 0.0, 0.0], [0.3, 0.004, 0.2])]);
    let a = SVector::<f64, 2>::new(-0.1, 0.0);
    let b = SVector::<f64, 2>::new(0.1, 0.0);
    // The straight motion passes through the wall (at q = 0 link 2 lies in it).
    assert!(checker.in_collision(&SVector::<f64, 2>::zeros()));
    for resolution in [0.01, 0.05, 0.2, 1.0] {
        assert!(!checker.motion_is_free(&a, &b, resolution), "{resolution}");
    }
    // A free motion stays free at every resolution; its sampled checks all count.
    let c = SVector::<f64, 2>::new(1.0, 0.5);
    checker.reset_checks();
    assert!(checker.motion_is_free(&a.map(|x| x + 1.0), &c, 0.01));
    assert!(checker.checks() > 10);
}

#[test]
fn bad_geometry_and_obstacles_are_errors() {
    // No capsule at all.
    let bare = RobotModel::from_toml_file(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("robots/ur5.toml"),
    )
    .unwrap();
    let err = CollisionModel::from_chain(bare.chain().view()).unwrap_err();
    assert!(
        err.to_string().contains("no link has a collision capsule"),
        "{err}"
    );
    // A prismatic joint without limits.
    let mut stanford = with_capsules("stanford.toml");
    stanford.links[2].limits = None;
    let err = CollisionModel::from_chain(stanford.chain().view()).unwrap_err();
    assert!(
        err.to_string()
            .contains("joint 3 is prismatic and has no limits"),
        "{err}"
    );
    // Obstacles.
    for (o, what) in [
        (Obstacle::sphere([0.0, 0.0, f64::NAN], 0.1), "not finite"),
        (Obstacle::sphere([0.0; 3], 0.0), "radius 0"),
        (
            Obstacle::cuboid([0.0; 3], [0.1, -0.1, 0.1]),
            "half extent -0.1",
        ),
        (
            Obstacle::capsule([0.0; 3], [1.0, 0.0, 0.0], f64::INFINITY),
            "radius inf",
        ),
    ] {
        let err = Scene::new(vec![Obstacle::sphere([1.0; 3], 0.1), o]).unwrap_err();
        assert!(
            matches!(err, PlanError::InvalidObstacle { index: 1, .. }),
            "{err}"
        );
        assert!(err.to_string().contains(what), "{err} should say {what}");
    }
}
