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

# The shared harness: run, begin/end, expect_rc/stderr/stdout, finish.
# shellcheck source=lib.sh
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
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

begin "--cache-mb out of range: one message for every command that takes it"
for command in "watch $PROJECTS/tiny.sylva --exit-after 1" "bench tiles" "bench terrain" \
               "bench objects"; do
  run $command --cache-mb 8
  expect_rc 2
  expect_stderr "sylva: --cache-mb expects a tile cache budget in MiB within 16..1048576, got '8'"
done
end

begin "bench vegetation --methods with an unknown method -> exit 2"
run bench vegetation --methods lod,trees
expect_rc 2
expect_stderr "sylva: --methods expects a comma-separated list of lod, bbc, mesh, points, dmbbc, impostors and farfield (got 'trees')"
end

begin "bench tiles without sample data -> exit 1 naming the file and scripts/fetch-samples"
run bench tiles --data "$SCRATCH/no-data"
expect_rc 1
expect_stderr "no-data/olinda/olinda_dem_utm25s.tif' is missing; run scripts/fetch-samples"
end

begin "bench turnaround without sample data -> exit 1 naming the file and scripts/fetch-samples"
mkdir -p "$SCRATCH/no-data/projects/olinda"
cp "$REPO/projects/olinda/olinda.sylva" "$SCRATCH/no-data/projects/olinda/"
(cd "$SCRATCH/no-data" && "$SYLVA" bench turnaround --project projects/olinda/olinda.sylva >"$OUT" 2>"$ERR")
RC=$?
expect_rc 1
expect_stderr "data/earth/earth.jpg' of projects/olinda/olinda.sylva is missing; run scripts/fetch-samples"
[ "$(ls -A "$SCRATCH/no-data/projects/olinda")" = "olinda.sylva" ] || fail "temporary project left behind"
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
expect_stderr "same_output.sylva:16:5: views 'main': two images would be written to '$SCRATCH/same/shot.png' (camera a, scenario world; camera b, scenario world)"
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
# The image and the batch manifest, nothing else.
[ "$(find "$SCRATCH/tiny" -type f | wc -l)" -eq 2 ] || fail "unexpected files: $(ls -A "$SCRATCH/tiny")"
[ -f "$SCRATCH/tiny/manifest.json" ] || fail "no manifest.json"
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

# --- view series: comparisons, manifest, resume, shards, interruption ------------

SERIES=$PROJECTS/series.sylva
list_images() { (cd "$1" && find . -name '*.png' ! -name '*contact_sheet*' | sort); }

begin "a view series renders images, comparisons, a contact sheet and a manifest"
run render "$SERIES" "${FAST[@]}" --out "$SCRATCH/series"
expect_rc 0
[ "$(list_images "$SCRATCH/series" | wc -l)" -eq 16 ] || fail "expected 16 images: $(list_images "$SCRATCH/series")"
for f in today/east_0900.png drought/west_1800.png change/east_0900.png halfway/west_1800.png \
         photos_contact_sheet.png manifest.json; do
    [ -s "$SCRATCH/series/$f" ] || fail "missing $f"
done
grep -q '"output": "change/east_0900.png"' "$SCRATCH/series/manifest.json" || fail "manifest lacks the comparison"
grep -q '"time": "2024-06-21T09:00:00+02:00"' "$SCRATCH/series/manifest.json" || fail "manifest lacks the time"
if cmp -s "$SCRATCH/series/today/east_0900.png" "$SCRATCH/series/today/east_1800.png"; then
    fail "the sun of 09:00 and 18:00 gave the same image"
fi
end

begin "--resume skips every image whose manifest entry matches"
touch -d '2020-01-01' "$SCRATCH/series/today/east_0900.png"
run render "$SERIES" "${FAST[@]}" --out "$SCRATCH/series" --resume --progress json
expect_rc 0
[ "$(grep -c '"skipped": true' "$OUT")" -eq 16 ] || fail "expected 16 skipped images"
[ "$(stat -c %Y "$SCRATCH/series/today/east_0900.png")" -lt 1600000000 ] || fail "a current image was rewritten"
expect_stdout '{"event": "done", "total": 16, "skipped": 16, "failed": 0, "degraded": 0}'
end

