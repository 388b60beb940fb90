"""Times `sim.removeObjects` of k pasted copies of `Line` in one call (k = 1 to 256) at idle fps
0, in the course scene and with 1,000 more objects, median of 7 each, in ms: what
`docs/measurements.md` "Removing and listing on 4.10" records. With `--all`, every copy of
scenes of the course and n copies (n = 250 to 4,000), median of 3, as the spec's table of
removing all n. PROTOCOL is 1 (CoppeliaSim 4.3-4.5) or 2 (4.6+); needs
`pip install coppeliasim-zmqremoteapi-client`.

    python examples/remove_costs.py PORT PROTOCOL [--all]
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

    def removal_ms(k, reps):
        """Median ms of removing k fresh copies in one call, over reps."""
        ts = []
        for _ in range(reps):
            made = copies(k)
            s = time.perf_counter()
            sim.removeObjects(made)
            ts.append((time.perf_counter() - s) * 1e3)
        return statistics.median(ts)

    if sys.argv[3:] == ['--all']:
        for n in (250, 500, 1000, 2000, 4000):
            print(f"all {n:5d} of {n + 5:5d}: {removal_ms(n, 3):8.2f}", flush=True)
        sys.exit()
    for filler in (0, 1000):
        extra = copies(filler) if filler else []
        row = [(k, removal_ms(k, 7)) for k in (1, 16, 64, 256)]
        n = len(sim.getObjectsInTree(sim.handle_scene))
        print(f"scene {n:5d}: " + "  ".join(f"{k}:{t:6.2f}" for k, t in row), flush=True)
        if extra:
            sim.removeObjects(extra)
finally:
    sim.setInt32Param(sim.intparam_idle_fps, fps)
