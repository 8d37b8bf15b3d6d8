//! Seeded hostile variants of a description, for robustness tests: what a careless editor, a
//! broken generator or a truncated download makes of a good file.
//!
//! [`mutate`] applies one to three edits, chosen by the seed, to a TOML description and
//! returns the bytes (which need not be UTF-8): byte flips, truncation, deleted, duplicated
//! and swapped lines, values replaced by other types or by hostile numbers (NaN, ±inf, 1e308,
//! −0.0, integers beyond 64 bits, subnormals), huge arrays, a hundred links more, deep nesting,
//! unknown keys and invalid UTF-8. The edits know the format's structure (lines, `key =
//! value`, `[[links]]`) so that most variants get past the TOML parser and reach validation.
//! The same seed gives the same variant everywhere (SplitMix64, no dependency).
//!
//! ```
//! use dhgen_description::hostile::mutate;
//! let text = "name = \"arm\"\nconvention = \"standard\"\n[[links]]\njoint = \"revolute\"\na = 1\nalpha = 0\nd = 0\ntheta = 0\n";
//! assert_eq!(mutate(text, 7), mutate(text, 7));
//! // Loading a variant gives a robot or an error, never a panic.
//! let bytes = mutate(text, 7);
//! if let Ok(variant) = std::str::from_utf8(&bytes) {
//!     let _ = dhgen_description::RobotModel::from_toml_str(variant);
//! }
//! ```

use dhgen_kernel::stream::Stream;

/// Values put in place of a value: other types, and numbers no validator should let through.
const HOSTILE_VALUES: &[&str] = &[
    "nan",
    "-nan",
    "inf",
    "-inf",
    "+inf",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "1e400",
    "-0.0",
    "0",
    "5e-324",
    "1e-320",
    "99999999999999999999",
    "-9223372036854775808",
    "9223372036854775807",
    "0x7FFFFFFFFFFFFFFF",
    "0xFFFFFFFFFFFFFFFF",
    "1e10",
    "-1e10",
    "\"1e308*pi\"",
    "\"pi/1e-320\"",
    "\"pi/0\"",
    "\"90deg\"",
    "\"-pi/2\"",
    "\"\"",
    "\"revolute\"",
    "\"prismatic\"",
    "\"modified\"",
    "\"spherical\"",
    "true",
    "false",
    "[]",
    "[1, 2]",
    "[1, 2, 3]",
    "[nan, inf, -inf]",
    "[\"a\", \"b\", \"c\"]",
    "[[1, 2], [3, 4]]",
    "{}",
    "{ xx = 1 }",
    "{ xx = -1, yy = 1, zz = 1 }",
    "{ xx = 1e308, yy = 1e308, zz = 1e308 }",
    "{ inertia = 1e-4, gear = 1e200 }",
    "{ viscous = -1 }",
    "{ radius = 0 }",
    "{ xyz = [0, 0, 1e308], rpy = [0, 0, 0] }",
    "1979-05-27T07:32:00Z",
];

/// Lines inserted whole: unknown keys, stray tables, headers.
const HOSTILE_LINES: &[&str] = &[
    "frobnicate = 1",
    "[[links]]",
    "[links]",
    "[inertia]",
    "allow_nonphysical_inertia = true",
    "allow_nonphysical_inertia = \"yes\"",
    "gravity = [0, 0, -1e308]",
    "limits = [1, -1]",
    "limits = [-1e10, 1e10]",
    "mass = -1",
    "motor = { inertia = 1e-4, gear = 0 }",
    "collision = { radius = -1 }",
    "joint = \"revolute\"",
    "a = ",
    "= 1",
    "\"unterminated",
    "[[",
    "x = [1, 2,",
    "x = { a = 1",
];

fn below(s: &mut Stream, n: usize) -> usize {
    ((s.next_f64() * n as f64) as usize).min(n.saturating_sub(1))
}

/// One to three seeded edits of `text` (see the [module docs](self)); the result may be any
/// bytes.
pub fn mutate(text: &str, seed: u64) -> Vec<u8> {
    let mut s = Stream(seed ^ 0x0005_EED0_FBAD_F11E);
    let mut out: Vec<u8> = text.as_bytes().to_vec();
    let edits = 1 + below(&mut s, 3);
    for _ in 0..edits {
        out = edit(&mut s, out);
    }
    out
}

/// The value part of a `key = value` line, as a byte range, when the line has one.
fn value_range(line: &[u8]) -> Option<(usize, usize)> {
    let eq = line.iter().position(|&b| b == b'=')?;
    let start = eq + 1 + line[eq + 1..].iter().take_while(|&&b| b == b' ').count();
    (start < line.len()).then_some((start, line.len()))
}

