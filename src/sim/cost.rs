//! The modeled server work of scene operations: how long a real CoppeliaSim 4.5.1 is busy
//! with each, from O(1) counts the scene keeps (objects in the scene, children of a parent,
//! parentless objects, handles in a call). Pure functions; the servers sleep what they return
//! when [`Timing`] asks for realistic costs. Every figure cites
//! `../shared/spec/real-coppeliasim-4.5.1.md` (the spec folder beside this repository).
//!
//! # Legacy drawing ("Drawing cost on the server (legacy API, idle fps 0)")
//!
//! In the core, `setObjectParent` costs O(children of the new parent + parentless objects)
//! (coppeliaSimLib `sceneObjectContainer.cpp:1110-1157`, `sceneObject.cpp:4676-4724`), the
//! largest term by reading the source; setting a position or orientation is O(1). Each pasted
//! copy's lowest free `Line<N>` name is found by a scan of the scene
//! (`sceneObjectContainer.cpp:108-175`), but the spec's own figures bound that scan to next to
//! nothing: `sim.copyPasteObjects` of 8,000 handles into a scene of some 8,000 objects took
//! 37.8 ms in all ("ZeroMQ costs at idle fps 0"), about 5 µs a copy, so the per-object growth
//! is put on re-parenting alone. Per line:
//!
//! ```text
//! paste          p
//! set parent     q  + c1 · (children of the new parent + parentless objects)
//! set position   x
//! set orientation o
//! c0 = p + q + x + o = 0.25 + 0.20 + 0.09 + 0.09 = 0.63 ms,  c1 = 127 ns per object
//! ```
//!
//! fitted to the table, plus [`CostModel::legacy_pass_floor`] (9 ms) per pass that executed
//! a command (the "legacy blocking call ... idle fps 0: 9–10 ms" row of "Pacing"). With our
//! client's pattern (pastes first, then one request with every set-parent, set-position and
//! set-orientation) into the course scene (5 objects, all parentless), L lines cost about
//! `c0·L + c1·(L² + 5·L)` plus the passes (while they are parented, `Maze`'s children and
//! the parentless copies add up to L):
//!
//! | maze | lines | passes | modeled | measured |
//! |---|---|---|---|---|
//! | 9x9 | 160 | 7 | 0.17 s | 0.35 s |
//! | 30x30 | 1,798 | 6 | 1.60 s | 1.54 s |
//! | 45x45 | 4,048 | 8 | 4.72 s | 5.6 s |
//! | 60x60 | 7,198 | 6 | 11.2 s | 11.1 s |
//! | 100x100 | 19,998 | – | 63.7 s | no reply within 60 s |
//!
//! The 9x9 row is dominated by time outside the server's drawing work (about 0.18 s the
//! model does not explain: connection, survey, verification on the client side).
//!
//! # ZeroMQ ("ZeroMQ costs at idle fps 0")
//!
//! A call costs about 0.45 ms (`sim.getObject`, `sim.getObjectPose`, `sim.setObjectPose`,
//! `sim.removeObjects` of one handle; `sim.setObjectParent` / `sim.setObjectPose` 0.33–0.45
//! ms whatever the scene size). Bulk calls follow the measured points, linearly between them
//! and beyond the last with the last slope: `sim.copyPasteObjects` of N handles 4.5 / 11.6 /
//! 37.8 ms at 500 / 2,000 / 8,000, `sim.removeObjects` of N 1.0 / 7.3 / 18.4 ms;
//! `sim.getObjectsInTree(Maze, -1, 3)` 0.3 ms, 0.9 ms with 500 children (0.3 ms + 1.2 µs per
//! handle returned).

use std::time::Duration;

/// Whether the emulated servers take the time a real CoppeliaSim takes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// The modeled server work of each operation; `None`: every operation is instant.
    pub costs: Option<CostModel>,
    /// Legacy API: after a session that did not end with the kill command (connection reset,
    /// end of file, the 10 s idle timeout, a protocol error), the port refuses every
    /// connection for this long. Spec "Connections (legacy API)": "a client that leaves
    /// abruptly ... makes the port refuse every connection for about 60 s (measured 62–65
    /// s)"; "while the simulation runs, after a client ended on an error ... 43–60 s". The
    /// cause: the server's socket in TIME_WAIT and a re-bind without SO_REUSEADDR retried
    /// every 2.5 s (simExtRemoteApi `inConnection.cpp:243-277`, `simxSocket.cpp:544-554`).
    pub reconnect_penalty: Duration,
}

impl Default for Timing {
    /// [`Timing::instant`]: the library's default, so tests stay fast.
    fn default() -> Self {
        Timing::instant()
    }
}

