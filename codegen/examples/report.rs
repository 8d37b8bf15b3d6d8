//! Prints, per robot description given on the command line, the operation count of every
//! generated function and the time the generator took.
//!
//! `cargo run -p dhgen-codegen --example report -- robots/*.toml`

use dhgen_codegen::{RobotModel, generate};
use std::time::Instant;

fn main() {
    for path in std::env::args().skip(1) {
        let model = match RobotModel::from_toml_file(&path) {
            Ok(m) => m,
            Err(e) => {
                eprintln!("{e}");
                std::process::exit(1);
            }
        };
        let start = Instant::now();
        let name = proc_macro2::Ident::new(&model.name, proc_macro2::Span::call_site());
        let generated = match generate(&model, quote::quote!(pub), &name) {
            Ok(g) => g,
            Err(e) => {
                eprintln!("{path}: {e}");
                std::process::exit(1);
            }
        };
        let elapsed = start.elapsed();
        let lines = generated.tokens.to_string().matches(';').count();
        println!(
            "## {} ({} DOF): generated in {:.1} ms, ~{} statements",
            model.name,
            model.dof(),
            elapsed.as_secs_f64() * 1e3,
            lines
        );
        println!("| function | add | mul | div | sqrt | sin/cos | total arithmetic |");
        println!("|---|---:|---:|---:|---:|---:|---:|");
        for (f, c) in &generated.ops {
            let row = [c.add, c.mul, c.div, c.sqrt, c.sincos, c.total()].map(|x| x.to_string());
            println!("| {f} | {} |", row.join(" | "));
        }
    }
}
