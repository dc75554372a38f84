//! Grid layouts: object placement, validation and precomputed move/adjacency tables.
//!
//! A layout is written row-major, rows separated by `/` (or newlines), one
//! character per cell:
//!
//! | char | object | ch0 code |
//! |------|--------|----------|
//! | `.`  | free cell | 0 |
//! | `O`  | onion dispenser | 3 |
//! | `D`  | delivery counter | 4 |
//! | `V`  | oven | 5 |
//! | `S`  | short delivery counter (bisection) | 4 |
//! | `L`  | long delivery counter (bisection) | 8 |
//! | `K`  | reward sink (dual task) | 6 |
//! | `B`  | manual oven-off button (uncertainty) | 8 |
//! | `3`  | third anchor counter (multi-anchor) | 9 |
//! | `4`  | fourth anchor counter (multi-anchor) | 10 |
//! | `W`  | second oven (multi-oven) | 9 |
//! | `X`  | third oven (multi-oven) | 12 |
//!
//! The codes are those of the single-oven tasks; the multi-anchor and multi-oven tasks
//! write the reference's own codes for their objects (the task spec maps them).
//!
//! Validation enforces the reference's implicit rule that interaction is
//! unambiguous: no free cell may touch two objects in its 4-neighbourhood.
//! It also requires the free cells to be connected and every object to be
//! reachable, so every start cell can complete the task.

use crate::action::Action;
use crate::error::EnvError;
use serde::{Deserialize, Serialize};

/// Largest supported grid side (cells are indexed with `u8`).
pub const MAX_SIDE: usize = 16;

/// Kinds of objects that can occupy a cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ObjectKind {
    /// Onion dispenser (code 3).
    OnionDispenser,
    /// Delivery counter (code 4).
    DeliveryCounter,
    /// Oven (code 5).
    Oven,
    /// Bisection "short" delivery counter (code 4).
    ShortCounter,
    /// Bisection "long" delivery counter (code 8).
    LongCounter,
    /// Dual-task reward sink (code 6).
    RewardSink,
    /// Uncertainty-task manual oven-off button (code 8).
    OvenButton,
    /// Multi-anchor: the counter of the third anchor.
    Counter3,
    /// Multi-anchor: the counter of the fourth anchor.
    Counter4,
    /// Multi-oven: the second oven (only the environment starts it).
    Oven2,
    /// Multi-oven: the third oven.
    Oven3,
}

impl ObjectKind {
    /// The kinds of the single-oven tasks, in one-hot channel order.
    pub const ALL: [ObjectKind; 7] = [
        ObjectKind::OnionDispenser,
        ObjectKind::DeliveryCounter,
        ObjectKind::Oven,
        ObjectKind::ShortCounter,
        ObjectKind::LongCounter,
        ObjectKind::RewardSink,
        ObjectKind::OvenButton,
    ];

    /// Every kind: [`ObjectKind::ALL`], then the multi-anchor counters and extra ovens.
    pub const EVERY: [ObjectKind; 11] = [
        ObjectKind::OnionDispenser,
        ObjectKind::DeliveryCounter,
        ObjectKind::Oven,
        ObjectKind::ShortCounter,
        ObjectKind::LongCounter,
        ObjectKind::RewardSink,
        ObjectKind::OvenButton,
        ObjectKind::Counter3,
        ObjectKind::Counter4,
        ObjectKind::Oven2,
        ObjectKind::Oven3,
    ];

    /// Reference code written in observation channel 0 by the single-oven tasks.
    pub fn code(self) -> u8 {
        match self {
            ObjectKind::OnionDispenser => 3,
            ObjectKind::DeliveryCounter | ObjectKind::ShortCounter => 4,
            ObjectKind::Oven => 5,
            ObjectKind::RewardSink => 6,
            ObjectKind::LongCounter | ObjectKind::OvenButton => 8,
            ObjectKind::Counter3 | ObjectKind::Oven2 => 9,
            ObjectKind::Counter4 => 10,
            ObjectKind::Oven3 => 12,
        }
    }

    /// The oven index of an oven kind (0, 1, 2), `None` for other kinds.
    pub fn oven_index(self) -> Option<usize> {
        match self {
            ObjectKind::Oven => Some(0),
            ObjectKind::Oven2 => Some(1),
            ObjectKind::Oven3 => Some(2),
            _ => None,
        }
    }

