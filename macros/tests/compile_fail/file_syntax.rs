// A description file that is not valid TOML: the TOML parser's message, with the file name.
dhgen_macros::robot!(pub mod arm = "tests/compile_fail/robots/bad_syntax.toml");

fn main() {}
