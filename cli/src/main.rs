//! `dhgen`: the command line of dhgen.
//!
//! - `dhgen info ROBOT.toml`: the DH table, joints, limits, masses, spherical wrist;
//! - `dhgen eval ROBOT.toml --q ... [--qd ...] [--qdd ...] [--json] [--derivatives]
//!   [--task-space]`: T, J, J_b (tool axes), D, C, g, τ, the kinetic and potential energy
//!   (and the derivatives of the dynamics, the tool's task-space dynamics) on the runtime path;
//! - `dhgen ik ROBOT.toml (--position X,Y,Z [--rpy R,P,Y | --axis X,Y,Z] | --at LIST)
//!   [--mask X,Y,Z,RX,RY,RZ] [--seed LIST] [--nearest LIST | --most-manipulable] [--json]`:
//!   inverse kinematics, closed form and numeric;
//! - `dhgen emit ROBOT.toml [-o FILE] [--name MOD] [--derivatives] [--regressor]`: the module `robot!`
//!   generates, formatted;
//! - `dhgen latex ROBOT.toml`: D(q), c_ijk, g(q) and P(q) as LaTeX equations;
//! - `dhgen ops ROBOT.toml`: operation counts of the generated functions;
//! - `dhgen convert ROBOT --to dh|mdh|toml|urdf`: between URDF and the description format;
//! - `dhgen params ROBOT [--latex | --json]`: the inertial parameters and the base parameters;
//! - `dhgen random --dof N [--style general|industrial] [--seed S]`: a random valid arm.
//!
//! Any failure is one line on stderr and a non-zero exit status: 2 for a malformed command
//! line, 1 for everything else (an unreadable or invalid description, a bad value).

mod emit;
mod eval;
mod ik;
mod info;
mod table;

