//! The runtime path against reference values from Robotics Toolbox for Python,
//! cross-checked against Pinocchio (tests/data/README.md): every sample of the four robots,
//! every quantity.
//!
//! Error measure, element-wise for every quantity: `|a − b| / max(1, |b|)` (relative for
//! entries above 1, absolute below), which must not exceed 1e-10. The worst value per
//! quantity is printed; run with `--nocapture` to see it.

use crate::support::runtime;
use serde_json::Value;
use std::collections::BTreeMap;

const TOLERANCE: f64 = 1e-10;

fn numbers(v: &Value) -> Vec<f64> {
    match v {
        Value::Array(items) => items.iter().flat_map(numbers).collect(),
        Value::Number(x) => vec![x.as_f64().unwrap()],
        other => panic!("expected numbers, found {other}"),
    }
}

/// Worst error per quantity, and the first failure, if any.
#[derive(Default)]
struct Errors {
    worst: BTreeMap<&'static str, f64>,
    failures: Vec<String>,
}

impl Errors {
    fn check(&mut self, quantity: &'static str, sample: usize, actual: &[f64], expected: &[f64]) {
        assert_eq!(actual.len(), expected.len(), "{quantity}: sizes differ");
        let worst = self.worst.entry(quantity).or_insert(0.0);
        for (index, (a, b)) in actual.iter().zip(expected).enumerate() {
            let error = (a - b).abs() / b.abs().max(1.0);
            *worst = worst.max(error);
            if error.is_nan() || error > TOLERANCE {
                self.failures.push(format!(
                    "sample {sample}, {quantity}[{index}]: got {a:e}, expected {b:e} (error {error:e})"
                ));
            }
        }
    }
}

impl Errors {
    /// Prints the worst error per quantity and fails with the first failures, if any.
    fn finish(&self, what: &str) {
        println!("{what}: worst |a - b| / max(1, |b|)");
        for (quantity, worst) in &self.worst {
            println!("  {quantity:<12} {worst:.1e}");
        }
        assert!(
            self.failures.is_empty(),
            "{what}: {} values off by more than {TOLERANCE:e}:\n{}",
            self.failures.len(),
            self.failures[..self.failures.len().min(20)].join("\n")
        );
    }
}

/// Row-major entries of a matrix.
fn row_major<R: nalgebra::Dim, C: nalgebra::Dim>(m: &nalgebra::OMatrix<f64, R, C>) -> Vec<f64>
where
    nalgebra::DefaultAllocator:
        nalgebra::allocator::Allocator<R, C> + nalgebra::allocator::Allocator<C, R>,
{
    m.transpose().as_slice().to_vec()
}

fn check_robot(name: &str) {
    let root = env!("CARGO_MANIFEST_DIR");
    let robot = runtime(name);
    let text = std::fs::read_to_string(format!("{root}/tests/data/{name}.json")).unwrap();
    let data: Value = serde_json::from_str(&text).unwrap();
    let n = robot.dof();
    assert_eq!(data["n"].as_u64(), Some(n as u64));
    let samples = data["samples"].as_array().unwrap();
    assert!(!samples.is_empty());
    let mut errors = Errors::default();
    for (s, sample) in samples.iter().enumerate() {
        let q = numbers(&sample["q"]);
        let qd = numbers(&sample["qd"]);
        let qdd = numbers(&sample["qdd"]);
        let t = robot.fk(&q).to_homogeneous();
        errors.check("T", s, t.transpose().as_slice(), &numbers(&sample["T"]));
        errors.check(
            "J0",
            s,
            &row_major(&robot.jacobian(&q)),
            &numbers(&sample["J0"]),
        );
        errors.check(
            "D",
            s,
            &row_major(&robot.mass_matrix(&q)),
            &numbers(&sample["D"]),
        );
        let c = robot.coriolis(&q, &qd);
        errors.check("C", s, &row_major(&c), &numbers(&sample["C"]));
        let cqd = &c * nalgebra::DVector::from_column_slice(&qd);
        errors.check("Cqd", s, cqd.as_slice(), &numbers(&sample["Cqd"]));
        errors.check("g", s, robot.gravity(&q).as_slice(), &numbers(&sample["g"]));
        let tau = robot.inverse_dynamics(&q, &qd, &qdd);
        let expected_tau = numbers(&sample["tau"]);
        errors.check("tau", s, tau.as_slice(), &expected_tau);
        // The file's Gamma has the equation index first: Gamma[k][j][i] = c_ijk.
        let christoffel = robot.christoffel(&q);
        let gamma = numbers(&sample["christoffel"]);
        let mut ours = vec![0.0; n * n * n];
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    ours[(k * n + j) * n + i] = christoffel[i][j][k];
                }
            }
        }
        errors.check("christoffel", s, &ours, &gamma);
        let forward = robot
            .forward_dynamics(&q, &qd, &expected_tau)
            .expect("D is positive definite");
        errors.check("forward qdd", s, forward.as_slice(), &qdd);
    }
    errors.finish(&format!("{name} over {} samples", samples.len()));
}

#[test]
fn planar_elbow() {
    check_robot("planar_elbow");
}

#[test]
fn puma560() {
    check_robot("puma560");
}

#[test]
fn stanford() {
    check_robot("stanford");
}

#[test]
fn panda() {
    check_robot("panda");
}

/// The kinetic and potential energy of the PUMA 560 and the Panda against Pinocchio's
/// `computeKineticEnergy` and `computePotentialEnergy` (tests/data/derivatives_*.json, made by
/// scripts/pinocchio_derivatives.py from the same tables), on the runtime path and the
/// generated one.
#[test]
fn energies_match_pinocchio() {
    use crate::catalogue::{panda, puma560};
    let mut errors = Errors::default();
    for name in ["puma560", "panda"] {
        let data = crate::support::pinocchio_reference(name);
        let robot = runtime(name);
        let samples = data["samples"].as_array().unwrap();
        assert_eq!(samples.len(), 10);
        for (k, s) in samples.iter().enumerate() {
            let (q, qd) = (numbers(&s["q"]), numbers(&s["qd"]));
            let expected = [
                s["kinetic_energy"].as_f64().unwrap(),
                s["potential_energy"].as_f64().unwrap(),
            ];
            errors.check(
                "energies (runtime)",
                k,
                &[robot.kinetic_energy(&q, &qd), robot.potential_energy(&q)],
                &expected,
            );
            macro_rules! generated {
                ($m:ident) => {{
                    let a = |v: &[f64]| -> [f64; $m::DOF] { v.try_into().unwrap() };
                    let st = $m::State::new(&a(&q));
                    [st.kinetic_energy(&a(&qd)), st.potential_energy()]
                }};
            }
            let generated = match name {
                "puma560" => generated!(puma560),
                _ => generated!(panda),
            };
            errors.check("energies (generated)", k, &generated, &expected);
        }
    }
    errors.finish("PUMA 560 and Panda against Pinocchio");
}
