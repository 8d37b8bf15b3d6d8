//! Repeatable cost of one call, for profiling on a noisy machine: runs 1,000 calls of one
//! quantity, generated or runtime, so that `valgrind --tool=callgrind` counts instructions
//! (the same count run after run, whatever else the machine does).
//!
//! ```sh
//! cargo build --release --example instructions
//! B=target/release/examples/instructions
//! for args in "none generated" "mass_matrix generated" "mass_matrix runtime"; do
//!   valgrind --tool=callgrind --callgrind-out-file=/dev/null $B puma560 $args 2>&1 | grep Collected
//! done
//! ```
//! Instructions per call = (count − count of the quantity `none`) / 1000. Read large counts
//! with `callgrind_annotate`: glibc's `memset` zeroes some arrays of a few KB (a split
//! function's scratch array, a regressor's output) with `rep stosb`: one instruction, which
//! valgrind counts once per byte it stores. `batch` evaluates the same 1,000
//! configurations through the module's `batch` functions (SIMD packs of four `f64`): its
//! count per configuration is the same formula. `packs` calls the generated functions on the
//! packs themselves (what `batch` does before unpacking each lane's value). `f32` and
//! `packs_f32` run the same configurations in `f32`, one at a time and as packs of eight
//! (`WideF32x8`), for a few quantities.

use std::hint::black_box;

dhgen::robot!(mod puma560 = "robots/puma560.toml", regressor, derivatives);
dhgen::robot!(mod panda = "robots/panda.toml", regressor, derivatives);
// Seeded random general arms (benches/arms/, `dhgen random --style general --seed 1`): the
// sizes where the generated code has the least structure to exploit.
dhgen::robot!(mod general_8 = "benches/arms/general_8.toml", regressor, derivatives);
dhgen::robot!(mod general_12 = "benches/arms/general_12.toml", regressor, derivatives);

const CALLS: usize = 1000;

fn inputs<const N: usize>(shift: usize) -> Vec<[f64; N]> {
    (0..CALLS)
        .map(|i| core::array::from_fn(|j| (((i + shift) * 7 + j * 13) as f64 * 0.37).sin() * 2.0))
        .collect()
}

/// dhgen's branch-free sine and cosine (what `f64` packs use), not inlined: its code on its
/// own, for reading (`objdump -d`).
#[inline(never)]
fn probe_sincos(x: f64) -> (f64, f64) {
    dhgen::sincos::sincos(x)
}

/// Fills CALLS outputs by one batch call and sums one entry of each.
fn through<O: Clone + Default>(
    fill: impl FnOnce(&mut [O]) -> Result<(), dhgen::batch::LengthMismatch>,
    pick: impl Fn(&O) -> f64,
) -> f64 {
    let mut out = vec![O::default(); CALLS];
    fill(&mut out).expect("equal lengths");
    out.iter().map(pick).sum()
}

