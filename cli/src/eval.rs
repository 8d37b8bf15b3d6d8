//! `dhgen eval`: T, J, D, C, g, τ, the kinetic and potential energy and the centre of mass at
//! one configuration,
//! on the runtime path, with `--derivatives` those of inverse and forward dynamics, and with
//! `--task-space` the tool's task-space dynamics.

use crate::table::{degrees, trimmed};
use dhgen::Robot;
use dhgen::nalgebra::{DMatrix, DVector, Matrix4};
use dhgen_description::{Angle, JointKind, validate};
use serde_json::{Value, json};
use std::fmt::Write as _;

/// Everything `eval` computes at one configuration.
pub struct Evaluation {
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    pose: Matrix4<f64>,
    jacobian: DMatrix<f64>,
    /// The same in the tool's own axes (`Arm::body_jacobian`).
    body_jacobian: DMatrix<f64>,
    /// `J̇ q̇` (world axes, `Arm::jdot_qdot`) and `J̇_b q̇` (tool axes, `Arm::body_jdot_qdot`):
    /// the tool's acceleration at q̈ = 0, as 1 × 6 rows.
    jdot_qdot: DMatrix<f64>,
    body_jdot_qdot: DMatrix<f64>,
    /// Yoshikawa's manipulability and its gradient ∂m/∂q
    /// (`velocity::manipulability_gradient`); `None` where J has lost rank.
    manipulability: Option<(f64, Vec<f64>)>,
    /// Present when the description has mass properties.
    dynamics: Option<Dynamics>,
}

/// D(q), C(q, q̇), g(q), τ(q, q̇, q̈) and the energies.
struct Dynamics {
    d: DMatrix<f64>,
    c: DMatrix<f64>,
    g: DVector<f64>,
    tau: DVector<f64>,
    /// The kinetic energy T(q, q̇) and the potential energy P(q), J.
    energy: [f64; 2],
    /// The links' mass M (kg) and centre of mass c (m, world frame), and c's Jacobian J_c.
    centre: (f64, [f64; 3]),
    centre_jacobian: DMatrix<f64>,
    /// Present when asked for (`--derivatives`).
    derivatives: Option<Derivatives>,
    /// Present when asked for (`--task-space`): the tool's Λ, μ and p, or why there are none.
    task_space: Option<Result<TaskSpace, String>>,
}

/// The tool's task-space dynamics at (q, q̇) (`dhgen::task_space::tool`).
struct TaskSpace {
    inertia: DMatrix<f64>,
    coriolis: DVector<f64>,
    gravity: DVector<f64>,
}

/// The derivatives of inverse dynamics at (q, q̇, q̈), and of forward dynamics at (q, q̇, τ)
/// for the τ above (whose accelerations are q̈).
struct Derivatives {
    dtau_dq: DMatrix<f64>,
    dtau_dqd: DMatrix<f64>,
    /// (∂q̈/∂q, ∂q̈/∂q̇, D⁻¹); `None` where D(q) is singular to working precision.
    forward: Option<(DMatrix<f64>, DMatrix<f64>, DMatrix<f64>)>,
}

