"""IR messages between robots in Enki worlds, through the whole pipeline
(issue 27): `send`, `on message` and its readings, compiled, run by the
runtime over libIrcom's API, carried by the world's channel model
(runtime_c/enki/world_channel.h). Skipped without Enki, except in CI."""
import math

import pytest

from tests.support.world import EXAMPLES, epuckc, run

# the channel's model error (docs/world.md): the bearing is the direction of
# the receiving sensor nearest to the true one, and the e-puck's widest gap
# between two sensors is 60 degrees (150 to 210); the range is the true
# distance times 1 +- range_noise (10 % by default)
BEARING_ERROR_DEG = 30.0
RANGE_NOISE = 0.10

SENDER = """var n = 0
every 200 ms do send(n), n = clamp(n + 1, 0, 255)
"""
LISTENER = """var v = 0
var b = 0 deg
var r = 0 mm
var heard = 0
on message repeat do v = message, b = message_bearing, r = message_range, heard = clamp(heard, 0, 1000) + 1
"""


pytestmark = pytest.mark.usefixtures("enki")


def _world(tmp_path, body: str, name="w.world"):
    (tmp_path / "sender.epk").write_text(SENDER)
    (tmp_path / "listener.epk").write_text(LISTENER)
    path = tmp_path / name
    path.write_text(body)
    return path


def _run(tmp_path, world, time_limit="2s", *extra, name="trace"):
    records, _, text = run(tmp_path / "listener.epk", tmp_path, "--world", world,
                           "--time-limit", time_limit, *extra, name=name, expect=None)
    return records, text


def _wrap(deg: float) -> float:
    return (deg + 180.0) % 360.0 - 180.0


def _true_bearing(m: dict) -> float:
    """Where the sender was, seen from the receiver: degrees counter-clockwise
    from its heading, from the poses in the delivery's record."""
    world = math.degrees(math.atan2(m["from_y_mm"] - m["y_mm"], m["from_x_mm"] - m["x_mm"]))
    return _wrap(world - m["heading_deg"])


def _deliveries(records, robot=None):
    return [r for r in records if r["kind"] == "message"
            and (robot is None or r["robot"] == robot)]


def _sets(records, robot, var):
    return [r["value"] for r in records if r["kind"] == "set" and r["robot"] == robot
            and r["var"] == var]


RING = """arena 150 cm x 150 cm
robot talker at 75 cm, 75 cm heading 10 deg program sender.epk
robot east at 90 cm, 77 cm heading 90 deg program listener.epk
robot north at 73 cm, 93 cm heading 200 deg program listener.epk
robot west at 58 cm, 70 cm heading -45 deg program listener.epk
robot south at 80 cm, 58 cm heading 135 deg program listener.epk
messages loss 0 %
"""


def test_a_message_reaches_every_robot_in_range_with_its_bearing_within_the_model_error(
        tmp_path):
    records, _ = _run(tmp_path, _world(tmp_path, RING))
    sends = [r for r in records if r["kind"] == "send"]
    assert [s["value"] for s in sends] == list(range(len(sends))) and len(sends) >= 9
    for robot in ("east", "north", "west", "south"):
        got = _deliveries(records, robot)
        # every send but one still on the air at the end, each once, in order
        assert [m["value"] for m in got] == [s["value"] for s in sends][:len(got)]
        assert len(got) >= len(sends) - 1
        for m in got:
            assert m["from"] == "talker"
            assert abs(_wrap(m["bearing_deg"] - _true_bearing(m))) <= BEARING_ERROR_DEG + 0.1
            true_mm = math.hypot(m["from_x_mm"] - m["x_mm"], m["from_y_mm"] - m["y_mm"])
            assert abs(m["range_mm"] - true_mm) <= RANGE_NOISE * true_mm + 0.1
        # the program's readings are the delivery's: the value, the bearing
        # in whole degrees (-180..179), the range in whole mm
        assert _sets(records, robot, "heard")[-1] == len(got)
        last = got[-1]
        values = _sets(records, robot, "b")
        assert values and abs(_wrap(values[-1] - last["bearing_deg"])) <= 0.5
        assert abs(_sets(records, robot, "r")[-1] - last["range_mm"]) <= 0.5
        assert _sets(records, robot, "v")[-1] == last["value"]


HIDDEN = """arena 150 cm x 100 cm
robot talker at 50 cm, 50 cm heading 0 deg program sender.epk
robot near at 65 cm, 58 cm heading 90 deg program listener.epk
robot far at 100 cm, 50 cm heading 0 deg program listener.epk
robot hidden at 50 cm, 32 cm program listener.epk
messages loss 0 %
"""
WALL = "box at 50 cm, 41 cm size 20 cm x 2 cm\n"


