//! Hostile URDF files: seeded variants (`dhgen_description::hostile::mutate`: byte flips,
//! truncations, deleted, duplicated and swapped lines, NaN/inf/1e308, invalid UTF-8, ...) of
//! the URDF fixtures through the URDF reader and the runtime path.
//!
//! The laws, as for TOML descriptions: reading never panics; every error is one line that
//! starts with `file:line:column:`; every accepted variant evaluates to finite values.
//! `DHGEN_HOSTILE_URDF_CASES` sets the number of variants (default 5,000).

use crate::hostile_descriptions::{accepted_evaluates, caught, one_located_line};
use dhgen::Robot;
use dhgen::model::urdf::{UrdfOptions, read_bytes};

const ORIGIN: &str = "hostile.urdf";

/// Reads one variant and checks the laws (those of the TOML test); `Ok(true)`: accepted.
fn check(bytes: &[u8], tip: Option<&str>) -> Result<bool, String> {
    let options = UrdfOptions {
        tip: tip.map(str::to_string),
        ..Default::default()
    };
    match read_bytes(bytes, ORIGIN, &options) {
        Ok(urdf) => {
            accepted_evaluates(&Robot::from_model(urdf.model))?;
            Ok(true)
        }
        Err(e) => {
            one_located_line(&e.to_string(), ORIGIN)?;
            Ok(false)
        }
    }
}

#[test]
fn hostile_urdf_files_load_or_fail_with_one_located_line() {
    let cases: u64 = std::env::var("DHGEN_HOSTILE_URDF_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(5_000);
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/urdf");
    let seeds: Vec<(String, Option<&str>)> = [
        ("panda.urdf", Some("panda_hand")),
        ("ur5.urdf", None),
        ("kinova.urdf", Some("j2s6s200_end_effector")),
        ("double_pendulum_continuous.urdf", None),
        ("human.urdf", Some("left_hand")),
    ]
    .iter()
    .map(|(f, tip)| (std::fs::read_to_string(format!("{dir}/{f}")).unwrap(), *tip))
    .collect();
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let (mut accepted, mut rejected) = (0u64, 0u64);
    let mut failures = Vec::new();
    for seed in 0..cases {
        let (text, tip) = &seeds[(seed % seeds.len() as u64) as usize];
        let bytes = dhgen::model::hostile::mutate(text, seed);
        let outcome = caught(|| check(&bytes, *tip));
        match outcome {
            Ok(true) => accepted += 1,
            Ok(false) => rejected += 1,
            Err(why) => failures.push(format!("seed {seed}: {why}")),
        }
        if failures.len() >= 20 {
            break;
        }
    }
    std::panic::set_hook(hook);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    eprintln!("{cases} hostile URDF variants: {accepted} accepted, {rejected} rejected");
    assert!(
        accepted > cases / 20 && rejected > cases / 5,
        "{accepted} accepted, {rejected} rejected"
    );
}
