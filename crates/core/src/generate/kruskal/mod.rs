//! Randomized Kruskal: knock down walls in random order unless that would make a loop.

mod union_find;
mod walls;

use std::sync::mpsc;

use fixedbitset::FixedBitSet;

use super::Generator;
use crate::maze::Maze;
use crate::rng::MazeRng;
use walls::Walls;

/// Shuffles every inner wall, then opens each wall, in shuffled order, whose two cells
/// are not yet joined (a union-find tells).
///
/// It runs from both ends of the shuffled list at once. The opened walls are the minimum
/// spanning tree of the grid weighted by shuffled position (unique: no two positions are
/// equal), so the walls left standing, with the border, are the maximum spanning tree of
/// the corners, the planar dual: a wall can as well be decided from the back of the list,
/// last first, standing when its two corners are not yet joined. A wall's fate then
/// depends only on the walls before it (front) or after it (back), so the two parts run
/// on two threads: the shuffle, which finishes the list from the back, hands finished
/// chunks to the back part as it goes, and the front part starts once the shuffle is
/// done. Where the list is split never changes the maze (the golden files pin it); on
/// one thread the parts simply run in turn.
///
/// Memory: one `u32` per wall (about two per cell), a union-find of four bytes per cell
/// for each part and two bits per wall: about 17.5 bytes per cell with the maze.
#[derive(Debug, Clone, Copy, Default)]
pub struct Kruskal;

/// The share of the shuffled walls decided from the front, in hundredths: the front half
/// waits for the shuffle, the back half does not, so the front gets less.
const FRONT_PERCENT: usize = 40;

/// Walls handed from the shuffle to the back half at a time.
const CHUNK: usize = 1 << 15;

impl Generator for Kruskal {
    fn carve(&self, maze: &mut Maze, rng: &mut MazeRng) {
        let walls = Walls::new(maze.grid());
        let mut list = walls.list();
        // At least the first wall is decided from the front: it is never a shuffle step.
        let front = (list.len() * FRONT_PERCENT / 100).max(1);
        let (chunks_out, chunks_in) = mpsc::channel::<&mut [u32]>();
        // The channel is unbounded, so the front never waits for the back: if no second
        // thread is free, rayon runs the back after the front on this one.
        let (mut opened, back_opened) = rayon::join(
            || {
                let mut rest = &mut list[..];
                while rest.len() > front {
                    let steps = CHUNK.min(rest.len() - front);
                    rng.shuffle_back(rest, steps);
                    let (head, done) = rest.split_at_mut(rest.len() - steps);
                    chunks_out
                        .send(done)
                        .expect("the back half outlives the shuffle");
                    rest = head;
                }
                drop(chunks_out);
                rng.shuffle(rest);
                decide_front(&walls, rest)
            },
            || decide_back(&walls, chunks_in),
        );
        opened.union_with(&back_opened);
        walls.for_each_opened(&opened, |index, dir| maze.carve_inside(index, dir));
    }
}

/// Kruskal from the front: a wall opens when its cells are not yet joined.
fn decide_front(walls: &Walls, front: &[u32]) -> FixedBitSet {
    let mut opened = FixedBitSet::with_capacity(walls.name_count());
    let ends = |wall| walls.cells(wall);
    walls.cell_sets().union_each(front, ends, |wall, joined| {
        if joined {
            opened.insert(wall as usize);
        }
    });
    opened
}

/// Kruskal on the corners from the back, chunk by chunk (each turned round, so its last
/// wall comes first): a wall stays when its corners are not yet joined, and opens otherwise.
fn decide_back(walls: &Walls, chunks: mpsc::Receiver<&mut [u32]>) -> FixedBitSet {
    let mut opened = FixedBitSet::with_capacity(walls.name_count());
    let mut corners = walls.corner_sets();
    let ends = |wall| walls.corners(wall);
    for chunk in chunks {
        chunk.reverse();
        corners.union_each(chunk, ends, |wall, joined| {
            if !joined {
                opened.insert(wall as usize);
            }
        });
    }
    opened
}
