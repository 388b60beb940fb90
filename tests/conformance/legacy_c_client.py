#!/usr/bin/env python3
"""Conformance of `vrep-maze serve` with the official compiled legacy remote API C client.

The C client is the one bundled in the PyPI wheel dqrobotics-interface-coppeliasim-vrep
(dqrobotics/interfaces/vrep/_core*.so), loaded with ctypes. Usage:

    legacy_c_client.py PATH/TO/vrep-maze PATH/TO/_core.so

Prints one line per check and finally `legacy-conformance: N passed, M failed`; exits 1 on
any failure.
"""
import ctypes as C
import json
import math
import re
import os
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import time

BIN, LIB = sys.argv[1], sys.argv[2]
lib = C.CDLL(LIB)
I, F, U = C.c_int, C.c_float, C.c_ubyte
BLOCKING, ONESHOT, STREAMING, BUFFER, DISCONTINUE = 0x10000, 0, 0x20000, 0x60000, 0x50000
OK, NOVALUE, REMOTE = 0, 1, 8

sig = {
    "simxStart": (I, [C.c_char_p, I, U, U, I, I]),
    "simxFinish": (None, [I]),
    "simxGetConnectionId": (I, [I]),
    "simxGetObjectHandle": (I, [I, C.c_char_p, C.POINTER(I), I]),
    "simxCopyPasteObjects": (I, [I, C.POINTER(I), I, C.POINTER(C.POINTER(I)), C.POINTER(I), I]),
    "simxSetObjectPosition": (I, [I, I, I, C.POINTER(F), I]),
    "simxGetObjectPosition": (I, [I, I, I, C.POINTER(F), I]),
    "simxSetObjectOrientation": (I, [I, I, I, C.POINTER(F), I]),
    "simxGetObjectOrientation": (I, [I, I, I, C.POINTER(F), I]),
    "simxGetObjectQuaternion": (I, [I, I, I, C.POINTER(F), I]),
    "simxSetObjectParent": (I, [I, I, I, U, I]),
    "simxGetObjectParent": (I, [I, I, C.POINTER(I), I]),
    "simxGetObjects": (I, [I, I, C.POINTER(I), C.POINTER(C.POINTER(I)), I]),
    "simxGetObjectGroupData": (I, [I, I, I, C.POINTER(I), C.POINTER(C.POINTER(I)), C.POINTER(I),
                                   C.POINTER(C.POINTER(I)), C.POINTER(I), C.POINTER(C.POINTER(F)),
                                   C.POINTER(I), C.POINTER(C.POINTER(C.c_char)), I]),
    "simxRemoveObject": (I, [I, I, I]),
    "simxGetPingTime": (I, [I, C.POINTER(I)]),
    "simxGetIntegerParameter": (I, [I, I, C.POINTER(I), I]),
    "simxSetIntegerParameter": (I, [I, I, I, I]),
    "simxStartSimulation": (I, [I, I]),
    "simxStopSimulation": (I, [I, I]),
    "simxGetInMessageInfo": (I, [I, I, C.POINTER(I)]),
    "simxPauseCommunication": (I, [I, U]),
    "simxGetIntegerSignal": (I, [I, C.c_char_p, C.POINTER(I), I]),
    "simxGetLastCmdTime": (I, [I]),
    "simxSetIntegerSignal": (I, [I, C.c_char_p, I, I]),
    "simxGetStringSignal": (I, [I, C.c_char_p, C.POINTER(C.POINTER(C.c_ubyte)), C.POINTER(I), I]),
    "simxSetStringSignal": (I, [I, C.c_char_p, C.c_char_p, I, I]),
    "simxTransferFile": (I, [I, C.c_char_p, C.c_char_p, I, I]),
    "simxLoadModel": (I, [I, C.c_char_p, U, C.POINTER(I), I]),
    "simxEraseFile": (I, [I, C.c_char_p, I]),
    "simxGetObjectFloatParameter": (I, [I, I, I, C.POINTER(F), I]),
    "simxSynchronous": (I, [I, U]),
    "simxSynchronousTrigger": (I, [I]),
    "simxSetJointTargetVelocity": (I, [I, I, F, I]),
    "simxGetJointPosition": (I, [I, I, C.POINTER(F), I]),
    "simxGetVisionSensorImage": (I, [I, I, C.POINTER(I), C.POINTER(C.POINTER(C.c_ubyte)), U, I]),
    "simxGetObjectChild": (I, [I, I, I, C.POINTER(I), I]),
    "simxGetObjectIntParameter": (I, [I, I, I, C.POINTER(I), I]),
}
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MESH_MODEL = os.path.join(ROOT, "tests", "coppeliasim-xml", "mesh-two-rects-4.5.1.simmodel.xml")
for name, (res, args) in sig.items():
    f = getattr(lib, name)
    f.restype, f.argtypes = res, args

passed = failed = 0


def check(name, cond, detail=""):
    global passed, failed
    if cond:
        passed += 1
        print(f"ok   {name}")
    else:
        failed += 1
        print(f"FAIL {name} {detail}")


def near(a, b, tol=2e-4):
    return len(a) == len(b) and all(abs(x - y) <= tol for x, y in zip(a, b))


def euler_matrix(e):
    """R = Rx(a) Ry(b) Rz(c), row-major, CoppeliaSim's Euler convention."""
    a, b, c = e
    ca, sa, cb, sb, cc, sc = math.cos(a), math.sin(a), math.cos(b), math.sin(b), math.cos(c), math.sin(c)
    return [cb * cc, -cb * sc, sb,
            ca * sc + sa * sb * cc, ca * cc - sa * sb * sc, -sa * cb,
            sa * sc - ca * sb * cc, sa * cc + ca * sb * sc, ca * cb]


def quat_matrix(q):
    x, y, z, w = q
    return [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w),
            2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w),
            2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    p = s.getsockname()[1]
    s.close()
    return p


