//! How long a copies draw takes on a real CoppeliaSim 4.5.1, before it starts: the work
//! `apply()` will make the simulator do, priced by the shared cost model
//! ([`vrep_maze_core::coppelia::cost`], every figure from `../shared/spec/real-coppeliasim-4.5.1.md`).
//! Pasting, re-parenting and removing each cost in proportion to the objects in the scene, so
//! a maze drawn as one object per line costs O(N²) on the server whatever the client does.

use std::time::Duration;

use vrep_maze_core::coppelia::cost::{CostModel, Op};
use vrep_maze_core::wording::{Message, Opt, Value};

/// Modelled times above this deserve a warning before drawing (issue 18: "before a copies
/// draw whose modelled time on a real simulator exceeds 10 s").
pub const SLOW_DRAW: Duration = Duration::from_secs(10);

/// Server time one legacy request may take: well within any reply timeout, and short enough
/// that a progress bar moves every couple of seconds.
pub const REQUEST_TIME: Duration = Duration::from_millis(1500);

/// The modelled server time of one pasted, re-parented and placed line over the legacy API in
/// a scene of `objects` objects (an upper bound: the maze dummy's children plus the
/// parentless objects are at most the objects in the scene).
pub fn legacy_line(objects: usize) -> Duration {
    let m = CostModel::measured();
    m.ops(&[
        Op::Paste { copies: 1, objects },
        Op::SetParent {
            children: objects,
            parentless: 0,
        },
        Op::Pose { objects },
    ]) + m.op(&Op::LegacyCommand) * 4
}

/// How many pieces (lines, walls or posts: a copy, or a parent and a pose) one legacy request
/// may carry so that the
/// simulator answers within [`REQUEST_TIME`] in a scene of `objects` objects (at least one).
pub fn legacy_pieces_per_request(objects: usize) -> usize {
    ((REQUEST_TIME.as_secs_f64() / legacy_line(objects).as_secs_f64()) as usize).max(1)
}

/// Which remote API carries the draw: the per-call costs differ.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RemoteApi {
    /// The legacy remote API: batched requests, each drawing command a little work.
    Legacy,
    /// The ZeroMQ remote API: one call per paste group, re-parenting and pose.
    Zmq,
}

/// What a copies draw will do, as `apply()` planned it after reading the scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CopiesWork {
    /// Objects the survey listed (the named ones, the maze's copies, parentless copies).
    pub objects: usize,
    /// Earlier copies removed.
    pub removed: usize,
    /// Objects placed without pasting (the template, reused copies, the markers).
    pub placed: usize,
    /// Copies pasted (each then re-parented under the maze dummy and placed).
    pub pasted: usize,
    /// Copies already under the maze dummy that stay (reused).
    pub kept_children: usize,
    /// Copy-paste calls per round ([`super::options::ApplyOptions::paste_blocks_per_round`]).
    pub blocks_per_round: usize,
}

/// The modelled time of `work` over `api` on a real CoppeliaSim 4.5.1 at idle fps 0 (apply
/// raises the idle rate first): removals first, then the pastes in rounds of
/// `blocks_per_round + 1` times the copies so far (over legacy at most
/// [`legacy_pieces_per_request`] a round), each round's copies re-parented and placed before
/// the next. Legacy pass floors (9 ms a request) are left out.
pub fn copies_draw(api: RemoteApi, work: &CopiesWork) -> Duration {
    let m = CostModel::measured();
    let mut objects = work.objects;
    let mut t = Duration::ZERO;
    // what one call or command adds besides its work, in a scene of `objects`
    let call = |objects: usize, set: bool| match api {
        RemoteApi::Legacy => m.op(&Op::LegacyCommand),
        RemoteApi::Zmq => {
            let base = if set { Op::ZmqSet } else { Op::ZmqCall };
            m.op(&base) + m.op(&Op::ZmqServe { objects })
        }
    };
    if work.removed > 0 {
        t += m.op(&Op::Remove {
            count: work.removed,
            objects,
        });
        t += match api {
            RemoteApi::Legacy => call(objects, false) * work.removed as u32,
            RemoteApi::Zmq => call(objects, false),
        };
        objects = objects.saturating_sub(work.removed);
    }
    // a pose is one ZeroMQ call, a position and an orientation command over legacy
    let place_calls: u32 = match api {
        RemoteApi::Legacy => 2,
        RemoteApi::Zmq => 1,
    };
    t += (m.op(&Op::Pose { objects }) + call(objects, true) * place_calls) * work.placed as u32;
    let mut children = work.kept_children;
    let mut sources = work.placed.max(1);
    let mut left = work.pasted;
    while left > 0 {
        let budget = match api {
            RemoteApi::Legacy => legacy_pieces_per_request(objects),
            RemoteApi::Zmq => usize::MAX,
        };
        let round = left.min(sources * work.blocks_per_round.max(1)).min(budget);
        let calls = round.div_ceil(sources);
        t += m.op(&Op::Paste {
            copies: round,
            objects,
        }) + call(objects, false) * calls as u32;
        objects += round;
        for k in 0..round {
            // the round's copies not placed yet are parentless, as are the course objects
            t += m.op(&Op::SetParent {
                children,
                parentless: round - k,
            }) + m.op(&Op::Pose { objects })
                + call(objects, true) * (1 + place_calls);
            children += 1;
        }
        sources += round;
        left -= round;
    }
    t
}

