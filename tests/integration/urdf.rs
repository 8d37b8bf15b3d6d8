//! URDF robots against Pinocchio 4.1.0 loading the same files (tests/data/urdf_*.json, made
//! by scripts/pinocchio_urdf.py): T, J, D, C, g, τ, forward dynamics and the kinetic and
//! potential energy at 20 random states per robot, on the runtime path here and on the
//! generated path in [`generated`].
//!
//! Pinocchio's τ has no joint friction; where a URDF gives `<dynamics damping friction>`,
//! dhgen's τ includes it, and the comparison takes it out.

use dhgen::Robot;
use dhgen::model::urdf::{UrdfOptions, read_file};
use nalgebra::DMatrix;
use serde_json::Value;
use std::collections::BTreeMap;

pub(crate) fn data(name: &str) -> Value {
    let path = format!("{}/tests/data/urdf_{name}.json", env!("CARGO_MANIFEST_DIR"));
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

pub(crate) fn vector(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// A list of rows, or a vector as one column.
pub(crate) fn matrix(v: &Value) -> DMatrix<f64> {
    if v[0].is_number() {
        return DMatrix::from_column_slice(v.as_array().unwrap().len(), 1, &vector(v));
    }
    let rows: Vec<Vec<f64>> = v.as_array().unwrap().iter().map(vector).collect();
    DMatrix::from_fn(rows.len(), rows[0].len(), |i, j| rows[i][j])
}

/// The robot the reference describes: its file, tip and base.
pub(crate) fn robot(name: &str, snap: f64) -> Robot {
    let d = data(name);
    let path = format!(
        "{}/tests/data/urdf/{}",
        env!("CARGO_MANIFEST_DIR"),
        d["urdf"].as_str().unwrap()
    );
    let options = UrdfOptions {
        tip: d["tip"].as_str().map(str::to_string),
        base: d["base"].as_str().map(str::to_string),
        snap,
    };
    let r = read_file(&path, &options).unwrap();
    let names: Vec<&str> = r.joints.iter().map(|j| j.name.as_str()).collect();
    let want: Vec<&str> = d["joint_names"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_str().unwrap())
        .collect();
    assert_eq!(names, want, "{name}: the chain's joints");
    let locked: Vec<&str> = d["locked_joints"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_str().unwrap())
        .collect();
    let mut locked = locked;
    locked.sort_unstable();
    assert_eq!(r.locked, locked, "{name}: the joints held at zero");
    Robot::from_model(r.model)
}

/// Worst error relative to max(1, |reference|), per quantity.
#[derive(Default)]
pub(crate) struct Worst(pub BTreeMap<&'static str, f64>);

impl Worst {
    pub(crate) fn check(&mut self, what: &'static str, got: f64, want: f64) {
        let err = (got - want).abs() / want.abs().max(1.0);
        assert!(
            err <= 1e-9,
            "{what}: got {got}, want {want}, relative error {err:e}"
        );
        let w = self.0.entry(what).or_default();
        *w = w.max(err);
    }

    pub(crate) fn matrix(&mut self, what: &'static str, got: &DMatrix<f64>, want: &Value) {
        let want = matrix(want);
        assert_eq!(got.shape(), want.shape(), "{what}");
        for (g, w) in got.iter().zip(want.iter()) {
            self.check(what, *g, *w);
        }
    }
}

/// The kinetic and potential energy against Pinocchio's `computeKineticEnergy` and
/// `computePotentialEnergy` (`K`, `V`).
pub(crate) fn energies_match(worst: &mut Worst, [kinetic, potential]: [f64; 2], s: &Value) {
    worst.check("K", kinetic, s["K"].as_f64().unwrap());
    worst.check("V", potential, s["V"].as_f64().unwrap());
}

/// The centre of mass and its Jacobian against Pinocchio's `centerOfMass` and
/// `jacobianCenterOfMass` (`com`, `Jcom`).
pub(crate) fn centre_matches(
    worst: &mut Worst,
    (centre, jacobian): (&[f64], &DMatrix<f64>),
    s: &Value,
) {
    for (got, want) in centre.iter().zip(vector(&s["com"])) {
        worst.check("com", *got, want);
    }
    worst.matrix("Jcom", jacobian, &s["Jcom"]);
}

/// The friction torque dhgen adds to τ (viscous·q̇ + Coulomb·sign q̇).
pub(crate) fn friction(robot: &Robot, qd: &[f64]) -> Vec<f64> {
    robot
        .chain()
        .bodies
        .iter()
        .zip(qd)
        .map(|(b, v)| b.friction.viscous * v + b.friction.coulomb * v.signum())
        .collect()
}

/// Forward dynamics against the reference. With the file's decimals as written (`snap` 0),
/// q̈ itself agrees. Snapped, dhgen's robot differs from Pinocchio's by the snapped amount
/// (UR5, Kinova: 4.9e-12 rad), which D⁻¹ amplifies by its condition number (Kinova's
/// reaches 1e5 with its light wrist): then the check is the backward error, that dhgen's q̈
/// satisfies Pinocchio's equation of motion, `D q̈ + C q̇ + g = τ`, to the same 1e-9.
pub(crate) fn qdd_matches(worst: &mut Worst, snap: f64, acc: &[f64], s: &Value) {
    if snap == 0.0 {
        let n = acc.len();
        worst.matrix("qdd", &DMatrix::from_column_slice(n, 1, acc), &s["qdd"]);
        return;
    }
    let d = matrix(&s["D"]);
    let h: Vec<f64> = vector(&s["Cqd"])
        .iter()
        .zip(vector(&s["g"]))
        .map(|(c, g)| c + g)
        .collect();
    let lhs = &d * nalgebra::DVector::from_column_slice(acc);
    for ((l, h), t) in lhs.iter().zip(&h).zip(vector(&s["tau"])) {
        worst.check("D qdd + h (snapped)", l + h, t);
    }
}

fn check_runtime(name: &str, snap: f64) {
    let robot = robot(name, snap);
    let d = data(name);
    let n = robot.dof();
    let mut worst = Worst::default();
    for s in d["samples"].as_array().unwrap() {
        let (q, qd, qdd) = (vector(&s["q"]), vector(&s["qd"]), vector(&s["qdd"]));
        let t = robot.fk(&q[..]).to_homogeneous();
        worst.matrix("T", &DMatrix::from_fn(4, 4, |i, j| t[(i, j)]), &s["T"]);
        let j = robot.jacobian(&q[..]);
        worst.matrix("J", &DMatrix::from_fn(6, n, |r, c| j[(r, c)]), &s["J0"]);
        worst.matrix("D", &robot.mass_matrix(&q[..]), &s["D"]);
        worst.matrix("C", &robot.coriolis(&q[..], &qd[..]), &s["C"]);
        let g = robot.gravity(&q[..]);
        worst.matrix(
            "g",
            &DMatrix::from_column_slice(n, 1, g.as_slice()),
            &s["g"],
        );
        let f = friction(&robot, &qd);
        let tau = robot.inverse_dynamics(&q[..], &qd[..], &qdd[..]);
        let tau: Vec<f64> = tau.iter().zip(&f).map(|(t, f)| t - f).collect();
        worst.matrix("tau", &DMatrix::from_column_slice(n, 1, &tau), &s["tau"]);
        let applied: Vec<f64> = vector(&s["tau"])
            .iter()
            .zip(&f)
            .map(|(t, f)| t + f)
            .collect();
        let acc = robot
            .forward_dynamics(&q[..], &qd[..], &applied[..])
            .expect("D is positive definite");
        qdd_matches(&mut worst, snap, acc.as_slice(), s);
        let energies = [
            robot.kinetic_energy(&q[..], &qd[..]),
            robot.potential_energy(&q[..]),
        ];
        energies_match(&mut worst, energies, s);
        let jc = robot.center_of_mass_jacobian(&q[..]);
        let jc = DMatrix::from_fn(3, n, |r, c| jc[(r, c)]);
        let centre = robot.center_of_mass(&q[..]).1;
        centre_matches(&mut worst, (centre.coords.as_slice(), &jc), s);
    }
    for (k, w) in &worst.0 {
        println!("{name} runtime (snap {snap:e}) {k}: worst relative error {w:.2e}");
    }
}

#[test]
fn panda_runtime_matches_pinocchio() {
    check_runtime("panda", UrdfOptions::DEFAULT_SNAP);
    check_runtime("panda", 0.0);
}

#[test]
fn ur5_runtime_matches_pinocchio() {
    check_runtime("ur5", UrdfOptions::DEFAULT_SNAP);
    check_runtime("ur5", 0.0);
}

#[test]
fn baxter_left_arm_runtime_matches_pinocchio() {
    check_runtime("baxter", UrdfOptions::DEFAULT_SNAP);
    check_runtime("baxter", 0.0);
}

#[test]
fn kinova_runtime_matches_pinocchio() {
    check_runtime("kinova", UrdfOptions::DEFAULT_SNAP);
    check_runtime("kinova", 0.0);
}

/// Random chains written by scripts/pinocchio_urdf.py --random: negative and oblique
/// (unnormalised) axes, prismatic and continuous joints, fixed joints with and without mass in
/// the middle of the chain, movable branches held at zero, exact ±π/2 pitches (the RPY gimbal
/// case), shuffled element order, 4 to 12 joints.
#[test]
fn random_urdf_chains_runtime_match_pinocchio() {
    for k in 1..=4 {
        let name = format!("random_{k}");
        check_runtime(&name, UrdfOptions::DEFAULT_SNAP);
        check_runtime(&name, 0.0);
    }
}

#[test]
fn double_pendulum_runtime_matches_pinocchio() {
    check_runtime("double_pendulum", UrdfOptions::DEFAULT_SNAP);
    check_runtime("double_pendulum", 0.0);
}

/// TIAGo's arm (a prismatic torso and seven revolute joints, from a tree with wheels, a head
/// and a hand), whose fixed base carries a 1 mg antenna with a tensor that is not positive
/// semi-definite: no moving body carries it, so the arm loads, as in Pinocchio.
#[test]
fn tiago_arm_runtime_matches_pinocchio() {
    check_runtime("tiago", UrdfOptions::DEFAULT_SNAP);
    check_runtime("tiago", 0.0);
}

/// Four more files from the wild (10 samples each): the xArm 7 (its quarter turns written
/// `1.5708`, 3.7e-6 rad short, read as written), a humanoid's left arm from the pelvis (Unitree
/// G1: three waist joints and seven arm joints, shoulders tilted by 0.279 rad, the legs and
/// the other arm locked), one arm of a wheeled quadruped (Centauro: a torso yaw and six arm
/// joints, mounted at 10° and −30°, legs, wheels, head and the other arm locked) and a
/// five-joint arm under a hexacopter, mounted at roll and pitch `1.5708` (next to the RPY
/// gimbal case).
#[test]
fn robots_from_the_wild_runtime_match_pinocchio() {
    for name in ["xarm7", "g1", "centauro", "hextilt"] {
        check_runtime(name, UrdfOptions::DEFAULT_SNAP);
        check_runtime(name, 0.0);
    }
}

/// A chain that starts below the root (`base`) is the same robot as the whole chain with the
/// joints above it held at 0 and at rest: the same τ, g, D and C for its joints, gravity staying
/// URDF's [0, 0, −9.81] in the root link's frame although the base link is turned against it
/// (the Panda's third link: a quarter turn about x).
#[test]
fn a_chain_from_a_base_below_the_root_is_the_whole_chain_held_above_it() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/urdf/panda.urdf");
    let options = |base: Option<&str>| UrdfOptions {
        tip: Some("panda_hand".into()),
        base: base.map(str::to_string),
        ..Default::default()
    };
    let whole = Robot::from_model(read_file(path, &options(None)).unwrap().model);
    let sub = read_file(path, &options(Some("panda_link2"))).unwrap();
    assert_ne!(
        sub.model.gravity,
        [0.0, 0.0, -9.81],
        "the base link is turned"
    );
    let sub = Robot::from_model(sub.model);
    let (n, m) = (7, 5);
    let mut worst: f64 = 0.0;
    for k in 0..10 {
        let x = |i: usize, s: f64| ((i * 7 + k * 13) as f64 * s).sin();
        let q: Vec<f64> = (0..m).map(|i| x(i, 0.37)).collect();
        let qd: Vec<f64> = (0..m).map(|i| x(i, 0.91)).collect();
        let qdd: Vec<f64> = (0..m).map(|i| x(i, 1.73)).collect();
        let held = |v: &[f64]| [vec![0.0; n - m], v.to_vec()].concat();
        let (wq, wqd, wqdd) = (held(&q), held(&qd), held(&qdd));
        let rows = |v: nalgebra::DVector<f64>| v.rows(n - m, m).into_owned();
        let block = |a: DMatrix<f64>| a.view((n - m, n - m), (m, m)).into_owned();
        let pairs = [
            (
                sub.inverse_dynamics(&q[..], &qd[..], &qdd[..]),
                rows(whole.inverse_dynamics(&wq[..], &wqd[..], &wqdd[..])),
            ),
            (sub.gravity(&q[..]), rows(whole.gravity(&wq[..]))),
        ];
        for (a, b) in pairs {
            worst = worst.max((a - b).amax());
        }
        worst = worst.max((sub.mass_matrix(&q[..]) - block(whole.mass_matrix(&wq[..]))).amax());
        worst = worst
            .max((sub.coriolis(&q[..], &qd[..]) - block(whole.coriolis(&wq[..], &wqd[..]))).amax());
    }
    assert!(worst < 1e-12, "{worst:e}");
}

/// A human model's arm from the root to the left hand: 13 joints, its spherical joints
/// written as three revolute ones through virtual links with no `<inertial>`, read as massless
/// (as Pinocchio reads them) and listed.
#[test]
fn human_arm_with_massless_virtual_links_matches_pinocchio() {
    check_runtime("human", UrdfOptions::DEFAULT_SNAP);
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/urdf/human.urdf");
    let options = UrdfOptions {
        tip: Some("left_hand".into()),
        ..Default::default()
    };
    let urdf = read_file(path, &options).unwrap();
    assert_eq!(
        urdf.massless,
        [
            "middle_abdomen_virtual",
            "middle_thorax_virtual",
            "middle_thorax_virtual_2",
            "left_upperarm_virtual",
            "left_upperarm_virtual_2",
            "left_lowerarm_virtual",
            "left_hand_virtual",
        ]
    );
}

/// Where an unphysical `<inertial>` matters: on a link the base carries it is ignored, on a
/// link a joint moves it is an error at its `<inertia>`; round-off below a micrometre's moment
/// of the link's mass (`ixx="-5.42101e-20"`, as exporters write zeros) is not unphysical.
#[test]
fn unphysical_inertials_are_errors_only_where_a_joint_moves_them() {
    let urdf = |base_tensor: &str, arm_tensor: &str| {
        format!(
            r#"<robot name="r">
  <link name="base"><inertial><mass value="1e-6"/><inertia {base_tensor}/></inertial></link>
  <link name="arm"><inertial><mass value="0.526"/><inertia {arm_tensor}/></inertial></link>
  <joint name="j" type="revolute"><parent link="base"/><child link="arm"/>
    <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
</robot>"#
        )
    };
    let good = r#"ixx="0.01" iyy="0.01" izz="0.01" ixy="0" iyz="0" ixz="0""#;
    let bad = r#"ixx="2.371e-8" iyy="2.833e-8" izz="3.849e-8" ixy="6.119e-8" iyz="0" ixz="0""#;
    let round_off = r#"ixx="-5.42101e-20" iyy="-5.42101e-20" izz="0" ixy="0" iyz="0" ixz="0""#;
    let read = |text: String| {
        dhgen::model::urdf::read(&text, "r.urdf", &UrdfOptions::default()).map(|u| u.model)
    };
    assert!(read(urdf(bad, good)).is_ok(), "the base's antenna");
    let e = read(urdf(good, bad)).unwrap_err().to_string();
    assert!(
        e.starts_with("r.urdf:3:") && e.contains("link `arm`") && e.contains("semi-definite"),
        "{e}"
    );
    let model = read(urdf(good, round_off)).expect("round-off is no error");
    assert_eq!(model.links[0].inertial.as_ref().unwrap().mass, 0.526);
}

/// The generated modules of the same files (`robot!(pub mod m = "x.urdf", tip = "...")`),
/// against the same references, and against the runtime path.
mod generated {
    use super::{
        Worst, centre_matches, data, energies_match, friction, qdd_matches, robot, vector,
    };
    use crate::catalogue::{
        baxter_left, centauro_arm, double_pendulum_urdf, g1_arm, hextilt_arm, human_arm,
        kinova_urdf, panda_urdf, random_urdf_2, random_urdf_3, tiago_arm, ur5_urdf, xarm7_urdf,
    };
    use dhgen::model::urdf::UrdfOptions;
    use nalgebra::DMatrix;

    macro_rules! check {
        ($test:ident, $m:ident, $name:literal) => {
            #[test]
            fn $test() {
                use $m as r;
                const N: usize = r::DOF;
                let d = data($name);
                let runtime = robot($name, UrdfOptions::DEFAULT_SNAP);
                let mut worst = Worst::default();
                for s in d["samples"].as_array().unwrap() {
                    let q: [f64; N] = vector(&s["q"]).try_into().unwrap();
                    let qd: [f64; N] = vector(&s["qd"]).try_into().unwrap();
                    let qdd: [f64; N] = vector(&s["qdd"]).try_into().unwrap();
                    let st = r::State::new(&q);
                    let t = st.fk().to_homogeneous();
                    worst.matrix("T", &DMatrix::from_fn(4, 4, |i, j| t[(i, j)]), &s["T"]);
                    let j = st.jacobian();
                    worst.matrix("J", &DMatrix::from_fn(6, N, |a, b| j[(a, b)]), &s["J0"]);
                    let dm = st.mass_matrix();
                    worst.matrix("D", &DMatrix::from_fn(N, N, |a, b| dm[(a, b)]), &s["D"]);
                    let c = st.coriolis(&qd);
                    worst.matrix("C", &DMatrix::from_fn(N, N, |a, b| c[(a, b)]), &s["C"]);
                    let g = st.gravity();
                    worst.matrix("g", &DMatrix::from_fn(N, 1, |a, _| g[a]), &s["g"]);
                    let f = friction(&runtime, &qd);
                    let tau = st.inverse_dynamics(&qd, &qdd);
                    worst.matrix(
                        "tau",
                        &DMatrix::from_fn(N, 1, |a, _| tau[a] - f[a]),
                        &s["tau"],
                    );
                    let applied: [f64; N] =
                        core::array::from_fn(|a| s["tau"][a].as_f64().unwrap() + f[a]);
                    let acc = st
                        .forward_dynamics(&qd, &applied)
                        .expect("D is positive definite");
                    qdd_matches(&mut worst, UrdfOptions::DEFAULT_SNAP, acc.as_slice(), s);
                    energies_match(
                        &mut worst,
                        [st.kinetic_energy(&qd), st.potential_energy()],
                        s,
                    );
                    let qv = nalgebra::SVector::<f64, N>::from(q);
                    let jc = dhgen::ArmDynamics::center_of_mass_jacobian(&r::Robot, &qv);
                    let jc = DMatrix::from_fn(3, N, |a, b| jc[(a, b)]);
                    let (_, centre) = dhgen::ArmDynamics::center_of_mass(&r::Robot, &qv);
                    centre_matches(&mut worst, (centre.coords.as_slice(), &jc), s);
                    // The two paths of dhgen agree more closely still.
                    let rt = runtime.inverse_dynamics(&q[..], &qd[..], &qdd[..]);
                    for a in 0..N {
                        let err = (rt[a] - tau[a]).abs() / rt[a].abs().max(1.0);
                        assert!(err < 1e-12, "{}: tau[{a}] {} vs {}", $name, rt[a], tau[a]);
                    }
                }
                for (k, w) in &worst.0 {
                    println!("{} generated {k}: worst relative error {w:.2e}", $name);
                }
            }
        };
    }

    check!(panda_generated_matches_pinocchio, panda_urdf, "panda");
    check!(ur5_generated_matches_pinocchio, ur5_urdf, "ur5");
    check!(
        baxter_left_arm_generated_matches_pinocchio,
        baxter_left,
        "baxter"
    );
    check!(kinova_generated_matches_pinocchio, kinova_urdf, "kinova");
    check!(
        double_pendulum_generated_matches_pinocchio,
        double_pendulum_urdf,
        "double_pendulum"
    );
    check!(
        random_2_generated_matches_pinocchio,
        random_urdf_2,
        "random_2"
    );
    check!(
        random_3_generated_matches_pinocchio,
        random_urdf_3,
        "random_3"
    );
    check!(tiago_arm_generated_matches_pinocchio, tiago_arm, "tiago");
    check!(human_arm_generated_matches_pinocchio, human_arm, "human");
    check!(xarm7_generated_matches_pinocchio, xarm7_urdf, "xarm7");
    check!(g1_arm_generated_matches_pinocchio, g1_arm, "g1");
    check!(
        centauro_arm_generated_matches_pinocchio,
        centauro_arm,
        "centauro"
    );
    check!(
        hextilt_arm_generated_matches_pinocchio,
        hextilt_arm,
        "hextilt"
    );

    /// A joint whose offset is a quarter turn (the UR5's shoulder lift and wrist 1, from the
    /// turns of their URDF origins about the joint axis; the Kinova's joints 1 and 3) gets
    /// the sine and cosine of q turned exactly, not those of the rounded q + offset: at q = 0
    /// each is exactly 0 or ±1, and everywhere a generated `State` holds ±sin q and ±cos q.
    #[test]
    fn quarter_turn_offsets_turn_the_sine_and_cosine_exactly() {
        use dhgen::Real;
        macro_rules! exact {
            ($m:ident, $turned:expr) => {{
                use $m as r;
                let home = r::State::new(&[0.0f64; r::DOF]);
                for x in home.c.iter().chain(&home.s) {
                    assert!(*x == 0.0 || x.abs() == 1.0, "{}: {x}", stringify!($m));
                }
                let q: [f64; r::DOF] = core::array::from_fn(|j| 0.37 + 0.81 * j as f64);
                let st = r::State::new(&q);
                let (s, c) = f64::sincos_array(q);
                let mut turned = 0;
                for j in 0..r::DOF {
                    let got = (st.s[j].to_bits(), st.c[j].to_bits());
                    let turns = [(s[j], c[j]), (c[j], -s[j]), (-s[j], -c[j]), (-c[j], s[j])];
                    let k = turns
                        .iter()
                        .position(|&(a, b)| (a.to_bits(), b.to_bits()) == got)
                        .unwrap_or_else(|| panic!("{} joint {j}", stringify!($m)));
                    turned += usize::from(k != 0);
                }
                assert_eq!(turned, $turned, "{}", stringify!($m));
            }};
        }
        exact!(ur5_urdf, 2);
        exact!(kinova_urdf, 2);
    }
}

/// The URDF robots converted to DH tables (`dhgen convert --to dh|mdh`: base and tool poses,
/// inertias re-expressed in the DH frames) are still Pinocchio's robots.
#[test]
fn urdf_robots_converted_to_dh_match_pinocchio() {
    use dhgen::Convention;
    use dhgen::model::convert::to_dh;
    let names = [
        "panda",
        "ur5",
        "baxter",
        "kinova",
        "double_pendulum",
        "random_1",
        "random_2",
        "random_3",
        "random_4",
    ];
    for name in names {
        let urdf = robot(name, UrdfOptions::DEFAULT_SNAP);
        let d = data(name);
        for convention in [Convention::Standard, Convention::Modified] {
            let dh = Robot::from_model(to_dh(urdf.model(), convention).unwrap());
            let n = dh.dof();
            let mut worst = Worst::default();
            for s in d["samples"].as_array().unwrap() {
                let (q, qd, qdd) = (vector(&s["q"]), vector(&s["qd"]), vector(&s["qdd"]));
                let t = dh.fk(&q[..]).to_homogeneous();
                worst.matrix("T", &DMatrix::from_fn(4, 4, |i, j| t[(i, j)]), &s["T"]);
                let j = dh.jacobian(&q[..]);
                worst.matrix("J", &DMatrix::from_fn(6, n, |r, c| j[(r, c)]), &s["J0"]);
                worst.matrix("D", &dh.mass_matrix(&q[..]), &s["D"]);
                let g = dh.gravity(&q[..]);
                worst.matrix(
                    "g",
                    &DMatrix::from_column_slice(n, 1, g.as_slice()),
                    &s["g"],
                );
                let f = friction(&dh, &qd);
                let tau = dh.inverse_dynamics(&q[..], &qd[..], &qdd[..]);
                let tau: Vec<f64> = tau.iter().zip(&f).map(|(t, f)| t - f).collect();
                worst.matrix("tau", &DMatrix::from_column_slice(n, 1, &tau), &s["tau"]);
                let energies = [
                    dh.kinetic_energy(&q[..], &qd[..]),
                    dh.potential_energy(&q[..]),
                ];
                energies_match(&mut worst, energies, s);
            }
            for (k, w) in &worst.0 {
                println!("{name} as {convention:?} DH {k}: worst relative error {w:.2e}");
            }
        }
    }
}
