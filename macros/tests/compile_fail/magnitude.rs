// A finite length no robot has: outside the documented range.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            { joint: revolute, a: -1e308, alpha: 0.0, d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
