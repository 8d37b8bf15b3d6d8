//! Writing a model back as a TOML description (the format of docs/robot-description.md),
//! exactly: reading the text back gives an equal model.

use crate::{Angle, Convention, Inertial, JointKind, Pose, RobotModel};
use std::fmt::Write as _;

/// `x` so that reading it back gives the same `f64` (Rust's shortest round-trip form).
fn number(x: f64) -> String {
    // `{:?}` writes `1.0`, `0.3`, `1e-9`: TOML floats, all (a validated model is finite).
    format!("{x:?}")
}

fn angle(a: Angle) -> String {
    number(a.radians())
}

fn vector(v: &[f64]) -> String {
    let parts: Vec<String> = v.iter().map(|x| number(*x)).collect();
    format!("[{}]", parts.join(", "))
}

/// A TOML basic string.
fn string(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            '\n' => out.push_str("\\n"),
            '\t' => out.push_str("\\t"),
            c if c.is_control() => {
                let _ = write!(out, "\\u{:04X}", u32::from(c));
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn pose(p: &Pose) -> String {
    format!(
        "{{ xyz = {}, rpy = [{}] }}",
        vector(&p.xyz),
        p.rpy.map(angle).join(", ")
    )
}

fn inertia(i: &Inertial) -> String {
    let parts: Vec<String> = i
        .inertia_fields()
        .iter()
        .map(|(k, v)| format!("{k} = {}", number(*v)))
        .collect();
    format!("{{ {} }}", parts.join(", "))
}

impl RobotModel {
    /// The description as TOML text that [`RobotModel::from_toml_str`] reads back into an
    /// equal model (numbers in their shortest exact form, angles in radians: quarter turns
    /// written as `1.5707963267948966` are recognised as exact again).
    ///
    /// `allow_nonphysical_inertia` is written when some inertia needs it.
    pub fn to_toml(&self) -> String {
        let mut out = String::new();
        let _ = writeln!(out, "name = {}", string(&self.name));
        if let Some(d) = &self.description {
            let _ = writeln!(out, "description = {}", string(d));
        }
        let convention = match self.convention {
            Convention::Standard => "standard",
            Convention::Modified => "modified",
            Convention::Urdf => "urdf",
        };
        let _ = writeln!(out, "convention = \"{convention}\"");
        let _ = writeln!(out, "gravity = {}", vector(&self.gravity));
        if let Some(b) = &self.base {
            let _ = writeln!(out, "base = {}", pose(b));
        }
        if let Some(t) = &self.tool {
            let _ = writeln!(out, "tool = {}", pose(t));
        }
        if self
            .links
            .iter()
            .filter_map(|l| l.inertial)
            .any(|i| !crate::validate::obeys_triangle_inequality(&i.inertia, i.mass))
        {
            let _ = writeln!(out, "allow_nonphysical_inertia = true");
        }
        for l in &self.links {
            let _ = writeln!(out, "\n[[links]]");
            let joint = match l.joint {
                JointKind::Revolute => "revolute",
                JointKind::Prismatic => "prismatic",
            };
            let _ = writeln!(out, "joint = \"{joint}\"");
            if let Some(p) = &l.placement {
                let _ = writeln!(out, "origin = {}", pose(&p.origin));
                let _ = writeln!(out, "axis = {}", vector(&p.axis));
            } else {
                let _ = writeln!(out, "a = {}", number(l.a));
                let _ = writeln!(out, "alpha = {}", angle(l.alpha));
                let _ = writeln!(out, "d = {}", number(l.d));
                let _ = writeln!(out, "theta = {}", angle(l.theta));
            }
            if let Some(limits) = l.limits {
                let _ = writeln!(out, "limits = {}", vector(&limits));
            }
            if let Some(i) = &l.inertial {
                let _ = writeln!(out, "mass = {}", number(i.mass));
                let _ = writeln!(out, "com = {}", vector(&i.com));
                let _ = writeln!(out, "inertia = {}", inertia(i));
            }
            if let Some(m) = &l.motor {
                let _ = writeln!(
                    out,
                    "motor = {{ inertia = {}, gear = {} }}",
                    number(m.inertia),
                    number(m.gear)
                );
            }
            if let Some(f) = &l.friction {
                let _ = writeln!(
                    out,
                    "friction = {{ viscous = {}, coulomb = {} }}",
                    number(f.viscous),
                    number(f.coulomb)
                );
            }
            if let Some(c) = &l.collision {
                let _ = writeln!(out, "collision = {{ radius = {} }}", number(c.radius));
            }
        }
        out
    }
}
