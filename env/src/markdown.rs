//! Markdown tables: the one writer of every table the lab prints (README settings tables,
//! reports, leaderboards, the paper study's RESULTS tables, mechanism cards).
//!
//! A table is a header of columns, each left- or right-aligned, and rows of cells:
//! `| a | b |`, then `|---|---:|`, then one line per row. Cells are written as given, with
//! `|` escaped so a cell never splits; no padding. Why not a table crate (`tabled`,
//! `comfy-table`): they pad every column to its widest cell, so one changed value re-flows a
//! whole committed table, and the README/RESULTS tables are compared byte for byte with
//! what the lab generates (tests regenerate them in place); GitHub renders either form the
//! same.

use std::fmt::Display;

/// How a column's cells are aligned (`---` or `---:` in the separator line).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Align {
    /// Text (`---`).
    Left,
    /// Numbers (`---:`).
    Right,
}

/// A Markdown table being built: columns, then rows.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Table {
    header: Vec<(String, Align)>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with these columns, every one left-aligned.
    pub fn new<S: Display>(columns: impl IntoIterator<Item = S>) -> Self {
        Table {
            header: columns
                .into_iter()
                .map(|c| (c.to_string(), Align::Left))
                .collect(),
            rows: Vec::new(),
        }
    }

    /// A table with these columns and alignments.
    pub fn aligned<S: Display>(columns: impl IntoIterator<Item = (S, Align)>) -> Self {
        Table {
            header: columns
                .into_iter()
                .map(|(c, a)| (c.to_string(), a))
                .collect(),
            rows: Vec::new(),
        }
    }

    /// Right-aligns the columns at `indices` (numbers), the others left.
    pub fn right(mut self, indices: impl IntoIterator<Item = usize>) -> Self {
        for i in indices {
            if let Some(c) = self.header.get_mut(i) {
                c.1 = Align::Right;
            }
        }
        self
    }

    /// Appends one row (as many cells as columns; a short row is filled with empty cells,
    /// extra cells are kept).
    pub fn row<S: Display>(&mut self, cells: impl IntoIterator<Item = S>) -> &mut Self {
        self.rows
            .push(cells.into_iter().map(|c| c.to_string()).collect());
        self
    }

    /// Number of rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Whether the table has no rows.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The table as Markdown text, each line ending in `\n`.
    pub fn render(&self) -> String {
        let line = |cells: &mut dyn Iterator<Item = String>| {
            let mut s = String::from("|");
            for c in cells {
                s.push(' ');
                s.push_str(&c.replace('|', "\\|"));
                s.push_str(" |");
            }
            s.push('\n');
            s
        };
        let mut out = line(&mut self.header.iter().map(|(c, _)| c.clone()));
        out.push('|');
        for (_, a) in &self.header {
            out.push_str(match a {
                Align::Left => "---|",
                Align::Right => "---:|",
            });
        }
        out.push('\n');
        for r in &self.rows {
            let n = r.len().max(self.header.len());
            out += &line(&mut (0..n).map(|i| r.get(i).cloned().unwrap_or_default()));
        }
        out
    }
}

impl std::fmt::Display for Table {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.render())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_table_is_its_header_separator_and_rows_with_pipes_escaped() {
        let mut t = Table::new(["model", "TD", "note"]).right([1]);
        t.row(["lstm125", "6", "a|b"]).row(["ddm", "12", ""]);
        assert_eq!(
            t.render(),
            "| model | TD | note |\n|---|---:|---|\n| lstm125 | 6 | a\\|b |\n| ddm | 12 |  |\n"
        );
        assert_eq!(t.len(), 2);
    }

    #[test]
    fn a_short_row_is_filled_and_an_empty_table_is_its_header() {
        let mut t = Table::new(["a", "b"]);
        assert_eq!(t.render(), "| a | b |\n|---|---|\n");
        t.row(["x"]);
        assert_eq!(t.render(), "| a | b |\n|---|---|\n| x |  |\n");
    }
}
