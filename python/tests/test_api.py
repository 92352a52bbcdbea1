"""The package's API: loading and its errors, decoding and encoding one frame, the stream
decoder, the readers (file, CAN log, serial port, asyncio stream) and the columnar export."""

from __future__ import annotations

import asyncio
import io

import pytest

import protocol_link
from conftest import CAPTURES, SPECS, spec

ATTITUDE = {
    "time_boot_ms": 583621,
    "roll": 0.0125,
    "pitch": -0.25,
    "yaw": 3.1,
    "rollspeed": 0.001,
    "pitchspeed": -0.002,
    "yawspeed": 0.5,
}
V2_HEADER = {"seq": 16, "sysid": 1, "compid": 1, "compat_flags": 0, "signature": None}


def test_a_spec_loads_from_a_path_and_from_text():
    by_path = protocol_link.Spec.load(SPECS / "hflink.toml")
    by_text = protocol_link.Spec.from_str((SPECS / "hflink.toml").read_text(), "hflink.toml")
    assert by_path.name == by_text.name == "hflink"
    assert by_path.commands == by_text.commands and "SET_ROBOT_SPEED" in by_path.commands
    assert by_text.path == "hflink.toml"


def test_a_bad_spec_raises_every_error_located_and_rendered():
    text = '[protocol]\nname = "x"\nbyte_order = "sideways"\n'
    with pytest.raises(protocol_link.SpecError) as info:
        protocol_link.Spec.from_str(text, "bad.toml")
    e = info.value
    assert isinstance(e, ValueError)
    assert "--> bad.toml:3:" in str(e)
    assert e.diagnostics, "each error is listed"
    located = [d for d in e.diagnostics if d["line"] == 3]
    assert located and located[0]["path"] == "bad.toml" and "^" in located[0]["rendered"]


def test_a_missing_spec_file_raises_spec_error():
    with pytest.raises(protocol_link.SpecError, match="no-such.toml"):
        protocol_link.Spec.load("no-such.toml")


def test_decode_gives_attribute_access_and_a_dict():
    mav = spec("mavlink")
    frame = mav.encode("ATTITUDE", ATTITUDE, header=V2_HEADER)
    msg = mav.decode(frame)
    assert (msg.name, msg.format, msg.id) == ("ATTITUDE", "v2", 30)
    assert msg.header.sysid == 1 and msg.header["seq"] == 16
    assert msg.payload.yaw == 3.1 and msg.yaw == 3.1, "payload fields are the message's attributes"
    assert msg.raw == frame
    d = msg.to_dict()
    assert d["command"] == "ATTITUDE" and d["payload"] == ATTITUDE and d["hex"] == frame.hex()
    assert dict(msg.payload.items()) == ATTITUDE and msg.payload == ATTITUDE
    with pytest.raises(AttributeError, match="no field `nope`"):
        msg.nope


def test_decode_raises_decode_error_on_a_bad_frame():
    mav = spec("mavlink")
    frame = bytearray(mav.encode("ATTITUDE", ATTITUDE, header=V2_HEADER))
    frame[-1] ^= 0xFF
    with pytest.raises(protocol_link.DecodeError, match="check"):
        mav.decode(bytes(frame))


def test_encode_takes_keywords_or_a_dict_and_names_the_bad_field():
    mav = spec("mavlink")
    assert mav.encode("ATTITUDE", header=V2_HEADER, **ATTITUDE) == mav.encode("ATTITUDE", ATTITUDE, header=V2_HEADER)
    missing = dict(ATTITUDE)
    del missing["yaw"]
    with pytest.raises(protocol_link.EncodeError) as info:
        mav.encode("ATTITUDE", missing, header=V2_HEADER)
    assert info.value.path == "payload.yaw"
    with pytest.raises(protocol_link.EncodeError, match="header.sysid") as info:
        mav.encode("ATTITUDE", ATTITUDE, header=dict(V2_HEADER, sysid=300))
    assert info.value.path == "header.sysid"
    with pytest.raises(protocol_link.EncodeError, match="NOT_A_COMMAND"):
        mav.encode("NOT_A_COMMAND", {}, header=V2_HEADER)


def test_a_can_frame_encodes_and_decodes():
    scout = spec("scout")
    first = next(protocol_link.iter_candump(scout, CAPTURES / "scout_can.log"))
    can_id, data, extended = scout.encode_can(first.name, first.payload, header=first.header)
    assert (can_id, data) == (first.can_id, first.raw) and extended is False
    assert scout.decode_can(can_id, data).to_dict()["payload"] == first.to_dict()["payload"]


