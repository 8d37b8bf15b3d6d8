//! Path planning (sections 6.1 to 6.4 of the reference text): collision checking, potential
//! fields in configuration space and in the workspace, and probabilistic roadmaps.
//!
//! Everything here is generic over [`Arm`](dhgen_kernel::Arm), so the same planner runs on a
//! generated module's `Robot` (allocation-free kinematics, the fast path) and on the runtime
//! `dhgen::Robot`.
//!
//! - [`collision`]: the robot as capsules around its DH segments (the description's
//!   per-link `collision = { radius }`), obstacles (spheres, boxes, capsules), distance and
//!   closest-point queries, and the straight-line local planner.
//! - [`potential`]: the configuration-space potential field of 6.2 and the gradient-descent
//!   planner of 6.2.3 with random-walk escapes from local minima.
//! - [`cspace_grid`]: the configuration-space obstacle region QO of a 2-joint arm, sampled
//!   on a grid: for pictures and as the obstacles of a C-space potential field.
//! - [`workspace_field`]: the workspace potential field of 6.3: forces on control points
//!   mapped to joint torques through transposed point Jacobians.
//! - [`prm`]: the probabilistic roadmap of 6.4.
//!
//! # When is a path collision-free?
//! A configuration is *free* when the clearance between the robot's capsules and the
//! obstacles exceeds a safety margin `δ = L·r/2`, where `r` is the resolution of the local
//! planner and `L` is a bound on how far any point of the robot moves per unit of joint
//! motion ([`CollisionModel::lipschitz`](crate::CollisionModel::lipschitz)). The local planner
//! checks a straight motion at samples between which no point of the robot moves more than
//! `L·r` (so at most `r` apart in joint space), so every configuration between two samples
//! is within `δ` of one of them in every point of the robot: the whole motion is free, not
//! just its samples. This is why the paths the planners return stay collision-free when they
//! are re-checked at any finer resolution.
//!
//! Self-collisions between the robot's own links are not modelled.

pub mod collision;
pub mod cspace_grid;
pub mod potential;
pub mod prm;
pub mod workspace_field;

pub use collision::{CollisionChecker, CollisionModel, Obstacle, Scene};
pub use cspace_grid::CSpaceGrid;
pub use potential::{
    CSpaceField, CSpaceObstacles, ConvexCSpaceObstacles, ConvexRegion, DescentParams, FieldPath,
};
pub use prm::{Prm, PrmConfig, PrmPath, PrmStats};
pub use workspace_field::{WorkspaceField, WorkspacePlanner};

/// Why planning could not start or did not succeed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum PlanError {
    /// An obstacle of the scene is malformed (`index` counts from 0).
    #[error("obstacle {index}: {reason}")]
    InvalidObstacle {
        /// Position of the obstacle in the list given to the scene.
        index: usize,
        /// What is wrong with it.
        reason: String,
    },
    /// The robot's collision geometry is missing or cannot be bounded.
    #[error("collision geometry: {0}")]
    InvalidGeometry(String),
    /// A parameter of a planner is out of its range.
    #[error("parameter `{name}`: {reason}")]
    InvalidParameter {
        /// The parameter's name.
        name: &'static str,
        /// What is wrong with its value.
        reason: String,
    },
    /// The start or goal configuration cannot be used.
    #[error("{which} configuration: {reason}")]
    InvalidConfiguration {
        /// `"start"` or `"goal"`.
        which: &'static str,
        /// Why (wrong length, outside the limits, in collision, ...).
        reason: String,
    },
    /// Gradient descent got stuck in a local minimum of the potential and the random walks
    /// did not get it out.
    #[error(
        "local minimum at q = {q:?} (potential {potential:.6}, {distance_to_goal:.4} from the goal in joint space) \
         after {iterations} iterations: no progress, and {random_walks} random walks did not escape it"
    )]
    LocalMinimum {
        /// Where the descent stopped.
        q: Vec<f64>,
        /// The potential there.
        potential: f64,
        /// Euclidean joint-space distance from there to the goal.
        distance_to_goal: f64,
        /// Gradient steps taken in all.
        iterations: usize,
        /// Random walks tried (all of them failed).
        random_walks: usize,
    },
    /// Gradient descent used up its iteration budget while still making progress.
    #[error(
        "no convergence within {iterations} iterations ({distance_to_goal:.4} from the goal in joint space)"
    )]
    IterationLimit {
        /// The budget.
        iterations: usize,
        /// Euclidean joint-space distance from the last iterate to the goal.
        distance_to_goal: f64,
    },
    /// The roadmap could not connect start and goal within its budget.
    #[error("no path: {reason} (roadmap of {nodes} nodes in {components} connected components)")]
    NoPath {
        /// Nodes in the roadmap when planning gave up.
        nodes: usize,
        /// Its connected components.
        components: usize,
        /// Which budget ran out, or what could not be connected.
        reason: String,
    },
}
