#!/usr/bin/env bash
# End-to-end tests of the sylva command line: runs the real binary on small valid
# and broken projects and checks exit codes, the key text of stderr and the files
# left on disk. No network; renders are 32x18 through EGL (llvmpipe).
#
# usage: SYLVA_BIN=path/to/sylva bash cli_test.sh TESTS_APP_DIR SCRATCH_DIR
set -u

if [ $# -ne 2 ]; then
    echo "usage: SYLVA_BIN=... $0 TESTS_APP_DIR SCRATCH_DIR" >&2
    exit 2
fi
APP_DIR=$(cd "$1" && pwd)
SCRATCH=$2
SYLVA=${SYLVA_BIN:?set SYLVA_BIN to the sylva binary}
PROJECTS=$APP_DIR/projects
# The repository root (for projects/demo), two levels above tests/app.
REPO=$(cd "$APP_DIR/../.." && pwd)
FAST=(--size 32x18 --gl egl)

rm -rf "$SCRATCH"
mkdir -p "$SCRATCH"
SCRATCH=$(cd "$SCRATCH" && pwd)

passed=0
failed=0
OUT=$SCRATCH/stdout
ERR=$SCRATCH/stderr
RC=0

# run ARGS...: runs sylva, storing exit code in RC and output in $OUT / $ERR.
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
# expect_no_png DIR: no PNG (nor temporary file) anywhere below DIR.
expect_no_png() {
    if [ -d "$1" ]; then
        local found
        found=$(find "$1" \( -name '*.png' -o -name '.sylva-*' \) -print)
        [ -z "$found" ] || fail "files left behind: $found"
    fi
}

# --- usage errors (exit 2) ------------------------------------------------------

begin "no arguments -> usage, exit 2"
run
expect_rc 2
expect_stderr "usage: sylva COMMAND [options]"
end

begin "unknown option -> exit 2"
run render "$PROJECTS/tiny.sylva" --frobnicate
expect_rc 2
expect_stderr "sylva: unknown option '--frobnicate'"
end

begin "--size 0x5 -> exit 2"
run render "$PROJECTS/tiny.sylva" --size 0x5 --out "$SCRATCH/size"
expect_rc 2
expect_stderr "sylva: --size expects WIDTHxHEIGHT within 1..16384, got '0x5'"
expect_no_png "$SCRATCH/size"
end

begin "--gl bogus -> exit 2"
run render "$PROJECTS/tiny.sylva" --gl bogus --out "$SCRATCH/glopt"
expect_rc 2
expect_stderr "sylva: --gl: unknown GL back end 'bogus' (expected egl, osmesa or glfw)"
expect_no_png "$SCRATCH/glopt"
end

begin "--cache-mb 2x -> exit 2"
run render "$PROJECTS/tiny.sylva" --cache-mb 2x --out "$SCRATCH/cache"
expect_rc 2
expect_stderr "sylva: --cache-mb expects a tile cache budget in MiB within 16..1048576, got '2x'"
expect_no_png "$SCRATCH/cache"
end

begin "bench tiles without sample data -> exit 1 naming the file and scripts/fetch-samples"
run bench tiles --data "$SCRATCH/no-data"
expect_rc 1
expect_stderr "no-data/olinda/olinda_dem_utm25s.tif' is missing; run scripts/fetch-samples"
end

# --- project errors (exit 1, located) ------------------------------------------

begin "missing project file"
run render "$SCRATCH/does-not-exist.sylva" "${FAST[@]}" --out "$SCRATCH/missing"
expect_rc 1
expect_stderr "cannot read '$SCRATCH/does-not-exist.sylva': no such file"
expect_no_png "$SCRATCH/missing"
end

begin "syntax error is located"
run render "$PROJECTS/syntax.sylva" "${FAST[@]}" --out "$SCRATCH/syntax"
expect_rc 1
expect_stderr "syntax.sylva:3:17"
expect_stderr "expected a value, found '='"
expect_no_png "$SCRATCH/syntax"
end

begin "unknown source kind is located, with did-you-mean"
run render "$PROJECTS/unknown_kind.sylva" "${FAST[@]}" --out "$SCRATCH/kind"
expect_rc 1
expect_stderr "unknown_kind.sylva:2:16"
expect_stderr "unknown source kind 'normal_mapp'"
expect_stderr "did you mean 'normal_map'?"
end

begin "unknown reference is located"
run render "$PROJECTS/unknown_ref.sylva" "${FAST[@]}" --out "$SCRATCH/ref"
expect_rc 1
expect_stderr "unknown_ref.sylva:3:14"
expect_stderr "unknown reference '@heigth'"
expect_stderr "did you mean '@height'"
end

# --- output and environment errors --------------------------------------------

begin "output folder under /proc cannot be created"
run render "$PROJECTS/tiny.sylva" "${FAST[@]}" --out /proc/sylva-no
expect_rc 1
expect_stderr "cannot create output folder '/proc/sylva-no'"
[ ! -e /proc/sylva-no ] || fail "/proc/sylva-no exists"
expect_no_png "$SCRATCH"
end

begin "output folder is a regular file"
: >"$SCRATCH/a-file"
run render "$PROJECTS/tiny.sylva" "${FAST[@]}" --out "$SCRATCH/a-file"
expect_rc 1
expect_stderr "cannot create output folder '$SCRATCH/a-file': Not a directory"
[ -f "$SCRATCH/a-file" ] && [ ! -s "$SCRATCH/a-file" ] || fail "the file given as folder was changed"
expect_no_png "$SCRATCH"
rm -f "$SCRATCH/a-file"
end

begin "SYLVA_GL=bogus -> no GL context, exit 1"
SYLVA_GL=bogus "$SYLVA" render "$PROJECTS/tiny.sylva" --size 32x18 --out "$SCRATCH/envgl" >"$OUT" 2>"$ERR"
RC=$?
expect_rc 1
expect_stderr "SYLVA_GL: unknown GL back end 'bogus' (expected egl, osmesa or glfw)"
expect_no_png "$SCRATCH/envgl"
end

begin "two cameras writing the same file -> exit 1 before rendering"
run render "$PROJECTS/same_output.sylva" "${FAST[@]}" --out "$SCRATCH/same"
expect_rc 1
expect_stderr "same_output.sylva:13:7: views 'main': two images would be written to '$SCRATCH/same/shot.png'"
# Rejected before any folder is created or GL is touched.
[ ! -e "$SCRATCH/same" ] || fail "output folder created although nothing may be rendered"
end

begin "camera below the terrain -> exit 1, named, no PNG"
run render "$PROJECTS/below.sylva" "${FAST[@]}" --out "$SCRATCH/below"
expect_rc 1
expect_stderr "below.sylva:7:8: camera 'deep': the camera is"
expect_stderr "below the terrain"
expect_stderr "sylva: 1 of 1 images could not be rendered"
expect_no_png "$SCRATCH/below"
end

# --- success ---------------------------------------------------------------------

begin "tiny project renders a 32x18 PNG"
run render "$PROJECTS/tiny.sylva" "${FAST[@]}" --out "$SCRATCH/tiny"
expect_rc 0
expect_stdout "$SCRATCH/tiny/high.png  32x18"
png=$SCRATCH/tiny/high.png
if [ -f "$png" ]; then
    if command -v oiiotool >/dev/null; then
        info=$(oiiotool --info "$png" 2>&1)
        case "$info" in
            *"32 x   18, 4 channel, uint8 png"*) ;;
            *) fail "unexpected image info: $info" ;;
        esac
    else
        file "$png" | grep -qF "PNG image data, 32 x 18" || fail "not a 32x18 PNG: $(file "$png")"
    fi
