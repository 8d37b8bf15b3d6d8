// Every element of `links` is a table.
dhgen::robot! {
    pub mod arm {
        convention: standard,
        links: [1.0],
    }
}

fn main() {}
