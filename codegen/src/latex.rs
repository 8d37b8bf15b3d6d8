//! LaTeX for the normal form: D(q), the Christoffel symbols c_ijk, g(q) and P(q) written as
//! equations, straight from the polynomials the generator works with.
//!
//! A term is a coefficient and a product of symbols: `c_2` = cos θ₂, `s_2` = sin θ₂ (θ_j
//! the full joint angle, offset included), `d_3` the full displacement of a prismatic
//! joint, and with [`Style::cumulative`] `c_{23}` = cos(θ₂ + θ₃) for runs of parallel axes.
//! Indices are 1-based, as in the textbook; they are separated by commas once a robot has
//! ten joints or more (`c_{10,11}`).

use crate::derive::{Derivation, parallel_runs, vars};
use crate::poly::{Basis, Mono, Poly, Var};
use dhgen_description::RobotModel;
use std::fmt::Write as _;

/// How polynomials are written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Style {
    /// Significant digits of each coefficient.
    pub digits: usize,
    /// Rewrite runs of parallel axes in cumulative angles (`c_{23}`) where that gives
    /// fewer terms, as the generator does before emitting code.
    pub cumulative: bool,
    /// Terms per line inside `align*` before breaking the line.
    pub terms_per_line: usize,
}

impl Default for Style {
    fn default() -> Style {
        Style {
            digits: 4,
            cumulative: false,
            terms_per_line: 4,
        }
    }
}

/// What the slots of a polynomial stand for, and how to name them.
pub struct Symbols<'a> {
    /// The variable kind of each joint.
    pub vars: &'a [Var],
    /// Plain or cumulative angles.
    pub basis: &'a Basis,
}

impl Symbols<'_> {
    fn index(&self, joints: &[usize]) -> String {
        let wide = self.vars.len() >= 10;
        let parts: Vec<String> = joints.iter().map(|j| (j + 1).to_string()).collect();
        let text = parts.join(if wide { "," } else { "" });
        if text.chars().count() == 1 {
            text
        } else {
            format!("{{{text}}}")
        }
    }

    /// The symbol of slot `v` (`2j` cosine or displacement, `2j + 1` sine).
    fn symbol(&self, v: usize) -> String {
        let j = v / 2;
        if self.vars[j] == Var::Length {
            return format!("d_{}", self.index(&[j]));
        }
        let joints: Vec<usize> = (self.basis.start[j]..=j).collect();
        let letter = if v.is_multiple_of(2) { 'c' } else { 's' };
        format!("{letter}_{}", self.index(&joints))
    }
}

/// `|x|` to `digits` significant digits, without trailing zeros; `\times 10^{e}` outside
/// `1e-4 ≤ |x| < 1e6`.
fn magnitude(x: f64, digits: usize) -> String {
    let digits = digits.max(1);
    let sci = format!("{:.*e}", digits - 1, x.abs());
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let trim = |s: &str| -> String {
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s.to_string()
        }
    };
    if (-4..6).contains(&exp) {
        let decimals = usize::try_from(i32::try_from(digits).unwrap_or(17) - 1 - exp).unwrap_or(0);
        trim(&format!("{:.*}", decimals, x.abs()))
    } else {
        format!("{} \\times 10^{{{exp}}}", trim(mantissa))
    }
}

/// The terms of `p` as `(negative, text)`, constant first, then by degree.
fn terms(p: &Poly, sym: &Symbols<'_>, style: &Style) -> Vec<(bool, String)> {
    let key = |m: &Mono| {
        let degree: u32 = m.iter().map(|e| u32::from(*e)).sum();
        let factors: Vec<(usize, u8)> = m
            .iter()
            .enumerate()
            .filter(|(_, e)| **e > 0)
            .map(|(v, e)| (v, *e))
            .collect();
        (degree, factors)
    };
    let mut sorted: Vec<&(Mono, f64)> = p.terms().iter().collect();
    sorted.sort_by_key(|(m, _)| key(m));
    sorted
        .into_iter()
        .map(|(m, c)| {
            let factors: Vec<String> = m
                .iter()
                .enumerate()
                .filter(|(_, e)| **e > 0)
                .map(|(v, e)| {
                    let s = sym.symbol(v);
                    match e {
                        1 => s,
                        e if *e < 10 => format!("{s}^{e}"),
                        e => format!("{s}^{{{e}}}"),
                    }
                })
                .collect();
            let k = magnitude(*c, style.digits);
            let text = match (factors.is_empty(), k.as_str()) {
                (true, _) => k,
                (false, "1") => factors.join(" "),
                (false, _) => format!("{k}\\,{}", factors.join(" ")),
            };
            (*c < 0.0, text)
        })
        .collect()
}

