// Only `standard` and `modified` DH exist.
dhgen_macros::robot! {
    pub mod arm {
        convention: craig,
        links: [
            { joint: revolute, a: 1.0, alpha: 0.0, d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
