"""static_transform_publisher's two argument forms."""
import math

import pytest

from car.ros import static_tf


def test_yaw_pitch_roll_form_of_the_seed():
    # the seed's support -> support_depth: yaw -1.57, pitch 0, roll -1.57
    xyz, q, frame, child = static_tf.parse('0 0 0 -1.57 0 -1.57 /support /support_depth'.split())
    assert (xyz, frame, child) == ((0.0, 0.0, 0.0), 'support', 'support_depth')
    # R = Rz(yaw) Rx(roll): the optical frame (z forward) looks along the link's x
    x, y, z, w = q
    R = [[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
         [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
         [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]]
    optical_z_in_link = [R[0][2], R[1][2], R[2][2]]
    assert optical_z_in_link == pytest.approx([1, 0, 0], abs=1e-3)


def test_quaternion_form_is_normalised():
    xyz, q, frame, child = static_tf.parse('1 2 3 0 0 2 2 a b'.split())
    assert xyz == (1.0, 2.0, 3.0)
    assert q == pytest.approx((0, 0, math.sqrt(0.5), math.sqrt(0.5)))


@pytest.mark.parametrize('args, message', [
    ('0 0 0 0 0 0 a', 'expected 8 or 9 arguments, got 7'),
    ('0 0 zero 0 0 0 a b', 'could not convert'),
    ('0 0 0 0 0 0 a a', "frame_id and child_frame_id are both 'a'"),
    ('0 0 0 0 0 0 0 a b', 'the quaternion has zero length'),
])
def test_bad_arguments(args, message):
    with pytest.raises(static_tf.UsageError, match=message):
        static_tf.parse(args.split())
