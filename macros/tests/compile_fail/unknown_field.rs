// A misspelt field name: the error points at the key and suggests the right one.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            { joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0, frction: { viscous: 0.1 } },
        ],
    }
}

fn main() {}
