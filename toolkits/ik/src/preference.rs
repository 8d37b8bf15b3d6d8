//! Redundancy resolution for numeric IK: among the configurations that reach a pose, the one a
//! secondary objective prefers (TRAC-IK's `Distance` and `Manip1` solve types).
//!
//! See [`NumericIk::solve_preferring`].

use super::numeric::{IkError, NumericIk, Solution, length_scale};
use dhgen_kernel::{Arm, ArmAllocator};
use dhgen_motion::velocity::{Axes, JacobianSvd, manipulability_gradient};
use nalgebra::{DefaultAllocator, Dim, Isometry3, OMatrix, OVector, U6};

/// What a redundant arm's solution should prefer among the configurations that reach the
/// pose; see [`NumericIk::solve_preferring`].
#[derive(Clone, Copy)]
pub enum Preference<'a, D: Dim>
where
    DefaultAllocator: nalgebra::allocator::Allocator<D>,
{
    /// The solution nearest this posture: the least `|q − posture|²` (joint by joint, in
    /// radians and metres, angles not wrapped). TRAC-IK's `Distance` with the posture the
    /// seed; a rest posture, or the mid-range of the limits, keeps an arm away from its limits.
    Posture(&'a OVector<f64, D>),
    /// The solution of the largest Yoshikawa manipulability of the rows `Axes` of the
    /// Jacobian (TRAC-IK's `Manip1` with [`Axes::All`]): farthest from singularities.
    Manipulability(Axes),
    /// The solution of the least cost by your function, which returns the cost at `q` and its
    /// gradient ∂cost/∂q (for example joint-limit avoidance, a weighted posture, a distance
    /// to an obstacle, or a sum of these). A non-finite cost or gradient, or a gradient of
    /// another length than `q`'s, ends the iteration where it is. The gain of a step is the difference of two costs, so near the optimum the
    /// rounding of the cost, not of the step, sets how stationary the result is.
    ///
    /// ```
    /// use dhgen::ik::{NumericIk, Preference};
    /// use dhgen::nalgebra::SVector;
    /// use dhgen::Arm;
    /// dhgen::robot!(mod panda = "../../robots/panda.toml");
    ///
    /// // Away from the joint limits: Σ ((q − mid) / range)², and its gradient.
    /// let arm = panda::Robot;
    /// let away = |q: &SVector<f64, 7>| {
    ///     let mut grad = SVector::<f64, 7>::zeros();
    ///     let mut cost = 0.0;
    ///     for k in 0..7 {
    ///         let [lo, hi] = arm.limits(k).unwrap();
    ///         let x = (q[k] - (lo + hi) / 2.0) / (hi - lo);
    ///         cost += x * x;
    ///         grad[k] = 2.0 * x / (hi - lo);
    ///     }
    ///     (cost, grad)
    /// };
    /// let target = arm.fk(&SVector::from([0.1, -0.4, 0.2, -1.8, 0.3, 1.5, 0.4]));
    /// let seed = SVector::from([2.0, 1.0, -2.0, -0.5, 2.0, 3.0, -2.0]);
    /// let ik = NumericIk::default();
    /// let first = ik.solve(&arm, &target, &seed).unwrap();
    /// let best = ik.solve_preferring(&arm, &target, &seed, Preference::Cost(&away)).unwrap();
    /// assert!(away(&best.q).0 <= away(&first.q).0);
    /// ```
    Cost(&'a CostFunction<'a, D>),
}

/// A cost of the user's for [`Preference::Cost`]: at `q`, the cost and its gradient ∂cost/∂q.
pub type CostFunction<'a, D> = dyn Fn(&OVector<f64, D>) -> (f64, OVector<f64, D>) + 'a;

impl<D: Dim> core::fmt::Debug for Preference<'_, D>
where
    DefaultAllocator: nalgebra::allocator::Allocator<D>,
{
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Preference::Posture(p) => f.debug_tuple("Posture").field(p).finish(),
            Preference::Manipulability(axes) => {
                f.debug_tuple("Manipulability").field(axes).finish()
            }
            Preference::Cost(_) => f.write_str("Cost(..)"),
        }
    }
}

