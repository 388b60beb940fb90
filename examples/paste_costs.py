"""Times `sim.copyPasteObjects` of k distinct copies of `Line` in one call (k = 1 to 64) at idle
fps 0, in the course scene and with 200 and 1,000 more objects, median of 7 each, in ms: what
`docs/measurements.md` "Pasting on 4.10" records. Needs a protocol-2 server (CoppeliaSim 4.6+,
or `vrep-maze serve --protocol 2`) and `pip install coppeliasim-zmqremoteapi-client`.

    python examples/paste_costs.py PORT
"""
import time, sys, statistics
from coppeliasim_zmqremoteapi_client import RemoteAPIClient
c = RemoteAPIClient('127.0.0.1', int(sys.argv[1])); sim = c.require('sim')
sim.setInt32Param(sim.intparam_idle_fps, 0)
line = sim.getObject('/Line')
def med(f, reps=7):
    ts=[]
    for r in range(reps):
        s=time.perf_counter(); x=f(); ts.append((time.perf_counter()-s)*1e3); sim.removeObjects(x)
    return statistics.median(ts)
print(f"scene {len(sim.getObjectsInTree(sim.handle_scene))} objects")
for filler in (0, 200, 1000):
    extra = []
    if filler:
        while len(extra) < filler:
            extra += sim.copyPasteObjects(([line] + extra)[:filler-len(extra)], 0)
    pool = sim.copyPasteObjects([line], 0) + sim.copyPasteObjects([line], 0)
    while len(pool) < 64: pool += sim.copyPasteObjects(pool[:64-len(pool)], 0)
    n = len(sim.getObjectsInTree(sim.handle_scene))
    row = []
    for k in (1, 2, 4, 8, 16, 32, 64):
        row.append((k, med(lambda: sim.copyPasteObjects(pool[:k], 0))))
    print(f"scene {n:5d}: " + "  ".join(f"{k}:{t:6.2f}" for k,t in row), flush=True)
    sim.removeObjects(pool + extra)
# one call for reference
s=time.perf_counter(); [sim.getSimulationState() for _ in range(100)]; print(f"trivial call {(time.perf_counter()-s)*10:.3f} ms")
sim.setInt32Param(sim.intparam_idle_fps, 8)
