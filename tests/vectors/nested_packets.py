"""Writes nested_packets.json: the golden frames of the fixture
protocol-codegen/tests/features/nested_packets.toml, packed with CPython's struct module from
the layout INAV's MSP V2 description gives.

A v2 frame is `$X`, the direction (`<` 0x3C, `>` 0x3E), flag (u8), function (u16 LE), payload
size (u16 LE), payload, and CRC-8/DVB-S2 (poly 0xD5, init 0, bit by bit as the description's C
snippet) over flag..payload. A v1 frame is `$M`, the direction, size (u8), function (u8),
payload, and the XOR of size, function and payload. "Encapsulation over V1": a v1 frame of
function 255 whose payload is the v2 frame without its first three bytes. The description's
example ("Hello flying world", function 0x4242, flag 0xA5) is checked byte for byte below.

Each carried frame names the same message framed natively as v2 (`native_hex`), so a reader can
compare the carried packet with the native one. `bad_carried` frames are well framed (both
checks right) but carry a packet the link does not know or whose payload is not its command's.
"""
import json, random, struct, sys

def crc8_dvb_s2(data):
    crc = 0
    for b in data:
        crc ^= b
        for _ in range(8):
            crc = ((crc << 1) ^ 0xD5) & 0xFF if crc & 0x80 else (crc << 1) & 0xFF
    return crc

def v2_body(flag, function, payload):
    body = struct.pack("<BHH", flag, function, len(payload)) + payload
    return body + bytes([crc8_dvb_s2(body)])

def v2(direction, flag, function, payload):
    return b"$X" + bytes([direction]) + v2_body(flag, function, payload)

def v1(direction, function, payload):
    xor = len(payload) ^ function
    for b in payload:
        xor ^= b
    return b"$M" + bytes([direction, len(payload), function]) + payload + bytes([xor])

REQ, RESP = 0x3C, 0x3E
hello = b"Hello flying world"
# The description's own bytes, as it prints them.
assert v2(RESP, 0xA5, 0x4242, hello).hex(" ") == (
    "24 58 3e a5 42 42 12 00 48 65 6c 6c 6f 20 66 6c 79 69 6e 67 20 77 6f 72 6c 64 82")
assert v1(RESP, 255, v2_body(0xA5, 0x4242, hello)).hex(" ") == (
    "24 4d 3e 18 ff a5 42 42 12 00 48 65 6c 6c 6f 20 66 6c 79 69 6e 67 20 77 6f 72 6c 64 82 e1")
assert v2(REQ, 0, 100, b"").hex(" ") == "24 58 3c 00 64 00 00 00 8f"

rng = random.Random(41)
frames = []

def native(name, direction, flag, function, payload, how):
    frames.append({"name": name, "hex": v2(direction, flag, function, payload).hex(),
                   "provenance": how})

def carried(name, direction, flag, function, payload, how):
    frames.append({"name": name, "hex": v1(direction, 255, v2_body(flag, function, payload)).hex(),
                   "carried": {"command": function, "flag": flag,
                               "native_hex": v2(direction, flag, function, payload).hex()},
                   "provenance": how})

native("hello_v2", RESP, 0xA5, 0x4242, hello, "INAV's MSP V2 description, Embedded example")
native("ident_v2_request", REQ, 0, 100, b"", "INAV's MSP V2 description, Sample Message")
carried("hello_in_v1", RESP, 0xA5, 0x4242, hello, "INAV's MSP V2 description, Embedded example")
carried("ident_request_in_v1", REQ, 0, 100, b"", "v2 body of the Sample Message in a v1 frame")
carried("api_version_in_v1", RESP, 0, 1, bytes([0, 1, 46]), "struct.pack of three u8")
channels = [rng.randrange(1000, 2001) for _ in range(8)]
carried("set_raw_rc_in_v1", REQ, 0, 200, struct.pack("<8H", *channels), "struct.pack('<8H')")
text = bytes(rng.randrange(32, 127) for _ in range(40))
carried("long_hello_in_v1", RESP, 0x01, 0x4242, text, "40 printable random bytes")
frames.append({"name": "api_version_v1", "hex": v1(RESP, 1, bytes([0, 1, 46])).hex(),
               "provenance": "struct.pack of three u8"})

bad = [
    ("unknown_command", v2_body(0, 0x7777, b"\x01\x02"), "UnknownCommand"),
    ("short_api_version", v2_body(0, 1, b"\x00\x01"), "PayloadLength"),
    ("request_with_bytes", v2_body(0, 100, b"\x05"), "PayloadLength"),
]
bad_frames = [{"name": n, "hex": v1(RESP if n != "request_with_bytes" else REQ, 255, body).hex(),
               "error": e} for n, body, e in bad]
# The carried CRC wrong, the v1 checksum right: the carrying struct's own check fails.
body = bytearray(v2_body(0, 1, bytes([0, 1, 46])))
body[-1] ^= 0xFF
bad_crc = v1(RESP, 255, bytes(body)).hex()

stream = bytes([0x00, 0x24, 0x4D, 0x3E])
expected = []
for f in frames:
    b = bytes.fromhex(f["hex"])
    damaged = bytearray(b); damaged[-1] ^= 0x01
    stream += bytes(damaged)
    expected.append({"offset": len(stream), "hex": f["hex"]})
    stream += b
    stream += b"$"
print(json.dumps({
    "protocol": "nested_packets",
    "source": {
        "repos": ["CPython %s standard library: struct" % sys.version.split()[0]],
        "layout": "INAV's MSP V2 description (MSP-V2 wiki page): message structure, "
                  "'Encapsulation over V1', its sample and embedded example frames",
        "check": "v1: XOR of size, function and payload; v2: CRC-8/DVB-S2 over flag..payload",
        "spec": "protocol-codegen/tests/features/nested_packets.toml",
    },
    "frames": frames,
    "bad_carried": bad_frames,
    "bad_carried_crc": bad_crc,
    "streams": [{"name": "garbage_and_damaged_copies", "hex": stream.hex(), "expected_frames": expected}],
}, indent=1))
