// Gravity has three components.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        gravity: [0.0, -9.81],
        links: [
            { joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
