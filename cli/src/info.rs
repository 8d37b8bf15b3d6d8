//! `dhgen info`: the DH table, the joints and the mass properties of a description, and
//! whether the arm has a spherical wrist.

use crate::table::{Align, Table, degrees, trimmed};
use dhgen::Robot;
use dhgen::nalgebra::{Matrix3, Vector3};
use dhgen_model::{Convention, JointKind, Link, Pose, RobotModel};
use std::fmt::Write as _;

/// The report printed by `dhgen info`.
pub fn report(robot: &Robot) -> String {
    let model = robot.model();
    let mut out = String::new();
    let kinds: String = model
        .links
        .iter()
        .map(|l| match l.joint {
            JointKind::Revolute => 'R',
            JointKind::Prismatic => 'P',
        })
        .collect();
    let title = match &model.description {
        Some(d) => format!("{} — {d}", model.name),
        None => model.name.clone(),
    };
    let _ = writeln!(out, "{title}");
    out += &dh_table(model).render();
    if model.has_dynamics() {
        out += &dynamics_table(model).render();
    }

    let revolute = kinds.chars().filter(|c| *c == 'R').count();
    let prismatic = kinds.len() - revolute;
    let conv = match model.convention {
        Convention::Standard => "standard (distal, Spong): A_j = Rz(θ_j) Tz(d_j) Tx(a_j) Rx(α_j)",
        Convention::Modified => {
            "modified (proximal, Craig): A_j = Rx(α_{j-1}) Tx(a_{j-1}) Rz(θ_j) Tz(d_j)"
        }
    };
    let field = |out: &mut String, name: &str, value: &str| {
        let _ = writeln!(out, "{:<16} {value}", format!("{name}:"));
    };
    field(&mut out, "DOF", &model.dof().to_string());
    field(&mut out, "convention", conv);
    field(
        &mut out,
        "joint types",
        &format!("{kinds} ({revolute} revolute, {prismatic} prismatic)"),
    );
    let limits = model.links.iter().filter(|l| l.limits.is_some()).count();
    field(
        &mut out,
        "limits",
        &format!("{limits} of {} joints (table columns q⁻, q⁺)", model.dof()),
    );
    field(
        &mut out,
        "gravity",
        &format!("{} m/s² (world frame)", vector(&model.gravity)),
    );
    field(&mut out, "base", &pose(model.base_pose()));
    field(&mut out, "tool", &pose(model.tool_pose()));
    if model.has_dynamics() {
        let total: f64 = model
            .links
            .iter()
            .filter_map(|l| l.inertial.map(|i| i.mass))
            .sum();
        let masses: Vec<String> = model
            .links
            .iter()
            .map(|l| trimmed(l.inertial.map_or(0.0, |i| i.mass), 4))
            .collect();
        field(
            &mut out,
            "masses",
            &format!("[{}] kg, total {} kg", masses.join(", "), trimmed(total, 4)),
        );
    } else {
        field(
            &mut out,
            "dynamics",
            "none (no mass properties: kinematics only)",
        );
    }
    field(&mut out, "spherical wrist", &wrist_text(robot));
    out
}

/// The DH table: one row per joint, the joint variable shown where it enters.
fn dh_table(model: &RobotModel) -> Table {
    let (a_head, alpha_head) = match model.convention {
        Convention::Standard => ("aⱼ", "αⱼ"),
        Convention::Modified => ("aⱼ₋₁", "αⱼ₋₁"),
    };
    let mut t = Table::new(&[
        ("j", Align::Right),
        ("joint", Align::Left),
        ("θⱼ", Align::Left),
        ("dⱼ", Align::Right),
        (a_head, Align::Right),
        (alpha_head, Align::Right),
        ("q⁻", Align::Right),
        ("q⁺", Align::Right),
    ]);
    for (i, l) in model.links.iter().enumerate() {
        let j = i + 1;
        let (theta, d) = match l.joint {
            JointKind::Revolute => (
                with_offset(j, &degrees(l.theta.radians()), l.theta.radians()),
                trimmed(l.d, 6),
            ),
            JointKind::Prismatic => (
                degrees(l.theta.radians()),
                with_offset(j, &trimmed(l.d, 6), l.d),
            ),
        };
        let (lo, hi) = match l.limits {
            Some([lo, hi]) => (limit(l, lo), limit(l, hi)),
            None => ("-".to_string(), "-".to_string()),
        };
        t.row(vec![
            j.to_string(),
            match l.joint {
                JointKind::Revolute => "revolute".to_string(),
                JointKind::Prismatic => "prismatic".to_string(),
            },
            theta,
            d,
            trimmed(l.a, 6),
            degrees(l.alpha.radians()),
            lo,
            hi,
        ]);
    }
    t
}

/// `q3`, or `q3 + 0.1` / `q1 − 90°` when the description adds an offset.
fn with_offset(j: usize, shown: &str, offset: f64) -> String {
    if offset == 0.0 {
        format!("q{j}")
    } else if let Some(magnitude) = shown.strip_prefix('-') {
        format!("q{j} − {magnitude}")
    } else {
        format!("q{j} + {shown}")
    }
}

/// A joint limit: degrees for a revolute joint, metres for a prismatic one.
fn limit(l: &Link, x: f64) -> String {
    match l.joint {
        JointKind::Revolute => format!("{}°", trimmed(x.to_degrees(), 1)),
        JointKind::Prismatic => format!("{} m", trimmed(x, 4)),
    }
}