impl Dynamics {
    /// Every result, named as `eval` prints it (the text's titles are longer), with its JSON
    /// key; vectors as one-row matrices.
    fn named(&self) -> Vec<(&'static str, &'static str, DMatrix<f64>)> {
        let row = |v: &DVector<f64>| DMatrix::from_row_slice(1, v.len(), v.as_slice());
        let mut all = vec![
            ("D(q)", "D", self.d.clone()),
            ("C(q, q̇)", "C", self.c.clone()),
            ("g(q)", "g", row(&self.g)),
            ("τ", "tau", row(&self.tau)),
            (
                "T(q, q̇)",
                "kinetic_energy",
                DMatrix::from_element(1, 1, self.energy[0]),
            ),
            (
                "P(q)",
                "potential_energy",
                DMatrix::from_element(1, 1, self.energy[1]),
            ),
            ("M", "mass", DMatrix::from_element(1, 1, self.centre.0)),
            ("c(q)", "com", DMatrix::from_row_slice(1, 3, &self.centre.1)),
            ("J_c(q)", "Jcom", self.centre_jacobian.clone()),
        ];
        if let Some(d) = &self.derivatives {
            all.push(("∂τ/∂q", "dtau_dq", d.dtau_dq.clone()));
            all.push(("∂τ/∂q̇", "dtau_dqd", d.dtau_dqd.clone()));
            if let Some((dq, dqd, inverse)) = &d.forward {
                all.push(("∂q̈/∂q", "dqdd_dq", dq.clone()));
                all.push(("∂q̈/∂q̇", "dqdd_dqd", dqd.clone()));
                all.push(("D(q)⁻¹", "Minv", inverse.clone()));
            }
        }
        if let Some(Ok(t)) = &self.task_space {
            let row = |v: &DVector<f64>| DMatrix::from_row_slice(1, v.len(), v.as_slice());
            all.push(("Λ(q)", "Lambda", t.inertia.clone()));
            all.push(("μ(q, q̇)", "mu", row(&t.coriolis)));
            all.push(("p(q)", "p", row(&t.gravity)));
        }
        all
    }
}

/// Reads the joint positions of the list argument `flag` (`--q`): numbers (rad or m), and for
/// revolute joints also the angle forms of the description format (`90deg`, `-pi/2`).
pub fn positions(robot: &Robot, flag: &str, values: &[String]) -> Result<Vec<f64>, String> {
    check_len(robot, flag, values.len())?;
    robot
        .model()
        .links
        .iter()
        .zip(values)
        .enumerate()
        .map(|(i, (l, v))| match l.joint {
            JointKind::Revolute => Angle::parse(v)
                .map(Angle::radians)
                .map_err(|e| format!("{flag}, joint {}: {e}", i + 1)),
            JointKind::Prismatic => v
                .trim()
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    format!(
                        "{flag}, joint {}: cannot read {v:?}: the joint is prismatic, give metres as a number",
                        i + 1
                    )
                }),
        })
        .collect()
}

/// The values of the list argument `flag` (`--q`): separated by commas or white space. An
/// empty entry between commas (`0,,0`, a leading or trailing comma) is an error naming its
/// position, not skipped; an empty list has no values.
pub fn split(flag: &str, list: &str) -> Result<Vec<String>, String> {
    if list.trim().is_empty() {
        return Ok(Vec::new());
    }
    let mut values = Vec::new();
    for field in list.split(',') {
        let before = values.len();
        values.extend(field.split_whitespace().map(str::to_string));
        if values.len() == before {
            return Err(format!(
                "{flag}: entry {} is empty in {list:?} (one value per joint, separated by commas or spaces)",
                before + 1
            ));
        }
    }
    Ok(values)
}

/// Reads joint velocities or accelerations (`flag` names them): one finite number per
/// joint, all zero when the flag is absent.
pub fn rates(robot: &Robot, flag: &str, list: Option<&str>) -> Result<Vec<f64>, String> {
    let Some(list) = list else {
        return Ok(vec![0.0; robot.dof()]);
    };
    let values = split(flag, list)?;
    check_len(robot, flag, values.len())?;
    values
        .iter()
        .enumerate()
        .map(|(i, v)| {
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| format!("{flag}, joint {}: {v:?} is not a finite number", i + 1))
        })
        .collect()
}

/// Checks that `flag` gave one value per joint.
pub fn check_len(robot: &Robot, flag: &str, len: usize) -> Result<(), String> {
    let n = robot.dof();
    if len == n {
        Ok(())
    } else {
        Err(format!(
            "{flag} has {len} value{}, but {} has {n} joints",
            if len == 1 { "" } else { "s" },
            robot.model().name
        ))
    }
}

