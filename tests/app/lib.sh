# Shared harness of the CLI tests (cli_test.sh, plant_cli_test.sh): sourced after the
# test has set SYLVA (the binary) and SCRATCH (an empty scratch folder, absolute).
# Cases: begin NAME; run ARGS...; expect_* ...; end. finish prints the summary and
# returns non-zero when a case failed.

passed=0
failed=0
OUT=$SCRATCH/stdout
ERR=$SCRATCH/stderr
RC=0

# run ARGS...: runs sylva, storing the exit code in RC and the output in $OUT / $ERR.
run() {
    "$SYLVA" "$@" >"$OUT" 2>"$ERR"
    RC=$?
}

# Per-case bookkeeping: a case fails if any of its checks fails.
case_name=""
case_ok=1
begin() {
    case_name=$1
    case_ok=1
}
fail() {
    case_ok=0
    echo "  FAIL [$case_name]: $*"
}
end() {
    if [ "$case_ok" -eq 1 ]; then
        passed=$((passed + 1))
        echo "ok   $case_name"
    else
        failed=$((failed + 1))
        echo "--- stdout:"; sed 's/^/    /' "$OUT"
        echo "--- stderr:"; sed 's/^/    /' "$ERR"
    fi
}
expect_rc() {
    [ "$RC" -eq "$1" ] || fail "exit code $RC, expected $1"
}
expect_stderr() {
    grep -qF -- "$1" "$ERR" || fail "stderr lacks: $1"
}
expect_stdout() {
    grep -qF -- "$1" "$OUT" || fail "stdout lacks: $1"
}
finish() {
    echo "$passed passed, $failed failed"
    [ "$failed" -eq 0 ]
}
