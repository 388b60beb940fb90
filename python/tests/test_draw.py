"""apply and clear against `vrep-maze serve`, over both remote APIs."""

import json
import re

import pytest

import vrep_maze
from conftest import MAZES, in_python_names, Serve, cli_error, run_cli

APIS = ["legacy", "zmq"]


@pytest.mark.parametrize("api", APIS)
def test_apply_replace_and_clear(serve, api):
    port = serve.port(api)
    first = vrep_maze.generate(seed=42, algo="prim")
    report = vrep_maze.apply(first, api=api, port=port)
    lines = len(first.segments)
    assert (report.lines, report.pasted, report.reused, report.removed) == (lines, lines - 1, 0, 0)
    assert report.verified and not report.dry_run and report.round_trips > 0
    assert str(report).startswith(f"drew {lines} lines: 1 kept (the template: ")
    assert report.unchanged + report.placed + report.pasted == report.lines
    assert report.markers_unchanged + report.markers_placed == 2
    # a second maze reuses the first one's copies
    second = vrep_maze.generate(seed=7, size=(5, 5))
    again = vrep_maze.apply(second, api=api, host="127.0.0.1", port=port)
    assert again.verified and again.reused == len(second.segments) - 1 and again.pasted == 0
    assert again.removed == lines - len(second.segments)
    # the same maze again: ZeroMQ sets every kept pose unread (reading costs what setting
    # does), legacy reads them all first and sends none
    same = vrep_maze.apply(second, api=api, port=port)
    expected = same.placed if api == "zmq" else 0
    assert same.placed_unread == expected and (api == "legacy" or expected > 0), str(same)
    dry = vrep_maze.clear(api=api, port=port, dry_run=True)
    assert dry.dry_run and len(dry.removed) == len(second.segments) - 1
    cleared = vrep_maze.clear(api=api, port=port)
    assert sorted(cleared.removed) == sorted(dry.removed)
    assert vrep_maze.clear(api=api, port=port).removed == []


@pytest.mark.parametrize("api", APIS)
def test_the_report_carries_the_numbers_the_command_prints(serve, api, tmp_path):
    layout = vrep_maze.generate(seed=3, algo="kruskal", size=(6, 4))
    ours = vrep_maze.apply(layout, api=api, port=serve.port(api))
    path = tmp_path / "m.json"
    layout.save(path)
    other = Serve("--timing", "instant")  # the same fresh scene for the command
    try:
        done = run_cli("apply", path, "--api", api, "--port", other.port(api))
    finally:
        other.process.kill()
        other.process.wait()
    assert done.returncode == 0, done.stderr
    line = next(l for l in done.stdout.decode().splitlines() if l.startswith("drew"))
    without_time = lambda text: re.sub(r", [0-9.]+ s$", "", text)
    assert without_time(str(ours)) == without_time(line)
    assert "verified: every line, start and end in place" in done.stdout.decode()


def test_zmq_creates_missing_objects_and_both_apis_share_the_scene(tmp_path):
    server = Serve("--timing", "instant", "--scene", "empty")
    try:
        layout = vrep_maze.generate(seed=1, size=(4, 4))
        report = vrep_maze.apply(layout, api="zmq", port=server.zmq_port, create_missing=True,
                                 save_scene=str(tmp_path / "scene.ttt"))
        assert set(report.created) == {"Floor", "Maze", "Line", "Start", "End"}
        assert report.saved_scene == str(tmp_path / "scene.ttt") and report.verified
        # the legacy API sees the maze the ZeroMQ one drew
        legacy = vrep_maze.apply(layout, api="legacy", port=server.legacy_port)
        assert legacy.unchanged == legacy.lines and legacy.pasted == 0
        assert legacy.markers_unchanged == 2
    finally:
        server.process.kill()
        server.process.wait()


def test_refused_options_raise_value_error_with_the_commands_message():
    layout = vrep_maze.generate(seed=1, size=(3, 3))
    with pytest.raises(ValueError) as raised:
        vrep_maze.apply(layout, api="rest")
    assert str(raised.value) == in_python_names(cli_error("apply", "m.json", "--api", "rest"))
    assert "api='rest'" in str(raised.value)
    with pytest.raises(ValueError) as raised:
        vrep_maze.clear(timeout=0)
    assert str(raised.value) == in_python_names(cli_error("clear", "--timeout", "0"))
    with pytest.raises(ValueError, match="create_missing=True and save_scene need the ZeroMQ"):
        vrep_maze.apply(layout, api="legacy", create_missing=True)
    with pytest.raises(TypeError, match="unexpected keyword argument 'colour'"):
        vrep_maze.clear(colour="red")