    /// The anchor index (0 … 3) of a multi-anchor counter kind (`S`, `L`, `3`, `4`).
    pub fn anchor_index(self) -> Option<usize> {
        match self {
            ObjectKind::ShortCounter => Some(0),
            ObjectKind::LongCounter => Some(1),
            ObjectKind::Counter3 => Some(2),
            ObjectKind::Counter4 => Some(3),
            _ => None,
        }
    }

    /// Layout character.
    pub fn symbol(self) -> char {
        match self {
            ObjectKind::OnionDispenser => 'O',
            ObjectKind::DeliveryCounter => 'D',
            ObjectKind::Oven => 'V',
            ObjectKind::ShortCounter => 'S',
            ObjectKind::LongCounter => 'L',
            ObjectKind::RewardSink => 'K',
            ObjectKind::OvenButton => 'B',
            ObjectKind::Counter3 => '3',
            ObjectKind::Counter4 => '4',
            ObjectKind::Oven2 => 'W',
            ObjectKind::Oven3 => 'X',
        }
    }

    /// Parses a layout character (`None` for a free cell `.`).
    fn from_symbol(c: char) -> Result<Option<Self>, char> {
        Ok(Some(match c {
            '.' => return Ok(None),
            'O' => ObjectKind::OnionDispenser,
            'D' => ObjectKind::DeliveryCounter,
            'V' => ObjectKind::Oven,
            'S' => ObjectKind::ShortCounter,
            'L' => ObjectKind::LongCounter,
            'K' => ObjectKind::RewardSink,
            'B' => ObjectKind::OvenButton,
            '3' => ObjectKind::Counter3,
            '4' => ObjectKind::Counter4,
            'W' => ObjectKind::Oven2,
            'X' => ObjectKind::Oven3,
            other => return Err(other),
        }))
    }

    /// Index of this kind in [`ObjectKind::EVERY`] (for the single-oven tasks, whose
    /// layouts hold only [`ObjectKind::ALL`], its one-hot channel).
    pub fn onehot_index(self) -> usize {
        Self::EVERY.iter().position(|&k| k == self).unwrap_or(0)
    }
}

/// A validated grid layout with precomputed tables for fast stepping.
#[derive(Debug, Clone, PartialEq)]
pub struct Layout {
    rows: usize,
    cols: usize,
    cells: Vec<Option<ObjectKind>>,
    free: Vec<u8>,
    /// `moves[cell][action]`: destination cell of each action from each cell.
    moves: Vec<[u8; 6]>,
    /// `adjacent[cell]`: the single object touching the cell, with its cell index.
    adjacent: Vec<Option<(ObjectKind, u8)>>,
}

impl Layout {
    /// Parses and validates a layout string (rows separated by `/` or newlines).
    pub fn parse(text: &str) -> Result<Self, EnvError> {
        let bad = |reason: String| EnvError::InvalidLayout { reason };
        let rows: Vec<&str> = text
            .split(['/', '\n'])
            .map(str::trim)
            .filter(|r| !r.is_empty())
            .collect();
        if rows.is_empty() {
            return Err(bad("the layout has no rows".into()));
        }
        let cols = rows[0].chars().count();
        if rows.len() > MAX_SIDE || cols > MAX_SIDE || cols == 0 {
            return Err(bad(format!(
                "{}x{} grid: rows and columns must be 1..={MAX_SIDE}",
                rows.len(),
                cols
            )));
        }
        let mut cells = Vec::with_capacity(rows.len() * cols);
        for (r, row) in rows.iter().enumerate() {
            if row.chars().count() != cols {
                return Err(bad(format!(
                    "row {r} has {} cells but row 0 has {cols}: rows must have equal length",
                    row.chars().count()
                )));
            }
            for (c, ch) in row.chars().enumerate() {
                let kind = ObjectKind::from_symbol(ch).map_err(|other| {
                    bad(format!(
                        "unknown cell character `{other}` at ({r},{c}) (allowed: . O D V S L K B 3 4 W X)"
                    ))
                })?;
                cells.push(kind);
            }
        }
        Self::from_cells(rows.len(), cols, cells)
    }

