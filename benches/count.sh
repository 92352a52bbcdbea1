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
# fastest baseline known (2 KiB appending feed, carry-less CRC-16), `best, slicing` the same feed
# and scan with a slicing-by-16 CRC-16 (HFLink has no CRC: the same decoder as `best`), the
# ceiling of a decoder without `unsafe` in the default build. `crc-fast` is the generated
# decoder built with the facade's `crc-fast` host feature (its CRCs by the `crc-fast` crate, with
# carry-less multiplication, as `best`'s CRC-16): the host configuration, compared with `best`
# like with like.
# `clmul` is the generated decoder built with the facade's `clmul` host feature for a CPU with
# carry-less multiplication (`RUSTFLAGS="-C target-feature=+pclmulqdq"`, in its own target
# directory): its reflected CRCs folded by the runtime, as `best` folds its CRC-16.
#
# With --ablation, prints instead the generated decoder's counts with and without the
# early-truncation rule (the runtime built with its measurement `cfg`,
# `RUSTFLAGS="--cfg protocol_ablate_early_truncation"`, in its own target directory: a
# candidate waits for its claimed length even when a frame is complete inside it): what the
# rule costs. The frames are checked against the ground truth either way. Beside them, the best
# baseline without and with the rule as one masked block test per chunk that ends inside a
# candidate (`best-early`): what the rule costs a decoder that does nothing else.
#
# Usage: bash benches/count.sh [--ablation] [BYTES]   (stream length, default 1 MiB)
set -euo pipefail
cd "$(dirname "$0")/.."

ablation=0
if [ "${1:-}" = "--ablation" ]; then
  ablation=1
  shift
fi
bytes="${1:-1048576}"
command -v valgrind >/dev/null || { echo "count.sh: valgrind is not installed" >&2; exit 1; }
target="${CARGO_TARGET_DIR:-$PWD/target}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
if [ "$ablation" = 1 ]; then
  # Other flags, other artifacts: kept apart from the default build's.
  RUSTFLAGS="${RUSTFLAGS:+$RUSTFLAGS }--cfg protocol_ablate_early_truncation" \
    CARGO_TARGET_DIR="$target/ablated" cargo build --quiet --release -p protocol-benches --bin count
  cp "$target/ablated/release/count" "$tmp/count-ablated"
fi
if [ "$ablation" = 0 ]; then
  cargo build --quiet --release -p protocol-benches --bin count --features runtime-crc-fast
  cp "$target/release/count" "$tmp/count-crcfast"
  RUSTFLAGS="-C target-feature=+pclmulqdq" CARGO_TARGET_DIR="$target/clmul" \
    cargo build --quiet --release -p protocol-benches --bin count --features runtime-clmul
  cp "$target/clmul/release/count" "$tmp/count-clmul"
fi
cargo build --quiet --release -p protocol-benches --bin count
tool="$target/release/count"

# Prints "INSTRUCTIONS FRAMES" for one run.
count() {
  local out="$tmp/callgrind.out"
  local line
  line="$(valgrind --tool=callgrind --collect-atstart=no --toggle-collect='*timed_decode*' \
    --callgrind-out-file="$out" "${TOOL:-$tool}" "$@" "$bytes" 2>/dev/null)"
  local frames="${line#*frames=}"
  frames="${frames%% *}"
  local instructions
  instructions="$(sed -n 's/^summary: *//p' "$out")"
  echo "$instructions $frames"
}

if [ "$ablation" = 1 ]; then
  echo "| workload | feed | frames | generated Ir/frame | without early truncation Ir/frame | the rule's cost Ir/frame | share | best Ir/frame | best with the rule Ir/frame | the rule's cost in best Ir/frame | share | generated / best with the rule |"
  echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
  for protocol in hflink referee; do
    for noise in clean noisy; do
      for feed in whole 64; do
        read -r gen frames < <(count "$protocol" "$noise" "$feed" generated)
        read -r abl abl_frames < <(TOOL="$tmp/count-ablated" count "$protocol" "$noise" "$feed" generated)
        read -r best best_frames < <(count "$protocol" "$noise" "$feed" best)
        read -r early early_frames < <(count "$protocol" "$noise" "$feed" best-early)
        [ "$frames" = "$abl_frames" ] && [ "$frames" = "$best_frames" ] && [ "$frames" = "$early_frames" ] ||
          { echo "count.sh: frame counts differ" >&2; exit 1; }
        awk -v w="$protocol-$noise" -v f="$feed" -v n="$frames" -v g="$gen" -v a="$abl" -v b="$best" -v e="$early" \
          'BEGIN { printf "| %s | %s | %d | %.1f | %.1f | %.1f | %.1f%% | %.1f | %.1f | %.1f | %.1f%% | %.3f |\n", w, f, n, g / n, a / n, (g - a) / n, 100 * (g - a) / g, b / n, e / n, (e - b) / n, 100 * (e - b) / e, g / e }'
      done
    done
  done
  exit 0
fi

echo "| workload | feed | frames | generated Ir/frame | crc-fast Ir/frame | clmul Ir/frame | hand Ir/frame | best Ir/frame | best, slicing Ir/frame | generated / hand | generated / best | crc-fast / best | clmul / best | generated / best, slicing |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
for protocol in hflink referee; do
  for noise in clean noisy; do
    for feed in whole 64; do
      read -r gen frames < <(count "$protocol" "$noise" "$feed" generated)
      read -r fast fast_frames < <(TOOL="$tmp/count-crcfast" count "$protocol" "$noise" "$feed" generated)
      read -r clmul clmul_frames < <(TOOL="$tmp/count-clmul" count "$protocol" "$noise" "$feed" generated)
      read -r hand hand_frames < <(count "$protocol" "$noise" "$feed" hand)
      read -r best best_frames < <(count "$protocol" "$noise" "$feed" best)
      read -r slicing slicing_frames < <(count "$protocol" "$noise" "$feed" best-slicing)
      [ "$frames" = "$fast_frames" ] && [ "$frames" = "$clmul_frames" ] && [ "$frames" = "$hand_frames" ] && [ "$frames" = "$best_frames" ] &&
        [ "$frames" = "$slicing_frames" ] || { echo "count.sh: frame counts differ" >&2; exit 1; }
      awk -v w="$protocol-$noise" -v f="$feed" -v n="$frames" -v g="$gen" -v c="$fast" -v m="$clmul" -v h="$hand" -v b="$best" -v s="$slicing" \
        'BEGIN { printf "| %s | %s | %d | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.3f | %.3f | %.3f | %.3f | %.3f |\n", w, f, n, g / n, c / n, m / n, h / n, b / n, s / n, g / h, g / b, c / b, m / b, g / s }'
    done
  done
done
