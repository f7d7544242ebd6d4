"""teleop_twist_keyboard: teleop_twist_keyboard's keys and speed controls, publishing geometry_msgs/Twist on
cmd_vel, in a plain terminal. The terminal is restored on exit, on Ctrl-C and on SIGTERM.
"""
from __future__ import annotations

import os
import select
import signal
import sys
import termios
import tty

HELP = """
Reading from the keyboard and publishing to Twist!
---------------------------
Moving around:
   u    i    o
   j    k    l
   m    ,    .

For Holonomic mode (strafing), hold down the shift key:
---------------------------
   U    I    O
   J    K    L
   M    <    >

t : up (+z)
b : down (-z)

anything else : stop

q/z : increase/decrease max speeds by 10%
w/x : increase/decrease only linear speed by 10%
e/c : increase/decrease only angular speed by 10%

CTRL-C to quit
"""

# key: (x, y, z, th) directions
MOVE = {
    'i': (1, 0, 0, 0), 'o': (1, 0, 0, -1), 'j': (0, 0, 0, 1), 'l': (0, 0, 0, -1),
    'u': (1, 0, 0, 1), ',': (-1, 0, 0, 0), '.': (-1, 0, 0, 1), 'm': (-1, 0, 0, -1),
    'O': (1, -1, 0, 0), 'I': (1, 0, 0, 0), 'J': (0, 1, 0, 0), 'L': (0, -1, 0, 0),
    'U': (1, 1, 0, 0), '<': (-1, 0, 0, 0), '>': (-1, -1, 0, 0), 'M': (-1, 1, 0, 0),
    't': (0, 0, 1, 0), 'b': (0, 0, -1, 0),
}
# key: (speed factor, turn factor)
SPEED = {'q': (1.1, 1.1), 'z': (0.9, 0.9), 'w': (1.1, 1.0), 'x': (0.9, 1.0), 'e': (1.0, 1.1), 'c': (1.0, 0.9)}
CTRL_C = '\x03'


class Teleop:
    """Key handling without I/O: feed keys, read the twist to publish."""

    def __init__(self, speed=0.5, turn=1.0, speed_limit=1000.0, turn_limit=1000.0):
        self.speed, self.turn = speed, turn
        self.speed_limit, self.turn_limit = speed_limit, turn_limit
        self.x = self.y = self.z = self.th = 0

    def key(self, k: str) -> bool:
        """Applies a key; returns True when the speeds changed (so they should be shown)."""
        if k in MOVE:
            self.x, self.y, self.z, self.th = MOVE[k]
            return False
        if k in SPEED:
            self.speed = min(self.speed_limit, self.speed * SPEED[k][0])
            self.turn = min(self.turn_limit, self.turn * SPEED[k][1])
            return True
        self.x = self.y = self.z = self.th = 0
        return False

    def twist(self):
        """(linear x, y, z, angular z)."""
        return (self.x * self.speed, self.y * self.speed, self.z * self.speed, self.th * self.turn)

    def status(self) -> str:
        return 'currently:\tspeed %s\tturn %s ' % (self.speed, self.turn)


class RawTerminal:
    """stdin in raw mode for the lifetime of the object; restores the saved settings whatever happens."""

    def __init__(self, fd: int):
        self.fd = fd
        self.saved = termios.tcgetattr(fd) if os.isatty(fd) else None

    def __enter__(self):
        if self.saved is not None:
            tty.setraw(self.fd)
        return self

    def restore(self):
        if self.saved is not None:
            termios.tcsetattr(self.fd, termios.TCSADRAIN, self.saved)

    def __exit__(self, *exc):
        self.restore()
        return False

    def read_key(self, timeout):
        ready, _, _ = select.select([self.fd], [], [], timeout)
        if not ready:
            return ''
        data = os.read(self.fd, 1)
        if not data:
            raise EOFError
        return data.decode('latin-1')


def main(argv=None) -> int:
    import rospy
    from geometry_msgs.msg import Twist

    rospy.init_node('teleop_twist_keyboard', argv=argv, disable_signals=True)
    t = Teleop(rospy.get_param('~speed', 0.5), rospy.get_param('~turn', 1.0),
               rospy.get_param('~speed_limit', 1000.0), rospy.get_param('~turn_limit', 1000.0))
    key_timeout = rospy.get_param('~key_timeout', 0.5)
    repeat = rospy.get_param('~repeat_rate', 0.0)
    pub = rospy.Publisher('cmd_vel', Twist, queue_size=1)
    out = sys.stdout

    def write(text):
        # raw mode: a newline needs a carriage return
        out.write(text.replace('\n', '\r\n'))
        out.flush()

    def publish():
        lx, ly, lz, az = t.twist()
        msg = Twist()
        msg.linear.x, msg.linear.y, msg.linear.z, msg.angular.z = lx, ly, lz, az
        pub.publish(msg)

    term = RawTerminal(sys.stdin.fileno())
    signal.signal(signal.SIGTERM, lambda *_: (term.restore(), sys.exit(0)))
    status_lines = 0
    with term:
        write(HELP)
        write(t.status() + '\n')
        try:
            while not rospy.is_shutdown():
                # with key_timeout > 0 the robot stops when no key comes in time, as upstream
                timeout = key_timeout if key_timeout > 0 else (1.0 / repeat if repeat > 0 else None)
                k = term.read_key(timeout)
                if k == CTRL_C:
                    break
                if k == '':
                    # no key in time: stop, unless already stopped (then nothing to say)
                    if t.twist() == (0, 0, 0, 0):
                        continue
                    if key_timeout > 0:
                        t.key('k')
                    publish()
                    continue
                if t.key(k):
                    write(t.status() + '\n')
                    status_lines += 1
                    if status_lines == 14:
                        write(HELP)
                        status_lines = 0
                publish()
        except (EOFError, KeyboardInterrupt):
            pass
        finally:
            t.key('k')
            publish()
    write('\n')
    rospy.signal_shutdown('teleop done')
    return 0


if __name__ == '__main__':
    sys.exit(main())
