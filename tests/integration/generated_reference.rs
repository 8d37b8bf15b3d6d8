//! Generated code against the independent reference values of tests/data (Robotics
//! Toolbox for Python, cross-checked with Pinocchio), to 1e-10 relative.

use crate::catalogue::{panda, planar_elbow, puma560, stanford};
use serde_json::Value;

fn load(name: &str) -> Value {
    let path = format!("{}/tests/data/{name}.json", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn arr<const N: usize>(v: &Value) -> [f64; N] {
    let a: Vec<f64> = v
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    a.try_into().unwrap()
}

/// Worst error relative to max(1, |reference|) over all entries.
#[derive(Default)]
struct Worst(f64);

impl Worst {
    fn check(&mut self, what: &str, got: f64, want: f64) {
        let err = (got - want).abs() / want.abs().max(1.0);
        assert!(
            err <= 1e-10,
            "{what}: got {got}, want {want}, relative error {err:e}"
        );
        self.0 = self.0.max(err);
    }
}

macro_rules! check_robot {
    ($test:ident, $m:ident, $name:literal) => {
        #[test]
        fn $test() {
            use $m as r;
            const N: usize = r::DOF;
            let data = load($name);
            let mut worst: std::collections::BTreeMap<&str, Worst> = Default::default();
            for s in data["samples"].as_array().unwrap() {
                let q: [f64; N] = arr(&s["q"]);
                let qd: [f64; N] = arr(&s["qd"]);
                let qdd: [f64; N] = arr(&s["qdd"]);
                let st = r::State::new(&q);
                let t = st.fk().to_homogeneous();
                for i in 0..4 {
                    for j in 0..4 {
                        worst.entry("T").or_default().check(
                            "T",
                            t[(i, j)],
                            s["T"][i][j].as_f64().unwrap(),
                        );
                    }
                }
                let jac = st.jacobian();
                for i in 0..6 {
                    for j in 0..N {
                        worst.entry("J").or_default().check(
                            "J",
                            jac[(i, j)],
                            s["J0"][i][j].as_f64().unwrap(),
                        );
                    }
                }
                let d = st.mass_matrix();
                let c = st.coriolis(&qd);
                let chr = st.christoffel();
                for i in 0..N {
                    for j in 0..N {
                        worst.entry("D").or_default().check(
                            "D",
                            d[(i, j)],
                            s["D"][i][j].as_f64().unwrap(),
                        );
                        worst.entry("C").or_default().check(
                            "C",
                            c[(i, j)],
                            s["C"][i][j].as_f64().unwrap(),
                        );
                        for k in 0..N {
                            // The data's index order is Gamma[k][j][i] = c_ijk.
                            let want = s["christoffel"][k][j][i].as_f64().unwrap();
                            worst
                                .entry("c_ijk")
                                .or_default()
                                .check("c_ijk", chr[i][j][k], want);
                        }
                    }
                }
                let g = st.gravity();
                let tau = st.inverse_dynamics(&qd, &qdd);
                for i in 0..N {
                    worst
                        .entry("g")
                        .or_default()
                        .check("g", g[i], s["g"][i].as_f64().unwrap());
                    worst.entry("tau").or_default().check(
                        "tau",
                        tau[i],
                        s["tau"][i].as_f64().unwrap(),
                    );
                }
                let tau_arr: [f64; N] = arr(&s["tau"]);
                let acc = st
                    .forward_dynamics(&qd, &tau_arr)
                    .expect("D is positive definite");
                for i in 0..N {
                    worst
                        .entry("qdd")
                        .or_default()
                        .check("forward dynamics", acc[i], qdd[i]);
                }
            }
            for (k, w) in &worst {
                println!("{} {k}: worst relative error {:.2e}", $name, w.0);
            }
        }
    };
}

check_robot!(planar_elbow_matches_reference, planar_elbow, "planar_elbow");
check_robot!(puma560_matches_reference, puma560, "puma560");
check_robot!(stanford_matches_reference, stanford, "stanford");
check_robot!(panda_matches_reference, panda, "panda");
