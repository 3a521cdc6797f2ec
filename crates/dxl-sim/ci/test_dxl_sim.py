"""Your bus code's check against dxl-sim: the ROBOTIS SDK pings two MX-28s, moves one, reads it.

Usage: python ci/test_dxl_sim.py PORT   (the path dxl-sim prints)
"""
import sys
import time

import dynamixel_sdk.port_handler
from dynamixel_sdk import COMM_SUCCESS, PacketHandler, PortHandler

MX28 = 30  # model number
TORQUE_ENABLE, GOAL_POSITION, PRESENT_POSITION = 64, 116, 132  # MX-28(2.0) addresses

# A simulator on a shared CI machine can answer later than the SDK's 16 ms USB latency timer.
dynamixel_sdk.port_handler.LATENCY_TIMER = 124
port = PortHandler(sys.argv[1])
assert port.openPort() and port.setBaudRate(1000000)
bus = PacketHandler(2.0)

for dxl_id in (1, 2):
    model, result, error = bus.ping(port, dxl_id)
    assert result == COMM_SUCCESS and error == 0 and model == MX28, (dxl_id, model, result, error)

assert bus.write1ByteTxRx(port, 1, TORQUE_ENABLE, 1) == (COMM_SUCCESS, 0)
assert bus.write4ByteTxRx(port, 1, GOAL_POSITION, 1024) == (COMM_SUCCESS, 0)
# The servo moves in real time (about 0.3 s for this quarter turn): read until it arrives.
deadline = time.monotonic() + 5.0
while True:
    position, result, error = bus.read4ByteTxRx(port, 1, PRESENT_POSITION)
    assert result == COMM_SUCCESS and error == 0, (result, error)
    if abs(position - 1024) <= 5:
        break
    assert time.monotonic() < deadline, f"servo 1 at {position}, not at its goal 1024"
    time.sleep(0.01)

assert bus.write1ByteTxRx(port, 1, TORQUE_ENABLE, 0) == (COMM_SUCCESS, 0)
port.closePort()
print("dxl-sim: servos 1 and 2 answer, servo 1 reached its goal")