fn edit(s: &mut Stream, bytes: Vec<u8>) -> Vec<u8> {
    let mut lines: Vec<Vec<u8>> = bytes.split(|&b| b == b'\n').map(<[u8]>::to_vec).collect();
    let n = lines.len().max(1);
    match below(s, 14) {
        // Flip one byte to a random one (often invalid UTF-8).
        0 if !bytes.is_empty() => {
            let mut b = bytes;
            let i = below(s, b.len());
            b[i] = (s.next_f64() * 256.0) as u8;
            return b;
        }
        // Flip one byte to a character TOML gives meaning to.
        1 if !bytes.is_empty() => {
            let mut b = bytes;
            let i = below(s, b.len());
            b[i] = s.pick(b"=[]{}\",.#\\'-+e0\n\t ");
            return b;
        }
        // Truncate anywhere (mid-string, mid-number, mid-UTF-8 sequence).
        2 => {
            let mut b = bytes;
            let i = below(s, b.len() + 1);
            b.truncate(i);
            return b;
        }
        // Delete a line.
        3 if lines.len() > 1 => {
            lines.remove(below(s, n));
        }
        // Duplicate a line (a duplicated key, or a new empty link).
        4 => {
            let i = below(s, n);
            let line = lines[i].clone();
            lines.insert(i, line);
        }
        // Swap two lines (keys move between tables).
        5 => {
            let (i, j) = (below(s, n), below(s, n));
            lines.swap(i, j);
        }
        // Replace a value by another type or a hostile number (twice as likely).
        6 | 7 => {
            let i = below(s, n);
            if let Some((a, b)) = value_range(&lines[i]) {
                let v = s.pick(HOSTILE_VALUES).as_bytes();
                lines[i].splice(a..b, v.iter().copied());
            }
        }
        // Scale a number by a power of ten from 1e-400 to 1e400, or negate it.
        8 => {
            let i = below(s, n);
            if let Some((a, b)) = value_range(&lines[i]) {
                let exponent = (s.next_f64() * 800.0) as i32 - 400;
                let suffix = if s.next_f64() < 0.5 {
                    format!("e{exponent}")
                } else {
                    String::new()
                };
                let value = String::from_utf8_lossy(&lines[i][a..b]).into_owned();
                let new = if suffix.is_empty() {
                    format!("-{value}")
                } else {
                    format!(
                        "{}{suffix}",
                        value.trim_end_matches(|c: char| !c.is_ascii_digit())
                    )
                };
                lines[i].splice(a..b, new.bytes());
            }
        }
        // A huge array in place of a value.
        9 => {
            let i = below(s, n);
            if let Some((a, b)) = value_range(&lines[i]) {
                let len = 1 + below(s, 5_000);
                let mut v = b"[".to_vec();
                for _ in 0..len {
                    v.extend_from_slice(b"0.5, ");
                }
                v.push(b']');
                lines[i].splice(a..b, v);
            }
        }
        // Deep nesting: arrays or inline tables thousands of levels deep.
        10 => {
            let i = below(s, n);
            if let Some((a, b)) = value_range(&lines[i]) {
                let depth = 1 + below(s, 5_000);
                let (open, close): (&[u8], &[u8]) = if s.next_f64() < 0.5 {
                    (b"[", b"]")
                } else {
                    (b"{ x = ", b" }")
                };
                let mut v = Vec::new();
                for _ in 0..depth {
                    v.extend_from_slice(open);
                }
                v.push(b'1');
                for _ in 0..depth {
                    v.extend_from_slice(close);
                }
                lines[i].splice(a..b, v);
            }
        }
        // Up to a hundred links more: the last `[[links]]` table repeated.
        11 => {
            if let Some(start) = lines.iter().rposition(|l| l.starts_with(b"[[links]]")) {
                let block = lines[start..].to_vec();
                for _ in 0..1 + below(s, 120) {
                    lines.extend(block.iter().cloned());
                }
            }
        }
        // Insert a hostile line.
        12 => {
            let i = below(s, n + 1);
            lines.insert(i, s.pick(HOSTILE_LINES).as_bytes().to_vec());
        }
        // Invalid UTF-8 or control characters inside a line.
        _ => {
            let i = below(s, n);
            let at = below(s, lines[i].len() + 1);
            let junk: &[u8] = s.pick(&[&[0xFF_u8][..], &[0xC3], &[0xE2, 0x82], &[0], &[0x1B]]);
            lines[i].splice(at..at, junk.iter().copied());
        }
    }
    lines.join(&b'\n')
}
