//! `dhgen info`: the DH table, the joints and the mass properties of a description, and
//! whether the arm has a spherical wrist.

use crate::table::{Align, Table, degrees, trimmed};
use dhgen::Robot;
use dhgen_description::{Convention, JointKind, Link, Pose, RobotModel};
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
    out += &match model.convention {
        Convention::Urdf => joint_table(model),
        _ => dh_table(model),
    }
    .render();
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
        Convention::Urdf => "urdf (joint frames): A_j = origin_j · Rot(axis_j, q_j)",
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
        Convention::Modified | Convention::Urdf => ("aⱼ₋₁", "αⱼ₋₁"),
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

/// A `urdf` description's joints: where each sits (origin in the previous link frame) and
/// its axis.
fn joint_table(model: &RobotModel) -> Table {
    let mut t = Table::new(&[
        ("j", Align::Right),
        ("joint", Align::Left),
        ("origin xyz [m]", Align::Left),
        ("origin rpy", Align::Left),
        ("axis", Align::Left),
        ("q⁻", Align::Right),
        ("q⁺", Align::Right),
    ]);
    for (i, l) in model.links.iter().enumerate() {
        let Some(p) = &l.placement else { continue };
        let rpy: Vec<String> = p.origin.rpy.iter().map(|a| degrees(a.radians())).collect();
        let (lo, hi) = match l.limits {
            Some([lo, hi]) => (limit(l, lo), limit(l, hi)),
            None => ("-".to_string(), "-".to_string()),
        };
        t.row(vec![
            (i + 1).to_string(),
            match l.joint {
                JointKind::Revolute => "revolute".to_string(),
                JointKind::Prismatic => "prismatic".to_string(),
            },
            vector(&p.origin.xyz),
            format!("[{}]", rpy.join(", ")),
            vector(&p.axis),
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
            row.push(l.motor.map_or("-".into(), |mo| trimmed(mo.armature(), 6)));
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

/// Whether the last three joints are revolute and their axes meet in one point (the one
/// test of the structure, [`dhgen::ChainRef::spherical_wrist`]: the same answer as the
/// generated module's `SPHERICAL_WRIST`); with the wrist centre at q = 0 when they do.
fn wrist_text(robot: &Robot) -> String {
    let n = robot.dof();
    match robot.chain().spherical_wrist() {
        Ok(w) => format!(
            "yes: the axes of joints {}, {}, {n} meet in one point (wrist centre at q = 0: {} m, world frame)",
            n - 2,
            n - 1,
            vector(&w.centre_at_zero)
        ),
        Err(dhgen::model::NotSpherical::TooFewJoints { dof }) => format!("no (only {dof} joints)"),
        Err(why) => format!(
            "no: the axes of joints {}, {}, {n} do not meet in one point ({why})",
            n - 2,
            n - 1
        ),
    }
}

/// What reading a URDF file decided: the chain's ends, its joints by name, the joints held
/// at zero, and every value read as an exact quarter turn or coordinate axis.
pub fn urdf_report(u: &dhgen_description::urdf::UrdfRobot) -> String {
    let mut out = String::new();
    let field = |out: &mut String, name: &str, value: &str| {
        let _ = writeln!(out, "{:<16} {value}", format!("{name}:"));
    };
    field(
        &mut out,
        "URDF chain",
        &format!(
            "from link `{}` to link `{}` (the tool frame)",
            u.base, u.tip
        ),
    );
    let names: Vec<String> = u
        .joints
        .iter()
        .enumerate()
        .map(|(i, j)| format!("{} {}", i + 1, j.name))
        .collect();
    field(&mut out, "URDF joints", &names.join(", "));
    field(
        &mut out,
        "held at zero",
        &if u.locked.is_empty() {
            "none".to_string()
        } else {
            format!(
                "{} (off the chain; their links' mass merged)",
                u.locked.join(", ")
            )
        },
    );
    if !u.left_out.is_empty() {
        field(
            &mut out,
            "left out",
            &format!(
                "{} (floating or planar joints off the chain: the free bodies they join are not \
                 attached, and no mass of theirs is merged)",
                u.left_out.join(", ")
            ),
        );
    }
    if !u.massless.is_empty() {
        field(
            &mut out,
            "massless",
            &format!(
                "{} (moved by a joint, no <inertial> on them or fixed to them)",
                u.massless.join(", ")
            ),
        );
    }
    if u.snaps.is_empty() {
        field(
            &mut out,
            "snapped",
            "none (no value within the tolerance of a quarter turn)",
        );
    } else {
        field(
            &mut out,
            "snapped",
            &format!("{} values read as exact:", u.snaps.len()),
        );
        for s in &u.snaps {
            if s.what.contains("<axis") {
                let _ = writeln!(
                    out,
                    "  line {}: {}: {:.3e} rad from a coordinate axis, read as that axis",
                    s.loc, s.what, s.from
                );
            } else {
                let _ = writeln!(
                    out,
                    "  line {}: {}: {} read as {} ({}°)",
                    s.loc,
                    s.what,
                    s.from,
                    s.to,
                    trimmed(s.to.to_degrees(), 6)
                );
            }
        }
    }
    out
}
