//! Configuration-space potential fields (section 6.2) and the gradient-descent planner
//! (6.2.3), with local minima detected and escaped by random walks.
//!
//! The robot is a point `q` in configuration space, attracted to `q_final` and repelled by
//! the configuration-space obstacles:
//!
//! - attractive (6.2.1): `U_att = ½ζρ_f²` for `ρ_f = ‖q − q_final‖ ≤ d`, and the conic
//!   `dζρ_f − ½ζd²` beyond, so that the force is `−ζ(q − q_final)` near the goal and has the
//!   constant magnitude `dζ` far from it;
//! - repulsive (6.2.2), summed over the obstacles: `U_rep = ½η(1/ρ − 1/ρ₀)²` within the
//!   distance of influence `ρ₀` of an obstacle, 0 beyond, where `ρ` is the distance to the
//!   obstacle and its gradient `(q − b)/‖q − b‖` points away from the nearest obstacle point
//!   `b`.
//!
//! Obstacles come from a [`CSpaceObstacles`]: explicit convex regions
//! ([`ConvexCSpaceObstacles`], the setting of the text), or the sampled obstacle region of a
//! 2-joint arm ([`CSpaceGrid`](super::CSpaceGrid)).
//!
//! Gradient descent (6.2.3) steps `q ← q + α F/‖F‖` until `‖q − q_final‖ < ε` (for the
//! workspace field: until every control point is within ε of its goal place). The force
//! is first projected onto the feasible directions (a joint at a limit that the force
//! pushes outward does not move), and `α` is at most `step` and at most `‖q − q_final‖`,
//! halved until the potential drops by at least `10⁻⁴ α ‖F‖` (Armijo's rule): a step never
//! raises the potential, so the descent cannot overshoot the goal and oscillate around it.
//! Lack of progress (the potential has not dropped by `min_decrease` over
//! `stall_iterations` steps), a vanishing projected force, no step that lowers the
//! potential, or a step blocked by an obstacle mark a local minimum; a random walk of `walk_steps` steps, each joint moving
//! uniformly within `±walk_step`, then tries to leave it. When `random_walks` walks have
//! not escaped, planning fails with [`PlanError::LocalMinimum`].
//!
//! ```
//! use dhgen::planning::{CSpaceField, ConvexCSpaceObstacles, ConvexRegion, DescentParams};
//!
//! let obstacles = ConvexCSpaceObstacles::new(2, vec![
//!     ConvexRegion::Ball { center: vec![0.5, 0.05], radius: 0.15 },
//! ]).unwrap();
//! let field = CSpaceField { zeta: 1.0, d: 0.5, eta: 1e-3, rho0: 0.2 };
//! let path = dhgen::planning::potential::plan(
//!     &field, obstacles, &[0.0, 0.0], &[1.0, 0.0], &DescentParams::default(),
//! ).unwrap();
//! assert_eq!(path.waypoints.last().unwrap(), &vec![1.0, 0.0]);
//! ```

use super::PlanError;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Gains of the configuration-space potential of 6.2.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CSpaceField {
    /// Attractive gain ζ (> 0).
    pub zeta: f64,
    /// Distance from the goal where the attractive potential turns from quadratic to conic
    /// (> 0).
    pub d: f64,
    /// Repulsive gain η (≥ 0; 0 switches repulsion off).
    pub eta: f64,
    /// Distance of influence ρ₀ of an obstacle (> 0).
    pub rho0: f64,
}

impl CSpaceField {
    fn check(&self) -> Result<(), PlanError> {
        positive("zeta", self.zeta)?;
        positive("d", self.d)?;
        positive("rho0", self.rho0)?;
        if !(self.eta >= 0.0 && self.eta.is_finite()) {
            return Err(PlanError::InvalidParameter {
                name: "eta",
                reason: format!("{} is not a finite number ≥ 0", self.eta),
            });
        }
        Ok(())
    }

    /// The attractive potential at `q` (6.2.1); adds the force `−∇U_att` to `force`.
    pub fn attractive(&self, q: &[f64], goal: &[f64], force: &mut [f64]) -> f64 {
        attractive(self.zeta, self.d, q, goal, force)
    }

