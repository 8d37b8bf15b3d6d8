//! Every robot the tests use, expanded by `robot!` once for the whole binary: the catalogue
//! of `robots/` and the fixtures of `tests/fixtures/` (each fixture says what it exercises).
//! Test modules import what they need, under another name where they read better:
//! `use crate::catalogue::puma560 as puma;`.

// The catalogue, robots/*.toml (with the regressor where the robot has mass properties and the
// modules below do not already have it).
dhgen::robot!(pub mod cylindrical = "robots/cylindrical.toml");
dhgen::robot!(pub mod panda = "robots/panda.toml");
dhgen::robot!(pub mod planar_elbow = "robots/planar_elbow.toml", regressor);
dhgen::robot!(pub mod puma560 = "robots/puma560.toml");
dhgen::robot!(pub mod scara = "robots/scara.toml");
dhgen::robot!(pub mod stanford = "robots/stanford.toml");
dhgen::robot!(pub mod ur5 = "robots/ur5.toml", regressor);

// Fixtures, tests/fixtures/*.toml.
dhgen::robot!(pub mod craig = "tests/fixtures/craig.toml");
dhgen::robot!(pub mod elbow = "tests/fixtures/elbow.toml");
dhgen::robot!(pub mod gantry = "tests/fixtures/gantry.toml");
dhgen::robot!(pub mod odd = "tests/fixtures/odd.toml");
dhgen::robot!(pub mod offset_elbow = "tests/fixtures/offset_elbow.toml");
dhgen::robot!(pub mod puma_offsets = "tests/fixtures/puma_offsets.toml");
dhgen::robot!(pub mod shoulder_singular_elbow = "tests/fixtures/shoulder_singular_elbow.toml");
dhgen::robot!(pub mod stiff_wrist = "tests/fixtures/stiff_wrist.toml");
dhgen::robot!(pub mod weightless_wrist = "tests/fixtures/weightless_wrist.toml");
dhgen::robot!(pub mod snake17 = "tests/fixtures/snake17.toml");

// With the derivatives of the dynamics and the regressor (`robot!(..., derivatives,
// regressor)`), for tests/integration/derivatives.rs and regressor.rs: a 6-joint arm, motors
// and friction, and everything at once; and the regressor alone for a 7-joint arm and
// prismatic joints.
dhgen::robot!(pub mod puma560_derivatives = "robots/puma560.toml", derivatives, regressor);
dhgen::robot!(pub mod scara_derivatives = "robots/scara.toml", derivatives, regressor);
dhgen::robot!(pub mod odd_derivatives = "tests/fixtures/odd.toml", derivatives, regressor);
// τ assembled from small normal forms and differentiated symbolically (the cheapest
// derivation of its derivatives there).
dhgen::robot!(pub mod stanford_derivatives = "robots/stanford.toml", derivatives);
// Echeandia–Wensing's terms and Carpentier–Mansard's closed form in joint frames (the
// cheapest derivation of C and ∂τ/∂q there), and Cᵀq̇ as the kinetic energy's gradient.
dhgen::robot!(pub mod panda_derivatives = "robots/panda.toml", derivatives);
// Past the joints up to which the Cholesky factorisation is unrolled: its looped form, in
// forward dynamics, D⁻¹ and their derivatives.
dhgen::robot!(pub mod snake17_derivatives = "tests/fixtures/snake17.toml", derivatives);
// No structure at all (every twist oblique, every length and offset non-zero, full inertia
// tensors, a prismatic joint, base, tool, motors, friction, tilted gravity), 9 joints: where
// the derivations in one frame's coordinates win (D in the middle joint's frame, C and ∂τ/∂q
// in the first joint's), not the joint-frame ones the catalogue's arms take.
dhgen::robot!(pub mod oblique9 = "tests/fixtures/oblique9.toml", derivatives, regressor);
dhgen::robot!(pub mod panda_regressor = "robots/panda.toml", regressor);
dhgen::robot!(pub mod stanford_regressor = "robots/stanford.toml", regressor);

// URDF files (tests/data/urdf/, from example-robot-data), read as `robot!` reads them.
dhgen::robot!(pub mod panda_urdf = "tests/data/urdf/panda.urdf", tip = "panda_hand");
dhgen::robot!(pub mod ur5_urdf = "tests/data/urdf/ur5.urdf");
dhgen::robot!(pub mod baxter_left = "tests/data/urdf/baxter.urdf", tip = "left_gripper");
dhgen::robot!(pub mod kinova_urdf = "tests/data/urdf/kinova.urdf", tip = "j2s6s200_end_effector");
dhgen::robot!(pub mod double_pendulum_urdf = "tests/data/urdf/double_pendulum_continuous.urdf");
dhgen::robot!(pub mod random_urdf_2 = "tests/data/urdf/random_2.urdf", tip = "link_7");
dhgen::robot!(pub mod random_urdf_3 = "tests/data/urdf/random_3.urdf", tip = "tool");
dhgen::robot!(pub mod tiago_arm = "tests/data/urdf/tiago.urdf", tip = "arm_7_link");
dhgen::robot!(pub mod human_arm = "tests/data/urdf/human.urdf", tip = "left_hand");
dhgen::robot!(pub mod xarm7_urdf = "tests/data/urdf/xarm7.urdf", tip = "link_eef");
dhgen::robot!(pub mod g1_arm = "tests/data/urdf/g1.urdf", tip = "left_wrist_yaw_link");
dhgen::robot!(pub mod centauro_arm = "tests/data/urdf/centauro.urdf", tip = "arm1_6");
dhgen::robot!(pub mod hextilt_arm = "tests/data/urdf/hextilt_flying_arm_5.urdf", tip = "flying_arm_5__gripper");
