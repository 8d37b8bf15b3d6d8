//! Collision geometry: the robot as capsules around the segments joining its link frames'
//! origins, obstacles in the world, distance and closest-point queries (by `parry3d-f64`),
//! and the straight-line local planner.
//!
//! Link i of the description may carry `collision = { radius = r }`: a capsule of radius r
//! around the segment joining the origins of link frames i−1 and i (link frame 0 = the base
//! frame, after the base pose), for either DH convention; see
//! `dhgen_kernel::Collision` for what that segment is on a modified-DH robot. The capsules
//! come with the arm's structure ([`Arm::chain`]), so a generated module carries its own.
//!
//! ```
//! use dhgen::planning::{CollisionChecker, Obstacle, Scene};
//! dhgen::robot!(mod planar = "../../robots/planar_elbow.toml");
//!
//! let scene = Scene::new(vec![Obstacle::sphere([1.2, 0.6, 0.0], 0.2)]).unwrap();
//! let mut checker = CollisionChecker::new(&planar::Robot, scene).unwrap();
//!
//! let stretched = dhgen::nalgebra::SVector::<f64, 2>::new(0.0, 0.0);
//! // Link 2 runs along the x axis from 1.0 to 1.8; the sphere's surface is 0.4 above it.
//! assert!((checker.clearance(&stretched) - (0.6 - 0.2 - 0.05)).abs() < 1e-9);
//! let raised = dhgen::nalgebra::SVector::<f64, 2>::new(0.5, 0.0);
//! assert!(checker.in_collision(&raised));
//! ```

use super::PlanError;
use dhgen_kernel::{Arm, ArmAllocator, JointVector};
use dhgen_kernel::{ChainRef, Frame, JointKind};
use nalgebra::{DefaultAllocator, Isometry3, Matrix3, Point3, Rotation3, UnitQuaternion, Vector3};
use parry3d_f64::math::{Pose, Rotation as ParryRotation, Vector as ParryVector};
use parry3d_f64::query::{self, ClosestPoints};
use parry3d_f64::shape::{Ball, Cuboid, Segment, Shape};

/// An obstacle in the world frame (the frame the description's `base` pose is given in).
#[derive(Clone, Debug, PartialEq)]
pub enum Obstacle {
    /// A ball.
    Sphere {
        /// Centre, m.
        center: [f64; 3],
        /// Radius, m (> 0).
        radius: f64,
    },
    /// A box: `half_extents` along the axes of `pose`, centred at its origin.
    Box {
        /// Centre and orientation of the box.
        pose: Isometry3<f64>,
        /// Half the edge lengths, m (each > 0).
        half_extents: [f64; 3],
    },
    /// The points within `radius` of the segment from `a` to `b`.
    Capsule {
        /// One end of the axis, m.
        a: [f64; 3],
        /// The other end of the axis, m.
        b: [f64; 3],
        /// Radius, m (> 0).
        radius: f64,
    },
}

impl Obstacle {
    /// A ball of `radius` about `center`.
    pub fn sphere(center: [f64; 3], radius: f64) -> Obstacle {
        Obstacle::Sphere { center, radius }
    }

    /// An axis-aligned box.
    pub fn cuboid(center: [f64; 3], half_extents: [f64; 3]) -> Obstacle {
        Obstacle::Box {
            pose: Isometry3::translation(center[0], center[1], center[2]),
            half_extents,
        }
    }

    /// A capsule around the segment `a`–`b`.
    pub fn capsule(a: [f64; 3], b: [f64; 3], radius: f64) -> Obstacle {
        Obstacle::Capsule { a, b, radius }
    }

    fn check(&self) -> Result<(), String> {
        let finite = |what: &str, v: &[f64]| {
            if v.iter().all(|x| x.is_finite()) {
                Ok(())
            } else {
                Err(format!("{what} {v:?} is not finite"))
            }
        };
        let positive = |what: &str, x: f64| {
            if x > 0.0 && x.is_finite() {
                Ok(())
            } else {
                Err(format!("{what} {x} is not a finite number > 0"))
            }
        };
        match self {
            Obstacle::Sphere { center, radius } => {
                finite("centre", center)?;
                positive("radius", *radius)
            }
            Obstacle::Box { pose, half_extents } => {
                finite("position", pose.translation.vector.as_slice())?;
                finite("orientation", pose.rotation.coords.as_slice())?;
                for h in half_extents {
                    positive("half extent", *h)?;
                }
                Ok(())
            }
            Obstacle::Capsule { a, b, radius } => {
                finite("end", a)?;
                finite("end", b)?;
                positive("radius", *radius)
            }
        }
    }
}

