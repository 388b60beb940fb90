"""Times ten reads (`sim.getObjectParent` and `sim.getObjectPose` of five objects) at idle fps 0,
median of 21, in ms: one request each, all in one `sim.executeLuaCode` program, and an empty
program. What `docs/measurements.md` "Calls made in one request" records. PROTOCOL is 1
(CoppeliaSim 4.3-4.5) or 2 (4.6+); needs `pip install coppeliasim-zmqremoteapi-client`.

    python examples/batch_cost.py PORT PROTOCOL
"""
import sys, time, statistics
from coppeliasim_zmqremoteapi_client import RemoteAPIClient
port = int(sys.argv[1]); v2 = sys.argv[2] == '2'
c = RemoteAPIClient('127.0.0.1', port)
sim = c.require('sim') if v2 else c.getObject('sim')
fps = sim.getInt32Param(sim.intparam_idle_fps); sim.setInt32Param(sim.intparam_idle_fps, 0)
names = ['/Floor', '/Maze', '/Line', '/Start', '/End']
hs = [sim.getObject(n) for n in names]
def med(f, reps=21):
    ts = []
    for _ in range(reps):
        t = time.perf_counter(); f(); ts.append((time.perf_counter()-t)*1000)
    return statistics.median(ts)
try:
    one = med(lambda: [(sim.getObjectParent(h), sim.getObjectPose(h, -1)) for h in hs])
    code = "local out = {} for i, h in ipairs({%s}) do out[#out+1] = {pcall(sim.getObjectParent, h)} out[#out+1] = {pcall(sim.getObjectPose, h, -1)} end return out" % ",".join(map(str, hs))
    prog = med(lambda: sim.executeLuaCode(code))
    ok, out = sim.executeLuaCode(code)
    empty = med(lambda: sim.executeLuaCode("return 1"))
    print(f"{len(hs)*2} calls: one request each {one:.2f} ms, one program {prog:.2f} ms, an empty program {empty:.2f}; sample {out[1]}")
finally:
    sim.setInt32Param(sim.intparam_idle_fps, fps)
