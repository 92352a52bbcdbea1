"""The keys of `to_dict()`: each field name is one Python string, shared by every message's dict,
and the names of two specs with fields of the same and of different names stay their own."""

from __future__ import annotations

from conftest import spec

ATTITUDE = {
    "time_boot_ms": 583621,
    "roll": 0.0125,
    "pitch": -0.25,
    "yaw": 3.1,
    "rollspeed": 0.001,
    "pitchspeed": -0.002,
    "yawspeed": 0.5,
}
HEADER = {"seq": 16, "sysid": 1, "compid": 1, "compat_flags": 0, "signature": None}


def test_messages_share_one_string_per_field_name():
    mav = spec("mavlink")
    first = mav.decode(mav.encode("ATTITUDE", ATTITUDE, header=HEADER)).to_dict()["payload"]
    other = dict(ATTITUDE, yaw=-1.5)
    second = mav.decode(mav.encode("ATTITUDE", other, header=dict(HEADER, seq=17))).to_dict()
    assert first == ATTITUDE and second["payload"] == other
    assert list(first) == list(ATTITUDE), "fields in spec order"
    for a, b in zip(first, second["payload"]):
        assert a is b, f"`{a}` is a new string in each dict"


def test_each_spec_keeps_its_own_names():
    mav, ubx = spec("mavlink"), spec("ubx")
    attitude = mav.decode(mav.encode("ATTITUDE", ATTITUDE, header=HEADER)).to_dict()
    posllh = {"itow": 1000, "lon": 1, "lat": 2, "height": 3, "h_msl": 4, "h_acc": 5, "v_acc": 6}
    nav = ubx.decode(ubx.encode("NAV_POSLLH", posllh)).to_dict()
    assert attitude["payload"] == ATTITUDE
    assert nav["payload"] == posllh and list(nav["payload"]) == list(posllh)