use clap::error::ErrorKind;
use clap::{Parser, Subcommand};
use dhgen::Robot;
use dhgen::ik::Task;
use dhgen_codegen::{Style, dynamics_equations};
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// dhgen: robot arms from Denavit–Hartenberg tables.
#[derive(Parser, Debug)]
#[command(name = "dhgen", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Print the DH table, DOF, convention, joint types, limits, masses and whether the arm
    /// has a spherical wrist.
    Info {
        #[command(flatten)]
        robot: Source,
    },
    /// Evaluate the pose T, Jacobian J (world axes) and J_b (tool axes), and (with mass
    /// properties) D, C, g, τ, the kinetic and potential energy and the centre of mass with its
    /// Jacobian at one configuration, on the runtime path (`dhgen::Robot`).
    Eval {
        #[command(flatten)]
        robot: Source,
        /// Joint positions, one per joint: radians (or `90deg`, `pi/2`) and metres for
        /// prismatic joints; one argument, comma-separated (`--q -0.5,0,pi/2,0,0,0`) or
        /// quoted and space-separated.
        #[arg(long, required = true, allow_hyphen_values = true, value_name = "LIST")]
        q: String,
        /// Joint velocities (rad/s, m/s), a list like `--q`; zero if omitted.
        #[arg(long, allow_hyphen_values = true, value_name = "LIST")]
        qd: Option<String>,
        /// Joint accelerations (rad/s², m/s²), a list like `--q`; zero if omitted.
        #[arg(long, allow_hyphen_values = true, value_name = "LIST")]
        qdd: Option<String>,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
        /// Also print the derivatives of inverse dynamics (∂τ/∂q, ∂τ/∂q̇) and of forward
        /// dynamics at the τ printed (∂q̈/∂q, ∂q̈/∂q̇, D⁻¹), analytic, on the runtime path.
        #[arg(long)]
        derivatives: bool,
        /// Also print the tool's task-space (operational-space) dynamics: its inertia
        /// Λ = (J D⁻¹ Jᵀ)⁻¹, and the forces μ and p (`dhgen::task_space::tool`), or why there
        /// are none (a kinematic singularity, fewer than six joints).
        #[arg(long)]
        task_space: bool,
    },
    /// Inverse kinematics on the runtime path: every closed-form solution where the arm has
    /// them (six joints, a spherical wrist or three parallel axes), the numeric solution from
    /// a seed, and for a redundant arm on request the one nearest a posture or the most
    /// manipulable. The pose: `--position` and `--rpy`, or `--at` (where the tool is at those
    /// joint values).
    Ik {
        #[command(flatten)]
        robot: Source,
        /// The tool's position in the world, m: `X,Y,Z`.
        #[arg(
            long,
            allow_hyphen_values = true,
            value_name = "X,Y,Z",
            required_unless_present = "at",
            conflicts_with = "at"
        )]
        position: Option<String>,
        /// The tool's orientation: roll, pitch, yaw about the fixed x, y, z axes (radians, or
        /// `90deg`, `pi/2`), applied in that order. Without it (and without `--axis`) only the
        /// position is solved for, the orientation left free.
        #[arg(
            long,
            allow_hyphen_values = true,
            value_name = "R,P,Y",
            conflicts_with_all = ["at", "axis"]
        )]
        rpy: Option<String>,
        /// The direction of the tool's z axis in the world, `X,Y,Z` (any length but zero): the
        /// position and this axis are solved for, the turn about the axis left free (a
        /// five-joint arm, a tool symmetric about its axis).
        #[arg(
            long,
            allow_hyphen_values = true,
            value_name = "X,Y,Z",
            conflicts_with = "at"
        )]
        axis: Option<String>,
        /// The pose of the tool at these joint values (a list like `eval`'s `--q`).
        #[arg(long, allow_hyphen_values = true, value_name = "LIST")]
        at: Option<String>,
        /// The components of the pose to reach, in world axes: `X,Y,Z,RX,RY,RZ`, each 1
        /// (counted) or 0 (free), the Robotics Toolbox's `mask`. Of `RX,RY,RZ` count none,
        /// two (free to turn about the world axis left out) or all three, the orientation
        /// given by `--rpy` or `--at`.
        #[arg(long, value_name = "X,Y,Z,RX,RY,RZ", conflicts_with = "axis")]
        mask: Option<String>,
        /// The numeric solver's seed (a list like `eval`'s `--q`); 0 if omitted (each joint
        /// clamped into its limits).
        #[arg(long, allow_hyphen_values = true, value_name = "LIST")]
        seed: Option<String>,
        /// Also the solution nearest this posture (a list like `--seed`), moved along the
        /// self-motion from the numeric one.
        #[arg(
            long,
            allow_hyphen_values = true,
            value_name = "LIST",
            conflicts_with = "most_manipulable"
        )]
        nearest: Option<String>,
        /// Also the most manipulable solution (Yoshikawa's measure), moved along the
        /// self-motion from the numeric one.
        #[arg(long)]
        most_manipulable: bool,
        /// Print JSON instead of text.
        #[arg(long)]
        json: bool,
    },
    /// Write the module `dhgen::robot!` generates for the description, formatted, as a Rust
    /// source file.
    Emit {
        #[command(flatten)]
        robot: Source,
        /// Output file; standard output if omitted.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Module name; the robot's name if omitted.
        #[arg(long)]
        name: Option<String>,
        /// Also generate the derivatives of the dynamics (∂τ/∂q, ∂τ/∂q̇, Ḋ, Cᵀq̇), as
        /// `robot!(..., derivatives)` does.
        #[arg(long)]
        derivatives: bool,
        /// Also generate the regressor, base regressor and base parameters, as
        /// `robot!(..., regressor)` does.
        #[arg(long)]
        regressor: bool,
    },
    /// Print D(q), the Christoffel symbols c_ijk, g(q) and the potential energy P(q) as LaTeX
    /// equations, from the symbolic engine.
    Latex {
        #[command(flatten)]
        robot: Source,
        /// Write runs of parallel axes with cumulative angles, c_{23} = cos(θ2 + θ3), where
        /// that shortens an entry.
        #[arg(long)]
        cumulative: bool,
        /// Significant digits of the coefficients (1 to 17).
        #[arg(long, default_value_t = 4, allow_negative_numbers = true,
              value_parser = clap::value_parser!(u8).range(1..=17))]
        digits: u8,
    },
    /// Print the operation count of every generated function and the generation time.
    Ops {
        #[command(flatten)]
        robot: Source,
        /// Include the derivatives of the dynamics (`robot!(..., derivatives)`).
        #[arg(long)]
        derivatives: bool,
        /// Include the regressor and base parameters (`robot!(..., regressor)`).
        #[arg(long)]
        regressor: bool,
    },
    /// Convert a description: a URDF file to a DH table (`dh`, `mdh`) or to the description
    /// format's `urdf` convention (`toml`), a TOML description to URDF (`urdf`) or to the
    /// other DH convention.
    Convert {
        #[command(flatten)]
        robot: Source,
        /// The form to write: `dh` (standard DH), `mdh` (modified DH), `toml` (the chain as
        /// read, `urdf` convention), `urdf`.
        #[arg(long)]
        to: ConvertTo,
        /// Output file; standard output if omitted.
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
    /// Print the inertial parameters π (the order `regressor` uses: per link m, m·c, inertia
    /// about the link frame's origin; then armature and friction), the number of base
    /// parameters and the regrouping rules.
    Params {
        #[command(flatten)]
        robot: Source,
        /// Print the base parameters as LaTeX equations.
        #[arg(long, conflicts_with = "json")]
        latex: bool,
        /// Print JSON instead: `names` and `values` of π, and `base` with the regrouping
        /// (`independent` and `dependent` indices into π, `beta` by rows, so that base
        /// parameter k is `values[independent[k]] + Σ_m beta[k][m] values[dependent[m]]`),
        /// `values` and `rules`, for tools outside Rust.
        #[arg(long)]
        json: bool,
    },
    /// Write a random valid arm (a seeded, reproducible description) for scale tests and
    /// benchmarks: `general` (no exact angles, full inertias) or `industrial` (twists and
    /// offsets in {0, ±90°}).
    Random {
        /// Number of joints (1 to 1000).
        #[arg(long, allow_negative_numbers = true,
              value_parser = clap::value_parser!(u16).range(1..=1000))]
        dof: u16,
        /// `general` or `industrial`.
        #[arg(long, default_value = "general")]
        style: RandomStyle,
        /// The seed: the same seed and size give the same arm (0 to 2⁶⁴ − 1).
        #[arg(long, default_value_t = 1, allow_negative_numbers = true, value_parser = seed)]
        seed: u64,
        /// Output file; standard output if omitted.
        #[arg(short, long)]
        output: Option<PathBuf>,
    },
}