/// The parry shape of an obstacle: a core, and how far the obstacle extends beyond it.
///
/// A capsule is kept as its axis plus a radius so that capsule-capsule queries are the
/// closed-form segment-segment ones rather than an iterative (GJK) support-map query.
///
/// Every body also keeps a cheap lower bound of its distance to a segment, a few nanoseconds
/// to evaluate, so that the exact parry query (60 ns for a ball, 170 ns for a capsule,
/// 800 ns for a box by GJK, measured) only runs for obstacles that are near: for a ball or
/// a capsule, the distance from the segment to a bounding sphere; for a box, the distance
/// from the box to the segment's bounding box in the box's own axes (a bounding sphere of a
/// thin panel would be far too loose).
#[derive(Clone, Debug)]
struct ObstacleShape {
    pose: Pose,
    core: Core,
    inflation: f64,
    bound: Bound,
}

#[derive(Clone, Debug)]
enum Bound {
    Sphere {
        center: [f64; 3],
        radius: f64,
    },
    Box {
        center: [f64; 3],
        /// Rows: the box's axes in the world frame.
        axes: [[f64; 3]; 3],
        half_extents: [f64; 3],
    },
}

#[derive(Clone, Debug)]
enum Core {
    Ball(Ball),
    Cuboid(Cuboid),
    Segment(Segment),
}

impl ObstacleShape {
    fn new(obstacle: &Obstacle) -> ObstacleShape {
        let bound = match obstacle {
            Obstacle::Sphere { center, radius } => Bound::Sphere {
                center: *center,
                radius: *radius,
            },
            Obstacle::Box { pose, half_extents } => {
                let r = pose.rotation.to_rotation_matrix();
                Bound::Box {
                    center: pose.translation.vector.into(),
                    axes: core::array::from_fn(|k| core::array::from_fn(|i| r[(i, k)])),
                    half_extents: *half_extents,
                }
            }
            Obstacle::Capsule { a, b, radius } => Bound::Sphere {
                center: core::array::from_fn(|i| 0.5 * (a[i] + b[i])),
                radius: 0.5 * distance(a, b) + radius,
            },
        };
        let (pose, core, inflation) = ObstacleShape::core(obstacle);
        ObstacleShape {
            pose,
            core,
            inflation,
            bound,
        }
    }

    /// A lower bound of the distance from the segment `a`–`b` to the obstacle.
    fn lower_bound(&self, a: &[f64; 3], b: &[f64; 3]) -> f64 {
        match &self.bound {
            Bound::Sphere { center, radius } => segment_point_distance(a, b, center) - radius,
            Bound::Box {
                center,
                axes,
                half_extents,
            } => {
                // Per box axis, the gap between the segment's extent and the box's.
                let mut gap2 = 0.0;
                for (axis, h) in axes.iter().zip(half_extents) {
                    let along = |p: &[f64; 3]| {
                        axis[0] * (p[0] - center[0])
                            + axis[1] * (p[1] - center[1])
                            + axis[2] * (p[2] - center[2])
                    };
                    let (u, v) = (along(a), along(b));
                    let gap = (u.min(v) - h).max(-h - u.max(v)).max(0.0);
                    gap2 += gap * gap;
                }
                gap2.sqrt()
            }
        }
    }

    fn core(obstacle: &Obstacle) -> (Pose, Core, f64) {
        match obstacle {
            Obstacle::Sphere { center, radius } => (
                Pose::from_translation(vector(center)),
                Core::Ball(Ball::new(*radius)),
                0.0,
            ),
            Obstacle::Box { pose, half_extents } => {
                let q = pose.rotation.coords;
                (
                    Pose::from_parts(
                        vector(&pose.translation.vector.into()),
                        ParryRotation::from_xyzw(q[0], q[1], q[2], q[3]).normalize(),
                    ),
                    Core::Cuboid(Cuboid::new(vector(half_extents))),
                    0.0,
                )
            }
            Obstacle::Capsule { a, b, radius } if a == b => (
                Pose::from_translation(vector(a)),
                Core::Ball(Ball::new(*radius)),
                0.0,
            ),
            Obstacle::Capsule { a, b, radius } => (
                Pose::IDENTITY,
                Core::Segment(Segment::new(vector(a), vector(b))),
                *radius,
            ),
        }
    }

