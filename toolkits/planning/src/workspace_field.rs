//! Workspace potential fields (section 6.3): potentials on control points of the arm, their
//! forces mapped to joint torques through the transposed Jacobian of each point and summed
//! (6.3.2), then the gradient descent of 6.2.3 (6.3.3).
//!
//! Control points:
//! - attractive: the DH frame origins `o_1 … o_n`, each pulled towards its place at the goal
//!   with gain `ζ_i` (quadratic within `d`, conic beyond, as in 6.2.1);
//! - repulsive: the same origins (each as a ball of the radius of the capsules that meet
//!   there), plus one floating point per link capsule: the point of the capsule's axis
//!   nearest to any obstacle. `ρ` is the distance from the control point's ball or capsule
//!   to the nearest obstacle, with gain `η` and distance of influence `ρ₀` (6.3.1).
//!
//! The Jacobian of a point `p` moved by joints `1 … m` has the column `z × (p − o)` for a
//! revolute joint and `z` for a prismatic one, where `z` and `o` are the axis and origin of
//! the frame carrying the joint: frame j−1 for joint j in standard DH (frame 0 being the base
//! after the base pose), frame j in modified DH. A frame origin `o_m` is moved by joints
//! `1 … m` in both conventions; a point `(1 − t)·o_{i−1} + t·o_i` of link capsule i has the
//! Jacobian `(1 − t)·J(o_{i−1}) + t·J(o_i)`. The torque `Σ Jᵀ F` is then exactly `−∇U`
//! wherever `U` is differentiable.
//!
//! The goal is reached when every attractive control point is within `tolerance` (metres,
//! here) of its place at the goal; the path then ends with the straight motion to
//! `q_final` when that motion is free. Joints that move no frame origin (the wrist of a
//! PUMA 560 whose last origins coincide) feel no attraction; their goal values are reached
//! by that final motion only.

use super::collision::origin;
use super::potential::{self, Descent, DescentParams, FieldPath};
use super::{CollisionChecker, PlanError};
use dhgen_kernel::JointKind;
use dhgen_kernel::{Arm, ArmAllocator, JointVector};
use nalgebra::{DefaultAllocator, Point3, U1, Vector3};

/// Gains of the workspace potential.
#[derive(Clone, Debug, PartialEq)]
pub struct WorkspaceField {
    /// Attractive gain ζ_i of the origin of frame i (1 … n), one per joint (each > 0).
    /// Weighting the last one more gives the "follow the leader" motion of 6.3.3.
    pub zeta: Vec<f64>,
    /// Distance where the attractive potential of a point turns from quadratic to conic, m
    /// (> 0).
    pub d: f64,
    /// Repulsive gain η of every repulsive control point (≥ 0).
    pub eta: f64,
    /// Distance of influence ρ₀ of the obstacles, m (> 0).
    pub rho0: f64,
}

impl WorkspaceField {
    /// The same attractive gain `zeta` on each of the `dof` frame origins.
    pub fn uniform(dof: usize, zeta: f64, d: f64, eta: f64, rho0: f64) -> WorkspaceField {
        WorkspaceField {
            zeta: vec![zeta; dof],
            d,
            eta,
            rho0,
        }
    }

    fn check(&self, dof: usize) -> Result<(), PlanError> {
        let bad = |name, reason: String| Err(PlanError::InvalidParameter { name, reason });
        if self.zeta.len() != dof {
            return bad(
                "zeta",
                format!("{} gains, expected {dof} (one per joint)", self.zeta.len()),
            );
        }
        if let Some(z) = self.zeta.iter().find(|z| !(**z > 0.0 && z.is_finite())) {
            return bad("zeta", format!("{z} is not a finite number > 0"));
        }
        for (name, x) in [("d", self.d), ("rho0", self.rho0)] {
            if !(x > 0.0 && x.is_finite()) {
                return bad(name, format!("{x} is not a finite number > 0"));
            }
        }
        if !(self.eta >= 0.0 && self.eta.is_finite()) {
            return bad("eta", format!("{} is not a finite number ≥ 0", self.eta));
        }
        Ok(())
    }
}

/// Gradient descent on a workspace potential for the arm of a [`CollisionChecker`].
pub struct WorkspacePlanner<'c, 'a, A: Arm>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    checker: &'c mut CollisionChecker<'a, A>,
    field: WorkspaceField,
    resolution: f64,
    goal_origins: Vec<Point3<f64>>,
    origins: Vec<Point3<f64>>,
    axes: Vec<(Vector3<f64>, Point3<f64>)>,
}