    /// Builds and validates a layout from row-major cells.
    pub fn from_cells(
        rows: usize,
        cols: usize,
        cells: Vec<Option<ObjectKind>>,
    ) -> Result<Self, EnvError> {
        let bad = |reason: String| EnvError::InvalidLayout { reason };
        if rows == 0 || cols == 0 || rows > MAX_SIDE || cols > MAX_SIDE {
            return Err(bad(format!(
                "{rows}x{cols} grid: rows and columns must be 1..={MAX_SIDE}"
            )));
        }
        if cells.len() != rows * cols {
            return Err(bad(format!(
                "{} cells given for a {rows}x{cols} grid",
                cells.len()
            )));
        }
        let idx = |r: usize, c: usize| r * cols + c;
        let neighbours = |cell: usize| {
            let (r, c) = (cell / cols, cell % cols);
            let mut out = [None; 4];
            if r > 0 {
                out[0] = Some(idx(r - 1, c));
            }
            if r + 1 < rows {
                out[1] = Some(idx(r + 1, c));
            }
            if c > 0 {
                out[2] = Some(idx(r, c - 1));
            }
            if c + 1 < cols {
                out[3] = Some(idx(r, c + 1));
            }
            out
        };
        let free: Vec<u8> = (0..cells.len())
            .filter(|&i| cells[i].is_none())
            .map(|i| i as u8)
            .collect();
        if free.is_empty() {
            return Err(bad("the layout has no free cell for the agent".into()));
        }
        let mut adjacent = vec![None; cells.len()];
        for &f in &free {
            let f = f as usize;
            let touching: Vec<usize> = neighbours(f)
                .into_iter()
                .flatten()
                .filter(|&n| cells[n].is_some())
                .collect();
            if touching.len() > 1 {
                let list: Vec<String> = touching
                    .iter()
                    .map(|&n| {
                        format!(
                            "{} at ({},{})",
                            cells[n].unwrap().symbol(),
                            n / cols,
                            n % cols
                        )
                    })
                    .collect();
                return Err(bad(format!(
                    "free cell ({},{}) touches {} objects ({}): each free cell may touch at most one object",
                    f / cols,
                    f % cols,
                    touching.len(),
                    list.join(", ")
                )));
            }
            if let Some(&n) = touching.first() {
                adjacent[f] = Some((cells[n].unwrap(), n as u8));
            }
        }
        // Connectivity of free cells (BFS from the first free cell).
        let mut seen = vec![false; cells.len()];
        let mut queue = vec![free[0] as usize];
        seen[free[0] as usize] = true;
        while let Some(cur) = queue.pop() {
            for n in neighbours(cur).into_iter().flatten() {
                if cells[n].is_none() && !seen[n] {
                    seen[n] = true;
                    queue.push(n);
                }
            }
        }
        if let Some(&cut) = free.iter().find(|&&f| !seen[f as usize]) {
            let cut = cut as usize;
            return Err(bad(format!(
                "free cell ({},{}) cannot be reached from ({},{}): free cells must be connected",
                cut / cols,
                cut % cols,
                free[0] as usize / cols,
                free[0] as usize % cols
            )));
        }
        for (i, kind) in cells.iter().enumerate() {
            if let Some(kind) = kind
                && !neighbours(i)
                    .into_iter()
                    .flatten()
                    .any(|n| cells[n].is_none())
            {
                return Err(bad(format!(
                    "object {} at ({},{}) has no free neighbour, so it can never be used",
                    kind.symbol(),
                    i / cols,
                    i % cols
                )));
            }
        }
        let moves = (0..cells.len())
            .map(|cell| {
                let (r, c) = ((cell / cols) as i32, (cell % cols) as i32);
                let mut row = [cell as u8; 6];
                for a in Action::ALL {
                    let (dr, dc) = a.delta();
                    let (nr, nc) = (r + dr, c + dc);
                    if nr >= 0 && nc >= 0 && (nr as usize) < rows && (nc as usize) < cols {
                        let n = idx(nr as usize, nc as usize);
                        if cells[n].is_none() {
                            row[a as usize] = n as u8;
                        }
                    }
                }
                row
            })
            .collect();
        Ok(Layout {
            rows,
            cols,
            cells,
            free,
            moves,
            adjacent,
        })
    }

    /// Number of rows.
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// Number of columns.
    pub fn cols(&self) -> usize {
        self.cols
    }

    /// Number of cells (`rows × cols`).
    pub fn n_cells(&self) -> usize {
        self.cells.len()
    }

    /// Object at a row-major cell index.
    pub fn object_at(&self, cell: usize) -> Option<ObjectKind> {
        self.cells[cell]
    }

