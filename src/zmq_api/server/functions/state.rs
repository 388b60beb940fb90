//! The simulation state (start, stop), integer parameters (program version, idle fps) and
//! integer and string signals.

use ciborium::Value;

use super::{Args, Ctx, Outcome, nothing, ret};
use crate::coppelia::{
    INTPARAM_PROGRAM_VERSION, SIMULATION_ADVANCING_RUNNING, SIMULATION_PAUSED, SIMULATION_STOPPED,
};
use crate::sim::SimState;
use crate::zmq_api::cbor::int;
use crate::zmq_api::message::Protocol;

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

/// `sim.startSimulation()`: scene edits from now on are undone on stop.
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

/// `sim.getInt32Signal(name)`: the value, or nil when the signal is not set.
pub(super) fn get_int32_signal(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let value = ctx.sim.int_signals.get(a.text(0)?).copied();
    ret(vec![value.map_or(Value::Null, |v| int(v.into()))])
}

/// `sim.setInt32Signal(name, value)`.
pub(super) fn set_int32_signal(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let (name, value) = (a.text(0)?, a.int(1)?);
    ctx.sim.int_signals.insert(name.to_string(), value);
    nothing()
}

/// `sim.clearInt32Signal(name)`; clearing an unset signal is no error.
pub(super) fn clear_int32_signal(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    ctx.sim.int_signals.remove(a.text(0)?);
    nothing()
}

/// `sim.getStringSignal(name)`: the value (text when it is UTF-8, else bytes), or nil when
/// the signal is not set.
pub(super) fn get_string_signal(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let value = ctx.sim.string_signals.get(a.text(0)?).map(|v| {
        String::from_utf8(v.clone()).map_or_else(|e| Value::Bytes(e.into_bytes()), Value::Text)
    });
    ret(vec![value.unwrap_or(Value::Null)])
}

/// `sim.setStringSignal(name, value)`: the value as text or bytes.
pub(super) fn set_string_signal(ctx: &mut Ctx<'_>, a: &Args<'_>) -> Result<Outcome, String> {
    let name = a.text(0)?;
    let value = match a.get(1) {
        Some(Value::Text(t)) => t.clone().into_bytes(),
        Some(Value::Bytes(b)) => b.clone(),
        _ => return Err(a.bad(1, "a string")),
    };
    ctx.sim.string_signals.insert(name.to_string(), value);
    nothing()
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
    use crate::coppelia::DEFAULT_IDLE_FPS;
    use crate::sim::{Scene, Simulator};

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
