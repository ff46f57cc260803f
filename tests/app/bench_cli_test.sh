#!/usr/bin/env bash
# End-to-end tests of the `sylva bench` commands that need no sample data and little time:
# the whole-number options (one helper, app/CommandLine: wholeNumberOption) with their exact
# usage messages, and the keys, key order and number format of `bench dsl`, whose body
# lives in sylva_bench.
#
# usage: SYLVA_BIN=path/to/sylva bash bench_cli_test.sh SCRATCH_DIR
set -u

if [ $# -ne 1 ]; then
    echo "usage: SYLVA_BIN=... $0 SCRATCH_DIR" >&2
    exit 2
fi
SCRATCH=$1
SYLVA=${SYLVA_BIN:?set SYLVA_BIN to the sylva binary}
rm -rf "$SCRATCH"
mkdir -p "$SCRATCH"
SCRATCH=$(cd "$SCRATCH" && pwd)

# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

# usage_error MESSAGE ARGS...: sylva ARGS exits 2 with "sylva: MESSAGE" as its stderr.
usage_error() {
    local message=$1
    shift
    begin "$* -> exit 2"
    run "$@"
    expect_rc 2
    [ "$(cat "$ERR")" = "sylva: $message" ] || fail "stderr is not exactly: sylva: $message"
    end
}

# --- whole-number options --------------------------------------------------------

usage_error "--threads needs a positive integer, got '0'" bench plantlod --threads 0
usage_error "--threads needs a positive integer, got '2x'" bench plantlod --threads 2x
usage_error "--leaves needs comma-separated leaf counts, got '1000,,5000'" \
    bench plantlod --leaves 1000,,5000
usage_error "--leaves: 7 has no thesis time to compare with (1000, 5000, 10000, 27000)" \
    bench plantlod --leaves 1000,7,x
usage_error "--dem expects a sample count per side within 16..8192" bench terrain --dem 8
usage_error "--dem expects a sample count per side within 16..8192" bench terrain --dem 64x
usage_error "--frames expects a whole number within 1..10000" bench terrain --frames 0
usage_error "--trees expects a whole number within 1..10000000" bench vegetation --trees 0
usage_error "--buildings expects a whole number within 1..1000000" bench objects --buildings 0
usage_error "--reference-scale expects a whole number within 1..8" \
    bench vegetation --reference-scale 9
usage_error "--synthetic needs a positive leaf count, got 'many'" \
    plant build --synthetic many -o "$SCRATCH/a.plod"
usage_error "--seed needs a non-negative integer, got '-1'" \
    plant build --synthetic 10 --seed -1 -o "$SCRATCH/a.plod"
usage_error "--restarts needs a positive integer, got '99999999999'" \
    plant build --synthetic 10 --restarts 99999999999 -o "$SCRATCH/a.plod"
usage_error "--ao-samples needs a non-negative integer, got ''" \
    plant build --synthetic 10 --ao-samples= -o "$SCRATCH/a.plod"

# --- suite names: every message lists every suite ----------------------------------

suites="dsl, vector, plants, analysis, views, terrain, tiles, plantlod, turnaround, vegetation, shading, objects, viewer"
usage_error "unknown bench suite 'nope' (suites: $suites)" bench nope
usage_error "bench needs one suite: $suites" bench
usage_error "--size expects WIDTHxHEIGHT within 16..16384" bench shading --size 10x10
usage_error "--shadow-margin expects a number within 0..1" bench shading --shadow-margin 2

begin "bench --help lists every suite"
run bench --help
expect_rc 0
expect_stdout "suites: $suites"
end

# --- bench dsl: keys, order and format ---------------------------------------------

begin "bench dsl --json: exactly check_ms_5k_lines and lines, three decimals"
run bench dsl --json
expect_rc 0
grep -qE '^\{"suite":"dsl","metrics":\{"check_ms_5k_lines":[0-9]+\.[0-9]{3},"lines":5000\.000\}\}$' \
    "$OUT" || fail "unexpected JSON: $(cat "$OUT")"
end

begin "bench dsl: one 'dsl.KEY = VALUE' line per metric"
run bench dsl
expect_rc 0
[ "$(sed 's/ = .*//' "$OUT" | tr '\n' ' ')" = "dsl.check_ms_5k_lines dsl.lines " ] ||
    fail "unexpected lines: $(cat "$OUT")"
expect_stdout "dsl.lines = 5000.000"
end

finish
