"""The exported robot-simulator files, read by each simulator's own parser.

Usage: export_parsers.py VREP_MAZE_BINARY

For a line maze and a wall maze with posts (both turned by 30 degrees), `vrep-maze export`
writes every format, then:

- MJCF: MuJoCo (PyPI `mujoco`) loads it, its geoms are counted against the layout, and a
  small ball pushed at a wall for 600 steps is stopped by it (in the line maze the same push
  crosses the lines, which touch nothing);
- SDF (`.sdf`, `.world`) and URDF: libsdformat's `ign sdf -k` says valid, `ign sdf -p`
  (libsdformat's own reading, URDF converted) is counted; urdfdom's `check_urdf` parses the
  URDF's link tree;
- each parser is also shown a broken file and must refuse it, so none of these checks can
  pass by accident.

Prints one line per check and `export-parsers: N passed, M failed` last; exits 1 on failure.
"""

import json
import math
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import mujoco

BIN = sys.argv[1]
RESULTS = []


def check(name, ok, detail=""):
    RESULTS.append(ok)
    print(("ok   " if ok else "FAIL ") + name + (f": {detail}" if detail else ""), flush=True)


def run(*args):
    return subprocess.run(args, capture_output=True, text=True, timeout=120)


def vrep_maze(*args):
    done = run(BIN, *args)
    if done.returncode != 0:
        sys.exit(f"vrep-maze {' '.join(args)} failed: {done.stderr.strip()}")


# --- the files --------------------------------------------------------------------------

tmp = tempfile.mkdtemp(prefix="export-parsers-")
MAZES = {
    "lines": ["--size", "5x4", "--seed", "11", "--rotation", "30"],
    "walls": ["--size", "5x4", "--seed", "11", "--rotation", "30", "--style", "walls",
              "--posts"],
}
ENDINGS = [".mjcf", ".mujoco.xml", ".sdf", ".world", ".urdf", ".wbt"]
layouts = {}
for style, options in MAZES.items():
    path = os.path.join(tmp, f"{style}.json")
    vrep_maze("generate", "-q", *options, "-o", path)
    with open(path) as f:
        layouts[style] = json.load(f)
    for ending in ENDINGS:
        vrep_maze("export", path, "-o", os.path.join(tmp, style + ending))


def file(style, ending):
    return os.path.join(tmp, style + ending)


def read(path):
    with open(path) as f:
        return f.read()


# --- MuJoCo -----------------------------------------------------------------------------

def mujoco_model(text):
    return mujoco.MjModel.from_xml_string(text)


def geoms(model, prefix):
    return [i for i in range(model.ngeom)
            if (mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, i) or "").startswith(prefix)]


def push_ball(style, speed=3.0, steps=600):
    """A ball of 4 cm radius at the centre of cell (0, 0), pushed west (the maze's -x, across
    the outer wall of a wall maze): how far west its centre got, and the names of the geoms
    it touched."""
    layout = layouts[style]
    rotation = layout["grid"]["rotation"]
    x0, y0 = layout["grid"]["origin"]
    west = (-math.cos(rotation), -math.sin(rotation))
    ball = (f'<body name="ball" pos="{x0} {y0} 0.05"><freejoint/>'
            '<geom name="ball" type="sphere" size="0.04" mass="0.05"/></body>')
    text = read(file(style, ".mjcf")).replace("</worldbody>", ball + "</worldbody>")
    model = mujoco_model(text)
    data = mujoco.MjData(model)
    data.qvel[0:3] = [west[0] * speed, west[1] * speed, 0.0]
    farthest, touched = 0.0, set()
    for _ in range(steps):
        mujoco.mj_step(model, data)
        x, y = data.qpos[0] - x0, data.qpos[1] - y0
        farthest = max(farthest, x * west[0] + y * west[1])
        for c in data.contact[: data.ncon]:
            for g in (c.geom1, c.geom2):
                touched.add(mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g))
    return farthest, touched


