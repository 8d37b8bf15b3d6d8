// Friction coefficients cannot be negative.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            {
                joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0,
                friction: { viscous: 0.1, coulomb: -0.5 },
            },
        ],
    }
}

fn main() {}
