//! Writes docs/performance.md from criterion's saved estimates: the host and toolchain, then
//! one Markdown table of the `generated` bench (robot × quantity → median ns of generated
//! f64, generated f32 and runtime, the speed-up, and the operation count of the generated
//! function) and, when `cargo bench --bench batch` has run, two of the time per configuration
//! of the scalar functions, of the `batch` slice functions and of the generated functions on
//! SIMD packs, in `f64` (`f64x4`) and in `f32` (`f32x8`).
//!
//! `cargo bench --bench generated && cargo bench --bench batch &&
//! cargo run --release --example bench_report -- docs/performance.md`
//! (without a path it prints to standard output).

use dhgen::RobotModel;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

const ROBOTS: [&str; 6] = [
    "puma560",
    "panda",
    "planar_elbow",
    "stanford",
    "scara",
    "ur5",
];
const QUANTITIES: [&str; 10] = [
    "fk",
    "frames",
    "jacobian",
    "mass_matrix",
    "christoffel",
    "coriolis",
    "gravity",
    "inverse_dynamics",
    "forward_dynamics",
    "all_terms",
];

fn median_ns(dir: &Path) -> Option<f64> {
    let text = std::fs::read_to_string(dir.join("new/estimates.json")).ok()?;
    let v: serde_json::Value = serde_json::from_str(&text).ok()?;
    v["median"]["point_estimate"].as_f64()
}

fn fmt(x: Option<f64>) -> String {
    x.map_or_else(|| "–".into(), |v| format!("{v:.0}"))
}

fn main() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let target =
        std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| root.join("target"), PathBuf::from);
    let criterion = target.join("criterion");
    if !criterion.exists() {
        eprintln!(
            "no criterion results in {}: run `cargo bench --bench generated` first",
            criterion.display()
        );
        std::process::exit(1);
    }
    let mut out = String::new();
    header(&mut out);
    writeln!(
        out,
        "| robot | quantity | generated f64 (ns) | generated f32 (ns) | runtime (ns) | runtime / generated f64 | ops (generated) |"
    )
    .unwrap();
    writeln!(out, "|---|---|---:|---:|---:|---:|---:|").unwrap();
    for robot in ROBOTS {
        let model = match RobotModel::from_toml_file(root.join(format!("robots/{robot}.toml"))) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("{e}");
                std::process::exit(1);
            }
        };
        let ops = match dhgen_codegen::op_counts(&model) {
            Ok(ops) => ops,
            Err(e) => {
                eprintln!("{robot}: {e}");
                std::process::exit(1);
            }
        };
        let op = |name: &str| ops.iter().find(|(n, _)| n == name).map(|(_, c)| c.total());
        for q in QUANTITIES {
            let dir = criterion.join(robot).join(q);
            let g64 = median_ns(&dir.join("generated_f64"));
            let g32 = median_ns(&dir.join("generated_f32"));
            let rt = median_ns(&dir.join("runtime"));
            if g64.is_none() && rt.is_none() {
                continue;
            }
            let ratio = match (rt, g64) {
                (Some(r), Some(g)) => format!("{:.1}×", r / g),
                _ => "–".into(),
            };
            let count = match q {
                "fk" => op("fk_matrix"),
                "frames" => op("frames_matrix"),
                "inverse_dynamics" => op("inverse_dynamics_smooth"),
                // Emitted directly when cheaper, else contracted from c_ijk at run time.
                "coriolis" => {
                    op("coriolis").or_else(|| op("christoffel").map(|c| c + 2 * model.dof().pow(3)))
                }
                "forward_dynamics" => op("mass_matrix")
                    .zip(op("bias_smooth"))
                    .zip(op("cholesky_solve"))
                    .map(|((a, b), c)| a + b + c),
                other => op(other),
            };
            writeln!(
                out,
                "| {robot} | {q} | {} | {} | {} | {ratio} | {} |",
                fmt(g64),
                fmt(g32),
                fmt(rt),
                count.map_or_else(|| "–".into(), |c| c.to_string())
            )
            .unwrap();
        }
        if let Some(sep) = median_ns(&criterion.join(robot).join("all_terms/separate_f64")) {
            writeln!(
                out,
                "| {robot} | all_terms (separate calls) | {sep:.0} | | | | |"
            )
            .unwrap();
        }
    }
    batch_table(&criterion, &mut out);
    match std::env::args().nth(1) {
        Some(path) => {
            if let Err(e) = std::fs::write(&path, out) {
                eprintln!("{path}: {e}");
                std::process::exit(1);
            }
        }
        None => print!("{out}"),
    }
}

