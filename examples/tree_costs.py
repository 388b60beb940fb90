"""Times `sim.getObjectsInTree(sim.handle_scene)` with n pasted copies of `Line` in the scene
(n = 0 to 1,000) at idle fps 0, median of 11, in ms: what `docs/measurements.md` "Removing
and listing on 4.10" records. PROTOCOL is 1 (CoppeliaSim 4.3-4.5) or 2 (4.6+); needs
`pip install coppeliasim-zmqremoteapi-client`.

    python examples/tree_costs.py PORT PROTOCOL
"""
import statistics
import sys
import time

from coppeliasim_zmqremoteapi_client import RemoteAPIClient

c = RemoteAPIClient('127.0.0.1', int(sys.argv[1]))
sim = c.require('sim') if sys.argv[2] == '2' else c.getObject('sim')
fps = sim.getInt32Param(sim.intparam_idle_fps)
sim.setInt32Param(sim.intparam_idle_fps, 0)
made = []
try:
    line = sim.getObject('/Line')
    row = []
    for n in (0, 100, 300, 1000):
        while len(made) < n:
            made += sim.copyPasteObjects(([line] + made)[:n - len(made)], 0)
        ts = []
        for _ in range(11):
            s = time.perf_counter()
            got = sim.getObjectsInTree(sim.handle_scene)
            ts.append((time.perf_counter() - s) * 1e3)
        row.append((len(got), statistics.median(ts)))
    print("handles:ms  " + "  ".join(f"{k}:{t:.2f}" for k, t in row))
finally:
    if made:
        sim.removeObjects(made)
    sim.setInt32Param(sim.intparam_idle_fps, fps)