impl Timing {
    /// No modeled costs and no reconnect penalty (the main loop still passes at the idle rate).
    pub fn instant() -> Timing {
        Timing {
            costs: None,
            reconnect_penalty: Duration::ZERO,
        }
    }

    /// What a real CoppeliaSim 4.5.1 takes: [`CostModel::measured`] and a 60 s reconnect
    /// penalty (spec "Connections (legacy API)", measured 62–65 s).
    pub fn realistic() -> Timing {
        Timing {
            costs: Some(CostModel::measured()),
            reconnect_penalty: Duration::from_secs(60),
        }
    }

    /// The modeled cost, or zero when instant.
    pub fn cost(&self, f: impl FnOnce(&CostModel) -> Duration) -> Duration {
        self.costs.as_ref().map_or(Duration::ZERO, f)
    }
}

/// The constants of the cost model (see the module documentation for the fit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CostModel {
    /// Legacy: one pasted copy, besides naming it.
    pub paste: Duration,
    /// Legacy: one set-parent, besides the scan of the siblings and parentless objects.
    pub set_parent: Duration,
    /// Legacy: one set-position.
    pub set_position: Duration,
    /// Legacy: one set-orientation.
    pub set_orientation: Duration,
    /// Per object re-parenting walks (children of the new parent, parentless objects).
    pub per_object: Duration,
    /// Legacy: the least time a main-loop pass that executed commands takes at idle fps 0
    /// (spec "Pacing": a legacy blocking call at idle fps 0 takes 9–10 ms).
    pub legacy_pass_floor: Duration,
    /// ZeroMQ: one call (spec "Pacing": about 0.45 ms at idle fps 0).
    pub zmq_call: Duration,
    /// ZeroMQ: one `sim.setObjectParent` or `sim.setObjectPose` (spec "ZeroMQ costs at idle
    /// fps 0": 0.33–0.45 ms per call, the middle of that range).
    pub zmq_set: Duration,
    /// ZeroMQ `sim.getObjectsInTree`: the call, and per handle returned (spec "ZeroMQ costs":
    /// 0.3 ms, 0.9 ms with 500 children).
    pub zmq_tree: Duration,
    /// See [`CostModel::zmq_tree`].
    pub zmq_tree_per_handle: Duration,
}

/// `sim.copyPasteObjects` of N handles, ms (spec "ZeroMQ costs", the 1-handle point is the
/// per-call cost of "Pacing").
const ZMQ_COPY_PASTE: [(f64, f64); 4] = [(1.0, 0.45), (500.0, 4.5), (2000.0, 11.6), (8000.0, 37.8)];
/// `sim.removeObjects` of N handles, ms (spec "ZeroMQ costs" and "Pacing").
const ZMQ_REMOVE: [(f64, f64); 4] = [(1.0, 0.45), (500.0, 1.0), (2000.0, 7.3), (8000.0, 18.4)];

fn us(micros: u64) -> Duration {
    Duration::from_micros(micros)
}

/// Piecewise-linear through `points` (sorted by x), extended with the first and last slopes.
fn interpolate(points: &[(f64, f64)], x: f64) -> f64 {
    let i = points
        .windows(2)
        .position(|w| x <= w[1].0)
        .unwrap_or(points.len() - 2);
    let ((x0, y0), (x1, y1)) = (points[i], points[i + 1]);
    (y0 + (y1 - y0) * (x - x0) / (x1 - x0)).max(0.0)
}

fn ms(v: f64) -> Duration {
    Duration::from_secs_f64(v.max(0.0) / 1000.0)
}

impl CostModel {
    /// The fit to the spec tables (module documentation).
    pub fn measured() -> CostModel {
        CostModel {
            paste: us(250),
            set_parent: us(200),
            set_position: us(90),
            set_orientation: us(90),
            per_object: Duration::from_nanos(127),
            legacy_pass_floor: Duration::from_millis(9),
            zmq_call: us(450),
            zmq_set: us(390),
            zmq_tree: us(300),
            zmq_tree_per_handle: Duration::from_nanos(1200),
        }
    }

    fn scan(&self, objects: u64) -> Duration {
        Duration::from_nanos(self.per_object.as_nanos() as u64 * objects)
    }

    /// Legacy: pasting `n` copies (into a scene of any size: see the module documentation on
    /// naming).
    pub fn legacy_paste(&self, n: usize) -> Duration {
        self.paste * n as u32
    }

    /// Legacy: one set-parent to a parent with `children` children, `parentless` objects in
    /// the scene.
    pub fn legacy_set_parent(&self, children: usize, parentless: usize) -> Duration {
        self.set_parent + self.scan((children + parentless) as u64)
    }

