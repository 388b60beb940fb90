//! The maze model: grids, the compact maze type, petgraph's view of it, and analysis.

pub mod analysis;
pub mod graph;
pub mod grid;
pub mod model;

pub use analysis::Metrics;
pub use grid::{Cell, Direction, Grid, GridError, MAX_CELLS};
pub use model::Maze;
