//! What of a target pose the numeric solver reaches: the whole pose, the tool's position, its
//! position and the direction of its z axis, or the components a mask counts in world axes
//! ([`Task`]).

use dhgen_kernel::rotation::rotation_vector;
#[cfg(not(feature = "std"))]
use nalgebra::RealField as _;
use nalgebra::{Dim, Isometry3, OMatrix, Rotation3, U6, Vector3, Vector6};

/// What of the target pose [`NumericIk`](super::NumericIk) reaches (its field
/// [`task`](super::NumericIk::task)): the constraints it drives to zero, and so the errors a
/// [`Solution`](super::Solution) reports. The default is the whole pose.
///
/// An arm with fewer than six joints cannot reach an arbitrary pose: a planar arm or a
/// four-joint SCARA reaches a position ([`Task::Position`]), a five-joint arm a position and
/// an approach direction ([`Task::PositionAndAxis`]). The freed constraints also give a
/// redundant arm more self-motion for
/// [`solve_preferring`](super::NumericIk::solve_preferring): a 7-joint arm that only positions
/// its tool has four free degrees of freedom.
///
/// ```
/// use dhgen::ik::{NumericIk, Task};
/// use dhgen::nalgebra::{Isometry3, SVector, Translation3, UnitQuaternion};
/// dhgen::robot!(mod panda = "../../robots/panda.toml");
/// use dhgen::Arm;
///
/// // A position only: the orientation is whatever the solution leaves.
/// let target = Isometry3::from_parts(Translation3::new(0.4, 0.2, 0.5), UnitQuaternion::identity());
/// let ik = NumericIk { task: Task::Position, ..NumericIk::default() };
/// let seed = SVector::<f64, 7>::from([0.0, 0.0, 0.0, -1.5, 0.0, 1.5, 0.0]);
/// let s = ik.solve(&panda::Robot, &target, &seed).unwrap();
/// let p = panda::Robot.fk(&s.q).translation.vector;
/// assert!((p - target.translation.vector).norm() <= 1e-10);
/// assert_eq!(s.orientation_error, 0.0);
/// ```
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Task {
    /// Position and orientation: six constraints.
    #[default]
    Pose,
    /// The tool's position only: three constraints; the orientation is free and its error
    /// reported as 0.
    Position,
    /// The tool's position and the direction of its z axis (the approach vector): five
    /// constraints, free to turn about that axis (a drill, a nozzle, a welding torch, a
    /// five-joint arm). The orientation error is the angle between the tool's z axis and the
    /// target's.
    PositionAndAxis,
    /// The components of the target pose that count, in world axes, `[x, y, z, rx, ry, rz]`
    /// (the Robotics Toolbox's `mask` with weights 0 and 1). A position component left out
    /// is free: `[true, true, false, true, true, true]` reaches a pose at any height. Of the
    /// orientation, count all three components (the whole orientation), none (any), or two:
    /// the orientation up to a turn about the world axis left out (`[true, true, true, true,
    /// true, false]`: a pose up to a turn about the vertical, for a gripper symmetric about
    /// a vertical axis). A mask counting one rotation component is refused
    /// ([`IkError::InvalidSettings`](super::IkError::InvalidSettings)): turns about two
    /// world axes are not a set of orientations that one could reach.
    ///
    /// The errors are the norm of the counted position components, and the angle of the
    /// rotation still to make (the whole orientation), 0 (none), or the angle between the
    /// world axis `u` left out and where the tool turns the direction that the target's
    /// orientation holds along `u` (`R R*ᵀ u`; it is `u` exactly when the orientations differ
    /// by a turn about `u`). The solver handles that direction as [`PositionAndAxis`]
    /// handles the tool's z axis.
    ///
    /// [`PositionAndAxis`]: Task::PositionAndAxis
    ///
    /// ```
    /// use dhgen::ik::Task;
    /// use dhgen::nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
    /// let a = Isometry3::new(Vector3::new(0.3, 0.1, 0.0), Vector3::new(0.2, -0.4, 0.1));
    /// // 2 m higher and turned by 0.3 rad about the vertical.
    /// let up = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 0.3);
    /// let b = Isometry3::from_parts(Translation3::new(0.3, 0.1, 2.0), up * a.rotation);
    /// let free_height_and_turn = Task::Mask([true, true, false, true, true, false]);
    /// assert_eq!(free_height_and_turn.constraints(), 4);
    /// let (dp, dr) = free_height_and_turn.errors(&a, &b);
    /// assert!(dp == 0.0 && dr < 1e-15);
    /// // Counted, the turn is the whole difference in orientation.
    /// let (_, dr) = Task::Mask([true; 6]).errors(&a, &b);
    /// assert!((dr - 0.3).abs() < 1e-15);
    /// ```
    Mask([bool; 6]),
}

impl Task {
    /// The number of constraints: 6, 3 or 5.
    ///
    /// ```
    /// assert_eq!(dhgen::ik::Task::PositionAndAxis.constraints(), 5);
    /// ```
    pub fn constraints(self) -> usize {
        match self {
            Task::Pose => 6,
            Task::Position => 3,
            Task::PositionAndAxis => 5,
            Task::Mask(mask) => mask.iter().filter(|&&m| m).count(),
        }
    }