    fn shape(&self) -> &dyn Shape {
        match &self.core {
            Core::Ball(b) => b,
            Core::Cuboid(c) => c,
            Core::Segment(s) => s,
        }
    }
}

/// Distance from the segment `a`–`b` (a point when `a == b`) to the point `p`.
///
/// On plain arrays, like the rest of the culling: it runs for every link and obstacle of
/// every configuration checked, and unoptimised (test) builds of nalgebra's generic
/// arithmetic would dominate their run time.
fn segment_point_distance(a: &[f64; 3], b: &[f64; 3], p: &[f64; 3]) -> f64 {
    let ab = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let ap = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
    let length2 = ab[0] * ab[0] + ab[1] * ab[1] + ab[2] * ab[2];
    let t = if length2 > 0.0 {
        ((ap[0] * ab[0] + ap[1] * ab[1] + ap[2] * ab[2]) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let d = [ap[0] - t * ab[0], ap[1] - t * ab[1], ap[2] - t * ab[2]];
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

fn distance(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let d = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt()
}

fn array(p: &Point3<f64>) -> [f64; 3] {
    [p.x, p.y, p.z]
}

fn vector(v: &[f64; 3]) -> ParryVector {
    ParryVector::new(v[0], v[1], v[2])
}

fn point(v: ParryVector) -> Point3<f64> {
    Point3::new(v.x, v.y, v.z)
}

/// A segment of the robot (a capsule's axis, or a single point) as a parry shape at the
/// identity pose, so that query results are in world coordinates.
enum Probe {
    Point(Ball),
    Segment(Segment),
}

impl Probe {
    fn new(a: &[f64; 3], b: &[f64; 3]) -> (Probe, Pose) {
        if a == b {
            // parry has no point shape: a ball of radius 0 is one.
            (
                Probe::Point(Ball::new(0.0)),
                Pose::from_translation(vector(a)),
            )
        } else {
            (
                Probe::Segment(Segment::new(vector(a), vector(b))),
                Pose::IDENTITY,
            )
        }
    }

    fn shape(&self) -> &dyn Shape {
        match self {
            Probe::Point(b) => b,
            Probe::Segment(s) => s,
        }
    }
}

/// The nearest obstacle to a segment (or point) of the robot.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Proximity {
    /// Distance from the segment to the obstacle's surface, m; `≤ 0` when the segment
    /// touches or enters the obstacle (then the two points below coincide and carry no
    /// direction).
    pub distance: f64,
    /// The point of the segment closest to the obstacle.
    pub on_robot: Point3<f64>,
    /// The point of the obstacle's surface closest to the segment.
    pub on_obstacle: Point3<f64>,
    /// Index of the obstacle in the scene.
    pub obstacle: usize,
}

/// The obstacles of a workspace, validated.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    obstacles: Vec<Obstacle>,
    shapes: Vec<ObstacleShape>,
}

impl Scene {
    /// A scene of these obstacles; each must have finite coordinates and positive sizes.
    pub fn new(obstacles: Vec<Obstacle>) -> Result<Scene, PlanError> {
        for (index, o) in obstacles.iter().enumerate() {
            o.check()
                .map_err(|reason| PlanError::InvalidObstacle { index, reason })?;
        }
        let shapes = obstacles.iter().map(ObstacleShape::new).collect();
        Ok(Scene { obstacles, shapes })
    }

    /// The obstacles, in the order given.
    pub fn obstacles(&self) -> &[Obstacle] {
        &self.obstacles
    }

    /// The distance from the segment `a`–`b` (a point when `a == b`) to the nearest obstacle,
    /// `0` when they touch or overlap; `+∞` for an empty scene; NaN when `a` or `b` is not
    /// finite.
    pub fn distance_to_segment(&self, a: &Point3<f64>, b: &Point3<f64>) -> f64 {
        let (a, b) = (array(a), array(b));
        if !finite(&a) || !finite(&b) {
            return f64::NAN;
        }
        let mut probe = None;
        let mut nearest = f64::INFINITY;
        for shape in &self.shapes {
            if shape.lower_bound(&a, &b) < nearest {
                let (probe, pose) = probe.get_or_insert_with(|| Probe::new(&a, &b));
                nearest = nearest.min(shape_distance(probe, pose, shape));
            }
        }
        nearest.max(0.0)
    }

    /// The nearest obstacle to the segment `a`–`b` (a point when `a == b`) among those
    /// closer than `max_distance`, with the closest points; `None` when there is none, and
    /// when `a` or `b` is not finite (then [`distance_to_segment`](Self::distance_to_segment)
    /// is NaN).
    pub fn nearest_to_segment(
        &self,
        a: &Point3<f64>,
        b: &Point3<f64>,
        max_distance: f64,
    ) -> Option<Proximity> {
        let (aa, bb) = (array(a), array(b));
        if !finite(&aa) || !finite(&bb) {
            return None;
        }
        let (probe, pose) = Probe::new(&aa, &bb);
        let mut best: Option<Proximity> = None;
        for (index, shape) in self.shapes.iter().enumerate() {
            let closest_yet = best.map_or(max_distance, |b| b.distance);
            if shape.lower_bound(&aa, &bb) >= closest_yet {
                continue;
            }
            let reach = max_distance + shape.inflation;
            let found =
                query::closest_points(&pose, probe.shape(), &shape.pose, shape.shape(), reach);
            let proximity = match found {
                Ok(ClosestPoints::WithinMargin(on_robot, on_core)) => {
                    let (on_robot, on_core) = (point(on_robot), point(on_core));
                    let gap = on_robot - on_core;
                    let core_distance = gap.norm();
                    let on_obstacle = if core_distance > 0.0 {
                        on_core + gap * (shape.inflation / core_distance)
                    } else {
                        on_core
                    };
                    Proximity {
                        distance: core_distance - shape.inflation,
                        on_robot,
                        on_obstacle,
                        obstacle: index,
                    }
                }
                // The robot's axis is inside the obstacle's core: deep in collision, no
                // meaningful direction. `Unsupported` cannot occur for these shape pairs;
                // should it, count it as a collision rather than as free space.
                Ok(ClosestPoints::Intersecting) | Err(_) => Proximity {
                    distance: -shape.inflation,
                    on_robot: *a,
                    on_obstacle: *a,
                    obstacle: index,
                },
                Ok(ClosestPoints::Disjoint) => continue,
            };
            if proximity.distance < max_distance
                && best.is_none_or(|b| proximity.distance < b.distance)
            {
                best = Some(proximity);
            }
        }
        best
    }
}

fn shape_distance(probe: &Probe, pose: &Pose, shape: &ObstacleShape) -> f64 {
    // `Unsupported` cannot occur for these shape pairs; should it, report contact.
    query::distance(pose, probe.shape(), &shape.pose, shape.shape())
        .map_or(0.0, |d| d.distance - shape.inflation)
}

/// The collision model of an arm, read from its kinematic structure
/// ([`Arm::chain`]): per link its capsule radius, where the joint axes sit relative to the
/// link frames, and bounds on how fast the arm's points move.
#[derive(Clone, Debug, PartialEq)]
pub struct CollisionModel {
    base: Isometry3<f64>,
    joints: Vec<JointKind>,
    limits: Vec<Option<[f64; 2]>>,
    /// Joint frame k in link frame k (the inverse of the link frame in the joint frame).
    joint_in_link: Vec<Isometry3<f64>>,
    radii: Vec<Option<f64>>,
    reach: Vec<f64>,
}

impl CollisionModel {
    /// Reads the collision capsules of an arm's structure.
    ///
    /// Errors when no link has a capsule (there would be nothing to check), and when a
    /// prismatic joint has no limits (how far the links beyond it reach would be unbounded).
    pub fn from_chain(chain: ChainRef<'_>) -> Result<CollisionModel, PlanError> {
        if chain.bodies.iter().all(|b| b.capsule.is_none()) {
            return Err(PlanError::InvalidGeometry(
                "no link has a collision capsule (`collision = { radius = ... }`)".into(),
            ));
        }
        let n = chain.dof();
        // Segment k joins the origins of link frames k − 1 and k (link frame −1: the base).
        // Its length, bounded over the joint's range: with `A` the translation between the
        // two origins at rest and `b` the link origin in its joint frame, turning the joint
        // by θ gives `A + R Rz(θ) b`, longest where `Rz(θ) b` lines up with `Rᵀ A`.
        let mut lengths = Vec::with_capacity(n);
        for (k, body) in chain.bodies.iter().enumerate() {
            let (start, placement) = if k == 0 {
                (chain.base.p, chain.placements[0])
            } else {
                // In joint frame k − 1.
                (chain.bodies[k - 1].link.p, chain.placements[k])
            };
            let a: [f64; 3] = core::array::from_fn(|i| placement.p[i] - start[i]);
            let b = body.link.p;
            let length = match body.joint {
                JointKind::Revolute => {
                    let r = &placement.r;
                    let u: [f64; 3] =
                        core::array::from_fn(|i| r[0][i] * a[0] + r[1][i] * a[1] + r[2][i] * a[2]);
                    let most = u[2] * b[2] + u[0].hypot(u[1]) * b[0].hypot(b[1]);
                    (dot3(&a, &a) + dot3(&b, &b) + 2.0 * most).max(0.0).sqrt()
                }
                JointKind::Prismatic => {
                    let Some([lo, hi]) = body.limits else {
                        return Err(PlanError::InvalidGeometry(format!(
                            "joint {} is prismatic and has no limits; planning needs them to \
                             bound the length of link {}",
                            k + 1,
                            k + 1
                        )));
                    };
                    let at = |d: f64| {
                        let v = placement.point(&[b[0], b[1], b[2] + d + body.offset]);
                        let w: [f64; 3] = core::array::from_fn(|i| v[i] - start[i]);
                        dot3(&w, &w).sqrt()
                    };
                    at(lo).max(at(hi))
                }
            };
            lengths.push(length);
        }
        // How far a point of the robot can move per unit of joint j's motion: 1 for a
        // prismatic joint; for a revolute one, the largest distance from its axis of any
        // segment it moves: its own link origin's distance from the axis, plus the lengths
        // of the segments beyond (segment j itself is rigid with the link before, or turns
        // about its start).
        let reach = chain
            .bodies
            .iter()
            .enumerate()
            .map(|(j, body)| match body.joint {
                JointKind::Prismatic => 1.0,
                JointKind::Revolute => {
                    body.link.p[0].hypot(body.link.p[1]) + lengths[j + 1..].iter().sum::<f64>()
                }
            })
            .collect();
        Ok(CollisionModel {
            base: isometry(&chain.base),
            joints: chain.bodies.iter().map(|b| b.joint).collect(),
            limits: chain.bodies.iter().map(|b| b.limits).collect(),
            joint_in_link: chain
                .bodies
                .iter()
                .map(|b| isometry(&b.link).inverse())
                .collect(),
            radii: chain.bodies.iter().map(|b| b.capsule).collect(),
            reach,
        })
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.joints.len()
    }

    /// The base link's frame in the world frame.
    pub fn base(&self) -> &Isometry3<f64> {
        &self.base
    }

    /// The kind of joint `j` (0-based).
    pub fn joint(&self, j: usize) -> JointKind {
        self.joints[j]
    }

    /// Joint `j`'s axis (unit direction and a point on it), given link `j`'s frame.
    pub fn joint_axis(&self, j: usize, link_frame: &Isometry3<f64>) -> (Vector3<f64>, Point3<f64>) {
        let joint_frame = link_frame * self.joint_in_link[j];
        (z_axis(&joint_frame), origin(&joint_frame))
    }

    /// The capsule radius of link `link` (0-based), if it has a capsule.
    pub fn radius(&self, link: usize) -> Option<f64> {
        self.radii.get(link).copied().flatten()
    }

    /// Per joint, a bound on how far any point of the robot moves per unit of that joint's
    /// motion (m/rad for revolute joints, m/m = 1 for prismatic ones).
    pub fn reach(&self) -> &[f64] {
        &self.reach
    }

    /// `L = ‖reach‖₂`: no point of the robot moves more than `L·‖Δq‖₂` along a straight
    /// joint-space motion `Δq` (by Cauchy-Schwarz on `Σ reach_j |Δq_j|`).
    pub fn lipschitz(&self) -> f64 {
        self.reach.iter().map(|r| r * r).sum::<f64>().sqrt()
    }

    /// A bound on how far any point of the robot moves along the straight joint-space
    /// motion from `a` to `b`: `Σ_j reach_j·|b_j − a_j|` (at most `L·‖b − a‖₂`).
    pub fn sweep(&self, a: &[f64], b: &[f64]) -> f64 {
        self.reach
            .iter()
            .zip(a.iter().zip(b))
            .map(|(r, (x, y))| r * (y - x).abs())
            .sum()
    }

    /// The number of equal steps the local planner cuts the motion from `a` to `b` into at
    /// `resolution`: the fewest whose sweep is at most `L·resolution` each.
    pub fn steps(&self, a: &[f64], b: &[f64], resolution: f64) -> usize {
        let per_step = self.lipschitz() * resolution;
        if per_step > 0.0 {
            sample_count(self.sweep(a, b), per_step)
        } else {
            1
        }
    }

    /// The safety margin `δ = L·resolution/2` that makes checking a straight motion at
    /// `resolution` sufficient for the whole motion (see the [module docs](super)).
    pub fn margin(&self, resolution: f64) -> f64 {
        0.5 * self.lipschitz() * resolution
    }
}

fn dot3(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The origin of a frame. (Outside the generic impls: there, the `DefaultAllocator` bounds
/// hide nalgebra's `From` conversions from the trait solver.)
pub(crate) fn origin(frame: &Isometry3<f64>) -> Point3<f64> {
    Point3::from(frame.translation.vector)
}

/// The z axis of a frame, in the outer frame.
pub(crate) fn z_axis(frame: &Isometry3<f64>) -> nalgebra::Vector3<f64> {
    frame.rotation * nalgebra::Vector3::z()
}

fn isometry(frame: &Frame<f64>) -> Isometry3<f64> {
    let r = Matrix3::from_fn(|i, j| frame.r[i][j]);
    Isometry3::from_parts(
        frame.p.into(),
        UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(r)),
    )
}

/// One link's capsule at a configuration, in the world frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LinkCapsule {
    /// Row of the DH table, 0-based.
    pub link: usize,
    /// Origin of frame `link` (frame i−1 in 1-based terms).
    pub a: Point3<f64>,
    /// Origin of frame `link + 1`.
    pub b: Point3<f64>,
    /// Capsule radius, m.
    pub radius: f64,
}

/// Collision queries of one arm among the obstacles of a scene.
///
/// Holds the arm by reference and scratch space for its frames, so queries allocate
/// nothing beyond what the arm's own kinematics allocate (nothing for generated code).
pub struct CollisionChecker<'a, A: Arm>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    arm: &'a A,
    model: CollisionModel,
    scene: Scene,
    /// Frames 0 (base) to n at the last configuration asked about.
    frames: Vec<Isometry3<f64>>,
    checks: u64,
}

