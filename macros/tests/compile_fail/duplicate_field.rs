// A field given twice (TOML forbids this itself; the macro form must check it).
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            { joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0, a: 2.0 },
        ],
    }
}

fn main() {}
