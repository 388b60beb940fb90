"""Times what decoding a request's arrays costs a ZeroMQ server, at idle fps 0, median of 7, in
ms: an empty `sim.getSimulationState()`, the same call carrying the vertex and index arrays of n
boxes (which the function ignores), as integers, and as one byte string of the same size; and
`sim.createShape` of those boxes (created and removed). What `docs/measurements.md` "Meshes
created in one request" records. Needs a protocol-2 server (CoppeliaSim 4.6+, or `vrep-maze
serve --protocol 2`) and `pip install coppeliasim-zmqremoteapi-client`.

    python examples/decode_cost.py PORT N [N...]
"""
import sys, time, statistics
from coppeliasim_zmqremoteapi_client import RemoteAPIClient
port = int(sys.argv[1])
c = RemoteAPIClient('127.0.0.1', port)
sim = c.require('sim')
fps = sim.getInt32Param(sim.intparam_idle_fps)
sim.setInt32Param(sim.intparam_idle_fps, 0)
def boxes(n):
    v, ix = [], []
    for k in range(n):
        x, y = (k % 10) * 0.2, (k // 10) * 0.2
        b = len(v) // 3
        for z in (0.0, 0.2):
            for dx, dy in ((0,0),(0.15,0),(0.15,0.02),(0,0.02)):
                v += [x+dx, y+dy, z]
        for t in ([0,1,2],[0,2,3],[4,6,5],[4,7,6],[0,4,5],[0,5,1],[1,5,6],[1,6,2],[2,6,7],[2,7,3],[3,7,4],[3,4,0]):
            ix += [b+i for i in t]
    return v, ix
def med(f, reps=7):
    ts = []
    for _ in range(reps):
        t = time.perf_counter(); f(); ts.append((time.perf_counter()-t)*1000)
    return statistics.median(ts)
try:
  for n in [int(a) for a in sys.argv[2:]]:
    v, ix = boxes(n)
    empty = med(lambda: sim.getSimulationState())
    carry = med(lambda: sim.getSimulationState(v, ix))
    def mk():
        h = sim.createShape(0, 0, v, ix); sim.removeObjects([h])
    make = med(mk)
    ints = med(lambda: sim.getSimulationState(list(range(len(v)+len(ix)))))
    strs = med(lambda: sim.getSimulationState(b'x'*(8*(len(v)+len(ix)))))
    print(f"{n} boxes, {len(v)//3} verts {len(ix)//3} tris: empty call {empty:.2f} ms, same call carrying the arrays {carry:.2f}, as ints {ints:.2f}, as a byte string {strs:.2f}; createShape+remove {make:.2f}")
finally:
    # the idle rate as it was, even when interrupted
    sim.setInt32Param(sim.intparam_idle_fps, fps)
