//! The compact passage encoding: one hex digit per cell, one string per row.

use crate::maze::{Grid, Maze};

/// The `passages.encoding` value of layout v1.
pub const ENCODING: &str =
    "hex digit per cell: 1 east, 2 north, 4 west, 8 south; passages[0] is row y = 0";

const DIGITS: &[u8; 16] = b"0123456789abcdef";

/// The passages of `maze`, encoded: one string per row, row 0 first.
pub fn encode(maze: &Maze) -> Vec<String> {
    let width = maze.grid().width() as usize;
    maze.masks()
        .chunks(width)
        .map(|row| row.iter().map(|&m| DIGITS[m as usize] as char).collect())
        .collect()
}

/// Checks that a layout's `passage_encoding` is the one this version reads.
pub fn check_encoding(encoding: &str) -> Result<(), String> {
    if encoding == ENCODING {
        Ok(())
    } else {
        Err(format!(
            "passage_encoding is \"{encoding}\"; this version reads \"{ENCODING}\""
        ))
    }
}

/// The maze that `rows` encode on `grid`, or the first problem found, naming the row
/// and column.
pub fn decode(grid: Grid, rows: &[String]) -> Result<Maze, String> {
    if rows.len() != grid.height() as usize {
        return Err(format!(
            "passages has {} rows but grid.rows is {}",
            rows.len(),
            grid.height()
        ));
    }
    let mut masks = Vec::with_capacity(grid.cell_count());
    for (y, row) in rows.iter().enumerate() {
        // a character that is no digit is named first: a multi-byte one (a Unicode digit)
        // is not a length problem
        let digits = row
            .chars()
            .enumerate()
            .map(|(x, ch)| {
                ch.to_digit(16)
                    .filter(|_| !ch.is_ascii_uppercase())
                    .ok_or_else(|| {
                        format!(
                            "passages[{y}] column {x}: '{}' (U+{:04X}) is not a hex digit 0-9a-f",
                            ch.escape_debug(),
                            u32::from(ch)
                        )
                    })
            })
            .collect::<Result<Vec<u32>, String>>()?;
        if digits.len() != grid.width() as usize {
            return Err(format!(
                "passages[{y}] has {} characters but grid.columns is {}",
                digits.len(),
                grid.width()
            ));
        }
        masks.extend(digits.into_iter().map(|d| d as u8));
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
        assert_eq!(encoded.len(), 4);
        assert_eq!(decode(maze.grid(), &encoded).unwrap(), maze);
    }

    #[test]
    fn names_the_bad_cell() {
        let grid = Grid::new(2, 1).unwrap();
        let rows = |r: &[&str]| r.iter().map(|s| s.to_string()).collect::<Vec<_>>();
        assert!(
            decode(grid, &rows(&["1g"]))
                .unwrap_err()
                .contains("column 1")
        );
        assert!(
            decode(grid, &rows(&["10"]))
                .unwrap_err()
                .contains("does not open West")
        );
        assert!(
            decode(grid, &rows(&["1"]))
                .unwrap_err()
                .contains("passages[0] has 1")
        );
        assert!(
            decode(grid, &rows(&["14", "00"]))
                .unwrap_err()
                .contains("2 rows")
        );
        let arabic_three = decode(grid, &rows(&["1\u{663}"])).unwrap_err();
        assert!(
            arabic_three.contains("column 1: '\u{663}' (U+0663) is not a hex digit"),
            "{arabic_three}"
        );
        let nul = decode(grid, &rows(&["\u{0}1"])).unwrap_err();
        assert!(nul.contains("'\\0' (U+0000)"), "{nul}");
        assert!(check_encoding("bits").is_err());
        assert!(check_encoding(ENCODING).is_ok());
    }
}