/// `--seed`: a whole number that fits 64 bits, said so when it does not (`-1`, `1.5`).
fn seed(value: &str) -> Result<u64, String> {
    value
        .parse()
        .map_err(|_| format!("the seed is a whole number from 0 to {}", u64::MAX))
}

/// A description file and, for a URDF file, how to read it.
#[derive(clap::Args, Debug)]
struct Source {
    /// The robot description: TOML, or URDF (a `.urdf` file).
    robot: PathBuf,
    /// URDF: the last link of the chain (default: the one end of the movable joints).
    #[arg(long, value_name = "LINK")]
    tip: Option<String>,
    /// URDF: the first link of the chain, fixed in the world (default: the root link).
    #[arg(long, value_name = "LINK")]
    base: Option<String>,
    /// URDF: read angles within this many radians (0 to 0.1) of a multiple of 90° as exact
    /// (default 1e-9; `dhgen info` lists every value read so).
    #[arg(long, value_name = "RAD", allow_negative_numbers = true)]
    snap: Option<f64>,
}

impl Source {
    fn display(&self) -> std::path::Display<'_> {
        self.robot.display()
    }
}

/// The targets of `dhgen convert`.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum ConvertTo {
    /// A standard (distal) DH table, with base and tool poses and the inertias in DH frames.
    Dh,
    /// A modified (proximal, Craig) DH table.
    Mdh,
    /// The description format as read (for a URDF file: the `urdf` convention).
    Toml,
    /// A URDF document.
    Urdf,
}

/// The styles of `dhgen random`.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum RandomStyle {
    /// Twists and offsets anywhere, nothing zero, full inertia tensors.
    General,
    /// Twists and offsets in {0, ±90°}, some lengths zero.
    Industrial,
}

/// Loads a description; the error (one line) names the file, and for a syntax error or a
/// rule violation the line, column, link and field.
fn load(source: &Source) -> Result<Robot, String> {
    read(source).map(|(robot, _)| robot)
}

