//! What of a target pose the numeric solver reaches: the whole pose, the tool's position, or
//! its position and the direction of its z axis ([`Task`]).

use crate::rotation::rotation_vector;
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
/// dhgen::robot!(mod panda = "robots/panda.toml");
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
        }
    }

    /// The error vector `[(p* − p)/length; δ]` the solver drives to zero, and the norms of its
    /// two parts in metres and radians: δ is `log(R* Rᵀ)` for the pose, 0 for the position,
    /// and for the axis the rotation vector of the shortest turn taking the tool's z axis to
    /// the target's (perpendicular to the tool's axis, as [`rows`](Task::rows) leaves the
    /// rotation rows).
    pub(super) fn residual(
        self,
        target: &Isometry3<f64>,
        pose: &Isometry3<f64>,
        length: f64,
    ) -> (Vector6<f64>, f64, f64) {
        let dp = target.translation.vector - pose.translation.vector;
        let (dw, dr) = match self {
            Task::Pose => {
                let rt: Rotation3<f64> = target.rotation.to_rotation_matrix();
                let r: Rotation3<f64> = pose.rotation.to_rotation_matrix();
                let dw = rotation_vector(&(rt * r.inverse()));
                (dw, dw.norm())
            }
            Task::Position => (Vector3::zeros(), 0.0),
            Task::PositionAndAxis => shortest_turn(pose, target),
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
    /// the axis does not move it). `pose` is called only for the axis, the one task that
    /// reads it.
    pub(super) fn rows<D: Dim>(
        self,
        j: &mut OMatrix<f64, U6, D>,
        pose: impl FnOnce() -> Isometry3<f64>,
    ) where
        nalgebra::DefaultAllocator: nalgebra::allocator::Allocator<U6, D>,
    {
        match self {
            Task::Pose => {}
            Task::Position => j.fixed_rows_mut::<3>(3).fill(0.0),
            Task::PositionAndAxis => {
                let a = pose() * Vector3::z();
                for mut column in j.column_iter_mut() {
                    let w = column.fixed_rows::<3>(3).into_owned();
                    column.fixed_rows_mut::<3>(3).axpy(-a.dot(&w), &a, 1.0);
                }
            }
        }
    }
}

/// The rotation vector of the shortest turn taking the z axis `a` of `pose` to the z axis `b`
/// of `target` (perpendicular to both), and its angle `atan2(|a × b|, a·b)`; for opposite
/// axes, a half turn about the x axis of `pose` (perpendicular to `a`).
fn shortest_turn(pose: &Isometry3<f64>, target: &Isometry3<f64>) -> (Vector3<f64>, f64) {
    let (a, b) = (pose * Vector3::z(), target * Vector3::z());
    let u = a.cross(&b);
    let (s, c) = (u.norm(), a.dot(&b));
    let angle = s.atan2(c);
    let turn = if s > 0.0 {
        u * (angle / s)
    } else if c >= 0.0 {
        Vector3::zeros()
    } else {
        (pose * Vector3::x()) * core::f64::consts::PI
    };
    (turn, angle)
}