    /// ZeroMQ `sim.copyPasteObjects` of `n` handles.
    pub fn zmq_copy_paste(&self, n: usize) -> Duration {
        ms(interpolate(&ZMQ_COPY_PASTE, n.max(1) as f64))
    }

    /// ZeroMQ `sim.removeObjects` of `n` handles.
    pub fn zmq_remove(&self, n: usize) -> Duration {
        ms(interpolate(&ZMQ_REMOVE, n.max(1) as f64))
    }

    /// ZeroMQ `sim.getObjectsInTree` returning `n` handles.
    pub fn zmq_objects_in_tree(&self, n: usize) -> Duration {
        self.zmq_tree + self.zmq_tree_per_handle * n as u32
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Server work of our client's legacy draw of `lines` lines into the course scene
    /// (5 parentless objects): pastes first, then one request with every set-parent (to
    /// `Maze`), set-position and set-orientation; plus `passes` passes of at least the floor.
    fn legacy_draw(m: &CostModel, lines: usize, passes: u32) -> f64 {
        let course = 5;
        let mut t = m.legacy_paste(lines);
        for k in 0..lines {
            // `Maze` has k children; 5 + lines - k objects are still parentless
            t += m.legacy_set_parent(k, course + lines - k) + m.set_position + m.set_orientation;
        }
        t += m.legacy_pass_floor * passes;
        t.as_secs_f64()
    }

    #[test]
    fn the_legacy_model_reproduces_the_drawing_table() {
        let m = CostModel::measured();
        // spec "Drawing cost on the server (legacy API, idle fps 0)": lines, round trips, s
        for (lines, passes, measured) in [(1798, 6, 1.54), (4048, 8, 5.6), (7198, 6, 11.1)] {
            let modeled = legacy_draw(&m, lines, passes);
            let error = (modeled - measured).abs() / measured;
            assert!(
                error < 0.25,
                "{lines} lines: {modeled:.2} s vs {measured} s"
            );
        }
        // 9x9: the server's share of 0.35 s (the rest is outside the server's drawing work)
        let small = legacy_draw(&m, 160, 7);
        assert!((0.1..0.35).contains(&small), "{small}");
        // 100x100: no reply within 60 s
        assert!(legacy_draw(&m, 19_998, 1) > 60.0);
    }

    #[test]
    fn pasting_costs_per_copy_and_re_parenting_grows_with_the_parent_and_the_parentless() {
        let m = CostModel::measured();
        assert_eq!(m.legacy_paste(0), Duration::ZERO);
        assert_eq!(m.legacy_paste(2), m.paste * 2);
        assert_eq!(
            m.legacy_set_parent(3, 4),
            m.set_parent + Duration::from_nanos(127 * 7)
        );
        // the spec's bulk paste bounds the naming scan: 8,000 copies in 37.8 ms over ZeroMQ
        assert!(m.zmq_copy_paste(8000) < Duration::from_millis(40));
    }

    #[test]
    fn the_zmq_model_reproduces_the_cost_table() {
        let m = CostModel::measured();
        let close = |d: Duration, want_ms: f64| {
            let got = d.as_secs_f64() * 1000.0;
            assert!(
                (got - want_ms).abs() <= want_ms * 0.05,
                "{got} ms vs {want_ms} ms"
            );
        };
        // spec "ZeroMQ costs at idle fps 0"
        for (n, paste, remove) in [(500, 4.5, 1.0), (2000, 11.6, 7.3), (8000, 37.8, 18.4)] {
            close(m.zmq_copy_paste(n), paste);
            close(m.zmq_remove(n), remove);
        }
        close(m.zmq_objects_in_tree(0), 0.3);
        close(m.zmq_objects_in_tree(500), 0.9);
        // spec "Pacing": one call, or the removal of one handle, about 0.45 ms
        close(m.zmq_call, 0.45);
        assert!((0.33..=0.45).contains(&(m.zmq_set.as_secs_f64() * 1000.0)));
        close(m.zmq_remove(1), 0.45);
        close(m.zmq_remove(0), 0.45);
        // beyond the table: the last slope
        assert!(m.zmq_copy_paste(16_000) > m.zmq_copy_paste(8000));
    }

    #[test]
    fn instant_timing_costs_nothing_and_the_library_default_is_instant() {
        assert_eq!(Timing::default(), Timing::instant());
        assert_eq!(Timing::instant().cost(|m| m.zmq_call), Duration::ZERO);
        let real = Timing::realistic();
        assert_eq!(real.cost(|m| m.zmq_call), Duration::from_micros(450));
        assert_eq!(real.reconnect_penalty, Duration::from_secs(60));
    }
}