/// Loads a description, with what the URDF reader found for a URDF file.
fn read(source: &Source) -> Result<(Robot, Option<dhgen_description::urdf::UrdfRobot>), String> {
    let path: &Path = &source.robot;
    if dhgen_description::urdf::is_urdf_path(path) {
        let mut options = dhgen_description::urdf::UrdfOptions {
            tip: source.tip.clone(),
            base: source.base.clone(),
            ..Default::default()
        };
        if let Some(snap) = source.snap {
            options.snap = dhgen_description::urdf::UrdfOptions::check_snap(snap)
                .map_err(|why| format!("--snap {snap}: {why}"))?;
        }
        let urdf = dhgen_description::urdf::read_file(path, &options).map_err(|e| e.to_string())?;
        Ok((Robot::from_model(urdf.model.clone()), Some(urdf)))
    } else {
        if source.tip.is_some() || source.base.is_some() || source.snap.is_some() {
            return Err(format!(
                "{}: --tip, --base and --snap read URDF files; this is a TOML description",
                path.display()
            ));
        }
        Robot::from_toml_file(path)
            .map(|r| (r, None))
            .map_err(|e| e.to_string())
    }
}

/// The command's text, written to `output` (then nothing is printed) or returned for
/// standard output.
fn deliver(output: Option<PathBuf>, text: String) -> Result<String, String> {
    match output {
        Some(path) => {
            std::fs::write(&path, text)
                .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
            Ok(String::new())
        }
        None => Ok(text),
    }
}

