// A robot must have at least one link.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [],
    }
}

fn main() {}
