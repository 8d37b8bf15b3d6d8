// A misspelt setting: the error names the settings a URDF file takes, at the word.
dhgen_macros::robot!(pub mod hand = "tests/compile_fail/robots/tree.urdf", tipp = "left_finger");

fn main() {}