fn run(command: Command) -> Result<String, String> {
    match command {
        Command::Info { robot } => {
            let (r, urdf) = read(&robot)?;
            let mut text = info::report(&r);
            if let Some(u) = urdf {
                text += &info::urdf_report(&u);
            }
            Ok(text)
        }
        Command::Eval {
            robot,
            q,
            qd,
            qdd,
            json,
            derivatives,
            task_space,
        } => {
            let r = load(&robot)?;
            let q = eval::positions(&r, "--q", &eval::split("--q", &q)?)?;
            let qd = eval::rates(&r, "--qd", qd.as_deref())?;
            let qdd = eval::rates(&r, "--qdd", qdd.as_deref())?;
            let e = eval::evaluate(&r, q, qd, qdd, derivatives, task_space)?;
            Ok(if json {
                format!("{}\n", e.json(&r))
            } else {
                e.text(&r)
            })
        }
        Command::Ik {
            robot,
            position,
            rpy,
            axis,
            at,
            mask,
            seed,
            nearest,
            most_manipulable,
            json,
        } => {
            let r = load(&robot)?;
            let (target, mut task) = match (at, position) {
                (Some(at), _) => {
                    let q = eval::positions(&r, "--at", &eval::split("--at", &at)?)?;
                    (r.fk(&q), Task::Pose)
                }
                (None, Some(position)) => ik::target(&position, rpy.as_deref(), axis.as_deref())?,
                (None, None) => {
                    return Err("give the pose: --position (with --rpy or --axis) or --at".into());
                }
            };
            if let Some(list) = mask {
                task = ik::mask(&list, task)?;
            }
            let prefer = match (nearest, most_manipulable) {
                (Some(list), _) => ik::Prefer::Posture(eval::positions(
                    &r,
                    "--nearest",
                    &eval::split("--nearest", &list)?,
                )?),
                (None, true) => ik::Prefer::Manipulability,
                (None, false) => ik::Prefer::Nothing,
            };
            ik::run(&r, &target, task, seed.as_deref(), prefer, json)
        }
        Command::Emit {
            robot,
            output,
            name,
            derivatives,
            regressor,
        } => {
            let r = load(&robot)?;
            let options = dhgen_codegen::Options {
                derivatives,
                regressor,
            };
            let code = emit::emit(r.model(), &robot.robot, name.as_deref(), options)?;
            deliver(output, code)
        }
        Command::Latex {
            robot,
            cumulative,
            digits,
        } => {
            let r = load(&robot)?;
            let style = Style {
                digits: usize::from(digits),
                cumulative,
                ..Style::default()
            };
            dynamics_equations(r.model(), &style)
                .map_err(|why| format!("{}: {why}", robot.display()))
        }
        Command::Ops {
            robot,
            derivatives,
            regressor,
        } => emit::ops_report(
            load(&robot)?.model(),
            dhgen_codegen::Options {
                derivatives,
                regressor,
            },
        )
        .map_err(|e| format!("{}: {e}", robot.display())),
        Command::Convert { robot, to, output } => {
            use dhgen_description::convert::{ConvertError, to_dh, to_urdf};
            let r = load(&robot)?;
            let model = r.model();
            // The model read is valid, so a failure of the conversion is the converted
            // description's: a value re-expressed in the new frames outside the format's
            // ranges, which the input need not show (the input's com 1000 m can become
            // 1000 m plus rounding). Said so, with the field of the converted description.
            let converted = |convention, name| {
                to_dh(model, convention).map_err(|e| {
                    let mut hint = String::new();
                    let (what, message) = match e {
                        ConvertError::Invalid {
                            joint,
                            field,
                            message,
                        } => {
                            // Where frames are placed: DH's own ill-conditioning.
                            if matches!(field.as_deref(), Some("a" | "d" | "base.xyz" | "tool.xyz"))
                            {
                                hint = "; DH puts the common normal of nearly parallel axes \
                                        far away"
                                    .to_string();
                                if dhgen_description::urdf::is_urdf_path(&robot.robot) {
                                    hint += " (if the file's angles are rounded quarter turns, \
                                             such as 1.5708, --snap 1e-4 reads them as exact)";
                                }
                            }
                            let what = match (joint, field) {
                                (Some(j), Some(f)) => format!("the converted `{f}` of link {j}"),
                                (Some(j), None) => format!("link {j} of the converted description"),
                                (None, Some(f)) => format!("the converted `{f}`"),
                                (None, None) => "the converted description".to_string(),
                            };
                            (what, message)
                        }
                        other => ("the converted description".to_string(), other.to_string()),
                    };
                    format!(
                        "{}: converting to {name}: {what} is not valid (a value the conversion \
                         computed; the input's are valid): {message}{hint}",
                        robot.display()
                    )
                })
            };
            let text = match to {
                ConvertTo::Dh => converted(dhgen::Convention::Standard, "standard DH")?.to_toml(),
                ConvertTo::Mdh => converted(dhgen::Convention::Modified, "modified DH")?.to_toml(),
                ConvertTo::Toml => model.to_toml(),
                ConvertTo::Urdf => to_urdf(model),
            };
            deliver(output, text)
        }
        Command::Params { robot, latex, json } => {
            let r = load(&robot)?;
            if !r.has_dynamics() {
                return Err(format!(
                    "{}: the robot has no mass properties, so no inertial parameters",
                    robot.display()
                ));
            }
            if r.dof() > MAX_PARAMS_DOF {
                return Err(format!(
                    "{}: field `links`: the robot has {} joints; `dhgen params` finds the base \
                     parameters of at most {MAX_PARAMS_DOF} joints (the work grows as n³: about \
                     2 s at {MAX_PARAMS_DOF} joints, 15 s at 200). Use the runtime path, \
                     `dhgen::Robot::base_parameters`, for longer chains",
                    robot.display(),
                    r.dof()
                ));
            }
            Ok(if json {
                format!("{}\n", params_json(&r))
            } else {
                params_report(&r, latex)
            })
        }
        Command::Random {
            dof,
            style,
            seed,
            output,
        } => {
            use dhgen_description::random::{ArmStyle, random_arm};
            let style = match style {
                RandomStyle::General => ArmStyle::General,
                RandomStyle::Industrial => ArmStyle::Industrial,
            };
            let text = random_arm(usize::from(dof), style, seed).to_toml();
            deliver(output, text)
        }
    }
}

/// The most joints `dhgen params` takes. The base parameters come from a pivoted QR of the
/// regressor (10 columns per joint, more with motors and friction) stacked over at least 40
/// random states: time grows as n³ and memory as n². Measured on the release build
/// (2026-12-01, a 2-core host): 32 joints 0.04 s, 50 joints 0.13 s, 80 joints 0.7 s, 100
/// joints 1.8 to 2.1 s and 75 MB, 120 joints 3.8 to 4.5 s, 200 joints 15 s, 400 joints over
/// two minutes and 1.1 GB. The generator's limits (`dhgen_codegen::limits`) do not apply:
/// `params` runs the runtime path, not the generator.
const MAX_PARAMS_DOF: usize = 100;