    /// Why the numeric solver refuses this task, if it does: a [`Mask`](Task::Mask) counting
    /// exactly one rotation component. [`NumericIk`](super::NumericIk) returns it as
    /// [`IkError::InvalidSettings`](super::IkError::InvalidSettings).
    ///
    /// ```
    /// use dhgen::ik::Task;
    /// assert!(Task::Mask([true, true, true, true, true, false]).check().is_ok());
    /// assert!(Task::Mask([true, true, true, false, false, true]).check().is_err());
    /// ```
    pub fn check(self) -> Result<(), &'static str> {
        match self {
            Task::Mask(mask) if free_turn(&mask).is_none() => {
                Err("task: a mask counts none, two or all three of the rotation components")
            }
            _ => Ok(()),
        }
    }

    /// `(position error in m, orientation error in rad)` of `pose` against `target` in this
    /// task: the distance between the tool origins, and the angle of the rotation between the
    /// orientations ([`Pose`](Task::Pose), as [`pose_error`](super::pose_error)), 0
    /// ([`Position`](Task::Position)), or the angle between the tool z axes
    /// ([`PositionAndAxis`](Task::PositionAndAxis)).
    ///
    /// ```
    /// use dhgen::ik::Task;
    /// use dhgen::nalgebra::{Isometry3, Vector3};
    /// let a = Isometry3::new(Vector3::new(1.0, 0.0, 0.0), Vector3::new(0.0, 0.0, 0.3));
    /// let b = Isometry3::new(Vector3::new(1.0, 0.0, 0.2), Vector3::zeros());
    /// // A turn about the z axis changes the pose, not the axis.
    /// let (dp, dr) = Task::PositionAndAxis.errors(&a, &b);
    /// assert!((dp - 0.2).abs() < 1e-15 && dr < 1e-15);
    /// assert!((Task::Pose.errors(&a, &b).1 - 0.3).abs() < 1e-15);
    /// ```
    pub fn errors(self, pose: &Isometry3<f64>, target: &Isometry3<f64>) -> (f64, f64) {
        let dp = (pose.translation.vector - target.translation.vector).norm();
        match self {
            Task::Pose => super::pose_error(pose, target),
            Task::Position => (dp, 0.0),
            Task::PositionAndAxis => (dp, shortest_turn(pose, target).1),
            Task::Mask(_) => {
                let (_, dp, dr) = self.residual(target, pose, 1.0);
                (dp, dr)
            }
        }
    }

    /// The error vector `[(p* − p)/length; δ]` the solver drives to zero, and the norms of its
    /// two parts in metres and radians: δ is `log(R* Rᵀ)` for the pose, 0 for the position,
    /// and for the axis the rotation vector of the shortest turn taking the tool's z axis to
    /// the target's (perpendicular to the tool's axis, as [`rows`](Task::rows) leaves the
    /// rotation rows); for a mask, the position components left out set to 0 and δ that of
    /// the whole orientation, none, or of the turn about the world axis left out
    /// ([`Task::Mask`]), as the axis'.
    pub(super) fn residual(
        self,
        target: &Isometry3<f64>,
        pose: &Isometry3<f64>,
        length: f64,
    ) -> (Vector6<f64>, f64, f64) {
        let mut dp = target.translation.vector - pose.translation.vector;
        let (dw, dr) = match self {
            Task::Pose => whole_turn(pose, target),
            Task::Position => (Vector3::zeros(), 0.0),
            Task::PositionAndAxis => shortest_turn(pose, target),
            Task::Mask(mask) => {
                for k in (0..3).filter(|&k| !mask[k]) {
                    dp[k] = 0.0;
                }
                masked_turn(&mask, pose, target)
            }
        };
        let e = Vector6::new(
            dp.x / length,
            dp.y / length,
            dp.z / length,
            dw.x,
            dw.y,
            dw.z,
        );
        (e, dp.norm(), dr)
    }

    /// The rows of the (scaled) Jacobian `j` at `pose` that this task constrains, in place: all
    /// six for the pose; the rotation rows zeroed for the position; for the axis, the rotation
    /// rows' components along the tool's z axis `a` removed (`(I − a aᵀ) J_ω`: turning about
    /// the axis does not move it); for a mask, the position rows left out zeroed and the
    /// rotation rows as for the whole pose, none, or as for the axis with the direction
    /// `R R*ᵀ u` ([`Task::Mask`]). `pose` is called only where the rows depend on it.
    pub(super) fn rows<D: Dim>(
        self,
        j: &mut OMatrix<f64, U6, D>,
        pose: impl FnOnce() -> Isometry3<f64>,
        target: &Isometry3<f64>,
    ) where
        nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<U6, D>,
    {
        // A turn about the tool-fixed direction `a` does not move it.
        let about = |j: &mut OMatrix<f64, U6, D>, a: Vector3<f64>| {
            for mut column in j.column_iter_mut() {
                let w = column.fixed_rows::<3>(3).into_owned();
                column.fixed_rows_mut::<3>(3).axpy(-a.dot(&w), &a, 1.0);
            }
        };
        match self {
            Task::Pose => {}
            Task::Position => j.fixed_rows_mut::<3>(3).fill(0.0),
            Task::PositionAndAxis => about(j, pose() * Vector3::z()),
            Task::Mask(mask) => {
                for r in (0..3).filter(|&r| !mask[r]) {
                    j.row_mut(r).fill(0.0);
                }
                match free_turn(&mask) {
                    Some(FreeTurn::Every) => j.fixed_rows_mut::<3>(3).fill(0.0),
                    Some(FreeTurn::About(u)) => {
                        let (a, _) = held_direction(&pose(), target, u);
                        about(j, a);
                    }
                    Some(FreeTurn::Nothing) | None => {}
                }
            }
        }
    }
}

