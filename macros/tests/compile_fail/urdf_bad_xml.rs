// A URDF file that is not well-formed XML: file, line and column of the XML parser's error.
dhgen_macros::robot!(pub mod broken = "tests/compile_fail/robots/bad_xml.urdf");

fn main() {}