/// `dhgen params`: π by name, then the base parameters and what each regroups.
fn params_report(r: &Robot, latex: bool) -> String {
    use std::fmt::Write as _;
    let names = r.parameter_names();
    let pi = r.parameters();
    let base = r.base_parameters();
    let rules = base.rules(&names);
    let pi_b = base.reduce(&pi);
    let mut out = String::new();
    if latex {
        let tex = |name: &str| {
            let split = name
                .find(|c: char| c.is_ascii_digit())
                .unwrap_or(name.len());
            let (stem, index) = name.split_at(split);
            format!("\\mathrm{{{stem}}}_{{{index}}}")
        };
        let _ = writeln!(out, "\\begin{{align*}}");
        for (k, rule) in rules.iter().enumerate() {
            let mut body = String::new();
            for token in rule.split(' ') {
                let t = match token {
                    "+" | "−" => token.replace('−', "-"),
                    t => match t.split_once('·') {
                        Some((c, n)) => format!("{c}\\,{}", tex(n)),
                        None => tex(t),
                    },
                };
                body += &t;
                body.push(' ');
            }
            let _ = writeln!(
                out,
                "\\pi_{{b,{}}} &= {}&&= {:.6} \\\\",
                k + 1,
                body.trim_end(),
                pi_b[k]
            );
        }
        let _ = writeln!(out, "\\end{{align*}}");
        return out;
    }
    let _ = writeln!(
        out,
        "{}: {} parameters (per link: m, m·c, inertia about the link frame origin; then armature and friction)",
        r.model().name,
        pi.len()
    );
    for (chunk, values) in names.chunks(10).zip(pi.as_slice().chunks(10)) {
        let row: Vec<String> = chunk
            .iter()
            .zip(values)
            .map(|(n, v)| format!("{n} = {v:.6}"))
            .collect();
        let _ = writeln!(out, "  {}", row.join(", "));
    }
    let _ = writeln!(
        out,
        "{} base parameters (the rest are without effect or regrouped into these):",
        base.count()
    );
    for (k, rule) in rules.iter().enumerate() {
        let _ = writeln!(out, "  πb{} = {rule} = {:.6}", k + 1, pi_b[k]);
    }
    out
}

/// `dhgen params --json`: π by name and the regrouping, exactly (shortest round-trip
/// decimals), as `dhgen_description::parameters::BaseParameters` holds it.
fn params_json(r: &Robot) -> serde_json::Value {
    let names = r.parameter_names();
    let pi = r.parameters();
    let base = r.base_parameters();
    let beta: Vec<Vec<f64>> = base
        .beta
        .row_iter()
        .map(|row| row.iter().copied().collect())
        .collect();
    serde_json::json!({
        "robot": r.model().name,
        "names": names,
        "values": pi.as_slice(),
        "base": {
            "independent": base.independent,
            "dependent": base.dependent,
            "beta": beta,
            "values": base.reduce(&pi).as_slice(),
            "rules": base.rules(&names),
        },
    })
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            return match e.kind() {
                ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
                    let _ = e.print();
                    ExitCode::SUCCESS
                }
                ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
                    eprintln!(
                        "dhgen: missing command: info, eval, ik, emit, latex, ops, convert, params or random (see dhgen --help)"
                    );
                    ExitCode::from(2)
                }
                _ => {
                    // clap's first paragraph (the message and, for missing arguments,
                    // their names), without the usage and tip paragraphs.
                    let text = e.render().to_string();
                    let message: Vec<&str> = text
                        .lines()
                        .take_while(|l| !l.trim().is_empty())
                        .map(str::trim)
                        .collect();
                    let message = message.join(" ");
                    let message = message.strip_prefix("error: ").unwrap_or(&message);
                    eprintln!("dhgen: {message} (see dhgen --help)");
                    ExitCode::from(2)
                }
            };
        }
    };
    match run(cli.command) {
        Ok(text) => {
            let mut out = std::io::stdout().lock();
            match out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
                Ok(()) => ExitCode::SUCCESS,
                // A closed pipe (`dhgen emit robot.toml | head`) is the reader's choice.
                Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("dhgen: cannot write the output: {e}");
                    ExitCode::FAILURE
                }
            }
        }
        Err(message) => {
            eprintln!("dhgen: {message}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn command_line_is_consistent() {
        use clap::CommandFactory;
        Cli::command().debug_assert();
    }
}
