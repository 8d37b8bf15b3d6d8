// A motor's rotor inertia cannot be negative.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            {
                joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0,
                motor: { inertia: -1e-4, gear: 62.6 },
            },
        ],
    }
}

fn main() {}
