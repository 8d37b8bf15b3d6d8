// Principal moments 0.1 + 0.1 < 1.0: no real body has them.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            {
                joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0,
                mass: 2.0, com: [-0.5, 0.0, 0.0], inertia: { xx: 0.1, yy: 0.1, zz: 1.0 },
            },
        ],
    }
}

fn main() {}
