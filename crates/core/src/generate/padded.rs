//! The walk grid of the random-walk generators (Aldous-Broder, Wilson): one byte per
//! cell in a grid padded with a one-cell frame of off-grid markers, so a walk step is a
//! table offset and one byte test, with no bounds arithmetic.

use crate::maze::Grid;

/// One byte per cell plus a frame; cell (x, y) lives at `(y + 1) * stride + x + 1`.
pub(super) struct PaddedGrid {
    /// The bytes, frame included.
    pub bytes: Vec<u8>,
    /// Offsets of one step in each of `Direction::ALL` (east, north, west, south).
    pub offsets: [isize; 4],
    width: usize,
    stride: usize,
}

impl PaddedGrid {
    /// Cells of `grid` set to `inside`, the frame to `frame`.
    pub fn new(grid: Grid, inside: u8, frame: u8) -> Self {
        let width = grid.width() as usize;
        let height = grid.height() as usize;
        let stride = width + 2;
        let mut bytes = vec![frame; stride * (height + 2)];
        for y in 0..height {
            let row = (y + 1) * stride + 1;
            bytes[row..row + width].fill(inside);
        }
        Self {
            bytes,
            offsets: [1, stride as isize, -1, -(stride as isize)],
            width,
            stride,
        }
    }

    /// The padded position of the cell with row-major index `cell`.
    pub fn position(&self, cell: usize) -> usize {
        (cell / self.width + 1) * self.stride + cell % self.width + 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_frame_surrounds_the_cells() {
        let padded = PaddedGrid::new(Grid::new(3, 2).unwrap(), 0, 9);
        assert_eq!(padded.bytes.len(), 5 * 4);
        assert_eq!(padded.bytes.iter().filter(|&&b| b == 0).count(), 6);
        assert_eq!(padded.position(0), 6);
        assert_eq!(padded.position(5), 13);
        for cell in 0..6 {
            let at = padded.position(cell);
            assert_eq!(padded.bytes[at], 0);
        }
        // West of cell 0 and south of cell 0 are frame.
        assert_eq!(
            padded.bytes[padded.position(0).wrapping_add_signed(padded.offsets[2])],
            9
        );
        assert_eq!(
            padded.bytes[padded.position(0).wrapping_add_signed(padded.offsets[3])],
            9
        );
    }
}
