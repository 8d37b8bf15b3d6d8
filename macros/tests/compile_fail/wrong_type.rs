// A number where a keyword is expected.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            { joint: 1, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
