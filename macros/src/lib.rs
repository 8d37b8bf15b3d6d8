//! The `robot!` proc macro of dhgen.
