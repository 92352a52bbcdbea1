# Sourced by the benchmark scripts: `codec_exe [cargo bench options]` builds the criterion
# binary of the `codec` bench as `cargo bench` does and prints its path. Picked by target kind
# and name: `--bench codec` builds the package's tools too, and cargo lists the artifacts in the
# order they finish.
codec_exe() {
  cargo bench --no-run -p protocol-benches --bench codec --message-format=json "$@" \
    | grep -F '"kind":["bench"],"crate_types":["bin"],"name":"codec"' \
    | sed -n 's/.*"executable":"\([^"]*\)".*/\1/p' | tail -n 1
}
