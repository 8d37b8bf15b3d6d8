// A joint type that is neither revolute nor prismatic.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            { joint: spherical, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
