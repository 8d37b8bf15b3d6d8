// The module keyword is part of the syntax: `robot!(pub mod name ...)`.
dhgen_macros::robot! {
    pub arm {
        convention: standard,
        links: [
            { joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
