#!/usr/bin/env bash
# Times criterion binaries in turn on the same boot, for ratios a drifting host cannot fake.
#
# One full `cargo bench` run times each decoder once, minutes after the one it is compared
# with; on a host whose speed drifts (a shared or virtual machine) a ratio between two builds,
# or between two benchmarks far apart in one run, then moves by more than the change being
# measured. This script builds the benchmark binary as `cargo bench` does, once with the
# default features ("after"), once with the runtime's measurement `cfg`
# (`RUSTFLAGS="--cfg protocol_ablate_early_truncation"`, in a target directory of its own:
# "ablated", where a candidate waits for its claimed length even when a frame is complete
# inside it), and with `--before REV` once more from that commit ("before"), then runs them one
# after the other, in quick mode, for several rounds, and prints per row:
#
# - the generated decoder against the best baseline (`best`'s median time over `generated`'s,
#   throughput ratio; `hand` where a row has no `best`: the encoders) in each round, for each
#   binary;
# - on the referee, the same against `best-slicing` (the best baseline with a slicing-by-16
#   CRC-16, the ceiling of a decoder without `unsafe` in a build without `pclmulqdq`), for the
#   after binary;
# - the generated decoder against `best-early` (the best baseline with the early-truncation
#   rule as one masked block test per chunk: the same frames at the same moments as the
#   generated decoder),
#   for the after binary, and `best-early` against `best` (what the rule costs the best
#   baseline) for the after and ablated binaries (the same code in both: two more samples);
# - the early-truncation rule's cost: the after binary's `generated` time over the ablated
#   one's, minus one, each first divided by its own binary's `best` time of the same round (the
#   two are timed seconds apart, the two binaries minutes apart: a drift of the host between
#   the binaries cancels), per round and their mean; and the mean of the undivided ratios.
#
# Each binary keeps its criterion data apart (CRITERION_HOME under a temporary directory), so
# `target/criterion`, which `bench-report` reads, is left as the last full run wrote it.
#
# With --clmul, every binary is built for a CPU with carry-less multiplication
# (`RUSTFLAGS="-C target-feature=+pclmulqdq"`, in its own target directory) and the after and
# ablated ones with the facade's `clmul` host feature: the generated decoders fold the
# referee's CRC-16 as `best` does (`best-slicing` keeps its tables).
#
# Usage: bash benches/alternate.sh [--rounds N] [--before REV] [--filter REGEX] [--clmul]
#   --rounds N    rounds of all binaries (default 3)
#   --before REV  also time the benchmark built from commit REV (a git worktree)
#   --clmul       the host configuration with carry-less multiplication (above)
#   --filter RE   criterion filter (default: the eight decoder rows, generated, best and
#                 best-slicing and best-early; '^(hflink|referee)-encode/' for the encoders)
set -euo pipefail
cd "$(dirname "$0")/.."

rounds=3
clmul=0
before=""
filter='^(hflink|referee)-(clean|noisy)-(whole|64)/(generated|best|best-slicing|best-early)$'
while [ $# -gt 0 ]; do
  case "$1" in
    --rounds) rounds="$2"; shift 2 ;;
    --before) before="$2"; shift 2 ;;
    --filter) filter="$2"; shift 2 ;;
    --clmul) clmul=1; shift ;;
    *) echo "usage: bash benches/alternate.sh [--rounds N] [--before REV] [--filter REGEX] [--clmul]" >&2; exit 2 ;;
  esac
done

features=()
if [ "$clmul" = 1 ]; then
  export RUSTFLAGS="-C target-feature=+pclmulqdq"
  # Other flags, other artifacts: kept apart from the default build's.
  export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target/clmul}"
  features=(runtime-clmul)
fi
# `--features` with the named features and EXTRA (comma-separated lists).
with_features() {
  local all
  all="$(IFS=,; echo "${features[*]}${1:+${features[*]:+,}$1}")"
  if [ -n "$all" ]; then echo "--features=$all"; fi
}

tmp="$(mktemp -d)"
worktree=""
cleanup() {
  if [ -n "$worktree" ]; then git worktree remove --force "$worktree" >/dev/null 2>&1 || true; fi
  rm -rf "$tmp"
}
trap cleanup EXIT

# shellcheck source=benches/codec-exe.sh
. benches/codec-exe.sh

labels=()
echo "building: after" >&2
# shellcheck disable=SC2046 # no features: no argument
cp "$(codec_exe $(with_features))" "$tmp/after"
labels+=(after)
echo "building: ablated" >&2
# Other flags, other artifacts: kept apart from the after build's (with --clmul, its flags too).
# shellcheck disable=SC2046 # no features: no argument
cp "$(RUSTFLAGS="${RUSTFLAGS:+$RUSTFLAGS }--cfg protocol_ablate_early_truncation" \
  CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}/ablated" codec_exe $(with_features))" \
  "$tmp/ablated"
labels+=(ablated)
if [ -n "$before" ]; then
  echo "building: before ($before)" >&2
  worktree="$tmp/worktree"
  git worktree add --detach "$worktree" "$before" >/dev/null
  # (The same features: with --clmul, the commit's own host configuration.)
  # shellcheck disable=SC2046 # no features: no argument
  (cd "$worktree" && cp "$(CARGO_TARGET_DIR="$tmp/target-before" codec_exe $(with_features))" "$tmp/before")
  labels=(before "${labels[@]}")
fi

