//! The integration tests of `dhgen`, in one test binary (`cargo test --test integration`).
//!
//! One binary instead of one per file: every robot is expanded by `robot!` once, in
//! [`catalogue`], rather than again by each file that uses it, which dominated the time
//! `cargo test` spent compiling.
//!
//! Organisation:
//! - one module per area, each a former `tests/<area>.rs`: its tests are `<area>::<name>`
//!   (`cargo test --test integration velocity::` runs one area);
//! - [`catalogue`]: the generated modules of the catalogue robots (`robots/`) and of the
//!   fixtures (`tests/fixtures/`, robots that exercise what the catalogue lacks);
//! - [`support`]: helpers shared by the modules, and the counting global allocator;
//! - `planning_support` and `trajectory_support`: scenes and checks of the planning and
//!   trajectory tests (the planning scenes are also compiled into `examples/planning.rs` and
//!   `benches/planning.rs`).
//!
//! Reference values are in `tests/data/`; proptest's saved failure cases in
//! `tests/proptest-regressions/<area>.txt`, where proptest looks for them. The compile-fail
//! tests of `robot!` live with the macro (`macros/tests/compile_fail.rs`, trybuild).

mod catalogue;
mod support;

// Compiled into examples/planning.rs and benches/planning.rs too; `pub` because those use
// parts of it (scene names and titles) that no test does.
pub mod planning_support;
mod trajectory_support;

mod batch;
mod derivatives;
mod generated_reference;
mod generated_velocity;
mod generated_vs_runtime;
mod hostile_descriptions;
mod hostile_urdf;
mod identification_periodic;
mod ik_closed_form;
mod ik_numeric;
mod ik_preference;
mod ik_random;
mod ik_singular;
mod ik_task;
mod non_finite;
mod payload;
mod planar_elbow;
mod planning_collision;
mod planning_potential;
mod planning_prm;
mod planning_workspace;
mod regressor;
mod ring_algorithms;
mod rotation;
mod rtb_models;
mod runtime_laws;
mod runtime_reference;
mod simulate;
mod singular_inertia;
mod task_space;
mod trajectory_fourier;
mod trajectory_lspb;
mod trajectory_min_time;
mod trajectory_multi;
mod trajectory_polynomial;
mod trajectory_sampling;
mod trajectory_via;
mod urdf;
mod velocity;
