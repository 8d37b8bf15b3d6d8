// A robot must have at least one link.
dhgen::robot! {
    pub mod arm {
        convention: standard,
        links: [],
    }
}

fn main() {}
