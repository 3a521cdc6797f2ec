"""Your arm code's check against ur-sim: ur_rtde connects, moves the arm and reads it back.

Usage: python ci/test_ur_sim.py [HOST]   (default 127.0.0.1, where ur-sim listens by default)
"""
import sys
import time

import rtde_control
import rtde_receive

host = sys.argv[1] if len(sys.argv) > 1 else "127.0.0.1"
control = rtde_control.RTDEControlInterface(host)
receive = rtde_receive.RTDEReceiveInterface(host)


def settles_at(read, target, tol, timeout_s=2.0):
    """Whether read() comes within tol of target (the receive link lags a package or two)."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        if all(abs(a - b) < tol for a, b in zip(read(), target)):
            return True
        time.sleep(0.01)
    return False


q = receive.getActualQ()
q[0] += 0.3
assert control.moveJ(q, 1.0, 2.0), "moveJ refused"
assert settles_at(receive.getActualQ, q, 1e-4), receive.getActualQ()

pose = receive.getActualTCPPose()
pose[2] += 0.05
assert control.moveL(pose, 0.25, 1.2), "moveL refused"
# Positions only: a rotation vector near π may come back as its equal, negated twin.
tcp = lambda: receive.getActualTCPPose()[:3]
assert settles_at(tcp, pose[:3], 1e-4), receive.getActualTCPPose()

assert not receive.isProtectiveStopped()
control.stopScript()
control.disconnect()
receive.disconnect()
print("ur-sim: moveJ and moveL reached their targets")