/// Largest step of the secondary objective on any joint, rad or m: the projection is a first-
/// order statement, and the return to the pose after each step is meant to be short (0.5 and
/// 1 took more iterations on the Panda and on 8- and 17-joint arms).
const MAX_STEP: f64 = 0.2;
/// Halvings of a step before the iteration gives up on improving.
const MAX_HALVINGS: usize = 30;
/// Iterations of the fallback return to the pose (from within second order of it).
const CORRECTION_ITERATIONS: usize = 20;
/// Gauss–Newton steps of the polish after each correction (two suffice from within the
/// tolerances: the convergence is quadratic).
const POLISH_STEPS: usize = 3;
/// Joints this close to a limit (rad or m) count as on it where the objective pushes them out:
/// they stay there, rather than step after step being moved the rest of the way.
const LIMIT_MARGIN: f64 = 1e-9;
/// Chord steps of the return to the pose after a step along the self-motion.
const CHORD_STEPS: usize = 20;

/// The projected gradient, and the SVD of the Jacobian without the joints held on limits.
type Direction<D> = (OVector<f64, D>, Option<JacobianSvd<D>>);

impl<D: Dim> Preference<'_, D>
where
    DefaultAllocator: nalgebra::allocator::Allocator<D>,
{
    /// The objective's descent direction at `q`, where the (world-axes) Jacobian is `j`:
    /// towards the posture, up the manipulability's gradient, or down the cost's; `None` where
    /// the manipulability has none (J has lost rank) or the cost is not finite.
    fn descent(&self, q: &OVector<f64, D>, j: &OMatrix<f64, U6, D>) -> Option<OVector<f64, D>>
    where
        DefaultAllocator: ArmAllocator<D>,
    {
        match self {
            Preference::Posture(p) => Some(*p - q),
            Preference::Manipulability(axes) => Some(manipulability_gradient(j, *axes)?.1),
            Preference::Cost(f) => {
                let (c, grad) = f(q);
                (c.is_finite() && grad.len() == q.len() && grad.iter().all(|x| x.is_finite()))
                    .then(|| -grad)
            }
        }
    }

    /// The objective to minimise at `q`: the squared distance to the posture, or minus the
    /// manipulability.
    fn cost<A: Arm<Dof = D>>(&self, arm: &A, q: &OVector<f64, D>) -> f64
    where
        DefaultAllocator: ArmAllocator<D>,
    {
        match self {
            Preference::Posture(p) => 0.5 * (*p - q).norm_squared(),
            Preference::Manipulability(Axes::All) => {
                -JacobianSvd::new(&arm.jacobian(q)).manipulability()
            }
            Preference::Manipulability(axes) => {
                manipulability_gradient(&arm.jacobian(q), *axes).map_or(0.0, |(m, _)| -m)
            }
            Preference::Cost(f) => f(q).0,
        }
    }

    /// How much better `to` is than `from` (whose objective is `cost`), and `to`'s objective.
    /// The posture's is taken from the difference `Δ = to − from` as `Δ · (p − from − Δ/2)`,
    /// not as the difference of two nearly equal squared distances, whose rounding (relative
    /// to the distance) would hide the gains near the optimum (relative to the step).
    fn gain<A: Arm<Dof = D>>(
        &self,
        arm: &A,
        from: &OVector<f64, D>,
        to: &OVector<f64, D>,
        cost: f64,
    ) -> (f64, f64)
    where
        DefaultAllocator: ArmAllocator<D>,
    {
        match self {
            Preference::Posture(p) => {
                let gain: f64 = (0..from.len())
                    .map(|k| {
                        let delta = to[k] - from[k];
                        delta * (p[k] - from[k] - 0.5 * delta)
                    })
                    .sum();
                (gain, cost - gain)
            }
            Preference::Manipulability(_) | Preference::Cost(_) => {
                let c = self.cost(arm, to);
                (cost - c, c)
            }
        }
    }
}

