#!/usr/bin/env bash
# Follows docs/tutorial.md as a user does, in a crate of its own outside the repository, so that
# the tutorial cannot drift from what works:
#
#   bash scripts/tutorial.sh
#
# - Every fenced block whose info string carries `file=PATH` (```toml file=specs/rover.toml) is
#   written whole to PATH in a new crate, `rover-link`, in a temporary directory.
# - Beside it, `protocol` is the repository (the tutorial's clone), so the crate's dependency
#   `{ path = "../protocol/protocol" }` resolves as it does for a user.
# - Every line `$ COMMAND` of a `console` block is run in the crate, in the tutorial's order, and
#   its standard output must be the lines that follow it, up to the next `$` line or the end of
#   the block. Its exit status must be 0, or N for a block marked `console status=N`.
# - `sh` blocks (clone, install, `cargo new`) are the user's set-up, done here by the lines
#   above and by putting the repository's `protocol` command first on PATH.
#
# The crate is built with the workspace's Cargo.lock (dependencies at the versions CI tests, none
# fetched beyond those), into `target/tutorial`. Prints `tutorial: PASS` at the end or stops at
# the first difference.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
crate="$scratch/rover-link"
steps="$scratch/steps"
mkdir -p "$crate" "$steps"
ln -s "$root" "$scratch/protocol"

# The files into the crate; each command into steps/NNN.cmd, its output into NNN.out, its exit
# status into NNN.status.
awk -v crate="$crate" -v steps="$steps" '
  /^```/ {
    if (open) { open = 0; next }
    open = 1; file = ""; console = 0; step = ""
    info = substr($0, 4)
    if (match(info, /file=[^ ]+/)) {
      file = crate "/" substr(info, RSTART + 5, RLENGTH - 5)
      dir = file; sub(/\/[^\/]*$/, "", dir)
      system("mkdir -p \"" dir "\"")
      printf "" > file
    } else if (info ~ /^console/) {
      console = 1; status = 0
      if (match(info, /status=[0-9]+/)) status = substr(info, RSTART + 7, RLENGTH - 7)
    }
    next
  }
  open && file != "" { print > file; next }
  open && console && /^\$ / {
    n++; step = sprintf("%s/%03d", steps, n)
    print substr($0, 3) > (step ".cmd")
    printf "" > (step ".out")
    print status > (step ".status")
    next
  }
  open && console && step != "" { print > (step ".out") }
' "$root/docs/tutorial.md"

for f in Cargo.toml specs/rover.toml src/lib.rs; do
  [[ -f "$crate/$f" ]] || { echo "docs/tutorial.md shows no $f" >&2; exit 1; }
done
cp "$root/Cargo.lock" "$crate/Cargo.lock"

# The `protocol` command the tutorial installs from the clone.
(cd "$root" && cargo build --quiet -p protocol-cli --bin protocol)
export PATH="$root/target/debug:$PATH"
export CARGO_TARGET_DIR="$root/target/tutorial"
export NO_COLOR=1

ran=0
for cmd in "$steps"/*.cmd; do
  step=${cmd%.cmd}
  line=$(cat "$cmd")
  echo "\$ $line"
  status=0
  (cd "$crate" && bash -c "$line") > "$step.actual" || status=$?
  want=$(cat "$step.status")
  if [[ $status != "$want" ]]; then
    echo "tutorial: \`$line\` exited with $status, docs/tutorial.md shows $want" >&2
    exit 1
  fi
  if ! diff -u "$step.out" "$step.actual" >&2; then
    echo "tutorial: \`$line\` printed otherwise than docs/tutorial.md shows (- shown, + printed)" >&2
    exit 1
  fi
  ran=$((ran + 1))
done
if ((ran < 5)); then
  echo "tutorial: only $ran commands found in docs/tutorial.md" >&2
  exit 1
fi
echo "tutorial: PASS ($ran commands)"
