#!/usr/bin/env bash
# End-to-end tests of the render-farm commands and the disk tile cache: `sylva jobs`,
# `render --jobs A-B`, Slurm array variables, `sylva assemble`, GNU parallel with three
# local "nodes" sharing one disk cache (the recipe of docs/farms.md), warm-cache images
# bit-identical to cold ones (a noise terrain), corrupt and unwritable caches, `sylva cache`, a full disk
# (a 24 KiB tmpfs when this user may mount one) and --resume after it, and the OpenJD
# template's chunks. Renders are tiny (32x18 or 48x27) through EGL (llvmpipe).
#
# usage: SYLVA_BIN=path/to/sylva bash farm_cli_test.sh TESTS_APP_DIR SCRATCH_DIR
set -u

if [ $# -ne 2 ]; then
    echo "usage: SYLVA_BIN=... $0 TESTS_APP_DIR SCRATCH_DIR" >&2
    exit 2
fi
APP_DIR=$(cd "$1" && pwd)
SCRATCH=$2
SYLVA=${SYLVA_BIN:?set SYLVA_BIN to the sylva binary}
PROJECTS=$APP_DIR/projects
REPO=$(cd "$APP_DIR/../.." && pwd)
SERIES=$PROJECTS/series.sylva
TERRAIN=$PROJECTS/terrain.sylva

rm -rf "$SCRATCH"
mkdir -p "$SCRATCH"
SCRATCH=$(cd "$SCRATCH" && pwd)
# Never the user's cache: the default folder is $SYLVA_CACHE_DIR/tiles.
export SYLVA_CACHE_DIR=$SCRATCH/cache-home

# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

# json_field FILE PYTHON-EXPRESSION: evaluates the expression with `d` = the JSON in FILE.
json_eval() {
    python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print($2)" "$1"
}

# images_recorded DIR: every image output recorded by any manifest in DIR, one a line
# (repeated when several manifests record it).
images_recorded() {
    python3 - "$1" <<'EOF'
import glob, json, os, sys
for name in sorted(glob.glob(os.path.join(sys.argv[1], "manifest*.json"))):
    data = json.load(open(name))
    entries = data["images"] if isinstance(data, dict) and "images" in data else data
    for entry in entries:
        if entry.get("kind", "image") == "image":
            print(entry["output"])
EOF
}

# --- sylva jobs ---------------------------------------------------------------------

begin "jobs --json lists every job with a stable index, group, output, cost and state"
run jobs "$SERIES" --json --out "$SCRATCH/jobs"
expect_rc 0
cp "$OUT" "$SCRATCH/jobs.json"
[ "$(json_eval "$SCRATCH/jobs.json" "[j['index'] for j in d['jobs']] == list(range(d['total']))")" = True ] ||
    fail "indices are not 0..N-1"
[ "$(json_eval "$SCRATCH/jobs.json" "d['total']")" = 16 ] || fail "expected 16 jobs (8 images, 4 compare, 4 blend)"
[ "$(json_eval "$SCRATCH/jobs.json" "sum(j['kind'] == 'image' for j in d['jobs'])")" = 8 ] || fail "expected 8 images"
[ "$(json_eval "$SCRATCH/jobs.json" "all(j['state'] == 'missing' and j['cost'] > 0 and len(j['hash']) == 16 for j in d['jobs'])")" = True ] ||
    fail "fresh jobs must be missing, with a cost and a hash"
[ ! -e "$SCRATCH/jobs" ] || fail "jobs wrote into the output folder"
end

begin "jobs: the same listing twice (stable)"
run jobs "$SERIES" --json --out "$SCRATCH/jobs"
cmp -s "$OUT" "$SCRATCH/jobs.json" || fail "the listing changed between two calls"
end

# --- --jobs usage -------------------------------------------------------------------

begin "--jobs 9-3 -> usage error, exit 2"
run render "$SERIES" --jobs 9-3 --out "$SCRATCH/bad"
expect_rc 2
expect_stderr "--jobs expects A-B with 0 <= A <= B"
[ ! -e "$SCRATCH/bad" ] || fail "output written"
end

begin "--jobs beyond the last job -> clear error, exit 1"
run render "$SERIES" --jobs 40-50 --out "$SCRATCH/bad"
expect_rc 1
expect_stderr "jobs 40-50 are not within the series' jobs 0-15"
end

begin "--jobs with --shard -> usage error"
run render "$SERIES" --jobs 0-3 --shard 1/2 --out "$SCRATCH/bad"
expect_rc 2
expect_stderr "--jobs and --shard exclude each other"
end

begin "a Slurm task outside the array -> usage error"
SLURM_ARRAY_TASK_ID=5 SLURM_ARRAY_TASK_COUNT=2 "$SYLVA" render "$SERIES" --out "$SCRATCH/bad" >"$OUT" 2>"$ERR"
RC=$?
expect_rc 2
expect_stderr "SLURM_ARRAY_TASK_ID=5 with SLURM_ARRAY_TASK_COUNT=2"
end

# --- assemble before the images -------------------------------------------------------

begin "assemble before the images -> exit 1, names what is missing"
run assemble "$SERIES" --out "$SCRATCH/ranges"
expect_rc 1
expect_stderr "8 images are not rendered"
end

# --- ranges over N tasks ------------------------------------------------------------

begin "--jobs ranges over 4 tasks (chunks of 5, the last clamped) render every image once"
for range in 0-4 5-9 10-14 15-19; do
    "$SYLVA" render "$SERIES" --jobs "$range" --out "$SCRATCH/ranges" --no-disk-cache \
        >>"$OUT" 2>>"$ERR" || fail "render --jobs $range failed"
done
grep -q "not within" "$ERR" && fail "a chunk reaching past the last job was not clamped"
images_recorded "$SCRATCH/ranges" | sort > "$SCRATCH/ranges.list"
[ "$(wc -l < "$SCRATCH/ranges.list")" = 8 ] || fail "expected 8 image records, got $(wc -l < "$SCRATCH/ranges.list")"
[ -z "$(uniq -d "$SCRATCH/ranges.list")" ] || fail "an image was rendered twice: $(uniq -d "$SCRATCH/ranges.list")"
[ "$(find "$SCRATCH/ranges" -name '*.png' | wc -l)" = 8 ] || fail "expected 8 PNGs before assemble"
end

begin "assemble makes the comparisons and the contact sheet without GL"
SYLVA_GL=bogus-no-gl-needed run assemble "$SERIES" --out "$SCRATCH/ranges"
expect_rc 0
[ -f "$SCRATCH/ranges/photos_contact_sheet.png" ] || fail "no contact sheet"
[ "$(find "$SCRATCH/ranges" -name '*.png' | wc -l)" = 17 ] || fail "expected 8 images + 8 comparisons + 1 sheet"
run jobs "$SERIES" --json --out "$SCRATCH/ranges"
cp "$OUT" "$SCRATCH/after.json"
[ "$(json_eval "$SCRATCH/after.json" "d['current']")" = 16 ] || fail "not every job is current after assemble"
run assemble "$SERIES" --out "$SCRATCH/ranges"
expect_rc 0
grep -v "contact sheet" "$OUT" | grep -q . && fail "a second assemble made comparisons again"
end

begin "--resume with other ranges skips what any range finished"
run render "$SERIES" --jobs 0-15 --resume --out "$SCRATCH/ranges" --progress json
expect_rc 0
expect_stdout '"skipped": 8'
end

# --- Slurm array variables -------------------------------------------------------------

begin "SLURM_ARRAY_TASK_ID/COUNT select a shard"
for task in 1 2; do
    SLURM_ARRAY_TASK_ID=$task SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_COUNT=2 \
        "$SYLVA" render "$SERIES" --out "$SCRATCH/slurm" >"$OUT" 2>>"$ERR" || fail "task $task failed"
done
expect_stderr "Slurm array task 2: shard 2/2"
[ -f "$SCRATCH/slurm/manifest.shard-1-of-2.json" ] && [ -f "$SCRATCH/slurm/manifest.shard-2-of-2.json" ] ||
    fail "no shard manifests"
[ "$(images_recorded "$SCRATCH/slurm" | sort | uniq -d | wc -l)" = 0 ] || fail "an image was rendered twice"
[ "$(images_recorded "$SCRATCH/slurm" | wc -l)" = 8 ] || fail "not every image was rendered"
end

# --- GNU parallel: 3 local nodes, one disk cache ------------------------------------------

begin "GNU parallel: 3 workers sharing a disk cache render the series exactly once"
if ! command -v parallel >/dev/null 2>&1 || ! parallel --version 2>/dev/null | grep -q "GNU parallel"; then
    fail "GNU parallel is not installed (scripts/setup installs it)"
else
    # The docs/farms.md line: one chunk of job indices per task, three at a time.
    run jobs "$TERRAIN" --json --out "$SCRATCH/parallel"
    total=$(python3 -c "import json,sys; print(json.load(open(sys.argv[1]))['total'])" "$OUT")
    chunks=$(python3 -c "import sys; n=int(sys.argv[1]); c=-(-n//3); print(' '.join(f'{a}-{a+c-1}' for a in range(0,n,c)))" "$total")
    # shellcheck disable=SC2086
    parallel --jobs 3 --halt now,fail=1 "$SYLVA" render "$TERRAIN" --jobs {} \
        --out "$SCRATCH/parallel" --disk-cache "$SCRATCH/shared-cache" ::: $chunks >"$OUT" 2>"$ERR"
    RC=$?
    expect_rc 0
    [ "$(images_recorded "$SCRATCH/parallel" | sort | uniq -d | wc -l)" = 0 ] || fail "an image was rendered twice"
    [ "$(images_recorded "$SCRATCH/parallel" | wc -l)" = "$total" ] || fail "not every image was rendered"
    "$SYLVA" cache stats --disk-cache "$SCRATCH/shared-cache" --json >"$OUT" 2>"$ERR"
    [ "$(json_eval "$OUT" "d['entries'] > 0 and d['temporary_files'] == 0")" = True ] ||
        fail "the shared cache holds no entries or unfinished writes"
fi
end

# --- warm disk cache: bit-identical images, no tiles produced --------------------------------

begin "a warm disk cache gives bit-identical images and produces no tiles"
run render "$TERRAIN" --out "$SCRATCH/nocache" --no-disk-cache
expect_rc 0
run render "$TERRAIN" --out "$SCRATCH/cold" --disk-cache "$SCRATCH/cache"
expect_rc 0
run render "$TERRAIN" --out "$SCRATCH/warm" --disk-cache "$SCRATCH/cache" --progress json
expect_rc 0
grep '"event": "image"' "$OUT" | grep -v '"tiles": 0,' | grep -q . && fail "the warm render produced tiles: $(grep -v '"tiles": 0,' "$OUT" | head -2)"
for image in "$SCRATCH"/cold/*.png; do
    name=$(basename "$image")
    cmp -s "$image" "$SCRATCH/warm/$name" || fail "$name differs between cold and warm"
    cmp -s "$image" "$SCRATCH/nocache/$name" || fail "$name differs with and without the cache"
done
end

begin "corrupt entries: detected, recomputed, one warning, same images"
count=0
while IFS= read -r entry; do
    count=$((count + 1))
    if [ $((count % 2)) -eq 0 ]; then truncate -s 100 "$entry"; else printf 'X' | dd of="$entry" bs=1 seek=300 conv=notrunc status=none; fi
done < <(find "$SCRATCH/cache" -name '*.tile')
[ "$count" -gt 2 ] || fail "too few entries to damage ($count)"
run render "$TERRAIN" --out "$SCRATCH/repaired" --disk-cache "$SCRATCH/cache"
expect_rc 0
[ "$(grep -c "warning: tile cache:" "$ERR")" = 1 ] || fail "expected exactly one cache warning"
expect_stderr "removed and recomputed"
for image in "$SCRATCH"/cold/*.png; do
    cmp -s "$image" "$SCRATCH/repaired/$(basename "$image")" || fail "$(basename "$image") differs after repair"
done
end

begin "an unwritable cache folder: render works, one warning"
touch "$SCRATCH/not-a-folder"
run render "$SERIES" --size 32x18 --out "$SCRATCH/unwritable" --disk-cache "$SCRATCH/not-a-folder/tiles"
expect_rc 0
[ "$(grep -c "warning: tile cache:" "$ERR")" = 1 ] || fail "expected exactly one cache warning"
expect_stderr "rendering goes on without writing the cache"
end

begin "sylva cache stats / prune / clear"
run cache stats --disk-cache "$SCRATCH/cache" --json
expect_rc 0
before=$(json_eval "$OUT" "d['entries']")
[ "$before" -gt 0 ] || fail "no entries"
run cache prune --disk-cache "$SCRATCH/cache" --budget-mb 64 --json
expect_rc 0
# Prune may have removed entries (64 MiB budget): clear must remove what is left.
run cache stats --disk-cache "$SCRATCH/cache" --json
expect_rc 0
left=$(json_eval "$OUT" "d['entries']")
[ "$left" -le "$before" ] || fail "prune added entries: $before -> $left"
run cache clear --disk-cache "$SCRATCH/cache"
expect_rc 0
removed=$(sed -n 's/.*removed \([0-9]*\) files.*/\1/p' "$OUT")
[ "${removed:-0}" -ge "$left" ] || fail "clear removed ${removed:-none} of $left entries"
run cache stats --disk-cache "$SCRATCH/cache" --json
[ "$(json_eval "$OUT" "d['entries']")" = 0 ] || fail "entries left after clear"
run cache frobnicate
expect_rc 2
run cache stats --budget-mb 1x
expect_rc 2
end

# --- a full disk -------------------------------------------------------------------------

begin "a full disk: exit 75, nothing half-written, --resume finishes after space returns"
FULL=$SCRATCH/full
mkdir -p "$FULL"
if mount -t tmpfs -o size=24k tmpfs "$FULL" 2>/dev/null; then
    run render "$SERIES" --out "$FULL/out" --no-disk-cache --no-comparisons
    expect_rc 75
    expect_stderr "run again with --resume"
    leftovers=$(find "$FULL" -name '.sylva-*' -o -name '.tmp-*')
    [ -z "$leftovers" ] || fail "temporary files left: $leftovers"
    for image in $(images_recorded "$FULL/out"); do
        python3 -c "import sys; d=open(sys.argv[1],'rb').read(); sys.exit(0 if d[:8]==b'\x89PNG\r\n\x1a\n' and d[-8:-4]==b'IEND' else 1)" \
            "$FULL/out/$image" || fail "recorded image $image is not a complete PNG"
    done
    done_before=$(images_recorded "$FULL/out" | wc -l)
    [ "$done_before" -lt 8 ] || fail "the disk never filled"
    mount -o remount,size=4m "$FULL"
    run render "$SERIES" --out "$FULL/out" --no-disk-cache --no-comparisons --resume --progress json
    expect_rc 0
    expect_stdout "\"skipped\": $done_before"
    [ "$(images_recorded "$FULL/out" | wc -l)" = 8 ] || fail "resume did not finish the series"
    umount "$FULL"
else
    echo "  (skipped: this user cannot mount a tmpfs; the disk cache's ENOSPC path is tested in core.DiskTileCache.*)"
fi
end

# --- the OpenJD template of docs/farms.md ----------------------------------------------------

begin "the OpenJD template's chunks cover every job once"
python3 "$APP_DIR/check_openjd_chunks.py" "$REPO/docs/farms/sylva-openjd.yaml" "$SCRATCH/jobs.json" >"$OUT" 2>"$ERR"
RC=$?
expect_rc 0
end

finish
