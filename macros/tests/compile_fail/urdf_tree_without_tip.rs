// A URDF tree with two ends and no `tip`: the error lists the candidate tips, at the path.
dhgen_macros::robot!(pub mod hand = "tests/compile_fail/robots/tree.urdf");

fn main() {}
