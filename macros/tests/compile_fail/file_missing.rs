// A description file that does not exist: the error points at the path literal.
dhgen_macros::robot!(pub mod arm = "tests/compile_fail/robots/no_such_robot.toml");

fn main() {}
