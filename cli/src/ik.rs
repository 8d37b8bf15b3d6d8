//! `dhgen ik`: the joint values that put the tool at a pose, on the runtime path: every
//! closed-form solution where the arm's structure has them (`dhgen::ik::DecoupledIk`), the
//! numeric solution from a seed (`NumericIk::solve`), and for a redundant arm on request the
//! one nearest a posture or the most manipulable (`NumericIk::solve_preferring`).

use crate::eval::{positions, split};
use crate::table::trimmed;
use dhgen::ik::{DecoupledIk, NumericIk, Preference, Task};
use dhgen::nalgebra::{DVector, Isometry3, Translation3, Unit, UnitQuaternion, Vector3};
use dhgen::rotation::Rpy;
use dhgen::velocity::JacobianSvd;
use dhgen::{Arm, Robot};
use dhgen_description::Angle;
use serde_json::{Value, json};
use std::f64::consts::PI;
use std::fmt::Write as _;

/// What to prefer among a redundant arm's solutions.
pub enum Prefer {
    /// Only the numeric solution from the seed.
    Nothing,
    /// The solution nearest this posture.
    Posture(Vec<f64>),
    /// The most manipulable solution.
    Manipulability,
}

/// The target and the task from `--position X,Y,Z` (m) with `--rpy R,P,Y` (roll, pitch, yaw
/// about the fixed x, y, z axes: radians or the angle forms of the description format; the
/// whole pose), `--axis X,Y,Z` (the tool's z axis: the position and that axis), or neither
/// (the position alone).
pub fn target(
    position: &str,
    rpy: Option<&str>,
    axis: Option<&str>,
) -> Result<(Isometry3<f64>, Task), String> {
    let three = |flag: &str, list: &str, read: &dyn Fn(&str) -> Option<f64>| {
        let values = split(flag, list)?;
        if values.len() != 3 {
            return Err(format!("{flag} takes 3 values, not {}", values.len()));
        }
        values
            .iter()
            .enumerate()
            .map(|(i, v)| {
                read(v).ok_or_else(|| format!("{flag}, entry {}: cannot read {v:?}", i + 1))
            })
            .collect::<Result<Vec<f64>, String>>()
    };
    let number = |v: &str| v.parse::<f64>().ok().filter(|x| x.is_finite());
    let angle = |v: &str| Angle::parse(v).ok().map(Angle::radians);
    let p = three("--position", position, &number)?;
    let (rotation, task) = match (rpy, axis) {
        (Some(list), _) => {
            let r = three("--rpy", list, &angle)?;
            let rotation = Rpy::new(r[0], r[1], r[2]).to_rotation();
            (UnitQuaternion::from_rotation_matrix(&rotation), Task::Pose)
        }
        (None, Some(list)) => {
            let a = three("--axis", list, &number)?;
            let a = Vector3::new(a[0], a[1], a[2]);
            let Some(a) = Unit::try_new(a, 0.0).filter(|a| a.iter().all(|x| x.is_finite())) else {
                return Err("--axis must be a non-zero direction".into());
            };
            // A rotation taking z to the axis (a half turn about x where they are opposite).
            let rotation = UnitQuaternion::rotation_between_axis(&Vector3::z_axis(), &a)
                .unwrap_or_else(|| UnitQuaternion::from_axis_angle(&Vector3::x_axis(), PI));
            (rotation, Task::PositionAndAxis)
        }
        (None, None) => (UnitQuaternion::identity(), Task::Position),
    };
    Ok((
        Isometry3::from_parts(Translation3::new(p[0], p[1], p[2]), rotation),
        task,
    ))
}

/// The task of `--mask X,Y,Z,RX,RY,RZ` (each 1 or 0), `given` that of the other flags: a
/// mask counting rotation components needs the orientation of `--rpy` or `--at` (the whole
/// pose).
pub fn mask(list: &str, given: Task) -> Result<Task, String> {
    let values = split("--mask", list)?;
    if values.len() != 6 {
        return Err(format!(
            "--mask takes 6 values (X,Y,Z,RX,RY,RZ), not {}",
            values.len()
        ));
    }
    let mut mask = [false; 6];
    for (k, v) in values.iter().enumerate() {
        mask[k] = match v.as_str() {
            "1" => true,
            "0" => false,
            _ => return Err(format!("--mask, entry {}: 1 or 0, not {v:?}", k + 1)),
        };
    }
    let task = Task::Mask(mask);
    // The library's rule, said in the flag's terms.
    task.check().map_err(|_| {
        "--mask counts none, two or all three of RX,RY,RZ (two: free to turn about the world \
         axis left out)"
            .to_string()
    })?;
    if mask[3..].contains(&true) && given != Task::Pose {
        return Err(
            "--mask counts rotation components: give the orientation with --rpy or --at".into(),
        );
    }
    Ok(task)
}