impl NumericIk {
    /// Solves `arm.fk(q) = target` from `seed` as [`solve`](Self::solve) does, then moves the
    /// solution along the set of configurations that reach the pose to the one `preference`
    /// prefers (a local optimum: the nearest to the posture, the most manipulable, or the least
    /// costly by your function, among the solutions connected to the first one).
    ///
    /// # Method
    /// [`NumericIk::solve`] first finds one solution, and undamped Gauss–Newton steps polish it
    /// to the rounding of the forward kinematics. Then, at each iteration, the descent
    /// direction `g` of the objective (towards the posture, up the manipulability gradient
    /// [`manipulability_gradient`], or down your cost's gradient) is projected onto the null space of the Jacobian,
    /// `d = (I − J⁺J) g`: the joint motions that, to first order, leave the tool where it is.
    /// Joints on a limit that the objective pushes further out are held (taken out of J and of
    /// `g`, an active set: each joint `d` would push out is held, each held one that released
    /// alone would move inwards is released), so the other joints make up for them. The step
    /// `q + t d` takes `t` from the last two iterations (Barzilai and Borwein's secant step: for
    /// a distant posture the curvature of the self-motion, not the objective's, sets the step),
    /// at most 0.2 rad or m on any joint and never past a limit. It leaves the pose only to
    /// second order; chord steps `J⁺ e` with the same Jacobian bring it back to the rounding
    /// (where they fail, [`NumericIk::solve`] without restarts and the polish), and the step is
    /// kept if the objective improved, else halved. The posture's improvement is computed from
    /// the difference of the two configurations, not as a difference of two distances, and every
    /// configuration compared reaches the pose to the rounding: solutions anywhere within the
    /// tolerances would differ in the objective by more than a step gains near the optimum.
    ///
    /// The iteration stops where `|d|∞` is below `1e-10 + 1e-8 |g|∞` (a stationary point of
    /// the objective on the set of solutions, which for a 7-joint arm is the one-dimensional
    /// self-motion, with the limits' multipliers of the right sign), where 30 halvings of a
    /// step do not improve it (the objective's rounding), or where [`NumericIk::max_iterations`],
    /// shared with the first solve, is spent: 10 iterations after the first solution for the
    /// median of 100 random Panda poses and postures (at most 62), 13 (at most 55) for the
    /// manipulability; 23 and 29 (37, 98) for a general 8-joint arm; 139 (177) for the nearest
    /// posture of a 17-joint arm. In time (release, this machine, 2026-12-05), the Panda's
    /// mean 110 µs for the posture and 140 for the manipulability, against 40 for `solve`.
    ///
    /// An arm without redundancy at the solution (six joints or fewer, at a regular pose) has
    /// an empty null space: the first solution is returned, polished.
    ///
    /// The result reaches the pose within the tolerances and is never worse than the first
    /// solution by the objective; its `iterations` count all Jacobian evaluations. Errors
    /// are those of [`solve`](Self::solve), and [`IkError::PostureLength`] /
    /// [`IkError::NonFinitePosture`] for a posture that is not one finite value per joint.
    ///
    /// ```
    /// use dhgen::ik::{NumericIk, Preference};
    /// use dhgen::nalgebra::SVector;
    /// use dhgen::velocity::{Axes, manipulability};
    /// use dhgen::Arm;
    /// dhgen::robot!(mod panda = "../../robots/panda.toml");
    ///
    /// let q = SVector::<f64, 7>::from([0.1, -0.4, 0.2, -1.8, 0.3, 1.5, 0.4]);
    /// let target = panda::Robot.fk(&q);
    /// let seed = SVector::<f64, 7>::from([0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0]);
    /// let ik = NumericIk::default();
    /// let first = ik.solve(&panda::Robot, &target, &seed).unwrap();
    ///
    /// // The solution nearest a rest posture, and the most manipulable one.
    /// let rest = SVector::<f64, 7>::from([0.0, -0.8, 0.0, -2.4, 0.0, 1.6, 0.8]);
    /// let near = ik.solve_preferring(&panda::Robot, &target, &seed, Preference::Posture(&rest))
    ///     .unwrap();
    /// assert!(near.position_error <= 1e-10 && near.orientation_error <= 1e-10);
    /// assert!((near.q - rest).norm() <= (first.q - rest).norm());
    ///
    /// let most = Preference::Manipulability(Axes::All);
    /// let best = ik.solve_preferring(&panda::Robot, &target, &seed, most).unwrap();
    /// let m = |q| manipulability(&panda::Robot.jacobian(q));
    /// assert!(m(&best.q) >= m(&first.q));
    /// ```
    pub fn solve_preferring<A: Arm>(
        &self,
        arm: &A,
        target: &Isometry3<f64>,
        seed: &OVector<f64, A::Dof>,
        preference: Preference<'_, A::Dof>,
    ) -> Result<Solution<A::Dof>, IkError>
    where
        DefaultAllocator: ArmAllocator<A::Dof>,
    {
        let n = arm.dof();
        if let Preference::Posture(p) = preference {
            if p.len() != n {
                return Err(IkError::PostureLength {
                    len: p.len(),
                    expected: n,
                });
            }
            if let Some(joint) = p.iter().position(|x| !x.is_finite()) {
                return Err(IkError::NonFinitePosture { joint });
            }
        }
        let mut best = self.solve(arm, target, seed)?;
        let mut trial = best.q.clone();
        let mut next = best.q.clone();
        self.polish(arm, target, &mut best, &mut trial);
        let mut cost = preference.cost(arm, &best.q);
        let (mut previous_q, mut previous_d, mut previous) =
            (best.q.clone(), best.q.clone(), false);
        // The posture's quadratic is minimised along d by t = 1 to first order (a step of
        // sequential quadratic programming that leaves out the curvature of the self-motion);
        // the manipulability and a cost of yours have no such scale: their steps start at
        // MAX_STEP. All then adapt,
        // doubling after a step that is kept.
        let mut scale = match preference {
            Preference::Posture(_) => 1.0,
            Preference::Manipulability(_) | Preference::Cost(_) => f64::INFINITY,
        };
        while best.iterations < self.max_iterations {
            best.iterations += 1;
            let j = arm.jacobian(&best.q);
            let Some(g) = preference.descent(&best.q, &j) else {
                break;
            };
            let length = length_scale(arm, &j);
            let mut scaled = j;
            scaled.fixed_rows_mut::<3>(0).unscale_mut(length);
            self.task.rows(&mut scaled, || arm.fk(&best.q), target);
            let svd = JacobianSvd::new(&scaled);
            let (d, reduced) = self.null_space_direction(arm, &best.q, &scaled, &svd, &g);
            let svd = reduced.unwrap_or(svd);
            let (d_max, g_max) = (d.amax(), g.amax());
            if d_max <= 1e-10 + 1e-8 * g_max || !d_max.is_finite() {
                break;
            }
            // The Barzilai–Borwein step from the last two iterations (a secant estimate of the
            // objective's curvature along the self-motion, which for a distant posture is
            // dominated by the self-motion's own curvature), else the adapted scale.
            let mut t = scale;
            if previous {
                let (mut ss, mut sy) = (0.0, 0.0);
                for k in 0..n {
                    let step = best.q[k] - previous_q[k];
                    ss += step * step;
                    sy += step * (previous_d[k] - d[k]);
                }
                if sy > 0.0 && ss > 0.0 {
                    t = ss / sy;
                }
            }
            t = t
                .min(MAX_STEP / d_max)
                .min(self.within_limits(arm, &best.q, &d));
            previous_q.copy_from(&best.q);
            previous_d.copy_from(&d);
            previous = true;
            let mut improved = false;
            for _ in 0..MAX_HALVINGS {
                if best.iterations >= self.max_iterations {
                    break;
                }
                trial.copy_from(&best.q);
                trial.axpy(t, &d, 1.0);
                self.clamp(arm, &mut trial);
                let back = self
                    .chord(arm, target, &svd, length, &mut trial, &mut next)
                    .or_else(|| self.correct(arm, target, &mut best.iterations, &mut trial));
                if let Some((position_error, orientation_error)) = back {
                    // The manipulability there takes a Jacobian.
                    if matches!(preference, Preference::Manipulability(_)) {
                        if best.iterations >= self.max_iterations {
                            break;
                        }
                        best.iterations += 1;
                    }
                    let (gain, c) = preference.gain(arm, &best.q, &trial, cost);
                    if gain > 0.0 {
                        cost = c;
                        best.q.copy_from(&trial);
                        (best.position_error, best.orientation_error) =
                            (position_error, orientation_error);
                        improved = true;
                        break;
                    }
                }
                t *= 0.5;
            }
            if !improved {
                break;
            }
            scale = 2.0 * t;
        }
        Ok(best)
    }

