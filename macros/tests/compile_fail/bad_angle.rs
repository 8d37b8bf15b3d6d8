// An angle written as tokens that do not read as an angle (`degrees` is not a unit).
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            { joint: revolute, a: 1.0, alpha: 90 degrees, d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