    /// The repulsive potential of one obstacle at distance `rho` with nearest point `b`
    /// (6.2.2); adds its force to `force`. Infinite, with no force, when `rho ≤ 0` (in
    /// collision).
    pub fn repulsive(&self, q: &[f64], rho: f64, b: &[f64], force: &mut [f64]) -> f64 {
        if rho <= 0.0 {
            return f64::INFINITY;
        }
        let Some(magnitude) = repulsive_magnitude(self.eta, self.rho0, rho) else {
            return 0.0;
        };
        let gap: f64 = q
            .iter()
            .zip(b)
            .map(|(x, y)| (x - y) * (x - y))
            .sum::<f64>()
            .sqrt();
        if gap > 0.0 {
            for ((f, x), y) in force.iter_mut().zip(q).zip(b) {
                *f += magnitude.1 * (x - y) / gap;
            }
        }
        magnitude.0
    }
}

/// `½ζρ²` within `d` of the goal, `dζρ − ½ζd²` beyond; the force `−∇U` is added to `force`.
/// Shared with the workspace field, whose control points have the same attractive law.
pub(crate) fn attractive(zeta: f64, d: f64, q: &[f64], goal: &[f64], force: &mut [f64]) -> f64 {
    let rho = q
        .iter()
        .zip(goal)
        .map(|(x, g)| (x - g) * (x - g))
        .sum::<f64>()
        .sqrt();
    let (potential, scale) = if rho <= d {
        (0.5 * zeta * rho * rho, zeta)
    } else {
        (d * zeta * rho - 0.5 * zeta * d * d, d * zeta / rho)
    };
    for ((f, x), g) in force.iter_mut().zip(q).zip(goal) {
        *f -= scale * (x - g);
    }
    potential
}

/// `(U_rep, |F_rep|)` at distance `rho` (> 0) from an obstacle, `None` beyond `rho0`.
pub(crate) fn repulsive_magnitude(eta: f64, rho0: f64, rho: f64) -> Option<(f64, f64)> {
    if rho > rho0 {
        return None;
    }
    let excess = 1.0 / rho - 1.0 / rho0;
    Some((0.5 * eta * excess * excess, eta * excess / (rho * rho)))
}

fn positive(name: &'static str, x: f64) -> Result<(), PlanError> {
    if x > 0.0 && x.is_finite() {
        Ok(())
    } else {
        Err(PlanError::InvalidParameter {
            name,
            reason: format!("{x} is not a finite number > 0"),
        })
    }
}

/// Obstacles of a configuration space, as the potential-field planner needs them.
pub trait CSpaceObstacles {
    /// The dimension of the configuration space.
    fn dim(&self) -> usize;

    /// The range `[lower, upper]` of coordinate `j` (may be infinite); steps and random
    /// walks stay inside it.
    fn bounds(&self, j: usize) -> [f64; 2];

    /// Calls `visit(ρ, b)` for every obstacle: the distance `ρ` from `q` to it (`≤ 0` when
    /// `q` is inside) and its point `b` nearest to `q`. Obstacles farther than `within` may
    /// be skipped.
    fn nearest(&mut self, q: &[f64], within: f64, visit: &mut dyn FnMut(f64, &[f64]));

    /// Whether the straight motion from `a` to `b` is collision-free.
    fn motion_is_free(&mut self, a: &[f64], b: &[f64]) -> bool;
}

/// A convex configuration-space obstacle.
#[derive(Clone, Debug, PartialEq)]
pub enum ConvexRegion {
    /// The points within `radius` of `center`.
    Ball {
        /// Centre.
        center: Vec<f64>,
        /// Radius (> 0).
        radius: f64,
    },
    /// The axis-aligned box `lower ≤ q ≤ upper`.
    Box {
        /// Lower corner.
        lower: Vec<f64>,
        /// Upper corner (each coordinate > the lower one).
        upper: Vec<f64>,
    },
}

