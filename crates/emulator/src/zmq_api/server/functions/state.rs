//! The simulation state (start, stop), integer parameters (program version, idle fps) and
//! integer and string signals.
//!
//! Signals differ between the generations. Protocol 1 (4.5.1) keeps a signal of any name
//! and its setters return nothing. Protocol 2 (4.10) keeps signals as scene properties: a
//! name that is no valid property name ([`is_property_name`]) is not stored, the setter
//! answers `[1]` all the same, and a getter of a signal that does not exist answers nothing
//! (`{}`), `../shared/spec/real-coppeliasim-4.10.md` "Signals are scene properties now".

use ciborium::Value;

use super::{Args, Ctx, Outcome, nothing, ret};
use crate::sim::SimState;
use crate::sim::property::is_property_name;
use crate::zmq_api::cbor::int;
use crate::zmq_api::message::Protocol;
use vrep_maze_core::coppelia::{
    INTPARAM_PROGRAM_VERSION, SIMULATION_ADVANCING_RUNNING, SIMULATION_PAUSED, SIMULATION_STOPPED,
};

/// The program version a protocol-2 server reports (CoppeliaSim 4.10.0); a protocol-1
/// server reports the scene model's 4.5.1.
const PROGRAM_VERSION_V2: i32 = 41000;

/// `sim.getSimulationState()`: `sim.simulation_stopped`, `_paused` or `_advancing_running`.
pub(super) fn get_simulation_state(ctx: &mut Ctx<'_>, _: &Args<'_>) -> Result<Outcome, String> {
    ret(vec![int(match ctx.sim.state {
        SimState::Stopped => SIMULATION_STOPPED,
        SimState::Paused => SIMULATION_PAUSED,
        SimState::Running => SIMULATION_ADVANCING_RUNNING,
    }
    .into())])
}

/// `sim.getSimulationTime()`: seconds of simulation time, whole steps (0 while stopped).
pub(super) fn get_simulation_time(ctx: &mut Ctx<'_>, _: &Args<'_>) -> Result<Outcome, String> {
    ret(vec![Value::Float(ctx.sim.time(std::time::Instant::now()))])
}

/// `sim.startSimulation()`: what is made from now on is removed on stop, and poses go back
/// (`Scene::end_run`).
pub(super) fn start_simulation(ctx: &mut Ctx<'_>, _: &Args<'_>) -> Result<Outcome, String> {
    ctx.sim.start();
    nothing()
}

/// `sim.stopSimulation()`: restores the scene. Over protocol 2, stopping a running
/// simulation is a blocking call, as with the add-on: the client waits through `_*wait*_`.
pub(super) fn stop_simulation(ctx: &mut Ctx<'_>, _: &Args<'_>) -> Result<Outcome, String> {
    let was_running = ctx.sim.stop();
    if was_running && ctx.protocol == Protocol::V2 {
        Ok(Outcome::WaitThen(vec![]))
    } else {
        nothing()
    }
}

/// The reply of a signal getter: the value, or for a signal that does not exist nil
/// (protocol 1) or nothing (protocol 2: see the module's doc).
fn signal_reply(ctx: &Ctx<'_>, value: Option<Value>) -> Result<Outcome, String> {
    match (value, ctx.protocol) {
        (Some(v), _) => ret(vec![v]),
        (None, Protocol::V1) => ret(vec![Value::Null]),
        (None, Protocol::V2) => nothing(),
    }
}

/// Whether a signal setter stores `name` (protocol 2: only a valid property name), and its
/// reply (protocol 2: `[1]`, stored or not). See the module's doc.
fn signal_set(ctx: &Ctx<'_>, name: &str) -> (bool, Result<Outcome, String>) {
    match ctx.protocol {
        Protocol::V1 => (true, nothing()),
        Protocol::V2 => (is_property_name(name), ret(vec![int(1)])),
    }
}

/// `sim.getInt32Signal(name)`: the value, or nil (protocol 2: nothing) when it is not set.
pub(super) fn get_int32_signal(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let value = ctx.sim.int_signals.get(a.text(0)?).copied();
    signal_reply(ctx, value.map(|v| int(v.into())))
}