# Runs one binary and prints "LABEL ROUND BENCHMARK MILLISECONDS" per benchmark: criterion's
# median (the middle of its `time: [low median high]`).
run() {
  local label="$1" round="$2"
  # (`best-early` is among the ablation rows.)
  CRITERION_HOME="$tmp/criterion-$label" PROTOCOL_BENCH_QUICK=1 PROTOCOL_BENCH_ABLATION=1 "$tmp/$label" --bench "$filter" 2>/dev/null \
    | awk -v label="$label" -v round="$round" '
        $1 ~ /\// && $1 !~ /^time:/ { name = $1 }
        /time:/ {
          sub(/.*time: *\[/, ""); split($0, f, " ")
          v = f[3]; u = f[4]
          if (u == "ns") v /= 1e6; else if (u == "µs" || u == "us") v /= 1e3; else if (u == "s") v *= 1e3
          if (name != "") print label, round, name, v
          name = ""
        }'
}

for round in $(seq 1 "$rounds"); do
  for label in "${labels[@]}"; do
    echo "round $round: $label" >&2
    run "$label" "$round" >> "$tmp/medians"
  done
done

awk -v rounds="$rounds" -v labels="${labels[*]}" '
  { t[$1, $2, $3] = $4; split($3, p, "/"); if (!(p[1] in seen)) { seen[p[1]] = 1; rows[++n] = p[1] } }
  function ratio(num, den) { return (num > 0 && den > 0) ? sprintf("%.2fx", num / den) : "-" }
  # The baseline of a row: `best`, or `hand` where there is no `best` (the encoders).
  function base(label, k, row) { return (t[label, k, row "/best"] > 0) ? t[label, k, row "/best"] : t[label, k, row "/hand"] }
  END {
    nl = split(labels, l, " ")
    head = "| row |"; rule = "|---|"
    for (i = 1; i <= nl; i++) if (l[i] != "ablated") { head = head " " l[i] ": generated vs best |"; rule = rule "---|" }
    head = head " ablated: generated vs best | after: generated vs best-slicing | after: generated vs best-early | after: best-early vs best | ablated: best-early vs best | the rule, against best | mean | the rule, raw mean |"
    rule = rule "---|---|---|---|---|---|---:|---:|"
    print head; print rule
    for (r = 1; r <= n; r++) {
      row = rows[r]; line = "| " row " |"
      for (i = 1; i <= nl; i++) {
        if (l[i] == "ablated") continue
        cells = ""
        for (k = 1; k <= rounds; k++) cells = cells (k > 1 ? " / " : "") ratio(base(l[i], k, row), t[l[i], k, row "/generated"])
        line = line " " cells " |"
      }
      cells = ""
      for (k = 1; k <= rounds; k++) cells = cells (k > 1 ? " / " : "") ratio(base("ablated", k, row), t["ablated", k, row "/generated"])
      line = line " " cells " |"
      cells = ""
      for (k = 1; k <= rounds; k++) cells = cells (k > 1 ? " / " : "") ratio(t["after", k, row "/best-slicing"], t["after", k, row "/generated"])
      line = line " " cells " |"
      cells = ""
      for (k = 1; k <= rounds; k++) cells = cells (k > 1 ? " / " : "") ratio(t["after", k, row "/best-early"], t["after", k, row "/generated"])
      line = line " " cells " |"
      cells = ""
      for (k = 1; k <= rounds; k++) cells = cells (k > 1 ? " / " : "") ratio(t["after", k, row "/best"], t["after", k, row "/best-early"])
      line = line " " cells " |"
      cells = ""
      for (k = 1; k <= rounds; k++) cells = cells (k > 1 ? " / " : "") ratio(t["ablated", k, row "/best"], t["ablated", k, row "/best-early"])
      line = line " " cells " |"
      # The rule: generated in the after binary over generated in the ablated, each first divided
      # by the `best` of its own binary and round (timed seconds apart, so a drift of the
      # host between the two binaries cancels), and undivided (the mean only).
      cells = ""; sum = 0; m = 0; rawsum = 0
      for (k = 1; k <= rounds; k++) {
        a = t["after", k, row "/generated"]; b = t["ablated", k, row "/generated"]
        ab = base("after", k, row); bb = base("ablated", k, row)
        if (a > 0 && b > 0 && ab > 0 && bb > 0) {
          c = (a / ab) / (b / bb) - 1; sum += c; rawsum += a / b - 1; m++
          cells = cells (k > 1 ? " / " : "") sprintf("%+.0f%%", 100 * c)
        } else cells = cells (k > 1 ? " / " : "") "-"
      }
      line = line " " cells " | " (m ? sprintf("%+.0f%%", 100 * sum / m) : "-") " | " (m ? sprintf("%+.0f%%", 100 * rawsum / m) : "-") " |"
      print line
    }
    print ""
    print "Medians (ms), per round:"
    print ""
    head = "| benchmark |"; rule = "|---|"
    for (i = 1; i <= nl; i++) { head = head " " l[i] " |"; rule = rule "---|" }
    print head; print rule
  }' "$tmp/medians"
# The raw medians, one line per benchmark: every binary's rounds.
awk '{ k = $3; if (!(k in seen)) { seen[k] = 1; order[++n] = k } v[$1, k] = v[$1, k] (v[$1, k] == "" ? "" : " / ") sprintf("%.2f", $4); if (!($1 in ls)) { ls[$1] = 1; lab[++m] = $1 } }
     END { for (i = 1; i <= n; i++) { line = "| " order[i] " |"; for (j = 1; j <= m; j++) line = line " " v[lab[j], order[i]] " |"; print line } }' "$tmp/medians"
