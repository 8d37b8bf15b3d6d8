// Link 2 lacks the mass properties that link 1 has.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            {
                joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0,
                mass: 2.0, com: [-0.5, 0.0, 0.0], inertia: { yy: 0.1667, zz: 0.1667 },
            },
            { joint: revolute, a: 0.8, alpha: 0.0, d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
