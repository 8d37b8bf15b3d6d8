//! Runs the `dhgen` binary for every command and checks what it prints against the
//! runtime path and against known values.

use dhgen::Robot;
use dhgen::nalgebra::DVector;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The workspace root: the paths in the commands are relative to it, as a user would type.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("cli/ has a parent")
        .to_path_buf()
}

fn dhgen(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_dhgen"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("the dhgen binary runs")
}

/// Runs a command that must succeed and returns its standard output.
fn stdout(args: &[&str]) -> String {
    let out = dhgen(args);
    assert!(
        out.status.success(),
        "dhgen {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

/// Runs a command that must fail and returns its one line of standard error.
fn failure(args: &[&str]) -> String {
    let out = dhgen(args);
    assert!(!out.status.success(), "dhgen {args:?} succeeded");
    assert!(
        out.stdout.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    let err = String::from_utf8(out.stderr).expect("UTF-8 error");
    assert_eq!(err.lines().count(), 1, "not one line: {err:?}");
    assert!(err.starts_with("dhgen: "), "{err}");
    assert!(!err.contains("panicked"), "{err}");
    err
}

/// The numbers of a JSON array.
fn numbers(v: &serde_json::Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

fn puma() -> Robot {
    Robot::from_toml_file(root().join("robots/puma560.toml")).unwrap()
}

#[test]
fn info_prints_the_dh_table_and_the_wrist() {
    let out = stdout(&["info", "robots/puma560.toml"]);
    assert!(out.starts_with("puma560 — Unimation PUMA 560\n"), "{out}");
    for row in [
        "│ 1 │ revolute │ q1 │ 0.67183 │      0 │  90° │ -160° │ 160° │",
        "│ 3 │ revolute │ q3 │ 0.15005 │ 0.0203 │ -90° │ -225° │  45° │",
        "│ 6 │ revolute │ q6 │       0 │      0 │   0° │ -266° │ 266° │",
    ] {
        assert!(out.contains(row), "missing {row:?} in\n{out}");
    }
    assert!(out.contains("DOF:             6\n"), "{out}");
    assert!(out.contains("RRRRRR (6 revolute, 0 prismatic)"), "{out}");
    assert!(
        out.contains("masses:          [0, 17.4, 4.8, 0.82, 0.34, 0.09] kg, total 23.45 kg"),
        "{out}"
    );
    // The wrist centre at q = 0: d4 above the elbow along z3, by the runtime frames.
    let line = out
        .lines()
        .find(|l| {
            l.starts_with("spherical wrist: yes: the axes of joints 4, 5, 6 meet in one point")
        })
        .unwrap_or_else(|| panic!("{out}"));
    let inside = line
        .split_once("q = 0: [")
        .unwrap()
        .1
        .split_once(']')
        .unwrap()
        .0;
    let centre: Vec<f64> = inside.split(", ").map(|x| x.parse().unwrap()).collect();
    // Frame 5's origin (index 4) lies on the axes of joints 5 and 6 and, d4 along z3, on 4's.
    let o5 = puma().frames(&[0.0; 6])[4].translation.vector;
    for i in 0..3 {
        assert!((centre[i] - o5[i]).abs() < 1e-6, "{line} vs {o5}");
    }
}

#[test]
fn info_on_other_arms() {
    let stanford = stdout(&["info", "robots/stanford.toml"]);
    // The prismatic joint's variable appears in the d column.
    assert!(stanford.contains("│ 3 │ prismatic │"), "{stanford}");
    assert!(stanford.contains("RRPRRR"), "{stanford}");
    assert!(stanford.contains("spherical wrist: yes"), "{stanford}");
    let panda = stdout(&["info", "robots/panda.toml"]);
    assert!(panda.contains("aⱼ₋₁"), "modified DH headers: {panda}");
    assert!(
        panda.contains("spherical wrist: no: the axes of joints 5, 6, 7 do not meet"),
        "{panda}"
    );
    let planar = stdout(&["info", "robots/planar_elbow.toml"]);
    assert!(
        planar.contains("spherical wrist: no (only 2 joints)"),
        "{planar}"
    );
    let cylindrical = stdout(&["info", "robots/cylindrical.toml"]);
    assert!(
        cylindrical.contains("dynamics:        none"),
        "{cylindrical}"
    );
    assert!(
        cylindrical.contains("spherical wrist: yes"),
        "{cylindrical}"
    );
}

/// The numbers of the block titled `title` in `eval`'s text output, row by row.
fn block(out: &str, title: &str) -> Vec<Vec<f64>> {
    out.lines()
        .skip_while(|l| !l.starts_with(title))
        .skip(1)
        .take_while(|l| !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect()
}

/// `eval`'s arguments for `file` at one state, asking for JSON.
fn eval_json(file: &str, q: &[f64], qd: &[f64], qdd: &[f64]) -> Vec<String> {
    let list = |v: &[f64]| v.iter().map(f64::to_string).collect::<Vec<_>>().join(",");
    let (q, qd, qdd) = (list(q), list(qd), list(qdd));
    [
        "eval", file, "--q", &q, "--qd", &qd, "--qdd", &qdd, "--json",
    ]
    .map(String::from)
    .to_vec()
}

fn as_strs(args: &[String]) -> Vec<&str> {
    args.iter().map(String::as_str).collect()
}

#[test]
fn eval_text_matches_the_runtime_at_zero() {
    let out = stdout(&["eval", "robots/puma560.toml", "--q", "0,0,0,0,0,0"]);
    let robot = puma();
    let d = block(&out, "D(q)");
    let want = robot.mass_matrix(&[0.0; 6]);
    assert_eq!(d.len(), 6, "{out}");
    for (r, row) in d.iter().enumerate() {
        assert_eq!(row.len(), 6);
        for (c, x) in row.iter().enumerate() {
            assert!(
                (x - want[(r, c)]).abs() <= 5e-7,
                "D[{r}][{c}] = {x}, want {}",
                want[(r, c)]
            );
        }
    }
    let g = block(&out, "g(q)");
    let want = robot.gravity(&[0.0; 6]);
    for (j, x) in g[0].iter().enumerate() {
        assert!((x - want[j]).abs() <= 5e-7, "g[{j}]");
    }
    // At q = 0 the tool sits at (a2 - ... ): the pose's translation column.
    let t = block(&out, "T:");
    let pose = robot.fk(&[0.0; 6]).translation.vector;
    for i in 0..3 {
        assert!((t[i][3] - pose[i]).abs() <= 5e-7);
    }
}

#[test]
fn eval_gives_the_tools_acceleration_at_zero_joint_acceleration() {
    // J̇_b q̇ against Pinocchio 4.1.0 (tests/data/pinocchio_kinematics.json, made by
    // scripts/pinocchio_kinematics.py), and J̇ q̇ against the runtime path, at its states.
    let data: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(root().join("tests/data/pinocchio_kinematics.json")).unwrap(),
    )
    .unwrap();
    for name in ["puma560", "panda"] {
        let file = format!("robots/{name}.toml");
        let robot = Robot::from_toml_file(root().join(&file)).unwrap();
        for sample in data["robots"][name].as_array().unwrap().iter().take(3) {
            let (q, qd) = (numbers(&sample["q"]), numbers(&sample["qd"]));
            let out = stdout(&as_strs(&eval_json(&file, &q, &qd, &vec![0.0; q.len()])));
            let v: serde_json::Value = serde_json::from_str(&out).unwrap();
            let (body, want) = (numbers(&v["Jb_dot_qd"]), numbers(&sample["Jb_dot_qd"]));
            let world = numbers(&v["Jdot_qd"]);
            let runtime = dhgen::Arm::jdot_qdot(
                &robot,
                &DVector::from_vec(q.clone()),
                &DVector::from_vec(qd.clone()),
            );
            assert_eq!((body.len(), world.len()), (6, 6), "{out}");
            for i in 0..6 {
                assert!(
                    (body[i] - want[i]).abs() <= 1e-10,
                    "{name} J̇_b q̇[{i}]: {out}"
                );
                assert!(
                    (world[i] - runtime[i]).abs() <= 1e-12,
                    "{name} J̇ q̇[{i}]: {out}"
                );
            }
        }
    }
    // The text output names both.
    let text = stdout(&[
        "eval",
        "robots/puma560.toml",
        "--q",
        "0,0.2,0,0,0.3,0",
        "--qd",
        "1,1,1,1,1,1",
    ]);
    assert!(text.contains("J̇q̇ (") && text.contains("J̇_b q̇ ("), "{text}");
}

#[test]
fn eval_json_matches_the_runtime() {
    let q = [0.1, -0.6, 0.4, 0.3, 0.8, -0.2];
    let qd = [0.5, -0.3, 0.2, 1.0, -0.7, 0.4];
    let qdd = [1.0, 0.5, -0.5, 0.2, 0.3, -1.0];
    let out = stdout(&as_strs(&eval_json("robots/puma560.toml", &q, &qd, &qdd)));
    let v: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
    let robot = puma();
    let matrix = |key: &str| -> Vec<Vec<f64>> {
        v[key]
            .as_array()
            .unwrap_or_else(|| panic!("{key} missing"))
            .iter()
            .map(|r| {
                r.as_array()
                    .unwrap()
                    .iter()
                    .map(|x| x.as_f64().unwrap())
                    .collect()
            })
            .collect()
    };
    let vector = |key: &str| -> Vec<f64> {
        v[key]
            .as_array()
            .unwrap_or_else(|| panic!("{key} missing"))
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect()
    };
    let close = |a: f64, b: f64| (a - b).abs() <= 1e-12 * (1.0 + b.abs());
    let check = |name: &str,
                 got: Vec<Vec<f64>>,
                 want: &dyn Fn(usize, usize) -> f64,
                 shape: (usize, usize)| {
        assert_eq!((got.len(), got[0].len()), shape, "{name}");
        for (r, row) in got.iter().enumerate() {
            for (c, x) in row.iter().enumerate() {
                assert!(
                    close(*x, want(r, c)),
                    "{name}[{r}][{c}]: {x} vs {}",
                    want(r, c)
                );
            }
        }
    };
    let t = robot.fk(&q).to_homogeneous();
    check("T", matrix("T"), &|r, c| t[(r, c)], (4, 4));
    let j = robot.jacobian(&q);
    check("J", matrix("J"), &|r, c| j[(r, c)], (6, 6));
    let jb = dhgen::Arm::body_jacobian(&robot, &dhgen::nalgebra::DVector::from_column_slice(&q));
    check("Jb", matrix("Jb"), &|r, c| jb[(r, c)], (6, 6));
    let (m, grad) =
        dhgen::velocity::manipulability_gradient(&j, dhgen::velocity::Axes::All).unwrap();
    assert!(m > 0.0 && close(v["manipulability"].as_f64().unwrap(), m));
    for (i, x) in vector("manipulability_gradient").iter().enumerate() {
        assert!(close(*x, grad[i]), "∂m/∂q_{i}: {x} vs {}", grad[i]);
    }
    let d = robot.mass_matrix(&q);
    check("D", matrix("D"), &|r, c| d[(r, c)], (6, 6));
    let cm = robot.coriolis(&q, &qd);
    check("C", matrix("C"), &|r, c| cm[(r, c)], (6, 6));
    let g = robot.gravity(&q);
    let tau = robot.inverse_dynamics(&q, &qd, &qdd);
    for i in 0..6 {
        assert!(close(vector("g")[i], g[i]));
        assert!(close(vector("tau")[i], tau[i]));
        assert_eq!(vector("q")[i], q[i]);
        assert_eq!(vector("qd")[i], qd[i]);
    }
    let kinetic = robot.kinetic_energy(&q, &qd);
    assert!(close(v["kinetic_energy"].as_f64().unwrap(), kinetic));
    let potential = robot.potential_energy(&q);
    assert!(close(v["potential_energy"].as_f64().unwrap(), potential));
    let (mass, centre) = robot.center_of_mass(&q);
    assert!(close(v["mass"].as_f64().unwrap(), mass));
    for i in 0..3 {
        assert!(close(vector("com")[i], centre[i]), "com[{i}]");
    }
    let jc = robot.center_of_mass_jacobian(&q);
    check("Jcom", matrix("Jcom"), &|r, c| jc[(r, c)], (3, 6));
    assert_eq!(v["robot"], "puma560");
    assert_eq!(v["dof"], 6);
    assert_eq!(v["has_dynamics"], true);
}

#[test]
fn eval_prints_the_derivatives_of_the_runtime() {
    // The SCARA: a prismatic joint, motors, viscous and Coulomb friction.
    let file = "robots/scara.toml";
    let robot = Robot::from_toml_file(root().join(file)).expect("scara loads");
    let (q, qd, qdd) = (
        [0.4, -1.1, 0.05, 0.7],
        [0.3, -0.8, 0.2, 1.5],
        [1.0, -0.5, 0.3, 2.0],
    );
    let args = eval_json(file, &q, &qd, &qdd);
    let args = as_strs(&args);
    let plain: serde_json::Value = serde_json::from_str(&stdout(&args)).expect("valid JSON");
    for key in ["dtau_dq", "dtau_dqd", "dqdd_dq", "dqdd_dqd", "Minv"] {
        assert!(
            plain.get(key).is_none(),
            "{key} printed without --derivatives"
        );
    }
    let v: serde_json::Value =
        serde_json::from_str(&stdout(&[&args[..], &["--derivatives"]].concat()))
            .expect("valid JSON");
    let (dtau_dq, dtau_dqd) = robot.inverse_dynamics_derivatives(&q, &qd, &qdd);
    let tau = robot.inverse_dynamics(&q, &qd, &qdd);
    let (dqdd_dq, dqdd_dqd, inverse) = robot
        .forward_dynamics_derivatives(&q, &qd, tau.as_slice())
        .expect("D is regular");
    let want = [
        ("dtau_dq", &dtau_dq),
        ("dtau_dqd", &dtau_dqd),
        ("dqdd_dq", &dqdd_dq),
        ("dqdd_dqd", &dqdd_dqd),
        ("Minv", &inverse),
    ];
    for (key, m) in want {
        let rows = v[key].as_array().unwrap_or_else(|| panic!("{key} missing"));
        assert_eq!(rows.len(), 4, "{key}");
        for (r, row) in rows.iter().enumerate() {
            let row = row.as_array().unwrap();
            assert_eq!(row.len(), 4, "{key}");
            for (c, x) in row.iter().enumerate() {
                let x = x.as_f64().unwrap();
                assert!(
                    (x - m[(r, c)]).abs() <= 1e-12 * (1.0 + m.amax()),
                    "{key}[{r}][{c}]: {x} vs {}",
                    m[(r, c)]
                );
            }
        }
    }
    // The viscous friction of joint 3 (20 N·s/m) is on the diagonal of ∂τ/∂q̇.
    let viscous = v["dtau_dqd"][2][2].as_f64().unwrap() - 2.0 * v["C"][2][2].as_f64().unwrap();
    assert!((viscous - 20.0).abs() < 1e-12, "{viscous}");
    let text = stdout(&[&args[..args.len() - 1], &["--derivatives"]].concat());
    for title in ["∂τ/∂q:", "∂τ/∂q̇", "∂q̈/∂q at", "∂q̈/∂q̇ at", "∂q̈/∂τ = D(q)⁻¹"]
    {
        assert!(text.contains(title), "{title} missing from\n{text}");
    }
    let m = block(&text, "∂q̈/∂τ = D(q)⁻¹");
    assert!((m[1][1] - inverse[(1, 1)]).abs() <= 5e-7 * (1.0 + inverse[(1, 1)].abs()));
}

#[test]
fn eval_prints_the_task_space_dynamics_of_the_tool() {
    let file = "robots/puma560.toml";
    let robot = Robot::from_toml_file(root().join(file)).expect("puma560 loads");
    let (q, qd, qdd) = (
        [0.2, -0.5, 0.4, 0.3, 0.9, -0.2],
        [0.5, -0.3, 0.8, 1.0, -0.4, 0.2],
        [0.0; 6],
    );
    let args = eval_json(file, &q, &qd, &qdd);
    let args = as_strs(&args);
    let plain: serde_json::Value = serde_json::from_str(&stdout(&args)).expect("valid JSON");
    for key in ["Lambda", "mu", "p", "task_space_error"] {
        assert!(
            plain.get(key).is_none(),
            "{key} printed without --task-space"
        );
    }
    let v: serde_json::Value =
        serde_json::from_str(&stdout(&[&args[..], &["--task-space"]].concat()))
            .expect("valid JSON");
    let (qv, qdv) = (DVector::from_row_slice(&q), DVector::from_row_slice(&qd));
    let task = dhgen::task_space::tool(&robot, &qv, &qdv).expect("away from singularities");
    let scale = 1.0 + task.inertia().amax();
    for r in 0..6 {
        for c in 0..6 {
            let x = v["Lambda"][r][c].as_f64().unwrap();
            assert!(
                (x - task.inertia()[(r, c)]).abs() <= 1e-12 * scale,
                "Λ[{r}][{c}]"
            );
        }
        let mu = v["mu"][r].as_f64().unwrap();
        assert!((mu - task.coriolis()[r]).abs() <= 1e-12 * scale, "μ[{r}]");
        let p = v["p"][r].as_f64().unwrap();
        assert!(
            (p - task.gravity()[r]).abs() <= 1e-12 * (1.0 + task.gravity().amax()),
            "p[{r}]"
        );
    }
    let text = stdout(&[&args[..args.len() - 1], &["--task-space"]].concat());
    let lambda = block(&text, "Λ(q) = (J D⁻¹ Jᵀ)⁻¹");
    assert!((lambda[1][1] - task.inertia()[(1, 1)]).abs() <= 5e-7 * scale);
    // At the wrist singularity (θ5 = 0) the command says why there is none.
    let singular = ["0.2", "-0.5", "0.4", "0.3", "0", "-0.2"].join(",");
    let text = stdout(&["eval", file, "--q", &singular, "--task-space"]);
    assert!(
        text.contains("no task-space dynamics: the task Jacobian has lost rank"),
        "{text}"
    );
    let json = stdout(&["eval", file, "--q", &singular, "--task-space", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&json).expect("valid JSON");
    assert!(v.get("Lambda").is_none());
    assert_eq!(
        v["task_space_error"],
        "task space: the task Jacobian has lost rank (J D⁻¹ Jᵀ is singular)"
    );
}

#[test]
fn eval_reads_angles_and_omits_missing_dynamics() {
    let deg = stdout(&[
        "eval",
        "robots/puma560.toml",
        "--json",
        "--q",
        // Within the PUMA's limits (joint 3: -225° to 45°): no warning.
        "90deg,0,-pi/2,0,0,0",
    ]);
    let rad = stdout(&[
        "eval",
        "robots/puma560.toml",
        "--json",
        "--q",
        &format!(
            "{},0,{},0,0,0",
            std::f64::consts::FRAC_PI_2,
            -std::f64::consts::FRAC_PI_2
        ),
    ]);
    assert_eq!(deg, rad);
    // A list may start with a negative number, be space-separated (one quoted argument),
    // and come before the robot, the order the usage line shows.
    let lists: [&[&str]; 4] = [
        &[
            "eval",
            "robots/planar_elbow.toml",
            "--json",
            "--q",
            "-0.5,1",
        ],
        &[
            "eval",
            "robots/planar_elbow.toml",
            "--json",
            "--q",
            "-0.5 1",
        ],
        &[
            "eval",
            "--q",
            "-0.5,1",
            "--json",
            "robots/planar_elbow.toml",
        ],
        &["eval", "--json", "--q=-0.5, 1", "robots/planar_elbow.toml"],
    ];
    for args in lists {
        let out = stdout(args);
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        assert_eq!(v["q"], serde_json::json!([-0.5, 1.0]), "{args:?}");
    }
    let out = stdout(&[
        "eval",
        "--q",
        "-0.5,1",
        "--qd",
        "-1,-2",
        "--qdd",
        "-3,4",
        "robots/planar_elbow.toml",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["qd"], serde_json::json!([-1.0, -2.0]));
    assert_eq!(v["qdd"], serde_json::json!([-3.0, 4.0]));
    // Huge values print in scientific notation, not as 300 digits.
    let out = stdout(&[
        "eval",
        "--q",
        "0,0",
        "--qdd",
        "1e300,0",
        "robots/planar_elbow.toml",
    ]);
    assert!(out.lines().all(|l| l.len() < 200), "{out}");
    assert!(out.contains("e30"), "{out}");

    let out = stdout(&[
        "eval",
        "robots/cylindrical.toml",
        "--q",
        "0,0.5,0.2,0,0,0",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["has_dynamics"], false);
    assert!(v.get("D").is_none() && v.get("tau").is_none(), "{out}");
    assert!(v.get("J").is_some());
    let text = stdout(&["eval", "robots/cylindrical.toml", "--q", "0,0.5,0.2,0,0,0"]);
    assert!(text.contains("no dynamics"), "{text}");
}

#[test]
fn emit_is_the_checked_in_file() {
    // If this fails after a change to the generator, regenerate the file:
    // `cargo run -p dhgen-cli -- emit robots/puma560.toml -o cli/tests/emitted/puma560.rs`
    let out = stdout(&["emit", "robots/puma560.toml"]);
    let checked_in = include_str!("emitted/puma560.rs");
    assert!(
        out == checked_in,
        "cli/tests/emitted/puma560.rs is stale: regenerate it with \
         `cargo run -p dhgen-cli -- emit robots/puma560.toml -o cli/tests/emitted/puma560.rs`"
    );
}

#[test]
fn emit_with_every_option_is_the_checked_in_file() {
    // The one-joint arm whose emitted file `emitted_code.rs` compiles with warnings denied.
    // Regenerate after a change to the generator:
    // `cargo run -p dhgen-cli -- emit cli/tests/emitted/one_joint.toml --derivatives
    // --regressor -o cli/tests/emitted/one_joint.rs`
    let out = stdout(&[
        "emit",
        "cli/tests/emitted/one_joint.toml",
        "--derivatives",
        "--regressor",
    ]);
    assert!(
        out == include_str!("emitted/one_joint.rs"),
        "cli/tests/emitted/one_joint.rs is stale: regenerate it with `cargo run -p dhgen-cli \
         -- emit cli/tests/emitted/one_joint.toml --derivatives --regressor -o \
         cli/tests/emitted/one_joint.rs`"
    );
}

#[test]
fn emit_writes_a_file_and_renames_the_module() {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("emit_planar.rs");
    let path_text = path.to_str().unwrap();
    let out = stdout(&[
        "emit",
        "robots/planar_elbow.toml",
        "-o",
        path_text,
        "--name",
        "arm",
    ]);
    assert!(out.is_empty());
    let written = std::fs::read_to_string(&path).unwrap();
    assert_eq!(
        written,
        stdout(&["emit", "robots/planar_elbow.toml", "--name", "arm"])
    );
    assert!(written.contains("\npub mod arm {\n"), "{written}");
    assert!(written.contains("pub const DOF: usize = 2"), "{written}");
    assert!(
        written.contains("impl ::dhgen::__private::ArmDynamics for Robot"),
        "{written}"
    );
    let err = failure(&["emit", "robots/planar_elbow.toml", "--name", "type"]);
    assert!(
        err.contains("--name \"type\" is not a Rust identifier"),
        "{err}"
    );
}

#[test]
fn latex_prints_the_equations() {
    let out = stdout(&["latex", "robots/puma560.toml"]);
    assert!(
        out.starts_with("% Unimation PUMA 560: D(q), Christoffel symbols, g(q) and P(q)"),
        "{out}"
    );
    // D, c_ijk, g, P, and (spherical wrist) det J11 / det J22.
    assert_eq!(out.matches("\\begin{align*}").count(), 5, "{out}");
    assert_eq!(out.matches("\\end{align*}").count(), 5, "{out}");
    // P at q = 0: 154.6 + 1.024 + 8.744 + 0.02825 (the constant, c_2, c_2 c_3, c_2 c_3 c_5
    // terms) = the runtime's.
    assert!(
        out.contains("  P &= 154.6 + 1.024\\,c_2 + 37.23\\,s_2 + 8.744\\,c_2 c_3"),
        "{out}"
    );
    assert!((154.6 + 1.024 + 8.744 + 0.02825 - puma().potential_energy(&[0.0; 6])).abs() < 0.06);
    assert!(out.contains("  \\det J_{22} &= -s_5"), "{out}");
    assert!(out.contains("  d_{11} &= 1.554 + "), "{out}");
    // g_2 at q = 0 is 37.23 + 0.2489 (the c_2 and c_2 c_3 terms) = g(0)[1] of the runtime.
    assert!(
        out.contains("  g_{2} &= 37.23\\,c_2 - 1.024\\,s_2 + 0.2489\\,c_2 c_3"),
        "{out}"
    );
    assert!((37.23 + 0.2489 - puma().gravity(&[0.0; 6])[1]).abs() < 6e-3);
    // g_1 is identically zero (joint 1's axis is vertical) and so is not listed.
    assert!(!out.contains("g_{1}"), "{out}");
    // Christoffel symbols with i > j are not listed; c_111 = ½ ∂d_11/∂q_1 = 0.
    assert!(out.contains("  c_{112} &="), "{out}");
    assert!(
        !out.contains("c_{211}") && !out.contains("c_{111}"),
        "{out}"
    );

    let cumulative = stdout(&[
        "latex",
        "robots/puma560.toml",
        "--cumulative",
        "--digits",
        "3",
    ]);
    assert!(
        cumulative.contains("  g_{3} &= 0.249\\,c_{23} - 8.74\\,s_{23}"),
        "{cumulative}"
    );

    let err = failure(&["latex", "robots/cylindrical.toml"]);
    assert!(
        err.contains("robots/cylindrical.toml: the description has no mass properties"),
        "{err}"
    );
}

/// The derivatives are generated on request only (`--derivatives`, as
/// `robot!(..., derivatives)`), and then appear in both the table and the module.
#[test]
fn derivatives_are_generated_on_request() {
    let rows = [
        "inverse_dynamics_derivatives",
        "mass_matrix_rate",
        "coriolis_transpose_qd",
    ];
    let plain = stdout(&["ops", "robots/puma560.toml"]);
    let with = stdout(&["ops", "--derivatives", "robots/puma560.toml"]);
    for name in rows {
        let row = format!("│ {name} ");
        assert!(!plain.contains(&row), "{plain}");
        assert!(with.contains(&row), "{with}");
    }
    let code = stdout(&["emit", "--derivatives", "robots/scara.toml"]);
    assert!(code.contains("pub fn inverse_dynamics_derivatives<T: ::dhgen::__private::Real>("));
    syn::parse_file(&code).expect("the emitted module parses");
    // A kinematics-only robot has no dynamics to differentiate: nothing is added.
    let kinematic = stdout(&["ops", "--derivatives", "robots/cylindrical.toml"]);
    assert!(!kinematic.contains("derivatives"), "{kinematic}");
    // Past the joints for which C is straight-line code, Ḋ = C + Cᵀ and Cᵀq̇ come from C's
    // loop as on the runtime path (straight-line, they took longer than the runtime's at 30
    // joints): listed with the loops, not in the table.
    let long = stdout(&["ops", "--derivatives", "tests/fixtures/snake17.toml"]);
    let looped = long
        .lines()
        .find(|l| l.starts_with("looped "))
        .unwrap_or_else(|| panic!("no loops in\n{long}"));
    for name in ["coriolis", "mass_matrix_rate", "coriolis_transpose_qd"] {
        assert!(looped.contains(name), "{long}");
        assert!(!long.contains(&format!("│ {name} ")), "{long}");
    }
    assert!(long.contains("│ inverse_dynamics_derivatives "), "{long}");
}

/// The regressor is generated on request only (`--regressor`, as `robot!(..., regressor)`),
/// and then appears in the table and the module, with the base parameters' constants.
#[test]
fn regressor_is_generated_on_request() {
    let plain = stdout(&["ops", "robots/puma560.toml"]);
    let with = stdout(&["ops", "--regressor", "robots/puma560.toml"]);
    for name in ["regressor_smooth", "base_regressor_smooth"] {
        let row = format!("│ {name} ");
        assert!(!plain.contains(&row), "{plain}");
        assert!(with.contains(&row), "{with}");
    }
    let code = stdout(&["emit", "--regressor", "robots/scara.toml"]);
    for item in [
        "pub fn regressor<T: ::dhgen::__private::Real>(",
        "pub fn base_regressor<T: ::dhgen::__private::Real>(",
        "pub fn base_parameters<T: ::dhgen::__private::Real>(",
        "pub const PARAMETERS: usize = 51;",
        "pub const BASE_PARAMETERS: usize = 18;",
    ] {
        assert!(code.contains(item), "{item} missing");
    }
    syn::parse_file(&code).expect("the emitted module parses");
    let kinematic = stdout(&["ops", "--regressor", "robots/cylindrical.toml"]);
    assert!(!kinematic.contains("regressor"), "{kinematic}");
}

#[test]
fn ops_prints_the_cost_table() {
    let out = stdout(&["ops", "robots/puma560.toml"]);
    let first = out.lines().next().unwrap();
    assert!(
        first.starts_with("puma560 (6 DOF, with dynamics): generated in "),
        "{out}"
    );
    assert!(first.contains(" ms, ~"), "{out}");
    let mut total = 0;
    let mut all = None;
    for name in [
        "fk_matrix",
        "jacobian",
        "mass_matrix",
        "christoffel",
        "gravity",
        "all",
    ] {
        let row = out
            .lines()
            .find(|l| l.starts_with(&format!("│ {name} ")))
            .unwrap_or_else(|| panic!("no row {name} in\n{out}"));
        let cells: Vec<usize> = row
            .split('│')
            .skip(2)
            .filter(|c| !c.trim().is_empty())
            .map(|c| c.trim().parse().unwrap())
            .collect();
        assert_eq!(cells.len(), 5, "{row}");
        // add + mul + div + sqrt = total.
        assert_eq!(cells[0] + cells[1] + cells[2] + cells[3], cells[4], "{row}");
        assert!(cells[4] > 0, "{row}");
        if name == "all" {
            all = Some(cells[4]);
        } else {
            total += cells[4];
        }
    }
    assert!(all.unwrap() >= total, "{out}");
}

#[test]
fn bad_files_and_arguments_fail_with_one_line() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));

    let err = failure(&["info", "robots/no_such_robot.toml"]);
    assert!(
        err.contains("robots/no_such_robot.toml: cannot read file"),
        "{err}"
    );

    let syntax = tmp.join("bad_syntax.toml");
    std::fs::write(
        &syntax,
        "name = \"x\"\nconvention = \"standard\"\n[[links]]\njoint = \"revolute\"\na = \n",
    )
    .unwrap();
    let err = failure(&["info", syntax.to_str().unwrap()]);
    assert!(
        err.contains("bad_syntax.toml:5:") && err.contains("invalid TOML"),
        "{err}"
    );

    let text = std::fs::read_to_string(root().join("robots/puma560.toml")).unwrap();
    let invalid = tmp.join("negative_mass.toml");
    let bad = text.replace("mass = 4.8", "mass = -4.8");
    std::fs::write(&invalid, &bad).unwrap();
    // The error points at the value: its line, and the column after `mass = ` (1-based).
    let line = bad.lines().position(|l| l == "mass = -4.8").unwrap() + 1;
    let at = format!("negative_mass.toml:{line}:8: link 3, field `mass`: mass -4.8 is negative");
    for command in ["info", "emit", "latex", "ops"] {
        let err = failure(&[command, invalid.to_str().unwrap()]);
        assert!(err.contains(&at), "{command}: {err}");
    }

    let err = failure(&["eval", "robots/puma560.toml", "--q", "1,2"]);
    assert_eq!(err, "dhgen: --q has 2 values, but puma560 has 6 joints\n");
    let err = failure(&[
        "eval",
        "robots/puma560.toml",
        "--q",
        "0,0,0,0,0,0",
        "--qd",
        "1",
    ]);
    assert!(
        err.contains("--qd has 1 value, but puma560 has 6 joints"),
        "{err}"
    );
    let err = failure(&["eval", "robots/puma560.toml", "--q", "0,0,0,0,0,x"]);
    assert!(
        err.contains("--q, joint 6: cannot parse angle \"x\""),
        "{err}"
    );
    let err = failure(&["eval", "robots/puma560.toml"]);
    assert!(err.contains("--q"), "{err}");
    let err = failure(&[
        "eval",
        "robots/puma560.toml",
        "--q",
        "0,0,0,0,0,0",
        "--qdd",
        "0,0,a,0,0,0",
    ]);
    assert!(
        err.contains("--qdd, joint 3: \"a\" is not a finite number"),
        "{err}"
    );
    let err = failure(&[
        "eval",
        "robots/puma560.toml",
        "--q",
        "0,0,0,0,0,0",
        "--qd",
        "0,0,0,0,0,inf",
    ]);
    assert!(
        err.contains("--qd, joint 6: \"inf\" is not a finite number"),
        "{err}"
    );
    let err = failure(&["frobnicate"]);
    assert!(err.contains("frobnicate"), "{err}");
    failure(&[]);
    failure(&["latex", "robots/puma560.toml", "--digits", "0"]);
}

#[test]
fn help_and_version_succeed() {
    let help = stdout(&["--help"]);
    for command in ["info", "eval", "emit", "latex", "ops"] {
        assert!(help.contains(command), "{help}");
    }
    assert!(stdout(&["--version"]).starts_with("dhgen "));
}

/// The generator takes 20-joint arms (a test that expands one, without compiling it) and
/// refuses, with a one-line error naming the limit, what it does not take: 33 joints with
/// dynamics, 1000 joints of kinematics (it once ran for minutes on those).
#[test]
fn emit_expands_twenty_joints_and_bounds_its_work() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let path = |name: &str| tmp.join(name).to_str().unwrap().to_string();
    let twenty = path("random20.toml");
    stdout(&[
        "random",
        "--dof",
        "20",
        "--style",
        "industrial",
        "--seed",
        "5",
        "-o",
        &twenty,
    ]);
    let code = stdout(&["emit", &twenty]);
    assert!(code.contains("(20 DOF)"), "{}", &code[..300]);
    for f in [
        "pub fn mass_matrix",
        "pub fn christoffel",
        "pub fn forward_dynamics",
    ] {
        assert!(code.contains(f), "no {f}");
    }
    syn::parse_file(&code).expect("the emitted 20-joint module parses");

    let long = path("random33.toml");
    stdout(&["random", "--dof", "33", "--seed", "5", "-o", &long]);
    let err = failure(&["emit", &long]);
    assert!(
        err.contains("random33.toml: field `links`: the robot has 33 joints")
            && err.contains("at most 32 joints with mass properties")
            && err.contains("dhgen::Robot"),
        "{err}"
    );
    assert!(failure(&["ops", &long]).contains("at most 32 joints"));

    // 1000 joints without mass properties: refused at once, not after minutes.
    let dynamics = stdout(&["random", "--dof", "1000", "--style", "industrial"]);
    let kinematics: String = dynamics
        .lines()
        .filter(|l| {
            !["mass", "com", "inertia", "motor", "friction"]
                .iter()
                .any(|k| l.starts_with(k))
        })
        .map(|l| format!("{l}\n"))
        .collect();
    let thousand = path("kinematics1000.toml");
    std::fs::write(&thousand, kinematics).unwrap();
    let err = failure(&["emit", &thousand]);
    assert!(
        err.contains("the robot has 1000 joints")
            && err.contains("at most 100 joints for kinematics"),
        "{err}"
    );
    // The runtime path takes it: `info` and `eval` work at any length.
    assert!(stdout(&["info", &thousand]).contains("1000"));
    let zeros = vec!["0"; 1000].join(",");
    let out = stdout(&["eval", "--json", "--q", &zeros, &thousand]);
    assert!(
        out.contains("\"dof\":1000") || out.contains("\"dof\": 1000"),
        "{}",
        &out[..200]
    );
}

/// Hostile files through the command line (`dhgen_description::hostile::mutate` of small catalogue
/// robots, the 100,000-variant run of the loader is tests/integration/hostile_descriptions.rs):
/// every command ends with status 0 or 1, never a panic or a signal, and a failure is one
/// line naming the file with the line and column.
#[test]
fn hostile_files_never_crash_a_command() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR")).join("hostile");
    std::fs::create_dir_all(&tmp).unwrap();
    let seeds = ["planar_elbow", "scara", "cylindrical", "stanford"];
    let (mut ok, mut rejected) = (0, 0);
    for seed in 0..400u64 {
        let name = seeds[(seed % 4) as usize];
        let source = root().join(format!("robots/{name}.toml"));
        let text = std::fs::read_to_string(&source).unwrap();
        let n = Robot::from_toml_file(&source).unwrap().dof();
        let path = tmp.join(format!("{name}_{seed}.toml"));
        std::fs::write(&path, dhgen::model::hostile::mutate(&text, seed)).unwrap();
        let file = path.to_str().unwrap();
        let zeros = vec!["0"; n].join(",");
        let short = Robot::from_toml_file(&path)
            .ok()
            .is_none_or(|r| r.dof() <= 8);
        let generator = match (short, seed % 2) {
            (false, _) => "info",
            (true, 0) => "emit",
            (true, _) => "ops",
        };
        let commands: [&[&str]; 3] = [
            &["info", file],
            &["eval", "--q", &zeros, file],
            // Generation costs seconds for the long chains some variants have: those go
            // through the loader only (the limits are tested above).
            &[generator, file],
        ];
        for args in commands {
            let out = dhgen(args);
            let err = String::from_utf8_lossy(&out.stderr);
            match out.status.code() {
                Some(0) => ok += 1,
                Some(1) => {
                    rejected += 1;
                    assert_eq!(err.lines().count(), 1, "{args:?}: {err:?}");
                    // A load error names the file and where in it; `eval` may also
                    // reject the joint count (the file's robot may differ from the seed).
                    let located = err.starts_with(&format!("dhgen: {file}:"));
                    let count = err.contains(&format!("--q has {n} values"));
                    assert!(located || count, "{args:?}: {err}");
                }
                other => panic!("dhgen {args:?} ended with {other:?}: {err}"),
            }
        }
    }
    assert!(
        ok > 60 && rejected > 400,
        "{ok} succeeded, {rejected} failed"
    );
}

#[test]
fn urdf_files_work_in_every_command() {
    let ur5 = "tests/data/urdf/ur5.urdf";
    let info = stdout(&["info", ur5]);
    assert!(info.contains("convention:      urdf"), "{info}");
    assert!(
        info.contains("URDF chain:      from link `world` to link `wrist_3_link`"),
        "{info}"
    );
    assert!(
        info.contains("1 shoulder_pan_joint, 2 shoulder_lift_joint"),
        "{info}"
    );
    // ROS-Industrial's 1.57079632679 is 4.9e-12 from π/2: listed, with its line.
    assert!(
        info.contains("line 86:13: joint `shoulder_lift_joint` <origin rpy> pitch: 1.57079632679 read as 1.5707963267948966 (90°)"),
        "{info}"
    );
    let strict = stdout(&["info", ur5, "--snap", "0"]);
    assert!(strict.contains("snapped:         none"), "{strict}");
    // eval agrees with the runtime path reading the same file.
    let robot = Robot::from_urdf_file(root().join(ur5)).unwrap();
    let q = [0.1, -0.5, 0.7, 0.2, -0.3, 0.4];
    let json = stdout(&["eval", ur5, "--q", "0.1,-0.5,0.7,0.2,-0.3,0.4", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let g = robot.gravity(&q[..]);
    for (i, gi) in g.iter().enumerate() {
        let got = v["g"][i].as_f64().unwrap();
        assert!(
            (got - gi).abs() <= 1e-12 * gi.abs().max(1.0),
            "{got} vs {gi}"
        );
    }
    // A tree needs its tip; with it, every command runs.
    let panda = "tests/data/urdf/panda.urdf";
    let e = failure(&["info", panda]);
    assert!(
        e.contains("2 ends (`panda_leftfinger`, `panda_rightfinger`)"),
        "{e}"
    );
    let info = stdout(&["info", panda, "--tip", "panda_hand"]);
    assert!(
        info.contains("held at zero:    panda_finger_joint1, panda_finger_joint2"),
        "{info}"
    );
    let code = stdout(&["emit", panda, "--tip", "panda_hand", "--name", "panda"]);
    assert!(code.contains("pub mod panda"), "{}", &code[..200]);
    let ops = stdout(&["ops", panda, "--tip", "panda_hand"]);
    assert!(ops.contains("inverse_dynamics_smooth"), "{ops}");
    let tex = stdout(&["latex", "tests/data/urdf/double_pendulum_continuous.urdf"]);
    assert!(tex.contains("\\begin"), "{tex}");
    // URDF settings on a TOML file are a mistake, said so.
    let e = failure(&["info", "robots/puma560.toml", "--tip", "link6"]);
    assert!(
        e.contains("--tip, --base and --snap read URDF files"),
        "{e}"
    );
    let e = failure(&["info", ur5, "--snap", "1"]);
    assert!(e.contains("from 0 to 0.1"), "{e}");
}

#[test]
fn convert_goes_between_urdf_and_dh() {
    let dir = std::env::temp_dir().join(format!("dhgen-convert-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let q = [0.3, -0.4, 0.9, -0.2, 0.5, 0.1];
    // A URDF robot as a DH table: the same runtime robot.
    let ur5 = root().join("tests/data/urdf/ur5.urdf");
    let urdf = Robot::from_urdf_file(&ur5).unwrap();
    let dh_text = stdout(&["convert", "tests/data/urdf/ur5.urdf", "--to", "dh"]);
    assert!(dh_text.contains("convention = \"standard\""), "{dh_text}");
    let dh = Robot::from_toml_str(&dh_text).unwrap();
    let mdh = Robot::from_toml_str(&stdout(&[
        "convert",
        "tests/data/urdf/ur5.urdf",
        "--to",
        "mdh",
    ]))
    .unwrap();
    let as_toml = Robot::from_toml_str(&stdout(&[
        "convert",
        "tests/data/urdf/ur5.urdf",
        "--to",
        "toml",
    ]))
    .unwrap();
    let tau = |r: &Robot| r.inverse_dynamics(&q[..], &[0.5; 6][..], &[-1.0; 6][..]);
    let want = tau(&urdf);
    for (what, r) in [("dh", &dh), ("mdh", &mdh), ("toml", &as_toml)] {
        let got = tau(r);
        for i in 0..6 {
            assert!(
                (got[i] - want[i]).abs() < 1e-12 * want[i].abs().max(1.0),
                "{what}"
            );
        }
        let (a, b) = (r.fk(&q[..]), urdf.fk(&q[..]));
        assert!(
            (a.translation.vector - b.translation.vector).norm() < 1e-14,
            "{what}"
        );
    }
    // A DH description to URDF and back through the reader.
    let out = dir.join("puma.urdf");
    stdout(&[
        "convert",
        "robots/puma560.toml",
        "--to",
        "urdf",
        "-o",
        out.to_str().unwrap(),
    ]);
    let back = Robot::from_urdf_file(&out).unwrap();
    let puma = puma();
    let (a, b) = (back.mass_matrix(&q[..]), puma.mass_matrix(&q[..]));
    // The URDF carries no motor inertia: compare without the armature on the diagonal.
    for i in 0..6 {
        for j in 0..6 {
            let arm = if i == j {
                puma.chain().bodies[i].armature
            } else {
                0.0
            };
            assert!((a[(i, j)] - (b[(i, j)] - arm)).abs() < 1e-12, "D[{i}][{j}]");
        }
    }
    let e = failure(&["convert", "robots/puma560.toml", "--to", "xml"]);
    assert!(e.contains("xml"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn params_prints_the_parameters_and_the_base_set() {
    let out = stdout(&["params", "robots/planar_elbow.toml"]);
    assert!(out.contains("planar_elbow: 20 parameters"), "{out}");
    assert!(out.contains("m1 = 2.000000, mx1 = -1.000000"), "{out}");
    assert!(out.contains("6 base parameters"), "{out}");
    let tex = stdout(&["params", "robots/puma560.toml", "--latex"]);
    assert!(tex.starts_with("\\begin{align*}"), "{tex}");
    assert_eq!(tex.matches("\\pi_{b,").count(), 36, "{tex}");
    let e = failure(&["params", "tests/fixtures/bare.toml"]);
    assert!(e.contains("no mass properties"), "{e}");
}

/// `params --json` gives π and the regrouping exactly: the library's own values and base
/// parameters, and β such that `π[independent[k]] + Σ_m β[k][m] π[dependent[m]]` is base
/// parameter k, on a robot with friction and motors; `--latex` and `--json` exclude each other.
#[test]
fn params_json_is_the_regrouping_exactly() {
    for file in [
        "robots/puma560.toml",
        "robots/scara.toml",
        "tests/fixtures/driven.toml",
    ] {
        let v: serde_json::Value =
            serde_json::from_str(&stdout(&["params", "--json", file])).expect("JSON");
        let robot = Robot::from_toml_file(root().join(file)).unwrap();
        let indices = |x: &serde_json::Value| -> Vec<usize> {
            x.as_array()
                .unwrap()
                .iter()
                .map(|e| e.as_u64().unwrap() as usize)
                .collect()
        };
        let pi = numbers(&v["values"]);
        assert_eq!(pi, robot.parameters().as_slice(), "{file}");
        let names: Vec<&str> = v["names"]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| n.as_str().unwrap())
            .collect();
        assert_eq!(names, robot.parameter_names(), "{file}");
        let base = robot.base_parameters();
        let b = &v["base"];
        let (independent, dependent) = (indices(&b["independent"]), indices(&b["dependent"]));
        assert_eq!(
            (&independent, &dependent),
            (&base.independent, &base.dependent),
            "{file}"
        );
        let pi_b = numbers(&b["values"]);
        assert_eq!(pi_b, base.reduce(&robot.parameters()).as_slice(), "{file}");
        for (k, row) in b["beta"].as_array().unwrap().iter().enumerate() {
            let row = numbers(row);
            let sum = pi[independent[k]]
                + row
                    .iter()
                    .zip(&dependent)
                    .map(|(beta, &d)| beta * pi[d])
                    .sum::<f64>();
            assert!(
                (sum - pi_b[k]).abs() <= 1e-12 * (1.0 + pi_b[k].abs()),
                "{file}: {k}"
            );
        }
        assert_eq!(b["rules"].as_array().unwrap().len(), base.count(), "{file}");
    }
    let e = failure(&["params", "--json", "--latex", "robots/puma560.toml"]);
    assert!(e.contains("cannot be used with"), "{e}");
}

/// A description's text goes into the emitted file's doc attributes, and its file name into
/// the header comment. Carriage returns, other control characters and the bidirectional
/// overrides cannot be written into comments (rustc rejects a bare CR in a doc comment and
/// denies `text_direction_codepoint_in_comment`): the doc stays an attribute with the
/// characters escaped, and the file name is escaped, so the file compiles and shows them.
#[test]
fn emit_escapes_control_and_bidi_characters_in_comments() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));
    let descriptions = [
        "Arm\rv2",
        "\u{1b}[31mred\u{1b}[0m \u{2028} \u{202e} rtl \u{85}",
        "a \u{2066}isolate\u{2069} and \u{202a}embedding\u{202c}, a\tb",
    ];
    let hidden = |c: char| {
        (c.is_control() && c != '\n')
            || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' | '\u{2028}')
    };
    for (k, description) in descriptions.iter().enumerate() {
        // The file name carries a line break and an override too.
        let path = tmp.join(format!("desc{k}\n\u{202e}.toml"));
        let escaped: String = description
            .chars()
            .map(|c| match c {
                '\r' => "\\r".to_string(),
                '\t' => "\\t".to_string(),
                c if c.is_control() || !c.is_ascii() => format!("\\u{:04X}", u32::from(c)),
                c => c.to_string(),
            })
            .collect();
        std::fs::write(
            &path,
            format!(
                "name = \"arm\"\ndescription = \"{escaped}\"\nconvention = \"standard\"\n\
                 [[links]]\njoint = \"revolute\"\na = 1.0\nalpha = 0\nd = 0\ntheta = 0\n\
                 mass = 1.0\ncom = [-0.5, 0, 0]\ninertia = {{ xx = 0.01, yy = 0.1, zz = 0.1 }}\n"
            ),
        )
        .unwrap();
        let code = stdout(&["emit", path.to_str().unwrap()]);
        let shown: String = code.chars().filter(|&c| hidden(c)).collect();
        assert!(
            shown.is_empty(),
            "{shown:?} written as is in\n{}",
            &code[..600]
        );
        assert!(code.starts_with(&format!(
            "// Generated by `dhgen emit` from desc{k}\\n\\u{{202e}}.toml: "
        )));
        let file = syn::parse_file(&code).expect("the emitted file parses");
        // The module's doc is the description, unchanged.
        let syn::Item::Mod(module) = &file.items[0] else {
            panic!("not a module first: {}", &code[..600]);
        };
        let doc = module
            .attrs
            .iter()
            .find_map(|a| match &a.meta {
                syn::Meta::NameValue(nv) if nv.path.is_ident("doc") => Some(&nv.value),
                _ => None,
            })
            .expect("a doc attribute");
        let syn::Expr::Lit(syn::ExprLit {
            lit: syn::Lit::Str(text),
            ..
        }) = doc
        else {
            panic!("the doc is not a string: {}", &code[..600]);
        };
        assert_eq!(
            text.value(),
            format!("{description} (1-DOF, generated by `dhgen::robot!`).")
        );
    }
}

/// `params` finds the base parameters by an O(n³) QR: 200 joints took 15 s in a release
/// build and 400 joints over two minutes, so past 100 joints it is refused at once, naming
/// the limit.
#[test]
fn params_refuses_long_chains_at_once() {
    let tmp = Path::new(env!("CARGO_TARGET_TMPDIR"));
    for dof in ["101", "200"] {
        let path = tmp.join(format!("params{dof}.toml"));
        let file = path.to_str().unwrap();
        stdout(&["random", "--dof", dof, "--seed", "2", "-o", file]);
        let start = std::time::Instant::now();
        let err = failure(&["params", file]);
        assert!(
            start.elapsed() < std::time::Duration::from_secs(10),
            "{:?}",
            start.elapsed()
        );
        assert!(
            err.contains(&format!(
                "params{dof}.toml: field `links`: the robot has {dof} joints"
            )) && err.contains("at most 100 joints")
                && err.contains("dhgen::Robot::base_parameters"),
            "{err}"
        );
    }
}

/// `eval` refuses a joint position beyond any robot's range (|q| ≤ 1e3 rad or m) and a
/// result that is not finite (docs/conventions.md, "Non-finite input"), and warns, without
/// failing, about a position outside the joint's limits.
#[test]
fn eval_refuses_out_of_range_input_and_warns_outside_limits() {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("prism_tilt.toml");
    std::fs::write(
        &path,
        "name = \"pt\"\nconvention = \"standard\"\ngravity = [3.0, 0.0, -9.81]\n\
         [[links]]\njoint = \"revolute\"\na = 0\nalpha = \"90deg\"\nd = 0\ntheta = 0\n\
         mass = 1.0\ncom = [0, 0, 0]\ninertia = { xx = 0.01, yy = 0.01, zz = 0.01 }\n\
         [[links]]\njoint = \"prismatic\"\na = 0\nalpha = 0\nd = 0\ntheta = 0\nlimits = [0, 1]\n\
         mass = 1.0\ncom = [0, 0, 0]\ninertia = { xx = 0.01, yy = 0.01, zz = 0.01 }\n",
    )
    .unwrap();
    let file = path.to_str().unwrap();
    // Once printed as NaN (and `null` in JSON) with status 0.
    let err = failure(&["eval", file, "--q", "0.3,1e308"]);
    assert!(
        err.contains("--q, joint 2: length 1e308 m is outside the range of any robot")
            && err.contains("at most 1e3 m"),
        "{err}"
    );
    let err = failure(&["eval", file, "--q", "1001,0", "--json"]);
    assert!(
        err.contains("--q, joint 1: angle 1001 rad is outside the range of any robot"),
        "{err}"
    );
    for args in [
        &["eval", file, "--q", "0.3,0.5", "--qd", "1e200,0", "--json"][..],
        &["eval", file, "--q", "0.3,0.5", "--qd", "1e200,0"][..],
    ] {
        let err = failure(args);
        assert!(
            // The first quantity evaluated that overflows: the tool's acceleration at q̈ = 0
            // (before J̇q̇ was printed, τ, whose entry 1 was NaN).
            err.contains("the result is not finite: J̇q̇ entry 1 is -inf")
                && err.contains("largest |q̇| 1e200"),
            "{err}"
        );
    }
    // Outside the limits [0, 1] m, within any robot's range: evaluated, with a warning.
    let out = dhgen(&["eval", file, "--q", "0.3,1.5", "--json"]);
    assert!(out.status.success());
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["q"], serde_json::json!([0.3, 1.5]));
    assert_eq!(
        String::from_utf8(out.stderr).unwrap(),
        "dhgen: warning: --q, joint 2: 1.5 m is outside the joint's limits [0, 1] m\n"
    );
    let out = dhgen(&["eval", "robots/puma560.toml", "--q", "0,0,0,0,0,400deg"]);
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8(out.stderr).unwrap(),
        "dhgen: warning: --q, joint 6: 6.981317 rad is outside the joint's limits \
         [-4.642576, 4.642576] rad (-266° to 266°)\n"
    );
}

/// `latex` says why it has no closed forms: the Panda (7 joints, exact quarter-turn twists)
/// exceeds the budget of D's normal form; a 17-joint arm exceeds the joints a normal form
/// can have. It once blamed missing parallel or perpendicular axes for both.
#[test]
fn latex_names_the_real_reason_for_no_closed_forms() {
    let err = failure(&["latex", "robots/panda.toml"]);
    assert!(
        err.contains("robots/panda.toml: the closed form of D(q)")
            && err.contains("more than the 30000 term operations allowed"),
        "{err}"
    );
    assert!(!err.contains("parallel"), "{err}");
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("latex17.toml");
    let file = path.to_str().unwrap();
    stdout(&["random", "--dof", "17", "--style", "industrial", "-o", file]);
    let err = failure(&["latex", file]);
    assert!(
        err.contains("the robot has 17 joints; the closed forms of D(q), c_ijk and g(q) are built for at most 16 joints"),
        "{err}"
    );
}

/// A negative number given to an option taking a number reaches its check, which says what
/// is allowed (clap once took `-1` for an unknown flag: "unexpected argument '-1' found").
#[test]
fn negative_numbers_are_checked_not_taken_for_flags() {
    for (args, message) in [
        (
            &["random", "--dof", "-1"][..],
            "invalid value '-1' for '--dof <DOF>': -1 is not in 1..=1000",
        ),
        (
            &["random", "--dof", "3", "--seed", "-1"][..],
            "invalid value '-1' for '--seed <SEED>': the seed is a whole number from 0 to 18446744073709551615",
        ),
        (
            &["latex", "robots/puma560.toml", "--digits", "-1"][..],
            "invalid value '-1' for '--digits <DIGITS>': -1 is not in 1..=17",
        ),
        (
            &["info", "tests/data/urdf/ur5.urdf", "--snap", "-1"][..],
            "--snap -1: the tolerance for reading angles as exact quarter turns is in radians, \
             from 0 to 0.1",
        ),
    ] {
        let err = failure(args);
        assert!(err.contains(message), "{args:?}: {err}");
        assert!(!err.contains("unexpected argument"), "{err}");
    }
}

/// An empty entry in a joint list is an error naming its position (it was dropped, so
/// `0,,0` read as two values).
#[test]
fn empty_list_entries_are_errors() {
    let err = failure(&["eval", "robots/planar_elbow.toml", "--q", "0,,0"]);
    assert_eq!(
        err,
        "dhgen: --q: entry 2 is empty in \"0,,0\" (one value per joint, separated by commas or spaces)\n"
    );
    let err = failure(&[
        "eval",
        "robots/planar_elbow.toml",
        "--q",
        "0,0",
        "--qd",
        "1,2,",
    ]);
    assert!(err.contains("--qd: entry 3 is empty"), "{err}");
    let err = failure(&[
        "eval",
        "robots/planar_elbow.toml",
        "--q",
        "0,0",
        "--qdd",
        ", 1,2",
    ]);
    assert!(err.contains("--qdd: entry 1 is empty"), "{err}");
    // Spaces around commas are separators, not entries.
    stdout(&["eval", "robots/planar_elbow.toml", "--q", "0 , 1"]);
}

/// A conversion that fails on a valid description blames the converted description, not
/// the input: a com 995 m beyond a 10 m link is 1005 m from the modified DH frame.
/// A URDF whose quarter turn is written 1.5708 (3.7e-6 rad short) puts modified DH's frame 0
/// kilometres away, out of range: the error says why and what to do, and the advice works.
#[test]
fn convert_explains_far_common_normals() {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("nearly_parallel.urdf");
    std::fs::write(
        &path,
        "<robot name=\"np\"><link name=\"base\"/><link name=\"l1\"/>\
         <joint name=\"j1\" type=\"revolute\"><parent link=\"base\"/><child link=\"l1\"/>\
         <origin xyz=\"0 -0.045 0.0165\" rpy=\"1.5708 0 0\"/><axis xyz=\"0 1 0\"/></joint>\
         </robot>",
    )
    .unwrap();
    let file = path.to_str().unwrap();
    let err = failure(&["convert", file, "--to", "mdh"]);
    assert!(
        err.contains("the converted `base.xyz` is not valid")
            && err.contains("DH puts the common normal of nearly parallel axes far away")
            && err.contains("--snap 1e-4"),
        "{err}"
    );
    let table = stdout(&["convert", file, "--to", "mdh", "--snap", "1e-4"]);
    assert!(table.contains("convention = \"modified\""), "{table}");
}

#[test]
fn convert_blames_the_converted_description() {
    let path = Path::new(env!("CARGO_TARGET_TMPDIR")).join("far_com.toml");
    std::fs::write(
        &path,
        "name = \"far\"\nconvention = \"standard\"\n[[links]]\njoint = \"revolute\"\n\
         a = 10.0\nalpha = 0\nd = 0\ntheta = 0\nmass = 1.0\ncom = [995.0, 0, 0]\n\
         inertia = { xx = 0.01, yy = 0.01, zz = 0.01 }\n",
    )
    .unwrap();
    let file = path.to_str().unwrap();
    stdout(&["info", file]);
    let err = failure(&["convert", file, "--to", "mdh"]);
    assert!(
        err.contains(
            "far_com.toml: converting to modified DH: the converted `com` of link 1 is not valid \
             (a value the conversion computed; the input's are valid): length 1005 m is outside"
        ),
        "{err}"
    );
}

/// The joint values of a solution in `dhgen ik --json`'s output.
fn ik_q(v: &serde_json::Value) -> Vec<f64> {
    v["q"]
        .as_array()
        .unwrap_or_else(|| panic!("no q in {v}"))
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// Every closed-form solution of the PUMA 560 at the pose of a configuration puts the tool
/// there, one of them is that configuration, and so does the numeric one.
#[test]
fn ik_finds_the_configuration_it_was_given_and_the_others() {
    let robot = puma();
    let q = [0.2, -0.3, 0.1, 0.4, 0.6, -0.5];
    let list: Vec<String> = q.iter().map(|x| x.to_string()).collect();
    let out = stdout(&[
        "ik",
        "robots/puma560.toml",
        "--at",
        &list.join(","),
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_str(&out).expect("valid JSON");
    let target = robot.fk(&q);
    let at_target = |s: &[f64]| {
        let (dp, dr) = dhgen::ik::pose_error(&robot.fk(s), &target);
        dp < 1e-10 && dr < 1e-10
    };
    let solutions = v["closed_form"]["solutions"].as_array().expect("solutions");
    assert_eq!(solutions.len(), 8);
    for s in solutions {
        assert!(at_target(&ik_q(s)), "{s}");
    }
    assert!(
        solutions
            .iter()
            .any(|s| { ik_q(s).iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9) })
    );
    assert!(at_target(&ik_q(&v["numeric"])));
    assert!(v["preferred"].is_null());
}

/// On the Panda (no closed form), the pose given by position and roll-pitch-yaw (about the
/// fixed axes: nalgebra's `from_euler_angles`) is reached, and the preferred solutions are
/// more manipulable or nearer the posture than the numeric one they start from.
#[test]
fn ik_on_a_redundant_arm_prefers() {
    let robot = Robot::from_toml_file(root().join("robots/panda.toml")).unwrap();
    let (p, rpy) = ([0.4, 0.1, 0.5], [3.0, 0.2, -0.4]);
    let target = dhgen::nalgebra::Isometry3::from_parts(
        dhgen::nalgebra::Translation3::new(p[0], p[1], p[2]),
        dhgen::nalgebra::UnitQuaternion::from_euler_angles(rpy[0], rpy[1], rpy[2]),
    );
    let seed = "0,0,0,-1.5,0,1.5,0";
    let run = |extra: &[&str]| -> serde_json::Value {
        let mut args = vec![
            "ik",
            "robots/panda.toml",
            "--position",
            "0.4,0.1,0.5",
            "--rpy",
            "3,0.2,-0.4",
            "--seed",
            seed,
            "--json",
        ];
        args.extend_from_slice(extra);
        serde_json::from_str(&stdout(&args)).expect("valid JSON")
    };
    let m = |q: &[f64]| dhgen::velocity::manipulability(&robot.jacobian(q));
    let reached = |q: &[f64]| {
        let (dp, dr) = dhgen::ik::pose_error(&robot.fk(q), &target);
        assert!(dp < 1e-10 && dr < 1e-10, "{dp:e} {dr:e}");
    };
    let v = run(&["--most-manipulable"]);
    assert!(v["closed_form"]["unavailable"].is_string());
    let (first, most) = (ik_q(&v["numeric"]), ik_q(&v["preferred"]));
    reached(&first);
    reached(&most);
    assert!(m(&most) >= m(&first));
    assert_eq!(v["preferred"]["preference"], "most manipulable");
    let posture = [0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785];
    let list: Vec<String> = posture.iter().map(|x| x.to_string()).collect();
    let v = run(&["--nearest", &list.join(",")]);
    let (first, near) = (ik_q(&v["numeric"]), ik_q(&v["preferred"]));
    reached(&near);
    let distance = |q: &[f64]| {
        q.iter()
            .zip(&posture)
            .map(|(a, b)| (a - b) * (a - b))
            .sum::<f64>()
    };
    assert!(distance(&near) <= distance(&first));
    // The text names each part.
    let text = stdout(&[
        "ik",
        "robots/panda.toml",
        "--position",
        "0.4,0.1,0.5",
        "--rpy",
        "3,0.2,-0.4",
        "--most-manipulable",
    ]);
    for part in [
        "closed form: none",
        "numeric, from the seed",
        "most manipulable:",
    ] {
        assert!(text.contains(part), "{part} missing in\n{text}");
    }
}

/// Part of a pose: a position alone (`--position` without `--rpy`) on a planar two-joint arm,
/// which cannot orient its tool at will, and a position with the tool's z axis (`--axis`) on
/// the Panda and, with the most manipulable solution, on the SCARA; each checked by the
/// robot's forward kinematics.
#[test]
fn ik_solves_part_of_a_pose() {
    let planar = Robot::from_toml_file(root().join("robots/planar_elbow.toml")).unwrap();
    let run = |args: &[&str]| -> serde_json::Value {
        serde_json::from_str(&stdout(args)).expect("valid JSON")
    };
    let v = run(&[
        "ik",
        "robots/planar_elbow.toml",
        "--position",
        "1,0.5,0",
        "--json",
    ]);
    assert_eq!(v["task"], "position");
    assert!(v["closed_form"]["unavailable"].is_string());
    let p = planar.fk(&ik_q(&v["numeric"])).translation.vector;
    assert!(
        (p - dhgen::nalgebra::Vector3::new(1.0, 0.5, 0.0)).norm() < 1e-10,
        "{p}"
    );
    assert_eq!(v["numeric"]["orientation_error"], 0.0);
    for (file, position, axis, extra) in [
        ("panda", [0.5, 0.1, 0.3], [0.0, 0.6, -0.8], None),
        (
            "scara",
            [0.3, 0.2, 0.25],
            [0.0, 0.0, -1.0],
            Some("--most-manipulable"),
        ),
    ] {
        let robot = Robot::from_toml_file(root().join(format!("robots/{file}.toml"))).unwrap();
        let list = |v: [f64; 3]| v.map(|x| x.to_string()).join(",");
        let (position_list, axis_list) = (list(position), list(axis));
        let mut args = vec![
            "ik".to_string(),
            format!("robots/{file}.toml"),
            "--position".into(),
            position_list,
            "--axis".into(),
            axis_list,
            "--json".into(),
        ];
        args.extend(extra.map(String::from));
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        let v = run(&args);
        assert_eq!(v["task"], "position and axis");
        let mut solutions = vec![ik_q(&v["numeric"])];
        if extra.is_some() {
            solutions.push(ik_q(&v["preferred"]));
        }
        for q in solutions {
            let pose = robot.fk(&q);
            let p = pose.translation.vector - dhgen::nalgebra::Vector3::from(position);
            let z = pose.rotation * dhgen::nalgebra::Vector3::new(0.0, 0.0, 1.0);
            let a = dhgen::nalgebra::Vector3::from(axis);
            assert!(
                p.norm() < 1e-10 && (z - a).norm() < 1e-10,
                "{file}: {p} {z}"
            );
        }
    }
    let text = stdout(&[
        "ik",
        "robots/scara.toml",
        "--position",
        "0.3,0.2,0.25",
        "--axis",
        "0,0,-1",
    ]);
    assert!(text.contains("z axis along (0, 0, -1)"), "{text}");
}

/// `--mask`: the SCARA placed over a point above its reach, and the Panda at the pose of
/// `--at` up to a turn about the vertical, checked with the robots' forward kinematics; bad
/// masks are refused with the reason.
#[test]
fn ik_solves_a_mask() {
    let run = |args: &[&str]| -> serde_json::Value {
        serde_json::from_str(&stdout(args)).expect("valid JSON")
    };
    let scara = Robot::from_toml_file(root().join("robots/scara.toml")).unwrap();
    let args = [
        "ik",
        "robots/scara.toml",
        "--position",
        "0.3,0.2,3",
        "--mask",
        "1,1,0,0,0,0",
    ];
    let v = run(&[&args[..], &["--json"]].concat());
    assert_eq!(v["task"], "mask");
    assert_eq!(v["mask"], serde_json::json!([1, 1, 0, 0, 0, 0]));
    assert!(v["closed_form"]["unavailable"].is_string());
    let p = scara.fk(&ik_q(&v["numeric"])).translation.vector;
    assert!(
        (p.x - 0.3).abs() < 1e-10 && (p.y - 0.2).abs() < 1e-10,
        "{p}"
    );
    assert!(stdout(&args).contains("any orientation, counting x, y"));

    let panda = Robot::from_toml_file(root().join("robots/panda.toml")).unwrap();
    let at = [0.1, -0.3, 0.2, -1.8, 0.1, 1.6, 0.5];
    let target = panda.fk(&at);
    let v = run(&[
        "ik",
        "robots/panda.toml",
        "--at",
        "0.1,-0.3,0.2,-1.8,0.1,1.6,0.5",
        "--mask",
        "1,1,1,1,1,0",
        "--seed",
        "0.6,0,0,-1.5,0,1.5,0",
        "--json",
    ]);
    let pose = panda.fk(&ik_q(&v["numeric"]));
    let dp = (pose.translation.vector - target.translation.vector).norm();
    // The turn still to make is about the vertical: it leaves the vertical where it is.
    let up = dhgen::nalgebra::Vector3::z();
    let left = target.rotation * pose.rotation.inverse();
    assert!(dp < 1e-10 && (left * up - up).norm() < 1e-10, "{dp:e}");
    assert!(
        left.angle() > 1e-3,
        "the seed's turn about the vertical is kept"
    );

    for (mask, rpy, why) in [
        (
            "1,1,1",
            true,
            "--mask takes 6 values (X,Y,Z,RX,RY,RZ), not 3",
        ),
        ("1,1,2,1,1,0", true, "--mask, entry 3: 1 or 0, not \"2\""),
        (
            "1,1,1,1,0,0",
            true,
            "--mask counts none, two or all three of RX,RY,RZ",
        ),
        (
            "1,1,1,1,1,0",
            false,
            "give the orientation with --rpy or --at",
        ),
    ] {
        let mut args = vec![
            "ik",
            "robots/panda.toml",
            "--position",
            "0.4,0.1,0.5",
            "--mask",
            mask,
        ];
        if rpy {
            args.extend(["--rpy", "0,0,0"]);
        }
        let err = failure(&args);
        assert!(err.contains(why), "{mask}: {err}");
    }
    let err = failure(&[
        "ik",
        "robots/panda.toml",
        "--position",
        "0.4,0.1,0.5",
        "--axis",
        "0,0,1",
        "--mask",
        "1,1,1,0,0,0",
    ]);
    assert!(err.contains("cannot be used with"), "{err}");
}

#[test]
fn ik_reports_what_it_cannot_do() {
    let err = failure(&[
        "ik",
        "robots/puma560.toml",
        "--position",
        "5,0,0",
        "--rpy",
        "0,0,0",
    ]);
    assert!(
        err.contains("no solution for this pose") && err.contains("out of reach"),
        "{err}"
    );
    // A position alone: no closed form, and the numeric solver says where it stopped.
    let err = failure(&["ik", "robots/puma560.toml", "--position", "5,0,0"]);
    assert!(
        err.contains("no solution for this pose")
            && err.contains("it needs the whole pose: give --rpy")
            && err.contains("numeric IK stalled"),
        "{err}"
    );
    let err = failure(&[
        "ik",
        "robots/panda.toml",
        "--position",
        "0.5,0,0.3",
        "--axis",
        "0,0,0",
    ]);
    assert!(err.contains("--axis must be a non-zero direction"), "{err}");
    let err = failure(&[
        "ik",
        "robots/panda.toml",
        "--position",
        "0.5,0,0.3",
        "--axis",
        "0,0,1",
        "--rpy",
        "0,0,0",
    ]);
    assert!(err.contains("cannot be used with"), "{err}");
    let err = failure(&[
        "ik",
        "robots/puma560.toml",
        "--position",
        "0.5,0",
        "--rpy",
        "0,0,0",
    ]);
    assert!(err.contains("--position takes 3 values, not 2"), "{err}");
    let err = failure(&[
        "ik",
        "robots/puma560.toml",
        "--position",
        "0.5,0,0.3",
        "--rpy",
        "0,x,0",
    ]);
    assert!(err.contains("--rpy, entry 2: cannot read \"x\""), "{err}");
    let err = failure(&[
        "ik",
        "robots/panda.toml",
        "--at",
        "0,0,0,-1.5,0,1.5,0",
        "--nearest",
        "0,0",
    ]);
    assert!(
        err.contains("--nearest has 2 values, but panda has 7 joints"),
        "{err}"
    );
    let err = failure(&[
        "ik",
        "robots/puma560.toml",
        "--at",
        "0,0,0,0,0,0",
        "--position",
        "0,0,0",
    ]);
    assert!(err.contains("cannot be used with"), "{err}");
    let err = failure(&["ik", "robots/puma560.toml"]);
    assert!(err.contains("--position"), "{err}");
}
