#!/usr/bin/env python3
"""Conformance of `vrep-maze serve` with the official compiled legacy remote API C client.

The C client is the one bundled in the PyPI wheel dqrobotics-interface-coppeliasim-vrep
(dqrobotics/interfaces/vrep/_core*.so), loaded with ctypes. Usage:

    legacy_c_client.py PATH/TO/vrep-maze PATH/TO/_core.so

Prints one line per check and finally `legacy conformance: N passed, M failed`; exits 1 on
any failure.
"""
import ctypes as C
import json
import math
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
}
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


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    p = s.getsockname()[1]
    s.close()
    return p


def start_server(port, dump):
    p = subprocess.Popen([BIN, "serve", "--listen", f"127.0.0.1:{port}", "--idle-fps", "8", "--dump", dump],
                         stdout=subprocess.PIPE, text=True)
    line = p.stdout.readline()
    if "legacy remote API on" not in line:
        raise SystemExit(f"serve did not start: {line!r}")
    return p


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
    server = start_server(port, dump)
    try:
        run(port, dump, server)
    finally:
        if server.poll() is None:
            server.send_signal(signal.SIGTERM)
            try:
                server.wait(5)
            except subprocess.TimeoutExpired:
                server.kill()
    print(f"legacy conformance: {passed} passed, {failed} failed")
    sys.exit(1 if failed else 0)


def run(port, dump, server):
    cid = lib.simxStart(b"127.0.0.1", port, 1, 1, 5000, 5)
    check("simxStart connects", cid >= 0, cid)
    check("simxGetConnectionId is 1 after the first connection", lib.simxGetConnectionId(cid) == 1)

    # idle rate: default 8 fps paces blocking calls at ~125 ms; 0 makes them fast
    v = I(-1)
    rc = lib.simxGetIntegerParameter(cid, 26, C.byref(v), BLOCKING)
    check("sim_intparam_idle_fps reads 8 by default", rc == OK and v.value == 8, (rc, v.value))
    slow = [ping(cid)[1] for _ in range(5)]
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
    cid2 = lib.simxStart(b"127.0.0.1", port, 1, 1, 5000, 5)
    check("a second client connects after simxFinish", cid2 >= 0, cid2)
    rc, h = handle(cid2, "Line2")
    check("the scene persists across clients", rc == OK and h == c2[0], (rc, h))
    lib.simxFinish(cid2)
    server.send_signal(signal.SIGTERM)
    check("serve exits cleanly on SIGTERM", server.wait(5) == 0)


if __name__ == "__main__":
    main()
