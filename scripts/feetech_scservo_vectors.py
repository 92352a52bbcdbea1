"""Golden Feetech SCS/STS packets from Feetech's Python SDK, for every command of `specs/feetech.toml`.

Writes `tests/vectors/feetech_scservo.json`. The SDK (PyPI feetech-servo-sdk, module
`scservo_sdk`) talks to a port object; here that object is a fake port that records the bytes
the SDK writes and feeds it status packets, so:

* every instruction packet is the bytes the SDK's packet handler writes for a random call of
  one of its functions (`ping`, `readTxRx`, `write1ByteTxRx`, `write2ByteTxRx`,
  `write4ByteTxRx`, `writeTxOnly`, `regWriteTxRx`, `action`, `GroupSyncWrite.txPacket`,
  `GroupSyncRead.txPacket`); RECOVERY and RESET, which the SDK has no function for, are written
  by its `txPacket` (which lays out the header and checksum of any instruction) with the
  instruction bytes of Feetech's C++ library (INST.h);
* every status packet is fed to the SDK as a servo's answer to one of those calls and read by
  its `rxPacket` (which verifies the header, the length and the checksum): the error byte and
  the data the SDK returns are the packet's recorded values.

Each frame records its values under the spec's names and in the spec's shape (byte lists as
hex, the status error byte as its bits).

Run with the SDK installed (the version is written into the file):

    python3 -m venv .venv && .venv/bin/pip install feetech-servo-sdk==1.0.0
    .venv/bin/python scripts/feetech_scservo_vectors.py
"""

from __future__ import annotations

import json
import random
from importlib.metadata import version
from pathlib import Path

import scservo_sdk as scs

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "tests" / "vectors" / "feetech_scservo.json"
ROUNDS = 4
SDK = f"feetech-servo-sdk {version('feetech-servo-sdk')}"

#: Instructions of Feetech's C++ library (INST.h) that the Python SDK has no function for.
INST_RECOVERY = 0x06
INST_RESET = 0x0A

#: The spec's names of the status error byte's bits 0 to 5 (bits 6 and 7: `error_reserved`).
ERROR_BITS = ["input_voltage", "angle_sensor", "overheat", "over_current", "bit4", "overload"]


class FakePort:
    """What the SDK's packet handler needs of a `PortHandler`: writes are recorded, reads take
    the status bytes queued for them, and a read that finds none has timed out."""

    def __init__(self) -> None:
        self.is_using = False
        self.written: list[bytes] = []
        self.incoming = bytearray()

    def clearPort(self) -> None:
        pass

    def writePort(self, packet) -> int:
        self.written.append(bytes(packet))
        return len(packet)

    def readPort(self, length: int) -> list[int]:
        data = self.incoming[:length]
        del self.incoming[:length]
        return list(data)

    def setPacketTimeout(self, packet_length) -> None:
        pass

    def setPacketTimeoutMillis(self, msec) -> None:
        pass

    def isPacketTimeout(self) -> bool:
        return not self.incoming

    def take(self) -> bytes:
        assert len(self.written) == 1, self.written
        return self.written.pop()


def status_packet(servo: int, error: int, params: bytes) -> bytes:
    """A servo's status packet, as the servo writes it."""
    body = bytes([servo, len(params) + 2, error]) + params
    return b"\xff\xff" + body + bytes([~sum(body) & 0xFF])


def instruction(name: str, command: str, servo: int, fields: dict, packet: bytes, call: str) -> dict:
    return {
        "name": name,
        "direction": "request",
        "command": command,
        "header": {"id": servo},
        "payload": fields,
        "scales": {},
        "hex": packet.hex(),
        "provenance": f"{SDK}: {call}, written to a fake port",
    }


def status(name: str, servo: int, error: int, params: list[int], packet: bytes, call: str) -> dict:
    fields = {bit: bool(error & (1 << i)) for i, bit in enumerate(ERROR_BITS)}
    fields["error_reserved"] = error >> 6
    fields["params"] = bytes(params).hex()
    return {
        "name": name,
        "direction": "response",
        "command": None,
        "header": {"id": servo},
        "payload": fields,
        "scales": {},
        "hex": packet.hex(),
        "provenance": f"{SDK}: the answer to {call}, read by rxPacket from a fake port",
    }


def answered(ph, port: FakePort, rng: random.Random, servo: int, data_len: int):
    """Queue a status packet of `data_len` random bytes from `servo`; the packet and its parts."""
    error = rng.choice([0, 0, rng.randrange(0x80)])
    params = bytes(rng.randrange(256) for _ in range(data_len))
    packet = status_packet(servo, error, params)
    port.incoming += packet
    return packet, error


