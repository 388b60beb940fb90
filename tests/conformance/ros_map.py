"""`vrep-maze export -o maze.yaml`, read as ROS map_server reads a map.

Usage: ros_map.py VREP_MAZE_BINARY

No ROS or nav2 map loader installs from PyPI or Debian, so the files are read with parsers
that are not ours, PyYAML for the YAML and Pillow for the PGM, and the map is made from them
by map_server's own rules (nav2_map_server `map_io.cpp`, ROS 1 `map_server/image_loader`):

- the YAML has `image` (relative to the YAML's folder), `resolution` (metres a pixel),
  `origin` (x, y, yaw of the lower-left pixel's corner), `negate`, `occupied_thresh`,
  `free_thresh` and `mode`;
- a pixel's occupancy is `(255 - value) / 255` (`value` inverted first when `negate` is 1);
  in `trinary` mode it is occupied (100) above `occupied_thresh`, free (0) below
  `free_thresh`, unknown (-1) between;
- map cell (i, j), j counted from the south, is image column i, row `height - 1 - j`; its
  centre is `origin + ((i + 0.5) * resolution, (j + 0.5) * resolution)`.

Then, point by point on a 30-degree-turned line maze and wall maze with posts: every line
segment's centre is free and every cell corner occupied (the reverse with
`--occupied-lines`); every wall's centre and the points along it are occupied and every cell
centre free; nothing is unknown. The same map read with `negate: 1` must fail the line
check, so the checks cannot pass by accident. Maps written under file names that YAML reads
as something else when bare (`a #b.yaml`, `c: d.yaml`, a newline, a leading space, ...) name
their own PGM.

Prints one line per check and `ros-map: N passed, M failed` last; exits 1 on failure.
"""

import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

import yaml
from PIL import Image

