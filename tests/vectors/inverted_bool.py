"""Writes inverted_bool.json: the golden frames of the fixture
protocol-codegen/tests/features/inverted_bool.toml, packed with CPython's struct module.

An inverted bool is packed as struct's `?` of the negated value: `?` writes True as 1 and
False as 0, so `not ready` gives the byte 0 for a ready flag.
"""
import json, struct, sys
from functools import reduce

def frame(cmd, payload):
    body = bytes([cmd]) + payload
    xor = reduce(lambda a, b: a ^ b, body, 0)
    return bytes([0x7E, len(payload)]) + body + bytes([xor])

frames = []
for name, ready, armed, lamps, ports in [
    ("ready_armed", True, True, [True, False, True], [True, True]),
    ("not_ready", False, False, [False, False, False], []),
    ("mixed", True, False, [False, True, True], [False, True, False, True]),
]:
    payload = (struct.pack('<??', not ready, armed)
               + b''.join(struct.pack('<?', not x) for x in lamps)
               + struct.pack('<B', len(ports))
               + b''.join(struct.pack('<?', not x) for x in ports))
    frames.append({
        "name": name,
        "hex": frame(0x10, payload).hex(),
        "fields": {"ready": ready, "armed": armed, "lamps_on": lamps, "count": len(ports),
                   "ports_up": ports},
        "provenance": "struct.pack('<?', not value) per inverted bool",
    })
stream = bytes([0x00, 0x7E])
expected = []
for f in frames:
    b = bytes.fromhex(f["hex"])
    bad = bytearray(b); bad[-1] ^= 0x01
    stream += bytes(bad)
    expected.append({"offset": len(stream), "hex": f["hex"]})
    stream += b
print(json.dumps({
    "protocol": "inverted_bool",
    "source": {
        "repos": ["CPython %s standard library: struct ('?'), functools.reduce for the XOR"
                  % sys.version.split()[0]],
        "check": "XOR of the command and payload bytes",
        "framing": "7E, payload length (u8), command (u8), payload, XOR",
        "how": "each inverted bool packed as struct's '?' of its negation; `fields` gives the values",
        "spec": "protocol-codegen/tests/features/inverted_bool.toml",
    },
    "frames": frames,
    "streams": [{"name": "garbage_and_corrupt_copies", "hex": stream.hex(), "expected_frames": expected}],
}, indent=1))
