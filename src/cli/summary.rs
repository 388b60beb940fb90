//! The lines `apply` ends with and an interrupted `clear` says, in the command line's words
//! (the Python package's `str(report)` and its interrupted message are the same lines).

use crate::draw::{ApplyReport, ClearReport, DrawMode, Picture};
use crate::layout::Style;
use vrep_maze_core::wording::Message;

/// What `clear` did, a line each, as the command prints them (after its warnings and the
/// stopped simulation): the idle rate restored, the user's objects left alone under the
/// maze dummy `parent`, the line template, the markers and the floor put back (the floor's
/// options worded by `word`), then what was removed (or, a dry run, would be).
pub fn clear_lines(
    report: &ClearReport,
    parent: &str,
    dry_run: bool,
    word: impl Fn(&Message) -> String,
) -> Vec<String> {
    let verb = if dry_run { "would remove" } else { "removed" };
    let mut lines = Vec::new();
    if let Some(fps) = report.restored_idle_fps {
        lines.push(format!(
            "restored the idle rate to {fps} fps (an interrupted apply had left it at 0)"
        ));
    }
    lines.extend(crate::draw::left_alone_line(&report.left_alone, parent));
    lines.extend(report.template.iter().cloned());
    lines.extend(report.markers.iter().cloned());
    lines.extend(report.floor.as_ref().map(word));
    if report.removed.is_empty() && report.removed_meshes.is_empty() {
        lines.push(format!(
            "nothing to remove: no maze (copies of lines, walls, posts, or meshes) under {parent} in the scene"
        ));
    }
    lines.extend(copies_line(verb, &report.removed));
    lines.extend(mesh_line(verb, &report.removed_meshes));
    lines
}

/// What an interrupted `clear` did: `placed` of `total` maze objects removed.
pub fn clear_interrupted(placed: usize, total: usize) -> String {
    format!(
        "interrupted: {placed} of {total} maze objects removed, {} remain; the idle rate is restored",
        total - placed
    )
}

/// What an interrupted `apply` of `picture` counts, in the words its progress uses: "lines
/// placed", "walls and posts placed" (copies), "line runs drawn" (meshes). The command line
/// and the Python package say "interrupted: N of M {this}" alike.
pub fn interrupted_counts(picture: &Picture) -> String {
    match picture {
        Picture::Copies(d) => match (d.style, d.posts.is_empty()) {
            (Style::Lines, _) => "lines placed",
            (Style::Walls, true) => "walls placed",
            (Style::Walls, false) => "walls and posts placed",
        }
        .into(),
        Picture::Mesh(m) => match m.style {
            Style::Lines => "line runs drawn",
            Style::Walls => "wall runs and posts drawn",
        }
        .into(),
    }
}

/// What `apply` did, in one line: the counts of [`ApplyReport`] and the cost.
pub fn apply_line(report: &ApplyReport) -> String {
    let posts = if report.posts > 0 {
        format!(" and {} posts", report.posts)
    } else {
        String::new()
    };
    let cost = format!(
        "{} round trip(s), {:.2} s",
        report.round_trips,
        report.elapsed.as_secs_f64()
    );
    if report.dry_run && report.nothing_to_do() {
        let what = if report.mode == DrawMode::Mesh {
            format!("{} mesh(es)", report.meshes)
        } else {
            format!("{} {}{posts}", report.pieces, report.style.name())
        };
        return format!(
            "nothing to do: the scene already shows this layout ({what}, markers in place); {cost}"
        );
    }
    let verb = if report.dry_run { "would draw" } else { "drew" };
    // Start and End, and the line template where it is no line of copies (on the first
    // line of a mesh maze, under `Start` in a one-cell maze): counted with them
    let what = if report.markers_unchanged + report.markers_placed > 2 {
        "Start, End and the line template"
    } else {
        "markers"
    };
    let markers = format!(
        "{what}: {} already in place, {} placed",
        report.markers_unchanged, report.markers_placed
    );
    if report.mode == DrawMode::Mesh {
        return format!(
            "{verb} {} {} runs{posts} as {} mesh(es): {} kept, {} created; {markers}; {} earlier object(s) removed; {cost}",
            report.pieces,
            report.style.name().trim_end_matches('s'),
            report.meshes,
            report.reused,
            report.pasted,
            report.removed,
        );
    }
    let kept = kept(report);
    let meshes = if report.removed_meshes > 0 {
        format!(
            "; {} object(s) of an earlier mesh maze removed",
            report.removed_meshes
        )
    } else {
        String::new()
    };
    format!(
        "{verb} {} {}{posts}: {kept}, {} pasted; {markers}; {} earlier copies removed{meshes}; {cost}",
        report.pieces,
        report.style.name(),
        report.pasted,
        report.removed,
    )
}