begin "--shard 1/2 and 2/2 render every image exactly once"
run render "$SERIES" "${FAST[@]}" --out "$SCRATCH/shards" --shard 1/2
expect_rc 0
first=$(list_images "$SCRATCH/shards")
run render "$SERIES" "${FAST[@]}" --out "$SCRATCH/shards" --shard 2/2
expect_rc 0
all=$(list_images "$SCRATCH/shards")
[ "$all" = "$(list_images "$SCRATCH/series")" ] || fail "the two shards do not add up to the series"
[ "$(echo "$first" | wc -l)" -eq 8 ] || fail "shard 1/2 rendered $(echo "$first" | wc -l) images, expected 8"
[ -f "$SCRATCH/shards/manifest.shard-1-of-2.json" ] && [ -f "$SCRATCH/shards/manifest.shard-2-of-2.json" ] ||
    fail "each shard keeps its own manifest"
run render "$SERIES" "${FAST[@]}" --out "$SCRATCH/shards" --shard 3/2
expect_rc 2
expect_stderr "--shard expects i/N with 1 <= i <= N (e.g. 2/4), got '3/2'"
end

begin "Ctrl-C stops after the current image; --resume finishes only the rest"
"$SYLVA" render "$SERIES" "${FAST[@]}" --out "$SCRATCH/interrupted" --progress json >"$OUT" 2>"$ERR" &
pid=$!
for _ in $(seq 1 600); do
    grep -q '"event": "image"' "$OUT" 2>/dev/null && break
    sleep 0.05
done
kill -INT "$pid"
wait "$pid"
RC=$?
expect_rc 130
expect_stderr "interrupted:"
expect_stderr "run again with --resume to finish"
partial=$(find "$SCRATCH/interrupted" -name '.sylva-*' -o -name '*.tmp*')
[ -z "$partial" ] || fail "half-written files left: $partial"
made=$(list_images "$SCRATCH/interrupted" | wc -l)
[ "$made" -ge 1 ] && [ "$made" -lt 16 ] || fail "expected a partial series, found $made images"
run render "$SERIES" "${FAST[@]}" --out "$SCRATCH/interrupted" --resume --progress json
expect_rc 0
[ "$(grep -c '"skipped": true' "$OUT")" -eq "$made" ] || fail "resume did not skip exactly the $made finished images"
[ "$(list_images "$SCRATCH/interrupted" | wc -l)" -eq 16 ] || fail "resume did not complete the series"
end

begin "a time without a zone is a located error before rendering"
run render "$PROJECTS/zoneless.sylva" "${FAST[@]}" --out "$SCRATCH/zoneless"
expect_rc 1
expect_stderr "zoneless.sylva:5:14: views 'photos': time 2024-06-21T09:00:00 has no zone"
[ ! -e "$SCRATCH/zoneless" ] || fail "output folder created although nothing may be rendered"
end

# --- output formats: EXR, metadata, blend sequences, MP4 -----------------------

FORMATS=$PROJECTS/formats.sylva
begin "EXR images are half float with metadata; PNGs carry the same as text"
run render "$FORMATS" "${FAST[@]}" --out "$SCRATCH/formats" --views exr
expect_rc 0
info=$(iinfo -v "$SCRATCH/formats/exr/today_east.exr" 2>&1)
echo "$info" | grep -q "half openexr" || fail "not a half-float EXR: $info"
echo "$info" | grep -q 'sylva:scenario: "today"' || fail "EXR lacks the scenario: $info"
echo "$info" | grep -q 'sylva:project_hash: "[0-9a-f]\{16\}"' || fail "EXR lacks the project hash: $info"
echo "$info" | grep -q 'sylva:version: "' || fail "EXR lacks the version: $info"
run render "$FORMATS" "${FAST[@]}" --out "$SCRATCH/formats" --views png
expect_rc 0
info=$(iinfo -v "$SCRATCH/formats/png/drought_east.png" 2>&1)
echo "$info" | grep -q 'sylva:time: "2024-06-21T09:00:00+02:00"' || fail "PNG lacks the time: $info"
echo "$info" | grep -q 'sylva:camera: "east"' || fail "PNG lacks the camera: $info"
end

begin "a blend with steps = 3 writes t = 0, 0.5, 1 (in EXR composed in linear light)"
for f in png/grow_east000.png png/grow_east001.png png/grow_east002.png exr/grow_east001.exr exr/change_east.exr; do
    [ -s "$SCRATCH/formats/$f" ] || fail "missing $f"
done
iinfo -v "$SCRATCH/formats/png/grow_east001.png" | grep -q 'sylva:blend_amount: "0.5"' || fail "step 1 is not t = 0.5"
end

