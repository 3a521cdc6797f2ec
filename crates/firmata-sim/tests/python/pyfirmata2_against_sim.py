"""pyfirmata2 2.5.1 against firmata-sim: firmware query, capability-based set-up, analog
reporting, and an I2C register read through pyfirmata2's generic sysex API (pyfirmata2 defines
the I2C constants but has no I2C methods).

Usage: python pyfirmata2_against_sim.py PORT
"""
import sys
import time

import pyfirmata2
from pyfirmata2 import Arduino

board = Arduino(sys.argv[1])  # opens the port (the board resets), waits 5 s, capability query
print(f"ok: firmware {board.firmware} {board.firmware_version}, protocol {board.get_firmata_version()}")
print(f"ok: {len(board.analog)} analog, {len(board.digital)} digital pins")

values = []
board.analog[0].register_callback(values.append)
board.samplingOn(10)
board.analog[0].enable_reporting()
deadline = time.monotonic() + 5.0
while len(values) < 5:
    assert time.monotonic() < deadline, "no analog report"
    time.sleep(0.01)
print(f"ok: A0 = {values[-1]} ({len(values)} reports)")

replies = []


def on_i2c_reply(*data):
    replies.append(list(data))


board.add_cmd_handler(pyfirmata2.I2C_REPLY, on_i2c_reply)
board.send_sysex(pyfirmata2.I2C_CONFIG, [0, 0])
# TCA9548A at 0x70: channel 0; then 2 bytes from register 0xA2 of the MS5611 at 0x77, read once
# (mode bits 01 in bits 4-3, auto-restart bit 6).
board.send_sysex(pyfirmata2.I2C_REQUEST, [0x70, 0x00, 0x01, 0x00])
board.send_sysex(pyfirmata2.I2C_REQUEST, [0x77, 0x08 | 0x40, 0x22, 0x01, 0x02, 0x00])
deadline = time.monotonic() + 5.0
while not replies:
    assert time.monotonic() < deadline, "no I2C reply"
    time.sleep(0.01)
r = replies[0]
address, register = r[0] | r[1] << 7, r[2] | r[3] << 7
data = [r[k] | r[k + 1] << 7 for k in range(4, len(r), 2)]
c1 = data[0] << 8 | data[1]
print(f"ok: I2C reply from {address:#04x} register {register:#04x}: C1 = {c1}")
assert (address, register, c1) == (0x77, 0xA2, 40127), (address, register, data)

board.exit()
print("DONE")
