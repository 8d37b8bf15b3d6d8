// An expression where a number is expected: only angles may be expressions.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            { joint: revolute, a: f64::NAN, alpha: 0.0, d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