def test_the_stream_decoder_takes_any_chunks_and_counts():
    data = (CAPTURES / "mavlink.bin").read_bytes()
    whole = spec("mavlink").stream()
    expected = [m.to_json() for m in whole.feed(data) + whole.flush() if isinstance(m, protocol_link.Message)]
    for size in (1, 7, 64):
        stream = spec("mavlink").stream()
        got = []
        for i in range(0, len(data), size):
            got += stream.feed(data[i : i + size])
        got += stream.flush()
        assert [m.to_json() for m in got if isinstance(m, protocol_link.Message)] == expected
        stats = stream.stats()
        assert stats["frames"] == len(expected) == sum(stats["per_command"].values())
        assert stats["input_bytes"] == len(data)
        assert stats["bad_checksum"] == sum(1 for e in got if isinstance(e, protocol_link.Event) and e.kind == "bad_checksum")


def test_events_are_reported_with_events_true():
    items = list(protocol_link.iter_file(spec("mavlink"), CAPTURES / "mavlink.bin", events=True))
    kinds = {i.kind for i in items if isinstance(i, protocol_link.Event)}
    assert {"skipped", "bad_checksum"} <= kinds
    assert all(isinstance(i, protocol_link.Message) for i in protocol_link.iter_file(spec("mavlink"), CAPTURES / "mavlink.bin"))


def test_candump_lines_of_both_formats_parse_alike():
    log = protocol_link.parse_candump_line("(1700000000.500000) can0 151#0001007B00000013")
    plain = protocol_link.parse_candump_line("  can0  151   [8]  00 01 00 7B 00 00 00 13")
    assert (log.can_id, log.data) == (plain.can_id, plain.data) == (0x151, bytes.fromhex("0001007B00000013"))
    assert log.time == "1700000000.500000" and not log.extended
    assert protocol_link.parse_candump_line("# comment") is None
    with pytest.raises(ValueError):
        protocol_link.parse_candump_line("can0 XYZ#00")


class FakePort:
    """A serial port's reading side: `read(n)` gives what arrived, then b"" once closed."""

    def __init__(self, data: bytes, chunk: int):
        self._data = io.BytesIO(data)
        self._chunk = chunk
        self.is_open = True

    @property
    def in_waiting(self) -> int:
        return self._chunk

    def read(self, n: int) -> bytes:
        chunk = self._data.read(n)
        if not chunk:
            self.is_open = False
        return chunk


def test_a_serial_port_is_read_as_it_arrives():
    data = (CAPTURES / "ubx.bin").read_bytes()
    from_port = [m.to_json() for m in protocol_link.iter_serial(spec("ubx"), FakePort(data, 13))]
    from_file = [m.to_json() for m in protocol_link.iter_file(spec("ubx"), CAPTURES / "ubx.bin")]
    assert from_port == from_file and from_port


def test_async_for_over_an_asyncio_stream():
    data = (CAPTURES / "ubx.bin").read_bytes()

    async def run():
        reader = asyncio.StreamReader()
        for i in range(0, len(data), 100):
            reader.feed_data(data[i : i + 100])
        reader.feed_eof()
        return [m.to_json() async for m in protocol_link.aiter_stream(spec("ubx"), reader, chunk_size=50)]

    got = asyncio.run(run())
    assert got == [m.to_json() for m in protocol_link.iter_file(spec("ubx"), CAPTURES / "ubx.bin")] and got


def test_columns_per_command():
    messages = list(protocol_link.iter_file(spec("mavlink"), CAPTURES / "mavlink.bin"))
    tables = protocol_link.to_columns(messages)
    attitude = [m for m in messages if m.name == "ATTITUDE"]
    table = tables["ATTITUDE"]
    assert table["roll"] == [m.roll for m in attitude]
    assert table["offset"] == [m.offset for m in attitude]
    assert table["header.sysid"] == [m.header.sysid for m in attitude]
    assert set(tables) == {m.name for m in messages}
    assert all(len(col) == len(attitude) for col in table.values())
    assert list(protocol_link.to_columns(messages, "ATTITUDE")) == ["ATTITUDE"]


def test_a_dataframe_per_command():
    pandas = pytest.importorskip("pandas")
    messages = list(protocol_link.iter_file(spec("ubx"), CAPTURES / "ubx.bin"))
    frame = protocol_link.to_dataframe(messages, "NAV_PVT")
    assert isinstance(frame, pandas.DataFrame)
    assert list(frame["lat"]) == [m.lat for m in messages if m.name == "NAV_PVT"]


def test_a_direction_is_given_to_a_spec_whose_header_does_not_tell_it():
    plain = spec("dynamixel1")
    assert plain.directions == ["request", "response"] and plain.direction is None
    request = plain.with_direction("request")
    assert request.direction == "request"
    with pytest.raises(ValueError, match="no direction `sideways`"):
        plain.with_direction("sideways")
    msgs = list(protocol_link.iter_file(request, CAPTURES / "dynamixel1.bin"))
    assert msgs and all(m.direction == "request" for m in msgs)