def test_a_simulator_that_does_not_answer_is_a_simulator_error_with_hints(serve):
    port = serve.legacy_port
    serve.process.kill()
    serve.process.wait()
    with pytest.raises(vrep_maze.SimulatorError) as raised:
        vrep_maze.clear(port=port, connect_timeout=0.3)
    assert raised.value.hints, raised.value
    assert f"127.0.0.1:{port}" in str(raised.value)
    assert "hint: " in str(raised.value)


def test_missing_scene_objects_are_named_with_remedies(serve):
    layout = vrep_maze.generate(seed=1, size=(3, 3))
    with pytest.raises(vrep_maze.SimulatorError) as raised:
        vrep_maze.apply(layout, port=serve.legacy_port, line="GreenLine")
    assert "missing in the scene: GreenLine" in str(raised.value)
    assert any(" line," in hint for hint in raised.value.hints), raised.value.hints
    assert not any("--" in hint for hint in raised.value.hints), raised.value.hints


def test_remedies_that_point_to_help_point_to_pythons(serve):
    layout = vrep_maze.generate(seed=1, size=(3, 3))
    with pytest.raises((ValueError, vrep_maze.SimulatorError)) as raised:
        vrep_maze.apply(layout, port=serve.legacy_port, line="Start")
    hints = getattr(raised.value, "hints", None) or [str(raised.value)]
    assert any("see `help(vrep_maze.apply)` for the defaults" in h for h in hints), hints
    thick = vrep_maze.generate(seed=1, size=(3, 3), line_width=0.2)
    with pytest.raises(vrep_maze.SimulatorError) as raised:
        vrep_maze.apply(thick, port=serve.legacy_port)
    assert any("(see `help(vrep_maze.generate)`)" in h for h in raised.value.hints), raised.value


def test_a_small_floor_is_refused_with_remedies_in_keywords_that_work(serve):
    layout = vrep_maze.generate(seed=1, size=(12, 12))
    with pytest.raises(vrep_maze.SimulatorError) as raised:
        vrep_maze.apply(layout, api="legacy", port=serve.legacy_port)
    assert raised.value.hints[0].startswith(
        'the legacy remote API cannot resize objects: pass resize_floor=True with api="zmq"'
    ), raised.value.hints
    with pytest.raises(vrep_maze.SimulatorError) as raised:
        vrep_maze.apply(layout, api="zmq", port=serve.zmq_port)
    assert raised.value.hints == [
        "pass resize_floor=True: apply scales `Floor` to 15 x 15 m and clear puts it back to 10 x 10 m",
        "or resize `Floor` in CoppeliaSim to at least 15 x 15 m",
    ]
    assert vrep_maze.apply(layout, api="zmq", port=serve.zmq_port, resize_floor=True).verified


@pytest.mark.parametrize("api", APIS)
def test_a_wall_maze_is_drawn_and_a_line_maze_replaces_it(api):
    scene = Serve("--timing", "instant", "--scene", "course-walls")
    try:
        port = scene.port(api)
        walls = vrep_maze.generate(seed=42, style="walls")
        report = vrep_maze.apply(walls, api=api, port=port)
        assert report.verified and report.lines == len(walls.walls)
        assert str(report).startswith(f"drew {len(walls.walls)} walls")
        lines = vrep_maze.generate(seed=42)
        again = vrep_maze.apply(lines, api=api, port=port)
        assert again.verified and again.removed == len(walls.walls)
    finally:
        scene.process.kill()
        scene.process.wait()


def test_create_missing_makes_a_wall_mazes_templates(serve):
    layout = vrep_maze.generate(seed=5, size=(4, 4), style="walls", posts=True)
    report = vrep_maze.apply(layout, api="zmq", port=serve.zmq_port, create_missing=True)
    assert {"Wall", "Post"} <= set(report.created), report.created
    assert len(layout.posts) == 5 * 5  # every lattice corner
    assert report.verified and (report.lines, report.posts) == (len(layout.walls), len(layout.posts))


def test_zmq_draws_a_mesh_maze_that_copies_and_clear_replace(serve):
    port = serve.port("zmq")
    layout = vrep_maze.generate(seed=5, size=(6, 6))
    report = vrep_maze.apply(layout, api="zmq", port=port, draw="mesh")
    assert report.verified and report.meshes == 1 and report.pasted == 1, str(report)
    assert str(report).startswith(f"drew {report.lines} line runs as 1 mesh(es)")
    again = vrep_maze.apply(layout, api="zmq", port=port, draw="mesh")
    assert (again.reused, again.pasted, again.removed) == (1, 0, 0), str(again)
    copies = vrep_maze.apply(layout, api="zmq", port=port)
    # the holder and its mesh are counted apart from copies
    assert copies.meshes == 0 and copies.removed == 0 and copies.removed_meshes == 2, str(copies)
    vrep_maze.apply(layout, api="zmq", port=port, draw="mesh")
    cleared = vrep_maze.clear(api="zmq", port=port)
    # a mesh maze is named apart from copies: its mesh, then the holder
    assert cleared.removed == [] and len(cleared.removed_meshes) == 2, repr(cleared)
    assert cleared.removed_meshes[-1] == "MazeMeshes", cleared.removed_meshes
    with pytest.raises(ValueError):
        vrep_maze.apply(layout, api="zmq", port=port, draw="meshes")