BIN = sys.argv[1]
RESULTS = []
KEYS = {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh", "mode"}


def check(name, ok, detail=""):
    RESULTS.append(ok)
    print(("ok   " if ok else "FAIL ") + name + (f": {detail}" if detail else ""), flush=True)


def vrep_maze(*args):
    done = subprocess.run([BIN, *args], capture_output=True, text=True, timeout=120)
    if done.returncode != 0:
        sys.exit(f"vrep-maze {' '.join(args)} failed: {done.stderr.strip()}")


def load(path, negate=None):
    """The map as map_server makes it: (meta, width, height, cells by [j][i])."""
    with open(path) as f:
        meta = yaml.safe_load(f)
    if negate is not None:
        meta["negate"] = negate
    image = Image.open(os.path.join(os.path.dirname(path), meta["image"]))
    width, height = image.size
    grey = image.convert("L")
    pixels = grey.load()
    cells = []
    for j in range(height):
        row = []
        for i in range(width):
            value = pixels[i, height - 1 - j]
            if meta["negate"]:
                value = 255 - value
            occ = (255 - value) / 255.0
            row.append(100 if occ > meta["occupied_thresh"]
                       else 0 if occ < meta["free_thresh"] else -1)
        cells.append(row)
    return meta, width, height, cells, image


def at(m, x, y):
    meta, width, height, cells, _ = m
    ox, oy, _ = meta["origin"]
    i = math.floor((x - ox) / meta["resolution"])
    j = math.floor((y - oy) / meta["resolution"])
    return cells[j][i] if 0 <= i < width and 0 <= j < height else None


def grid_point(layout, gx, gy):
    """Floor point of grid coordinates (gx, gy) in cells (cell centres are whole numbers)."""
    g = layout["grid"]
    c, (ox, oy), r = g["cell_size"], g["origin"], g["rotation"]
    x, y = gx * c, gy * c
    return ox + x * math.cos(r) - y * math.sin(r), oy + x * math.sin(r) + y * math.cos(r)


def corners(layout):
    g = layout["grid"]
    return [grid_point(layout, cx + 0.5, cy + 0.5)
            for cx in range(g["columns"] - 1) for cy in range(g["rows"] - 1)]


tmp = tempfile.mkdtemp(prefix="ros-map-")
MAZES = {
    "lines": ["--size", "5x4", "--seed", "11", "--rotation", "30"],
    "walls": ["--size", "5x4", "--seed", "11", "--rotation", "30", "--style", "walls",
              "--posts"],
}
layouts = {}
for style, options in MAZES.items():
    path = os.path.join(tmp, f"{style}.json")
    vrep_maze("generate", "-q", *options, "-o", path)
    with open(path) as f:
        layouts[style] = json.load(f)
    vrep_maze("export", path, "-o", os.path.join(tmp, f"{style}.yaml"))
vrep_maze("export", os.path.join(tmp, "lines.json"), "-o", os.path.join(tmp, "reverse.yml"),
          "--occupied-lines", "--px-per-m", "40")

for name in ["lines.yaml", "walls.yaml", "reverse.yml"]:
    m = load(os.path.join(tmp, name))
    meta, width, height, cells, image = m
    check(f"{name}: PyYAML reads every map_server key",
          KEYS <= set(meta) and meta["mode"] == "trinary" and meta["negate"] == 0,
          ", ".join(sorted(meta)))
    check(f"{name}: Pillow reads {meta['image']} as an 8-bit grey PGM",
          image.format == "PPM" and image.mode == "L", f"{image.format} {image.mode} "
          f"{width}x{height}")
    floor = layouts["walls" if name.startswith("walls") else "lines"]["floor"]["size"]
    ox, oy, yaw = meta["origin"]
    check(f"{name}: origin is the floor's south-west corner, the map covers the floor",
          (ox, oy, yaw) == (-floor[0] / 2, -floor[1] / 2, 0)
          and width * meta["resolution"] >= floor[0] and height * meta["resolution"] >= floor[1],
          f"origin {meta['origin']}, {width * meta['resolution']} m wide")
    unknown = sum(row.count(-1) for row in cells)
    check(f"{name}: no cell is unknown", unknown == 0, f"{unknown} unknown")

lines = layouts["lines"]
m = load(os.path.join(tmp, "lines.yaml"))
on = [at(m, s["x"], s["y"]) for s in lines["segments"]]
off = [at(m, x, y) for x, y in corners(lines)]
check("lines.yaml: every segment's centre is free, every cell corner occupied",
      on.count(0) == len(on) and off.count(100) == len(off),
      f"{on.count(0)}/{len(on)} free, {off.count(100)}/{len(off)} occupied")
outside = at(m, lines["floor"]["size"][0] / 2 - 0.01, lines["floor"]["size"][1] / 2 - 0.01)
check("lines.yaml: the ground off the lines is occupied", outside == 100, str(outside))
wrong = load(os.path.join(tmp, "lines.yaml"), negate=1)
on = [at(wrong, s["x"], s["y"]) for s in lines["segments"]]
check("read with negate: 1 the same image fails the line check", on.count(0) == 0,
      f"{on.count(0)} free")

m = load(os.path.join(tmp, "reverse.yml"))
on = [at(m, s["x"], s["y"]) for s in lines["segments"]]
off = [at(m, x, y) for x, y in corners(lines)]
check("reverse.yml (--occupied-lines, 40 px/m): segments occupied, cell corners free",
      m[0]["resolution"] == 0.025 and on.count(100) == len(on) and off.count(0) == len(off),
      f"{on.count(100)}/{len(on)} occupied, {off.count(0)}/{len(off)} free")

walls = layouts["walls"]
m = load(os.path.join(tmp, "walls.yaml"))
along = []
for w in walls["walls"]:
    half = walls["wall"]["length"] / 2 * 0.9
    for k in range(-4, 5):
        d = half * k / 4
        along.append(at(m, w["x"] + d * math.cos(w["yaw"]), w["y"] + d * math.sin(w["yaw"])))
g = walls["grid"]
centres = [at(m, *grid_point(walls, cx, cy))
           for cx in range(g["columns"]) for cy in range(g["rows"])]
posts = [at(m, p["x"], p["y"]) for p in walls["posts"]]
check("walls.yaml: every wall occupied along its length, every post occupied",
      along.count(100) == len(along) and posts.count(100) == len(posts),
      f"{along.count(100)}/{len(along)} wall points, {posts.count(100)}/{len(posts)} posts")
check("walls.yaml: every cell centre is free", centres.count(0) == len(centres),
      f"{centres.count(0)}/{len(centres)}")

# file names YAML reads as something else when written bare (a comment, a mapping, flow
# collections, an alias, an anchor, a tag, a directive, reserved indicators, quotes, block
# scalars, a line break, a leading space, a backslash, a control sequence): the YAML must
# name each one's PGM, which Pillow then opens
HOSTILE = ["a #b", "c: d", "[e", "{f", "*g", "&h", "!i", "'j\"", "%k", "@l", "|m", ">n",
           "o\np", " q", "r\\s", "t\x1b[31m", "u\tv", "w\u2028x", "-", "~", "null", "y,z"]
named = []
for name in HOSTILE:
    path = os.path.join(tmp, f"{name}.yaml")
    vrep_maze("export", os.path.join(tmp, "lines.json"), "-o", path)
    try:
        meta = load(path)[0]
        named.append(meta["image"] == f"{name}.pgm" and meta["mode"] == "trinary")
    except Exception as e:  # a YAML error is a failed check, named below
        print(f"     {name!r}: {type(e).__name__}: {e}")
        named.append(False)
check(f"a hostile file name's YAML names its own PGM ({len(HOSTILE)} names)",
      all(named), ", ".join(repr(n) for n, ok in zip(HOSTILE, named) if not ok))

shutil.rmtree(tmp)
passed, failed = RESULTS.count(True), RESULTS.count(False)
print(f"ros-map: {passed} passed, {failed} failed")
sys.exit(1 if failed else 0)
