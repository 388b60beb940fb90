"""Layout.export: the files `vrep-maze export` writes, chosen by the ending."""

import pytest

import vrep_maze
from conftest import MAZES, run_cli

GOLDEN = MAZES / "dfs-9x9-seed42-walls.json"
ENDINGS = [".simmodel.xml", ".simscene.xml", ".mjcf", ".mujoco.xml", ".sdf", ".world",
           ".urdf", ".wbt", ".pointmaze.json"]


@pytest.mark.parametrize("ending", ENDINGS)
def test_export_writes_what_the_command_writes(tmp_path, ending):
    ours, theirs = tmp_path / f"ours{ending}", tmp_path / f"theirs{ending}"
    assert vrep_maze.load(GOLDEN).export(ours) is None
    done = run_cli("export", GOLDEN, "-o", theirs)
    assert done.returncode == 0, done.stderr
    assert ours.read_bytes() == theirs.read_bytes()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([ours.name, theirs.name])


def test_export_refuses_unknown_and_ambiguous_endings(tmp_path):
    layout = vrep_maze.load(GOLDEN)
    with pytest.raises(ValueError, match=r"a bare \.xml is ambiguous.*\.mjcf, \.mujoco\.xml"):
        layout.export(tmp_path / "m.xml")
    with pytest.raises(ValueError, match=r"\.sdf, \.world, \.urdf, \.wbt"):
        layout.export(str(tmp_path / "m.obj"))
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("ending", [".yaml", ".yml"])
def test_export_writes_a_ros_map_as_the_command_does(tmp_path, ending):
    ours, theirs = tmp_path / "ours", tmp_path / "theirs"
    ours.mkdir()
    theirs.mkdir()
    assert vrep_maze.load(GOLDEN).export(ours / f"m{ending}") is None
    done = run_cli("export", GOLDEN, "-o", theirs / f"m{ending}")
    assert done.returncode == 0, done.stderr
    for name in [f"m{ending}", "m.pgm"]:
        assert (ours / name).read_bytes() == (theirs / name).read_bytes()
    assert sorted(p.name for p in ours.iterdir()) == sorted(p.name for p in theirs.iterdir())


@pytest.mark.parametrize("name", ["a #b", "c: d", "[e", "{f", "*g", "&h", "!i", "'j\"", "%k",
                                  "@l", "|m", ">n", "o\np", " q", "r\\s", "t\x1b[31m"])
def test_a_ros_maps_yaml_names_its_own_image_for_any_file_name(tmp_path, name):
    yaml = pytest.importorskip("yaml")
    path = tmp_path / f"{name}.yaml"
    vrep_maze.load(GOLDEN).export(path)
    meta = yaml.safe_load(path.read_text())
    assert meta["image"] == f"{name}.pgm" and meta["mode"] == "trinary", path.read_text()
    assert (tmp_path / meta["image"]).is_file()


@pytest.mark.skipif(not hasattr(__import__("os"), "symlink"), reason="needs symbolic links")
def test_a_ros_map_that_cannot_be_written_leaves_no_file_behind(tmp_path):
    yaml = tmp_path / "s.yaml"
    yaml.symlink_to(tmp_path / "gone" / "s.yaml")
    with pytest.raises(FileNotFoundError, match="s.yaml: .*so neither file was written"):
        vrep_maze.load(GOLDEN).export(yaml)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["s.yaml"]