begin "MP4 without ffmpeg on PATH -> located error before rendering"
PATH=/nonexistent "$SYLVA" render "$FORMATS" "${FAST[@]}" --out "$SCRATCH/nofilm" --views film >"$OUT" 2>"$ERR"
RC=$?
expect_rc 1
expect_stderr "formats.sylva:32:5: views 'film': writing MP4 (film/today_fly.mp4) needs ffmpeg on PATH; install it (apt install ffmpeg)"
[ ! -e "$SCRATCH/nofilm" ] || fail "output folder created although nothing may be rendered"
end

if command -v ffmpeg >/dev/null 2>&1 && command -v ffprobe >/dev/null 2>&1; then
    begin "a path views block with an .mp4 template writes one H.264 video"
    run render "$FORMATS" "${FAST[@]}" --out "$SCRATCH/formats" --views film
    expect_rc 0
    probe=$(ffprobe -v error -show_entries stream=codec_name,pix_fmt,nb_frames -of csv=p=0 "$SCRATCH/formats/film/today_fly.mp4" 2>&1)
    [ "$probe" = "h264,yuv420p,4" ] || fail "expected h264,yuv420p,4 frames, got: $probe"
    [ -z "$(find "$SCRATCH/formats/film" -name '.*' -print)" ] || fail "frames or temporaries left behind"
    end
else
    echo "skip MP4 encoding test: ffmpeg/ffprobe not on PATH (apt install ffmpeg)"
fi

begin "render.cache_mb out of range is a located error"
sed 's/cache_mb = 64/cache_mb = 8/' "$FORMATS" >"$SCRATCH/cache.sylva"
run render "$SCRATCH/cache.sylva" "${FAST[@]}" --out "$SCRATCH/cache"
expect_rc 1
expect_stderr "cache.sylva:34:68"
expect_stderr "8 is below the minimum 16"
end

# --- watch ----------------------------------------------------------------------

begin "watch: an edit recomputes only the changed node's tiles; errors keep the image"
mkdir -p "$SCRATCH/watch"
cp "$PROJECTS/watch.sylva" "$SCRATCH/watch/watch.sylva"
WLOG=$SCRATCH/watch/log.txt
("$SYLVA" watch "$SCRATCH/watch/watch.sylva" --gl egl --out "$SCRATCH/watch/out" --exit-after 3 --interval-ms 100 \
    --tile-stats >"$WLOG" 2>&1; echo "rc=$?" >>"$WLOG") &
wait_for() { for _ in $(seq 1 1200); do grep -q "$1" "$WLOG" 2>/dev/null && return 0; sleep 0.1; done; return 1; }
wait_for "watching" || fail "watch did not start"
first=$(grep -m1 -o '[0-9]* tiles recomputed' "$WLOG" | cut -d' ' -f1)
sed -i 's/saturation = 1.0/saturation = 1.5/' "$SCRATCH/watch/watch.sylva"
for _ in $(seq 1 1200); do [ "$(grep -c latency "$WLOG")" -ge 2 ] && break; sleep 0.1; done
second=$(grep -o '[0-9]* tiles recomputed' "$WLOG" | sed -n 2p | cut -d' ' -f1)
sed -i 's/saturation = 1.5/saturation = oops/' "$SCRATCH/watch/watch.sylva"
wait_for "keeping the last images" || fail "an error did not keep the last image"
[ -s "$SCRATCH/watch/out/east.png" ] || fail "the last image is gone"
sed -i 's/saturation = oops/saturation = 0.5/' "$SCRATCH/watch/watch.sylva"
wait_for "rc=" || fail "watch did not finish after three renders"
cp "$WLOG" "$OUT"
: >"$ERR"
expect_stdout "rc=0"
expect_stdout "expected number, found word"
[ -n "$first" ] && [ -n "$second" ] && [ "$second" -gt 0 ] && [ $((second * 3)) -lt "$first" ] ||
    fail "edit recomputed $second tiles of $first: expected only the adjust node's"
# --tile-stats: per source, what each render produced; the edit's table (the second)
# shows the adjust node recomputed and the noise terrain untouched.
produced() { awk -v name="$1" -v n="$2" '$1 == name && ++seen == n { print $2 }' "$WLOG"; }
[ "$(produced height 1)" -gt 0 ] && [ "$(produced height 2)" = 0 ] && [ "$(produced graded 2)" -gt 0 ] &&
    [ "$(produced graded 2)" = "$second" ] ||
    fail "--tile-stats: height $(produced height 1) then $(produced height 2), graded $(produced graded 2) of $second"
end

# --- check ----------------------------------------------------------------------

