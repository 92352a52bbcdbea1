"""Plot one field of one command over time from a capture, with matplotlib.

    python python/examples/plot_field.py          # the referee's chassis power, 50 Hz for 2 s
    python python/examples/plot_field.py specs/hflink.toml examples/captures/hflink.bin \\
        READ_GLOBAL_COORDINATE x --out x.png

The x axis is a time field of the command when `--time` names one (MAVLink's `time_boot_ms`,
UBX's `itow`), else the frame's offset in the capture (bytes, which on a link of a constant
rate is time). Without a display the plot is written
to `--out` (matplotlib's Agg backend). Needs matplotlib: `pip install matplotlib`.
"""

from __future__ import annotations

import argparse
from pathlib import Path

import protocol_link

ROOT = Path(__file__).resolve().parents[2]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("spec", nargs="?", default=str(ROOT / "specs" / "referee.toml"))
    parser.add_argument("capture", nargs="?", default=str(ROOT / "examples" / "captures" / "referee.bin"))
    parser.add_argument("command", nargs="?", default="POWER_HEAT_DATA")
    parser.add_argument("field", nargs="?", default="chassis_power")
    parser.add_argument("--time", default="", help="the command's time field (default: the frame's offset)")
    parser.add_argument("--out", default="", help="write the plot to this file instead of showing it")
    args = parser.parse_args()

    import matplotlib

    if args.out:
        matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    spec = protocol_link.Spec.load(args.spec)
    # One call: the capture's frames of this command as columns (a dict of lists).
    columns = protocol_link.to_columns(protocol_link.iter_file(spec, args.capture), args.command).get(args.command)
    if columns:
        # Frames of the command that carry no value of the field (an answer without payload).
        rows = [(x, y) for x, y in zip(columns[args.time or "offset"], columns.get(args.field, [])) if y is not None]
        columns = {"x": [x for x, _ in rows], "y": [y for _, y in rows]}
    if not columns or not columns["y"]:
        raise SystemExit(f"no {args.command} frame in {args.capture}")
    fig, ax = plt.subplots(figsize=(8, 3.5))
    ax.plot(columns["x"], columns["y"], marker=".", linewidth=1)
    ax.set_xlabel(args.time or "offset in the capture (bytes)")
    ax.set_ylabel(f"{args.command}.{args.field}")
    ax.set_title(f"{spec.name}: {args.command}.{args.field} ({len(columns['y'])} frames)")
    ax.grid(True, alpha=0.3)
    fig.tight_layout()
    if args.out:
        fig.savefig(args.out, dpi=100)
        print(f"wrote {args.out}")
    else:
        plt.show()


if __name__ == "__main__":
    main()