    /// Brings `trial`, a step along the self-motion from a solution whose scaled Jacobian's
    /// SVD is `svd`, back onto the pose by the chord method: Gauss–Newton steps `J⁺ e` with
    /// that solution's J (no Jacobian evaluated), while they reduce the pose error, to the
    /// rounding of the forward kinematics. The final position and orientation errors where
    /// they are within the tolerances; `None` otherwise (a step too long for the chord).
    fn chord<A: Arm>(
        &self,
        arm: &A,
        target: &Isometry3<f64>,
        svd: &JacobianSvd<A::Dof>,
        length: f64,
        trial: &mut OVector<f64, A::Dof>,
        next: &mut OVector<f64, A::Dof>,
    ) -> Option<(f64, f64)>
    where
        DefaultAllocator: ArmAllocator<A::Dof>,
    {
        let (mut e, mut dp, mut dr) = self.task.residual(target, &arm.fk(trial), length);
        let mut error = e.norm_squared();
        for _ in 0..CHORD_STEPS {
            next.copy_from(trial);
            *next += svd.solve(&e, 0.0);
            self.clamp(arm, next);
            let (e_new, dp_new, dr_new) = self.task.residual(target, &arm.fk(next), length);
            let error_new = e_new.norm_squared();
            let better = error_new < error;
            if !better {
                break;
            }
            core::mem::swap(trial, next);
            (e, dp, dr, error) = (e_new, dp_new, dr_new, error_new);
        }
        (dp <= self.position_tolerance && dr <= self.orientation_tolerance).then_some((dp, dr))
    }

