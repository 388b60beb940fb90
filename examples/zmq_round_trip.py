"""Times one ZeroMQ round trip at idle fps 0, 200 calls each, median and 90th percentile in ms:
`sim.getSimulationState`, `sim.getInt32Signal`, `sim.getObject('/Floor')`, and one
`sim.executeLuaCode` that makes ten signal reads (what folding a reset's reads into one program
costs). What `docs/measurements.md` "Session resets, measured again" records. Puts the idle rate
back. Needs a protocol-2 server (CoppeliaSim 4.6+, or `vrep-maze serve --protocol 2`) and
`pip install coppeliasim-zmqremoteapi-client`.

    python examples/zmq_round_trip.py PORT
"""
import sys, time, statistics
from coppeliasim_zmqremoteapi_client import RemoteAPIClient
c = RemoteAPIClient('127.0.0.1', int(sys.argv[1]))
sim = c.require('sim')
fps = sim.getInt32Param(sim.intparam_idle_fps)
sim.setInt32Param(sim.intparam_idle_fps, 0)


def timed(call, n=200):
    xs = []
    for _ in range(n):
        t = time.perf_counter()
        call()
        xs.append((time.perf_counter() - t) * 1000)
    xs.sort()
    return f"median {statistics.median(xs):.2f} ms, p90 {xs[int(n * 0.9)]:.2f}"


ten_reads = "for i=1,10 do sim.getInt32Signal('vrepMaze.probe') end return 1"
print("sim.getSimulationState:", timed(lambda: sim.getSimulationState()))
print("sim.getInt32Signal:", timed(lambda: sim.getInt32Signal('vrepMaze.probe')))
print("sim.getObject('/Floor'):", timed(lambda: sim.getObject('/Floor')))
print("sim.executeLuaCode, ten reads:", timed(lambda: sim.executeLuaCode(ten_reads)))
sim.setInt32Param(sim.intparam_idle_fps, fps)
