//! Parsing `robot!`'s two forms into the model's raw description tree.
//!
//! - `vis mod name = "path/to/robot.toml";`
//! - `vis mod name { field: value, ... }` with the fields of the TOML format; values are
//!   numbers, strings, bare words (`revolute`), `[...]`, `{...}`, and angles written as
//!   `90 deg` or `PI / 2` (any tokens up to the next comma are read as an angle string).

use dhgen_model::raw::{Table, Value};
use proc_macro2::{Delimiter, Span, TokenStream, TokenTree};
use syn::parse::{Parse, ParseStream};
use syn::{Ident, LitStr, Token, Visibility};

/// The macro input.
pub struct RobotInput {
    pub vis: Visibility,
    pub name: Ident,
    pub body: Body,
}

/// Where the description is.
pub enum Body {
    /// A TOML file, relative to the invoking crate's manifest directory.
    File(LitStr),
    /// Inline fields.
    Inline(Table<Span>),
}

impl Parse for RobotInput {
    fn parse(input: ParseStream<'_>) -> syn::Result<Self> {
        let vis: Visibility = input.parse()?;
        input.parse::<Token![mod]>()?;
        let name: Ident = input.parse()?;
        let body = if input.peek(Token![=]) {
            input.parse::<Token![=]>()?;
            let path: LitStr = input.parse()?;
            if input.peek(Token![;]) {
                input.parse::<Token![;]>()?;
            }
            Body::File(path)
        } else {
            let content;
            let brace = syn::braced!(content in input);
            let tokens: TokenStream = content.parse()?;
            Body::Inline(table(tokens, brace.span.join())?)
        };
        if !input.is_empty() {
            return Err(input.error("unexpected tokens after the robot description"));
        }
        Ok(RobotInput { vis, name, body })
    }
}

/// `key: value, key: value, ...`
fn table(tokens: TokenStream, span: Span) -> syn::Result<Table<Span>> {
    let mut entries = Vec::new();
    for item in split_commas(tokens) {
        let mut it = item.into_iter();
        let key = match it.next() {
            Some(TokenTree::Ident(i)) => i,
            Some(other) => return Err(syn::Error::new(other.span(), "expected a field name")),
            None => continue,
        };
        match it.next() {
            Some(TokenTree::Punct(p)) if p.as_char() == ':' => {}
            Some(other) => {
                return Err(syn::Error::new(
                    other.span(),
                    "expected `:` after the field name",
                ));
            }
            None => {
                return Err(syn::Error::new(
                    key.span(),
                    format!("field `{key}` has no value"),
                ));
            }
        }
        let rest: Vec<TokenTree> = it.collect();
        if rest.is_empty() {
            return Err(syn::Error::new(
                key.span(),
                format!("field `{key}` has no value"),
            ));
        }
        entries.push((key.to_string(), key.span(), value(rest)?));
    }
    Ok(Table { entries, loc: span })
}

fn split_commas(tokens: TokenStream) -> Vec<Vec<TokenTree>> {
    let mut items = vec![Vec::new()];
    for t in tokens {
        match &t {
            TokenTree::Punct(p) if p.as_char() == ',' => items.push(Vec::new()),
            _ => items.last_mut().expect("non-empty").push(t),
        }
    }
    items.retain(|i| !i.is_empty());
    items
}

fn number(lit: &proc_macro2::Literal) -> Option<f64> {
    let text = lit.to_string().replace('_', "");
    let text = text
        .trim_end_matches("f64")
        .trim_end_matches("f32")
        .trim_end_matches("i32")
        .trim_end_matches("u32");
    text.parse().ok()
}

fn value(tokens: Vec<TokenTree>) -> syn::Result<Value<Span>> {
    let first = tokens[0].span();
    if tokens.len() == 1 {
        match &tokens[0] {
            TokenTree::Literal(lit) => {
                if let Ok(s) = syn::parse2::<LitStr>(TokenTree::Literal(lit.clone()).into()) {
                    return Ok(Value::Str(s.value(), first));
                }
                if let Some(x) = number(lit) {
                    return Ok(Value::Number(x, first));
                }
                return Err(syn::Error::new(first, "expected a number or a string"));
            }
            TokenTree::Ident(i) if i == "true" || i == "false" => {
                return Ok(Value::Bool(i == "true", first));
            }
            TokenTree::Ident(i) if !i.to_string().eq_ignore_ascii_case("pi") => {
                return Ok(Value::Word(i.to_string(), first));
            }
            TokenTree::Group(g) if g.delimiter() == Delimiter::Bracket => {
                let items = split_commas(g.stream())
                    .into_iter()
                    .map(value)
                    .collect::<syn::Result<Vec<_>>>()?;
                return Ok(Value::Array(items, g.span()));
            }
            TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => {
                return Ok(Value::Table(table(g.stream(), g.span())?));
            }
            _ => {}
        }
    }
    if let [TokenTree::Punct(p), TokenTree::Literal(lit)] = tokens.as_slice() {
        if p.as_char() == '-' {
            if let Some(x) = number(lit) {
                return Ok(Value::Number(-x, first));
            }
        }
    }
    // Anything else (`90 deg`, `PI / 2`, `-3 * PI / 4`) is an angle expression, read by
    // the same parser as the TOML strings.
    let text: String = tokens.iter().map(ToString::to_string).collect();
    Ok(Value::Str(text, first))
}
