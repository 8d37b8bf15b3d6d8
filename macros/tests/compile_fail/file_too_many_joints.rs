// A valid description with more joints than the generator takes with dynamics (33 > 32):
// the error says so and points at the runtime path. tests/compile_fail.rs places a copy
// of the file where the path resolves inside trybuild's scratch crate.
dhgen_macros::robot!(pub mod snake = "tests/compile_fail/robots/snake33.toml");

fn main() {}