impl ConvexRegion {
    /// The distance from `q` (`≤ 0` inside) and the nearest point, written to `b`.
    fn nearest(&self, q: &[f64], b: &mut [f64]) -> f64 {
        match self {
            ConvexRegion::Ball { center, radius } => {
                let gap = q
                    .iter()
                    .zip(center)
                    .map(|(x, c)| (x - c) * (x - c))
                    .sum::<f64>()
                    .sqrt();
                for ((bi, x), c) in b.iter_mut().zip(q).zip(center) {
                    *bi = if gap > 0.0 {
                        c + radius * (x - c) / gap
                    } else {
                        *x
                    };
                }
                gap - radius
            }
            ConvexRegion::Box { lower, upper } => {
                let mut outside = 0.0;
                let mut inside = f64::INFINITY;
                for (j, bj) in b.iter_mut().enumerate() {
                    *bj = q[j].clamp(lower[j], upper[j]);
                    outside += (q[j] - *bj) * (q[j] - *bj);
                    inside = inside.min((q[j] - lower[j]).min(upper[j] - q[j]));
                }
                if outside > 0.0 {
                    outside.sqrt()
                } else {
                    // Inside: minus the depth, and `b` stays at `q` (no outward direction
                    // is needed: the planner never steps inside).
                    -inside
                }
            }
        }
    }
}

/// Explicit convex obstacles in an n-dimensional configuration space (the setting of 6.2).
#[derive(Clone, Debug, PartialEq)]
pub struct ConvexCSpaceObstacles {
    dim: usize,
    regions: Vec<ConvexRegion>,
    bounds: Vec<[f64; 2]>,
    scratch: Vec<f64>,
}

impl ConvexCSpaceObstacles {
    /// Obstacles of a `dim`-dimensional space, which is unbounded until
    /// [`with_bounds`](Self::with_bounds).
    pub fn new(dim: usize, regions: Vec<ConvexRegion>) -> Result<Self, PlanError> {
        for (index, r) in regions.iter().enumerate() {
            let bad = |reason: String| PlanError::InvalidObstacle { index, reason };
            match r {
                ConvexRegion::Ball { center, radius } => {
                    if center.len() != dim {
                        return Err(bad(format!(
                            "centre has {} coordinates, expected {dim}",
                            center.len()
                        )));
                    }
                    if center.iter().any(|x| !x.is_finite())
                        || !(*radius > 0.0 && radius.is_finite())
                    {
                        return Err(bad(format!(
                            "ball {center:?}, radius {radius}: needs a finite centre and a finite radius > 0"
                        )));
                    }
                }
                ConvexRegion::Box { lower, upper } => {
                    if lower.len() != dim || upper.len() != dim {
                        return Err(bad(format!(
                            "corners have {} and {} coordinates, expected {dim}",
                            lower.len(),
                            upper.len()
                        )));
                    }
                    if lower.iter().chain(upper).any(|x| !x.is_finite())
                        || lower.iter().zip(upper).any(|(l, u)| l >= u)
                    {
                        return Err(bad(format!(
                            "box {lower:?} to {upper:?}: needs finite corners, lower < upper"
                        )));
                    }
                }
            }
        }
        Ok(ConvexCSpaceObstacles {
            dim,
            regions,
            bounds: vec![[f64::NEG_INFINITY, f64::INFINITY]; dim],
            scratch: vec![0.0; dim],
        })
    }

    /// Limits the space to the box `bounds` (one `[lower, upper]` per coordinate).
    pub fn with_bounds(mut self, bounds: Vec<[f64; 2]>) -> Result<Self, PlanError> {
        if bounds.len() != self.dim
            || bounds
                .iter()
                .any(|[l, u]| l.partial_cmp(u) != Some(core::cmp::Ordering::Less))
        {
            return Err(PlanError::InvalidParameter {
                name: "bounds",
                reason: format!(
                    "{bounds:?}: expected {} ranges with lower < upper",
                    self.dim
                ),
            });
        }
        self.bounds = bounds;
        Ok(self)
    }

    /// The obstacles.
    pub fn regions(&self) -> &[ConvexRegion] {
        &self.regions
    }

    /// The distance from `q` to the nearest obstacle (`≤ 0` inside one), `+∞` without any;
    /// NaN when `q` has a NaN coordinate.
    pub fn distance(&mut self, q: &[f64]) -> f64 {
        let b = &mut self.scratch;
        // Not `f64::min`, which would drop a NaN distance.
        self.regions
            .iter()
            .map(|r| r.nearest(q, b))
            .fold(
                f64::INFINITY,
                |m, d| if d < m || d.is_nan() { d } else { m },
            )
    }
}

