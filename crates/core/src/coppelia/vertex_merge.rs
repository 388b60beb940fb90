//! How much work CoppeliaSim does to merge a new mesh's coincident vertices, counted as the
//! steps of its search: a model input, since that work depends on where the vertices lie and
//! in which order they come, not only on how many there are.
//!
//! Every mesh made by `sim.createMeshShape` (4.5.1) or `sim.createShape` (4.10) goes through
//! `CMeshRoutines::removeDuplicateVerticesAndTriangles` (`meshRoutines.cpp:1790-1838` at
//! coppeliasim-v4.10.0-rev0, the same at v4.5.1-rev4), with the default
//! `identicalVertexTolerance` of 1e-6 m (`userSettings.cpp`). As read there, it first deals the
//! vertices out of the two halves of the list in turn (the first vertex of each half, then
//! the second of each, ...), then puts them one by one into a 3-d tree that splits on x, y,
//! z, x, ... by depth, in that order, unbalanced. At each node the new vertex goes left when it
//! lies below the node's coordinate on the node's axis and right otherwise; but when the two
//! coordinates are within the tolerance on that axis and the vertices are not the same point,
//! both subtrees are searched for a match first. Vertices that share coordinates exactly (the
//! corners of posts on one row, of walls on one line) meet that case again and again, and
//! each meeting searches whole subtrees.
//!
//! [`merge_steps`] counts the nodes that procedure visits; `docs/measurements.md` "Where
//! posts spend their time" fits what a step costs on each build.

/// Vertices closer than this are one point (CoppeliaSim's default `identicalVertexTolerance`).
pub const TOLERANCE: f64 = 1e-6;

/// One point in the tree, with its two subtrees (below, not below), by index.
struct Node {
    at: [f64; 3],
    below: Option<u32>,
    above: Option<u32>,
}

/// The nodes the simulator visits merging the vertices (x, y, z each) of one mesh.
pub fn merge_steps(vertices: &[f32]) -> u64 {
    let points: Vec<[f64; 3]> = vertices
        .chunks_exact(3)
        .map(|v| [f64::from(v[0]), f64::from(v[1]), f64::from(v[2])])
        .collect();
    let mut nodes: Vec<Node> = Vec::with_capacity(points.len());
    let mut steps = 0;
    let mut search = Vec::new();
    for p in dealt(&points) {
        if nodes.is_empty() {
            nodes.push(Node {
                at: p,
                below: None,
                above: None,
            });
            continue;
        }
        let (mut node, mut axis) = (0usize, 0usize);
        loop {
            steps += 1;
            let d = p[axis] - nodes[node].at[axis];
            if d.abs() < TOLERANCE {
                if distance(p, nodes[node].at) < TOLERANCE {
                    break;
                }
                search.clear();
                search.extend(
                    [nodes[node].below, nodes[node].above]
                        .into_iter()
                        .flatten()
                        .map(|n| (n, (axis + 1) % 3)),
                );
                let (found, seen) = find_near(&nodes, p, &mut search);
                steps += seen;
                if found {
                    break;
                }
            }
            let fresh = nodes.len() as u32;
            let next = if d < 0.0 {
                &mut nodes[node].below
            } else {
                &mut nodes[node].above
            };
            match *next {
                Some(n) => {
                    node = n as usize;
                    axis = (axis + 1) % 3;
                }
                None => {
                    *next = Some(fresh);
                    nodes.push(Node {
                        at: p,
                        below: None,
                        above: None,
                    });
                    break;
                }
            }
        }
    }
    steps
}

/// The vertices in the order the simulator puts them in its tree: the two halves of the list
/// dealt out in turn, and an odd last one last.
fn dealt(points: &[[f64; 3]]) -> impl Iterator<Item = [f64; 3]> + '_ {
    let half = points.len() / 2;
    (0..half)
        .flat_map(move |i| [points[i], points[half + i]])
        .chain(points.get(2 * half).copied())
}

/// Whether a node within the tolerance of `p` lies in the subtrees on `stack` (node, its
/// axis), searched depth first as the simulator does (stopping at the first found), and the
/// nodes visited.
fn find_near(nodes: &[Node], p: [f64; 3], stack: &mut Vec<(u32, usize)>) -> (bool, u64) {
    let mut seen = 0;
    while let Some((n, axis)) = stack.pop() {
        seen += 1;
        let node = &nodes[n as usize];
        let d = p[axis] - node.at[axis];
        if d.abs() < TOLERANCE && distance(p, node.at) < TOLERANCE {
            return (true, seen);
        }
        let next = (axis + 1) % 3;
        // pushed above first, so the side below is searched first
        if d > -TOLERANCE
            && let Some(a) = node.above
        {
            stack.push((a, next));
        }
        if d < TOLERANCE
            && let Some(b) = node.below
        {
            stack.push((b, next));
        }
    }
    (false, seen)
}

fn distance(a: [f64; 3], b: [f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_in_general_position_cost_their_depth() {
        // dealt: (0,0,0) (4,4,4) (2,1,3) (1,3,2), each walking to a leaf: (4,4,4) right of
        // the root on x; (2,1,3) right, then below (4,4,4) on y; (1,3,2) right, below on y,
        // then below (2,1,3) on z
        let v = [0., 0., 0., 2., 1., 3., 4., 4., 4., 1., 3., 2.];
        assert_eq!(merge_steps(&v), 1 + 2 + 3);
    }

    #[test]
    fn a_repeated_point_is_found_where_it_was_put() {
        let v = [1., 2., 3., 5., 5., 5., 1., 2., 3., 5., 5., 5.];
        // dealt: a, a, b, b: the second a is found at the root (1 step); b goes right of the
        // root (1 step), the second b walks root, then a match at b (2 steps)
        assert_eq!(merge_steps(&v), 1 + 1 + 2);
    }

    #[test]
    fn shared_coordinates_search_both_sides_and_cost_far_more() {
        // 64 points on one line of x (all x equal) against the same points turned off every
        // axis: the first searches every subtree at each insertion
        let line: Vec<f32> = (0..64).flat_map(|k| [0.0, k as f32, 0.0]).collect();
        let turned: Vec<f32> = (0..64)
            .flat_map(|k| [k as f32 * 0.37, k as f32, k as f32 * 0.61])
            .collect();
        let (a, b) = (merge_steps(&line), merge_steps(&turned));
        assert!(a > 3 * b, "shared x: {a} steps, general: {b}");
    }
}
