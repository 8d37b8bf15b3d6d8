// `tip` chooses the chain of a URDF file; a TOML description has none: the error is at `tip`.
dhgen_macros::robot!(pub mod arm = "tests/compile_fail/robots/negative_mass.toml", tip = "hand");

fn main() {}
