// A motor with gear ratio 0 would transmit nothing.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            {
                joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0,
                motor: { inertia: 2.0e-4, gear: 0.0 },
            },
        ],
    }
}

fn main() {}
