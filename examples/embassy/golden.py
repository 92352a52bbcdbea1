"""The golden conversation of the embassy example: what a master sends to the HFLink slave
and the bytes the slave must answer, built from the golden vectors (tests/vectors/hflink.json,
captures of the original implementations).

Requests are vector frames, and frames built here by HFLink's framing rule (FF FF, sender,
receiver, length of command + payload as u16 big-endian, command, payload, sum of every
preceding byte modulo 255), which is first checked to rebuild every vector frame. Expected
answers are vector frames where one exists, otherwise built by the same rule from the spec's
`[session]`: the same command back, the addresses swapped.

Usage: python3 golden.py VECTORS.json INPUT.bin EXPECTED.bin
Writes the bytes to feed into the UART and the bytes the UART must send back, and prints one
line per exchange.
"""

import json
import sys

MASTER, SLAVE = 0x01, 0x11


def frame(sender, receiver, data):
    """An HFLink frame of `data` (the command byte and the payload)."""
    head = bytes([0xFF, 0xFF, sender, receiver, len(data) >> 8, len(data) & 0xFF])
    body = head + data
    return body + bytes([sum(body) % 255])


def answer(request, payload=b""):
    """The slave's answer to `request`: its command back with `payload`, addresses swapped."""
    return frame(request[3], request[2], request[6:7] + payload)


def main():
    vectors_path, input_path, expected_path = sys.argv[1:4]
    vectors = json.load(open(vectors_path))
    v = {f["name"]: bytes.fromhex(f["hex"]) for f in vectors["frames"]}
    for f in vectors["frames"]:
        rebuilt = frame(f["sender"], f["receiver"], bytes.fromhex(f["data_hex"]))
        assert rebuilt == v[f["name"]], f"the framing rule does not rebuild {f['name']}"
    stream = next(s for s in vectors["streams"] if s["name"] == "stream_garbage_corrupt_truncated")
    noise = bytes.fromhex(stream["hex"])
    # The stream's READ_ROBOT_SPEED response: the speed a SET below asks for and READ reads back.
    speed_reply = next(
        bytes.fromhex(f["hex"]) for f in stream["expected_frames"] if f["hex"][12:14] == "0d"
    )
    set_speed = frame(MASTER, SLAVE, b"\x0c" + speed_reply[7:-1])
    read_speed = frame(MASTER, SLAVE, b"\x0d")
    chassis = v["set_chassis_parameters_request"]
    motor = v["set_motor_parameters_request_pc_layout"]
    set_negative = v["set_robot_speed_request_negative"]
    corrupt = set_negative[:-1] + bytes([set_negative[-1] ^ 0x01])

    # (what the exchange shows, bytes sent, bytes expected back)
    conversation = [
        ("a request before the handshake is refused (empty SHAKING_HANDS)",
         v["read_system_info_request"], v["slave_requests_handshake"]),
        ("garbage, slave frames, a bad checksum and a truncated frame: no answer",
         noise, b""),
        ("the handshake, answered with an empty SHAKING_HANDS",
         v["shaking_hands_request"], answer(v["shaking_hands_request"])),
        ("READ_SYSTEM_INFO answered with the original slave's reply",
         v["read_system_info_request"], v["read_system_info_response"]),
        ("a SET_ROBOT_SPEED with a bad checksum: no answer",
         corrupt, b""),
        ("a truncated SET_CHASSIS_PARAMETERS, then SET_ROBOT_SPEED: resynced, acknowledged",
         chassis[:11] + set_negative, v["set_robot_speed_ack"]),
        ("SET_MOTOR_PARAMETERS (the PC layout), acknowledged",
         motor, answer(motor)),
        ("SET_CHASSIS_PARAMETERS, answered with the parameters",
         chassis, answer(chassis, chassis[7:-1])),
        ("SET_ROBOT_SPEED, acknowledged",
         set_speed, answer(set_speed)),
        ("READ_ROBOT_SPEED answered with the speed set (the stream vector's reply)",
         read_speed, speed_reply),
        ("a request for another slave (0x12): no answer",
         frame(MASTER, 0x12, b"\x01"), b""),
        ("READ_SYSTEM_INFO again, the last answer",
         v["read_system_info_request"], v["read_system_info_response"]),
    ]
    sent, expected = b"", b""
    for what, request, reply in conversation:
        print(f"{len(request):4} bytes in, {len(reply):3} out: {what}")
        sent += request
        expected += reply
    open(input_path, "wb").write(sent)
    open(expected_path, "wb").write(expected)


main()
