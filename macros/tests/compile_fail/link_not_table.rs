// Every element of `links` is a table.
dhgen_macros::robot! {
    pub mod arm {
        convention: standard,
        links: [1.0],
    }
}

fn main() {}
