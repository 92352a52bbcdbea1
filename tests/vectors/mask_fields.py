"""Writes mask_fields.json: the golden frames of the fixture
protocol-codegen/tests/features/mask_fields.toml, packed with CPython's struct module.

Each frame is an SRXL2 packet: 0xA6, the packet type, the length of the whole packet, the
payload, and CRC-16/XMODEM over everything before it (binascii.crc_hqx with a zero seed),
high byte first. A Control Data packet's channel values are packed one `<H` per bit set in
the channel mask, lowest channel first. A Cycling Speed and Cadence or Cycling Power
Measurement packs each group of fields only when its flag bit is set. A scaled field is
packed as its raw integer; `fields` gives the physical value (raw times the scale).
"""
import binascii, json, random, struct, sys

def frame(packet_type, payload):
    body = bytes([0xA6, packet_type, len(payload) + 5]) + payload
    return body + binascii.crc_hqx(body, 0).to_bytes(2, "big")

rng = random.Random(41)
frames = []

def add(name, packet_type, payload, fields, how):
    frames.append({"name": name, "hex": frame(packet_type, payload).hex(), "fields": fields,
                   "provenance": how})

for name, mask in [("four_channels", 0x0000000F), ("first_and_last", 0x80000001),
                   ("no_channel", 0), ("every_channel", 0xFFFFFFFF),
                   ("random_mask", rng.getrandbits(32))]:
    values = [rng.randrange(1 << 16) for _ in range(bin(mask).count("1"))]
    rssi, losses = rng.randrange(-128, 128), rng.randrange(1 << 16)
    payload = struct.pack("<BBbHI", 0x00, 0x10, rssi, losses, mask)
    payload += b"".join(struct.pack("<H", v) for v in values)
    add(name, 0xCD, payload,
        {"command": 0, "reply_id": 0x10, "rssi": rssi, "frame_losses": losses,
         "channel_mask": mask, "channels": values},
        "struct.pack('<BBbHI') then '<H' per set bit of the mask")

def csc(name, flags):
    payload = struct.pack("<B", flags)
    fields = {"flags": flags, "wheel": None, "crank": None}
    if flags & 1:
        revs, time = rng.getrandbits(32), rng.getrandbits(16)
        payload += struct.pack("<IH", revs, time)
        fields["wheel"] = {"cumulative_wheel_revolutions": revs,
                           "last_wheel_event_time": time / 1024}
    if flags & 2:
        revs, time = rng.getrandbits(16), rng.getrandbits(16)
        payload += struct.pack("<HH", revs, time)
        fields["crank"] = {"cumulative_crank_revolutions": revs,
                           "last_crank_event_time": time / 1024}
    add(name, 0x01, payload, fields, "struct.pack('<B'), then '<IH' if bit 0, '<HH' if bit 1")

for name, flags in [("csc_none", 0), ("csc_wheel", 1), ("csc_crank", 2), ("csc_both", 3)]:
    csc(name, flags)

def power(name, flags):
    watts = rng.randrange(-(1 << 15), 1 << 15)
    payload = struct.pack("<Hh", flags, watts)
    fields = {"flags": flags, "instantaneous_power": watts, "pedal_power_balance": None,
              "accumulated_torque": None, "wheel_revolutions": None,
              "last_wheel_event_time": None, "crank": None}
    if flags & 1:
        raw = rng.getrandbits(8)
        payload += struct.pack("<B", raw)
        fields["pedal_power_balance"] = raw / 2
    if flags & 4:
        raw = rng.getrandbits(16)
        payload += struct.pack("<H", raw)
        fields["accumulated_torque"] = raw / 32
    if flags & 16:
        revs, time = rng.getrandbits(32), rng.getrandbits(16)
        payload += struct.pack("<IH", revs, time)
        fields["wheel_revolutions"] = revs
        fields["last_wheel_event_time"] = time / 2048
    if flags & 32:
        revs, time = rng.getrandbits(16), rng.getrandbits(16)
        payload += struct.pack("<HH", revs, time)
        fields["crank"] = {"cumulative_crank_revolutions": revs,
                           "last_crank_event_time": time / 1024}
    add(name, 0x02, payload, fields,
        "struct.pack('<Hh'), then '<B' if bit 0, '<H' if bit 2, '<IH' if bit 4, '<HH' if bit 5")

for name, flags in [("power_only", 0x00), ("power_all", 0x3F), ("power_balance_crank", 0x23),
                    ("power_torque_wheel", 0x14)]:
    power(name, flags)

stream = bytes([0x00, 0xA6, 0x13])
expected = []
for f in frames:
    b = bytes.fromhex(f["hex"])
    bad = bytearray(b); bad[-1] ^= 0x01
    stream += bytes(bad)
    expected.append({"offset": len(stream), "hex": f["hex"]})
    stream += b
print(json.dumps({
    "protocol": "mask_fields",
    "source": {
        "repos": ["CPython %s standard library: struct, binascii.crc_hqx (CRC-16/XMODEM with seed 0)"
                  % sys.version.split()[0]],
        "check": "CRC-16/XMODEM over the whole packet before it, high byte first",
        "framing": "A6, packet type (u8), packet length (u8, the whole packet), payload, CRC",
        "how": "groups of fields packed only when their mask bit is set; channel values one per set bit",
        "spec": "protocol-codegen/tests/features/mask_fields.toml",
    },
    "frames": frames,
    "streams": [{"name": "garbage_and_corrupt_copies", "hex": stream.hex(), "expected_frames": expected}],
}, indent=1))
