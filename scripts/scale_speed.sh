#!/usr/bin/env bash
# Generated code against the runtime path on random arms too large for the criterion
# benchmark (benches/random_arms.rs stops at 12 joints): for each size, a seeded arm
# (`dhgen random --dof N --style STYLE --seed 1`) is expanded by `robot!` in a release crate,
# and fk, J, D, C, g, the kinetic and potential energy, τ and q̈ are timed on 64 fixed states, generated against
# `dhgen::Robot`, best of seven runs of 20,000 calls (ns per call; the ratio is runtime /
# generated, above 1 where the generated code is faster).
#
#   scripts/scale_speed.sh [--more] [general|industrial] [N ...]   (default: general 16 20 30)
#
# `--more` also expands the derivatives (`robot!(..., derivatives)`) and times c_ijk, the
# payload's D, g, τ, q̈ and C (against `dhgen::payload`'s functions on `Robot`; C against the
# runtime's C without the payload, which has no payload variant: its cost is the same), Ḋ,
# Cᵀq̇, ∂τ, ∂q̈ and D⁻¹, and ∂τ and ∂q̈ with the payload (against `Robot::with_payload`'s). A 30-joint arm takes about five minutes to build (about eight with
# `--more`). Scratch files in target/scale-speed/.
set -euo pipefail
cd "$(dirname "$0")/.."
more=false
if [[ "${1:-}" == --more ]]; then more=true; shift; fi
style=general
if [[ "${1:-}" == general || "${1:-}" == industrial ]]; then style=$1; shift; fi
sizes=("$@")
[[ ${#sizes[@]} -gt 0 ]] || sizes=(16 20 30)
root=$(pwd)
crate=target/scale-speed
mkdir -p "$crate/src"
cargo build -q --release -p dhgen-cli
mods=""
calls=""
options=""
extra=""
setup=""
if $more; then
  options=", derivatives"
  # The payload the `--more` rows hold: its parameters, and the runtime robot holding it.
  setup='
        let pl = dhgen::payload::Payload::new(1.5, [0.01, -0.02, 0.05], [[0.01, 0.0, 0.0], [0.0, 0.012, 0.0], [0.0, 0.0, 0.008]]).unwrap();
        let pp = pl.parameters();
        let held = robot.with_payload(&pl).unwrap();'
  extra='
            ("christoffel", time(|i| $m::christoffel(&black_box(&s[i % 64])[0])), time(|i| robot.christoffel(&black_box(&d[i % 64])[0]))),
            ("mass_matrix_with_payload", time(|i| $m::mass_matrix_with_payload(&black_box(&s[i % 64])[0], &pp)), time(|i| dhgen::payload::mass_matrix(&robot, &pl, &black_box(&d[i % 64])[0]))),
            ("gravity_with_payload", time(|i| $m::gravity_with_payload(&black_box(&s[i % 64])[0], &pp)), time(|i| dhgen::payload::gravity(&robot, &pl, &black_box(&d[i % 64])[0]))),
            ("inverse_dynamics_with_payload", time(|i| { let [q, qd, qdd] = black_box(&s[i % 64]); $m::inverse_dynamics_with_payload(q, qd, qdd, &pp) }), time(|i| { let [q, qd, qdd] = black_box(&d[i % 64]); dhgen::payload::inverse_dynamics(&robot, &pl, q, qd, qdd) })),
            ("forward_dynamics_with_payload", time(|i| { let [q, qd, t] = black_box(&s[i % 64]); $m::forward_dynamics_with_payload(q, qd, t, &pp) }), time(|i| { let [q, qd, t] = black_box(&d[i % 64]); dhgen::payload::forward_dynamics(&robot, &pl, q, qd, t) })),
            ("coriolis_with_payload", time(|i| { let [q, qd, _] = black_box(&s[i % 64]); $m::coriolis_with_payload(q, qd, &pp) }), time(|i| { let [q, qd, _] = black_box(&d[i % 64]); robot.coriolis(q, qd) })),
            ("mass_matrix_rate", time(|i| { let [q, qd, _] = black_box(&s[i % 64]); $m::mass_matrix_rate(q, qd) }), time(|i| { let [q, qd, _] = black_box(&d[i % 64]); robot.mass_matrix_rate(q, qd) })),
            ("coriolis_transpose_qd", time(|i| { let [q, qd, _] = black_box(&s[i % 64]); $m::coriolis_transpose_qd(q, qd) }), time(|i| { let [q, qd, _] = black_box(&d[i % 64]); robot.coriolis_transpose_qd(q, qd) })),
            ("inverse_dynamics_derivatives", time(|i| { let [q, qd, qdd] = black_box(&s[i % 64]); $m::inverse_dynamics_derivatives(q, qd, qdd) }), time(|i| { let [q, qd, qdd] = black_box(&d[i % 64]); robot.inverse_dynamics_derivatives(q, qd, qdd) })),
            ("forward_dynamics_derivatives", time(|i| { let [q, qd, t] = black_box(&s[i % 64]); $m::forward_dynamics_derivatives(q, qd, t) }), time(|i| { let [q, qd, t] = black_box(&d[i % 64]); robot.forward_dynamics_derivatives(q, qd, t) })),
            ("mass_matrix_inverse", time(|i| $m::mass_matrix_inverse(&black_box(&s[i % 64])[0])), time(|i| robot.mass_matrix_inverse(&black_box(&d[i % 64])[0]))),
            ("inverse_dynamics_derivatives_with_payload", time(|i| { let [q, qd, qdd] = black_box(&s[i % 64]); $m::inverse_dynamics_derivatives_with_payload(q, qd, qdd, &pp) }), time(|i| { let [q, qd, qdd] = black_box(&d[i % 64]); held.inverse_dynamics_derivatives(q, qd, qdd) })),
            ("forward_dynamics_derivatives_with_payload", time(|i| { let [q, qd, t] = black_box(&s[i % 64]); $m::forward_dynamics_derivatives_with_payload(q, qd, t, &pp) }), time(|i| { let [q, qd, t] = black_box(&d[i % 64]); held.forward_dynamics_derivatives(q, qd, t) })),'
fi
for n in "${sizes[@]}"; do
  target/release/dhgen random --dof "$n" --style "$style" --seed 1 -o "$crate/${style}_$n.toml"
  mods+="dhgen::robot!(mod ${style}_$n = \"${style}_$n.toml\"$options);"$'\n'
  calls+="    arm!(${style}_$n);"$'\n'
done
cat > "$crate/Cargo.toml" <<TOML
[package]
name = "scale-speed"
version = "0.0.0"
edition = "2024"
publish = false
[dependencies]
dhgen = { path = "$root" }
[workspace]
TOML
cat > "$crate/src/main.rs" <<RUST
use dhgen::nalgebra::{DVector, SVector};
use dhgen::{Arm, ArmDynamics, Robot};
use std::hint::black_box;
use std::time::Instant;

$mods
/// Best of seven runs of 20,000 calls, ns per call.
fn time<R>(mut f: impl FnMut(usize) -> R) -> f64 {
    let reps = 20_000;
    (0..7)
        .map(|_| {
            let t = Instant::now();
            for i in 0..reps {
                black_box(f(i));
            }
            t.elapsed().as_nanos() as f64 / reps as f64
        })
        .fold(f64::INFINITY, f64::min)
}

macro_rules! arm {
    (\$m:ident) => {{
        const N: usize = \$m::DOF;
        let robot = Robot::from_toml_file(concat!(stringify!(\$m), ".toml")).unwrap();
        let s: Vec<[SVector<f64, N>; 3]> = (0..64)
            .map(|i| {
                [
                    SVector::from_fn(|j, _| ((i * 7 + j * 13) as f64 * 0.37).sin()),
                    SVector::from_fn(|j, _| ((i * 5 + j * 11) as f64 * 0.29).sin() * 2.0),
                    SVector::from_fn(|j, _| ((i * 3 + j * 17) as f64 * 0.31).sin() * 5.0),
                ]
            })
            .collect();
        let d: Vec<[DVector<f64>; 3]> = s
            .iter()
            .map(|x| x.clone().map(|v| DVector::from_column_slice(v.as_slice())))
            .collect();
        let g = \$m::Robot;
        let (s, d) = (&s, &d);
$setup
        let rows: Vec<(&str, f64, f64)> = vec![
            ("fk", time(|i| g.fk(&black_box(&s[i % 64])[0])), time(|i| robot.fk(&black_box(&d[i % 64])[0]))),
            ("jacobian", time(|i| g.jacobian(&black_box(&s[i % 64])[0])), time(|i| robot.jacobian(&black_box(&d[i % 64])[0]))),
            ("mass_matrix", time(|i| g.mass_matrix(&black_box(&s[i % 64])[0])), time(|i| robot.mass_matrix(&black_box(&d[i % 64])[0]))),
            ("coriolis", time(|i| { let [q, qd, _] = black_box(&s[i % 64]); g.coriolis(q, qd) }), time(|i| { let [q, qd, _] = black_box(&d[i % 64]); robot.coriolis(q, qd) })),
            ("gravity", time(|i| g.gravity(&black_box(&s[i % 64])[0])), time(|i| robot.gravity(&black_box(&d[i % 64])[0]))),
            ("kinetic_energy", time(|i| { let [q, qd, _] = black_box(&s[i % 64]); g.kinetic_energy(q, qd) }), time(|i| { let [q, qd, _] = black_box(&d[i % 64]); robot.kinetic_energy(q, qd) })),
            ("potential_energy", time(|i| g.potential_energy(&black_box(&s[i % 64])[0])), time(|i| robot.potential_energy(&black_box(&d[i % 64])[0]))),
            ("inverse_dynamics", time(|i| { let [q, qd, qdd] = black_box(&s[i % 64]); g.inverse_dynamics(q, qd, qdd) }), time(|i| { let [q, qd, qdd] = black_box(&d[i % 64]); robot.inverse_dynamics(q, qd, qdd) })),
            ("forward_dynamics", time(|i| { let [q, qd, t] = black_box(&s[i % 64]); g.forward_dynamics(q, qd, t) }), time(|i| { let [q, qd, t] = black_box(&d[i % 64]); robot.forward_dynamics(q, qd, t) })),$extra
        ];
        for (what, generated, runtime) in rows {
            println!("| {} | {what} | {generated:.0} | {runtime:.0} | {:.2}× |", stringify!(\$m), runtime / generated);
        }
    }};
}

fn main() {
    println!("| arm | quantity | generated (ns) | runtime (ns) | runtime / generated |");
    println!("|---|---|---:|---:|---:|");
$calls}
RUST
(cd "$crate" && cargo build -q --release && ./target/release/scale-speed)