/// A copies draw's kept lines and posts: "0 kept", or "N kept (the template and M earlier
/// copies: K already in place, P placed, U set unread, ...)".
fn kept(report: &ApplyReport) -> String {
    let kept = report.unchanged + report.placed;
    let template = kept > report.reused;
    let of = match (template, report.reused) {
        (_, _) if kept == 0 => String::new(),
        (true, 0) => "the template: ".to_string(),
        (true, n) => format!("the template and {n} earlier copies: "),
        (false, n) => format!("{n} earlier copies: "),
    };
    if kept == 0 {
        return "0 kept".to_string();
    }
    let unread = if report.unread > 0 {
        format!(
            ", {} set unread, as reading costs what setting does",
            report.unread
        )
    } else {
        String::new()
    };
    format!(
        "{kept} kept ({of}{} already in place, {} placed{unread})",
        report.unchanged,
        report.placed - report.unread
    )
}

/// "removed N maze copies: a, b, ... (M more)", naming the first dozen; `None` when none
/// were removed.
fn copies_line(verb: &str, removed: &[String]) -> Option<String> {
    if removed.is_empty() {
        return None;
    }
    let shown: Vec<&str> = removed.iter().take(12).map(String::as_str).collect();
    let more = if removed.len() > shown.len() {
        format!(", ... ({} more)", removed.len() - shown.len())
    } else {
        String::new()
    };
    Some(format!(
        "{verb} {} maze cop{}: {}{more}",
        removed.len(),
        if removed.len() == 1 { "y" } else { "ies" },
        shown.join(", ")
    ))
}

/// The line that says a mesh maze (`apply --draw mesh`) went: its meshes and their holder.
fn mesh_line(verb: &str, removed: &[String]) -> Option<String> {
    let meshes: Vec<&str> = removed
        .iter()
        .map(String::as_str)
        .filter(|n| *n != crate::draw::mesh::HOLDER)
        .collect();
    if removed.is_empty() {
        return None;
    }
    if meshes.is_empty() {
        return Some(format!(
            "{verb} the empty holder `{}` of a mesh maze",
            crate::draw::mesh::HOLDER
        ));
    }
    let shown = meshes
        .iter()
        .take(4)
        .copied()
        .collect::<Vec<_>>()
        .join(", ");
    let more = if meshes.len() > 4 {
        format!(", ... ({} more)", meshes.len() - 4)
    } else {
        String::new()
    };
    // the holder goes only if it is ours (it holds none of the user's objects)
    let holder = if meshes.len() < removed.len() {
        format!(" and their holder `{}`", crate::draw::mesh::HOLDER)
    } else {
        String::new()
    };
    Some(format!(
        "{verb} a mesh maze: {} mesh(es) ({shown}{more}){holder}",
        meshes.len(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::draw::mesh::MeshMaze;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::Grid;

    #[test]
    fn an_interrupted_apply_counts_what_its_mode_draws() {
        let layout = build_layout(&GenerateSpec::course(
            Grid::new(3, 3).unwrap(),
            Algorithm::Dfs,
            1,
        ))
        .unwrap();
        let copies = Picture::Copies(crate::draw::Drawing::try_from(&layout).unwrap());
        let mesh = Picture::Mesh(MeshMaze::try_from(&layout).unwrap());
        assert_eq!(interrupted_counts(&copies), "lines placed");
        assert_eq!(interrupted_counts(&mesh), "line runs drawn");
    }
}