/// The page's title, how it is made, and the host and toolchain the figures are from.
fn header(out: &mut String) {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let rustc = std::process::Command::new(std::env::var("RUSTC").unwrap_or("rustc".into()))
        .arg("-V")
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default();
    writeln!(
        out,
        "# Performance\n\n\
         Written by `examples/bench_report.rs` from the last benchmark run; do not edit by hand.\n\
         Regenerate with\n\n\
         ```sh\n\
         cargo bench --bench generated && cargo bench --bench batch\n\
         cargo run --release --example bench_report -- docs/performance.md\n\
         ```\n\n\
         Medians of criterion benchmarks (inputs and outputs through `std::hint::black_box`, 64\n\
         random states cycled), on {cpu} ({cores} threads), {rustc}, the default target. Times\n\
         move between hosts and sessions; the ratios measured side by side, and the instruction\n\
         counts of `examples/instructions.rs` (callgrind), do not. \"ops\" counts the generated\n\
         function's additions and multiplications after sharing (sines and cosines come on top,\n\
         once per joint read). How each figure was reached, and the changes measured and not\n\
         kept: [experiments.md](experiments.md). Comparisons with Pinocchio and CppADCodeGen:\n\
         `scripts/pinocchio_bench.sh`, `scripts/cppadcg_counts.sh`.\n\n\
         ## Generated code against the runtime path\n"
    )
    .unwrap();
}

/// The `batch` bench's figures, per configuration (each of its measurements covers 64).
fn batch_table(criterion: &Path, out: &mut String) {
    const BATCH: [&str; 9] = [
        "fk",
        "fk_matrix",
        "jacobian",
        "mass_matrix",
        "christoffel",
        "coriolis",
        "gravity",
        "inverse_dynamics",
        "forward_dynamics",
    ];
    if median_ns(&criterion.join("puma560/fk/batch_f64x4")).is_none() {
        eprintln!("(no batch figures: run `cargo bench --bench batch` for them)");
        return;
    }
    for (scalar, batch, packs) in [
        ("scalar_f64", "batch_f64x4", "packs_f64x4"),
        ("scalar_f32", "batch_f32x8", "packs_f32x8"),
    ] {
        writeln!(out, "\n## SIMD batches, {batch}\n").unwrap();
        writeln!(
            out,
            "| robot | quantity | {scalar} (ns/config) | {batch} (ns/config) | {packs} (ns/config) | scalar / batch | scalar / packs |"
        )
        .unwrap();
        writeln!(out, "|---|---|---:|---:|---:|---:|---:|").unwrap();
        for robot in ["puma560", "panda"] {
            for q in BATCH {
                let dir = criterion.join(robot).join(q);
                let per = |v: &str| median_ns(&dir.join(v)).map(|t| t / 64.0);
                let (s, b, p) = (per(scalar), per(batch), per(packs));
                let ratio = |x: Option<f64>| match (s, x) {
                    (Some(s), Some(x)) => format!("{:.1}×", s / x),
                    _ => "–".into(),
                };
                writeln!(
                    out,
                    "| {robot} | {q} | {} | {} | {} | {} | {} |",
                    fmt(s),
                    fmt(b),
                    fmt(p),
                    ratio(b),
                    ratio(p)
                )
                .unwrap();
            }
        }
    }
}