/// `sim.setInt32Signal(name, value)` (protocol 2: a name that is no property name is
/// silently not stored).
pub(super) fn set_int32_signal(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let (name, value) = (a.text(0)?, a.int(1)?);
    let (stored, reply) = signal_set(ctx, name);
    if stored {
        ctx.sim.int_signals.insert(name.to_string(), value);
    }
    reply
}

/// `sim.clearInt32Signal(name)`; clearing an unset signal is no error.
pub(super) fn clear_int32_signal(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    ctx.sim.int_signals.remove(a.text(0)?);
    nothing()
}

/// `sim.getStringSignal(name)`: the value (text when it is UTF-8, else bytes), or nil
/// (protocol 2: nothing) when the signal is not set.
pub(super) fn get_string_signal(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let value = ctx.sim.string_signals.get(a.text(0)?).map(|v| {
        String::from_utf8(v.clone()).map_or_else(|e| Value::Bytes(e.into_bytes()), Value::Text)
    });
    signal_reply(ctx, value)
}

/// `sim.setStringSignal(name, value)`: the value as text or bytes (protocol 2: a name that
/// is no property name is silently not stored). Protocol 2 refuses bytes that are not
/// UTF-8: 4.10's add-on would never answer the signal's read (it fails to encode it and
/// restarts, losing the client's signals, `../shared/spec/real-coppeliasim-4.10.md` "The
/// remote APIs"); refusing at once makes such a write a clear error here instead of a hang.
pub(super) fn set_string_signal(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let name = a.text(0)?;
    let value = match a.get(1) {
        Some(Value::Text(t)) => t.clone().into_bytes(),
        Some(Value::Bytes(b)) => b.clone(),
        _ => return Err(a.bad(1, "a string")),
    };
    if ctx.protocol == Protocol::V2 && std::str::from_utf8(&value).is_err() {
        return Err(format!(
            "in {}: the value of string signal `{name}` is not UTF-8 (CoppeliaSim 4.10's add-on never answers its read)",
            a.func
        ));
    }
    let (stored, reply) = signal_set(ctx, name);
    if stored {
        ctx.sim.string_signals.insert(name.to_string(), value);
    }
    reply
}

/// `sim.clearStringSignal(name)`; clearing an unset signal is no error.
pub(super) fn clear_string_signal(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    ctx.sim.string_signals.remove(a.text(0)?);
    nothing()
}

/// `sim.getInt32Param(param)`: the program version (per protocol generation) and the
/// simulator's parameters.
pub(super) fn get_int32_param(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let p = a.int(0)?;
    if p == INTPARAM_PROGRAM_VERSION && ctx.protocol == Protocol::V2 {
        return ret(vec![int(PROGRAM_VERSION_V2.into())]);
    }
    match ctx.sim.int_param(p) {
        Some(v) => ret(vec![int(v.into())]),
        None => Err(format!("in {}: invalid parameter {p}.", a.func)),
    }
}