def test_no_message_out_of_range_or_behind_a_wall(tmp_path):
    records, _ = _run(tmp_path, _world(tmp_path, HIDDEN + WALL))
    assert len(_deliveries(records, "near")) >= 4
    assert _deliveries(records, "far") == []            # 50 cm away: beyond 22.5 cm
    assert _deliveries(records, "hidden") == []         # 18 cm away, behind the box
    assert _sets(records, "far", "heard") == [] and _sets(records, "hidden", "heard") == []
    # without the box the hidden robot hears it; with a longer range the far one
    records, _ = _run(tmp_path, _world(tmp_path, HIDDEN.replace("loss 0 %", "loss 0 % range 60 cm"),
                                      "open.world"),
                      name="open")
    assert len(_deliveries(records, "hidden")) >= 4 and len(_deliveries(records, "far")) >= 4


def test_the_loss_model_is_seeded_and_loses_its_share(tmp_path):
    body = RING.replace("messages loss 0 %", "messages loss 50 %")
    _, first = _run(tmp_path, _world(tmp_path, body), "4s", name="a")
    records, again = _run(tmp_path, _world(tmp_path, body), "4s", name="b")
    assert first == again                               # the same seed, the same run
    sends = len([r for r in records if r["kind"] == "send"])
    delivered = len(_deliveries(records))
    assert 0.3 * 4 * sends < delivered < 0.7 * 4 * sends
    records2, _ = _run(tmp_path, _world(tmp_path, body + "seed 2\n", "seed2.world"), "4s",
                       name="c")
    assert [(m["t_ms"], m["robot"]) for m in _deliveries(records2)] != \
        [(m["t_ms"], m["robot"]) for m in _deliveries(records)]


def test_a_robot_sends_at_most_one_message_per_interval(tmp_path):
    """Sending at every poll: the library puts one message on the air per
    `interval`; the runtime keeps the newest value waiting meanwhile."""
    (tmp_path / "chatty.epk").write_text("var n = 0\non immediate repeat do send(n), "
                                         "n = clamp(n + 1, 0, 255)\n")
    for interval, expected in ((100, 10), (40, 25)):
        body = (f"robot talker at 0 cm, 0 cm program chatty.epk\n"
                f"robot ear at 15 cm, 0 cm heading 180 deg program listener.epk\n"
                f"messages loss 0 % interval {interval} ms\n")
        records, _ = _run(tmp_path, _world(tmp_path, body, f"i{interval}.world"), "1s",
                          name=f"i{interval}")
        sends = [r for r in records if r["kind"] == "send"]
        assert len(sends) == expected
        assert all(b["t_ms"] - a["t_ms"] == interval for a, b in zip(sends, sends[1:]))
        # what goes is the newest value: n counts polls
        assert sends[1]["value"] > sends[0]["value"] + interval - 5


def test_the_queue_keeps_the_newest_eight_when_more_come_at_once(tmp_path):
    """Twelve robots around one send in the same world step: the listener's
    library gets twelve, the runtime's queue (RT_MESSAGE_QUEUE 8) keeps the
    newest eight, and `on message` takes them one a poll, in order."""
    (tmp_path / "once.epk").write_text("on immediate do send(random(0, 255))\n")
    lines = ["arena 100 cm x 100 cm", "robot ear at 50 cm, 50 cm program listener.epk",
             "messages loss 0 %"]
    for k in range(12):
        a = 2 * math.pi * k / 12
        lines.append(f"robot s{k} at {50 + 16 * math.cos(a):.2f} cm, "
                     f"{50 + 16 * math.sin(a):.2f} cm program once.epk")
    records, _ = _run(tmp_path, _world(tmp_path, "\n".join(lines) + "\n"), "300ms")
    got = _deliveries(records, "ear")
    assert len(got) == 12
    fired = [r for r in records if r.get("robot") == "ear" and r["kind"] == "event"]
    assert len(fired) == 8
    assert [r["t_ms"] for r in fired] == list(range(fired[0]["t_ms"], fired[0]["t_ms"] + 8))
    # what the program read, in order: the newest eight (a value equal to
    # the variable's is not traced again)
    expected, v = [], 0
    for m in got[4:]:
        if m["value"] != v:
            expected.append(m["value"])
        v = m["value"]
    assert _sets(records, "ear", "v") == expected


