//! What a draw of either mode tells as it goes ([`Stage`]) and when it is done
//! ([`ApplyReport`]).

use std::time::Duration;

use vrep_maze_core::layout::Style;

/// How a maze is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DrawMode {
    /// One copy of the template per line, wall or post (`apply()`).
    #[default]
    Copies,
    /// A few mesh shapes, one rectangle or box per straight run (`mesh::apply()`).
    Mesh,
}

/// Progress of `apply()`, for a progress display.
#[derive(Debug, Clone, PartialEq)]
pub enum Stage {
    /// The missing objects were created (`Job::create_missing`): their names.
    Created(Vec<String>),
    /// The scene has been read (names resolved, objects listed).
    Surveyed,
    /// Copies pasted so far / to paste.
    Pasting {
        /// Copies pasted so far.
        done: usize,
        /// Copies this apply pastes in all.
        total: usize,
    },
    /// Lines, or walls and posts, placed so far (parent and pose sent, or found in place) / in
    /// all.
    Placing {
        /// Lines (or walls and posts) placed so far.
        done: usize,
        /// Lines (or walls and posts) in the drawing.
        total: usize,
    },
    /// The work planned, before any change: [`super::estimate::copies_draw`] prices it.
    Planned(super::estimate::CopiesWork),
    /// Reading back.
    Verifying,
}

/// What `apply()` did. In copies mode the counts add up: `pieces + posts` = `unchanged +
/// placed + pasted` (the drawing's lines and posts), and `unchanged + placed` = `reused`,
/// plus the template itself in a line maze with lines; the markers are counted apart.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ApplyReport {
    /// Copies or meshes: how the maze was drawn (what `meshes`, `reused` and `pasted` count).
    pub mode: DrawMode,
    /// Lines or walls: what `pieces` counts.
    pub style: Style,
    /// Lines drawn (template included), or walls.
    pub pieces: usize,
    /// Posts drawn (a wall maze with posts), else 0.
    pub posts: usize,
    /// Mesh mode (`--draw mesh`): the meshes the maze is drawn as (then `pieces` and `posts`
    /// count rectangles and boxes, `reused` meshes kept, `pasted` meshes created); 0 in
    /// copies mode.
    pub meshes: usize,
    /// Earlier copies reused (kept), the template not counted; [`DrawMode::Mesh`]: meshes
    /// kept.
    pub reused: usize,
    /// Copies pasted; [`DrawMode::Mesh`]: meshes created.
    pub pasted: usize,
    /// Earlier copies removed (the surplus, another style's copies); mesh mode: the
    /// earlier meshes and copies removed.
    pub removed: usize,
    /// Copies mode: the objects of an earlier mesh maze removed (its meshes and their
    /// holder), counted apart from the copies.
    pub removed_meshes: usize,
    /// Lines and posts kept (the template, reused copies) that were already in place: no
    /// edit sent. Mesh mode: the meshes kept.
    pub unchanged: usize,
    /// Lines and posts kept whose pose (or parent) was sent: found elsewhere, or a pose the
    /// backend had not read (ZeroMQ sends a reused copy's pose rather than read it first).
    pub placed: usize,
    /// Of `placed`: poses sent unread, perhaps in place already (ZeroMQ reads a copy's pose
    /// no more cheaply than it sets it, one round trip each, so it sets it unread).
    pub unread: usize,
    /// Markers already in place: `Start`, `End` and the line template where it is not a
    /// line (hidden under `Start` in a one-cell maze; in mesh mode, on the first line).
    pub markers_unchanged: usize,
    /// Markers whose pose was sent (or, on a dry run, would be).
    pub markers_placed: usize,
    /// Edits sent.
    pub edits: usize,
    /// Round trips.
    pub round_trips: usize,
    /// Wall time.
    pub elapsed: Duration,
    /// The simulation was running when the scene was read.
    pub simulation_running: bool,
    /// The simulation was stopped first.
    pub stopped_simulation: bool,
    /// Dry run: nothing was changed.
    pub dry_run: bool,
    /// What the user should know: markers larger than a cell, sizes not read
    /// (`fit::check_sizes`).
    pub warnings: Vec<String>,
    /// The floor grown to the layout's (`--resize-floor`, `floor::resize`): one
    /// line saying from what size to what.
    pub floor: Option<String>,
    /// The user's objects under the maze dummy (and root objects named like copies of a
    /// template but of another type): left alone (`ownership::sort_out`).
    pub left_alone: Vec<String>,
}

impl ApplyReport {
    /// `true` when the scene already shows the drawing: nothing to paste, remove or place,
    /// and no simulation to stop (on a dry run: nothing a real run would change).
    pub fn nothing_to_do(&self) -> bool {
        self.pasted == 0
            && self.removed == 0
            && self.removed_meshes == 0
            && self.placed == 0
            && self.markers_placed == 0
            && !self.simulation_running
            && self.floor.is_none()
    }
}

/// "left alone: N object(s) of yours under `Maze` that are no copies of a template: a, b,
/// ..." naming at most the first few, for the reports of `apply` and `clear` (`None` when
/// there are none).
pub fn left_alone_line(left_alone: &[String], parent: &str) -> Option<String> {
    const NAMED: usize = 8;
    if left_alone.is_empty() {
        return None;
    }
    let shown: Vec<&str> = left_alone.iter().take(NAMED).map(String::as_str).collect();
    let more = if left_alone.len() > NAMED {
        format!(", ... ({} more)", left_alone.len() - NAMED)
    } else {
        String::new()
    };
    Some(format!(
        "left alone: {} object(s) under `{parent}` or at the scene root that are no copies of a template (not the maze's): {}{more}",
        left_alone.len(),
        shown.join(", ")
    ))
}
