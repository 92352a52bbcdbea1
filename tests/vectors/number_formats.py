"""Writes number_formats.json: the golden frames of the fixture
protocol-codegen/tests/features/number_formats.toml, packed with CPython's struct module and
int.to_bytes, framed with binascii.crc_hqx (CRC-16/XMODEM)."""
import binascii, json, struct

def frame(cmd, payload):
    body = bytes([cmd]) + payload
    crc = binascii.crc_hqx(body, 0)  # CRC-16/XMODEM
    return bytes([0xA5, len(payload)]) + body + crc.to_bytes(2, 'big')
frames = []
def add(name, cmd, payload, fields, how):
    frames.append({"name": name, "hex": frame(cmd, payload).hex(), "wire": fields, "provenance": how})
# ScaledFloats: raw wire values packed with struct.
raw = {"speed": 1234.0, "temperature": 650.0, "latitude": 473977418.0, "gain": 0.375, "trim": 8.0}
p = struct.pack('<f', raw["speed"]) + struct.pack('>f', raw["temperature"]) + struct.pack('<d', raw["latitude"]) + struct.pack('<e', raw["gain"]) + struct.pack('<f', raw["trim"])
add("scaled_floats", 1, p, raw, "struct.pack '<f' '>f' '<d' '<e' '<f'")
raw2 = {"speed": -0.5, "temperature": -123.25, "latitude": -1223999999.0, "gain": -0.0009765625, "trim": -20.0}
p = struct.pack('<f', raw2["speed"]) + struct.pack('>f', raw2["temperature"]) + struct.pack('<d', raw2["latitude"]) + struct.pack('<e', raw2["gain"]) + struct.pack('<f', raw2["trim"])
add("scaled_floats_negative", 1, p, raw2, "struct.pack '<f' '>f' '<d' '<e' '<f'")
# WideInts: int.to_bytes of each width.
w = {"timestamp": 0xFE_DCBA_9876, "position": -123456789012, "odometer": 0x12_3456_789A_BCDE, "offset": -1000,
     "history": [-1, 0x7F_FFFF_FFFF_FFFF], "station": 0xFF_FFFF_FFFF}
p = (w["timestamp"].to_bytes(5, 'little') + w["position"].to_bytes(6, 'big', signed=True)
     + w["odometer"].to_bytes(7, 'little') + w["offset"].to_bytes(5, 'little', signed=True)
     + b''.join(h.to_bytes(7, 'big', signed=True) for h in w["history"]) + w["station"].to_bytes(5, 'little'))
add("wide_ints", 2, p, w, "int.to_bytes(n, order, signed=...)")
# The widths' extremes; a scaled raw value stays below 2^53, which an f64 holds exactly.
w2 = {"timestamp": 0, "position": -(1 << 47), "odometer": 10**12 + 7, "offset": (1 << 39) - 1,
      "history": [-(1 << 55), 0], "station": 0x01_0000_0000}
p = (w2["timestamp"].to_bytes(5, 'little') + w2["position"].to_bytes(6, 'big', signed=True)
     + w2["odometer"].to_bytes(7, 'little') + w2["offset"].to_bytes(5, 'little', signed=True)
     + b''.join(h.to_bytes(7, 'big', signed=True) for h in w2["history"]) + w2["station"].to_bytes(5, 'little'))
add("wide_ints_extremes", 2, p, w2, "int.to_bytes(n, order, signed=...)")
# Halves: struct's 'e' format (IEEE 754 binary16, round half to even).
for name, thr, att in [("halves", 1/3, [-2.0, 65504.0, 2.0**-24]),
                       ("halves_rounded", 0.1, [65519.0, -6.1e-5, 1e-8])]:
    p = struct.pack('<e', thr) + b''.join(struct.pack('>e', a) for a in att)
    exact = {"throttle": struct.unpack('<e', struct.pack('<e', thr))[0],
             "attitude": [struct.unpack('>e', struct.pack('>e', a))[0] for a in att]}
    add(name, 3, p, {"packed": {"throttle": thr, "attitude": att}, "read_back": exact}, "struct.pack '<e' '>e'")
# Infinity and NaN halves: JSON holds no such number, so only their bytes.
p = struct.pack('<e', float('inf')) + struct.pack('>e', float('-inf')) + struct.pack('>e', float('nan')) + struct.pack('>e', -0.0)
add("halves_special", 3, p, {"throttle": "inf", "attitude": ["-inf", "NaN", "-0.0"]}, "struct.pack '<e' '>e'")
# A value beyond the largest half: struct refuses it, as the encoders must.
try:
    struct.pack('<e', 65520.0); refused = False
except OverflowError as e:
    refused = str(e)
out = {
  "protocol": "number_formats",
  "source": {
    "repos": ["CPython %s standard library: struct ('<e' '>e' '<f' '>f' '<d'), int.to_bytes, binascii.crc_hqx" % __import__('sys').version.split()[0]],
    "check": "CRC-16/XMODEM (binascii.crc_hqx with init 0) over the command and payload, stored big-endian",
    "framing": "A5, payload length (u8), command (u8), payload, CRC",
    "how": "each field's wire value packed by struct (floats, halves) or int.to_bytes (40-, 48- and 56-bit integers); `wire` gives the values packed",
    "f16_overflow": "struct.pack('<e', 65520.0) raises OverflowError: %s" % refused,
    "spec": "protocol-codegen/tests/features/number_formats.toml"
  },
  "frames": frames,
}
stream = bytes([0x00, 0xA5, 0x02])
expected = []
for f in frames:
    b = bytes.fromhex(f["hex"])
    bad = bytearray(b); bad[-1] ^= 0x80
    stream += bytes(bad)
    expected.append({"offset": len(stream), "hex": f["hex"]})
    stream += b
out["streams"] = [{"name": "garbage_and_corrupt_copies", "hex": stream.hex(), "expected_frames": expected}]
print(json.dumps(out, indent=1))
