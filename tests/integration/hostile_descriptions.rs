//! Hostile descriptions at scale: seeded variants of every catalogue robot and fixture
//! (`dhgen_description::hostile::mutate`: byte flips, truncations, deleted, duplicated and swapped
//! lines, swapped types, NaN/inf/1e308/−0.0, integers beyond 64 bits, huge arrays, a hundred
//! links more, deep nesting, invalid UTF-8) through the TOML reader and the runtime loader.
//!
//! The laws: loading never panics; every error is one line that starts with
//! `file:line:column:` and, for a rule violation, names the link or the field; every
//! accepted variant evaluates (pose, Jacobian, dynamics) and passes or fails the generator's
//! limits without a panic.
//!
//! `DHGEN_HOSTILE_CASES` sets the number of variants (default 100,000, the number CI runs);
//! `DHGEN_HOSTILE_SEED` the first seed, to explore beyond the default stream.

use dhgen::{LoadError, Robot, RobotModel};
use std::panic::{AssertUnwindSafe, catch_unwind};

const ORIGIN: &str = "hostile.toml";

fn env_or(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.replace('_', "").parse().ok())
        .unwrap_or(default)
}

/// Every description of the repository: the starting points of the variants.
fn seeds() -> Vec<(String, String)> {
    let seeds: Vec<(String, String)> = crate::support::description_paths()
        .into_iter()
        .map(|p| {
            (
                p.display().to_string(),
                std::fs::read_to_string(&p).unwrap(),
            )
        })
        .collect();
    assert!(seeds.len() >= 10, "found only {} descriptions", seeds.len());
    seeds
}

/// What happened to one variant.
enum Outcome {
    Accepted,
    Rejected,
}

/// The law for an accepted description: it evaluates to finite values (pose, Jacobian, D,
/// g), forward dynamics answers without a panic, and the generator's limits hold or are
/// reported. Shared with the hostile URDF test.
pub(crate) fn accepted_evaluates(robot: &Robot) -> Result<(), String> {
    let q = vec![0.1; robot.dof()];
    let pose = robot.fk(&q);
    let j = robot.jacobian(&q);
    if !pose
        .translation
        .vector
        .iter()
        .chain(j.iter())
        .all(|x| x.is_finite())
    {
        return Err("an accepted description gives a non-finite pose or Jacobian".into());
    }
    // Dynamics are O(n²) to O(n³): checked up to the generator's size.
    if robot.has_dynamics() && robot.dof() <= dhgen_codegen::limits::MAX_DYNAMICS_DOF {
        let d = robot.mass_matrix(&q);
        let g = robot.gravity(&q);
        if !d.iter().chain(g.iter()).all(|x| x.is_finite()) {
            return Err("an accepted description gives a non-finite D or g".into());
        }
        // `None` (a singular D) is an answer; a panic is not.
        let _ = robot.forward_dynamics(&q, &q, &g);
    }
    // The generator's limits hold or are reported.
    let _ = dhgen_codegen::limits::check(robot.chain());
    Ok(())
}

/// The law for a rejected description: one line that starts with `origin:line:column: `.
pub(crate) fn one_located_line(shown: &str, origin: &str) -> Result<(), String> {
    if shown.contains('\n') {
        return Err(format!("the error is not one line: {shown:?}"));
    }
    let located = shown
        .strip_prefix(origin)
        .and_then(|rest| rest.strip_prefix(':'))
        .and_then(|rest| {
            let mut parts = rest.splitn(3, ':');
            let line = parts.next()?.parse::<usize>().ok()?;
            let column = parts.next()?.parse::<usize>().ok()?;
            (line > 0 && column > 0 && parts.next()?.starts_with(' ')).then_some(())
        })
        .is_some();
    if located {
        Ok(())
    } else {
        Err(format!(
            "the error does not start with file:line:column: {shown:?}"
        ))
    }
}

/// `f`'s answer, or its panic as an `Err` naming the panic's message (the caller silences the
/// default hook, which would print each one).
pub(crate) fn caught<T>(f: impl FnOnce() -> Result<T, String>) -> Result<T, String> {
    catch_unwind(AssertUnwindSafe(f)).unwrap_or_else(|p| {
        let why = p
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        Err(format!("panicked: {why}"))
    })
}

/// Loads one variant and checks the laws; `Err` describes a broken one.
fn check(bytes: &[u8]) -> Result<Outcome, String> {
    match RobotModel::from_toml_bytes(bytes, ORIGIN) {
        Ok(model) => {
            accepted_evaluates(&Robot::from_model(model))?;
            Ok(Outcome::Accepted)
        }
        Err(e) => {
            let shown = e.to_string();
            one_located_line(&shown, ORIGIN)?;
            if let LoadError::Invalid { error, .. } = &e
                && error.link.is_none()
                && error.field.is_none()
            {
                return Err(format!("the error names neither link nor field: {shown:?}"));
            }
            Ok(Outcome::Rejected)
        }
    }
}

#[test]
fn hostile_descriptions_load_or_fail_with_one_located_line() {
    let cases = env_or("DHGEN_HOSTILE_CASES", 100_000);
    let first = env_or("DHGEN_HOSTILE_SEED", 0);
    let seeds = seeds();
    let (mut accepted, mut rejected) = (0u64, 0u64);
    // Panics are caught to report the variant; the default hook would print each one.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let mut failures = Vec::new();
    for seed in first..first + cases {
        let (name, text) = &seeds[(seed % seeds.len() as u64) as usize];
        let bytes = dhgen::model::hostile::mutate(text, seed);
        let outcome = caught(|| check(&bytes));
        match outcome {
            Ok(Outcome::Accepted) => accepted += 1,
            Ok(Outcome::Rejected) => rejected += 1,
            Err(why) => failures.push(format!("seed {seed} (from {name}): {why}")),
        }
        if failures.len() >= 20 {
            break;
        }
    }
    std::panic::set_hook(hook);
    assert!(
        failures.is_empty(),
        "{} variants broke a law (reproduce with `dhgen::model::hostile::mutate(text, seed)`):\n{}",
        failures.len(),
        failures.join("\n")
    );
    eprintln!("{cases} hostile variants: {accepted} accepted, {rejected} rejected");
    // The mutator must reach both outcomes in quantity, or the test tests little.
    assert!(
        accepted > cases / 20 && rejected > cases / 2,
        "{accepted} accepted, {rejected} rejected"
    );
}