def start_server(port, dump, trace=None, env=None, extra=()):
    extra = (["--trace"] if trace else []) + list(extra)
    p = subprocess.Popen([BIN, "serve", "--listen", f"127.0.0.1:{port}", "--idle-fps", "8", "--dump", dump] + extra,
                         stdout=subprocess.PIPE, stderr=trace, text=True, env=env)
    line = p.stdout.readline()
    if "legacy remote API on" not in line:
        raise SystemExit(f"serve did not start: {line!r}")
    return p


def stop(server):
    if server.poll() is None:
        server.send_signal(signal.SIGTERM)
        try:
            server.wait(5)
        except subprocess.TimeoutExpired:
            server.kill()


def c_connect(port):
    """simxStart, then check the server answers: right after a client left, the server may
    drop a fresh connection while it re-creates its listening socket; retry then."""
    deadline = time.time() + 10
    while True:
        cid = lib.simxStart(b"127.0.0.1", port, 1, 1, 5000, 5)
        if cid >= 0 and ping(cid)[0] == OK:
            return cid
        if cid >= 0:
            lib.simxFinish(cid)
        if time.time() > deadline:
            return -1
        time.sleep(0.2)


def handle(cid, name):
    h = I(12345)
    rc = lib.simxGetObjectHandle(cid, name.encode(), C.byref(h), BLOCKING)
    return rc, h.value


def pos(cid, h, rel, get=lib.simxGetObjectPosition):
    v = (F * 3)()
    rc = get(cid, h, rel, v, BLOCKING)
    return rc, [v[0], v[1], v[2]]


def orient(cid, h, rel):
    return pos(cid, h, rel, lib.simxGetObjectOrientation)


def setv(fn, cid, h, rel, xyz, mode=BLOCKING):
    return fn(cid, h, rel, (F * 3)(*xyz), mode)


def copy_paste(cid, handles):
    arr = (I * len(handles))(*handles)
    out, n = C.POINTER(I)(), I(0)
    rc = lib.simxCopyPasteObjects(cid, arr, len(handles), C.byref(out), C.byref(n), BLOCKING)
    return rc, [out[i] for i in range(n.value)]


def group(cid, data_type, obj_type=109):
    hc, ic, fc, sc = I(), I(), I(), I()
    hs, ints, fl, st = C.POINTER(I)(), C.POINTER(I)(), C.POINTER(F)(), C.POINTER(C.c_char)()
    rc = lib.simxGetObjectGroupData(cid, obj_type, data_type, C.byref(hc), C.byref(hs), C.byref(ic), C.byref(ints),
                                    C.byref(fc), C.byref(fl), C.byref(sc), C.byref(st), BLOCKING)
    if rc != OK:
        return rc, None
    strings, k = [], 0
    for _ in range(sc.value):
        s = b""
        while st[k] != b"\0":
            s += st[k]
            k += 1
        k += 1
        strings.append(s.decode())
    return rc, {"handles": [hs[i] for i in range(hc.value)], "ints": [ints[i] for i in range(ic.value)],
                "floats": [fl[i] for i in range(fc.value)], "strings": strings}


def names(cid):
    _, g = group(cid, 0)
    return dict(zip(g["handles"], g["strings"]))


def ping(cid):
    t = I(-1)
    rc = lib.simxGetPingTime(cid, C.byref(t))
    return rc, t.value