    /// The fallback where the chord fails (a long step, or a joint on a limit): [`solve`]
    /// (Self::solve) from `trial` without restarts, then the polish; its iterations added to
    /// `iterations`. The errors where it converged.
    fn correct<A: Arm>(
        &self,
        arm: &A,
        target: &Isometry3<f64>,
        iterations: &mut usize,
        trial: &mut OVector<f64, A::Dof>,
    ) -> Option<(f64, f64)>
    where
        DefaultAllocator: ArmAllocator<A::Dof>,
    {
        let budget = self.max_iterations.saturating_sub(*iterations);
        let correct = NumericIk {
            restarts: 0,
            max_iterations: budget.min(CORRECTION_ITERATIONS),
            ..*self
        };
        match correct.solve(arm, target, trial) {
            Ok(mut s) => {
                s.iterations += *iterations;
                let mut scratch = s.q.clone();
                self.polish(arm, target, &mut s, &mut scratch);
                *iterations = s.iterations;
                trial.copy_from(&s.q);
                Some((s.position_error, s.orientation_error))
            }
            Err(
                IkError::NotConverged { iterations: k, .. }
                | IkError::Singular { iterations: k, .. }
                | IkError::LocalMinimum { iterations: k, .. },
            ) => {
                *iterations += k;
                None
            }
            Err(_) => None,
        }
    }

    /// Undamped Gauss–Newton steps `q += J⁺ e` from a solution within the tolerances, kept while
    /// they reduce the pose error, to the rounding of the forward kinematics: the objective of
    /// two solutions is then compared at the same pose, not at two points up to the tolerances
    /// apart, whose difference in the objective (first order in the pose error) would otherwise
    /// hide its decrease along the self-motion (second order in the step) near the optimum.
    fn polish<A: Arm>(
        &self,
        arm: &A,
        target: &Isometry3<f64>,
        s: &mut Solution<A::Dof>,
        trial: &mut OVector<f64, A::Dof>,
    ) where
        DefaultAllocator: ArmAllocator<A::Dof>,
    {
        for _ in 0..POLISH_STEPS {
            if s.iterations >= self.max_iterations {
                return;
            }
            s.iterations += 1;
            let mut j = arm.jacobian(&s.q);
            let length = length_scale(arm, &j);
            j.fixed_rows_mut::<3>(0).unscale_mut(length);
            let pose = arm.fk(&s.q);
            self.task.rows(&mut j, || pose, target);
            let (e, _, _) = self.task.residual(target, &pose, length);
            let error = e.norm_squared();
            if error == 0.0 {
                return;
            }
            trial.copy_from(&s.q);
            *trial += JacobianSvd::new(&j).solve(&e, 0.0);
            self.clamp(arm, trial);
            let (e_new, dp, dr) = self.task.residual(target, &arm.fk(trial), length);
            let better = e_new.norm_squared() < error;
            if !better {
                return;
            }
            s.q.copy_from(trial);
            (s.position_error, s.orientation_error) = (dp, dr);
        }
    }