/// `p` as a LaTeX expression on one line, e.g. `0.35 + 2.3\,c_2 s_3 - 0.1\,c_3^2`; `0` for
/// the zero polynomial.
#[cfg(test)]
pub fn poly(p: &Poly, sym: &Symbols<'_>, style: &Style) -> String {
    join(&terms(p, sym, style), usize::MAX)
}

/// Terms joined with their signs, with an `align*` line break every `per_line` terms.
fn join(terms: &[(bool, String)], per_line: usize) -> String {
    if terms.is_empty() {
        return "0".to_string();
    }
    let mut out = String::new();
    for (i, (negative, text)) in terms.iter().enumerate() {
        if i == 0 {
            if *negative {
                out.push('-');
            }
        } else {
            if i % per_line.max(1) == 0 {
                out.push_str(" \\\\\n    &\\qquad");
            }
            out.push_str(if *negative { " - " } else { " + " });
        }
        out.push_str(text);
    }
    out
}

/// `p` in cumulative angles of `runs` when that has fewer terms (returning the basis used).
fn in_best_basis(p: &Poly, vars: &[Var], runs: &Basis, plain: &Basis) -> (Poly, bool) {
    if runs == plain {
        return (p.clone(), false);
    }
    let mut q = p.clone();
    for k in 1..vars.len() {
        if runs.start[k] != k {
            q = q.to_cumulative(k, vars);
        }
    }
    if q.terms().len() < p.terms().len() {
        (q, true)
    } else {
        (p.clone(), false)
    }
}

/// Why [`dynamics_equations`] has nothing to print.
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Unavailable {
    /// The description has no mass properties.
    #[error("the description has no mass properties, so there is no D(q), c_ijk or g(q) to print")]
    NoDynamics,
    /// More joints than a normal form has variables for (two per joint).
    #[error(
        "the robot has {joints} joints; the closed forms of D(q), c_ijk and g(q) are built \
         for at most {most} joints (two variables per joint in a monomial)"
    )]
    TooManyJoints {
        /// The robot's joints.
        joints: usize,
        /// The most the normal form takes.
        most: usize,
    },
    /// Building a closed form ran out of its budget of term operations.
    #[error(
        "the closed form of {quantity} is too large to print: building it takes more than the \
         {budget} term operations allowed (multiplying polynomials of a and b terms counts \
         a·b, adding them a + b); `dhgen eval` evaluates the dynamics at any configuration"
    )]
    TooLarge {
        /// What could not be built: `D(q)` (from which c_ijk is derived) or `g(q)`.
        quantity: &'static str,
        /// Its budget ([`MASS_MATRIX_WORK`](crate::derive::MASS_MATRIX_WORK) or
        /// [`GRAVITY_WORK`](crate::derive::GRAVITY_WORK)).
        budget: u64,
    },
}

