// An option word `robot!` does not know, after the description: the error lists the options.
dhgen_macros::robot!(pub mod arm = "tests/compile_fail/robots/negative_mass.toml", derivativs);

fn main() {}
