//! The compact passage encoding: one hex digit per cell, one string per row.

use super::Passages;
use crate::maze::{Grid, Maze};

/// The `passages.encoding` value of layout v1.
pub const ENCODING: &str = "hex digit per cell: 1 east, 2 north, 4 west, 8 south; rows[0] is y = 0";

const DIGITS: &[u8; 16] = b"0123456789abcdef";

/// The passages of `maze`, encoded.
pub fn encode(maze: &Maze) -> Passages {
    let width = maze.grid().width() as usize;
    let rows = maze
        .masks()
        .chunks(width)
        .map(|row| row.iter().map(|&m| DIGITS[m as usize] as char).collect())
        .collect();
    Passages {
        encoding: ENCODING.to_string(),
        rows,
    }
}

/// The maze that `passages` encodes on `grid`, or the first problem found, naming the
/// row and column.
pub fn decode(grid: Grid, passages: &Passages) -> Result<Maze, String> {
    if passages.encoding != ENCODING {
        return Err(format!(
            "passages.encoding is \"{}\"; this version reads \"{ENCODING}\"",
            passages.encoding
        ));
    }
    if passages.rows.len() != grid.height() as usize {
        return Err(format!(
            "passages.rows has {} rows but grid.rows is {}",
            passages.rows.len(),
            grid.height()
        ));
    }
    let mut masks = Vec::with_capacity(grid.cell_count());
    for (y, row) in passages.rows.iter().enumerate() {
        if row.len() != grid.width() as usize {
            return Err(format!(
                "passages.rows[{y}] has {} characters but grid.columns is {}",
                row.chars().count(),
                grid.width()
            ));
        }
        for (x, ch) in row.chars().enumerate() {
            let digit = ch
                .to_digit(16)
                .filter(|_| !ch.is_ascii_uppercase())
                .ok_or_else(|| {
                    format!("passages.rows[{y}] column {x}: '{ch}' is not a hex digit 0-9a-f")
                })?;
            masks.push(digit as u8);
        }
    }
    Maze::from_masks(grid, masks).map_err(|e| format!("passages: {e}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::{Algorithm, generate};

    #[test]
    fn round_trips() {
        let maze = generate(Grid::new(7, 4).unwrap(), Algorithm::Prim, 1);
        let encoded = encode(&maze);
        assert_eq!(encoded.rows.len(), 4);
        assert_eq!(decode(maze.grid(), &encoded).unwrap(), maze);
    }

    #[test]
    fn names_the_bad_cell() {
        let grid = Grid::new(2, 1).unwrap();
        let mut p = Passages {
            encoding: ENCODING.into(),
            rows: vec!["1g".into()],
        };
        assert!(decode(grid, &p).unwrap_err().contains("column 1"));
        p.rows = vec!["10".into()];
        assert!(decode(grid, &p).unwrap_err().contains("does not open West"));
        p.rows = vec!["1".into()];
        assert!(decode(grid, &p).unwrap_err().contains("rows[0] has 1"));
        p.rows = vec!["14".into(), "00".into()];
        assert!(decode(grid, &p).unwrap_err().contains("2 rows"));
    }
}
