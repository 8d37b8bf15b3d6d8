//! The description before validation: a small tree of values, each tagged with where it
//! came from.
//!
//! Both front ends produce this tree: the TOML reader (location = line and column, see
//! [`from_toml_text`]) and the `robot!` macro (location = a token's span). Validation then
//! runs once, on the tree, so the two forms accept exactly the same fields with the same
//! meanings, and every error can point back at its source.

/// A value of the description, with its source location `L`.
#[derive(Clone, Debug)]
pub enum Value<L> {
    /// A number (integers are widened).
    Number(f64, L),
    /// A quoted string.
    Str(String, L),
    /// A bare word, as written in the macro form (`revolute`, `standard`).
    Word(String, L),
    /// Several tokens of the macro form (`PI / 2`, `90 deg`, `f64::NAN`), as text: read as
    /// an angle where one is expected, an error anywhere else.
    Expr(String, L),
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
            | Value::Expr(_, l)
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
            Value::Expr(..) => "an expression",
            Value::Bool(..) => "a boolean",
            Value::Array(..) => "an array",
            Value::Table(..) => "a table",
        }
    }
}

/// A place in a text: 1-based line and column, the column counted in characters.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Position {
    /// Line, from 1.
    pub line: usize,
    /// Column, from 1, in characters (not bytes).
    pub column: usize,
}

impl core::fmt::Display for Position {
    /// `line:column`, the form editors and compilers use after a file name.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

/// Byte offsets to [`Position`]s: the start of every line, and marks of the column every
/// [`MARK_BYTES`] bytes within a line, each searched by bisection (the TOML and URDF readers
/// locate every value through one: O(log n) each, plus at most `MARK_BYTES` bytes counted in
/// characters, however long the line; a file on one line of megabytes is read in linear time).
pub(crate) struct LineIndex<'t> {
    text: &'t str,
    starts: Vec<usize>,
    /// `(byte offset, column in characters from 0)`, at every line start and then every
    /// `MARK_BYTES` bytes or so, on character boundaries.
    marks: Vec<(usize, usize)>,
}

/// Spacing of [`LineIndex`]'s column marks.
const MARK_BYTES: usize = 256;

impl<'t> LineIndex<'t> {
    pub(crate) fn new(text: &'t str) -> Self {
        let starts = core::iter::once(0)
            .chain(text.match_indices('\n').map(|(i, _)| i + 1))
            .collect();
        let mut marks = Vec::new();
        let (mut column, mut next) = (0, 0);
        for (i, c) in text.char_indices() {
            if i >= next {
                marks.push((i, column));
                next = i + MARK_BYTES;
            }
            if c == '\n' {
                // The next line's start is marked.
                (column, next) = (0, i + 1);
            } else {
                column += 1;
            }
        }
        LineIndex {
            text,
            starts,
            marks,
        }
    }

    pub(crate) fn position(&self, offset: usize) -> Position {
        let offset = offset.min(self.text.len());
        let line = self.starts.partition_point(|&s| s <= offset) - 1;
        // The last mark at or before `offset`: on its line, since every line start is one
        // (an offset at the very end of a text ending in a newline has none on its line).
        let (start, column) = match self.marks.partition_point(|&(b, _)| b <= offset) {
            0 => (self.starts[line], 0),
            k if self.marks[k - 1].0 >= self.starts[line] => self.marks[k - 1],
            _ => (self.starts[line], 0),
        };
        // Spans fall on character boundaries; should one not, count bytes rather than panic.
        let column = column
            + self
                .text
                .get(start..offset)
                .map_or(offset - start, |s| s.chars().count());
        Position {
            line: line + 1,
            column: column + 1,
        }
    }
}

/// Where the first byte that is not UTF-8 stands (`e` from `str::from_utf8(bytes)`): line and
/// column of the text before it, for the readers' "not UTF-8" errors.
pub fn utf8_error_position(bytes: &[u8], e: &core::str::Utf8Error) -> Position {
    let valid = core::str::from_utf8(&bytes[..e.valid_up_to()]).unwrap_or("");
    Position {
        line: valid.matches('\n').count() + 1,
        column: valid.rsplit('\n').next().unwrap_or("").chars().count() + 1,
    }
}

/// Text that is not a TOML document (or holds a number TOML does not allow): where, and
/// what is wrong, on one line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SyntaxError {
    /// Where the parser stopped.
    pub loc: Position,
    /// The TOML parser's message, its lines joined.
    pub message: String,
}

