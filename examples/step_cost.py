"""Times `sim.step` alone with the course scene's physics on and off, 60 steps each, camera
spared: the simulator's own step, the floor under RobotMaze-v0's step. What
`docs/measurements.md` "What a stop undoes, and resets that leave the simulation running"
records (5.8-7.5 ms on, 2.0-3.0 ms off, on an idle 2-core machine). Needs a protocol-2 server
with the course robot (`sim.sh start 4.10.0 --robot`) and
`pip install coppeliasim-zmqremoteapi-client`.

    python examples/step_cost.py PORT
"""
import statistics
import sys
import time

from coppeliasim_zmqremoteapi_client import RemoteAPIClient

sim = RemoteAPIClient("127.0.0.1", int(sys.argv[1])).require("sim")
idle = sim.getInt32Param(sim.intparam_idle_fps)
camera = sim.getObject("/Robot/camera")
flag = sim.getExplicitHandling(camera)
sim.setInt32Param(sim.intparam_idle_fps, 0)
sim.setExplicitHandling(camera, 1)
sim.setStepping(True)
sim.startSimulation()
try:
    for physics in (True, False):
        sim.setBoolParam(sim.boolparam_dynamics_handling_enabled, physics)
        times = []
        for _ in range(60):
            began = time.perf_counter()
            sim.step()
            times.append(time.perf_counter() - began)
        print(f"physics {'on' if physics else 'off'}: sim.step median {statistics.median(times) * 1e3:.2f} ms")
finally:
    sim.setBoolParam(sim.boolparam_dynamics_handling_enabled, True)
    sim.setStepping(False)
    sim.stopSimulation()
    while sim.getSimulationState() != sim.simulation_stopped:
        time.sleep(0.005)
    sim.setExplicitHandling(camera, flag)
    sim.setInt32Param(sim.intparam_idle_fps, idle)