/// `sim.setInt32Param(param, value)`: the simulator's writable parameters (idle fps).
pub(super) fn set_int32_param(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let (p, v) = (a.int(0)?, a.int(1)?);
    if ctx.sim.set_int_param(p, v) {
        nothing()
    } else {
        Err(format!(
            "in {}: invalid parameter {p} or value {v}.",
            a.func
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Extras, call};
    use super::*;
    use crate::sim::{Scene, Simulator};
    use vrep_maze_core::coppelia::DEFAULT_IDLE_FPS;

    /// One call over `protocol`, on a shared simulator.
    fn on(sim: &mut Simulator, protocol: Protocol, func: &str, args: &[Value]) -> Outcome {
        call(sim, &mut Extras::default(), protocol, func, args)
    }

    #[test]
    fn protocol_2_silently_drops_a_signal_that_is_no_property_name() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let text = |s: &str| Value::Text(s.into());
        for name in ["vrep-maze.lease", "vrep_maze.lease"] {
            let set = on(
                &mut sim,
                Protocol::V2,
                "sim.setInt32Signal",
                &[text(name), int(7)],
            );
            assert_eq!(set, Outcome::Ret(vec![int(1)]), "{name}");
            let set = on(
                &mut sim,
                Protocol::V2,
                "sim.setStringSignal",
                &[text(name), text("x")],
            );
            assert_eq!(set, Outcome::Ret(vec![int(1)]), "{name}");
        }
        // the spec's table: nothing for the name with '-', the value for the other
        let get = |sim: &mut Simulator, f: &str, n: &str| on(sim, Protocol::V2, f, &[text(n)]);
        assert_eq!(
            get(&mut sim, "sim.getInt32Signal", "vrep-maze.lease"),
            Outcome::Ret(vec![])
        );
        assert_eq!(
            get(&mut sim, "sim.getStringSignal", "vrep-maze.lease"),
            Outcome::Ret(vec![])
        );
        assert_eq!(
            get(&mut sim, "sim.getInt32Signal", "vrep_maze.lease"),
            Outcome::Ret(vec![int(7)])
        );
        assert_eq!(
            get(&mut sim, "sim.getStringSignal", "vrep_maze.lease"),
            Outcome::Ret(vec![text("x")])
        );
        // protocol 1 (4.5.1) keeps any name, answers nothing to a setter and nil for no signal
        let set = on(
            &mut sim,
            Protocol::V1,
            "sim.setInt32Signal",
            &[text("a-b"), int(3)],
        );
        assert_eq!(set, Outcome::Ret(vec![]));
        assert_eq!(
            on(&mut sim, Protocol::V1, "sim.getInt32Signal", &[text("a-b")]),
            Outcome::Ret(vec![int(3)])
        );
        assert_eq!(
            on(&mut sim, Protocol::V1, "sim.getInt32Signal", &[text("c")]),
            Outcome::Ret(vec![Value::Null])
        );
    }

    #[test]
    fn protocol_2_refuses_a_string_signal_that_is_not_utf8() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let args = [Value::Text("s".into()), Value::Bytes(vec![0xff, 0x41])];
        let refused = on(&mut sim, Protocol::V2, "sim.setStringSignal", &args);
        assert!(
            matches!(&refused, Outcome::Err(e) if e.contains("not UTF-8")),
            "{refused:?}"
        );
        assert!(sim.string_signals.is_empty());
        assert_eq!(
            on(&mut sim, Protocol::V1, "sim.setStringSignal", &args),
            Outcome::Ret(vec![])
        );
        let read = on(&mut sim, Protocol::V1, "sim.getStringSignal", &args[..1]);
        assert_eq!(read, Outcome::Ret(vec![Value::Bytes(vec![0xff, 0x41])]));
    }

    #[test]
    fn protocol_1_reports_4_5_1_and_protocol_2_reports_4_10() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let mut x = Extras::default();
        let v1 = call(
            &mut sim,
            &mut x,
            Protocol::V1,
            "sim.getInt32Param",
            &[int(1)],
        );
        let v2 = call(
            &mut sim,
            &mut x,
            Protocol::V2,
            "sim.getInt32Param",
            &[int(1)],
        );
        assert_eq!(
            (v1, v2),
            (
                Outcome::Ret(vec![int(40501)]),
                Outcome::Ret(vec![int(41000)])
            )
        );
    }

    #[test]
    fn stopping_a_running_simulation_waits_over_protocol_2_only() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let mut x = Extras::default();
        for (protocol, stop) in [
            (Protocol::V2, Outcome::WaitThen(vec![])),
            (Protocol::V1, Outcome::Ret(vec![])),
        ] {
            call(&mut sim, &mut x, protocol, "sim.startSimulation", &[]);
            let Outcome::Ret(time) = call(&mut sim, &mut x, protocol, "sim.getSimulationTime", &[])
            else {
                panic!("sim.getSimulationTime returns")
            };
            assert!(
                matches!(time[..], [Value::Float(t)] if (0.0..60.0).contains(&t)),
                "{time:?}"
            );
            let state = call(&mut sim, &mut x, protocol, "sim.getSimulationState", &[]);
            assert_eq!(state, Outcome::Ret(vec![int(17)]));
            assert_eq!(
                call(&mut sim, &mut x, protocol, "sim.stopSimulation", &[]),
                stop
            );
            // stopping a stopped simulation answers at once
            assert_eq!(
                call(&mut sim, &mut x, protocol, "sim.stopSimulation", &[]),
                Outcome::Ret(vec![])
            );
        }
    }
}