impl<'a, A: Arm> CollisionChecker<'a, A>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    /// A checker for `arm` among the obstacles of `scene`, with the collision model read
    /// from the arm's own structure ([`CollisionModel::from_chain`], whose errors it
    /// returns).
    pub fn new(arm: &'a A, scene: Scene) -> Result<CollisionChecker<'a, A>, PlanError> {
        let model = CollisionModel::from_chain(arm.chain())?;
        Ok(CollisionChecker {
            frames: vec![Isometry3::identity(); model.dof() + 1],
            arm,
            model,
            scene,
            checks: 0,
        })
    }

    /// The arm.
    pub fn arm(&self) -> &'a A {
        self.arm
    }

    /// The collision model of the arm.
    pub fn model(&self) -> &CollisionModel {
        &self.model
    }

    /// The obstacles.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Number of joints.
    pub fn dof(&self) -> usize {
        self.frames.len() - 1
    }

    /// The range planners sample joint `j` in and keep it in: its limits, or `[−π, π]` for
    /// a revolute joint without limits (a prismatic joint always has limits here: the
    /// collision model requires them).
    pub fn joint_range(&self, j: usize) -> [f64; 2] {
        self.model.limits[j].unwrap_or([-core::f64::consts::PI, core::f64::consts::PI])
    }

    /// Checks that `q` has one finite entry per joint, each within
    /// [`joint_range`](Self::joint_range); the error says which is not.
    pub fn check_configuration(&self, q: &[f64]) -> Result<(), String> {
        if q.len() != self.dof() {
            return Err(format!(
                "{} entries, expected {} (one per joint)",
                q.len(),
                self.dof()
            ));
        }
        for (j, x) in q.iter().enumerate() {
            if !x.is_finite() {
                return Err(format!("joint {} = {x} is not finite", j + 1));
            }
            let [lo, hi] = self.joint_range(j);
            if !(lo <= *x && *x <= hi) {
                return Err(format!(
                    "joint {} = {x} is outside its range [{lo}, {hi}]",
                    j + 1
                ));
            }
        }
        Ok(())
    }

    /// How many configurations have been checked ([`clearance`](Self::clearance),
    /// [`is_free`](Self::is_free) and everything built on them) since the checker was made
    /// or [`reset_checks`](Self::reset_checks) was called.
    pub fn checks(&self) -> u64 {
        self.checks
    }

    /// Restarts the count of [`checks`](Self::checks).
    pub fn reset_checks(&mut self) {
        self.checks = 0;
    }

    /// Frames 0 (the base) to n in the world frame at `q` (the tool pose not applied).
    pub fn frames(&mut self, q: &JointVector<A>) -> &[Isometry3<f64>] {
        self.frames[0] = self.model.base;
        self.arm.frames_into(q, &mut self.frames[1..]);
        &self.frames
    }

    /// The frames [`frames`](Self::frames) computed last.
    pub fn last_frames(&self) -> &[Isometry3<f64>] {
        &self.frames
    }

    fn segment(&self, link: usize) -> (Point3<f64>, Point3<f64>) {
        (origin(&self.frames[link]), origin(&self.frames[link + 1]))
    }

    /// The capsules of the links that have one, at `q`.
    pub fn capsules(&mut self, q: &JointVector<A>) -> Vec<LinkCapsule> {
        self.frames(q);
        (0..self.dof())
            .filter_map(|link| {
                let radius = self.model.radius(link)?;
                let (a, b) = self.segment(link);
                Some(LinkCapsule { link, a, b, radius })
            })
            .collect()
    }

    /// The smallest distance between a link capsule and an obstacle at `q`, `0` when
    /// anything touches or overlaps, `+∞` without obstacles; NaN when `q` (or a capsule's
    /// end, for an overflowing prismatic joint) is not finite.
    pub fn clearance(&mut self, q: &JointVector<A>) -> f64 {
        self.checks += 1;
        if !finite(q.as_slice()) {
            return f64::NAN;
        }
        self.frames(q);
        let mut clearance = f64::INFINITY;
        for link in 0..self.dof() {
            if let Some(radius) = self.model.radius(link) {
                let (a, b) = self.segment(link);
                let distance = self.scene.distance_to_segment(&a, &b);
                if distance.is_nan() {
                    return f64::NAN;
                }
                clearance = clearance.min(distance - radius);
            }
        }
        clearance.max(0.0)
    }

    /// True when every link capsule is more than `margin` away from every obstacle at `q`.
    /// Stops at the first capsule that is not.
    ///
    /// False when `q` or `margin` is NaN, or `q` is infinite (or a capsule's end is, for an
    /// overflowing prismatic joint): a configuration that cannot be placed is not free, with
    /// or without obstacles.
    pub fn is_free(&mut self, q: &JointVector<A>, margin: f64) -> bool {
        self.checks += 1;
        if margin.is_nan() || !finite(q.as_slice()) {
            return false;
        }
        self.frames(q);
        for link in 0..self.dof() {
            let Some(radius) = self.model.radius(link) else {
                continue;
            };
            let translation = |f: &Isometry3<f64>| {
                let t = &f.translation;
                [t.x, t.y, t.z]
            };
            let (a, b) = (
                translation(&self.frames[link]),
                translation(&self.frames[link + 1]),
            );
            if !finite(&a) || !finite(&b) {
                return false;
            }
            let limit = margin + radius;
            // The parry shape is only built when some obstacle is too near for the cheap
            // bound to clear it.
            let mut probe = None;
            for shape in &self.scene.shapes {
                if shape.lower_bound(&a, &b) > limit {
                    continue;
                }
                let (probe, pose) = probe.get_or_insert_with(|| Probe::new(&a, &b));
                if shape_distance(probe, pose, shape) <= limit {
                    return false;
                }
            }
        }
        true
    }

    /// True when a link capsule touches or overlaps an obstacle at `q`, and when `q` is not
    /// finite (see [`is_free`](Self::is_free)).
    pub fn in_collision(&mut self, q: &JointVector<A>) -> bool {
        !self.is_free(q, 0.0)
    }

    /// The straight-line local planner: true when the joint-space segment from `a` to `b`
    /// is free, checked at `resolution` with the safety margin
    /// [`margin(resolution)`](CollisionModel::margin), which covers the configurations between
    /// the samples too.
    ///
    /// The segment is cut into equal steps, as few as keep the
    /// [`sweep`](CollisionModel::sweep) of each step within `L·resolution`: no point of the
    /// robot moves more than that between two checked configurations. The steps are then at
    /// most `resolution` long in joint space (Euclidean), and longer where the moving
    /// joints swing little of the robot (a wrist that only turns spheres about their
    /// centres costs no samples at all).
    ///
    /// Both ends are checked; the samples in between in bisection order (midpoint first),
    /// which finds a blocked segment sooner than a sweep from one end.
    ///
    /// False, without checking anything, when `a` or `b` is not finite, when `resolution` is
    /// not a finite number > 0, and when the motion would need more than
    /// [`MAX_MOTION_SAMPLES`] samples (a motion of 10¹⁰ rad, say): a motion that cannot be
    /// checked is not free.
    pub fn motion_is_free(
        &mut self,
        a: &JointVector<A>,
        b: &JointVector<A>,
        resolution: f64,
    ) -> bool {
        let checkable =
            valid_resolution(resolution) && finite(a.as_slice()) && finite(b.as_slice());
        if !checkable {
            return false;
        }
        let margin = self.model.margin(resolution);
        let steps = self.model.steps(a.as_slice(), b.as_slice(), resolution);
        if steps > MAX_MOTION_SAMPLES {
            return false;
        }
        if !self.is_free(a, margin) || !self.is_free(b, margin) {
            return false;
        }
        let mut stride = steps.next_power_of_two();
        while stride > 1 {
            let half = stride / 2;
            let mut k = half;
            while k < steps {
                let q = a.lerp(b, k as f64 / steps as f64);
                if !self.is_free(&q, margin) {
                    return false;
                }
                k += stride;
            }
            stride = half;
        }
        true
    }

    /// True when every configuration on the polyline through `path` passes
    /// [`motion_is_free`](Self::motion_is_free) at `resolution` (so false when a waypoint is
    /// not finite).
    pub fn path_is_free(&mut self, path: &[JointVector<A>], resolution: f64) -> bool {
        path.windows(2)
            .all(|w| self.motion_is_free(&w[0], &w[1], resolution))
    }

    /// True when no configuration sampled along the polyline through `path`, at most
    /// `resolution` apart, is in collision (margin 0): a plain re-check, for testing what a
    /// planner returned.
    ///
    /// False, as [`motion_is_free`](Self::motion_is_free), when a waypoint is not finite,
    /// `resolution` is not a finite number > 0, or a segment needs more than
    /// [`MAX_MOTION_SAMPLES`] samples.
    pub fn path_touches_nothing(&mut self, path: &[JointVector<A>], resolution: f64) -> bool {
        let checkable = valid_resolution(resolution) && path.iter().all(|q| finite(q.as_slice()));
        if !checkable {
            return false;
        }
        path.windows(2).all(|w| {
            let steps = sample_count((&w[1] - &w[0]).norm(), resolution);
            if steps > MAX_MOTION_SAMPLES {
                return false;
            }
            (0..=steps).all(|k| {
                let q = w[0].lerp(&w[1], k as f64 / steps as f64);
                !self.in_collision(&q)
            })
        })
    }
}

/// The most configurations [`CollisionChecker::motion_is_free`] and
/// [`CollisionChecker::path_touches_nothing`] check along one straight motion, 2²⁰: at a
/// resolution of 0.02 rad a joint-space motion of about 2·10⁴ rad, far beyond any joint range.
/// A longer motion is reported as not free instead of being checked for hours.
pub const MAX_MOTION_SAMPLES: usize = 1 << 20;

/// True for a resolution the local planner can step by: a finite number > 0.
fn valid_resolution(resolution: f64) -> bool {
    resolution > 0.0 && resolution.is_finite()
}

/// True when every value is finite.
fn finite(values: &[f64]) -> bool {
    values.iter().all(|x| x.is_finite())
}

/// The number of equal steps, each at most `resolution` long, that cover `length`.
pub(crate) fn sample_count(length: f64, resolution: f64) -> usize {
    ((length / resolution).ceil() as usize).max(1)
}
