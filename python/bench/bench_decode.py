"""Decoding the same MAVLink and UBX captures with protocol_link, pymavlink and pyubx2.

Each capture of `examples/captures` (noisy: damaged frames, garbage between frames) is
repeated to some thousands of frames, and each decoder finds and decodes every frame of the
whole byte string in one process, in two ways: to message objects, and to message objects
whose every field is read (`to_dict()`). The time is the best of several runs, in the
thread's CPU time (`time.thread_time`: what the decoding costs, whatever else shares the
cores). The output is a Markdown table, as BENCHMARKS.md quotes it.

    python python/bench/bench_decode.py [--repeat 40] [--runs 3]

Not a test: it asserts only that the decoders agree on how many messages they found.
"""

from __future__ import annotations

import argparse
import io
import platform
import time
from pathlib import Path

import protocol_link

ROOT = Path(__file__).resolve().parents[2]


def best(runs: int, fn):
    times, result = [], None
    for _ in range(runs):
        start = time.thread_time()
        result = fn()
        times.append(time.thread_time() - start)
    return min(times), result


def ours(spec: protocol_link.Spec, data: bytes, fields: bool):
    def run():
        stream = spec.stream()
        msgs = [m for m in stream.feed(data) + stream.flush() if isinstance(m, protocol_link.Message)]
        if fields:
            for m in msgs:
                m.to_dict()
        return len(msgs)

    return run


def pymavlink_decoder(data: bytes, fields: bool):
    from pymavlink.dialects.v20 import common as mavlink2

    def run():
        mav = mavlink2.MAVLink(None)
        mav.robust_parsing = True
        msgs = [m for m in mav.parse_buffer(data) or [] if m.get_type() != "BAD_DATA"]
        if fields:
            for m in msgs:
                m.to_dict()
        return len(msgs)

    return run


def pyubx2_decoder(data: bytes, fields: bool):
    from pyubx2 import UBX_PROTOCOL, UBXReader

    def run():
        reader = UBXReader(io.BytesIO(data), protfilter=UBX_PROTOCOL, quitonerror=0)
        msgs = [parsed for _, parsed in reader if parsed is not None]
        if fields:
            for m in msgs:
                # pyubx2 sets every field as an attribute when it parses; reading them is
                # `vars()`, as `to_dict()` reads a protocol_link message.
                dict(vars(m))
        return len(msgs)

    return run


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=40, help="copies of each capture")
    parser.add_argument("--runs", type=int, default=3, help="runs of each decoder; the best counts")
    args = parser.parse_args()
    cases = [
        ("MAVLink", "mavlink", "mavlink.bin", "pymavlink", pymavlink_decoder),
        ("UBX", "ubx", "ubx.bin", "pyubx2", pyubx2_decoder),
    ]
    print(
        f"Python {platform.python_version()}, {platform.machine()}; each capture x{args.repeat}, "
        f"best of {args.runs}, thread CPU time\n"
    )
    print("| capture | frames | what | protocol_link | reference | reference time | speed-up (capture) | speed-up (per frame) |")
    print("| --- | ---: | --- | ---: | --- | ---: | ---: | ---: |")
    for label, spec_name, capture, ref_name, ref in cases:
        spec = protocol_link.Spec.load(ROOT / "specs" / f"{spec_name}.toml")
        data = (ROOT / "examples" / "captures" / capture).read_bytes() * args.repeat
        for fields in (False, True):
            t_ours, n_ours = best(args.runs, ours(spec, data, fields))
            t_ref, n_ref = best(args.runs, ref(data, fields))
            what = "decode, read every field" if fields else "decode"
            note = "" if n_ours == n_ref else f" (reference found {n_ref})"
            print(
                f"| {label} `{capture}` x{args.repeat} | {n_ours}{note} | {what} | {t_ours * 1e3:.1f} ms "
                f"({t_ours / n_ours * 1e6:.2f} µs/frame) | {ref_name} | {t_ref * 1e3:.1f} ms "
                f"({t_ref / max(n_ref, 1) * 1e6:.2f} µs/frame) | {t_ref / t_ours:.1f}x | "
                f"{(t_ref / max(n_ref, 1)) / (t_ours / n_ours):.1f}x |"
            )


if __name__ == "__main__":
    main()