impl CSpaceObstacles for ConvexCSpaceObstacles {
    fn dim(&self) -> usize {
        self.dim
    }

    fn bounds(&self, j: usize) -> [f64; 2] {
        self.bounds[j]
    }

    fn nearest(&mut self, q: &[f64], within: f64, visit: &mut dyn FnMut(f64, &[f64])) {
        for r in &self.regions {
            let rho = r.nearest(q, &mut self.scratch);
            if rho <= within {
                visit(rho, &self.scratch);
            }
        }
    }

    /// Exact: advances along the segment by the distance to the nearest obstacle, which
    /// no obstacle point can be closer than (conservative advancement). A segment that
    /// passes closer than 10⁻⁹ to an obstacle counts as blocked, and so does one with an
    /// end that is not finite.
    fn motion_is_free(&mut self, a: &[f64], b: &[f64]) -> bool {
        if !a.iter().chain(b).all(|x| x.is_finite()) {
            return false;
        }
        let length = a
            .iter()
            .zip(b)
            .map(|(x, y)| (x - y) * (x - y))
            .sum::<f64>()
            .sqrt();
        let mut p = a.to_vec();
        let mut t = 0.0;
        // Each step advances by at least 1e-9; a cap keeps a grazing segment from taking
        // forever, and counts it as blocked.
        for _ in 0..100_000 {
            for ((pj, x), y) in p.iter_mut().zip(a).zip(b) {
                *pj = x + t * (y - x);
            }
            let clearance = self.distance(&p);
            if clearance <= 1e-9 {
                return false;
            }
            if t >= 1.0 {
                return true;
            }
            t = if length > 0.0 {
                (t + clearance / length).min(1.0)
            } else {
                1.0
            };
        }
        false
    }
}

/// Step size, tolerance, budgets and random-walk settings of gradient descent (6.2.3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DescentParams {
    /// Largest step length α in joint space (> 0); the line search shortens it.
    pub step: f64,
    /// Goal tolerance ε: done when `‖q − q_final‖ < ε` (> 0). For the workspace field,
    /// metres: done when every attractive control point is within ε of its goal place.
    pub tolerance: f64,
    /// Gradient steps allowed in all.
    pub max_iterations: usize,
    /// Steps without progress after which the descent is in a local minimum (≥ 1).
    pub stall_iterations: usize,
    /// The drop of the lowest potential seen that counts as progress, relative to
    /// `max(1, |U|)` (≥ 0).
    pub min_decrease: f64,
    /// Random walks allowed before the local minimum is reported as a failure.
    pub random_walks: usize,
    /// Steps of one random walk (≥ 1).
    pub walk_steps: usize,
    /// Largest move of one joint in one random-walk step (> 0, and at most `f64::MAX / 2` so
    /// that the range `±walk_step` has a finite width).
    pub walk_step: f64,
    /// Seed of the random walks.
    pub seed: u64,
}

impl Default for DescentParams {
    /// α = 0.01, ε = 0.01, 20 000 steps, a local minimum after 50 steps without a 10⁻⁶ drop,
    /// 10 random walks of 30 steps of up to 0.1, seed 0.
    fn default() -> Self {
        DescentParams {
            step: 0.01,
            tolerance: 0.01,
            max_iterations: 20_000,
            stall_iterations: 50,
            min_decrease: 1e-6,
            random_walks: 10,
            walk_steps: 30,
            walk_step: 0.1,
            seed: 0,
        }
    }
}

impl DescentParams {
    fn check(&self) -> Result<(), PlanError> {
        positive("step", self.step)?;
        positive("tolerance", self.tolerance)?;
        positive("walk_step", self.walk_step)?;
        // The walk draws from [−walk_step, walk_step], whose width must be a number.
        if !(2.0 * self.walk_step).is_finite() {
            return Err(PlanError::InvalidParameter {
                name: "walk_step",
                reason: format!(
                    "{} is too large: the range ±walk_step must have a finite width",
                    self.walk_step
                ),
            });
        }
        if self.stall_iterations == 0 || self.walk_steps == 0 {
            return Err(PlanError::InvalidParameter {
                name: if self.stall_iterations == 0 {
                    "stall_iterations"
                } else {
                    "walk_steps"
                },
                reason: "must be at least 1".into(),
            });
        }
        if !(self.min_decrease >= 0.0 && self.min_decrease.is_finite()) {
            return Err(PlanError::InvalidParameter {
                name: "min_decrease",
                reason: format!("{} is not a finite number ≥ 0", self.min_decrease),
            });
        }
        Ok(())
    }
}

