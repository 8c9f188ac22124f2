"""The studio's folder (epuckc/studio/workspace.py): every path the page
names stays inside it, saves are whole and never overwrite a change made
outside."""
from __future__ import annotations

import os

import pytest

from epuckc.studio.workspace import Conflict, PathRefused, Workspace, version_of


@pytest.fixture
def ws(tmp_path):
    root = tmp_path / "class"
    root.mkdir()
    (root / "a.epk").write_text("on immediate do set_speed(1 steps/s, 1 steps/s)\n")
    (root / "sub").mkdir()
    (root / "sub" / "b.world").write_text("arena 1 m x 1 m\nrobot at 10 cm, 10 cm\n")
    (tmp_path / "secret.epk").write_text("outside\n")
    return Workspace(root)


@pytest.mark.parametrize("path", ["../secret.epk", "sub/../../secret.epk", "/etc/passwd",
                                  "sub//b.world", "./a.epk", ".hidden.epk", "sub\\b.world",
                                  "", "a.epk\0", "sub/.git/config"])
def test_paths_that_leave_or_hide_are_refused(ws, path):
    with pytest.raises(PathRefused):
        ws.resolve(path)


def test_a_link_out_of_the_folder_is_refused_and_not_listed(ws, tmp_path):
    os.symlink(tmp_path / "secret.epk", ws.root / "link.epk")
    os.symlink(tmp_path, ws.root / "up")
    with pytest.raises(PathRefused):
        ws.read("link.epk")
    with pytest.raises(PathRefused):
        ws.read("up/secret.epk")
    with pytest.raises(PathRefused):
        ws.save("link.epk", "x", version_of(b"outside\n"))
    assert (tmp_path / "secret.epk").read_text() == "outside\n"
    assert ws.files() == ["a.epk", "sub/b.world"]


def test_a_link_inside_the_folder_is_followed(ws):
    os.symlink(ws.root / "a.epk", ws.root / "same.epk")
    assert ws.read("same.epk") == ws.read("a.epk")


def test_save_writes_over_the_version_read_and_refuses_another(ws):
    text, version = ws.read("a.epk")
    new = ws.save("a.epk", text + "# more\n", version)
    assert (ws.root / "a.epk").read_text() == text + "# more\n"
    assert new == version_of((ws.root / "a.epk").read_bytes()) != version
    # an editor outside the studio changes the file: the old version no longer saves
    (ws.root / "a.epk").write_text("changed outside\n")
    with pytest.raises(Conflict) as exc:
        ws.save("a.epk", "mine\n", new)
    assert exc.value.version == version_of(b"changed outside\n")
    assert (ws.root / "a.epk").read_text() == "changed outside\n"
    # a new file only where there is none
    assert ws.save("c.epk", "x\n", None)
    with pytest.raises(Conflict):
        ws.save("c.epk", "y\n", None)


def test_save_leaves_no_temporary_file_and_keeps_other_kinds_out(ws):
    ws.save("sub/new.scn", "0 ms ir0 = 0\n", None)
    assert sorted(p.name for p in (ws.root / "sub").iterdir()) == ["b.world", "new.scn"]
    with pytest.raises(PathRefused):
        ws.save("run.sh", "rm -rf /\n", None)
    assert not (ws.root / "run.sh").exists()


def test_a_new_world_is_a_world_file_that_parses(ws):
    from epuckc.sim.world import parse_world
    ws.new_world("arena2.world")
    world = parse_world(ws.root / "arena2.world")
    assert len(world.robots) == 1
    with pytest.raises(Conflict):
        ws.new_world("arena2.world")