begin "check demo project -> exit 0"
run check "$REPO/projects/demo/demo.sylva"
expect_rc 0
expect_stdout "demo.sylva: ok (7 sources, 4 cameras, 1 views)"
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

begin "plant build --synthetic writes a .plod, plant info reads it"
mkdir -p "$SCRATCH/plant"
run plant build --synthetic 60 -o "$SCRATCH/plant/tree.plod" --threads 2 --ao-samples 4
expect_rc 0
expect_stdout "wrote $SCRATCH/plant/tree.plod:"
[ -f "$SCRATCH/plant/tree.plod" ] || fail "no .plod written"
[ -z "$(ls "$SCRATCH/plant" | grep tmp)" ] || fail "temporary file left behind"
run plant info "$SCRATCH/plant/tree.plod"
expect_rc 0
expect_stdout "plant 'synthetic-60', .plod version 1"
expect_stdout "ELLI"
end

begin "plant info on a truncated .plod -> exit 1"
head -c 300 "$SCRATCH/plant/tree.plod" >"$SCRATCH/plant/cut.plod"
run plant info "$SCRATCH/plant/cut.plod"
expect_rc 1
expect_stderr "$SCRATCH/plant/cut.plod: truncated or padded: the header says"
end

begin "plant build without -o -> exit 2"
run plant build --synthetic 10
expect_rc 2
expect_stderr "plant build needs -o OUT.plod"
end

begin "montage with a missing photograph -> located error, exit 1, nothing written"
run montage "$PROJECTS/montage_missing_photo.sylva" --out "$SCRATCH/montage"
expect_rc 1
expect_stderr "montage_missing_photo.sylva:8:12: photo 'vp_photo': $PROJECTS/no_such_photo.jpg: the photograph does not exist"
expect_no_png "$SCRATCH/montage"
end

begin "montage without a project -> usage, exit 2"
run montage
expect_rc 2
expect_stderr "montage needs exactly one project file"
end

# --- a viewpoint pack from one command (issue 18) ---------------------------------
# The pack project at 161 x 51 pixels (its cameras' print format at 50 dpi: fast); the
# stand-in photograph is rendered by Sylva first (no real photograph exists).
PACK=$SCRATCH/pack
mkdir -p "$PACK/photos"
cp "$PROJECTS/pack.sylva" "$PROJECTS/pack_proposal.geojson" "$PACK/"

begin "pack: the stand-in photograph renders"
run render "$PACK/pack.sylva" --views standin --out "$PACK/standin" --gl egl
expect_rc 0
cp "$PACK/standin/vp_standin.png" "$PACK/photos/vp.png" 2>/dev/null || fail "no stand-in"
end

begin "pack: one command writes every deliverable"
run render "$PACK/pack.sylva" --views pack --out "$PACK/out" --gl egl
expect_rc 0
for file in vp_today.png vp_proposed.png vp_wireline.png vp_pano_today.png vp_pano_proposed.png \
    vp_today.sheet.pdf vp_today.sheet.png vp_today.json vp_proposed.sheet.pdf \
    vp_pano_today.sheet.pdf vp_pano_proposed.sheet.png vp_pano_proposed.json \
    vp_photo_montage.png vp_photo_wireline.png vp_photo_model.png vp_photo.json \
    vp_photo.sheet.pdf vp_photo.sheet.png vp_photo_map.png vp_pano_wireline.png \
    vp_photo_annotated.png; do
    [ -s "$PACK/out/viewpoints/$file" ] || fail "missing viewpoints/$file"
done
grep -q '"proposal_distance_m"' "$PACK/out/viewpoints/vp_proposed.json" 2>/dev/null ||
    fail "the proposed sheet's record lacks the proposal's distance"
grep -q '"proposal_distance_m"' "$PACK/out/viewpoints/vp_today.json" 2>/dev/null &&
    fail "the baseline's record has a proposal"
if command -v pdfinfo >/dev/null; then
    pdfinfo "$PACK/out/viewpoints/vp_photo.sheet.pdf" | grep -q '^Pages: *1' ||
        fail "the photomontage sheet is no one-page PDF"
fi
end

begin "pack: a photo block without its photograph stops before anything renders"
rm "$PACK/photos/vp.png"
run render "$PACK/pack.sylva" --views pack --out "$PACK/broken" --gl egl
expect_rc 1
expect_stderr "pack.sylva:46:12: photo 'vp_photo': $PACK/photos/vp.png: the photograph does not exist"
expect_no_png "$PACK/broken"
end

finish