/// A path found by gradient descent.
#[derive(Clone, Debug, PartialEq)]
pub struct FieldPath<V = Vec<f64>> {
    /// The iterates `q⁰ = q_init, q¹, …`, random-walk steps included, ending at the goal.
    pub waypoints: Vec<V>,
    /// Gradient steps taken.
    pub iterations: usize,
    /// Random walks taken to leave local minima (all of which were escaped).
    pub random_walks: usize,
    /// True when the path ends exactly at `q_final`; false when the last iterate was within
    /// the tolerance but the straight motion from it to `q_final` was blocked (then the
    /// path ends at that iterate).
    pub ends_at_goal: bool,
}

/// What gradient descent needs of a potential field.
pub(crate) trait Descent {
    fn dim(&self) -> usize;
    fn bounds(&self, j: usize) -> [f64; 2];
    /// `U(q)`, writing `F(q) = −∇U(q)` to `force`.
    fn potential(&mut self, q: &[f64], force: &mut [f64]) -> f64;
    fn motion_is_free(&mut self, a: &[f64], b: &[f64]) -> bool;
    /// Whether `q` counts as having reached the goal.
    fn reached(&mut self, q: &[f64], goal: &[f64], tolerance: f64) -> bool {
        distance(q, goal) < tolerance
    }
}

pub(crate) fn distance(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// Gradient descent with random-walk escapes (6.2.3), shared by the configuration-space and
/// workspace fields. The start must be free (the caller checks).
pub(crate) fn descend(
    field: &mut impl Descent,
    start: &[f64],
    goal: &[f64],
    params: &DescentParams,
) -> Result<FieldPath, PlanError> {
    params.check()?;
    let n = field.dim();
    let mut rng = ChaCha8Rng::seed_from_u64(params.seed);
    let mut q = start.to_vec();
    let mut next = vec![0.0; n];
    let mut force = vec![0.0; n];
    let mut trial_force = vec![0.0; n];
    let mut waypoints = vec![q.clone()];
    let mut walks = 0;
    let mut best = field.potential(&q, &mut force);
    let mut since_best = 0;
    for iteration in 0..params.max_iterations {
        if field.reached(&q, goal, params.tolerance) {
            let ends_at_goal = q == goal || field.motion_is_free(&q, goal);
            if q != goal && ends_at_goal {
                waypoints.push(goal.to_vec());
            }
            return Ok(FieldPath {
                waypoints,
                iterations: iteration,
                random_walks: walks,
                ends_at_goal,
            });
        }
        let potential = field.potential(&q, &mut force);
        if potential < best - params.min_decrease * best.abs().max(1.0) {
            best = potential;
            since_best = 0;
        } else {
            since_best += 1;
        }
        // A joint at a bound whose force pushes outward takes no share of the step (the
        // gradient projected onto the feasible directions).
        for (j, f) in force.iter_mut().enumerate() {
            let [lo, hi] = field.bounds(j);
            if (q[j] <= lo && *f < 0.0) || (q[j] >= hi && *f > 0.0) {
                *f = 0.0;
            }
        }
        let norm = force.iter().map(|f| f * f).sum::<f64>().sqrt();
        let mut stuck = since_best >= params.stall_iterations || norm.is_nan() || norm <= 1e-12;
        if !stuck {
            // Backtracking line search: halve the step until the potential drops by a
            // fraction of what the slope promises (Armijo's rule), so no step overshoots a
            // goal that the joint-space distance does not see (joints that move no control
            // point keep that distance large).
            let mut step = params.step.min(distance(&q, goal));
            let accepted = loop {
                for j in 0..n {
                    let [lo, hi] = field.bounds(j);
                    next[j] = (q[j] + step * force[j] / norm).clamp(lo, hi);
                }
                if next == q {
                    break false;
                }
                let trial = field.potential(&next, &mut trial_force);
                if trial <= potential - 1e-4 * step * norm {
                    break true;
                }
                step *= 0.5;
                if step < params.step * 1e-6 {
                    break false;
                }
            };
            if accepted && field.motion_is_free(&q, &next) {
                q.copy_from_slice(&next);
                waypoints.push(q.clone());
            } else {
                // The field pushes into an obstacle or a joint limit, or no step lowers it:
                // no way on.
                stuck = true;
            }
        }
        if stuck {
            if walks == params.random_walks {
                return Err(PlanError::LocalMinimum {
                    distance_to_goal: distance(&q, goal),
                    potential,
                    q,
                    iterations: iteration,
                    random_walks: walks,
                });
            }
            walks += 1;
            for _ in 0..params.walk_steps {
                for j in 0..n {
                    let [lo, hi] = field.bounds(j);
                    let v = rng.random_range(-params.walk_step..=params.walk_step);
                    next[j] = (q[j] + v).clamp(lo, hi);
                }
                if field.motion_is_free(&q, &next) {
                    q.copy_from_slice(&next);
                    waypoints.push(q.clone());
                }
            }
            best = field.potential(&q, &mut force);
            since_best = 0;
        }
    }
    Err(PlanError::IterationLimit {
        iterations: params.max_iterations,
        distance_to_goal: distance(&q, goal),
    })
}

/// The C-space field over a set of obstacles, as [`Descent`] needs it.
struct CSpaceProblem<'f, O> {
    field: &'f CSpaceField,
    obstacles: O,
    goal: Vec<f64>,
}