def main():
    port = free_port()
    dump = os.path.join(tempfile.mkdtemp(), "scene.json")
    trace_path = os.path.join(tempfile.mkdtemp(), "trace.log")
    with open(trace_path, "w") as trace:
        server = start_server(port, dump, trace)
        try:
            run(port, dump, server)
        finally:
            stop(server)
    check_wire(trace_path)
    port = free_port()
    server = start_server(port, os.path.join(tempfile.mkdtemp(), "scene2.json"))
    try:
        run_apply(port)
    finally:
        stop(server)
    port = free_port()
    server_tmp = tempfile.mkdtemp()
    server = start_server(port, os.path.join(tempfile.mkdtemp(), "scene3.json"),
                          env=dict(os.environ, TMPDIR=server_tmp))
    try:
        run_models(port, server_tmp)
    finally:
        stop(server)
    port = free_port()
    robot_path = os.path.join(tempfile.mkdtemp(), "path.csv")
    with open(robot_path, "w") as f:
        # 1 m/s along x from the floor origin for 2 s, then stand still
        f.write("t,x,y,yaw\n0,0,0,0\n2,2,0,0\n")
    server = start_server(port, os.path.join(tempfile.mkdtemp(), "scene3.json"), extra=["--robot", robot_path])
    try:
        run_robot(port)
    finally:
        stop(server)
    print(f"legacy-conformance: {passed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


def run_robot(port):
    """`serve --robot`: the robot's pose streamed while the simulation runs, each reply
    stamped with the simulation time it was read at (simxGetLastCmdTime), as the course's
    camera loop reads it."""
    cid = c_connect(port)
    rc, robot = handle(cid, "Robot")
    _, floor = handle(cid, "Floor")
    check("serve --robot adds an object named Robot", rc == OK, rc)
    v = (F * 3)()
    lib.simxGetObjectPosition(cid, robot, floor, v, STREAMING)
    rc = lib.simxStartSimulation(cid, BLOCKING)
    samples, deadline = [], time.time() + 3
    while time.time() < deadline and len(samples) < 20:
        time.sleep(0.02)
        if lib.simxGetObjectPosition(cid, robot, floor, v, BUFFER) == OK:
            t = lib.simxGetLastCmdTime(cid)
            if t > 0 and (not samples or samples[-1][0] != t):
                samples.append((t, v[0]))
    lib.simxStopSimulation(cid, BLOCKING)
    times = [t for t, _ in samples]
    check("streamed replies carry the simulation time, whole 50 ms steps, increasing",
          len(samples) >= 10 and all(t % 50 == 0 for t in times) and times == sorted(times), times)
    check("the robot is where its path is at that simulation time (x = t / 1 s, until 2 s)",
          all(abs(x - min(t / 1000.0, 2.0)) < 1e-4 for t, x in samples), samples)
    deadline, x = time.time() + 2, None
    while time.time() < deadline:
        time.sleep(0.05)
        lib.simxGetObjectPosition(cid, robot, floor, v, BUFFER)
        if lib.simxGetLastCmdTime(cid) == 0:
            x = v[0]
            break
    check("after the stop the stream is stamped 0 and the robot is back at its start",
          x is not None and abs(x) < 1e-6, x)
    lib.simxGetObjectPosition(cid, robot, floor, v, DISCONTINUE)
    lib.simxFinish(cid)


def run(port, dump, server):
    cid = lib.simxStart(b"127.0.0.1", port, 1, 1, 5000, 5)
    check("simxStart connects", cid >= 0, cid)
    check("simxGetConnectionId is 1 after the first connection", lib.simxGetConnectionId(cid) == 1)
    info = I(-7)
    check("simxGetInMessageInfo returns -1 before the first non-empty reply (spec 8.4)",
          lib.simxGetInMessageInfo(cid, 17, C.byref(info)) == -1)

    # idle rate: default 8 fps paces blocking calls at ~125 ms; 0 makes them fast
    v = I(-1)
    rc = lib.simxGetIntegerParameter(cid, 26, C.byref(v), BLOCKING)
    check("sim_intparam_idle_fps reads 8 by default", rc == OK and v.value == 8, (rc, v.value))
    slow = [ping(cid)[1] for _ in range(9)]
    print(f"     (ping times at idle fps 8: {sorted(slow)} ms, median {statistics.median(slow)})")
    check("at idle fps 8 a blocking call takes about one pass (>= 60 ms median)", statistics.median(slow) >= 60, slow)
    rc = lib.simxSetIntegerParameter(cid, 26, 0, BLOCKING)
    lib.simxGetIntegerParameter(cid, 26, C.byref(v), BLOCKING)
    check("sim_intparam_idle_fps set to 0 and read back", rc == OK and v.value == 0, (rc, v.value))
    fast = [ping(cid) for _ in range(5)]
    check("simxGetPingTime returns 0 and at idle fps 0 is fast (< 60 ms median)",
          all(r == OK for r, _ in fast) and statistics.median(t for _, t in fast) < 60, fast)
    rc = lib.simxGetIntegerParameter(cid, 1, C.byref(v), BLOCKING)
    check("sim_intparam_program_version readable", rc == OK and v.value >= 30000, (rc, v.value))

    # handles and names
    hs = {}
    for n in ["Floor", "Maze", "Line", "Start", "End"]:
        rc, hs[n] = handle(cid, n)
        check(f"simxGetObjectHandle({n!r}) succeeds", rc == OK and hs[n] >= 0, (rc, hs[n]))
    check("handles are distinct", len(set(hs.values())) == 5, hs)
    rc, h = handle(cid, "/Line")
    check("path '/Line' resolves to Line", rc == OK and h == hs["Line"], (rc, h))
    for bad in ["NoSuchObject", "Line#0"]:
        rc, h = handle(cid, bad)
        # the server replies -1 with the error bit; the C client leaves the output untouched on error
        check(f"unknown name {bad!r} gives return code 8, output not written", rc == REMOTE and h == 12345, (rc, h))

    # bounding box: float parameters 15..20 (spec 12.15; real 4.5.1: Line gives -0.3, -0.05, 0, 0.3, 0.05, 0)
    bbox = []
    for param in range(15, 21):
        f = F(12345)
        rc = lib.simxGetObjectFloatParameter(cid, hs["Line"], param, C.byref(f), BLOCKING)
        bbox.append((rc, f.value))
    check("simxGetObjectFloatParameter(Line, 15..20) is the bounding box",
          all(rc == OK for rc, _ in bbox) and near([v for _, v in bbox], [-0.3, -0.05, 0, 0.3, 0.05, 0]), bbox)
    f = F(12345)
    rc = lib.simxGetObjectFloatParameter(cid, 987654, 15, C.byref(f), BLOCKING)
    check("simxGetObjectFloatParameter of an unknown object: return code 8", rc == REMOTE, rc)

    # always-ok commands and failing group data (spec 12.2, 12.10-12.12, 14.11)
    p = I(99)
    rc = lib.simxGetObjectParent(cid, 987654, C.byref(p), BLOCKING)
    check("simxGetObjectParent of an unknown handle: return code 0, parent -1", rc == OK and p.value == -1, (rc, p.value))
    rc, new = copy_paste(cid, [987654])
    check("simxCopyPasteObjects of an unknown handle: return code 0, no copies", rc == OK and new == [], (rc, new))
    rc, g = group(cid, 0, obj_type=987654)
    check("group data for a non-collection object type: return code 8", rc == REMOTE, rc)
    rc, g = group(cid, 99)
    check("group data of an unknown data type: return code 8", rc == REMOTE, rc)
    cnt, arr = I(), C.POINTER(I)()
    rc = lib.simxGetObjects(cid, 4, C.byref(cnt), C.byref(arr), BLOCKING)
    check("simxGetObjects(dummy type 4) lists Maze only", rc == OK and [arr[i] for i in range(cnt.value)] == [hs["Maze"]],
          (rc, cnt.value))
    # oneshot: first call has no value yet; a later call returns the reply that arrived meanwhile (spec 6, 14.13)
    v = (F * 3)()
    rc1 = lib.simxGetObjectPosition(cid, hs["Maze"], -1, v, ONESHOT)
    time.sleep(0.3)
    rc2 = lib.simxGetObjectPosition(cid, hs["Maze"], -1, v, ONESHOT)
    check("oneshot get: novalue flag first, then the value", rc1 == NOVALUE and rc2 == OK and near(list(v), [0, 0, 0]),
          (rc1, rc2, list(v)))

    # copy-paste naming
    line, start, maze = hs["Line"], hs["Start"], hs["Maze"]
    rc, c0 = copy_paste(cid, [line])
    check("copy-paste of Line returns one new handle", rc == OK and len(c0) == 1 and c0[0] > max(hs.values()), (rc, c0))
    rc, c1 = copy_paste(cid, [line])
    nm = names(cid)
    check("copies of Line are named Line0, Line1", nm.get(c0[0]) == "Line0" and nm.get(c1[0]) == "Line1",
          (nm.get(c0[0]), nm.get(c1[0])))
    check("simxRemoveObject(Line0) succeeds", lib.simxRemoveObject(cid, c0[0], BLOCKING) == OK)
    check("removing an already removed handle gives return code 8",
          lib.simxRemoveObject(cid, c0[0], BLOCKING) == REMOTE)
    rc, again = copy_paste(cid, [line])
    nm = names(cid)
    check("lowest free number is reused: Line0 again", nm.get(again[0]) == "Line0", nm.get(again[0]))
    check("handles are never reused", again[0] > c1[0], (again, c1))
    rc, h = handle(cid, "Line0")
    check("the new Line0 resolves by name", rc == OK and h == again[0], (rc, h))
    rc = lib.simxSetObjectParent(cid, c1[0], maze, 1, BLOCKING)
    check("simxSetObjectParent(Line1, Maze, keep in place)", rc == OK, rc)
    rc, c2 = copy_paste(cid, [c1[0]])
    nm = names(cid)
    check("a copy of Line1 is named Line2", nm.get(c2[0]) == "Line2", nm.get(c2[0]))
    p = I(99)
    lib.simxGetObjectParent(cid, c2[0], C.byref(p), BLOCKING)
    check("a pasted copy of a child of Maze is parentless", p.value == -1, p.value)
    lib.simxGetObjectParent(cid, c1[0], C.byref(p), BLOCKING)
    check("simxGetObjectParent(Line1) is Maze", p.value == maze, p.value)
    rc, both = copy_paste(cid, [line, start])
    nm = names(cid)
    check("pasting [Line, Start] gives Line3 and Start0", [nm.get(x) for x in both] == ["Line3", "Start0"],
          [nm.get(x) for x in both])
    rc, g = group(cid, 20)
    alias = dict(zip(g["handles"], g["strings"])) if g else {}
    check("copies keep the alias Line", alias.get(c1[0]) == "Line" and alias.get(both[0]) == "Line", alias)
    rc, g = group(cid, 21)
    paths = dict(zip(g["handles"], g["strings"])) if g else {}
    check("parentless copies have paths /Line[n], the template /Line, a child of Maze /Maze/Line",
          paths.get(again[0], "").startswith("/Line[") and paths.get(c2[0], "").startswith("/Line[")
          and paths.get(line) == "/Line" and paths.get(c1[0]) == "/Maze/Line", paths)
    back = {h: handle(cid, p_) for h, p_ in paths.items()}
    check("every path resolves back to its object", all(rc == OK and h2 == h for h, (rc, h2) in back.items()), back)

    # relative frames with rotation (values measured on CoppeliaSim 4.5.1)
    a, b = hs["Start"], hs["End"]
    r = [setv(lib.simxSetObjectPosition, cid, a, -1, [1, 2, 0.001]),
         setv(lib.simxSetObjectOrientation, cid, a, -1, [0, 0, math.pi / 2]),
         setv(lib.simxSetObjectPosition, cid, b, a, [0.5, 0, 0]),
         setv(lib.simxSetObjectOrientation, cid, b, a, [0.1, 0.2, 0.3])]
    check("set position/orientation (world and relative) succeed", r == [OK] * 4, r)
    rc, v3 = pos(cid, b, -1)
    check("B world position is (1, 2.5, 0.001)", rc == OK and near(v3, [1, 2.5, 0.001]), v3)
    rc, v3 = orient(cid, b, -1)
    check("B world Euler is (-0.2010, 0.0980, 1.8907)", rc == OK and near(v3, [-0.2010, 0.0980, 1.8907]), v3)
    rc, v3 = pos(cid, a, b)
    check("A relative to B is (-0.4681, 0.1448, -0.0993)", rc == OK and near(v3, [-0.4681, 0.1448, -0.0993]), v3)
    rc, v3 = orient(cid, b, a)
    check("B orientation relative to A reads back (0.1, 0.2, 0.3)", rc == OK and near(v3, [0.1, 0.2, 0.3]), v3)
    rc, v3 = pos(cid, 987654, -1)
    check("position of an unknown handle gives return code 8", rc == REMOTE, rc)
    # keep-in-place off keeps the local pose
    rc = lib.simxSetObjectParent(cid, b, a, 0, BLOCKING)
    rc2, local = pos(cid, b, -11)
    rc3, world = pos(cid, b, -1)
    check("set parent without keep-in-place keeps the local pose",
          rc == OK and near(local, [1, 2.5, 0.001]) and not near(world, [1, 2.5, 0.001]), (rc, local, world))
    check("a parent cycle is refused with return code 8", lib.simxSetObjectParent(cid, a, b, 1, BLOCKING) == REMOTE)

    # group data against single calls
    cnt, arr = I(), C.POINTER(I)()
    rc = lib.simxGetObjects(cid, -2, C.byref(cnt), C.byref(arr), BLOCKING)
    all_h = [arr[i] for i in range(cnt.value)]
    rc, gt = group(cid, 1)
    rc2, gp = group(cid, 2)
    rc3, gx = group(cid, 3)
    check("group data covers every object of simxGetObjects", rc == OK and sorted(gt["handles"]) == sorted(all_h),
          (gt and gt["handles"], all_h))
    types = dict(zip(gt["handles"], gt["ints"]))
    check("group types: Floor is a shape (0), Maze a dummy (4)", types.get(hs["Floor"]) == 0 and types.get(maze) == 4,
          types)
    parents = dict(zip(gp["handles"], gp["ints"]))
    check("group parents: End under Start, Line1 under Maze, Floor none",
          parents.get(b) == a and parents.get(c1[0]) == maze and parents.get(hs["Floor"]) == -1, parents)
    k = gx["handles"].index(b)
    rc, v3 = pos(cid, b, -1)
    check("group absolute positions agree with simxGetObjectPosition", near(gx["floats"][3 * k:3 * k + 3], v3),
          (gx["floats"][3 * k:3 * k + 3], v3))
    rc, g9 = group(cid, 9)
    rc2, e3 = orient(cid, b, -1)
    k = g9["handles"].index(b)
    check("group pose data (9) gives position + Euler", near(g9["floats"][6 * k:6 * k + 6], v3 + e3), g9["floats"][6 * k:6 * k + 6])

    rc, g5 = group(cid, 5)
    k = g5["handles"].index(b)
    check("group Euler data (5) agrees with simxGetObjectOrientation", near(g5["floats"][3 * k:3 * k + 3], e3),
          g5["floats"][3 * k:3 * k + 3])
    q = (F * 4)()
    rcq = lib.simxGetObjectQuaternion(cid, b, -1, q, BLOCKING)
    rc, g7 = group(cid, 7)
    k = g7["handles"].index(b)
    qg = g7["floats"][4 * k:4 * k + 4]
    check("quaternion (x, y, z, w) of simxGetObjectQuaternion = group data 7, same rotation as the Euler angles",
          rcq == OK and (near(list(q), qg) or near(list(q), [-x for x in qg]))
          and near(quat_matrix(list(q)), euler_matrix(e3), 1e-4), (list(q), qg))

    # batching with simxPauseCommunication: several oneshot commands in one message
    lib.simxPauseCommunication(cid, 1)
    targets = {c1[0]: [0.25, 1.0, 0.001], c2[0]: [0.75, 1.0, 0.001], again[0]: [1.25, 1.0, 0.001]}
    for h, xyz in targets.items():
        setv(lib.simxSetObjectPosition, cid, h, hs["Floor"], xyz, ONESHOT)
    lib.simxPauseCommunication(cid, 0)
    time.sleep(0.2)
    check("batched oneshot positions are applied", all(near(pos(cid, h, hs["Floor"])[1], xyz) for h, xyz in targets.items()))

    # streaming + buffer, then discontinue
    v = (F * 3)()
    lib.simxGetObjectPosition(cid, c2[0], -1, v, STREAMING)
    deadline, rc = time.time() + 2, NOVALUE
    while time.time() < deadline and rc != OK:
        time.sleep(0.01)
        rc = lib.simxGetObjectPosition(cid, c2[0], -1, v, BUFFER)
    check("streaming position arrives in the buffer", rc == OK and near(list(v), [0.75, 1.0, 0.001]), (rc, list(v)))
    setv(lib.simxSetObjectPosition, cid, c2[0], -1, [0.75, 2.0, 0.001])
    deadline = time.time() + 2
    while time.time() < deadline and not near(list(v), [0.75, 2.0, 0.001]):
        time.sleep(0.01)
        rc = lib.simxGetObjectPosition(cid, c2[0], -1, v, BUFFER)
    check("the stream follows a moved object", near(list(v), [0.75, 2.0, 0.001]), list(v))
    lib.simxGetObjectPosition(cid, c2[0], -1, v, DISCONTINUE)
    time.sleep(0.2)
    rc = lib.simxGetObjectPosition(cid, c2[0], -1, v, BUFFER)
    check("discontinue clears the stream's buffered value", rc == NOVALUE, rc)

    # simulation state bit
    info = I(-1)
    rc = lib.simxStartSimulation(cid, BLOCKING)
    ping(cid)
    lib.simxGetInMessageInfo(cid, 17, C.byref(info))
    check("simxStartSimulation sets server state bit 0", rc == OK and info.value & 1 == 1, (rc, info.value))
    rc = lib.simxStopSimulation(cid, BLOCKING)
    ping(cid)
    lib.simxGetInMessageInfo(cid, 17, C.byref(info))
    check("simxStopSimulation clears server state bit 0", rc == OK and info.value & 1 == 0, (rc, info.value))
    check("stopping a stopped simulation gives return code 8", lib.simxStopSimulation(cid, BLOCKING) == REMOTE)
    rc = lib.simxGetInMessageInfo(cid, 3, C.byref(info))
    check("simxGetInMessageInfo message ID is set", rc == 1 and info.value > 0, (rc, info.value))

    # the wheeled robot's commands (drive --wheels over legacy): serve has no physics,
    # joints or cameras and refuses them as a real port refuses what it cannot do; their
    # bytes are checked in check_wire
    run_stepping(cid)

    # clean close; the server accepts the next client and wrote the dump
    lib.simxFinish(cid)
    deadline = time.time() + 5
    while time.time() < deadline and not os.path.exists(dump):
        time.sleep(0.05)
    try:
        with open(dump) as f:
            scene = json.load(f)
        dumped = {o["name"] for o in scene["world"]}
    except (OSError, ValueError, KeyError) as e:
        dumped = {str(e)}
    check("scene dump written after the client left", {"Line0", "Line1", "Line2", "Line3", "Start0"} <= dumped, dumped)
    # simxFinish sends one more message after the kill reply: the server's side ends with a
    # reset, no TIME_WAIT, so the port listens again after the plugin's 0.5 s (spec
    # real-coppeliasim-4.5.1.md, "Why the legacy port refuses for a minute: TIME_WAIT")
    started = time.time()
    cid2 = c_connect(port)
    waited = time.time() - started
    check("a second client connects after simxFinish", cid2 >= 0, cid2)
    check("after simxFinish the port listens again within 1.5 s (no TIME_WAIT)", waited < 1.5, waited)
    rc, h = handle(cid2, "Line2")
    check("the scene persists across clients", rc == OK and h == c2[0], (rc, h))
    lib.simxFinish(cid2)
    server.send_signal(signal.SIGTERM)
    check("serve exits cleanly on SIGTERM", server.wait(5) == 0)


def check_wire(trace_path):
    """What the C client put on the wire (as `serve --trace` decoded it) against the spec."""
    sessions, blocks = [[]], []
    with open(trace_path) as f:
        for line in f:
            m = re.match(r"trace: message id=(-?\d+) client_time=(-?\d+) bytes=(\d+) blocks=(\d+)", line)
            if m:
                sessions[-1].append(tuple(int(x) for x in m.groups()))
                blocks.append([])
                continue
            m = re.match(r"trace:   block cmd=(\w+) opmode=(\w+) delay=(\d+) status=(\d+) id_bytes=(\d+) "
                         r"data_bytes=(\d+) size=(\d+)", line)
            if m:
                blocks[-1].append(tuple(int(x, 0) for x in m.groups()))
            elif "left:" in line:
                sessions.append([])
    first = sessions[0]
    check("wire: message IDs start at 0 and count up by 1 (spec 4)",
          bool(first) and [m[0] for m in first] == list(range(len(first))), [m[0] for m in first[:5]])
    check("wire: client time is a 26-bit millisecond clock (spec 4)",
          all(0 <= m[1] < 1 << 26 for m in first) and first[-1][1] - first[0][1] > 1000, (first[0][1], first[-1][1]))
    check("wire: header-only keep-alive messages are 18 bytes",
          all(m[2] == 18 for m in first if m[3] == 0) and any(m[3] == 0 for m in first))
    allb = [b for bl in blocks for b in bl]

    def having(cmd, mode=None):
        return [b for b in allb if b[0] == cmd and (mode is None or b[1] == mode)]

    cp = having(0x102E)
    check("wire: copy-paste = ID int 0, data n handles, do-not-overwrite bit (spec 12.2)",
          bool(cp) and all(b[3] == 1 and b[4] == 4 and b[5] % 4 == 0 and b[5] > 0 for b in cp), cp[:3])
    sp = having(0x101C)
    check("wire: set parent = ID handle, data parent + keep-in-place byte (spec 12.13)",
          bool(sp) and all(b[4] == 4 and b[5] == 5 for b in sp), sp[:3])
    pos_set = having(0x101B) + having(0x101A)
    check("wire: set position/orientation = ID handle, data rel + 3 floats (spec 12.5, 12.7)",
          bool(pos_set) and all(b[4] == 4 and b[5] == 16 for b in pos_set), pos_set[:3])
    gets = having(0x200E) + having(0x200D)
    check("wire: get position/orientation use the 8-byte form 0x200E/0x200D (spec 12.6, 12.8)",
          bool(gets) and all(b[4] == 8 and b[5] == 0 for b in gets) and not having(0x1019) and not having(0x1018),
          gets[:3])
    check("wire: group data = ID object type + data type (spec 12.11)",
          bool(having(0x200C)) and all(b[4] == 8 for b in having(0x200C)))
    check("wire: streaming and discontinue travel as opmodes 0x20000 / 0x50000 (spec 6)",
          bool(having(0x200E, 0x20000)) and bool(having(0x200E, 0x50000)))
    check("wire: blocking calls carry opmode 0x10000", bool(having(0x3001, 0x10000)))
    ping = having(0x1021)
    check("wire: simxGetPingTime sends get-integer-parameter (spec 12.9)", bool(ping) and all(b[4] == 4 for b in ping))
    sim = having(0x1007)
    check("wire: start/stop simulation = 0x1007 with an int ID (spec 12.17)", len(sim) >= 3 and all(b[4] == 4 for b in sim))
    null = having(0x0001) + having(0x0002) + having(0x0003)
    check("wire: simxSynchronous / simxSynchronousTrigger = 26-byte null blocks 0x0001/2/3, blocking (spec 12.21)",
          len(null) == 3 and all(b[1] == 0x10000 and b[4] == 0 and b[5] == 0 and b[6] == 26 for b in null), null)
    vel = having(0x1008)
    check("wire: set joint target velocity = ID handle, data f32 (spec 12.25)",
          bool(vel) and all(b[4] == 4 and b[5] == 4 for b in vel), vel)
    joint = having(0x1001)
    check("wire: get joint position = ID handle, no data (spec 12.25)",
          bool(joint) and all(b[4] == 4 and b[5] == 0 for b in joint), joint)
    check("wire: the vision sensor image is 0x1004 (RGB) or 0x1003 (options bit 0, grey), ID handle, streamed (spec 12.25)",
          bool(having(0x1004, 0x20000)) and bool(having(0x1003, 0x20000))
          and all(b[4] == 4 and b[5] == 0 for b in having(0x1004) + having(0x1003)))
    pairs = having(0x200B) + having(0x2008)
    check("wire: object child / int parameter = ID handle + int (spec 12.15, 12.25)",
          len(pairs) == 2 and all(b[4] == 8 and b[5] == 0 for b in pairs), pairs)
    last = [bl for bl in blocks if bl][-1][-1]
    check("wire: simxFinish sends a 30-byte kill block 0x000A, oneshot, 4-byte int payload (spec 12.14)",
          last[0] == 0x000A and last[1] == 0 and last[5] == 4 and last[6] == 30, last)


def run_stepping(cid):
    """The commands `LegacyRobot` sends, from the C client, against serve (which refuses
    them: return code 8)."""
    _, line = handle(cid, "Line")
    f, i, res = F(), I(), (I * 2)()
    img = C.POINTER(C.c_ubyte)()
    codes = [
        lib.simxSynchronous(cid, 1),
        lib.simxSynchronousTrigger(cid),
        lib.simxSetJointTargetVelocity(cid, line, 4.0, BLOCKING),
        lib.simxGetJointPosition(cid, line, C.byref(f), BLOCKING),
        lib.simxGetObjectIntParameter(cid, line, 1002, C.byref(i), BLOCKING),
        lib.simxSynchronous(cid, 0),
    ]
    check("serve refuses the stepping, joint and camera commands with return code 8", codes == [REMOTE] * 6, codes)
    rc = lib.simxGetObjectChild(cid, line, 0, C.byref(i), BLOCKING)
    check("simxGetObjectChild is answered (serve: refused)", rc in (OK, REMOTE), rc)
    for options in (0, 1):
        lib.simxGetVisionSensorImage(cid, line, res, C.byref(img), options, STREAMING)
    ping(cid)
    for options in (0, 1):
        lib.simxGetVisionSensorImage(cid, line, res, C.byref(img), options, DISCONTINUE)
    ping(cid)


def wrap(a):
    return (a + math.pi) % (2 * math.pi) - math.pi


def scene_lines(cid):
    """(line objects by handle: name, parent, x, y, z, roll, pitch, yaw) read with the C client."""
    rc0, gn = group(cid, 0)
    rc2, gp = group(cid, 2)
    rc9, g9 = group(cid, 9)
    objs = {}
    for k, h in enumerate(gn["handles"]):
        f = g9["floats"][6 * k:6 * k + 6]
        objs[h] = (gn["strings"][k], gp["ints"][k], *f)
    return objs


def check_drawn(cid, layout, label):
    hs = {n: handle(cid, n)[1] for n in ["Floor", "Maze", "Line", "Start", "End"]}
    objs = scene_lines(cid)
    floor = objs[hs["Floor"]]
    check(f"{label}: Floor at the world origin (layout frame = world)", near(floor[2:], [0] * 6), floor)
    children = {h: o for h, o in objs.items() if o[1] == hs["Maze"]}
    segs = layout["segments"]
    check(f"{label}: Maze has one child per segment but the template ({len(segs) - 1})",
          len(children) == len(segs) - 1, len(children))
    check(f"{label}: the children are Line copies named Line<N>",
          all(re.fullmatch(r"Line\d+", o[0]) for o in children.values()))
    strays = [o[0] for h, o in objs.items() if o[1] == -1 and re.fullmatch(r"Line#?\d+", o[0])]
    check(f"{label}: no parentless Line copies", not strays, strays)
    pool = [hs["Line"]] + list(children)
    missing = 0
    for sgm in segs:
        hit = next((h for h in pool if near(objs[h][2:5], [sgm["x"], sgm["y"], sgm["z"]], 1e-4)
                    and abs(wrap(objs[h][7] - sgm["yaw"])) < 1e-4 and abs(objs[h][5]) < 1e-4
                    and abs(objs[h][6]) < 1e-4), None)
        if hit is None:
            missing += 1
        else:
            pool.remove(hit)
    check(f"{label}: every segment has a line in place (1e-4 m, 1e-4 rad), none left over",
          missing == 0 and not pool, (missing, pool))
    for name in ["start", "end"]:
        o, want = objs[hs[name.capitalize()]], layout[name]["pose"]
        check(f"{label}: {name.capitalize()} in place", near(o[2:5], [want["x"], want["y"], want["z"]], 1e-4), o)


def run_apply(port):
    """Our Rust client draws (vrep-maze apply / clear); the C client checks the result."""
    tmp = tempfile.mkdtemp()
    layouts = []
    for seed, algo in [("42", "prim"), ("7", "dfs")]:
        path = os.path.join(tmp, f"{algo}{seed}.json")
        subprocess.run([BIN, "generate", "--seed", seed, "--algo", algo, "-o", path], check=True,
                       stdout=subprocess.DEVNULL)
        with open(path) as f:
            layouts.append((path, json.load(f)))
    for label, (path, layout) in zip(["apply", "re-apply of another maze"], layouts):
        r = subprocess.run([BIN, "apply", path, "--port", str(port)], capture_output=True, text=True)
        check(f"{label}: vrep-maze apply succeeds", r.returncode == 0, r.stderr)
        cid = c_connect(port)
        check_drawn(cid, layout, label)
        v = I(-1)
        lib.simxGetIntegerParameter(cid, 26, C.byref(v), BLOCKING)
        check(f"{label}: the idle rate is restored to 8", v.value == 8, v.value)
        rc = lib.simxGetIntegerSignal(cid, b"vrep_maze.saved_idle_fps", C.byref(v), BLOCKING)
        check(f"{label}: the saved-idle-rate signal is deleted", rc == REMOTE, rc)
        lib.simxFinish(cid)
    cid = c_connect(port)
    ok = (lib.simxSetIntegerSignal(cid, b"vrep_maze.saved_idle_fps", 8, BLOCKING) == OK
          and lib.simxSetIntegerParameter(cid, 26, 0, BLOCKING) == OK)
    check("integer signals can be set with the C client", ok)
    buf, n = C.POINTER(C.c_ubyte)(), I(0)
    rc = lib.simxGetStringSignal(cid, b"vrep_maze.copies", C.byref(buf), C.byref(n), BLOCKING)
    record = bytes(buf[:n.value]).decode() if rc == OK else ""
    check("apply left the record of its copies (string signal vrep_maze.copies)",
          rc == OK and re.fullmatch(r"Line:[0-9,-]+", record) is not None, (rc, record))
    ok = lib.simxSetStringSignal(cid, b"vrep_maze.copies", b"Line:7-9", 8, BLOCKING) == OK
    rc = lib.simxGetStringSignal(cid, b"vrep_maze.copies", C.byref(buf), C.byref(n), BLOCKING)
    check("string signals can be set and read with the C client",
          ok and rc == OK and bytes(buf[:n.value]) == b"Line:7-9", (ok, rc, n.value))
    lib.simxSetStringSignal(cid, b"vrep_maze.copies", record.encode(), len(record), BLOCKING)
    lib.simxFinish(cid)
    r = subprocess.run([BIN, "clear", "--port", str(port)], capture_output=True, text=True)
    check("vrep-maze clear succeeds and restores a rate left at 0 by an interrupted apply",
          r.returncode == 0 and "restored the idle rate to 8 fps" in r.stdout, (r.stdout, r.stderr))
    cid = c_connect(port)
    objs = scene_lines(cid)
    lines = sorted(o[0] for o in objs.values() if re.fullmatch(r"Line#?\d*", o[0]))
    check("after clear only the template Line is left, Start and End stay",
          lines == ["Line"] and handle(cid, "Start")[0] == OK and handle(cid, "End")[0] == OK, lines)
    v = I(-1)
    lib.simxGetIntegerParameter(cid, 26, C.byref(v), BLOCKING)
    check("after clear the idle rate is 8 again", v.value == 8, v.value)
    lib.simxFinish(cid)


def run_models(port, server_tmp):
    """simxTransferFile, simxLoadModel and simxEraseFile with a model a real 4.5.1 wrote."""
    cid = c_connect(port)
    name = b"REMOTE_API_TEMPFILE_77.simmodel.xml"
    rc = lib.simxTransferFile(cid, MESH_MODEL.encode(), name, 5000, BLOCKING)
    sent = os.path.join(server_tmp, name.decode())
    with open(MESH_MODEL, "rb") as f:
        same = os.path.exists(sent) and open(sent, "rb").read() == f.read()
    check("simxTransferFile writes the file into the server's folder for transferred files",
          rc == OK and same, rc)
    base = I(-1)
    rc = lib.simxLoadModel(cid, name, 0, C.byref(base), BLOCKING)
    rc2, h = handle(cid, "MazeMesh")
    check("simxLoadModel of the transferred XML model gives its base, the shape MazeMesh",
          rc == OK and rc2 == OK and h == base.value and base.value >= 0, (rc, rc2, h, base.value))
    objs = scene_lines(cid)
    rc, types = group(cid, 1)
    kind = dict(zip(types["handles"], types["ints"])).get(base.value)
    check("the loaded mesh is a shape (type 0) without parent, at the file's pose",
          kind == 0 and objs.get(base.value, ("", -2))[:2] == ("MazeMesh", -1)
          and near(objs[base.value][2:5], [0, 0, 0]), (kind, objs.get(base.value)))
    rc = lib.simxEraseFile(cid, name, BLOCKING)
    check("simxEraseFile removes the transferred file", rc == OK and not os.path.exists(sent), rc)
    rc = lib.simxEraseFile(cid, name, BLOCKING)
    check("erasing it again gives return code 8", rc == REMOTE, rc)
    rc = lib.simxLoadModel(cid, MESH_MODEL.encode(), 0, C.byref(base), BLOCKING)
    rc2, h = handle(cid, "MazeMesh0")
    check("simxLoadModel(path on the server's machine, 0) loads it again, named MazeMesh0",
          rc == OK and rc2 == OK and h == base.value, (rc, rc2, h, base.value))
    rc = lib.simxLoadModel(cid, MESH_MODEL.encode(), 1, C.byref(base), BLOCKING)
    check("simxLoadModel(option 1) fails with return code 8: the official client sends the file as .ttm",
          rc == REMOTE, rc)
    rc = lib.simxLoadModel(cid, b"/nonexistent/m.simmodel.xml", 0, C.byref(base), BLOCKING)
    check("simxLoadModel of a missing file gives return code 8", rc == REMOTE, rc)
    lib.simxFinish(cid)
    # vrep-maze apply --draw mesh over legacy loads its meshes as an XML model
    path = os.path.join(tempfile.mkdtemp(), "m.json")
    subprocess.run([BIN, "generate", "--seed", "3", "-o", path], check=True, stdout=subprocess.DEVNULL)
    r = subprocess.run([BIN, "apply", path, "--draw", "mesh", "--port", str(port)], capture_output=True, text=True)
    check("vrep-maze apply --draw mesh over legacy", r.returncode == 0 and "verified" in r.stdout, r.stdout + r.stderr)
    cid = c_connect(port)
    rc, holder = handle(cid, "/Maze/MazeMeshes")
    objs = scene_lines(cid)
    meshes = [h for h, o in objs.items() if o[1] == holder and o[0].startswith("MazeMesh_l_")]
    low, high = F(-1), F(-1)
    rc2 = lib.simxGetObjectFloatParameter(cid, meshes[0], 15, C.byref(low), BLOCKING) if meshes else -1
    rc3 = lib.simxGetObjectFloatParameter(cid, meshes[0], 18, C.byref(high), BLOCKING) if meshes else -1
    # the box as half-extents about its centre, not in the shape's frame (spec
    # real-coppeliasim-4.5.1.md, "Meshes on the real 4.5.1")
    check("the C client finds the mesh under Maze/MazeMeshes, its box about its centre",
          rc == OK and len(meshes) == 1 and rc2 == OK and rc3 == OK and high.value > 0
          and abs(low.value + high.value) < 1e-6, (rc, meshes, rc2, rc3, low.value, high.value))
    lib.simxFinish(cid)
    r = subprocess.run([BIN, "clear", "--port", str(port)], capture_output=True, text=True)
    cid = c_connect(port)
    check("vrep-maze clear removes the mesh maze", r.returncode == 0 and handle(cid, "/Maze/MazeMeshes")[0] == REMOTE,
          r.stdout + r.stderr)
    lib.simxFinish(cid)


if __name__ == "__main__":
    main()
