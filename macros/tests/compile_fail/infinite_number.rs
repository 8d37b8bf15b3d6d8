// `1e400` is a valid Rust token but overflows f64 to infinity. (NaN has no literal form in
// Rust tokens, so the NaN rule is covered by model/tests/model/validation.rs only.)
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            { joint: revolute, a: 1e400, alpha: 0.0, d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
