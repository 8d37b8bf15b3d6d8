//! Plain-text tables drawn with box-drawing characters, in the style of Robotics Toolbox's
//! printed DH tables, and the number formats the tables use.

/// How a column's cells are aligned.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Align {
    /// Text flush left (names).
    Left,
    /// Text flush right (numbers).
    Right,
}

/// A table: a header row and data rows, every row as wide as the header.
#[derive(Clone, Debug)]
pub struct Table {
    headers: Vec<String>,
    align: Vec<Align>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with the given column headers and alignments.
    pub fn new(columns: &[(&str, Align)]) -> Table {
        Table {
            headers: columns.iter().map(|(h, _)| (*h).to_string()).collect(),
            align: columns.iter().map(|(_, a)| *a).collect(),
            rows: Vec::new(),
        }
    }

    /// Appends a row; missing cells are left empty, extra cells are dropped.
    pub fn row(&mut self, cells: Vec<String>) {
        let mut cells = cells;
        cells.resize(self.headers.len(), String::new());
        self.rows.push(cells);
    }

    /// The table as text, one line per row plus the rules, ending with a newline.
    pub fn render(&self) -> String {
        let width = |s: &str| s.chars().count();
        let widths: Vec<usize> = (0..self.headers.len())
            .map(|c| {
                self.rows
                    .iter()
                    .map(|r| width(&r[c]))
                    .chain([width(&self.headers[c])])
                    .max()
                    .unwrap_or(0)
            })
            .collect();
        let rule = |left: char, mid: char, right: char| {
            let parts: Vec<String> = widths.iter().map(|w| "─".repeat(w + 2)).collect();
            format!("{left}{}{right}\n", parts.join(&mid.to_string()))
        };
        let line = |cells: &[String], header: bool| {
            let parts: Vec<String> = cells
                .iter()
                .zip(&widths)
                .zip(&self.align)
                .map(|((cell, &w), &a)| {
                    let pad = w - width(cell);
                    // Headers are centred, like Robotics Toolbox's.
                    let (before, after) = match (header, a) {
                        (true, _) => (pad / 2, pad - pad / 2),
                        (false, Align::Left) => (0, pad),
                        (false, Align::Right) => (pad, 0),
                    };
                    format!(" {}{cell}{} ", " ".repeat(before), " ".repeat(after))
                })
                .collect();
            format!("│{}│\n", parts.join("│"))
        };
        let mut out = rule('┌', '┬', '┐');
        out += &line(&self.headers, true);
        out += &rule('├', '┼', '┤');
        for r in &self.rows {
            out += &line(r, false);
        }
        out += &rule('└', '┴', '┘');
        out
    }
}

/// A number with at most `decimals` decimals and no trailing zeros: `0.4318`, `0`, `-9.81`.
pub fn trimmed(x: f64, decimals: usize) -> String {
    // Magnitudes from 1e9 in scientific notation: `1.5e20`, not 21 digits.
    if x.is_finite() && x.abs() >= 1e9 {
        let s = format!("{x:.decimals$e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        return format!("{mantissa}e{exponent}");
    }
    let s = format!("{x:.decimals$}");
    let s = if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    };
    if s == "-0" { "0".to_string() } else { s }
}

/// An angle in radians shown in degrees: `90°`, `-22.5°`.
pub fn degrees(rad: f64) -> String {
    format!("{}°", trimmed(rad.to_degrees(), 2))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_trimmed() {
        assert_eq!(trimmed(0.431_800, 6), "0.4318");
        assert_eq!(trimmed(0.0, 6), "0");
        assert_eq!(trimmed(-1e-9, 6), "0");
        assert_eq!(trimmed(12.0, 3), "12");
        assert_eq!(trimmed(1.5e300, 6), "1.5e300");
        assert_eq!(trimmed(-2e9, 2), "-2e9");
        assert_eq!(trimmed(f64::INFINITY, 2), "inf");
        assert_eq!(degrees(core::f64::consts::FRAC_PI_2), "90°");
        assert_eq!(degrees(-core::f64::consts::PI / 8.0), "-22.5°");
    }

    #[test]
    fn columns_line_up() {
        let mut t = Table::new(&[("j", Align::Left), ("value", Align::Right)]);
        t.row(vec!["1".into(), "0.5".into()]);
        t.row(vec!["12".into(), "-100.25".into()]);
        let text = t.render();
        let widths: Vec<usize> = text.lines().map(|l| l.chars().count()).collect();
        assert!(widths.iter().all(|w| *w == widths[0]), "{text}");
        assert!(text.contains("│ 12 │ -100.25 │"), "{text}");
        assert!(text.contains("│ 1  │     0.5 │"), "{text}");
    }
}
