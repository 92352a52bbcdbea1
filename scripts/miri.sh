#!/usr/bin/env bash
# Runs the runtime's tests under Miri (nightly): undefined behaviour, out-of-bounds accesses and
# arithmetic overflow in the no_std runtime, on every unit, integration and doc test.
#
#   bash scripts/miri.sh                   # the whole runtime test suite
#   bash scripts/miri.sh TESTNAME          # only the tests whose name contains TESTNAME
#   bash scripts/miri.sh --test-threads=1  # each test printed as it ends
#
# Miri interprets the code, so the tests that sweep a range take a sample of it there
# (`cfg!(miri)`, docs/fuzzing.md); the run still takes long, and it is not part of `.ci/run`
# (CI stays on stable). The result is printed on the last line: `miri: PASS` or `miri: FAIL`.
set -uo pipefail
cd "$(dirname "$0")/.."

if ! rustup +nightly component list --installed 2>/dev/null | grep -q '^miri'; then
  rustup +nightly component add miri rust-src
fi
cargo +nightly miri setup >/dev/null

# Strict provenance catches more than the defaults. (Not `-Zmiri-symbolic-alignment-check`:
# memchr aligns its pointers by address, which that check cannot follow, so it reports a false
# positive in `memchr`'s SSE2 loop.) The runtime has no unsafe code, so any report points into
# a dependency or the standard library.
export MIRIFLAGS="${MIRIFLAGS:--Zmiri-strict-provenance}"
# Leave the default target dir to the stable toolchain.
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-target/miri}"

start=$(date +%s)
cargo +nightly miri test -p protocol-runtime --all-features -- "$@"
status=$?
echo "miri: $( [ $status -eq 0 ] && echo PASS || echo FAIL ) ($(( $(date +%s) - start )) s, MIRIFLAGS=$MIRIFLAGS)"
exit $status
