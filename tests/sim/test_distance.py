"""The e-puck2's time-of-flight sensor in Enki worlds (issue 27): the
reading `distance` is a ray straight ahead from the body's edge."""
import pytest

from conftest import require_enki
from tests.support.world import run

PROGRAM = """var d = 0 mm
after 50 ms do d = distance
after 100 ms do exit_main
"""


@pytest.mark.parametrize("world, expected_mm", [
    # a wall 40 cm ahead of the centre: 400 - 37 (the body's radius)
    ("arena 100 cm x 100 cm\nrobot at 60 cm, 50 cm heading 0 deg\n", 400 - 37),
    # a box's near face 200 mm ahead, another robot 150 mm ahead (centres 224 mm apart)
    ("arena 200 cm x 200 cm\nrobot at 50 cm, 50 cm heading 90 deg\n"
     "box at 50 cm, 75 cm size 20 cm x 10 cm\n", 200 - 37),
    ("arena 200 cm x 200 cm\nrobot at 50 cm, 50 cm heading 180 deg\n"
     "robot other at 27.6 cm, 50 cm\n", 224 - 2 * 37),
    # nothing within 2 m: RT_DISTANCE_MAX
    ("arena none\nrobot at 0 cm, 0 cm\n", 2000),
])
def test_distance_is_the_ray_ahead(tmp_path, world, expected_mm):
    require_enki()
    (tmp_path / "tof.epk").write_text(PROGRAM)
    (tmp_path / "w.world").write_text(world)
    records, _, _ = run(tmp_path / "tof.epk", tmp_path, "--world", tmp_path / "w.world")
    first = next(r for r in records if r["kind"] == "set" and r["var"] == "d")
    assert abs(first["value"] - expected_mm) <= 1