impl<'c, 'a, A: Arm> WorkspacePlanner<'c, 'a, A>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    /// A planner with the gains `field`, whose every step is checked by the straight-line
    /// local planner at `resolution` (see
    /// [`CollisionChecker::motion_is_free`]).
    pub fn new(
        checker: &'c mut CollisionChecker<'a, A>,
        field: WorkspaceField,
        resolution: f64,
    ) -> Result<Self, PlanError> {
        let n = checker.dof();
        field.check(n)?;
        if !(resolution > 0.0 && resolution.is_finite()) {
            return Err(PlanError::InvalidParameter {
                name: "resolution",
                reason: format!("{resolution} is not a finite number > 0"),
            });
        }
        Ok(WorkspacePlanner {
            checker,
            field,
            resolution,
            goal_origins: vec![Point3::origin(); n + 1],
            origins: vec![Point3::origin(); n + 1],
            axes: vec![(Vector3::zeros(), Point3::origin()); n],
        })
    }

    /// The collision checker.
    pub fn checker(&mut self) -> &mut CollisionChecker<'a, A> {
        self.checker
    }

    /// Sets the goal whose frame origins attract.
    fn set_goal(&mut self, goal: &JointVector<A>) {
        let frames = self.checker.frames(goal);
        for (g, f) in self.goal_origins.iter_mut().zip(frames) {
            *g = origin(f);
        }
    }

    /// The frame origins and joint axes at `q`.
    fn update(&mut self, q: &JointVector<A>) {
        self.checker.frames(q);
        let (frames, model) = (self.checker.last_frames(), self.checker.model());
        for (o, f) in self.origins.iter_mut().zip(frames) {
            *o = origin(f);
        }
        for (j, axis) in self.axes.iter_mut().enumerate() {
            *axis = model.joint_axis(j, &frames[j + 1]);
        }
    }

    /// Adds `J(p)ᵀ F` to `torque` for a point `p` moved by joints `1 … m`.
    fn add_transposed_jacobian(
        &self,
        m: usize,
        p: &Point3<f64>,
        f: &Vector3<f64>,
        torque: &mut [f64],
    ) {
        let model = self.checker.model();
        for (j, (z, o)) in self.axes.iter().enumerate().take(m) {
            let column = match model.joint(j) {
                JointKind::Revolute => z.cross(&(p - o)),
                JointKind::Prismatic => *z,
            };
            torque[j] += f.dot(&column);
        }
    }

    /// The repulsive potential of a control point at distance `rho` from the nearest
    /// obstacle, `away` pointing from the obstacle's nearest point to the control point; its
    /// force (added to `force`) is `η(1/ρ − 1/ρ₀)/ρ² · away/‖away‖`. Infinite when
    /// `rho ≤ 0`.
    fn repulsion(&self, rho: f64, away: Vector3<f64>, force: &mut Vector3<f64>) -> f64 {
        if rho <= 0.0 {
            return f64::INFINITY;
        }
        match potential::repulsive_magnitude(self.field.eta, self.field.rho0, rho) {
            Some((u, magnitude)) => {
                if let Some(direction) = away.try_normalize(0.0) {
                    *force += direction * magnitude;
                }
                u
            }
            None => 0.0,
        }
    }

    /// The workspace potential `U(q)` for the goal last planned for (or set by
    /// [`potential_towards`](Self::potential_towards)), writing the joint torques
    /// `Σ Jᵀ F = −∇U(q)` to `torque`. Infinite when a control point touches an obstacle.
    fn potential_at(&mut self, q: &JointVector<A>, torque: &mut [f64]) -> f64 {
        self.update(q);
        torque.iter_mut().for_each(|t| *t = 0.0);
        let n = self.origins.len() - 1;
        let rho0 = self.field.rho0;
        let mut total = 0.0;
        for m in 1..=n {
            let o = self.origins[m];
            // Attraction of origin m towards its goal place.
            let mut f = [0.0; 3];
            total += potential::attractive(
                self.field.zeta[m - 1],
                self.field.d,
                o.coords.as_slice(),
                self.goal_origins[m].coords.as_slice(),
                &mut f,
            );
            let mut force = Vector3::from(f);
            // Repulsion of origin m, a ball as wide as the capsules meeting there.
            let model = self.checker.model();
            let radius = model
                .radius(m - 1)
                .unwrap_or(0.0)
                .max(model.radius(m).unwrap_or(0.0));
            if let Some(p) = self
                .checker
                .scene()
                .nearest_to_segment(&o, &o, rho0 + radius)
            {
                total += self.repulsion(p.distance - radius, o - p.on_obstacle, &mut force);
            }
            self.add_transposed_jacobian(m, &o, &force, torque);
        }
        // One floating repulsive point per link capsule.
        for link in 0..n {
            let Some(radius) = self.checker.model().radius(link) else {
                continue;
            };
            let (a, b) = (self.origins[link], self.origins[link + 1]);
            let Some(p) = self
                .checker
                .scene()
                .nearest_to_segment(&a, &b, rho0 + radius)
            else {
                continue;
            };
            let mut force = Vector3::zeros();
            total += self.repulsion(p.distance - radius, p.on_robot - p.on_obstacle, &mut force);
            let axis = b - a;
            let t = if axis.norm_squared() > 0.0 {
                ((p.on_robot - a).dot(&axis) / axis.norm_squared()).clamp(0.0, 1.0)
            } else {
                0.0
            };
            self.add_transposed_jacobian(link, &a, &(force * (1.0 - t)), torque);
            self.add_transposed_jacobian(link + 1, &b, &(force * t), torque);
        }
        total
    }

    /// The workspace potential `U(q)` with the control points attracted to their places at
    /// `goal`, writing the joint torques `Σ Jᵀ F = −∇U(q)` to `torque` (one per joint).
    pub fn potential_towards(
        &mut self,
        q: &JointVector<A>,
        goal: &JointVector<A>,
        torque: &mut [f64],
    ) -> f64 {
        self.set_goal(goal);
        self.potential_at(q, torque)
    }

    /// Plans from `start` to `goal` by gradient descent on the workspace potential.
    /// `params.tolerance` is in metres here: the largest distance of an attractive control
    /// point from its goal place that counts as arrived.
    ///
    /// Errors: a start or goal outside the joint ranges or not free (clearance within the
    /// margin of `resolution`); [`PlanError::LocalMinimum`] when stuck;
    /// [`PlanError::IterationLimit`] when the step budget runs out.
    pub fn plan(
        &mut self,
        start: &JointVector<A>,
        goal: &JointVector<A>,
        params: &DescentParams,
    ) -> Result<FieldPath<JointVector<A>>, PlanError> {
        let margin = self.checker.model().margin(self.resolution);
        for (which, q) in [("start", start), ("goal", goal)] {
            let bad = |reason| PlanError::InvalidConfiguration { which, reason };
            self.checker
                .check_configuration(q.as_slice())
                .map_err(bad)?;
            if !self.checker.is_free(q, margin) {
                return Err(bad(format!(
                    "the arm is within the safety margin {margin:.4} m of an obstacle"
                )));
            }
        }
        self.set_goal(goal);
        let dim = self.checker.arm().dim();
        let found = potential::descend(self, start.as_slice(), goal.as_slice(), params)?;
        Ok(FieldPath {
            waypoints: found
                .waypoints
                .iter()
                .map(|q| JointVector::<A>::from_column_slice_generic(dim, U1, q))
                .collect(),
            iterations: found.iterations,
            random_walks: found.random_walks,
            ends_at_goal: found.ends_at_goal,
        })
    }

    fn vector(&self, q: &[f64]) -> JointVector<A> {
        JointVector::<A>::from_column_slice_generic(self.checker.arm().dim(), U1, q)
    }
}

impl<A: Arm> Descent for WorkspacePlanner<'_, '_, A>
where
    DefaultAllocator: ArmAllocator<A::Dof>,
{
    fn dim(&self) -> usize {
        self.checker.dof()
    }

    fn bounds(&self, j: usize) -> [f64; 2] {
        self.checker.joint_range(j)
    }

    fn potential(&mut self, q: &[f64], force: &mut [f64]) -> f64 {
        let q = self.vector(q);
        self.potential_at(&q, force)
    }

    fn motion_is_free(&mut self, a: &[f64], b: &[f64]) -> bool {
        let (a, b) = (self.vector(a), self.vector(b));
        self.checker.motion_is_free(&a, &b, self.resolution)
    }

    fn reached(&mut self, q: &[f64], _goal: &[f64], tolerance: f64) -> bool {
        let q = self.vector(q);
        self.update(&q);
        self.origins
            .iter()
            .zip(&self.goal_origins)
            .all(|(o, g)| (o - g).norm() < tolerance)
    }
}
