// An integer beyond 64 bits is an error (as in TOML), not silently 1e20.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            { joint: revolute, a: 99999999999999999999, alpha: 0.0, d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
