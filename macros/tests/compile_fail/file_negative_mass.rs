// A description file with a negative mass on link 2: the error names the file, the line and
// column, the link and the field. tests/compile_fail.rs places a copy of the file where the
// path resolves inside trybuild's scratch crate.
dhgen_macros::robot!(pub mod arm = "tests/compile_fail/robots/negative_mass.toml");

fn main() {}
