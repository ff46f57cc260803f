#!/usr/bin/env bash
# End-to-end tests of `sylva plant`: generate, info and montage on the real binary,
# good and bad arguments, exit codes, the key text of stderr and the files left on
# disk. CPU only (no GL), no network.
#
# usage: SYLVA_BIN=path/to/sylva bash plant_cli_test.sh SCRATCH_DIR
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

# The shared harness: run, begin/end, expect_rc/stderr/stdout, finish.
# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
expect_no_temporaries() {
    local found
    found=$(find "$SCRATCH" -name '.sylva-*' -print)
    [ -z "$found" ] || fail "temporary files left behind: $found"
}

# --- usage errors (exit 2) ------------------------------------------------------

begin "plant without action -> usage, exit 2"
run plant
expect_rc 2
expect_stderr "usage: sylva plant generate"
end

begin "unknown preset -> exit 2, lists the presets"
run plant generate --preset baobab --seed 1 -o "$SCRATCH/baobab.glb"
expect_rc 2
expect_stderr "sylva: unknown plant preset 'baobab' (presets: oak, conifer, birch, bush, palm)"
[ ! -e "$SCRATCH/baobab.glb" ] || fail "a file was written"
end

begin "bad seed -> exit 2"
run plant generate --preset oak --seed minus1 -o "$SCRATCH/oak.glb"
expect_rc 2
expect_stderr "--seed needs a non-negative integer, got 'minus1'"
end

begin "bad leaf count -> exit 2"
run plant generate --preset oak --seed 1 --leaves -5 -o "$SCRATCH/oak.glb"
expect_rc 2
expect_stderr "--leaves needs an integer in [0, 2000000], got '-5'"
end

begin "missing -o -> exit 2"
run plant generate --preset oak --seed 1
expect_rc 2
expect_stderr "plant generate needs -o MODEL.gltf or MODEL.glb"
end

begin "wrong output extension -> exit 2"
run plant generate --preset oak --seed 1 -o "$SCRATCH/oak.obj"
expect_rc 2
expect_stderr "-o must name a .gltf or .glb file, got '$SCRATCH/oak.obj'"
end

begin "unknown option -> exit 2"
run plant generate --preset oak --seed 1 --height 3 -o "$SCRATCH/oak.glb"
expect_rc 2
expect_stderr "unknown option '--height'"
end

begin "unknown action -> exit 2"
run plant grow
expect_rc 2
expect_stderr "unknown plant action 'grow' (generate, montage, info)"
end

# --- generate, deterministic, and info on the result ----------------------------

begin "generate glb and gltf with a leaf target"
run plant generate --preset birch --seed 5 --leaves 1000 -o "$SCRATCH/out/birch.glb"
expect_rc 0
expect_stdout "birch, seed 5, 2000 leaf and"
[ -s "$SCRATCH/out/birch.glb" ] || fail "no birch.glb"
[ "$(head -c 4 "$SCRATCH/out/birch.glb")" = "glTF" ] || fail "birch.glb lacks the GLB magic"
run plant generate --preset conifer --seed 5 -o "$SCRATCH/out/conifer.gltf"
expect_rc 0
grep -q '"sylva_skeleton"' "$SCRATCH/out/conifer.gltf" || fail "no skeleton extras"
grep -q '"alphaMode": "MASK"' "$SCRATCH/out/conifer.gltf" || fail "no alpha-masked leaf material"
expect_no_temporaries
end

begin "same seed -> identical bytes, other seed -> different"
run plant generate --preset oak --seed 9 -o "$SCRATCH/a.glb"
run plant generate --preset oak --seed 9 -o "$SCRATCH/b.glb"
cmp -s "$SCRATCH/a.glb" "$SCRATCH/b.glb" || fail "seed 9 twice differs"
run plant generate --preset oak --seed 10 -o "$SCRATCH/c.glb"
if cmp -s "$SCRATCH/a.glb" "$SCRATCH/c.glb"; then
    fail "seeds 9 and 10 give the same file"
fi
end

begin "info imports the generated model"
run plant info "$SCRATCH/out/birch.glb"
expect_rc 0
expect_stdout "2 materials, 2 meshes, 2000 leaf and"
end

begin "info on a truncated model -> exit 1 naming the file"
head -c 100 "$SCRATCH/out/birch.glb" >"$SCRATCH/cut.glb"
run plant info "$SCRATCH/cut.glb"
expect_rc 1
expect_stderr "sylva: $SCRATCH/cut.glb: truncated GLB: the header says"
end

begin "montage writes a PNG"
run plant montage --seed 1 --leaves 500 --size 64x80 -o "$SCRATCH/montage.png"
expect_rc 0
[ -s "$SCRATCH/montage.png" ] || fail "no montage.png"
expect_no_temporaries
end

finish
