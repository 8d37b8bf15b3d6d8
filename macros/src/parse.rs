//! Parsing `robot!`'s two forms into the model's raw description tree.
//!
//! - `vis mod name = "path/to/robot.toml";`
//! - `vis mod name { field: value, ... }` with the fields of the TOML format; values are
//!   numbers, strings, bare words (`revolute`), `[...]`, `{...}`, and angles written as
//!   `90 deg` or `PI / 2` (any other tokens up to the next comma are an expression, which
//!   only an angle field accepts).
//!
//! Either form may end with option words: `vis mod name = "robot.toml", derivatives;`
//! (`dhgen_codegen::Options`).

use dhgen_description::raw::{Table, Value};
use proc_macro2::{Delimiter, Punct, Spacing, Span, TokenStream, TokenTree};
use quote::ToTokens;
use syn::parse::{Parse, ParseStream};
use syn::{Ident, LitStr, Token, Visibility};

/// The macro input.
pub struct RobotInput {
    pub vis: Visibility,
    pub name: Ident,
    pub body: Body,
    /// The option words after the description (`, derivatives`).
    pub options: dhgen_codegen::Options,
    /// How to read a URDF file (`, tip = "hand", base = "link0", snap = 1e-6`), with the
    /// span of the first such option, which a TOML description must not have.
    pub urdf: (dhgen_description::urdf::UrdfOptions, Option<Span>),
}

/// Where the description is.
pub enum Body {
    /// A TOML file, relative to the invoking crate's manifest directory.
    File(LitStr),
    /// Inline fields.
    Inline(Table<Loc>),
}

/// Where a value of the inline form was written: its first and last token.
///
/// A value such as `-2.0` or `90 deg` is several tokens, and joining their spans into one
/// (`Span::join`) is not available on stable Rust. Keeping both ends lets an error underline
/// the whole value rather than its minus sign or its first word.
#[derive(Clone, Copy, Debug)]
pub struct Loc {
    first: Span,
    last: Span,
}

impl Loc {
    /// A location that is one token or one delimited group.
    fn of(span: Span) -> Loc {
        Loc {
            first: span,
            last: span,
        }
    }

    /// The tokens `tokens[0] ..= tokens[last]`; `tokens` is not empty.
    fn range(tokens: &[TokenTree]) -> Loc {
        Loc {
            first: tokens[0].span(),
            last: tokens[tokens.len() - 1].span(),
        }
    }

    /// A compile error covering this location.
    pub fn error(self, message: impl core::fmt::Display) -> syn::Error {
        // `new_spanned` spans from its argument's first token to its last one: exactly
        // the range, and the only way to report one on stable Rust.
        syn::Error::new_spanned(self, message)
    }
}

impl ToTokens for Loc {
    /// Two placeholder tokens carrying the two ends, for [`Loc::error`]; never emitted as
    /// code.
    fn to_tokens(&self, tokens: &mut TokenStream) {
        for span in [self.first, self.last] {
            let mut end = Punct::new('.', Spacing::Alone);
            end.set_span(span);
            tokens.extend([TokenTree::Punct(end)]);
        }
    }
}

impl Parse for RobotInput {
    fn parse(input: ParseStream<'_>) -> syn::Result<Self> {
        let vis: Visibility = input.parse()?;
        input.parse::<Token![mod]>()?;
        let name: Ident = input.parse()?;
        let body = if input.peek(Token![=]) {
            input.parse::<Token![=]>()?;
            let path: LitStr = input.parse()?;
            Body::File(path)
        } else {
            let content;
            let brace = syn::braced!(content in input);
            let tokens: TokenStream = content.parse()?;
            Body::Inline(table(tokens, Loc::of(brace.span.join()))?)
        };
        // `, derivatives`: option words, each naming what the module holds beyond the default;
        // `, tip = "..."`: how to read a URDF file.
        let mut options = dhgen_codegen::Options::default();
        let mut urdf = (dhgen_description::urdf::UrdfOptions::default(), None);
        while input.peek(Token![,]) {
            input.parse::<Token![,]>()?;
            if input.is_empty() || input.peek(Token![;]) {
                break;
            }
            let word: Ident = input.parse()?;
            if input.peek(Token![=]) {
                input.parse::<Token![=]>()?;
                urdf.1.get_or_insert(word.span());
                match word.to_string().as_str() {
                    "tip" => urdf.0.tip = Some(input.parse::<LitStr>()?.value()),
                    "base" => urdf.0.base = Some(input.parse::<LitStr>()?.value()),
                    "snap" => {
                        let lit: syn::LitFloat = input.parse()?;
                        let x: f64 = lit.base10_parse()?;
                        urdf.0.snap =
                            dhgen_description::urdf::UrdfOptions::check_snap(x).map_err(|why| {
                                syn::Error::new(lit.span(), format!("snap = {x}: {why}"))
                            })?;
                    }
                    other => {
                        return Err(syn::Error::new(
                            word.span(),
                            format!(
                                "unknown setting `{other}`; a URDF file takes `tip = \"link\"`, \
                                 `base = \"link\"` and `snap = 1e-6`"
                            ),
                        ));
                    }
                }
                continue;
            }
            if !options.set(&word.to_string()) {
                let known = dhgen_codegen::Options::WORDS
                    .iter()
                    .map(|(w, what)| format!("`{w}` ({what})"))
                    .collect::<Vec<_>>()
                    .join(", ");
                return Err(syn::Error::new(
                    word.span(),
                    format!("unknown option `{word}`; the options are {known}"),
                ));
            }
        }
        if input.peek(Token![;]) {
            input.parse::<Token![;]>()?;
        }
        if !input.is_empty() {
            return Err(input.error("unexpected tokens after the robot description"));
        }
        Ok(RobotInput {
            vis,
            name,
            body,
            options,
            urdf,
        })
    }
}