/// Evaluates at `q`, `qd`, `qdd` (lengths already checked, values finite), with the
/// derivatives of the dynamics when `derivatives` is set and the tool's task-space dynamics
/// when `task_space` is; the one place
/// `eval` checks its input against the robot (docs/conventions.md, "Non-finite input": the
/// runtime path does not check, so the command does):
///
/// - a joint position beyond the range of any robot (magnitude above 1e3 rad or m, the
///   bound of the description format on angles and lengths) is an error naming the joint;
/// - a result that is not finite (velocities or accelerations so large that the arithmetic
///   overflows) is an error naming the result and entry;
/// - a joint position outside the joint's limits is evaluated, with a warning on standard
///   error naming the joint and its limits (printed only when the evaluation succeeds, so a
///   failure stays one line).
pub fn evaluate(
    robot: &Robot,
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    derivatives: bool,
    task_space: bool,
) -> Result<Evaluation, String> {
    let mut warnings = Vec::new();
    for (i, (l, &x)) in robot.model().links.iter().zip(&q).enumerate() {
        let range = match l.joint {
            JointKind::Revolute => validate::ANGLE,
            JointKind::Prismatic => validate::LENGTH,
        };
        // The description format's rule for angles and lengths, in its words.
        range
            .check_value(x)
            .map_err(|why| format!("--q, joint {}: {why}", i + 1))?;
        let unit = range.unit;
        if let Some([lo, hi]) = l.limits
            && !(lo..=hi).contains(&x)
        {
            let degrees = match l.joint {
                JointKind::Revolute => {
                    format!(" ({} to {})", degrees(lo), degrees(hi))
                }
                JointKind::Prismatic => String::new(),
            };
            warnings.push(format!(
                "dhgen: warning: --q, joint {}: {} {unit} is outside the joint's limits [{}, {}] {unit}{degrees}",
                i + 1,
                trimmed(x, 6),
                trimmed(lo, 6),
                trimmed(hi, 6)
            ));
        }
    }
    let e = compute(robot, q, qd, qdd, derivatives, task_space);
    let matrices: [(&str, DMatrix<f64>); 5] = [
        ("T", DMatrix::from_fn(4, 4, |r, c| e.pose[(r, c)])),
        ("J", e.jacobian.clone()),
        ("Jb", e.body_jacobian.clone()),
        ("J̇q̇", e.jdot_qdot.clone()),
        ("J̇_b q̇", e.body_jdot_qdot.clone()),
    ];
    let dynamics = e
        .dynamics
        .iter()
        .flat_map(Dynamics::named)
        .map(|(name, _, m)| (name, m));
    for (name, m) in matrices.into_iter().chain(dynamics) {
        let bad = (0..m.nrows())
            .flat_map(|r| (0..m.ncols()).map(move |c| (r, c)))
            .find(|&rc| !m[rc].is_finite());
        if let Some((r, c)) = bad {
            let entry = if m.nrows() == 1 {
                format!("entry {}", c + 1)
            } else {
                format!("entry ({}, {})", r + 1, c + 1)
            };
            let largest = |v: &[f64]| trimmed(v.iter().fold(0.0_f64, |m, x| m.max(x.abs())), 6);
            return Err(format!(
                "the result is not finite: {name} {entry} is {}; the input overflows f64 \
                 arithmetic (largest |q̇| {}, |q̈| {}: give smaller --qd and --qdd)",
                m[(r, c)],
                largest(&e.qd),
                largest(&e.qdd)
            ));
        }
    }
    for w in warnings {
        eprintln!("{w}");
    }
    Ok(e)
}

