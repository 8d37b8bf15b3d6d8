//! dhgen's symbolic engine: a validated [`RobotModel`] becomes a Rust module of
//! straight-line, allocation-free functions.
//!
//! Its interface is [`generate_with`] (what `robot!` and `dhgen emit` call), the operation
//! counts ([`op_counts`]), the LaTeX equations ([`dynamics_equations`]) and the [`limits`] it
//! takes. The pipeline behind it, one module per step:
//! - `chain`: the kinematic chain in joint frames, generic over the arithmetic;
//! - `poly`: the normal form (polynomials in cos/sin of the joint angles) and Horner
//!   factoring back into expressions;
//! - `graph`: the hash-consed expression DAG (common subexpressions shared by
//!   construction, constants folded, signs pushed outward);
//! - `derive`: each quantity (T, J, D, c_ijk, C, g, τ), choosing the cheaper derivation;
//! - `emit`: tokens, one `let` per node, functions split under a statement limit;
//! - `module`: the generated module, driven by its table of quantities
//!   (`module::quantities`);
//! - `latex`: the normal forms of D(q), c_ijk, g(q) and P(q) as LaTeX equations (`dhgen latex`).

mod chain;
mod derive;
mod dual;
mod emit;
mod graph;
mod latex;
pub mod limits;
mod module;
mod poly;

pub use dhgen_description::RobotModel;
pub use graph::OpCount;
pub use latex::{Style, dynamics_equations};
pub use limits::Unsupported;
pub use module::{
    Generated, LOOP_C_ABOVE_PER_JOINT, LOOP_D_ABOVE_PER_JOINT, LOOPED_ABOVE, Options, generate,
    generate_with, module_doc, op_counts, op_counts_with,
};

/// The symbolic recursions evaluated on numbers, for the tests that check them against the
/// runtime path's (not part of the API).
#[doc(hidden)]
pub use chain::{Coordinates, Numbers, RingChain};