/// `key: value, key: value, ...`
fn table(tokens: TokenStream, loc: Loc) -> syn::Result<Table<Loc>> {
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
        // `joint: revolute a: 1.0`: the next field's `name:` inside this value means a
        // comma is missing before it.
        if let Some(next) = rest.windows(2).position(|w| {
            matches!((&w[0], &w[1]), (TokenTree::Ident(_), TokenTree::Punct(p))
                if p.as_char() == ':' && p.spacing() == Spacing::Alone)
        }) && (next == 0
            || !matches!(&rest[next - 1], TokenTree::Punct(p) if p.as_char() == ':'))
        {
            return Err(syn::Error::new(
                rest[next].span(),
                format!(
                    "expected `,` before `{}`: fields are separated by commas",
                    rest[next]
                ),
            ));
        }
        if rest.is_empty() {
            return Err(syn::Error::new(
                key.span(),
                format!("field `{key}` has no value"),
            ));
        }
        entries.push((key.to_string(), Loc::of(key.span()), value(rest)?));
    }
    Ok(Table { entries, loc })
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

/// A number literal: a float, or an integer within 64 bits (as in TOML, and as rustc requires
/// of an `i64`); `Err` for an integer beyond that, `Ok(None)` for any other literal.
fn number(lit: &proc_macro2::Literal) -> Result<Option<f64>, String> {
    match syn::parse2::<syn::Lit>(TokenTree::Literal(lit.clone()).into()) {
        Ok(syn::Lit::Float(f)) => Ok(f.base10_parse::<f64>().ok()),
        Ok(syn::Lit::Int(i)) => match i.base10_parse::<i64>() {
            Ok(x) => Ok(Some(x as f64)),
            Err(_) => Err(format!(
                "the integer `{i}` is outside the 64-bit range; write it as a float, e.g. `1e20`"
            )),
        },
        _ => Ok(None),
    }
}

/// The tokens of one value; `tokens` is not empty.
fn value(tokens: Vec<TokenTree>) -> syn::Result<Value<Loc>> {
    let loc = Loc::range(&tokens);
    if tokens.len() == 1 {
        match &tokens[0] {
            TokenTree::Literal(lit) => {
                if let Ok(s) = syn::parse2::<LitStr>(TokenTree::Literal(lit.clone()).into()) {
                    return Ok(Value::Str(s.value(), loc));
                }
                if let Some(x) = number(lit).map_err(|m| loc.error(m))? {
                    return Ok(Value::Number(x, loc));
                }
                return Err(loc.error("expected a number or a string"));
            }
            TokenTree::Ident(i) if i == "true" || i == "false" => {
                return Ok(Value::Bool(i == "true", loc));
            }
            TokenTree::Ident(i) if !i.to_string().eq_ignore_ascii_case("pi") => {
                return Ok(Value::Word(i.to_string(), loc));
            }
            TokenTree::Group(g) if g.delimiter() == Delimiter::Bracket => {
                let items = split_commas(g.stream())
                    .into_iter()
                    .map(value)
                    .collect::<syn::Result<Vec<_>>>()?;
                return Ok(Value::Array(items, loc));
            }
            TokenTree::Group(g) if g.delimiter() == Delimiter::Brace => {
                return Ok(Value::Table(table(g.stream(), loc)?));
            }
            _ => {}
        }
    }
    if let [TokenTree::Punct(p), TokenTree::Literal(lit)] = tokens.as_slice()
        && p.as_char() == '-'
        && let Some(x) = number(lit).map_err(|m| loc.error(m))?
    {
        return Ok(Value::Number(-x, loc));
    }
    // Anything else (`90 deg`, `PI / 2`, `-3 * PI / 4`) is an angle expression, read by
    // the same parser as the TOML strings, which ignores spaces. The tokens are printed
    // the way rustc prints them, so that an error quotes them much as they were written.
    let text = tokens.into_iter().collect::<TokenStream>().to_string();
    Ok(Value::Expr(text, loc))
}