macro_rules! run {
    ($m:ident, $dir:literal, $quantity:expr, $path:expr) => {{
        const N: usize = $m::DOF;
        let file = format!(
            "{}/{}/{}.toml",
            env!("CARGO_MANIFEST_DIR"),
            $dir,
            stringify!($m)
        );
        let robot = dhgen::Robot::from_toml_file(file).expect("a checked-in robot");
        // A payload: 1.7 kg, off-centre, a full inertia tensor (benches/parameters.rs's).
        let payload = dhgen::payload::Payload::new(
            1.7,
            [0.03, -0.02, 0.06],
            [
                [0.012, 0.001, -0.002],
                [0.001, 0.010, 0.0015],
                [-0.002, 0.0015, 0.008],
            ],
        )
        .expect("a physical payload");
        let pp = payload.parameters();
        let (qs, qds) = (inputs::<N>(0), inputs::<N>(3));
        let generated = $path == "generated";
        let mut acc = 0.0;
        if $path == "packs" {
            // The same configurations as packs of four, the generated functions called on
            // the packs directly (no unpacking into per-configuration values).
            use dhgen::batch::WideF64x4;
            let pack = |v: &[[f64; N]], i: usize| -> [WideF64x4; N] {
                core::array::from_fn(|j| {
                    WideF64x4([v[i][j], v[i + 1][j], v[i + 2][j], v[i + 3][j]].into())
                })
            };
            for i in (0..CALLS).step_by(4) {
                let (q, qd) = (black_box(pack(&qs, i)), black_box(pack(&qds, i)));
                let lane = |x: WideF64x4| x.0.to_array()[1];
                acc += match $quantity {
                    "none" => 0.0,
                    "fk" => lane($m::fk(&q).translation.x),
                    "jacobian" => lane($m::jacobian(&q)[(0, 1)]),
                    "mass_matrix" => lane($m::mass_matrix(&q)[(1, 1)]),
                    "christoffel" => lane($m::christoffel(&q)[1][2][0]),
                    "coriolis" => lane($m::coriolis(&q, &qd)[(1, 0)]),
                    "gravity" => lane($m::gravity(&q)[1]),
                    "inverse_dynamics" => lane($m::inverse_dynamics(&q, &qd, &qd)[1]),
                    "forward_dynamics" => lane($m::forward_dynamics_lanes(&q, &qd, &qd).0[1]),
                    other => {
                        eprintln!("no pack form of {other}");
                        std::process::exit(2);
                    }
                };
            }
            println!("{acc}");
            return;
        }
        if $path == "f32" || $path == "packs_f32" {
            // The same configurations in `f32`: one at a time, or as packs of eight
            // (`WideF32x8`) with the generated functions called on the packs directly.
            use dhgen::batch::WideF32x8;
            let narrow = |v: &[[f64; N]]| -> Vec<[f32; N]> {
                v.iter().map(|x| x.map(|e| e as f32)).collect()
            };
            let (qs, qds) = (narrow(&qs), narrow(&qds));
            let pack = |v: &[[f32; N]], i: usize| -> [WideF32x8; N] {
                core::array::from_fn(|j| {
                    WideF32x8(core::array::from_fn::<f32, 8, _>(|l| v[i + l][j]).into())
                })
            };
            macro_rules! quantity {
                ($q:expr, $qd:expr, $lane:expr) => {{
                    let (q, qd, lane) = ($q, $qd, $lane);
                    match $quantity {
                        "none" => 0.0,
                        "fk" => lane($m::fk(&q).translation.x),
                        "fk_matrix" => lane($m::fk_matrix(&q)[(0, 3)]),
                        "frames" => lane($m::frames(&q)[2].translation.x),
                        "frames_matrix" => lane($m::frames_matrix(&q)[2][(0, 3)]),
                        "jacobian" => lane($m::jacobian(&q)[(0, 1)]),
                        "mass_matrix" => lane($m::mass_matrix(&q)[(1, 1)]),
                        "gravity" => lane($m::gravity(&q)[1]),
                        "inverse_dynamics" => lane($m::inverse_dynamics(&q, &qd, &qd)[1]),
                        other => {
                            eprintln!("no f32 form of {other}");
                            std::process::exit(2);
                        }
                    }
                }};
            }
            if $path == "f32" {
                for i in 0..CALLS {
                    let (q, qd) = (black_box(qs[i]), black_box(qds[i]));
                    acc += f64::from(quantity!(q, qd, |x: f32| x));
                }
            } else {
                for i in (0..CALLS).step_by(8) {
                    let (q, qd) = (black_box(pack(&qs, i)), black_box(pack(&qds, i)));
                    acc += f64::from(quantity!(q, qd, |x: WideF32x8| x.0.to_array()[1]));
                }
            }
            println!("{acc}");
            return;
        }
        if $path == "batch" {
            // All CALLS configurations through the module's `batch` functions (f64x4 packs).
            let (qs, qds) = (black_box(&qs), black_box(&qds));
            acc += match $quantity {
                "none" => 0.0,
                "fk" => through(|o| $m::batch::fk(qs, o), |x| x.translation.x),
                "jacobian" => through(|o| $m::batch::jacobian(qs, o), |x| x[(0, 1)]),
                "mass_matrix" => through(|o| $m::batch::mass_matrix(qs, o), |x| x[(1, 1)]),
                "christoffel" => through(|o| $m::batch::christoffel(qs, o), |x| x[1][2][0]),
                "coriolis" => through(|o| $m::batch::coriolis(qs, qds, o), |x| x[(1, 0)]),
                "gravity" => through(|o| $m::batch::gravity(qs, o), |x| x[1]),
                "inverse_dynamics" => {
                    through(|o| $m::batch::inverse_dynamics(qs, qds, qds, o), |x| x[1])
                }
                "forward_dynamics" => through(
                    |o| $m::batch::forward_dynamics(qs, qds, qds, o),
                    |x| x.map_or(0.0, |x| x[1]),
                ),
                other => {
                    eprintln!("no batch form of {other}");
                    std::process::exit(2);
                }
            };
            println!("{acc}");
            return;
        }
        for i in 0..CALLS {
            let (q, qd) = (black_box(&qs[i]), black_box(&qds[i]));
            acc += match ($quantity, generated) {
                ("none", _) => 0.0,
                // One sine and cosine: dhgen's branch-free one against `libm`'s.
                ("sincos", true) => probe_sincos(q[0]).0,
                ("sincos", false) => libm::sincos(q[0]).0,
                // Every joint's sine and cosine, as a generated `State` takes them (packs of four
                // where the target has AVX), against one call each of `libm`'s.
                ("sincos_joints", true) => {
                    let (s, _) = <f64 as dhgen::Real>::sincos_array(*q);
                    s.iter().sum()
                }
                ("sincos_joints", false) => q.iter().map(|&x| libm::sincos(x).0).sum(),
                ("fk", true) => $m::fk(q).translation.x,
                ("fk", false) => robot.fk(q).translation.x,
                // The pose as a matrix (no rotation-to-quaternion conversion).
                ("fk_matrix", true) => $m::fk_matrix(q)[(0, 3)],
                ("frames", true) => $m::frames(q)[2].translation.x,
                ("frames_matrix", true) => $m::frames_matrix(q)[2][(0, 3)],
                ("jacobian", true) => $m::jacobian(q)[(0, 1)],
                ("jacobian", false) => robot.jacobian(q)[(0, 1)],
                ("body_jacobian", true) => $m::body_jacobian(q)[(0, 1)],
                ("body_jacobian", false) => {
                    dhgen::Arm::body_jacobian(&robot, &dhgen::nalgebra::DVector::from_row_slice(q))
                        [(0, 1)]
                }
                ("body_jdot_qdot", true) => {
                    let (q, qd) = (dhgen::nalgebra::SVector::from(*q), dhgen::nalgebra::SVector::from(*qd));
                    dhgen::Arm::body_jdot_qdot(&$m::Robot, &q, &qd)[1]
                }
                ("body_jdot_qdot", false) => {
                    let (q, qd) = (
                        dhgen::nalgebra::DVector::from_row_slice(q),
                        dhgen::nalgebra::DVector::from_row_slice(qd),
                    );
                    dhgen::Arm::body_jdot_qdot(&robot, &q, &qd)[1]
                }
                // The trait's default (fk, then J rotated into tool axes) on the generated arm.
                ("body_jacobian_default", true) => {
                    let q = dhgen::nalgebra::SVector::from(*q);
                    dhgen::velocity::body_jacobian_from_jacobian(
                        &dhgen::Arm::fk(&$m::Robot, &q),
                        dhgen::Arm::jacobian(&$m::Robot, &q),
                    )[(0, 1)]
                }
                // The kinematic Hessian (every ∂J/∂q_k) and the manipulability gradient, from
                // the generated J or the runtime's.
                ("kinematic_hessian", true) => {
                    let j = $m::jacobian(q);
                    dhgen::velocity::kinematic_hessian(&j).map(|h| h[(0, 1)]).sum()
                }
                ("kinematic_hessian", false) => {
                    let j = robot.jacobian(q);
                    dhgen::velocity::kinematic_hessian(&j).map(|h| h[(0, 1)]).sum()
                }
                ("manipulability_gradient", true) => {
                    let j = $m::jacobian(q);
                    dhgen::velocity::manipulability_gradient(&j, dhgen::velocity::Axes::All)
                        .map_or(0.0, |(m, g)| m + g[1])
                }
                ("manipulability_gradient", false) => {
                    let j = robot.jacobian(q);
                    dhgen::velocity::manipulability_gradient(&j, dhgen::velocity::Axes::All)
                        .map_or(0.0, |(m, g)| m + g[1])
                }
                ("center_of_mass", true) => $m::center_of_mass(q).1.x,
                ("center_of_mass", false) => robot.center_of_mass(q).1.x,
                ("center_of_mass_jacobian", true) => $m::center_of_mass_jacobian(q)[(0, 1)],
                ("center_of_mass_jacobian", false) => robot.center_of_mass_jacobian(q)[(0, 1)],
                ("mass_matrix", true) => $m::mass_matrix(q)[(1, 1)],
                ("mass_matrix", false) => robot.mass_matrix(q)[(1, 1)],
                ("christoffel", true) => $m::christoffel(q)[1][2][0],
                ("christoffel", false) => robot.christoffel(q)[1][2][0],
                ("coriolis", true) => $m::coriolis(q, qd)[(1, 0)],
                ("coriolis", false) => robot.coriolis(q, qd)[(1, 0)],
                ("gravity", true) => $m::gravity(q)[1],
                ("gravity", false) => robot.gravity(q)[1],
                ("inverse_dynamics", true) => $m::inverse_dynamics(q, qd, qd)[1],
                ("inverse_dynamics", false) => robot.inverse_dynamics(q, qd, qd)[1],
                ("forward_dynamics", true) => $m::forward_dynamics(q, qd, qd).map_or(0.0, |x| x[1]),
                ("forward_dynamics", false) => {
                    robot.forward_dynamics(q, qd, qd).map_or(0.0, |x| x[1])
                }
                ("inverse_dynamics_with_payload", true) => {
                    $m::inverse_dynamics_with_payload(q, qd, qd, &pp)[1]
                }
                ("inverse_dynamics_with_payload", false) => {
                    let (q, qd) = (
                        dhgen::nalgebra::DVector::from_row_slice(q),
                        dhgen::nalgebra::DVector::from_row_slice(qd),
                    );
                    dhgen::payload::inverse_dynamics(&robot, &payload, &q, &qd, &qd)[1]
                }
                ("coriolis_with_payload", true) => $m::coriolis_with_payload(q, qd, &pp)[(1, 0)],
                ("forward_dynamics_with_payload", true) => {
                    $m::forward_dynamics_with_payload(q, qd, qd, &pp).map_or(0.0, |x| x[1])
                }
                ("forward_dynamics_with_payload", false) => {
                    let (q, qd) = (
                        dhgen::nalgebra::DVector::from_row_slice(q),
                        dhgen::nalgebra::DVector::from_row_slice(qd),
                    );
                    dhgen::payload::forward_dynamics(&robot, &payload, &q, &qd, &qd)
                        .map_or(0.0, |x| x[1])
                }
                // Task-space dynamics of the tool (Λ, J̄, μ, p) from the arm's D, J, J̇ q̇ and g.
                ("task_space", true) => {
                    let q = dhgen::nalgebra::SVector::from(*q);
                    let qd = dhgen::nalgebra::SVector::from(*qd);
                    dhgen::task_space::tool(&$m::Robot, &q, &qd)
                        .map_or(0.0, |t| t.inertia()[(1, 1)])
                }
                ("task_space", false) => {
                    let (q, qd) = (
                        dhgen::nalgebra::DVector::from_row_slice(q),
                        dhgen::nalgebra::DVector::from_row_slice(qd),
                    );
                    dhgen::task_space::tool(&robot, &q, &qd)
                        .map_or(0.0, |t| t.inertia()[(1, 1)])
                }
                // The same with the payload in the tool frame.
                ("task_space_payload", true) => {
                    let q = dhgen::nalgebra::SVector::from(*q);
                    let qd = dhgen::nalgebra::SVector::from(*qd);
                    dhgen::task_space::tool_with_payload(&$m::Robot, &payload, &q, &qd)
                        .map_or(0.0, |t| t.inertia()[(1, 1)])
                }
                ("task_space_payload", false) => {
                    let (q, qd) = (
                        dhgen::nalgebra::DVector::from_row_slice(q),
                        dhgen::nalgebra::DVector::from_row_slice(qd),
                    );
                    dhgen::task_space::tool_with_payload(&robot, &payload, &q, &qd)
                        .map_or(0.0, |t| t.inertia()[(1, 1)])
                }
                ("regressor", true) => $m::regressor(q, qd, qd)[(1, 12)],
                ("regressor", false) => robot.regressor(q, qd, qd)[(1, 12)],
                ("base_regressor", true) => $m::base_regressor(q, qd, qd)[(1, 3)],
                ("inverse_dynamics_derivatives", true) => {
                    $m::inverse_dynamics_derivatives(q, qd, qd).0[(1, 0)]
                }
                ("inverse_dynamics_derivatives", false) => {
                    robot.inverse_dynamics_derivatives(q, qd, qd).0[(1, 0)]
                }
                ("inverse_dynamics_derivatives_with_payload", true) => {
                    $m::inverse_dynamics_derivatives_with_payload(q, qd, qd, &pp).0[(1, 0)]
                }
                ("forward_dynamics_derivatives_with_payload", true) => {
                    $m::forward_dynamics_derivatives_with_payload(q, qd, qd, &pp)
                        .map_or(0.0, |x| x.0[(1, 0)])
                }
                ("forward_dynamics_derivatives", true) => {
                    $m::forward_dynamics_derivatives(q, qd, qd).map_or(0.0, |x| x.0[(1, 0)])
                }
                ("forward_dynamics_derivatives", false) => robot
                    .forward_dynamics_derivatives(q, qd, qd)
                    .map_or(0.0, |x| x.0[(1, 0)]),
                (other, _) => {
                    eprintln!("unknown quantity {other}");
                    std::process::exit(2);
                }
            };
        }
        println!("{acc}");
    }};
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 4 {
        eprintln!(
            "usage: instructions ROBOT QUANTITY generated|runtime|batch|packs|f32|packs_f32  \
             (ROBOT: puma560, panda, general_8 or general_12)"
        );
        std::process::exit(2);
    }
    match args[1].as_str() {
        "puma560" => run!(puma560, "robots", args[2].as_str(), args[3].as_str()),
        "panda" => run!(panda, "robots", args[2].as_str(), args[3].as_str()),
        "general_8" => run!(
            general_8,
            "benches/arms",
            args[2].as_str(),
            args[3].as_str()
        ),
        "general_12" => run!(
            general_12,
            "benches/arms",
            args[2].as_str(),
            args[3].as_str()
        ),
        other => {
            eprintln!("unknown robot {other}: puma560, panda, general_8 or general_12");
            std::process::exit(2);
        }
    }
}