print(f"mujoco {mujoco.__version__}")
for style in MAZES:
    layout = layouts[style]
    for ending in (".mjcf", ".mujoco.xml"):
        check(f"MuJoCo loads {style}{ending}", mujoco_model(read(file(style, ending))).ngeom > 1)
    model = mujoco_model(read(file(style, ".mjcf")))
    sites = {mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_SITE, i) for i in range(model.nsite)}
    check(f"MuJoCo {style}: sites start and end", sites == {"start", "end"}, str(sites))
    walls, posts, lines = geoms(model, "wall_"), geoms(model, "post_"), geoms(model, "line_")
    check(f"MuJoCo {style}: floor + maze geoms = all geoms",
          model.ngeom == 1 + len(walls) + len(posts) + len(lines), f"{model.ngeom} geoms")
    if style == "walls":
        cell = layout["grid"]["cell_size"]
        length = sum(2 * max(model.geom_size[g][:2]) for g in walls)
        check("MuJoCo walls: the runs are as long as the layout's walls",
              abs(length - len(layout["walls"]) * cell) < 1e-5,
              f"{len(walls)} runs, {length:.6f} m for {len(layout['walls'])} walls")
        check("MuJoCo walls: one post geom per post", len(posts) == len(layout["posts"]),
              f"{len(posts)} posts")
        check("MuJoCo walls: walls and posts collide",
              all(model.geom_contype[g] and model.geom_conaffinity[g] for g in walls + posts))
        farthest, touched = push_ball("walls")
        check("MuJoCo walls: a ball pushed west at 3 m/s stops at the outer wall",
              0.3 < farthest < 0.5 - 0.025 and any(t and t.startswith("wall_") for t in touched),
              f"got {farthest:.3f} m from the cell centre (wall face at 0.475 m), "
              f"touched {sorted(t for t in touched if t)}")
    else:
        check("MuJoCo lines: no walls or posts, some lines", not walls and not posts and lines)
        check("MuJoCo lines: lines collide with nothing",
              all(model.geom_contype[g] == 0 and model.geom_conaffinity[g] == 0 for g in lines))
        farthest, touched = push_ball("lines")
        check("MuJoCo lines: the same push crosses the maze's edge, touching no line",
              farthest > 0.6 and not any(t and t.startswith("line_") for t in touched),
              f"got {farthest:.3f} m, touched {sorted(t for t in touched if t)}")
try:
    mujoco_model(read(file("walls", ".mjcf")).replace('type="box"', 'type="boxx"', 1))
    check("MuJoCo refuses a broken file", False)
except ValueError as e:
    check("MuJoCo refuses a broken file", True, str(e).splitlines()[0])


# --- libsdformat and urdfdom ------------------------------------------------------------

def sdf_check(path):
    done = run("ign", "sdf", "-k", path)
    said = [l for l in (done.stdout + done.stderr).splitlines() if "backward" not in l]
    return done.returncode == 0 and "Valid." in done.stdout, "\n".join(said).strip()


def sdf_print(path):
    done = run("ign", "sdf", "-p", path)
    if done.returncode != 0:
        return None
    return ET.fromstring(done.stdout)


versions = run("dpkg-query", "-W", "-f", "${Package} ${Version}\n", "libsdformat12-12",
               "liburdfdom-tools", "ignition-tools").stdout.strip()
print(versions.replace("\n", ", "))
for style in MAZES:
    for ending in (".sdf", ".world"):
        ok, said = sdf_check(file(style, ending))
        check(f"libsdformat: {style}{ending} is valid", ok, said.splitlines()[-1] if said else "")
    root = sdf_print(file(style, ".sdf"))
    models = {m.get("name"): m for m in root.iter("model")} if root is not None else {}
    maze = models.get("maze")
    check(f"libsdformat {style}: a ground plane and one static maze model",
          set(models) == {"ground_plane", "maze"} and maze.findtext("static") in ("true", "1"),
          str(sorted(models)))
    mj = mujoco_model(read(file(style, ".mjcf")))
    boxes = len(geoms(mj, "wall_")) + len(geoms(mj, "post_")) + len(geoms(mj, "line_"))
    solid = len(geoms(mj, "wall_")) + len(geoms(mj, "post_"))
    visuals = [v.get("name") for v in maze.iter("visual")]
    collisions = list(maze.iter("collision"))
    check(f"libsdformat {style}: one collision per MuJoCo wall/post geom, visuals for all",
          len(collisions) == solid and len(visuals) == boxes + 2
          and {"start", "end"} <= set(visuals),
          f"{len(collisions)} collisions, {len(visuals)} visuals")

    done = run("check_urdf", file(style, ".urdf"))
    check(f"urdfdom check_urdf: {style}.urdf parses, world -> maze",
          done.returncode == 0 and "root Link: world" in done.stdout
          and "child(1):  maze" in done.stdout, done.stdout.strip().splitlines()[-1])
    urdf = sdf_print(file(style, ".urdf"))
    collisions = list(urdf.iter("collision")) if urdf is not None else []
    visuals = list(urdf.iter("visual")) if urdf is not None else []
    check(f"libsdformat reads {style}.urdf: a collision per wall run and post, visuals for all",
          urdf is not None and len(collisions) == solid and len(visuals) == boxes + 3,
          f"{len(collisions)} collisions, {len(visuals)} visuals (floor, boxes, start, end)")

broken = os.path.join(tmp, "broken.sdf")
with open(broken, "w") as f:
    f.write(read(file("walls", ".sdf")).replace('name="wall_1_collision"',
                                                'name="wall_0_collision"', 1))
ok, said = sdf_check(broken)
check("libsdformat refuses a duplicate name", not ok, said.splitlines()[0] if said else "")
broken = os.path.join(tmp, "broken.urdf")
with open(broken, "w") as f:
    f.write(read(file("walls", ".urdf")).replace('<link name="world"/>', "", 1))
done = run("check_urdf", broken)
check("check_urdf refuses a joint to a missing link", done.returncode != 0)

shutil.rmtree(tmp)
passed, failed = RESULTS.count(True), RESULTS.count(False)
print(f"export-parsers: {passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