impl<O: CSpaceObstacles> Descent for CSpaceProblem<'_, O> {
    fn dim(&self) -> usize {
        self.obstacles.dim()
    }

    fn bounds(&self, j: usize) -> [f64; 2] {
        self.obstacles.bounds(j)
    }

    fn potential(&mut self, q: &[f64], force: &mut [f64]) -> f64 {
        force.iter_mut().for_each(|f| *f = 0.0);
        let mut potential = self.field.attractive(q, &self.goal, force);
        let field = self.field;
        self.obstacles.nearest(q, field.rho0, &mut |rho, b| {
            potential += field.repulsive(q, rho, b, force);
        });
        potential
    }

    fn motion_is_free(&mut self, a: &[f64], b: &[f64]) -> bool {
        self.obstacles.motion_is_free(a, b)
    }
}

/// Plans from `start` to `goal` by gradient descent on the C-space potential `field` over
/// `obstacles` (6.2.3).
///
/// Errors: a bad parameter, a start or goal of the wrong dimension, not finite, outside the
/// bounds or inside an obstacle; [`PlanError::LocalMinimum`] when the descent is stuck and
/// the random walks do not free it; [`PlanError::IterationLimit`] when the step budget runs
/// out.
pub fn plan<O: CSpaceObstacles>(
    field: &CSpaceField,
    mut obstacles: O,
    start: &[f64],
    goal: &[f64],
    params: &DescentParams,
) -> Result<FieldPath, PlanError> {
    field.check()?;
    let n = obstacles.dim();
    for (which, q) in [("start", start), ("goal", goal)] {
        let bad = |reason: String| PlanError::InvalidConfiguration { which, reason };
        if q.len() != n {
            return Err(bad(format!("{} coordinates, expected {n}", q.len())));
        }
        for (j, x) in q.iter().enumerate() {
            // An unbounded space admits ±∞ between its bounds.
            if !x.is_finite() {
                return Err(bad(format!("coordinate {j} = {x} is not finite")));
            }
            let [lo, hi] = obstacles.bounds(j);
            if !(lo <= *x && *x <= hi) {
                return Err(bad(format!("coordinate {j} = {x} is outside [{lo}, {hi}]")));
            }
        }
        let mut inside = None;
        obstacles.nearest(q, 0.0, &mut |rho, _| {
            if rho <= 0.0 {
                inside = Some(rho);
            }
        });
        if let Some(rho) = inside {
            return Err(bad(format!("{q:?} is inside an obstacle (distance {rho})")));
        }
        if !obstacles.motion_is_free(q, q) {
            return Err(bad(format!("{q:?} is in collision")));
        }
    }
    let mut problem = CSpaceProblem {
        field,
        obstacles,
        goal: goal.to_vec(),
    };
    descend(&mut problem, start, goal, params)
}
