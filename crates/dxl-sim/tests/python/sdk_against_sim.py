"""The official ROBOTIS SDK (PyPI `dynamixel-sdk`) drives the simulated bus.

Usage: sdk_against_sim.py PORT ID,ID,...   (run by tests/it/sdk_python.rs)
Exits non-zero with a message on the first mismatch; prints one line per check.
"""
import sys

import dynamixel_sdk.port_handler
from dynamixel_sdk import (BROADCAST_ID, COMM_SUCCESS, GroupBulkRead, GroupSyncRead, GroupSyncWrite,
                           PacketHandler, PortHandler)

MX28_MODEL = 30
ADDR_LED, ADDR_TORQUE, ADDR_GOAL_PWM, ADDR_PWM_LIMIT, ADDR_ID = 65, 64, 100, 36, 7


def check(cond, what):
    if not cond:
        print("FAIL:", what, flush=True)
        sys.exit(1)
    print("ok:", what, flush=True)


def main():
    # The SDK allows 2 x LATENCY_TIMER (the USB adapter's 16 ms) + 2 ms per reply; the simulator is
    # a thread on a shared machine, so give it the same 250 ms as the Rust tests (REPLY_LATENCY).
    dynamixel_sdk.port_handler.LATENCY_TIMER = 124
    path, ids = sys.argv[1], [int(x) for x in sys.argv[2].split(",")]
    port = PortHandler(path)
    check(port.openPort(), "open " + path)
    check(port.setBaudRate(1000000), "baud 1 Mbps")
    ph = PacketHandler(2.0)

    for i in ids:
        model, res, err = ph.ping(port, i)
        check(res == COMM_SUCCESS and err == 0 and model == MX28_MODEL, f"ping {i} -> model {model}")
    found, res = ph.broadcastPing(port)
    check(res == COMM_SUCCESS and sorted(found) == sorted(ids), f"broadcast ping -> {sorted(found)}")

    res, err = ph.write1ByteTxRx(port, ids[0], ADDR_LED, 1)
    check(res == COMM_SUCCESS and err == 0, "write LED")
    val, res, err = ph.read1ByteTxRx(port, ids[0], ADDR_LED)
    check(res == COMM_SUCCESS and val == 1, f"read LED -> {val}")
    val, res, err = ph.read2ByteTxRx(port, ids[0], ADDR_PWM_LIMIT)
    check(res == COMM_SUCCESS and val == 885, f"read PWM Limit -> {val}")
    res, err = ph.write1ByteTxRx(port, ids[0], ADDR_TORQUE, 2)
    check(res == COMM_SUCCESS and err == 4, f"torque enable 2 -> data range error {err}")

    gsw = GroupSyncWrite(port, ph, ADDR_GOAL_PWM, 2)
    for k, i in enumerate(ids):
        v = 100 + 50 * k
        gsw.addParam(i, [v & 0xFF, v >> 8])
    check(gsw.txPacket() == COMM_SUCCESS, "sync write Goal PWM")

    gsr = GroupSyncRead(port, ph, ADDR_GOAL_PWM, 2)
    for i in ids:
        gsr.addParam(i)
    check(gsr.txRxPacket() == COMM_SUCCESS, "sync read Goal PWM")
    for k, i in enumerate(ids):
        check(gsr.isAvailable(i, ADDR_GOAL_PWM, 2), f"sync read {i} available")
        got = gsr.getData(i, ADDR_GOAL_PWM, 2)
        check(got == 100 + 50 * k, f"sync read {i} -> {got}")

    gbr = GroupBulkRead(port, ph)
    check(gbr.addParam(ids[0], ADDR_ID, 1), "bulk read param 1")
    if len(ids) > 1:
        check(gbr.addParam(ids[1], ADDR_PWM_LIMIT, 2), "bulk read param 2")
    check(gbr.txRxPacket() == COMM_SUCCESS, "bulk read")
    check(gbr.getData(ids[0], ADDR_ID, 1) == ids[0], "bulk read ID")
    if len(ids) > 1:
        check(gbr.getData(ids[1], ADDR_PWM_LIMIT, 2) == 885, "bulk read PWM Limit")

    # REG_WRITE holds the value until ACTION.
    res, err = ph.regWriteTxRx(port, ids[0], ADDR_LED, 1, [0])
    check(res == COMM_SUCCESS and err == 0, "reg write LED 0")
    val, res, err = ph.read1ByteTxRx(port, ids[0], ADDR_LED)
    check(res == COMM_SUCCESS and val == 1, f"LED still {val} before ACTION")
    # Broadcast: the SDK's txRxPacket does not wait for a unicast ACTION's status packet, which a
    # servo (and the simulator) sends, so that packet would be read as the next reply.
    res = ph.action(port, BROADCAST_ID)
    check(res == COMM_SUCCESS, "broadcast ACTION")
    val, res, err = ph.read1ByteTxRx(port, ids[0], ADDR_LED)
    check(res == COMM_SUCCESS and val == 0, f"LED {val} after ACTION")

    # REBOOT resets RAM (LED back to 0, torque off); FACTORY RESET (keep ID) resets EEPROM.
    res, err = ph.write1ByteTxRx(port, ids[-1], ADDR_LED, 1)
    res, err = ph.reboot(port, ids[-1])
    check(res == COMM_SUCCESS and err == 0, "reboot")
    val, res, err = ph.read1ByteTxRx(port, ids[-1], ADDR_LED)
    check(res == COMM_SUCCESS and val == 0, f"LED {val} after reboot")
    res, err = ph.write2ByteTxRx(port, ids[-1], ADDR_PWM_LIMIT, 300)
    check(res == COMM_SUCCESS and err == 0, "write PWM Limit 300")
    res, err = ph.factoryReset(port, ids[-1], 0x01)
    check(res == COMM_SUCCESS and err == 0, "factory reset, keep ID")
    val, res, err = ph.read2ByteTxRx(port, ids[-1], ADDR_PWM_LIMIT)
    check(res == COMM_SUCCESS and val == 885, f"PWM Limit {val} after factory reset")

    port.closePort()
    print("DONE", flush=True)


if __name__ == "__main__":
    main()