/// Parses TOML text into the tree, each value and key located by its line and column.
///
/// Entries keep their order in the text, so the first of several faults in a table is
/// the one reported.
pub fn from_toml_text(text: &str) -> Result<Table<Position>, SyntaxError> {
    use toml::de::{DeTable, DeValue};

    fn table(
        lines: &LineIndex<'_>,
        t: &DeTable<'_>,
        span: core::ops::Range<usize>,
    ) -> Result<Table<Position>, SyntaxError> {
        let mut entries = t.iter().collect::<Vec<_>>();
        // DeTable sorts its keys; the text's order is what a reader expects.
        entries.sort_by_key(|(k, _)| k.span().start);
        Ok(Table {
            entries: entries
                .into_iter()
                .map(|(k, v)| {
                    let key_loc = lines.position(k.span().start);
                    Ok((
                        k.get_ref().to_string(),
                        key_loc,
                        value(lines, v.get_ref(), v.span())?,
                    ))
                })
                .collect::<Result<_, SyntaxError>>()?,
            loc: lines.position(span.start),
        })
    }

    fn value(
        lines: &LineIndex<'_>,
        v: &DeValue<'_>,
        span: core::ops::Range<usize>,
    ) -> Result<Value<Position>, SyntaxError> {
        let loc = lines.position(span.start);
        Ok(match v {
            DeValue::String(s) => Value::Str(s.to_string(), loc),
            DeValue::Integer(i) => match integer(i.as_str(), i.radix()) {
                Some(x) => Value::Number(x, loc),
                None => {
                    return Err(SyntaxError {
                        loc,
                        message: format!(
                            "the integer `{}` is outside the 64-bit range of TOML integers; \
                             write it as a float, e.g. `1e20`",
                            i.as_str()
                        ),
                    });
                }
            },
            // The parser hands over the float's text without underscores: `1e3`, `-inf`,
            // `nan`, all of which Rust reads. A value too large for f64 reads as infinite
            // and is then rejected by validation with its location.
            DeValue::Float(f) => match f.as_str().parse::<f64>() {
                Ok(x) => Value::Number(x, loc),
                Err(_) => {
                    return Err(SyntaxError {
                        loc,
                        message: format!("cannot read the number `{}`", f.as_str()),
                    });
                }
            },
            DeValue::Boolean(b) => Value::Bool(*b, loc),
            DeValue::Datetime(d) => Value::Str(d.to_string(), loc),
            DeValue::Array(a) => Value::Array(
                a.iter()
                    .map(|item| value(lines, item.get_ref(), item.span()))
                    .collect::<Result<_, _>>()?,
                loc,
            ),
            DeValue::Table(t) => Value::Table(table(lines, t, span)?),
        })
    }

    /// Every number of the description is an f64. An integer is one of TOML's 64-bit
    /// signed integers (the TOML specification requires an error for any other), in decimal,
    /// hex, octal or binary; `None` when it is out of that range.
    fn integer(digits: &str, radix: u32) -> Option<f64> {
        // i64's range includes -2^63 only with its sign: parse signed.
        i64::from_str_radix(&digits.replace('_', ""), radix)
            .ok()
            .map(|i| i as f64)
    }

    let lines = LineIndex::new(text);
    let doc = DeTable::parse(text).map_err(|e| {
        // The parser's own message, without the quoted line it adds when displayed.
        let mut message = e
            .message()
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join("; ");
        // A URDF file under another name: say so rather than leave a TOML puzzle.
        if text
            .trim_start_matches(['\u{feff}', ' ', '\t', '\r', '\n'])
            .starts_with('<')
        {
            message.push_str("; this looks like XML (URDF): name the file .urdf");
        }
        SyntaxError {
            loc: lines.position(e.span().map_or(0, |s| s.start)),
            message,
        }
    })?;
    table(&lines, doc.get_ref(), doc.span())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn number(v: &Value<Position>) -> f64 {
        match v {
            Value::Number(x, _) => *x,
            other => panic!("expected a number, got {other:?}"),
        }
    }

    #[test]
    fn numbers_in_every_toml_form() {
        let t = from_toml_text("h = 0x1F\no = 0o17\nb = 0b101\nu = 1_000\nf = -2.5e-3\nn = -7\n")
            .unwrap();
        let values: Vec<f64> = t.entries.iter().map(|(_, _, v)| number(v)).collect();
        assert_eq!(values, [31.0, 15.0, 5.0, 1000.0, -2.5e-3, -7.0]);
        // TOML integers are 64-bit: beyond that is an error, at the number.
        let t = from_toml_text("big = -9223372036854775808").unwrap();
        assert_eq!(number(&t.entries[0].2), i64::MIN as f64);
        let e = from_toml_text("a = 1\nbig = 99999999999999999999").unwrap_err();
        assert_eq!(e.loc, Position { line: 2, column: 7 });
        assert!(e.message.contains("64-bit"), "{e:?}");
        let e = from_toml_text("big = 0xFFFFFFFFFFFFFFFF").unwrap_err();
        assert!(e.message.contains("64-bit"), "{e:?}");
    }

    /// Marks within long lines give the column a count from the line's start gives, at every
    /// character boundary: lines longer than several marks, multi-byte characters, CRLF, empty
    /// lines, a text with and without a final newline.
    #[test]
    fn column_marks_agree_with_counting_from_the_line_start() {
        let long: String = (0..2000)
            .map(|i| match i % 7 {
                0 => 'é',
                3 => '中',
                5 => '\r',
                _ => 'a',
            })
            .collect();
        for text in [
            format!("{long}\n\nx = 1\r\n{long}{long}\n"),
            format!("{long}é"),
            String::new(),
            "\n\n".to_string(),
        ] {
            let index = super::LineIndex::new(&text);
            for (offset, _) in text.char_indices().chain([(text.len(), ' ')]) {
                let before = &text[..offset];
                let line = before.matches('\n').count() + 1;
                let column = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
                assert_eq!(
                    index.position(offset),
                    Position { line, column },
                    "offset {offset}"
                );
            }
        }
    }

    #[test]
    fn positions_count_lines_and_characters() {
        let t = from_toml_text("a = 1\r\n\r\n[t]\nkey = \"é\"\nb = [1,\n  22]\n").unwrap();
        let (key, key_loc, value) = &t.entries[1];
        assert_eq!(key, "t");
        assert_eq!(*key_loc, Position { line: 3, column: 2 });
        let Value::Table(inner) = value else {
            panic!("expected a table")
        };
        assert_eq!(inner.loc, Position { line: 3, column: 1 });
        assert_eq!(*inner.entries[0].2.loc(), Position { line: 4, column: 7 });
        let Value::Array(items, loc) = &inner.entries[1].2 else {
            panic!("expected an array")
        };
        assert_eq!(*loc, Position { line: 5, column: 5 });
        assert_eq!(*items[1].loc(), Position { line: 6, column: 3 });
        assert_eq!(Position { line: 6, column: 3 }.to_string(), "6:3");
    }
}
