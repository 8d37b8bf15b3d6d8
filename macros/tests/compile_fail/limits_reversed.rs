// Joint limits with the lower bound above the upper one.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            { joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0, limits: [90 deg, 45 deg] },
        ],
    }
}

fn main() {}