/// `mask`'s counted components by name.
fn counted(mask: &[bool; 6]) -> String {
    let names = ["x", "y", "z", "rx", "ry", "rz"];
    let counted: Vec<&str> = names
        .iter()
        .zip(mask)
        .filter(|(_, c)| **c)
        .map(|(n, _)| *n)
        .collect();
    counted.join(", ")
}

/// One solution, as printed.
struct Found {
    q: Vec<f64>,
    position_error: f64,
    orientation_error: f64,
    /// 1-based joints outside their limits.
    outside: Vec<usize>,
    iterations: Option<usize>,
}

impl Found {
    fn new(
        robot: &Robot,
        target: &Isometry3<f64>,
        task: Task,
        q: &[f64],
        iterations: Option<usize>,
    ) -> Self {
        let (position_error, orientation_error) = task.errors(&robot.fk(q), target);
        let outside = (0..robot.dof())
            .filter(|&k| {
                robot
                    .limits(k)
                    .is_some_and(|[lo, hi]| q[k] < lo - 1e-12 || q[k] > hi + 1e-12)
            })
            .map(|k| k + 1)
            .collect();
        Found {
            q: q.to_vec(),
            position_error,
            orientation_error,
            outside,
            iterations,
        }
    }

    fn json(&self) -> Value {
        json!({
            "q": self.q,
            "position_error": self.position_error,
            "orientation_error": self.orientation_error,
            "within_limits": self.outside.is_empty(),
            "iterations": self.iterations,
        })
    }

    fn text(&self) -> String {
        let q: Vec<String> = self.q.iter().map(|x| format!("{x:9.5}")).collect();
        let mut out = format!(
            "[{}]  error {:.1e} m, {:.1e} rad",
            q.join(","),
            self.position_error,
            self.orientation_error
        );
        if let Some(i) = self.iterations {
            write!(out, ", {i} iterations").unwrap();
        }
        if !self.outside.is_empty() {
            let joints: Vec<String> = self.outside.iter().map(|k| k.to_string()).collect();
            write!(out, "  (outside the limits of joint {})", joints.join(", ")).unwrap();
        }
        out
    }
}

