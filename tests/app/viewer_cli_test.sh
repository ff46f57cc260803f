#!/usr/bin/env bash
# End-to-end tests of `sylva view` (docs/viewer.md): the scripted flight of
# tests/render/viewer/flight.script in a real GLFW window under Xvfb (started here;
# the test is skipped, exit 77, only when Xvfb cannot start), its screenshots against
# the same run headless through EGL (oiiotool RMSE), a saved camera rendered in batch by
# `sylva render` against the viewer's screenshot, and the bad inputs: an unknown script
# command (located), no display (one error naming DISPLAY and the headless options).
#
# usage: SYLVA_BIN=path/to/sylva bash viewer_cli_test.sh TESTS_DIR SCRATCH_DIR
set -u

if [ $# -ne 2 ]; then
    echo "usage: SYLVA_BIN=... $0 TESTS_DIR SCRATCH_DIR" >&2
    exit 2
fi
TESTS=$(cd "$1" && pwd)
SCRATCH=$2
SYLVA=${SYLVA_BIN:?set SYLVA_BIN to the sylva binary}
FIXTURE=$TESTS/render/viewer

rm -rf "$SCRATCH"
mkdir -p "$SCRATCH"
SCRATCH=$(cd "$SCRATCH" && pwd)
# shellcheck source=lib.sh
source "$TESTS/app/lib.sh"
# Never the user's cache: the disk tile cache is on by default ($SYLVA_CACHE_DIR/tiles).
export SYLVA_CACHE_DIR=$SCRATCH/cache-home

# copy_fixture DIR: the viewer test project and flight script in DIR.
copy_fixture() {
    mkdir -p "$1"
    cp "$FIXTURE/viewer.sylva" "$FIXTURE/flight.script" "$1/"
}
# expect_same A B LIMIT: RMSE over RGB of two images of one size at most LIMIT (0..1).
expect_same() {
    local report
    report=$(oiiotool "$1" "$2" --diff --fail "$3" --failpercent 100 --hardfail 1 2>&1)
    local rc=$?
    local rmse
    rmse=$(printf '%s\n' "$report" | sed -n 's/.*RMS error *[:=] *\([0-9.e+-]*\).*/\1/p' | head -1)
    # Identical images: oiiotool prints only PASS.
    if [ -z "$rmse" ] && printf '%s\n' "$report" | grep -qx "PASS"; then
        rmse=0
    fi
    [ -n "$rmse" ] || { fail "oiiotool could not compare $1 and $2: $report"; return; }
    awk -v r="$rmse" -v l="$3" 'BEGIN { exit !(r <= l) }' ||
        fail "$1 vs $2: RMS error $rmse > $3 (rc $rc)"
}

begin "unknown script command -> located error, exit 1, no window needed"
printf 'camera aircraft\n  jump 3\n' >"$SCRATCH/bad.script"
run view "$FIXTURE/viewer.sylva" --gl egl --script "$SCRATCH/bad.script"
expect_rc 1
expect_stderr "bad.script:2:3: unknown script command 'jump' (expected camera,"
end

begin "no display -> one error naming DISPLAY and the headless options, exit 1"
RC=0
env -u DISPLAY "$SYLVA" view "$FIXTURE/viewer.sylva" >"$OUT" 2>"$ERR" || RC=$?
expect_rc 1
expect_stderr "no display (DISPLAY is not set)"
expect_stderr "--gl egl or osmesa"
[ "$(wc -l <"$ERR")" -eq 1 ] || fail "expected one line on stderr"
end

begin "--gl egl without a script -> usage error"
run view "$FIXTURE/viewer.sylva" --gl egl
expect_rc 2
expect_stderr "--gl egl has no window: give a --script to run headless"
end

begin "scripted flight headless (EGL)"
copy_fixture "$SCRATCH/egl"
run view "$SCRATCH/egl/viewer.sylva" --gl egl --size 320x180 --script "$SCRATCH/egl/flight.script"
expect_rc 0
expect_stdout "screenshot: $SCRATCH/egl/flown.png  320x180"
expect_stdout "saved camera 'flown'"
[ -n "$(find "$SCRATCH/cache-home/tiles" -type f 2>/dev/null | head -1)" ] ||
    fail "the viewer wrote no tiles into the default disk tile cache"
end

begin "--no-disk-cache: the viewer writes no disk tiles; a bad --disk-cache-mb is a usage error"
copy_fixture "$SCRATCH/nodisk"
run view "$SCRATCH/nodisk/viewer.sylva" --gl egl --size 320x180 --disk-cache-mb 1 \
    --script "$SCRATCH/nodisk/flight.script"
expect_rc 2
expect_stderr "--disk-cache-mb expects a disk tile cache budget in MiB within 64..1000000000"
SYLVA_CACHE_DIR=$SCRATCH/nodisk/cache-home run view "$SCRATCH/nodisk/viewer.sylva" --gl egl \
    --size 320x180 --no-disk-cache --script "$SCRATCH/nodisk/flight.script"
expect_rc 0
[ -z "$(find "$SCRATCH/nodisk/cache-home" -type f 2>/dev/null | head -1)" ] ||
    fail "tiles written to the disk cache despite --no-disk-cache"
end

# The window: an Xvfb server of our own on a free display number.
XVFB_PID=""
cleanup() { [ -n "$XVFB_PID" ] && kill "$XVFB_PID" 2>/dev/null; }
trap cleanup EXIT
DISPLAY_NUMBER=""
if command -v Xvfb >/dev/null; then
    for n in $(seq $((100 + $$ % 300)) $((120 + $$ % 300))); do
        [ -e "/tmp/.X$n-lock" ] && continue
        Xvfb ":$n" -screen 0 640x480x24 -nolisten tcp >"$SCRATCH/xvfb.log" 2>&1 &
        XVFB_PID=$!
        for _ in $(seq 50); do
            [ -e "/tmp/.X11-unix/X$n" ] && break
            sleep 0.1
        done
        if kill -0 "$XVFB_PID" 2>/dev/null && [ -e "/tmp/.X11-unix/X$n" ]; then
            DISPLAY_NUMBER=$n
            break
        fi
        XVFB_PID=""
    done
fi
if [ -z "$DISPLAY_NUMBER" ]; then
    echo "SKIP: Xvfb could not start (install the Debian package xvfb); window tests skipped"
    finish || exit 1
    exit 77
fi

begin "scripted flight in a GLFW window under Xvfb equals the headless run"
copy_fixture "$SCRATCH/window"
RC=0
DISPLAY=":$DISPLAY_NUMBER" "$SYLVA" view "$SCRATCH/window/viewer.sylva" --size 320x180 \
    --script "$SCRATCH/window/flight.script" >"$OUT" 2>"$ERR" || RC=$?
expect_rc 0
expect_stdout "screenshot: $SCRATCH/window/aircraft.png  320x180"
expect_same "$SCRATCH/window/aircraft.png" "$SCRATCH/egl/aircraft.png" 0.01
expect_same "$SCRATCH/window/flown.png" "$SCRATCH/egl/flown.png" 0.01
end

begin "the saved camera renders in batch (sylva render) like the viewer's screenshot"
run render "$SCRATCH/window/viewer.sylva" --views check --out "$SCRATCH/batch" --gl egl
expect_rc 0
[ -f "$SCRATCH/batch/flown.png" ] || fail "no batch image of the saved camera"
expect_same "$SCRATCH/batch/flown.png" "$SCRATCH/window/flown.png" 0.01
grep -q "# The hot-reload test edits this brightness" "$SCRATCH/window/viewer.sylva" ||
    fail "the project's comments were lost"
end

finish
