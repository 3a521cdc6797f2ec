"""Your board code's check against firmata-sim: pyfirmata2 reads the firmware and A0.

Usage: python ci/test_firmata_sim.py PORT   (the path firmata-sim prints)
"""
import sys
import time

from pyfirmata2 import Arduino

board = Arduino(sys.argv[1])  # waits 5 s for the board's reset, then asks for capabilities
assert board.firmware == "StandardFirmata", board.firmware
values = []
board.analog[0].register_callback(values.append)  # pyfirmata2 scales counts to 0..1
board.samplingOn(10)
board.analog[0].enable_reporting()
deadline = time.monotonic() + 5.0
while len(values) < 5:  # reports every 10 ms
    assert time.monotonic() < deadline, "no analog report"
    time.sleep(0.01)
value = values[-1]
assert abs(value - 256 / 1023) < 0.002, value
board.exit()
print(f"firmata-sim: {board.firmware} {board.firmware_version}, A0 = {value}")