    /// `(I − J⁺J) g` at `q`, where the scaled Jacobian is `j` and `svd` its SVD, with the joints
    /// on a limit (or within [`LIMIT_MARGIN`] of it) that the objective pushes further out held
    /// (taken out of J and of `g`): the projected gradient of the objective on the face of the
    /// limits, an active set found by locking each joint the result would push out and
    /// releasing each locked one that, released alone, would move inwards. Also the SVD of J
    /// without the held joints, where there are any, for the return to the pose (which then
    /// leaves them where they are).
    fn null_space_direction<A: Arm>(
        &self,
        arm: &A,
        q: &OVector<f64, A::Dof>,
        j: &OMatrix<f64, U6, A::Dof>,
        svd: &JacobianSvd<A::Dof>,
        g: &OVector<f64, A::Dof>,
    ) -> Direction<A::Dof>
    where
        DefaultAllocator: ArmAllocator<A::Dof>,
    {
        let n = arm.dof();
        let g_max = g.amax();
        let d = svd.null_space_projection(g);
        // -1 or +1 where a joint is on its lower or upper limit, 0 elsewhere.
        let side = |k: usize| match arm.limits(k) {
            Some([lo, _]) if self.respect_limits && q[k] <= lo + LIMIT_MARGIN => -1.0,
            Some([_, hi]) if self.respect_limits && q[k] >= hi - LIMIT_MARGIN => 1.0,
            _ => 0.0,
        };
        if (0..n).all(|k| side(k) * d[k] <= 0.0) {
            return (d, None);
        }
        // `held[k]` is 1 for a joint held on its limit.
        let mut held = g.map(|_| 0.0);
        let project = |held: &OVector<f64, A::Dof>| {
            let (mut jr, mut gr) = (j.clone(), g.clone());
            for k in (0..n).filter(|&k| held[k] != 0.0) {
                jr.column_mut(k).fill(0.0);
                gr[k] = 0.0;
            }
            let svd_r = JacobianSvd::new(&jr);
            (svd_r.null_space_projection(&gr), svd_r)
        };
        let (mut d, mut svd_r) = (d, svd.clone());
        // Each round locks or releases at least one joint; bounded against cycling.
        for _ in 0..=2 * n {
            let mut changed = false;
            for k in 0..n {
                if held[k] == 0.0 && side(k) * d[k] > 0.0 {
                    held[k] = 1.0;
                    changed = true;
                }
            }
            if !changed {
                // `svd_r` is that of J with the joints now held taken out.
                let released = Released::new(&svd_r, j, g, &held);
                for k in 0..n {
                    if held[k] == 0.0 {
                        continue;
                    }
                    held[k] = 0.0;
                    let d_k = released
                        .as_ref()
                        .map_or_else(|| project(&held).0[k], |r| r.component(j, g[k], k));
                    if side(k) * d_k < -1e-12 * g_max {
                        changed = true;
                        break;
                    }
                    held[k] = 1.0;
                }
            }
            if !changed {
                break;
            }
            (d, svd_r) = project(&held);
        }
        (d, Some(svd_r))
    }

    /// The longest step `t` along `d` from `q` that keeps every joint within its limits.
    fn within_limits<A: Arm>(
        &self,
        arm: &A,
        q: &OVector<f64, A::Dof>,
        d: &OVector<f64, A::Dof>,
    ) -> f64
    where
        DefaultAllocator: ArmAllocator<A::Dof>,
    {
        let mut t = f64::INFINITY;
        if !self.respect_limits {
            return t;
        }
        for k in 0..arm.dof() {
            if let Some([lo, hi]) = arm.limits(k) {
                if d[k] < 0.0 {
                    t = t.min((q[k] - lo).max(0.0) / -d[k]);
                } else if d[k] > 0.0 {
                    t = t.min((hi - q[k]).max(0.0) / d[k]);
                }
            }
        }
        t
    }
}

/// What releasing one held joint does to the projected gradient, from the SVD of the Jacobian
/// `J_F` of the free joints alone (a rank-one update instead of an SVD per held joint). With
/// `G = J_F J_Fᵀ` invertible, releasing joint k adds its column `j_k` (`G' = G + j_k j_kᵀ`) and
/// its gradient `g_k`, and by Sherman and Morrison component k of `(I − J'⁺ J') g'` is
/// `(g_k − j_kᵀ G⁻¹ J_F g_F) / (1 + j_kᵀ G⁻¹ j_k)`.
struct Released {
    /// `G⁻¹ J_F g_F`.
    y: nalgebra::Vector6<f64>,
    /// `G⁻¹ = U Σ⁻² Uᵀ`, from the SVD.
    u: nalgebra::Matrix6<f64>,
    inverse_squares: nalgebra::Vector6<f64>,
}