    /// Row-major indices of the free cells, in row-major order.
    pub fn free_cells(&self) -> &[u8] {
        &self.free
    }

    /// Destination cell of `action` from `cell` (the same cell when blocked).
    #[inline]
    pub fn move_from(&self, cell: usize, action: Action) -> usize {
        self.moves[cell][action as usize] as usize
    }

    /// The object touching `cell`, with its cell index.
    #[inline]
    pub fn adjacent_object(&self, cell: usize) -> Option<(ObjectKind, usize)> {
        self.adjacent[cell].map(|(k, i)| (k, i as usize))
    }

    /// Row-major index of `(row, col)`.
    pub fn index(&self, row: usize, col: usize) -> usize {
        row * self.cols + col
    }

    /// `(row, col)` of a row-major index.
    pub fn coords(&self, cell: usize) -> (usize, usize) {
        (cell / self.cols, cell % self.cols)
    }

    /// The free cells as `(row, col)`, in row-major order (start cells of a protocol).
    pub fn free_coords(&self) -> Vec<(usize, usize)> {
        self.free.iter().map(|&c| self.coords(c as usize)).collect()
    }

    /// Cells holding `kind`.
    pub fn cells_of(&self, kind: ObjectKind) -> Vec<usize> {
        (0..self.cells.len())
            .filter(|&i| self.cells[i] == Some(kind))
            .collect()
    }

    /// Whether `(row, col)` is a free cell.
    pub fn is_free(&self, row: usize, col: usize) -> bool {
        row < self.rows && col < self.cols && self.cells[self.index(row, col)].is_none()
    }

    /// The layout as text, rows joined by `/` (parses back to the same layout).
    pub fn to_text(&self) -> String {
        (0..self.rows)
            .map(|r| {
                (0..self.cols)
                    .map(|c| self.cells[self.index(r, c)].map_or('.', ObjectKind::symbol))
                    .collect::<String>()
            })
            .collect::<Vec<_>>()
            .join("/")
    }

    /// Shortest-path distances (in moves) from every cell to `target`, `u32::MAX` if unreachable.
    pub fn distances_to(&self, target: usize) -> Vec<u32> {
        let mut dist = vec![u32::MAX; self.cells.len()];
        dist[target] = 0;
        let mut queue = std::collections::VecDeque::from([target]);
        while let Some(cur) = queue.pop_front() {
            for a in &Action::ALL[1..5] {
                // Moves are symmetric on a grid, so reverse BFS uses the same table.
                let n = self.move_from(cur, *a);
                if n != cur && dist[n] == u32::MAX {
                    dist[n] = dist[cur] + 1;
                    queue.push_back(n);
                }
            }
        }
        dist
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reference_fi_layout_parses() {
        let l = Layout::parse(".OD/.../V../.../...").unwrap();
        assert_eq!((l.rows(), l.cols()), (5, 3));
        assert_eq!(l.free_cells().len(), 12);
        assert_eq!(
            l.adjacent_object(l.index(1, 0)),
            Some((ObjectKind::Oven, 6))
        );
        assert_eq!(
            l.adjacent_object(l.index(0, 0)),
            Some((ObjectKind::OnionDispenser, 1))
        );
        assert_eq!(l.adjacent_object(l.index(4, 2)), None);
        assert_eq!(l.to_text(), ".OD/.../V../.../...");
        // Moving up from (1,1) is blocked by the onion dispenser.
        assert_eq!(l.move_from(l.index(1, 1), Action::Up), l.index(1, 1));
        assert_eq!(l.move_from(l.index(1, 1), Action::Down), l.index(2, 1));
    }

    #[test]
    fn two_objects_next_to_one_free_cell_is_rejected() {
        let err = Layout::parse("O.D/.../V..").unwrap_err();
        match err {
            EnvError::InvalidLayout { reason } => assert!(reason.contains("(0,1)"), "{reason}"),
            other => panic!("unexpected {other:?}"),
        }
    }

    #[test]
    fn malformed_layouts_are_rejected() {
        assert!(Layout::parse("").is_err());
        assert!(Layout::parse(".O/...").is_err());
        assert!(Layout::parse(".X.").is_err());
        assert!(Layout::parse("VVV").is_err());
        // Disconnected free cells (each touches only the oven).
        assert!(matches!(
            Layout::parse(".V."),
            Err(EnvError::InvalidLayout { reason }) if reason.contains("connected")
        ));
    }
}
