"""Writes bit_stream.json: the golden frames of the fixture
protocol-codegen/tests/features/bit_stream.toml, packed with CPython's int.to_bytes.

A bit stream is one integer built member by member, most significant first
(`acc = acc << width | (value & mask)`), shifted left to whole bytes and written with
`int.to_bytes(n, "big")`. A signed member is its value modulo 2**width (two's complement); a
scaled one is round((physical - offset) / scale). The bitfield word of `Trim` is built lowest
member first and written with `int.to_bytes(2, "little")`. The frame check is CRC-16/XMODEM,
computed bit by bit below (poly 0x1021, init 0).
"""
import json, random, sys

def crc16_xmodem(data):
    crc = 0
    for b in data:
        crc ^= b << 8
        for _ in range(8):
            crc = ((crc << 1) ^ 0x1021) if crc & 0x8000 else crc << 1
            crc &= 0xFFFF
    return crc

def frame(cmd, payload):
    body = bytes([0xD3, len(payload), cmd]) + payload
    return body + crc16_xmodem(body).to_bytes(2, "big")

def stream(members):
    acc, bits = 0, 0
    for width, raw in members:
        acc = (acc << width) | (raw & ((1 << width) - 1))
        bits += width
    n = (bits + 7) // 8
    return (acc << (8 * n - bits)).to_bytes(n, "big")

rng = random.Random(41)
frames = []
for i in range(6):
    number, station = rng.randrange(1 << 12), rng.randrange(1 << 12)
    x_raw = rng.randrange(-(1 << 37), 1 << 37)
    valid, quality = rng.randrange(2), rng.choice([0, 1, 4, 6])
    y_raw = rng.randrange(-(1 << 37), 1 << 37)
    h_raw = rng.randrange(1 << 6)
    if i == 0:
        x_raw, y_raw = -(1 << 37), (1 << 37) - 1
    seq, tail = rng.randrange(256), rng.randrange(1 << 16)
    payload = (bytes([seq])
               + stream([(12, number), (12, station), (38, x_raw), (1, valid), (3, quality),
                         (38, y_raw), (6, h_raw)])
               + tail.to_bytes(2, "little"))
    frames.append({
        "name": f"position_{i}", "command": "POSITION",
        "hex": frame(1, payload).hex(),
        "fields": {"seq": seq, "number": number, "station": station,
                   "x_raw": x_raw, "x": x_raw * 0.0001, "valid": bool(valid),
                   "quality": quality, "raw_y": y_raw, "height_raw": h_raw,
                   "height": h_raw * 0.5 - 4.0, "tail": tail},
        "provenance": "int.to_bytes of the members shifted in MSB first",
    })
for i in range(4):
    pitch, roll, gain = rng.randrange(-32, 32), rng.randrange(-16, 16), rng.randrange(16)
    if i == 0:
        pitch, roll, gain = -32, -16, 15
    level = rng.randrange(-128, 128)
    word = (pitch & 0x3F) | ((roll & 0x1F) << 6) | (gain << 11)
    payload = word.to_bytes(2, "little") + (level & 0xFF).to_bytes(1, "little")
    frames.append({
        "name": f"trim_{i}", "command": "TRIM",
        "hex": frame(2, payload).hex(),
        "fields": {"pitch": pitch, "roll_raw": roll, "roll": roll * 0.25, "gain_raw": gain,
                   "gain": gain * 0.1, "level": level},
        "provenance": "int.to_bytes(2, 'little') of the members shifted in lowest first",
    })
data = bytes([0x00, 0xD3, 0x05])
expected = []
for f in frames:
    b = bytes.fromhex(f["hex"])
    bad = bytearray(b); bad[5] ^= 0x10
    data += bytes(bad)
    expected.append({"offset": len(data), "hex": f["hex"]})
    data += b
print(json.dumps({
    "protocol": "bit_stream",
    "source": {
        "repos": ["CPython %s standard library: int.to_bytes, random.Random(41)"
                  % sys.version.split()[0]],
        "check": "CRC-16/XMODEM of sync, length, command and payload, big-endian",
        "framing": "D3, payload length (u8), command (u8), payload, CRC",
        "how": "bit streams as one integer shifted in MSB first, a word lowest member first; `fields` gives raw and physical values",
        "spec": "protocol-codegen/tests/features/bit_stream.toml",
    },
    "frames": frames,
    "streams": [{"name": "garbage_and_corrupt_copies", "hex": data.hex(), "expected_frames": expected}],
}, indent=1))
