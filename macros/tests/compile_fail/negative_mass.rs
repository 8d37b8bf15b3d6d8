// A negative mass: the error covers the whole `-2.0`, not only the minus sign.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            {
                joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0,
                mass: -2.0, com: [-0.5, 0.0, 0.0], inertia: { yy: 0.1667, zz: 0.1667 },
            },
        ],
    }
}

fn main() {}