def _distances(records):
    poses = {}
    for r in records:
        if r["kind"] == "pose":
            poses.setdefault(r["t_ms"], {})[r["robot"]] = (r["x_mm"], r["y_mm"])
    return [(t, math.dist(p["leader"], p["follower"]), p["leader"])
            for t, p in sorted(poses.items()) if len(p) == 2]


def test_a_follower_stays_near_its_leader_by_message_bearing(tmp_path):
    world = EXAMPLES / "follow.world"
    records, _, _ = run(EXAMPLES / "follower.epk", tmp_path, "--world", world,
                        "--time-limit", "30s", "--pose-interval", "500ms", expect=None)
    d = _distances(records)
    leader_path = sum(math.dist(a[2], b[2]) for a, b in zip(d, d[1:]))
    assert leader_path > 500                            # the leader drove half a metre and more
    assert max(dist for t, dist, _ in d if t >= 3000) < 200
    assert not any(r["robots"] for r in records if r["kind"] == "contacts")
    # deaf (a channel of 1 cm), the same follower is left behind
    deaf = tmp_path / "deaf.world"
    deaf.write_text(world.read_text().replace("program leader.epk",
                                              f"program {EXAMPLES / 'leader.epk'}")
                    .replace("program follower.epk", f"program {EXAMPLES / 'follower.epk'}")
                    + "messages range 1 cm\n")
    records, _, _ = run(EXAMPLES / "follower.epk", tmp_path, "--world", deaf,
                        "--time-limit", "30s", "--pose-interval", "500ms", name="deaf",
                        expect=None)
    assert max(dist for _, dist, _ in _distances(records)) > 300


@pytest.mark.parametrize("line, message", [
    ("messages loss 120 %", "the loss is from 0 % to 100 %"),
    ("messages range -3 cm", "must be positive"),
    ("messages interval 0 ms", "the interval is a whole number of ms"),
    ("messages emitter 400 deg", "the emitter cone's width is from 0 to 360 deg"),
    ("messages volume 3", "unknown setting `volume` of messages"),
    ("messages", "`messages` needs a setting"),
])
def test_bad_message_settings_are_reported_with_their_place(tmp_path, line, message):
    path = tmp_path / "bad.world"
    path.write_text(f"arena 1 m x 1 m\n{line}\n")
    result = epuckc("check", path)
    assert result.returncode == 1
    assert "bad.world:2:" in result.stdout + result.stderr
    assert message in result.stdout + result.stderr


def _swarm(records):
    """Per pose time: the mean distance from each robot to its nearest
    neighbour, and the number of clusters (robots within 15 cm joined)."""
    poses = {}
    for r in records:
        if r["kind"] == "pose":
            poses.setdefault(r["t_ms"], {})[r["robot"]] = (r["x_mm"], r["y_mm"])
    out = []
    for t, p in sorted(poses.items()):
        pts = list(p.values())
        nearest = sum(min(math.dist(a, b) for j, b in enumerate(pts) if j != i)
                      for i, a in enumerate(pts)) / len(pts)
        parent = list(range(len(pts)))

        def root(i):
            while parent[i] != i:
                i = parent[i]
            return i
        for i in range(len(pts)):
            for j in range(i + 1, len(pts)):
                if math.dist(pts[i], pts[j]) < 150:
                    parent[root(i)] = root(j)
        out.append((t, nearest, len({root(i) for i in range(len(pts))})))
    return out


def test_an_aggregation_swarm_gathers_in_clusters_by_messages(tmp_path):
    world = EXAMPLES / "aggregation.world"
    records, _, _ = run(EXAMPLES / "aggregation.epk", tmp_path, "--world", world,
                        "--time-limit", "60s", "--pose-interval", "1s", expect=None)
    swarm = _swarm(records)
    assert swarm[0][2] == 10 and swarm[0][1] > 250          # scattered at the start
    late = [s for s in swarm if s[0] >= 30_000]
    assert all(nearest < 100 for _, nearest, _ in late)     # each beside a neighbour
    assert all(clusters <= 4 for _, _, clusters in late)
    # deaf (a channel of 1 cm), the same robots wander and stay apart
    deaf = tmp_path / "deaf.world"
    deaf.write_text(world.read_text().replace("arena 100 cm x 100 cm",
                                              "arena 100 cm x 100 cm\nmessages range 1 cm"))
    records, _, _ = run(EXAMPLES / "aggregation.epk", tmp_path, "--world", deaf,
                        "--time-limit", "60s", "--pose-interval", "1s", expect=None,
                        name="deaf")
    late = [s for s in _swarm(records) if s[0] >= 30_000]
    assert sum(nearest for _, nearest, _ in late) / len(late) > 120