else
    fail "$png was not written"
fi
leftovers=$(find "$SCRATCH/tiny" -name '.sylva-*' -print)
[ -z "$leftovers" ] || fail "temporary files left: $leftovers"
[ "$(find "$SCRATCH/tiny" -type f | wc -l)" -eq 1 ] || fail "unexpected files: $(ls -A "$SCRATCH/tiny")"
end

begin "each scenario renders its own model"
run render "$PROJECTS/scenarios.sylva" "${FAST[@]}" --out "$SCRATCH/scenarios"
expect_rc 0
expect_stdout "$SCRATCH/scenarios/hilly/low.png  32x18"
expect_stdout "$SCRATCH/scenarios/flat/low.png  32x18"
if cmp -s "$SCRATCH/scenarios/hilly/low.png" "$SCRATCH/scenarios/flat/low.png"; then
    fail "the override of scenario 'flat' did not change its image"
fi
end

# --- check ----------------------------------------------------------------------

begin "check demo project -> exit 0"
run check "$REPO/projects/demo/demo.sylva"
expect_rc 0
expect_stdout "demo.sylva: ok (3 sources, 3 cameras, 1 views)"
end

begin "check broken project -> exit 1"
run check "$PROJECTS/unknown_kind.sylva"
expect_rc 1
expect_stderr "unknown_kind.sylva:2:16"
expect_stderr "unknown source kind 'normal_mapp'"
end

begin "check missing file -> exit 1"
run check "$SCRATCH/nope.sylva"
expect_rc 1
expect_stderr "cannot read '$SCRATCH/nope.sylva': no such file"
end

echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