/// T, J and (with mass properties) D, C, g, τ and, if asked, the derivatives and the
/// task-space dynamics at `q`, `qd`, `qdd`, unchecked.
fn compute(
    robot: &Robot,
    q: Vec<f64>,
    qd: Vec<f64>,
    qdd: Vec<f64>,
    derivatives: bool,
    task_space: bool,
) -> Evaluation {
    let pose = robot.fk(&q).to_homogeneous();
    let j = robot.jacobian(&q);
    let jacobian = DMatrix::from_column_slice(6, robot.dof(), j.as_slice());
    let (qv, qdv) = (
        DVector::from_column_slice(&q),
        DVector::from_column_slice(&qd),
    );
    let jb = dhgen::Arm::body_jacobian(robot, &qv);
    let body_jacobian = DMatrix::from_column_slice(6, robot.dof(), jb.as_slice());
    let row = |v: dhgen::nalgebra::Vector6<f64>| DMatrix::from_row_slice(1, 6, v.as_slice());
    let jdot_qdot = row(dhgen::Arm::jdot_qdot(robot, &qv, &qdv));
    let body_jdot_qdot = row(dhgen::Arm::body_jdot_qdot(robot, &qv, &qdv));
    let manipulability = dhgen::velocity::manipulability_gradient(&j, dhgen::velocity::Axes::All)
        .map(|(m, grad)| (m, grad.as_slice().to_vec()));
    let dynamics = robot.has_dynamics().then(|| {
        let tau = robot.inverse_dynamics(&q, &qd, &qdd);
        let derivatives = derivatives.then(|| {
            let (dtau_dq, dtau_dqd) = robot.inverse_dynamics_derivatives(&q, &qd, &qdd);
            Derivatives {
                dtau_dq,
                dtau_dqd,
                forward: robot.forward_dynamics_derivatives(&q, &qd, tau.as_slice()),
            }
        });
        let task_space = task_space.then(|| {
            let (qv, qdv) = (
                DVector::from_column_slice(&q),
                DVector::from_column_slice(&qd),
            );
            dhgen::task_space::tool(robot, &qv, &qdv)
                .map(|t| TaskSpace {
                    inertia: DMatrix::from_column_slice(6, 6, t.inertia().as_slice()),
                    coriolis: DVector::from_column_slice(t.coriolis().as_slice()),
                    gravity: DVector::from_column_slice(t.gravity().as_slice()),
                })
                .map_err(|e| e.to_string())
        });
        Dynamics {
            d: robot.mass_matrix(&q),
            c: robot.coriolis(&q, &qd),
            g: robot.gravity(&q),
            tau,
            energy: [robot.kinetic_energy(&q, &qd), robot.potential_energy(&q)],
            centre: {
                let (mass, c) = robot.center_of_mass(&q);
                (mass, c.coords.into())
            },
            centre_jacobian: {
                let jc = robot.center_of_mass_jacobian(&q);
                DMatrix::from_column_slice(3, jc.ncols(), jc.as_slice())
            },
            derivatives,
            task_space,
        }
    });
    Evaluation {
        q,
        qd,
        qdd,
        pose,
        jacobian,
        body_jacobian,
        jdot_qdot,
        body_jdot_qdot,
        manipulability,
        dynamics,
    }
}

impl Evaluation {
    /// The evaluation as JSON: vectors as arrays, matrices as arrays of rows; `T`, `J` and `Jb`
    /// (the body Jacobian, tool axes), `Jdot_qd` and `Jb_dot_qd` (J̇ q̇ in world axes and
    /// J̇_b q̇ in tool axes, 6 numbers each), `manipulability` and `manipulability_gradient` (null
    /// where J has lost rank) always; `D`, `C`, `g`,
    /// `tau`, `kinetic_energy` and `potential_energy` (numbers), `mass` (the links', kg), `com`
    /// (their centre of mass, world frame, 3 numbers) and `Jcom` (its Jacobian, 3 × n) only
    /// when the robot has dynamics; with `--derivatives` also `dtau_dq`,
    /// `dtau_dqd` (entry `[k][m]` = ∂τ_k/∂x_m) and, unless D(q) is singular, `dqdd_dq`,
    /// `dqdd_dqd` and `Minv` (forward dynamics' derivatives at the τ above); with
    /// `--task-space` the tool's `Lambda`, `mu` and `p`, or `task_space_error` saying why there
    /// are none.
    pub fn json(&self, robot: &Robot) -> Value {
        let rows = |m: &DMatrix<f64>| -> Value {
            Value::from(
                m.row_iter()
                    .map(|r| r.iter().copied().collect::<Vec<f64>>())
                    .collect::<Vec<_>>(),
            )
        };
        let pose = DMatrix::from_fn(4, 4, |r, c| self.pose[(r, c)]);
        let mut v = json!({
            "robot": robot.model().name,
            "dof": robot.dof(),
            "has_dynamics": robot.has_dynamics(),
            "q": self.q,
            "qd": self.qd,
            "qdd": self.qdd,
            "T": rows(&pose),
            "J": rows(&self.jacobian),
            "Jb": rows(&self.body_jacobian),
            "Jdot_qd": self.jdot_qdot.as_slice(),
            "Jb_dot_qd": self.body_jdot_qdot.as_slice(),
            "manipulability": self.manipulability.as_ref().map_or(0.0, |(m, _)| *m),
            "manipulability_gradient": self.manipulability.as_ref().map(|(_, grad)| grad),
        });
        if let (Some(dynamics), Some(obj)) = (&self.dynamics, v.as_object_mut()) {
            for (_, key, m) in dynamics.named() {
                // Numbers, vectors (one row) as arrays, matrices as arrays of rows.
                let value = if matches!(key, "kinetic_energy" | "potential_energy" | "mass") {
                    Value::from(m[(0, 0)])
                } else if matches!(key, "g" | "tau" | "com" | "mu" | "p") {
                    Value::from(m.as_slice().to_vec())
                } else {
                    rows(&m)
                };
                obj.insert(key.into(), value);
            }
            if let Some(Err(why)) = &dynamics.task_space {
                obj.insert("task_space_error".into(), Value::from(why.as_str()));
            }
        }
        v
    }

