//! The description before validation: a small tree of values, each tagged with where it
//! came from.
//!
//! Both front ends produce this tree: the TOML reader (location = the file) and the
//! `robot!` macro (location = a token's span). Validation then runs once, on the tree, so
//! the two forms accept exactly the same fields with the same meanings, and every error
//! can point back at its source.

/// A value of the description, with its source location `L`.
#[derive(Clone, Debug)]
pub enum Value<L> {
    /// A number (integers are widened).
    Number(f64, L),
    /// A quoted string.
    Str(String, L),
    /// A bare word, as written in the macro form (`revolute`, `standard`).
    Word(String, L),
    /// `true` / `false`.
    Bool(bool, L),
    /// `[a, b, ...]`.
    Array(Vec<Value<L>>, L),
    /// `{ key = value, ... }`.
    Table(Table<L>),
}

/// A table: ordered entries `key = value`, each key with its own location.
#[derive(Clone, Debug)]
pub struct Table<L> {
    /// `(key, key location, value)`, in source order.
    pub entries: Vec<(String, L, Value<L>)>,
    /// Where the table itself is (for "missing field" errors).
    pub loc: L,
}

impl<L> Value<L> {
    /// The location of the value.
    pub fn loc(&self) -> &L {
        match self {
            Value::Number(_, l)
            | Value::Str(_, l)
            | Value::Word(_, l)
            | Value::Bool(_, l)
            | Value::Array(_, l) => l,
            Value::Table(t) => &t.loc,
        }
    }

    /// A short name of the value's kind, for error messages.
    pub fn kind(&self) -> &'static str {
        match self {
            Value::Number(..) => "a number",
            Value::Str(..) => "a string",
            Value::Word(..) => "a word",
            Value::Bool(..) => "a boolean",
            Value::Array(..) => "an array",
            Value::Table(..) => "a table",
        }
    }
}

/// Converts a parsed TOML document; every location is `()` (the caller knows the file).
pub fn from_toml(table: &toml::Table) -> Table<()> {
    fn value(v: &toml::Value) -> Value<()> {
        match v {
            toml::Value::String(s) => Value::Str(s.clone(), ()),
            toml::Value::Integer(i) => Value::Number(*i as f64, ()),
            toml::Value::Float(f) => Value::Number(*f, ()),
            toml::Value::Boolean(b) => Value::Bool(*b, ()),
            toml::Value::Datetime(d) => Value::Str(d.to_string(), ()),
            toml::Value::Array(a) => Value::Array(a.iter().map(value).collect(), ()),
            toml::Value::Table(t) => Value::Table(from_toml(t)),
        }
    }
    Table {
        entries: table
            .iter()
            .map(|(k, v)| (k.clone(), (), value(v)))
            .collect(),
        loc: (),
    }
}