def round_of(rng: random.Random, r: int) -> list[dict]:
    ph = scs.PacketHandler(0)
    port = FakePort()
    out: list[dict] = []
    servo = lambda: rng.randrange(0xFE)  # noqa: E731: unicast ids the SDK sends to

    # PING: the SDK pings, then reads the model number (address 3, two bytes).
    s = servo()
    ping_answer, ping_error = answered(ph, port, rng, s, 0)
    model_answer, model_error = answered(ph, port, rng, s, 2)
    model, result, error = ph.ping(port, s)
    assert result == scs.COMM_SUCCESS, result
    ping_packet, read_packet = port.written
    port.written.clear()
    out.append(instruction(f"ping_{r}", "PING", s, {}, ping_packet, f"ping({s})"))
    out.append(status(f"ping_status_{r}", s, ping_error, [], ping_answer, f"ping({s})"))
    out.append(instruction(f"read_model_{r}", "READ", s, {"address": 3, "length": 2}, read_packet,
                           f"ping({s})'s model read"))
    model_bytes = list(model_answer[5:7])
    assert model == model_bytes[0] | model_bytes[1] << 8 and error == model_error
    out.append(status(f"read_model_status_{r}", s, error, model_bytes, model_answer, f"ping({s})'s model read"))

    # READ of a random run.
    s, address, length = servo(), rng.randrange(70), rng.randint(1, 16)
    answer, _ = answered(ph, port, rng, s, length)
    data, result, error = ph.readTxRx(port, s, address, length)
    assert result == scs.COMM_SUCCESS, result
    call = f"readTxRx({s}, {address}, {length})"
    out.append(instruction(f"read_{r}", "READ", s, {"address": address, "length": length}, port.take(), call))
    out.append(status(f"read_status_{r}", s, error, data, answer, call))

    # WRITE of one, two and four bytes, answered; a longer one without an answer.
    for size, fn in [(1, ph.write1ByteTxRx), (2, ph.write2ByteTxRx), (4, ph.write4ByteTxRx)]:
        s, address, value = servo(), rng.randrange(70), rng.randrange(1 << (8 * size))
        answer, _ = answered(ph, port, rng, s, 0)
        result, error = fn(port, s, address, value)
        assert result == scs.COMM_SUCCESS, result
        call = f"write{size}ByteTxRx({s}, {address}, {value})"
        data = value.to_bytes(size, "little").hex()
        out.append(instruction(f"write{size}_{r}", "WRITE", s, {"address": address, "data": data},
                               port.take(), call))
        out.append(status(f"write{size}_status_{r}", s, error, [], answer, call))
    s, address = rng.choice([servo(), scs.BROADCAST_ID]), rng.randrange(70)
    data = [rng.randrange(256) for _ in range(rng.randint(1, 12))]
    assert ph.writeTxOnly(port, s, address, len(data), data) == scs.COMM_SUCCESS
    out.append(instruction(f"write_tx_only_{r}", "WRITE", s, {"address": address, "data": bytes(data).hex()},
                           port.take(), f"writeTxOnly({s}, {address}, {len(data)}, ...)"))

    # REG_WRITE, then ACTION to every servo.
    s, address = servo(), rng.randrange(70)
    data = [rng.randrange(256) for _ in range(rng.randint(1, 8))]
    answer, _ = answered(ph, port, rng, s, 0)
    result, error = ph.regWriteTxRx(port, s, address, len(data), data)
    assert result == scs.COMM_SUCCESS, result
    call = f"regWriteTxRx({s}, {address}, {len(data)}, ...)"
    out.append(instruction(f"reg_write_{r}", "REG_WRITE", s, {"address": address, "data": bytes(data).hex()},
                           port.take(), call))
    out.append(status(f"reg_write_status_{r}", s, error, [], answer, call))
    assert ph.action(port, scs.BROADCAST_ID) == scs.COMM_SUCCESS
    out.append(instruction(f"action_{r}", "ACTION", scs.BROADCAST_ID, {}, port.take(), "action(BROADCAST_ID)"))

    # SYNC_WRITE and SYNC_READ of random servos.
    start, width = rng.randrange(70), rng.randint(1, 6)
    group = scs.GroupSyncWrite(port, ph, start, width)
    servos = []
    for sid in rng.sample(range(0xFE), rng.randint(1, 6)):
        data = [rng.randrange(256) for _ in range(width)]
        assert group.addParam(sid, data)
        servos.append({"id": sid, "data": bytes(data).hex()})
    assert group.txPacket() == scs.COMM_SUCCESS
    out.append(instruction(f"sync_write_{r}", "SYNC_WRITE", scs.BROADCAST_ID,
                           {"start_address": start, "data_length": width, "servos": servos},
                           port.take(), "GroupSyncWrite.txPacket"))
    group = scs.GroupSyncRead(port, ph, start, width)
    ids = rng.sample(range(0xFE), rng.randint(1, 8))
    for sid in ids:
        assert group.addParam(sid)
    assert group.txPacket() == scs.COMM_SUCCESS
    out.append(instruction(f"sync_read_{r}", "SYNC_READ", scs.BROADCAST_ID,
                           {"start_address": start, "data_length": width, "ids": ids},
                           port.take(), "GroupSyncRead.txPacket"))

    # RECOVERY and RESET: the SDK's txPacket writes the header and checksum of any instruction.
    for inst, command in [(INST_RECOVERY, "RECOVERY"), (INST_RESET, "RESET")]:
        s = servo()
        packet = [0, 0, s, 2, inst, 0]
        # A sync read's txPacket leaves the port busy for its answers, which none follow here.
        port.is_using = False
        assert ph.txPacket(port, packet) == scs.COMM_SUCCESS
        port.is_using = False
        out.append(instruction(f"{command.lower()}_{r}", command, s, {}, port.take(),
                               f"txPacket of instruction {inst:#04x} (Feetech INST.h)"))
    return out


def main() -> None:
    rng = random.Random(0x53_43_53)
    frames = [f for r in range(ROUNDS) for f in round_of(rng, r)]
    doc = {
        "protocol": "feetech",
        "source": {
            "generator": "scripts/feetech_scservo_vectors.py",
            "feetech-servo-sdk": version("feetech-servo-sdk"),
            "what": "instruction packets the SDK's packet handler writes to a fake port for random calls "
            "(RECOVERY and RESET by its txPacket with Feetech INST.h's instruction bytes), and status packets "
            "fed to it as the answers, read by its rxPacket",
            "payload": "the spec's names: byte lists as hex, the status error byte as its bits",
        },
        "frames": frames,
    }
    OUT.write_text(json.dumps(doc, indent=1) + "\n")
    print(f"{len(frames)} frames -> {OUT.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