/// D(q) (`d_ij`, i ≤ j), the Christoffel symbols (`c_ijk`, i ≤ j), g(q) and the potential
/// energy P(q) (where its normal form fits g's budget) of `model` as LaTeX `align*` blocks,
/// each non-zero entry one equation, with `%` comments saying what the symbols mean.
pub fn dynamics_equations(model: &RobotModel, style: &Style) -> Result<String, Unavailable> {
    if !model.has_dynamics() {
        return Err(Unavailable::NoDynamics);
    }
    let n = model.dof();
    let structure = model.chain();
    let chain = structure.view();
    let v = vars(chain);
    let plain = Basis::joint_angles(n);
    let runs = if style.cumulative {
        parallel_runs(chain)
    } else {
        plain.clone()
    };
    let most = crate::derive::NORMAL_FORM_JOINTS;
    if n > most {
        return Err(Unavailable::TooManyJoints { joints: n, most });
    }
    let dv = Derivation::new(chain);
    // c_ijk are D's derivatives: built whenever D is, so D's budget is theirs.
    let no_d = || Unavailable::TooLarge {
        quantity: "D(q) (from which c_ijk is derived)",
        budget: crate::derive::MASS_MATRIX_WORK,
    };
    let d = dv.mass_matrix_polys().ok_or_else(no_d)?;
    let c = dv.christoffel_polys().ok_or_else(no_d)?;
    let g = dv.gravity_polys().ok_or(Unavailable::TooLarge {
        quantity: "g(q)",
        budget: crate::derive::GRAVITY_WORK,
    })?;

    let idx = |ids: &[usize]| {
        let parts: Vec<String> = ids.iter().map(|i| (i + 1).to_string()).collect();
        parts.join(if n >= 10 { "," } else { "" })
    };
    let mut cumulative_used = false;
    let mut equation = |lhs: String, p: &Poly| -> String {
        let (p, used) = in_best_basis(p, &v, &runs, &plain);
        cumulative_used |= used;
        let basis = if used { &runs } else { &plain };
        let sym = Symbols { vars: &v, basis };
        format!(
            "  {lhs} &= {}",
            join(&terms(&p, &sym, style), style.terms_per_line)
        )
    };
    let block = |lines: Vec<String>| -> String {
        if lines.is_empty() {
            "% (all zero)\n".to_string()
        } else {
            format!(
                "\\begin{{align*}}\n{}\n\\end{{align*}}\n",
                lines.join(" \\\\\n")
            )
        }
    };

    // D and c_ijk are symmetric (d_ij = d_ji, c_ijk = c_jik): i ≤ j only.
    let mut d_lines = Vec::new();
    for (i, row) in d.iter().enumerate() {
        for (j, p) in row.iter().enumerate().skip(i) {
            if !p.is_zero() {
                d_lines.push(equation(format!("d_{{{}}}", idx(&[i, j])), p));
            }
        }
    }
    let mut c_lines = Vec::new();
    for (i, plane) in c.iter().enumerate() {
        for (j, column) in plane.iter().enumerate().skip(i) {
            for (k, p) in column.iter().enumerate() {
                if !p.is_zero() {
                    c_lines.push(equation(format!("c_{{{}}}", idx(&[i, j, k])), p));
                }
            }
        }
    }
    let mut g_lines = Vec::new();
    for (i, gi) in g.iter().enumerate() {
        if !gi.is_zero() {
            g_lines.push(equation(format!("g_{{{}}}", idx(&[i])), gi));
        }
    }
    // The potential energy, of which g is the gradient.
    let p_lines = dv.potential_energy_poly().map(|p| {
        if p.is_zero() {
            Vec::new()
        } else {
            vec![equation("P".to_string(), &p)]
        }
    });
    // Arms with a spherical wrist: the decoupled singularity conditions (section 5.6.1).
    let wrist_lines: Option<Vec<String>> =
        crate::derive::singularity::decoupled_determinants(chain).map(|(j11, j22)| {
            vec![
                equation("\\det J_{11}".to_string(), &j11),
                equation("\\det J_{22}".to_string(), &j22),
            ]
        });

    let mut out = String::new();
    let _ = writeln!(
        out,
        "% {}: D(q), Christoffel symbols, g(q) and P(q) from dhgen's symbolic engine (normal form).",
        model.description.as_deref().unwrap_or(&model.name)
    );
    let _ = writeln!(
        out,
        "% c_j = cos(theta_j), s_j = sin(theta_j): theta_j = q_j + theta offset (revolute joints);"
    );
    let _ = writeln!(
        out,
        "% d_j = q_j + d offset (prismatic joints). Indices 1-based; coefficients to {} significant digits, SI units.",
        style.digits
    );
    if cumulative_used {
        let _ = writeln!(
            out,
            "% c_{{23}} = cos(theta_2 + theta_3), s_{{23}} = sin(theta_2 + theta_3): cumulative angles of parallel axes."
        );
    }
    let _ = writeln!(
        out,
        "\n% Inertia matrix D(q), symmetric (d_ji = d_ij); entries not listed are zero."
    );
    out += &block(d_lines);
    let _ = writeln!(
        out,
        "\n% Christoffel symbols c_ijk = 1/2 (dd_kj/dq_i + dd_ki/dq_j - dd_ij/dq_k), k the equation index:\n\
         % tau_k = sum_j d_kj qdd_j + sum_ij c_ijk qd_i qd_j + g_k. Symmetric (c_jik = c_ijk), so i <= j;\n\
         % symbols not listed are zero."
    );
    out += &block(c_lines);
    let _ = writeln!(
        out,
        "\n% Gravity torques g(q); entries not listed are zero."
    );
    out += &block(g_lines);
    match p_lines {
        Some(lines) => {
            let _ = writeln!(
                out,
                "\n% Potential energy P(q) = -sum_k m_k gravity . c_k, centres of mass in the world frame\n\
                 % (zero at the world origin); g_k = dP/dq_k."
            );
            out += &block(lines);
        }
        None => {
            let _ = writeln!(
                out,
                "\n% Potential energy P(q): its closed form is too large to print (more than {} term\n\
                 % operations); `dhgen eval` evaluates it.",
                crate::derive::GRAVITY_WORK
            );
        }
    }
    if let Some(lines) = wrist_lines {
        let _ = writeln!(
            out,
            "\n% Spherical wrist: det J = det J11 det J22 about the wrist centre; the arm is singular\n\
             % where det J11 = 0, the wrist where det J22 = 0."
        );
        out += &block(lines);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reads back a term list written by [`poly`] for plain angles and evaluates it.
    fn eval_latex(text: &str, c: &[f64], s: &[f64]) -> f64 {
        let mut total = 0.0;
        let spaced = text.replace(" - ", " + -");
        for term in spaced.split(" + ") {
            let (sign, term) = match term.strip_prefix('-') {
                Some(t) => (-1.0, t),
                None => (1.0, term),
            };
            let number = |k: &str| -> f64 {
                match k.split_once(" \\times 10^{") {
                    Some((m, e)) => {
                        let e: i32 = e.trim_end_matches('}').parse().unwrap();
                        m.parse::<f64>().unwrap() * 10f64.powi(e)
                    }
                    None => k.parse().unwrap(),
                }
            };
            let (coef, factors) = match term.split_once("\\,") {
                Some((k, f)) => (number(k), f),
                None if term.starts_with(['c', 's']) => (1.0, term),
                None => (number(term), ""),
            };
            let mut value = sign * coef;
            for f in factors.split_whitespace() {
                let (base, power) = match f.split_once('^') {
                    Some((b, p)) => (b, p.parse::<i32>().unwrap()),
                    None => (f, 1),
                };
                let j: usize = base[2..].parse::<usize>().unwrap() - 1;
                let x = if base.starts_with('c') { c[j] } else { s[j] };
                value *= x.powi(power);
            }
            total += value;
        }
        total
    }

    fn puma() -> RobotModel {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../robots/puma560.toml");
        RobotModel::from_toml_file(path).unwrap()
    }

    #[test]
    fn numbers() {
        assert_eq!(magnitude(0.35, 4), "0.35");
        assert_eq!(magnitude(-2.345_678, 4), "2.346");
        assert_eq!(magnitude(1234.6, 4), "1235");
        assert_eq!(magnitude(0.000_123_4, 3), "0.000123");
        assert_eq!(magnitude(1.5e-7, 4), "1.5 \\times 10^{-7}");
    }

    #[test]
    fn printed_mass_matrix_evaluates_to_the_normal_form() {
        let model = puma();
        let structure = model.chain();
        let v = vars(structure.view());
        let basis = Basis::joint_angles(6);
        let sym = Symbols {
            vars: &v,
            basis: &basis,
        };
        // Enough digits that reading the text back reproduces the coefficients.
        let style = Style {
            digits: 17,
            ..Style::default()
        };
        let d = Derivation::new(structure.view())
            .mass_matrix_polys()
            .expect("the PUMA's normal form is small")
            .clone();
        let q = [0.3, -0.7, 1.1, 0.4, -0.9, 2.0];
        let (c, s): (Vec<f64>, Vec<f64>) = q.iter().map(|x: &f64| (x.cos(), x.sin())).unzip();
        let values: Vec<f64> = c.iter().zip(&s).flat_map(|(c, s)| [*c, *s]).collect();
        for row in &d {
            for p in row {
                let text = poly(p, &sym, &style);
                let back = eval_latex(&text, &c, &s);
                assert!((back - p.eval(&values)).abs() < 1e-12, "{text}");
            }
        }
    }

    #[test]
    fn planar_elbow_has_the_textbook_form() {
        // Two links: d_12 = m2 (lc2² + a1 lc2 c2) + I2, a constant plus a c_2 term only.
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../robots/planar_elbow.toml");
        let model = RobotModel::from_toml_file(path).unwrap();
        let text = dynamics_equations(&model, &Style::default()).unwrap();
        let d12 = text
            .lines()
            .find(|l| l.trim_start().starts_with("d_{12}"))
            .unwrap();
        assert!(
            d12.contains("c_2") && !d12.contains("s_2") && !d12.contains("c_1"),
            "{d12}"
        );
        // Spong's h = -m2 a1 lc2 s2 with m2 = 1.5, a1 = 1, lc2 = 0.8 - 0.4: c_121 = c_221 = h,
        // c_112 = -h, c_111 = c_122 = c_222 = 0.
        assert!(text.contains("c_{112} &= 0.6\\,s_2 \\\\\n"), "{text}");
        assert!(text.contains("c_{121} &= -0.6\\,s_2 \\\\\n"), "{text}");
        assert!(text.contains("c_{221} &= -0.6\\,s_2\n"), "{text}");
        for zero in ["c_{111}", "c_{122}", "c_{222}", "c_{211}"] {
            assert!(!text.contains(zero), "{zero} in {text}");
        }
        assert!(text.contains("g_{1} &="), "{text}");
        // The text's P = (m1 lc1 + m2 l1) g s1 + m2 lc2 g s12, gravity along −y:
        // (2·0.5 + 1.5·1)·9.81 = 24.525 and 1.5·0.4·9.81 = 5.886.
        let cumulative = Style {
            cumulative: true,
            ..Style::default()
        };
        let text = dynamics_equations(&model, &cumulative).unwrap();
        assert!(
            text.contains("  P &= 24.53\\,s_1 + 5.886\\,s_{12}\n"),
            "{text}"
        );
    }

    #[test]
    fn cumulative_angles_shorten_puma_equations() {
        let model = puma();
        let plain = dynamics_equations(&model, &Style::default()).unwrap();
        let cumulative = dynamics_equations(
            &model,
            &Style {
                cumulative: true,
                ..Style::default()
            },
        )
        .unwrap();
        assert!(cumulative.contains("c_{23}"), "{cumulative}");
        assert!(!plain.contains("c_{23}"));
        assert!(cumulative.len() < plain.len());
        // Christoffel symbols are listed with i <= j only.
        // c_121 is not zero, so c_211 = c_121 would be listed if i > j were.
        assert!(plain.contains("  c_{121} &="));
        assert!(!plain.contains("c_{211}"));
    }

    #[test]
    fn no_dynamics_no_equations() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../robots/cylindrical.toml");
        let model = RobotModel::from_toml_file(path).unwrap();
        assert_eq!(
            dynamics_equations(&model, &Style::default()),
            Err(Unavailable::NoDynamics)
        );
    }
}
