"""Writes unterminated_text.json: the golden frames of the fixture
protocol-codegen/tests/features/unterminated_text.toml, packed with CPython's struct module.

A text without a terminator is its bytes as they are: no NUL after it, a NUL inside it is a
byte of the text. `fields` gives a text as a string when it is UTF-8, else as its bytes.
"""
import json, struct, sys
from functools import reduce

def frame(cmd, payload):
    body = bytes([cmd]) + payload
    xor = reduce(lambda a, b: a ^ b, body, 0)
    return bytes([0x7E, len(payload)]) + body + bytes([xor])

def text(b):
    try:
        return b.decode("utf-8")
    except UnicodeDecodeError:
        return list(b)

frames = []
for name, level, line in [
    ("log_line", 6, "GNSS fix acquired: 12 satellites".encode()),
    ("log_empty", 0, b""),
    ("log_nul_and_invalid_utf8", 3, b"a\x00b\xffc"),
    ("log_utf8", 4, "température 21 °C".encode()),
]:
    payload = struct.pack("<B", level) + line
    frames.append({"name": name, "command": "LOG", "hex": frame(0x01, payload).hex(),
                   "fields": {"level": level, "text": text(line)},
                   "provenance": "struct.pack('<B', level) + the text's bytes"})
for name, label, value in [("named", b"servo_left", -1234), ("named_empty", b"", 7)]:
    payload = struct.pack("<B", len(label)) + label + struct.pack("<h", value)
    frames.append({"name": name, "command": "NAMED", "hex": frame(0x02, payload).hex(),
                   "fields": {"name_size": len(label), "name": text(label), "value": value},
                   "provenance": "struct.pack('<B', len) + the name + struct.pack('<h', value)"})
for name, ident, note in [("note", 9, b"calibrated"), ("note_empty", 1, b"")]:
    body = struct.pack("<B", ident) + note
    payload = body + bytes([reduce(lambda a, b: a ^ b, body, 0)])
    frames.append({"name": name, "command": "NOTE", "hex": frame(0x03, payload).hex(),
                   "fields": {"id": ident, "note": text(note)},
                   "provenance": "struct.pack('<B', id) + the note + the XOR of both"})
stream = bytes([0x00, 0x7E])
expected = []
for f in frames:
    b = bytes.fromhex(f["hex"])
    bad = bytearray(b); bad[-1] ^= 0x01
    stream += bytes(bad)
    expected.append({"offset": len(stream), "hex": f["hex"]})
    stream += b
print(json.dumps({
    "protocol": "unterminated_text",
    "source": {
        "repos": ["CPython %s standard library: struct, str.encode('utf-8'), functools.reduce for the XOR"
                  % sys.version.split()[0]],
        "check": "XOR of the command and payload bytes; NOTE's payload ends with the XOR of its id and note",
        "framing": "7E, payload length (u8), command (u8), payload, XOR",
        "how": "texts written as their bytes with no terminator; `fields` gives the values",
        "spec": "protocol-codegen/tests/features/unterminated_text.toml",
    },
    "frames": frames,
    "streams": [{"name": "garbage_and_corrupt_copies", "hex": stream.hex(), "expected_frames": expected}],
}, indent=1, ensure_ascii=False))
