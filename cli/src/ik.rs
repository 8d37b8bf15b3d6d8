//! `dhgen ik`: the joint values that put the tool at a pose, on the runtime path: every
//! closed-form solution where the arm's structure has them (`dhgen::ik::DecoupledIk`), the
//! numeric solution from a seed (`NumericIk::solve`), and for a redundant arm on request the
//! one nearest a posture or the most manipulable (`NumericIk::solve_preferring`).

use crate::eval::{positions, split};
use crate::table::trimmed;
use dhgen::ik::{DecoupledIk, NumericIk, Preference, pose_error};
use dhgen::nalgebra::{DVector, Isometry3, Translation3, UnitQuaternion};
use dhgen::rotation::Rpy;
use dhgen::velocity::JacobianSvd;
use dhgen::{Arm, Robot};
use dhgen_model::Angle;
use serde_json::{Value, json};
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

/// The tool pose from `--position X,Y,Z` (m) and `--rpy R,P,Y` (roll, pitch, yaw about the
/// fixed x, y, z axes: radians or the angle forms of the description format; 0 if omitted).
pub fn pose(position: &str, rpy: Option<&str>) -> Result<Isometry3<f64>, String> {
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
    let metres = |v: &str| v.parse::<f64>().ok().filter(|x| x.is_finite());
    let angle = |v: &str| Angle::parse(v).ok().map(Angle::radians);
    let p = three("--position", position, &metres)?;
    let r = match rpy {
        Some(list) => three("--rpy", list, &angle)?,
        None => vec![0.0; 3],
    };
    let rotation = Rpy::new(r[0], r[1], r[2]).to_rotation();
    Ok(Isometry3::from_parts(
        Translation3::new(p[0], p[1], p[2]),
        UnitQuaternion::from_rotation_matrix(&rotation),
    ))
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
    fn new(robot: &Robot, target: &Isometry3<f64>, q: &[f64], iterations: Option<usize>) -> Self {
        let (position_error, orientation_error) = pose_error(&robot.fk(q), target);
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
    seed: Option<&str>,
    prefer: Prefer,
    json: bool,
) -> Result<String, String> {
    let n = robot.dof();
    let seed = match seed {
        Some(list) => positions(robot, "--seed", &split("--seed", list)?)?,
        None => vec![0.0; n],
    };
    let closed = DecoupledIk::from_chain(robot.chain()).map(|ik| {
        ik.solve(target)
            .iter()
            .map(|q| Found::new(robot, target, q.as_slice(), None))
            .collect::<Vec<_>>()
    });
    let ik = NumericIk::default();
    let seed_v = DVector::from_vec(seed.clone());
    let found = |s: Result<dhgen::ik::Solution<dhgen::nalgebra::Dyn>, _>| {
        s.map(|s| Found::new(robot, target, s.q.as_slice(), Some(s.iterations)))
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
            "rpy": rpy_of(target),
            "closed_form": match &closed {
                Ok(list) => json!({ "solutions": list.iter().map(Found::json).collect::<Vec<_>>() }),
                Err(e) => json!({ "unavailable": e.to_string() }),
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
    let r = rpy_of(target);
    writeln!(
        out,
        "{}: tool at ({}, {}, {}) m, roll-pitch-yaw ({}, {}, {}) rad",
        robot.model().name,
        trimmed(t.x, 6),
        trimmed(t.y, 6),
        trimmed(t.z, 6),
        trimmed(r[0], 6),
        trimmed(r[1], 6),
        trimmed(r[2], 6)
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

/// Roll, pitch, yaw of the pose (the |pitch| ≤ π/2 branch).
fn rpy_of(pose: &Isometry3<f64>) -> [f64; 3] {
    let [r, _] = Rpy::from_rotation(&pose.rotation.to_rotation_matrix());
    [r.roll, r.pitch, r.yaw]
}