/// Solves for `target` and prints the solutions (text, or JSON with `json`). An error where
/// there is none: the pose out of reach, or the numeric solver stalled and no closed form.
pub fn run(
    robot: &Robot,
    target: &Isometry3<f64>,
    task: Task,
    seed: Option<&str>,
    prefer: Prefer,
    json: bool,
) -> Result<String, String> {
    let n = robot.dof();
    let seed = match seed {
        Some(list) => positions(robot, "--seed", &split("--seed", list)?)?,
        None => vec![0.0; n],
    };
    // The closed form solves whole poses.
    let closed = match task {
        Task::Pose => DecoupledIk::from_chain(robot.chain())
            .map(|ik| {
                ik.solve(target)
                    .iter()
                    .map(|q| Found::new(robot, target, task, q.as_slice(), None))
                    .collect::<Vec<_>>()
            })
            .map_err(|e| e.to_string()),
        Task::Mask(_) => Err("it solves whole poses, not a --mask".to_string()),
        _ => Err("it needs the whole pose: give --rpy".to_string()),
    };
    let ik = NumericIk {
        task,
        ..NumericIk::default()
    };
    let seed_v = DVector::from_vec(seed.clone());
    let found = |s: Result<dhgen::ik::Solution<dhgen::nalgebra::Dyn>, _>| {
        s.map(|s| Found::new(robot, target, task, s.q.as_slice(), Some(s.iterations)))
            .map_err(|e: dhgen::ik::IkError| e.to_string())
    };
    let numeric = found(ik.solve(robot, target, &seed_v));
    let (label, preferred) = match &prefer {
        Prefer::Nothing => ("", None),
        Prefer::Posture(p) => {
            let p = DVector::from_vec(p.clone());
            let s = ik.solve_preferring(robot, target, &seed_v, Preference::Posture(&p));
            ("nearest the posture", Some(found(s)))
        }
        Prefer::Manipulability => {
            let most = Preference::Manipulability(dhgen::velocity::Axes::All);
            let s = ik.solve_preferring(robot, target, &seed_v, most);
            ("most manipulable", Some(found(s)))
        }
    };
    let closed_count = closed.as_ref().map_or(0, Vec::len);
    if closed_count == 0 && numeric.is_err() {
        let why = match &closed {
            Ok(_) => "no closed-form solution (the pose is out of reach)".to_string(),
            Err(e) => format!("no closed form ({e})"),
        };
        return Err(format!(
            "no solution for this pose: {why}; {}",
            numeric.err().unwrap_or_default()
        ));
    }
    let manipulability = |q: &[f64]| JacobianSvd::new(&robot.jacobian(q)).manipulability();
    if json {
        let result = |r: &Result<Found, String>| match r {
            Ok(f) => {
                let mut v = f.json();
                v["manipulability"] = json!(manipulability(&f.q));
                v
            }
            Err(e) => json!({ "error": e }),
        };
        let out = json!({
            "position": target.translation.vector.as_slice(),
            "task": match task {
                Task::Position => "position",
                Task::PositionAndAxis => "position and axis",
                Task::Mask(_) => "mask",
                _ => "pose",
            },
            "mask": match task {
                Task::Mask(m) => Some(m.map(u8::from)),
                _ => None,
            },
            "rpy": match task {
                Task::Pose => Some(rpy_of(target)),
                Task::Mask(m) if m[3..].contains(&true) => Some(rpy_of(target)),
                _ => None,
            },
            "axis": (task == Task::PositionAndAxis).then(|| axis_of(target)),
            "closed_form": match &closed {
                Ok(list) => json!({ "solutions": list.iter().map(Found::json).collect::<Vec<_>>() }),
                Err(e) => json!({ "unavailable": e }),
            },
            "seed": seed,
            "numeric": result(&numeric),
            "preferred": preferred.as_ref().map(|p| {
                let mut v = result(p);
                v["preference"] = json!(label);
                v
            }),
        });
        return Ok(format!("{out}\n"));
    }
    let mut out = String::new();
    let t = &target.translation.vector;
    let listed = |v: [f64; 3]| v.map(|x| trimmed(x, 6)).join(", ");
    let orientation = match task {
        Task::Position => "any orientation".to_string(),
        Task::PositionAndAxis => format!("z axis along ({})", listed(axis_of(target))),
        Task::Mask(m) if m[3..].contains(&true) => format!(
            "roll-pitch-yaw ({}) rad, counting {}",
            listed(rpy_of(target)),
            counted(&m)
        ),
        Task::Mask(m) => format!("any orientation, counting {}", counted(&m)),
        _ => format!("roll-pitch-yaw ({}) rad", listed(rpy_of(target))),
    };
    writeln!(
        out,
        "{}: tool at ({}) m, {orientation}",
        robot.model().name,
        listed([t.x, t.y, t.z]),
    )
    .unwrap();
    match &closed {
        Ok(list) => {
            let within = list.iter().filter(|f| f.outside.is_empty()).count();
            writeln!(
                out,
                "closed form (kinematic decoupling): {} solution{}, {within} within the limits",
                list.len(),
                if list.len() == 1 { "" } else { "s" }
            )
            .unwrap();
            for (i, f) in list.iter().enumerate() {
                writeln!(out, "  {:>2}  {}", i + 1, f.text()).unwrap();
            }
        }
        Err(e) => writeln!(out, "closed form: none ({e})").unwrap(),
    }
    let seed_text: Vec<String> = seed.iter().map(|x| trimmed(*x, 4)).collect();
    writeln!(out, "numeric, from the seed [{}]:", seed_text.join(", ")).unwrap();
    let line = |r: &Result<Found, String>| match r {
        Ok(f) => format!(
            "      {}\n      manipulability {:.4}",
            f.text(),
            manipulability(&f.q)
        ),
        Err(e) => format!("      {e}"),
    };
    writeln!(out, "{}", line(&numeric)).unwrap();
    if let (Some(p), Prefer::Posture(posture)) = (&preferred, &prefer) {
        let posture: Vec<String> = posture.iter().map(|x| trimmed(*x, 4)).collect();
        writeln!(out, "nearest the posture [{}]:", posture.join(", ")).unwrap();
        writeln!(out, "{}", line(p)).unwrap();
    } else if let Some(p) = &preferred {
        writeln!(out, "{label}:").unwrap();
        writeln!(out, "{}", line(p)).unwrap();
    }
    Ok(out)
}

/// The pose's z axis in the world.
fn axis_of(pose: &Isometry3<f64>) -> [f64; 3] {
    let a = pose.rotation * Vector3::z();
    [a.x, a.y, a.z]
}

/// Roll, pitch, yaw of the pose (the |pitch| ≤ π/2 branch).
fn rpy_of(pose: &Isometry3<f64>) -> [f64; 3] {
    let [r, _] = Rpy::from_rotation(&pose.rotation.to_rotation_matrix());
    [r.roll, r.pitch, r.yaw]
}