@pytest.mark.parametrize("api", APIS)
def test_the_reports_carry_warnings_left_alone_and_the_template(api):
    """The new report fields: apply's `warnings`, `left_alone`, `nothing_to_do` and
    `placed`, clear's `left_alone` and `template`, as the command line says them."""
    server = Serve("--timing", "instant")
    try:
        port = server.port(api)
        # 0.8 m cells: the 1 m markers cover their neighbours, which apply warns about
        layout = vrep_maze.generate(seed=5, size=(4, 4), cell_size=0.8)
        first = vrep_maze.apply(layout, api=api, port=port)
        assert any("covers the neighbouring cells" in w for w in first.warnings), first.warnings
        assert first.left_alone == [] and not first.nothing_to_do and first.pasted > 0
        dry = vrep_maze.apply(layout, api=api, port=port, dry_run=True)
        assert dry.dry_run and dry.nothing_to_do and dry.placed == 0, str(dry)
        assert str(dry).startswith("nothing to do: the scene already shows this layout")
        planned = vrep_maze.clear(api=api, port=port, dry_run=True)
        assert planned.left_alone == []
        assert planned.template == "would put `Line` back where it stood before the first apply"
        done = vrep_maze.clear(api=api, port=port)
        assert done.template is not None and done.template.startswith("put `Line` back")
        # print(report) shows the lines `vrep-maze clear` prints, as an apply report does
        assert str(done).splitlines() == [
            done.template,
            "put `Start` and `End` back where they stood before the first apply",
            f"removed {len(done.removed)} maze copies: {', '.join(done.removed[:12])}"
            + (f", ... ({len(done.removed) - 12} more)" if len(done.removed) > 12 else ""),
        ]
        assert done.markers == str(done).splitlines()[1]
        again = vrep_maze.clear(api=api, port=port)
        assert again.template is None and again.markers is None
        assert str(again) == (
            "nothing to remove: no maze (copies of lines, walls, posts, or meshes) under Maze"
            " in the scene")
    finally:
        server.process.kill()
        server.process.wait()


# The jobs both adapters run in turn on a fresh emulator each: a maze, the next one over it
# (reuse), a dry run over that, the other draw mode over it, and a wall maze with posts.
SAME_JOBS = [
    ("prim-9x9-seed42.json", {}),
    ("kruskal-9x9-seed42.json", {}),
    ("kruskal-9x9-seed42.json", {"dry_run": True}),
    ("dfs-9x9-seed42.json", {"draw": "mesh"}),
    ("prim-9x9-seed42.json", {}),
    ("dfs-9x9-seed42-walls.json", {"scene": "course-walls"}),
]

# The fields of `apply --json` that the Python report has under the same name.
COMPARED = ["lines", "posts", "reused", "pasted", "removed", "removed_meshes", "unchanged",
            "placed", "markers_unchanged", "markers_placed", "nothing_to_do", "edits",
            "round_trips", "stopped_simulation", "dry_run", "verified", "created",
            "saved_scene"]


def run_jobs(api: str, through_cli: bool, scene: str | None) -> list[dict]:
    """`SAME_JOBS` of `scene` on a fresh emulator through one adapter: the compared fields of
    each report."""
    extra = ["--scene", scene] if scene else []
    server = Serve("--timing", "instant", *extra)
    reports = []
    try:
        port = server.port(api)
        for name, options in SAME_JOBS:
            options = dict(options)
            if options.pop("scene", None) != scene:
                continue
            path = MAZES / name
            if through_cli:
                words = [f"--{k.replace('_', '-')}" if v is True else f"--{k}={v}"
                         for k, v in options.items()]
                done = run_cli("apply", path, "--api", api, "--port", port, "--json", *words)
                assert done.returncode == 0, done
                document = json.loads(done.stdout.decode().strip().splitlines()[-1])
                # `--json` leaves out an empty `created` and an unsaved scene
                absent = {"created": [], "saved_scene": None}
                reports.append({k: document.get(k, absent.get(k)) for k in COMPARED})
            else:
                report = vrep_maze.apply(vrep_maze.load(path), api=api, port=port, **options)
                reports.append({k: getattr(report, k) for k in COMPARED})
    finally:
        server.stop()
    return reports


@pytest.mark.parametrize("scene", [None, "course-walls"])
@pytest.mark.parametrize("api", APIS)
def test_the_command_line_and_python_run_the_same_jobs_alike(api, scene):
    # both are adapters over one `draw::run`: the same jobs give the same reports
    by_cli = run_jobs(api, True, scene)
    by_python = run_jobs(api, False, scene)
    assert by_cli and by_cli == by_python
