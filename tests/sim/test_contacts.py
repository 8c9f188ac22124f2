"""What a robot touched, told apart (issue 41): Enki reports a collision
with a wall and with a static box or cylinder alike, with no partner, and
the world runner tells them apart from the world's own objects
(runtime_c/enki/contacts.h). A blind robot is driven into each kind on its
own, with walls around and without; each count is checked apart (a sum of
the three could not see a wall counted for a cylinder), in the run's
summary line, the trace's `contacts` record, the experiment's columns and
the picture's label."""
import csv

import pytest

from conftest import require_enki

from tests.support.world import by_class, epuckc, run, svg

BLIND = ("on immediate do start_straight(400 steps/s, 1 m)\n"
         "on stop_motor do exit_main\n")
# the robot starts at (10 cm, 20 cm) heading along +x: what is at 40 cm is hit
THINGS = {
    "wall": "",
    "box": "box at 40 cm, 20 cm size 6 cm x 30 cm angle 20 deg\n",
    "cylinder": "cylinder at 40 cm, 20 cm radius 6 cm\n",
    "robot": "robot other at 40 cm, 20 cm heading 180 deg\n",
}


@pytest.fixture(autouse=True)
def _enki():
    require_enki()


def _world(tmp_path, thing: str, walled: bool) -> str:
    # the wall case: an arena whose right wall is what is met; otherwise the
    # walls are far beyond the thing (or there are none)
    arena = ("arena 40 cm x 60 cm\n" if thing == "wall" else
             "arena 200 cm x 60 cm\n" if walled else "arena none\n")
    path = tmp_path / f"{thing}-{walled}.world"
    path.write_text(arena + "robot r1 at 10 cm, 20 cm heading 0 deg\n" + THINGS[thing])
    return path


def _contacts(records, robot="r1"):
    [c] = [r for r in records if r["kind"] == "contacts" and r["robot"] == robot]
    return c


@pytest.mark.parametrize("thing,walled", [("wall", True), ("box", True), ("box", False),
                                          ("cylinder", True), ("cylinder", False),
                                          ("robot", True), ("robot", False)])
def test_each_kind_is_counted_as_what_it_is(tmp_path, thing, walled):
    program = tmp_path / "blind.epk"
    program.write_text(BLIND)
    picture = tmp_path / "run.svg"
    records, out, _ = run(program, tmp_path, "--world", _world(tmp_path, thing, walled),
                          "--time-limit", "7s", "--svg", picture, expect=3)
    c = _contacts(records)
    key = {"wall": "walls", "box": "objects", "cylinder": "objects", "robot": "robots"}[thing]
    assert c[key] > 50, c
    assert all(c[k] == 0 for k in ("walls", "objects", "robots") if k != key), c
    assert c["steps"] == c[key] and 0 < c["first_ms"] < 7000
    words = {"walls": "walls", "objects": "obstacles", "robots": "robots"}[key]
    assert f"r1: {c[key]} physics steps in contact with {words}; the first at " \
           f"{c['first_ms']} ms" in out
    if thing == "robot":        # and the other robot saw the same
        assert _contacts(records, "other")["robots"] > 50
    # the marker's tooltip says it (and its label, where there is room for one)
    said = f"{c[key]} steps in contact with {words}"
    root = svg(picture)
    tips = [t.text for e in by_class(root, "contact") for t in e.iter() if t.tag.endswith("title")]
    assert f"r1: {c['first_ms']} ms {said}" in tips, tips
    assert all(e.text.endswith(" steps in contact with " + words)
               for e in by_class(root, "contact-label"))


def test_a_robot_wedged_between_a_box_and_a_wall_touches_both(tmp_path):
    """Each in its own count, and a step touching both is one step."""
    program = tmp_path / "blind.epk"
    program.write_text(BLIND)
    world = tmp_path / "corner.world"
    world.write_text("arena 40 cm x 60 cm\nbox at 35 cm, 10 cm size 10 cm x 20 cm\n"
                     "robot at 10 cm, 22 cm heading -30 deg\n")
    records, out, _ = run(program, tmp_path, "--world", world, "--time-limit", "8s", expect=3)
    c = _contacts(records)
    assert c["walls"] > 20 and c["objects"] > 20 and c["robots"] == 0, c
    assert max(c["walls"], c["objects"]) <= c["steps"] < c["walls"] + c["objects"]
    assert f"{c['steps']} physics steps in contact: {c['walls']} with walls, " \
           f"{c['objects']} with obstacles" in out


def test_the_experiment_s_columns_count_the_obstacle(tmp_path):
    (tmp_path / "blind.epk").write_text(BLIND)
    (tmp_path / "cyl.world").write_text("arena 100 cm x 60 cm\ncylinder at 40 cm, 20 cm radius "
                                        "6 cm\nrobot at 10 cm, 20 cm heading 0 deg\n")
    (tmp_path / "exp.toml").write_text('program = "blind.epk"\nworld = "cyl.world"\n'
                                       'duration = "6 s"\nseeds = 1\nmetrics = ["contacts"]\n')
    result = epuckc("experiment", "exp.toml", "-o", "out", cwd=tmp_path)
    assert result.returncode == 0, result.stdout + result.stderr
    with open(tmp_path / "out" / "runs.csv", newline="") as f:
        [row] = list(csv.DictReader(f))
    assert int(row["contacts_objects"]) > 50
    assert (row["contacts_walls"], row["contacts_robots"]) == ("0", "0")
    assert row["contacts"] == row["contacts_objects"]