    /// The evaluation as aligned text.
    pub fn text(&self, robot: &Robot) -> String {
        let mut out = String::new();
        let _ = writeln!(
            out,
            "{} at q = {} (rad, m for prismatic joints)",
            robot.model().name,
            list(&self.q)
        );
        let _ = writeln!(out, "q̇ = {}, q̈ = {}", list(&self.qd), list(&self.qdd));
        let pose = DMatrix::from_fn(4, 4, |r, c| self.pose[(r, c)]);
        block(
            &mut out,
            "T: tool pose in the world frame (base · A1 ⋯ An · tool)",
            &pose,
        );
        block(
            &mut out,
            "J: geometric Jacobian of the tool origin, world axes, rows vx vy vz ωx ωy ωz",
            &self.jacobian,
        );
        block(
            &mut out,
            "J_b: the same in the tool's own axes (body Jacobian, Pinocchio LOCAL, Toolbox jacobe)",
            &self.body_jacobian,
        );
        let _ = writeln!(
            out,
            "\nJ̇q̇ (the tool's acceleration at q̈ = 0, world axes) = {}\nJ̇_b q̇ (the same in tool \
             axes, Pinocchio getFrameJacobianTimeVariation(LOCAL) q̇) = {}",
            list(self.jdot_qdot.as_slice()),
            list(self.body_jdot_qdot.as_slice())
        );
        let _ = match &self.manipulability {
            Some((m, grad)) => writeln!(
                out,
                "\nmanipulability m = {} (product of the Jacobian's singular values), ∂m/∂q = {}",
                trimmed(*m, 6),
                list(grad)
            ),
            None => writeln!(
                out,
                "\nmanipulability m = 0: the Jacobian has lost rank (no gradient there)"
            ),
        };
        match &self.dynamics {
            Some(Dynamics {
                d,
                c,
                g,
                tau,
                energy: [kinetic, potential],
                centre: (mass, centre),
                centre_jacobian,
                derivatives,
                task_space,
            }) => {
                block(&mut out, "D(q): joint-space inertia matrix", d);
                block(
                    &mut out,
                    "C(q, q̇): Coriolis matrix, C_kj = Σ_i c_ijk q̇_i",
                    c,
                );
                block(
                    &mut out,
                    "g(q): gravity torques (transposed)",
                    &DMatrix::from_row_slice(1, g.len(), g.as_slice()),
                );
                block(
                    &mut out,
                    "τ = D(q) q̈ + C(q, q̇) q̇ + g(q) (+ friction), transposed",
                    &DMatrix::from_row_slice(1, tau.len(), tau.as_slice()),
                );
                let _ = writeln!(
                    out,
                    "\nkinetic energy T(q, q̇) = ½ q̇ᵀ D(q) q̇ = {} J; potential energy P(q) = {} J \
                     (zero at the world origin)",
                    trimmed(*kinetic, 6),
                    trimmed(*potential, 6)
                );
                let _ = writeln!(
                    out,
                    "\nlinks' mass M = {} kg, centre of mass c(q) = {} m (world frame)",
                    trimmed(*mass, 6),
                    list(centre)
                );
                block(
                    &mut out,
                    "J_c(q): Jacobian of the centre of mass, world axes (g(q) = −M J_cᵀ gravity)",
                    centre_jacobian,
                );
                if let Some(Derivatives {
                    dtau_dq,
                    dtau_dqd,
                    forward,
                }) = derivatives
                {
                    block(&mut out, "∂τ/∂q: entry (k, m) = ∂τ_k/∂q_m", dtau_dq);
                    block(
                        &mut out,
                        "∂τ/∂q̇ (= 2 C(q, q̇) + viscous friction on the diagonal)",
                        dtau_dqd,
                    );
                    match forward {
                        Some((dq, dqd, inverse)) => {
                            block(&mut out, "∂q̈/∂q at the τ above (= −D⁻¹ ∂τ/∂q)", dq);
                            block(&mut out, "∂q̈/∂q̇ at the τ above (= −D⁻¹ ∂τ/∂q̇)", dqd);
                            block(&mut out, "∂q̈/∂τ = D(q)⁻¹", inverse);
                        }
                        None => {
                            let _ = writeln!(
                                out,
                                "\nno forward dynamics derivatives: D(q) is singular to working precision"
                            );
                        }
                    }
                }
                match task_space {
                    Some(Ok(TaskSpace {
                        inertia,
                        coriolis,
                        gravity,
                    })) => {
                        let row =
                            |v: &DVector<f64>| DMatrix::from_row_slice(1, v.len(), v.as_slice());
                        block(
                            &mut out,
                            "Λ(q) = (J D⁻¹ Jᵀ)⁻¹: task-space inertia of the tool, rows and columns vx vy vz ωx ωy ωz",
                            inertia,
                        );
                        block(
                            &mut out,
                            "μ(q, q̇): task-space Coriolis, centrifugal and friction forces (transposed)",
                            &row(coriolis),
                        );
                        block(
                            &mut out,
                            "p(q): task-space gravity forces (transposed)",
                            &row(gravity),
                        );
                    }
                    Some(Err(why)) => {
                        let why = why.strip_prefix("task space: ").unwrap_or(why);
                        let _ = writeln!(out, "\nno task-space dynamics: {why}");
                    }
                    None => {}
                }
            }
            None => {
                let _ = writeln!(out, "\nno dynamics: the description has no mass properties");
            }
        }
        out
    }
}

fn list(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|x| trimmed(*x, 6)).collect();
    format!("[{}]", parts.join(", "))
}

/// A titled matrix, columns right-aligned to a common width, six decimals.
fn block(out: &mut String, title: &str, m: &DMatrix<f64>) {
    let cells: Vec<Vec<String>> = m
        .row_iter()
        .map(|r| {
            r.iter()
                .map(|x| {
                    if x.is_finite() && x.abs() >= 1e9 {
                        return format!("{x:.6e}");
                    }
                    let s = format!("{x:.6}");
                    // A rounding residue like -1e-17 prints as 0, not -0.000000.
                    if s.trim_start_matches('-')
                        .chars()
                        .all(|c| c == '0' || c == '.')
                    {
                        "0".to_string()
                    } else {
                        s
                    }
                })
                .collect()
        })
        .collect();
    let width = cells.iter().flatten().map(String::len).max().unwrap_or(1);
    let _ = writeln!(out, "\n{title}");
    for row in cells {
        let line: Vec<String> = row.iter().map(|c| format!("{c:>width$}")).collect();
        let _ = writeln!(out, "  {}", line.join("  "));
    }
}