impl Released {
    /// `None` unless `J_F` has six singular values above 1e-6 of the largest (then the update
    /// is as accurate as a new SVD; the caller decomposes instead).
    fn new<D: Dim>(
        svd: &JacobianSvd<D>,
        j: &OMatrix<f64, U6, D>,
        g: &OVector<f64, D>,
        held: &OVector<f64, D>,
    ) -> Option<Released>
    where
        DefaultAllocator: ArmAllocator<D>,
    {
        let sigma = svd.singular_values();
        // False for NaN singular values too.
        let well_conditioned = sigma[5] > 1e-6 * sigma[0];
        if svd.rank_bound() < 6 || !well_conditioned {
            return None;
        }
        let mut b = nalgebra::Vector6::zeros();
        for k in (0..g.len()).filter(|&k| held[k] == 0.0) {
            b += j.column(k) * g[k];
        }
        let (u, inverse_squares) = (*svd.u(), sigma.map(|s| 1.0 / (s * s)));
        Some(Released {
            y: Self::solve(&u, &inverse_squares, &b),
            u,
            inverse_squares,
        })
    }

    /// `G⁻¹ x = U Σ⁻² Uᵀ x`.
    fn solve(
        u: &nalgebra::Matrix6<f64>,
        inverse_squares: &nalgebra::Vector6<f64>,
        x: &nalgebra::Vector6<f64>,
    ) -> nalgebra::Vector6<f64> {
        u * u.tr_mul(x).component_mul(inverse_squares)
    }

    /// `G⁻¹ x`.
    fn gram_inverse(&self, x: &nalgebra::Vector6<f64>) -> nalgebra::Vector6<f64> {
        Self::solve(&self.u, &self.inverse_squares, x)
    }

    /// Component k of the projected gradient once joint k (held, gradient `g_k`) is released.
    fn component<D: Dim>(&self, j: &OMatrix<f64, U6, D>, g_k: f64, k: usize) -> f64
    where
        DefaultAllocator: ArmAllocator<D>,
    {
        let column: nalgebra::Vector6<f64> = j.fixed_view::<6, 1>(0, k).into_owned();
        let a = column.dot(&self.gram_inverse(&column));
        (g_k - column.dot(&self.y)) / (1.0 + a)
    }
}

#[cfg(test)]
mod tests {
    use super::Released;
    use dhgen_motion::velocity::JacobianSvd;
    use nalgebra::{SMatrix, SVector};

    /// The rank-one update gives the component a new SVD of the Jacobian with the joint
    /// released gives, for every held joint of several held sets of a 6×9 Jacobian; and it
    /// declines a Jacobian whose free columns have lost rank.
    #[test]
    fn releasing_a_joint_by_the_update_matches_a_new_svd() {
        // Entries from a hash-like sequence (a sine of a linear index would have rank 2).
        let noise = |i: usize| ((i as f64 * 12.9898 + 4.1).sin() * 43_758.545).fract();
        let j = SMatrix::<f64, 6, 9>::from_fn(|r, c| noise(r * 9 + c));
        let g = SVector::<f64, 9>::from_fn(|k, _| (k as f64 * 1.3).cos());
        let zeroed = |held: &SVector<f64, 9>| {
            let (mut jr, mut gr) = (j, g);
            for k in (0..9).filter(|&k| held[k] != 0.0) {
                jr.column_mut(k).fill(0.0);
                gr[k] = 0.0;
            }
            (jr, gr)
        };
        for pattern in [0b000000011u32, 0b100000100, 0b010101000] {
            let held = SVector::<f64, 9>::from_fn(|k, _| f64::from((pattern >> k) & 1));
            let (jr, _) = zeroed(&held);
            let svd = JacobianSvd::new(&jr);
            let released = Released::new(&svd, &j, &g, &held).expect("six free columns of rank 6");
            for k in (0..9).filter(|&k| held[k] != 0.0) {
                let mut one_less = held;
                one_less[k] = 0.0;
                let (jk, gk) = zeroed(&one_less);
                let want = JacobianSvd::new(&jk).null_space_projection(&gk)[k];
                let got = released.component(&j, g[k], k);
                assert!(
                    (got - want).abs() <= 1e-12 * g.amax(),
                    "joint {k}: {got} vs {want}"
                );
            }
        }
        // Four free columns: J_F has rank 4, and the caller must decompose.
        let held = SVector::<f64, 9>::from_fn(|k, _| if k < 5 { 1.0 } else { 0.0 });
        let (jr, _) = zeroed(&held);
        assert!(Released::new(&JacobianSvd::new(&jr), &j, &g, &held).is_none());
    }
}
