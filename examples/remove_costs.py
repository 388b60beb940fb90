"""Times `sim.removeObjects` of k pasted copies of `Line` in one call (k = 1 to 256) at idle fps
0, in the course scene and with 1,000 more objects, median of 7 each, in ms: what
`docs/measurements.md` "Removing on 4.10" records. PROTOCOL is 1 (CoppeliaSim 4.3-4.5) or 2
(4.6+); needs `pip install coppeliasim-zmqremoteapi-client`.

    python examples/remove_costs.py PORT PROTOCOL
"""
import statistics
import sys
import time

from coppeliasim_zmqremoteapi_client import RemoteAPIClient

c = RemoteAPIClient('127.0.0.1', int(sys.argv[1]))
sim = c.require('sim') if sys.argv[2] == '2' else c.getObject('sim')
fps = sim.getInt32Param(sim.intparam_idle_fps)
sim.setInt32Param(sim.intparam_idle_fps, 0)
try:
    line = sim.getObject('/Line')

    def copies(k):
        made = []
        while len(made) < k:
            made += sim.copyPasteObjects(([line] + made)[:k - len(made)], 0)
        return made

    for filler in (0, 1000):
        extra = copies(filler) if filler else []
        row = []
        for k in (1, 16, 64, 256):
            ts = []
            for _ in range(7):
                made = copies(k)
                s = time.perf_counter()
                sim.removeObjects(made)
                ts.append((time.perf_counter() - s) * 1e3)
            row.append((k, statistics.median(ts)))
        n = len(sim.getObjectsInTree(sim.handle_scene))
        print(f"scene {n:5d}: " + "  ".join(f"{k}:{t:6.2f}" for k, t in row), flush=True)
        if extra:
            sim.removeObjects(extra)
finally:
    sim.setInt32Param(sim.intparam_idle_fps, fps)
