// A link without its required `alpha`: the error points at that link's table.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [
            { joint: revolute, a: 1.0, d: 0.0, theta: 0.0 },
        ],
    }
}

fn main() {}