/// What a mask leaves free of the orientation ([`free_turn`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum FreeTurn {
    /// Every turn: no rotation component counted.
    Every,
    /// No turn: all three counted.
    Nothing,
    /// The turns about world axis `u` (0, 1, 2), the one not counted.
    About(usize),
}

/// [`FreeTurn`] of `mask`; `None` for a mask counting one rotation component.
fn free_turn(mask: &[bool; 6]) -> Option<FreeTurn> {
    let free: [bool; 3] = core::array::from_fn(|k| !mask[3 + k]);
    match free.iter().filter(|&&f| f).count() {
        3 => Some(FreeTurn::Every),
        0 => Some(FreeTurn::Nothing),
        1 => free.iter().position(|&f| f).map(FreeTurn::About),
        _ => None,
    }
}

/// For a mask leaving the turns about world axis `u` free: the direction `R R*ᵀ e_u` in which
/// the tool holds what the target's orientation holds along `e_u` (it is `e_u` exactly when
/// the orientations differ by a turn about `e_u`), and a direction perpendicular to it, the
/// same map of the next world axis.
fn held_direction(
    pose: &Isometry3<f64>,
    target: &Isometry3<f64>,
    u: usize,
) -> (Vector3<f64>, Vector3<f64>) {
    let axis = |k: usize| Vector3::from_fn(|i, _| if i == k { 1.0 } else { 0.0 });
    let held = |k: usize| pose.rotation * (target.rotation.inverse() * axis(k));
    (held(u), held((u + 1) % 3))
}

/// The rotation part of [`Task::residual`] for a mask, and its angle: as [`Task::Mask`] says
/// (0 for a mask counting one rotation component, which [`Task::check`] refuses).
fn masked_turn(
    mask: &[bool; 6],
    pose: &Isometry3<f64>,
    target: &Isometry3<f64>,
) -> (Vector3<f64>, f64) {
    match free_turn(mask) {
        Some(FreeTurn::Nothing) => whole_turn(pose, target),
        Some(FreeTurn::About(u)) => {
            let (a, across) = held_direction(pose, target, u);
            let b = Vector3::from_fn(|i, _| if i == u { 1.0 } else { 0.0 });
            turn_between(&a, &b, &across)
        }
        Some(FreeTurn::Every) | None => (Vector3::zeros(), 0.0),
    }
}

/// The rotation vector `log(R* Rᵀ)` of the turn still to make from `pose` to `target`, and its
/// angle.
fn whole_turn(pose: &Isometry3<f64>, target: &Isometry3<f64>) -> (Vector3<f64>, f64) {
    let rt: Rotation3<f64> = target.rotation.to_rotation_matrix();
    let r: Rotation3<f64> = pose.rotation.to_rotation_matrix();
    let dw = rotation_vector(&(rt * r.inverse()));
    (dw, dw.norm())
}

/// The rotation vector of the shortest turn taking the z axis `a` of `pose` to the z axis `b`
/// of `target` (perpendicular to both), and its angle `atan2(|a × b|, a·b)`; for opposite
/// axes, a half turn about the x axis of `pose` (perpendicular to `a`).
fn shortest_turn(pose: &Isometry3<f64>, target: &Isometry3<f64>) -> (Vector3<f64>, f64) {
    turn_between(
        &(pose * Vector3::z()),
        &(target * Vector3::z()),
        &(pose * Vector3::x()),
    )
}

/// The rotation vector of the shortest turn taking the unit vector `a` to the unit vector
/// `b` (perpendicular to both), and its angle `atan2(|a × b|, a·b)`; for opposite vectors, a
/// half turn about `across`, a unit vector perpendicular to `a`.
fn turn_between(a: &Vector3<f64>, b: &Vector3<f64>, across: &Vector3<f64>) -> (Vector3<f64>, f64) {
    let u = a.cross(b);
    let (s, c) = (u.norm(), a.dot(b));
    let angle = s.atan2(c);
    let turn = if s > 0.0 {
        u * (angle / s)
    } else if c >= 0.0 {
        Vector3::zeros()
    } else {
        across * core::f64::consts::PI
    };
    (turn, angle)
}
