#!/usr/bin/env bash
# The language tools of the sylva command line: check (exit codes, --print-params,
# --lenient, --diagnostics=json, --set), fmt, dump --json, doc and bench dsl.
# usage: SYLVA_BIN=path/to/sylva bash cli_tools_test.sh CASES_DIR SCRATCH_DIR
set -u
CASES=$(cd "$1" && pwd)
SCRATCH=$2
SYLVA=${SYLVA_BIN:?set SYLVA_BIN}
rm -rf "$SCRATCH" && mkdir -p "$SCRATCH"
failed=0
check() {  # check NAME EXPECTED_RC COMMAND...
    local name=$1 expected=$2
    shift 2
    "$@" >"$SCRATCH/out" 2>"$SCRATCH/err"
    local rc=$?
    if [ "$rc" -ne "$expected" ]; then
        echo "FAIL $name: exit $rc, expected $expected"; sed 's/^/    /' "$SCRATCH/err"; failed=1
    else
        echo "ok   $name"
    fi
}
contains() {  # contains NAME FILE TEXT
    grep -qF -- "$3" "$2" || { echo "FAIL $1: $(basename "$2") lacks '$3'"; failed=1; }
}

cd "$CASES"
check "check clean" 0 "$SYLVA" check valid_olinda.sylva
check "check errors" 1 "$SYLVA" check unknown_reference.sylva
contains "check errors" "$SCRATCH/err" "error[E0201]: unknown reference '@ground_gradd'"
check "check usage" 2 "$SYLVA" check
check "check bad option" 2 "$SYLVA" check valid_olinda.sylva --diagnostics=xml
check "check warnings only" 0 "$SYLVA" check bare_number.sylva
check "check lenient" 0 "$SYLVA" check --lenient lenient_unknown_attribute.sylva
check "check strict" 1 "$SYLVA" check lenient_unknown_attribute.sylva
check "check json" 1 "$SYLVA" check --diagnostics=json unit_mismatch.sylva
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert d['diagnostics'][0]['code']=='E0401'" \
    "$SCRATCH/out" || { echo "FAIL check json: not the expected JSON"; failed=1; }
check "check print-params" 0 "$SYLVA" check --print-params -D relief=1.5km valid_define.sylva
contains "check print-params" "$SCRATCH/out" "relief = 1500m    (from -D)"
check "check set" 1 "$SYLVA" check --set render.exposur=2 valid_minimal.sylva
contains "check set" "$SCRATCH/err" "error[E0208]: unknown attribute 'exposur'"

check "dump" 0 "$SYLVA" dump --json valid_scenarios.sylva
cmp -s "$SCRATCH/out" valid_scenarios.json || { echo "FAIL dump: differs from valid_scenarios.json"; failed=1; }
check "dump errors" 1 "$SYLVA" dump --json unknown_attribute.sylva
check "dump usage" 2 "$SYLVA" dump valid_minimal.sylva

cp "$CASES/valid_olinda.sylva" "$SCRATCH/a.sylva"
printf 'project{title="x"}\nsource n:noise{seed=1;amplitude=2km}\n' >"$SCRATCH/b.sylva"
check "fmt check clean" 0 "$SYLVA" fmt --check "$SCRATCH/a.sylva"
check "fmt check dirty" 1 "$SYLVA" fmt --check "$SCRATCH/b.sylva"
check "fmt rewrite" 0 "$SYLVA" fmt "$SCRATCH/b.sylva"
check "fmt idempotent" 0 "$SYLVA" fmt --check "$SCRATCH/b.sylva"
contains "fmt rewrite" "$SCRATCH/b.sylva" "source n : noise { seed = 1; amplitude = 2km }"
check "fmt syntax error" 1 "$SYLVA" fmt --check unclosed_brace.sylva
check "fmt usage" 2 "$SYLVA" fmt

check "doc list" 0 "$SYLVA" doc
check "doc kind" 0 "$SYLVA" doc camera
contains "doc kind" "$SCRATCH/out" "fov : angle = optional  [1deg .. 170deg]"
check "doc unknown" 1 "$SYLVA" doc camra
contains "doc unknown" "$SCRATCH/err" "did you mean 'camera'?"
check "doc markdown" 0 "$SYLVA" doc --markdown

check "bench dsl" 0 "$SYLVA" bench dsl --json
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); assert d['suite']=='dsl' and d['metrics']['check_ms_5k_lines']>0" \
    "$SCRATCH/out" || { echo "FAIL bench: bad JSON"; failed=1; }
check "bench unknown" 2 "$SYLVA" bench nope
exit $failed
