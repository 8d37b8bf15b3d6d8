// An angle string that cannot be parsed.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            { joint: revolute, a: 1.0, alpha: "ninety", d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
