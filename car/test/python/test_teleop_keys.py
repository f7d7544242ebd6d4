"""teleop_twist_keyboard's key bindings, without a terminal."""
import pytest

from car.ros.teleop import Teleop


@pytest.mark.parametrize('key, twist', [
    ('i', (0.5, 0, 0, 0)), (',', (-0.5, 0, 0, 0)), ('j', (0, 0, 0, 1.0)), ('l', (0, 0, 0, -1.0)),
    ('u', (0.5, 0, 0, 1.0)), ('o', (0.5, 0, 0, -1.0)), ('m', (-0.5, 0, 0, -1.0)), ('.', (-0.5, 0, 0, 1.0)),
    ('J', (0, 0.5, 0, 0)), ('L', (0, -0.5, 0, 0)), ('t', (0, 0, 0.5, 0)), ('b', (0, 0, -0.5, 0)),
])
def test_move_keys(key, twist):
    t = Teleop()
    t.key(key)
    assert t.twist() == pytest.approx(twist)


def test_any_other_key_stops():
    t = Teleop()
    t.key('i')
    t.key('k')
    assert t.twist() == (0, 0, 0, 0)


@pytest.mark.parametrize('key, speed, turn', [('q', 0.55, 1.1), ('z', 0.45, 0.9), ('w', 0.55, 1.0),
                                              ('x', 0.45, 1.0), ('e', 0.5, 1.1), ('c', 0.5, 0.9)])
def test_speed_keys(key, speed, turn):
    t = Teleop()
    assert t.key(key) is True
    assert (t.speed, t.turn) == pytest.approx((speed, turn))


def test_speed_limit_caps():
    t = Teleop(speed=0.95, speed_limit=1.0)
    t.key('q')
    assert t.speed == 1.0
