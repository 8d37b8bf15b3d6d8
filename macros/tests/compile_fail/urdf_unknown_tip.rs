// A `tip` that is not a link of the file: the error lists the links, at the path.
dhgen_macros::robot!(pub mod hand = "tests/compile_fail/robots/tree.urdf", tip = "thumb");

fn main() {}