/// Masses, centres of mass and inertias, plus motors and friction when any joint has them.
fn dynamics_table(model: &RobotModel) -> Table {
    let motors = model.links.iter().any(|l| l.motor.is_some());
    let friction = model.links.iter().any(|l| l.friction.is_some());
    let mut columns = vec![
        ("j", Align::Right),
        ("m [kg]", Align::Right),
        ("centre of mass [m]", Align::Left),
        ("I_xx, I_yy, I_zz [kg·m²]", Align::Left),
        ("I_xy, I_yz, I_xz", Align::Left),
    ];
    if motors {
        columns.extend([("Jm·G² [kg·m²]", Align::Right)]);
    }
    if friction {
        columns.extend([("viscous", Align::Right), ("Coulomb", Align::Right)]);
    }
    let mut t = Table::new(&columns);
    for (i, l) in model.links.iter().enumerate() {
        let Some(inr) = l.inertial else { continue };
        let m = inr.inertia;
        let mut row = vec![
            (i + 1).to_string(),
            trimmed(inr.mass, 4),
            vector(&inr.com),
            vector(&[m[0][0], m[1][1], m[2][2]]),
            vector(&[m[0][1], m[1][2], m[0][2]]),
        ];
        if motors {
            row.push(
                l.motor
                    .map_or("-".into(), |mo| trimmed(mo.reflected_inertia(), 6)),
            );
        }
        if friction {
            row.push(l.friction.map_or("-".into(), |f| trimmed(f.viscous, 6)));
            row.push(l.friction.map_or("-".into(), |f| trimmed(f.coulomb, 6)));
        }
        t.row(row);
    }
    t
}

fn vector(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|x| trimmed(*x, 6)).collect();
    format!("[{}]", parts.join(", "))
}

fn pose(p: Option<&Pose>) -> String {
    match p {
        None => "identity".to_string(),
        Some(p) => {
            let rpy: Vec<String> = p.rpy.iter().map(|a| degrees(a.radians())).collect();
            format!("xyz {} m, rpy [{}]", vector(&p.xyz), rpy.join(", "))
        }
    }
}

/// Whether the last three joints are revolute and their axes meet in one point at every
/// configuration; with the wrist centre at q = 0 when they do.
fn wrist_text(robot: &Robot) -> String {
    let n = robot.dof();
    if n < 3 {
        return format!("no (only {n} joints)");
    }
    let model = robot.model();
    if model.links[n - 3..]
        .iter()
        .any(|l| l.joint != JointKind::Revolute)
    {
        return format!("no (joints {}–{n} are not all revolute)", n - 2);
    }
    match spherical_wrist_centre(robot) {
        Some(c) => format!(
            "yes: the axes of joints {}, {}, {n} meet in one point (wrist centre at q = 0: {} m, world frame)",
            n - 2,
            n - 1,
            vector(&[c.x, c.y, c.z])
        ),
        None => format!(
            "no: the axes of joints {}, {}, {n} do not meet in one point",
            n - 2,
            n - 1
        ),
    }
}

/// Tests the wrist at q = 0 and at several pseudo-random configurations (within the limits
/// where given): at each, the point closest to the three axes (least squares) must lie on
/// all of them. Returns that point at q = 0.
pub fn spherical_wrist_centre(robot: &Robot) -> Option<Vector3<f64>> {
    let n = robot.dof();
    let mut seed = 0x9E37_79B9_7F4A_7C15_u64;
    let mut uniform = move || {
        // SplitMix64: a fixed sequence, so `info` prints the same thing every time.
        seed = seed.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = seed;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut centre = None;
    for sample in 0..8 {
        let q: Vec<f64> = robot
            .model()
            .links
            .iter()
            .map(|l| {
                if sample == 0 {
                    return 0.0;
                }
                let [lo, hi] = l.limits.unwrap_or(match l.joint {
                    JointKind::Revolute => [-std::f64::consts::PI, std::f64::consts::PI],
                    JointKind::Prismatic => [-0.5, 0.5],
                });
                lo + (hi - lo) * uniform()
            })
            .collect();
        let axes: Vec<(Vector3<f64>, Vector3<f64>)> =
            (n - 3..n).map(|j| joint_axis(robot, &q, j)).collect();
        let c = common_point(&axes)?;
        if sample == 0 {
            centre = Some(c);
        }
    }
    centre
}

/// Joint `j`'s axis at `q` in the world frame: a point on it and its unit direction.
fn joint_axis(robot: &Robot, q: &[f64], j: usize) -> (Vector3<f64>, Vector3<f64>) {
    let model = robot.model();
    // Frame 0 is the base; `Robot::frames` gives frames 1..n.
    let frame = model.convention.joint_frame(j);
    if frame == 0 {
        let base = model
            .base_pose()
            .map_or(dhgen_model::Frame::identity(), |p| p.frame::<f64>());
        let z = base.z_axis();
        return (Vector3::from(base.p), Vector3::from(z));
    }
    let f = robot.frames(q)[frame - 1];
    (
        f.translation.vector,
        f.rotation * Vector3::new(0.0, 0.0, 1.0),
    )
}

/// The point nearest to all lines in the least-squares sense, if the lines are not all
/// parallel and that point lies on every line (to 1e-9 relative to the arm's size).
fn common_point(lines: &[(Vector3<f64>, Vector3<f64>)]) -> Option<Vector3<f64>> {
    let mut a = Matrix3::zeros();
    let mut b = Vector3::zeros();
    let mut scale = 1.0_f64;
    for (p, z) in lines {
        let proj = Matrix3::identity() - z * z.transpose();
        a += proj;
        b += proj * p;
        scale = scale.max(p.norm());
    }
    // All lines parallel: the normal equations are singular along the common direction.
    if a.symmetric_eigenvalues().min() < 1e-9 {
        return None;
    }
    let x = a.try_inverse()? * b;
    let on_all = lines.iter().all(|(p, z)| {
        let d = x - p;
        (d - z * z.dot(&d)).norm() <= 1e-9 * scale
    });
    on_all.then_some(x)
}