/// The one-line warning `apply` prints before a copies draw modelled to take more than
/// [`SLOW_DRAW`], or `None`.
pub fn slow_draw_warning(api: RemoteApi, work: &CopiesWork) -> Option<Message> {
    let t = copies_draw(api, work);
    (t > SLOW_DRAW).then(|| {
        Message::text(format!(
            "warning: drawing this maze as copies takes about {:.0} s on a real CoppeliaSim 4.5.1 (its work grows with the objects in the scene); ",
            t.as_secs_f64()
        ))
        .and_setting(Opt::Draw, Value::word("mesh"))
        .and(" draws it as a few meshes instead")
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The course scene's 5 objects plus `lines` lines of an earlier maze (its template
    /// included), redrawn as a maze of `want` lines.
    fn replace(lines: usize, want: usize) -> CopiesWork {
        let copies = lines.saturating_sub(1);
        let needed = want - 1;
        CopiesWork {
            objects: 4 + lines,
            removed: copies.saturating_sub(needed),
            placed: 3 + copies.min(needed),
            pasted: needed.saturating_sub(copies),
            kept_children: copies.min(needed),
            blocks_per_round: 16,
        }
    }

    /// Within a factor 0.75..1.33 of the real figure.
    fn close(api: RemoteApi, work: CopiesWork, real: f64) {
        let got = copies_draw(api, &work).as_secs_f64();
        assert!(
            (0.75..=1.33).contains(&(got / real)),
            "{work:?}: {got:.1} s modelled vs {real} s"
        );
    }

    #[test]
    fn the_estimate_follows_the_real_draws_of_the_spec() {
        // spec "Costs that grow with the scene", through vrep-maze (lines: 9x9 160,
        // 30x30 1,798, 60x60 7,198, 100x100 19,998)
        close(RemoteApi::Legacy, replace(7_198, 19_998), 62.1);
        close(RemoteApi::Legacy, replace(1_798, 7_198), 9.92);
        close(RemoteApi::Zmq, replace(160, 19_998), 139.8);
        close(RemoteApi::Zmq, replace(19_998, 160), 29.5);
        close(RemoteApi::Zmq, replace(19_998, 1_798), 32.4);
    }

    #[test]
    fn legacy_requests_carry_fewer_lines_as_the_scene_grows() {
        let (small, big) = (
            legacy_pieces_per_request(5),
            legacy_pieces_per_request(20_000),
        );
        assert!(small > 1_000 && (1..300).contains(&big), "{small} {big}");
        // a full request of lines stays within the budget
        let t = legacy_line(20_000) * big as u32;
        assert!(t <= REQUEST_TIME, "{t:?}");
        assert_eq!(legacy_pieces_per_request(usize::MAX / 2), 1);
    }

    #[test]
    fn only_slow_draws_are_warned_about() {
        use vrep_maze_core::wording::Part;
        let small = replace(1, 160);
        assert!(copies_draw(RemoteApi::Zmq, &small) < Duration::from_secs(1));
        assert_eq!(slow_draw_warning(RemoteApi::Zmq, &small), None);
        let big = slow_draw_warning(RemoteApi::Legacy, &replace(7_198, 19_998)).unwrap();
        assert!(
            big.parts()
                .iter()
                .any(|p| matches!(p, Part::Settings(s) if s[0].opt == Opt::Draw))
                && !big.to_string().contains('\n'),
            "{big}"
        );
        // nothing to do costs nothing
        let none = replace(160, 160);
        assert_eq!(none.pasted + none.removed, 0);
        assert!(copies_draw(RemoteApi::Legacy, &none) < Duration::from_millis(100));
    }
}
