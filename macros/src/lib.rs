//! The `robot!` proc macro of dhgen: parse the input, validate it with the shared model
//! rules, and hand the model to the code generator. See the `dhgen` crate for the docs.

mod expand;
mod parse;

/// Generates a module of specialised kinematics and dynamics functions for a robot.
/// Documented in the `dhgen` crate, which re-exports it.
#[proc_macro]
pub fn robot(input: proc_macro::TokenStream) -> proc_macro::TokenStream {
    let input = syn::parse_macro_input!(input as parse::RobotInput);
    expand::expand(input)
        .unwrap_or_else(syn::Error::into_compile_error)
        .into()
}
