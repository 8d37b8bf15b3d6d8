//! Token tidy-up: what makes printed generated code read like hand-written code.

use proc_macro2::TokenStream;

/// `1usize` → `1`: quote writes integer literals with their type suffix, which only adds
/// noise to indices in printed code.
pub fn unsuffix_indices(tokens: TokenStream) -> TokenStream {
    use proc_macro2::{Group, Literal, TokenTree};
    tokens
        .into_iter()
        .map(|t| match t {
            TokenTree::Group(g) => {
                let mut ng = Group::new(g.delimiter(), unsuffix_indices(g.stream()));
                ng.set_span(g.span());
                TokenTree::Group(ng)
            }
            TokenTree::Literal(l) => match l
                .to_string()
                .strip_suffix("usize")
                .and_then(|d| d.parse::<usize>().ok())
            {
                Some(v) => {
                    let mut nl = Literal::usize_unsuffixed(v);
                    nl.set_span(l.span());
                    TokenTree::Literal(nl)
                }
                None => TokenTree::Literal(l),
            },
            other => other,
        })
        .collect()
}
