#!/usr/bin/env python3
"""Conformance of `vrep-maze serve --api zmq --protocol 2` with the official ZeroMQ remote API
client (PyPI coppeliasim-zmqremoteapi-client, with pyzmq and cbor2). Usage:

    zmq_official_client.py PATH/TO/vrep-maze

Prints one line per check and finally `zmq-conformance: N passed, M failed`; exits 1 on any
failure.
"""
import json
import math
import os
import socket
import subprocess
import sys
import tempfile
import threading
import time

import cbor2
import zmq
from coppeliasim_zmqremoteapi_client import RemoteAPIClient

BIN = sys.argv[1]
passed = failed = 0


def check(name, ok, detail=""):
    global passed, failed
    if ok:
        passed += 1
        print(f"ok   {name}")
    else:
        failed += 1
        print(f"FAIL {name} {detail}")


def raises(f, needle):
    try:
        f()
    except Exception as e:  # the client raises a bare Exception with the server's text
        return needle in str(e), str(e)
    return False, "no exception"


def close(a, b, tol=1e-4):
    return len(a) == len(b) and all(abs(x - y) <= tol for x, y in zip(a, b))


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def start_server(*extra):
    port = free_port()
    proc = subprocess.Popen(
        [BIN, "serve", "--api", "zmq", "--listen", f"127.0.0.1:{port}", *extra],
        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = proc.stdout.readline()
    if "ZeroMQ remote API" not in line:
        print("server did not start:", line, proc.stderr.read())
        sys.exit(1)
    return proc, port


def stop(proc):
    proc.terminate()
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        proc.kill()


tmp = tempfile.mkdtemp(prefix="zmq-conformance-")
proc, port = start_server("--protocol", "2", "--idle-fps", "0", "--scene", "course")
try:
    client = RemoteAPIClient("127.0.0.1", port)
    sim = client.require("sim")
    check("require('sim') builds the sim object from zmqRemoteApi.info", hasattr(sim, "getObject"))
    check("constants from info", (sim.handle_world, sim.handle_all, sim.intparam_idle_fps) == (-1, -2, 26))
    version = sim.getInt32Param(sim.intparam_program_version)
    check("program version is a 4.6+ one (protocol 2)", isinstance(version, int) and version >= 40600, version)
    check("simulation stopped", sim.getSimulationState() == sim.simulation_stopped)

    line = sim.getObject("/Line")
    maze = sim.getObject("/Maze")
    start, end, floor = sim.getObject("/Start"), sim.getObject("/End"), sim.getObject("/Floor")
    check("getObject finds the course objects", all(isinstance(h, int) and h >= 0 for h in (line, maze, start, end, floor)))
    ok, msg = raises(lambda: sim.getObject("/Nope"), "does not exist")
    check("getObject of a missing path is an error", ok, msg)
    check("getObject with noError gives -1", sim.getObject("/Nope", {"noError": True}) == -1)
    bbox = [sim.getObjectFloatParam(line, p) for p in range(15, 21)]
    check("getObjectFloatParam(Line, 15..20) is the bounding box",
          all(abs(a - b) < 1e-6 for a, b in zip(bbox, [-0.3, -0.05, 0, 0.3, 0.05, 0])), bbox)

    copies = sim.copyPasteObjects([line], 0)
    check("copyPasteObjects returns a list of new handles", isinstance(copies, list) and len(copies) == 1 and copies[0] > line, copies)
    copy = copies[0]
    check("a copy keeps the alias", sim.getObjectAlias(copy) == "Line")
    check("getObjectAlias(copy, 1) is /Line[1]", sim.getObjectAlias(copy, 1) == "/Line[1]", sim.getObjectAlias(copy, 1))
    check("getObject('/Line[1]') finds the copy", sim.getObject("/Line[1]") == copy)
    check("a pasted copy has no parent", sim.getObjectParent(copy) == -1)
    more = sim.copyPasteObjects([line, copy], 0)
    check("pasting two objects at once", len(more) == 2 and sim.getObjectAlias(more[1], 1) == "/Line[3]", more)
    repeated = sim.copyPasteObjects([line, line, line, line], 0)
    check("a repeated handle is pasted once, each repetition answers the first object (4.5.1: [5, 0, 0, 0])",
          len(repeated) == 4 and repeated[0] > line and repeated[1:] == [floor] * 3, repeated)
    sim.removeObjects([repeated[0]])

    sim.setObjectPosition(copy, [1.0, 2.0, 0.001], sim.handle_world)
    check("setObjectPosition, 4.6+ order (h, pos, rel)", close(sim.getObjectPosition(copy, sim.handle_world), [1, 2, 0.001]))
    sim.setObjectPosition(copy, sim.handle_world, [3.0, 4.0, 0.001])
    check("setObjectPosition, 4.5 order (h, rel, pos)", close(sim.getObjectPosition(copy, sim.handle_world), [3, 4, 0.001]))
    sim.setObjectPosition(copy, [0.5, 0.25, 0.0])
    check("setObjectPosition relative to the world by default", close(sim.getObjectPosition(copy, -1), [0.5, 0.25, 0.0]))

    # the relative-frame test vector measured on a real CoppeliaSim 4.5.1
    sim.setObjectPosition(start, [1.0, 2.0, 0.001], -1)
    sim.setObjectOrientation(start, [0.0, 0.0, math.pi / 2], -1)
    sim.setObjectPosition(end, [0.5, 0.0, 0.0], start)
    sim.setObjectOrientation(end, start, [0.1, 0.2, 0.3])
    check("position relative to a rotated object", close(sim.getObjectPosition(end, -1), [1.0, 2.5, 0.001]))
    check("Euler angles relative to a rotated object", close(sim.getObjectOrientation(end, -1), [-0.2010, 0.0980, 1.8907]), sim.getObjectOrientation(end, -1))
    check("position of A relative to B", close(sim.getObjectPosition(start, end), [-0.4681, 0.1448, -0.0993]))
    s2 = math.sqrt(0.5)
    sim.setObjectPose(copy, [1.0, -1.0, 0.001, 0.0, 0.0, s2, s2], floor)
    pose = sim.getObjectPose(copy, floor)
    check("setObjectPose / getObjectPose (quaternion x, y, z, w)", close(pose[:3], [1, -1, 0.001]) and close([abs(x) for x in pose[3:]], [0, 0, s2, s2]), pose)
    check("getObjectOrientation of that pose has yaw pi/2", close(sim.getObjectOrientation(copy, floor), [0, 0, math.pi / 2]))

    before = sim.getObjectPosition(copy, -1)
    sim.setObjectPosition(maze, [0.0, 0.0, 1.0], -1)
    sim.setObjectParent(copy, maze, True)
    check("setObjectParent keep-in-place keeps the world position", close(sim.getObjectPosition(copy, -1), before))
    check("getObjectParent", sim.getObjectParent(copy) == maze)
    check("getObjectsInTree(maze, handle_all, 1) lists the children", sim.getObjectsInTree(maze, sim.handle_all, 1) == [copy])
    check("getObjectsInTree(maze, handle_all, 0) includes the base", sim.getObjectsInTree(maze, sim.handle_all, 0) == [maze, copy])
    check("getObject('/Maze/Line') finds the child", sim.getObject("/Maze/Line") == copy)
    sim.setObjectParent(copy, -1, False)
    check("setObjectParent keep-in-place off keeps the local position", close(sim.getObjectPosition(copy, -1), [before[0], before[1], before[2] - 1.0]))

    check("a function without return values returns None", sim.setInt32Param(sim.intparam_idle_fps, 5) is None)
    check("setInt32Param / getInt32Param idle fps", sim.getInt32Param(sim.intparam_idle_fps) == 5)
    sim.setInt32Param(sim.intparam_idle_fps, 0)
    sim.setStringSignal("vrep_maze.copies", "Line:12-40,45")
    check("setStringSignal / getStringSignal", sim.getStringSignal("vrep_maze.copies") in ("Line:12-40,45", b"Line:12-40,45"),
          sim.getStringSignal("vrep_maze.copies"))
    sim.clearStringSignal("vrep_maze.copies")
    check("getStringSignal of a cleared signal is None", sim.getStringSignal("vrep_maze.copies") is None)
    # 4.10 keeps signals as scene properties and silently drops a name that is no valid
    # property name (../shared/spec/real-coppeliasim-4.10.md "Signals are scene properties now")
    check("setInt32Signal of a name with '-' answers 1", sim.setInt32Signal("vrep-maze.lease", 7) == 1)
    check("getInt32Signal of a name with '-' is None: it was not stored", sim.getInt32Signal("vrep-maze.lease") is None)
    sim.setInt32Signal("vrep_maze.lease", 7)
    check("getInt32Signal of a property name gives the value", sim.getInt32Signal("vrep_maze.lease") == 7)
    sim.clearInt32Signal("vrep_maze.lease")
    sim.setStringSignal("a-b", "x")
    check("getStringSignal of a name with '-' is None", sim.getStringSignal("a-b") is None)

    plane = sim.createPrimitiveShape(sim.primitiveshape_plane, [0.6, 0.1, 0.0], 0)
    sim.setObjectAlias(plane, "Fresh-Line")
    check("createPrimitiveShape + setObjectAlias (bad characters become _)", sim.getObject("/Fresh_Line") == plane)
    sim.setShapeColor(plane, None, sim.colorcomponent_ambient_diffuse, [0.0, 1.0, 0.0])
    res, rgb = sim.getShapeColor(plane, None, 0)
    check("setShapeColor pure green", close(rgb, [0, 1, 0]), rgb)
    sim.setObjectSpecialProperty(plane, sim.objectspecialproperty_renderable)
    sim.setObjectInt32Param(plane, sim.shapeintparam_respondable, 0)
    check("special property and respondable flag", sim.getObjectSpecialProperty(plane) == 2048 and sim.getObjectInt32Param(plane, sim.shapeintparam_respondable) == 0)
    dummy = sim.createDummy(0.05)
    check("createDummy", isinstance(dummy, int) and dummy > plane)

    sim.removeObjects([copy, plane])
    check("removeObjects", sim.getObject("/Fresh_Line", {"noError": True}) == -1 and sim.getObject("/Line[3]", {"noError": True}) == -1)
    # a real CoppeliaSim 4.5.1 skips handles already removed (spec real-coppeliasim-4.5.1.md)
    try:
        sim.removeObjects([copy])
        ok, msg = True, ""
    except Exception as e:  # noqa: BLE001
        ok, msg = False, str(e)
    check("removing a removed handle succeeds", ok, msg)
    ok, msg = raises(lambda: client.call("sim.noSuchThing", [1]), "No such function: sim.noSuchThing")
    check("unknown function: 'No such function: sim.noSuchThing'", ok, msg)
    ok, msg = raises(lambda: sim.getObjectPosition("x", -1), "argument")
    check("a bad argument is an error, not a crash", ok, msg)

    path = os.path.join(tmp, "saved.json")
    sim.saveScene(path)
    check("saveScene writes the file", os.path.exists(path) and json.load(open(path))["format"] == "vrep-maze scene")

    sim.startSimulation()
    check("simulation running", sim.getSimulationState() == sim.simulation_advancing_running)
    sim.stopSimulation()  # answered with _*wait*_ first: the client's wait loop must run
    check("stopSimulation through the wait loop", sim.getSimulationState() == sim.simulation_stopped)

    other = RemoteAPIClient("127.0.0.1", port)
    sim2 = other.require("sim")
    check("a second client (another uuid) is served", sim2.getObject("/Line") == line)

    # raw protocol facts the client hides
    ctx = zmq.Context()
    raw = ctx.socket(zmq.REQ)
    raw.setsockopt(zmq.RCVTIMEO, 3000)
    raw.setsockopt(zmq.LINGER, 0)
    raw.connect(f"tcp://127.0.0.1:{port}")
    raw.send(cbor2.dumps({"func": "sim.setInt32Param", "args": [26, 0], "uuid": "raw-1", "ver": 2, "argsL": 2}))
    check("an empty return is encoded as an empty map (Lua's {})", raw.recv() == cbor2.dumps({"ret": {}}))
    raw.send(cbor2.dumps({"func": "sim.getObject", "args": ["/Line"]}))
    reply = cbor2.loads(raw.recv())
    check("a request without uuid is an old client", reply.get("success") is False and "does not match" in reply.get("error", ""), reply)
    raw.send(cbor2.dumps({"func": "sim.x\n", "args": [], "uuid": "raw-1"}))
    reply = cbor2.loads(raw.recv())
    check("newlines in errors are sent as _=NL=_", reply.get("err") == "No such function: sim.x_=NL=_", reply)
    raw.send(cbor2.dumps({"func": "_*end*_", "args": [], "uuid": "raw-1"}))
    check("_*end*_ is answered with an empty map", cbor2.loads(raw.recv()) == {})
    raw.close()

    # our `apply` over ZeroMQ, read back with the official client
    layout = os.path.join(tmp, "m.json")
    subprocess.run([BIN, "generate", "--seed", "42", "--algo", "prim", "-o", layout], check=True, capture_output=True)
    r = subprocess.run([BIN, "apply", "--api", "zmq", "--port", str(port), layout], capture_output=True, text=True)
    check("vrep-maze apply --api zmq", r.returncode == 0 and "verified" in r.stdout, r.stdout + r.stderr)
    segs = json.load(open(layout))["segments"]
    kids = sim.getObjectsInTree(maze, sim.handle_all, 3)
    check("the maze has one child per segment but the template", len(kids) == len(segs) - 1, (len(kids), len(segs)))
    want = sorted((round(s["x"], 3), round(s["y"], 3), round(s["yaw"] % math.pi, 3)) for s in segs)
    got = []
    for h in kids + [line]:
        p = sim.getObjectPosition(h, floor)
        e = sim.getObjectOrientation(h, floor)
        got.append((round(p[0], 3), round(p[1], 3), round(e[2] % math.pi, 3)))
    check("every segment has a line in place (read with the official client)", sorted(got) == want)

    # mesh shapes (spec real-coppeliasim-4.5.1.md, "One object instead of thousands")
    verts = [0, 0, 0, 0.5, 0, 0, 0.5, 0.1, 0, 0, 0.1, 0, 0.5, 0, 0, 1, 0, 0, 1, 0.1, 0, 0.5, 0.1, 0]
    mesh = sim.createMeshShape(0, 0.349, verts, [0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7])
    check("createMeshShape returns a handle at the world origin", isinstance(mesh, int) and close(sim.getObjectPosition(mesh, -1), [0, 0, 0]))
    sim.setShapeColor(mesh, "", 0, [0.0, 1.0, 0.0])
    check("getShapeColor of a mesh", close(sim.getShapeColor(mesh, "", 0)[1], [0, 1, 0]))
    # 4.10 answers the box's pose too (spec real-coppeliasim-4.10.md, "Other API changes that matter")
    sizes, bb_pose = sim.getShapeBB(mesh)
    check("getShapeBB of two rectangles is 1 x 0.1 x 0, and the box's pose", close(sizes, [1.0, 0.1, 0.0])
          and close(bb_pose, [0.5, 0.05, 0.0, 0.0, 0.0, 0.0, 1.0]), (sizes, bb_pose))
    shape = sim.createShape(0, 0.349, verts, [0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7])
    check("createShape makes the same shape at the world origin", close(sim.getObjectPosition(shape, -1), [0, 0, 0])
          and close(sim.getShapeBB(shape)[0], [1.0, 0.1, 0.0]) and len(sim.getShapeMesh(shape)[0]) == 18)
    sim.removeObjects([shape])
    sim.setObjectPosition(mesh, [2.0, 0.0, 0.0], -1)
    v, i, n = sim.getShapeMesh(mesh)
    check("getShapeMesh: relative to the shape, duplicates merged", len(v) == 18 and len(i) == 12 and len(n) == 36 and max(v[0::3]) <= 1.0, (len(v), len(i)))
    lv, li, _ = sim.getShapeMesh(line)
    check("getShapeMesh of the Line template: its 0.6 x 0.1 plane", len(lv) == 12 and len(li) == 6 and close([max(lv[0::3]), max(lv[1::3])], [0.3, 0.05]), lv)
    ok, msg = raises(lambda: sim.createMeshShape(0, 0.0, [0, 0, 0], [0, 1, 2]), "invalid")
    check("createMeshShape with bad vertices is an error", ok, msg)
    merged = sim.groupShapes([mesh, sim.createMeshShape(0, 0.0, verts, [0, 1, 2])], True)
    check("groupShapes merges into one shape", sim.getObjectType(merged) == 0 and len(sim.getShapeMesh(merged)[1]) == 15)
    sim.removeObjects([merged])

    # our `apply --draw mesh` over ZeroMQ, read back with the official client
    r = subprocess.run([BIN, "apply", "--api", "zmq", "--port", str(port), "--draw", "mesh", layout], capture_output=True, text=True)
    check("vrep-maze apply --draw mesh", r.returncode == 0 and "verified" in r.stdout, r.stdout + r.stderr)
    holder = sim.getObject("/Maze/MazeMeshes")
    meshes = sim.getObjectsInTree(holder, sim.handle_all, 3)
    names = [sim.getObjectAlias(h) for h in meshes]
    check("one mesh under Maze/MazeMeshes, named with its fingerprint", len(meshes) == 1 and names[0].startswith("MazeMesh_l_"), names)
    check("the copies are gone", sim.getObjectsInTree(maze, sim.handle_all, 3) == [holder])
    mv, mi, _ = sim.getShapeMesh(meshes[0])
    check("the mesh is green and holds two triangles per run", close(sim.getShapeColor(meshes[0], "", 0)[1], [0, 1, 0]) and len(mi) % 6 == 0 and len(mi) > 0)
    r = subprocess.run([BIN, "clear", "--api", "zmq", "--port", str(port)], capture_output=True, text=True)
    check("vrep-maze clear removes the mesh maze", r.returncode == 0 and sim.getObject("/Maze/MazeMeshes", {"noError": True}) == -1, r.stdout + r.stderr)
    # XML models: a model base saved and loaded back; a model a real 4.5.1 wrote loads too
    model_path = os.path.join(tempfile.mkdtemp(), "line.simmodel.xml")
    line = sim.getObject("/Line")
    ok, msg = raises(lambda: sim.saveModel(line, model_path), "model base")
    check("saveModel of an object that is no model base is an error", ok, msg)
    sim.setModelProperty(line, 0)
    sim.saveModel(line, model_path)
    check("setModelProperty(h, 0) + saveModel write an XML model", os.path.exists(model_path) and "<filetype>exhaustiveModel</filetype>" in open(model_path).read())
    copy = sim.loadModel(model_path)
    check("loadModel gives the base of a copy, alias Line, with the plane's mesh",
          sim.getObjectAlias(copy, -1) == "Line" and copy != line and len(sim.getShapeMesh(copy)[1]) == 6)
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ref = sim.loadModel(os.path.join(root, "tests", "coppeliasim-xml", "mesh-two-rects-4.5.1.simmodel.xml"))
    check("loadModel of the two-rectangle model a real 4.5.1 wrote: green, 1.4 x 1.1",
          close(sim.getShapeColor(ref, "", 0)[1], [0, 1, 0]) and close(sim.getShapeBB(ref)[0], [1.4, 1.1, 0.0]))
    ok, msg = raises(lambda: sim.loadModel(os.path.join(root, "m.ttm")), "XML models only")
    check("loadModel of a .ttm is an error (the emulator reads XML models only)", ok, msg)
finally:
    stop(proc)

# protocol 1: the official 2.x client fails on require('sim'), as on a real 4.5.1
proc, port = start_server("--protocol", "1", "--idle-fps", "0")
try:
    client = RemoteAPIClient("127.0.0.1", port)
    try:
        client.require("sim")
        check("protocol 1: official 2.x client fails on require with KeyError 'ret'", False, "no error")
    except KeyError as e:
        check("protocol 1: official 2.x client fails on require with KeyError 'ret'", str(e) == "'ret'", e)
    ctx = zmq.Context()
    raw = ctx.socket(zmq.REQ)
    raw.setsockopt(zmq.RCVTIMEO, 3000)
    raw.connect(f"tcp://127.0.0.1:{port}")
    raw.send(cbor2.dumps({"func": "sim.getObject", "args": ["/Line"]}))
    reply = cbor2.loads(raw.recv())
    check("protocol 1: {func, args} -> {success, ret}", reply.get("success") is True and isinstance(reply.get("ret"), list), reply)
    raw.close(linger=0)
finally:
    stop(proc)

# --api both: our legacy `apply` draws, the official ZeroMQ client sees the same scene
lport, zport = free_port(), free_port()
proc = subprocess.Popen(
    [BIN, "serve", "--api", "both", "--listen", f"127.0.0.1:{lport}", "--zmq-listen", f"127.0.0.1:{zport}", "--idle-fps", "0"],
    stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
try:
    lines = [proc.stdout.readline(), proc.stdout.readline()]
    check("serve --api both prints both servers", "legacy" in lines[0] and "ZeroMQ" in lines[1], lines)
    layout = os.path.join(tmp, "m7.json")
    subprocess.run([BIN, "generate", "--seed", "7", "--algo", "kruskal", "-o", layout], check=True, capture_output=True)
    r = subprocess.run([BIN, "apply", "--port", str(lport), layout], capture_output=True, text=True)
    check("vrep-maze apply over legacy into the shared scene", r.returncode == 0, r.stdout + r.stderr)
    sim = RemoteAPIClient("127.0.0.1", zport).require("sim")
    maze = sim.getObject("/Maze")
    segs = json.load(open(layout))["segments"]
    check("the official ZeroMQ client sees the lines drawn over legacy", len(sim.getObjectsInTree(maze, sim.handle_all, 3)) == len(segs) - 1)
finally:
    stop(proc)

# serve --robot: the robot moves with the simulation time, as sim.getSimulationTime reads it
robot_path = os.path.join(tmp, "path.csv")
with open(robot_path, "w") as f:
    f.write("t,x,y,yaw\n0,0,0,0\n2,2,0,0\n")  # 1 m/s along x for 2 s
proc, port = start_server("--protocol", "2", "--idle-fps", "0", "--robot", robot_path)
try:
    sim = RemoteAPIClient("127.0.0.1", port).require("sim")
    robot, floor = sim.getObject("/Robot"), sim.getObject("/Floor")
    check("sim.getSimulationTime is 0 while stopped", sim.getSimulationTime() == 0)
    sim.startSimulation()
    # Each call waits for a main-loop pass, so a (time, x, time) bracket may span steps
    # under load: x must be the path's place at one whole step inside the bracket.
    seen = []
    deadline = time.time() + 10
    while time.time() < deadline and len(seen) < 10:
        before = sim.getSimulationTime()
        x = sim.getObjectPosition(robot, floor)[0]
        after = sim.getSimulationTime()
        if before > 0 and after < 2.0:
            seen.append((before, x, after))
        time.sleep(0.02)
    sim.stopSimulation()
    steps = [round(t / 0.05, 6) for b, _, a in seen for t in (b, a)]
    check("sim.getSimulationTime advances in whole 50 ms steps while running",
          len(seen) >= 5 and all(s == int(s) for s in steps) and seen[-1][2] > seen[0][0], seen)
    def at_a_step_between(before, x, after):
        k = round(x / 0.05)
        return abs(x - k * 0.05) < 1e-9 and before - 1e-9 <= k * 0.05 <= after + 1e-9
    check("the robot is where its path is at a simulation time the calls around it read",
          seen and all(at_a_step_between(*s) for s in seen), seen)
    check("after the stop: time 0, the robot back at its start",
          sim.getSimulationTime() == 0 and abs(sim.getObjectPosition(robot, floor)[0]) < 1e-9)
finally:
    stop(proc)

print(f"zmq-conformance: {passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
