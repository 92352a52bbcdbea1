#!/usr/bin/env bash
# Instructions per frame of the generated decoders and the hand-written ones, counted by
# valgrind's callgrind: deterministic, so it compares decoders on a machine whose timings are
# not to be trusted (shared cores, other work).
#
# For each workload (HFLink and referee, clean and noisy) and feed (the whole stream, 64-byte
# chunks), runs the `count` tool of protocol-benches once per decoder under callgrind,
# collecting only its counted decode (see src/bin/count.rs), and prints a Markdown table of
# instructions per frame and the ratios generated / hand and generated / best (below 1: the
# generated decoder executes fewer instructions). `hand` is the staged slice scan, `best` the
# fastest baseline known (2 KiB appending feed, carry-less CRC-16).
#
# Usage: bash benches/count.sh [BYTES]   (stream length, default 1 MiB)
set -euo pipefail
cd "$(dirname "$0")/.."

bytes="${1:-1048576}"
command -v valgrind >/dev/null || { echo "count.sh: valgrind is not installed" >&2; exit 1; }
target="${CARGO_TARGET_DIR:-$PWD/target}"
cargo build --quiet --release -p protocol-benches --bin count
tool="$target/release/count"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT

# Prints "INSTRUCTIONS FRAMES" for one run.
count() {
  local out="$tmp/callgrind.out"
  local line
  line="$(valgrind --tool=callgrind --collect-atstart=no --toggle-collect='*timed_decode*' \
    --callgrind-out-file="$out" "$tool" "$@" "$bytes" 2>/dev/null)"
  local frames="${line#*frames=}"
  frames="${frames%% *}"
  local instructions
  instructions="$(sed -n 's/^summary: *//p' "$out")"
  echo "$instructions $frames"
}

echo "| workload | feed | frames | generated Ir/frame | hand Ir/frame | best Ir/frame | generated / hand | generated / best |"
echo "|---|---|---:|---:|---:|---:|---:|---:|"
for protocol in hflink referee; do
  for noise in clean noisy; do
    for feed in whole 64; do
      read -r gen frames < <(count "$protocol" "$noise" "$feed" generated)
      read -r hand hand_frames < <(count "$protocol" "$noise" "$feed" hand)
      read -r best best_frames < <(count "$protocol" "$noise" "$feed" best)
      [ "$frames" = "$hand_frames" ] && [ "$frames" = "$best_frames" ] ||
        { echo "count.sh: frame counts differ" >&2; exit 1; }
      awk -v w="$protocol-$noise" -v f="$feed" -v n="$frames" -v g="$gen" -v h="$hand" -v b="$best" \
        'BEGIN { printf "| %s | %s | %d | %.1f | %.1f | %.1f | %.3f | %.3f |\n", w, f, n, g / n, h / n, b / n, g / h, g / b }'
    done
  done
done
