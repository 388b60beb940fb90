//! Gymnasium-Robotics' PointMaze/AntMaze keyword arguments (`.pointmaze.json`): the layout's
//! block grid ([`crate::layout::block_grid`]) as `maze_map`, one row a line, and the
//! `maze_size_scaling` that would keep the layout's cell size.

use crate::layout::block_grid::BlockGrid;

/// The JSON object: `maze_map` is what `gymnasium.make("PointMaze_UMaze-v3", maze_map=...)`
/// takes; `maze_size_scaling` is for Gymnasium-Robotics' `MazeEnv` (PointMaze and AntMaze fix
/// their own block size).
pub fn document(blocks: &BlockGrid) -> String {
    let rows: Vec<String> = blocks
        .maze_map
        .iter()
        .map(|row| {
            format!(
                "    {}",
                serde_json::to_string(row).expect("blocks serialize")
            )
        })
        .collect();
    format!(
        "{{\n  \"maze_map\": [\n{}\n  ],\n  \"maze_size_scaling\": {}\n}}\n",
        rows.join(",\n"),
        serde_json::to_string(&blocks.maze_size_scaling).expect("a finite float")
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::block_grid::Block;

    #[test]
    fn is_json_with_one_row_a_line() {
        let blocks = BlockGrid {
            maze_map: vec![
                vec![Block::Wall; 3],
                vec![Block::Wall, Block::Reset, Block::Wall],
                vec![Block::Wall; 3],
            ],
            maze_size_scaling: 0.25,
        };
        let text = document(&blocks);
        assert!(text.contains("\n    [1,\"r\",1],\n"), "{text}");
        let value: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(value["maze_size_scaling"], 0.25);
        assert_eq!(value["maze_map"][1][1], "r");
    }
}
