#!/usr/bin/env bash
# End-to-end tests of `sylva analyse`: a synthetic DEM (a hill on a plain, made here with
# gdal_translate, UTM 25S, 30 m) and small projects written into the scratch folder; the
# GeoTIFF written is read back with GDAL (gdalinfo: size, origin, pixel size, CRS, bands,
# compression, overviews), the PNG map beside it has the grid's aspect, and broken projects
# or unwritable outputs give errors and leave nothing behind.
# With the sample data, the keys of `sylva bench analysis --json`.
#
# usage: SYLVA_BIN=path/to/sylva bash analyse_cli_test.sh SCRATCH_DIR
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

# The DEM: 60 x 50 cells of 30 m from (290000, 9116500), a 60 m hill at the centre.
{
    echo "ncols 60"; echo "nrows 50"; echo "xllcorner 290000"; echo "yllcorner 9115000"
    echo "cellsize 30"
    awk 'BEGIN { for (r = 0; r < 50; r++) { line = ""; for (c = 0; c < 60; c++) {
        d2 = ((c - 30) ^ 2 + (r - 25) ^ 2) / 60.0; line = line sprintf("%.2f ", 10 + 60 * exp(-d2)) }
        print line } }'
} >"$SCRATCH/dem.asc"
gdal_translate -q -a_srs EPSG:32725 "$SCRATCH/dem.asc" "$SCRATCH/dem.tif" || { echo "gdal_translate failed"; exit 1; }

# project NAME BODY: a project file with the DEM source and BODY appended.
project() {
    {
        echo 'source dem : raster { file = "dem.tif"; kind = elevation }'
        echo 'source hills : noise {}'
        printf '%s\n' "$2"
    } >"$SCRATCH/$1.sylva"
}
# expect_nothing_written: no .tif, .png nor temporary file under the output folder.
expect_nothing_written() {
    local found
    found=$(find "$SCRATCH/out" -type f \( -name '*.tif' -o -name '*.png' -o -name '.sylva-*' \) \
        -print 2>/dev/null)
    [ -z "$found" ] || fail "files left behind: $found"
}

begin "no project -> usage, exit 2"
run analyse
expect_rc 2
expect_stderr "analyse needs exactly one project file"
end

# The hill top is at cell (30, 25): x = 290000 + 30.5 * 30, y = 9116500 - 25.5 * 30.
project good 'ztv mast {
    elevation = @dem
    targets = [{ position = [290915m, 9115735m], height = 40m }]
    extent = [290150m, 9115300m, 291350m, 9116380m]
    resolution = 30m
    output = "out/{name}.tif"
}
project { crs = "EPSG:32725" }'

begin "analyse writes a georeferenced, compressed GeoTIFF with overviews"
(cd "$SCRATCH" && "$SYLVA" analyse good.sylva --json >"$OUT" 2>"$ERR"); RC=$?
expect_rc 0
expect_stdout '"name": "mast"'
expect_stdout '"cells": 1440'
expect_stderr "ztv 'mast': 40 x 36 cells of 30.0 m, 1 target(s)"
tif=$SCRATCH/out/mast.tif
if [ -f "$tif" ]; then
    info=$(gdalinfo "$tif")
    grep -qF "Size is 40, 36" <<<"$info" || fail "size: $(grep 'Size is' <<<"$info")"
    grep -qF "Origin = (290150.000000000000000,9116380.000000000000000)" <<<"$info" ||
        fail "origin: $(grep Origin <<<"$info")"
    grep -qF "Pixel Size = (30.000000000000000,-30.000000000000000)" <<<"$info" ||
        fail "pixel size: $(grep 'Pixel Size' <<<"$info")"
    grep -qF 'ID["EPSG",32725]' <<<"$info" || fail "CRS is not EPSG:32725"
    grep -qF "COMPRESSION=DEFLATE" <<<"$info" || fail "not DEFLATE-compressed"
    [ "$(grep -c 'Overviews: 20x18' <<<"$info")" -eq 3 ] || fail "bands lack overviews"
    for band in visible count fraction; do
        grep -qF "Description = $band" <<<"$info" || fail "no band '$band'"
    done
    # The hill top sees the mast: pixel (25, 21) of the grid is the top cell (30, 25) of the DEM.
    value=$(gdallocationinfo -valonly -b 3 "$tif" 25 21)
    [ "$value" = "1" ] || fail "the hill top does not see all of the mast (fraction = '$value')"
else
    fail "no $tif"
fi
png=$SCRATCH/out/mast.png
if [ -f "$png" ]; then
    size=$(gdalinfo "$png" | sed -n 's/^Size is \([0-9]*\), \([0-9]*\)$/\1 \2/p')
    read -r pw ph <<<"$size"
    # 40 x 36 cells: the map keeps the grid's aspect (whole pixels per cell).
    [ -n "$pw" ] && [ $((pw * 36)) -eq $((ph * 40)) ] || fail "map size '$size' lacks the 40:36 aspect"
    [ "${pw:-0}" -ge 400 ] || fail "map only $pw px wide"
    gdalinfo "$png" | grep -q "Band 3" || fail "map is not RGB"
else
    fail "no $png"
fi
expect_stdout '"map": '
[ -z "$(find "$SCRATCH/out" -name '.sylva-*')" ] || fail "temporary file left behind"
end

begin "the map cannot be written -> error, no GeoTIFF, nothing left behind"
rm -rf "$SCRATCH/out"
mkdir -p "$SCRATCH/out/mast.png"
(cd "$SCRATCH" && "$SYLVA" analyse good.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "ztv 'mast': "
expect_nothing_written
end

begin "the GeoTIFF cannot be written -> error, its map removed, nothing left behind"
rm -rf "$SCRATCH/out"
mkdir -p "$SCRATCH/out/mast.tif"
(cd "$SCRATCH" && "$SYLVA" analyse good.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "ztv 'mast': "
expect_nothing_written
end

project outside 'ztv mast {
    elevation = @dem
    targets = [{ position = [290915m, 9115735m], height = 40m }]
    extent = [289000m, 9115300m, 291350m, 9116380m]
}
project { crs = "EPSG:32725" }'
begin "extent outside the DEM -> located error, nothing written"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse outside.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "outside.sylva:6:14: ztv 'mast': the extent reaches outside the elevation raster"
expect_nothing_written
end

project target 'ztv mast {
    elevation = @dem
    targets = [
        { position = [290915m, 9115735m], height = 40m },
        { position = [291700m, 9115735m], height = 40m },
    ]
    extent = [290150m, 9115300m, 291350m, 9116380m]
}
project { crs = "EPSG:32725" }'
begin "target outside the extent -> located error at the target, nothing written"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse target.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "target.sylva:7:9: ztv 'mast': the target lies outside the extent"
expect_nothing_written
end

project height 'ztv mast {
    elevation = @dem
    targets = [{ position = geo(-8deg, -34.9deg), height = -5m }]
}'
begin "non-positive target height -> located DSL error"
(cd "$SCRATCH" && "$SYLVA" analyse height.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "error[E0404]: value out of range for 'height'"
expect_stderr "height.sylva:5:60"
expect_nothing_written
end

project fine 'ztv mast {
    elevation = @dem
    targets = [{ position = [290915m, 9115735m], height = 40m }]
    resolution = 0.1m
}
project { crs = "EPSG:32725" }'
begin "resolution below the limit -> located DSL error"
(cd "$SCRATCH" && "$SYLVA" analyse fine.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "fine.sylva:6:18"
expect_stderr "is below the minimum 1m"
end

project noise 'ztv mast {
    elevation = @hills
    targets = [{ position = [290915m, 9115735m], height = 40m }]
}
project { crs = "EPSG:32725" }'
begin "elevation that is no raster source -> located error"
(cd "$SCRATCH" && "$SYLVA" analyse noise.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "noise.sylva:4:17: ztv 'mast': 'hills' is a noise source; a ztv needs a raster source"
end

begin "--only with an unknown name -> error naming the blocks"
(cd "$SCRATCH" && "$SYLVA" analyse good.sylva --only mats >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "--only mats: the project has no ztv block of that name (it has: mast)"
end

# A building footprint (UTM 25S) west of the hill, 30 m high, for the screened ZTV and
# the shadow study.
cat >"$SCRATCH/town.geojson" <<'JSON'
{"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32725"}},
 "features":[{"type":"Feature","properties":{"height":30},"geometry":{"type":"Polygon",
 "coordinates":[[[290500,9115600],[290620,9115600],[290620,9115900],[290500,9115900],[290500,9115600]]]}}]}
JSON
project screened 'source town : features { file = "town.geojson" }
ztv mast {
    elevation = @dem
    targets = [{ position = [290915m, 9115735m], height = 40m }]
    extent = [290150m, 9115300m, 291350m, 9116380m]
    screening = [@town]
    output = "out/{name}.tif"
}
shadow_study sun {
    elevation = @dem
    extent = [290300m, 9115400m, 290900m, 9116000m]
    resolution = 10m
    screening = [@town]
    dates = [2024-06-21]
    from = 09:00:00
    to = 15:00:00
    step_minutes = 120
    utc_offset = -3
    output = "out/{name}"
}
project { crs = "EPSG:32725" }'

begin "screened ztv and shadow study: buildings block, files georeferenced"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse screened.sylva --json >"$OUT" 2>"$ERR"); RC=$?
expect_rc 0
expect_stdout '"screened": true'
expect_stdout '"building_cells": 40'
expect_stdout '"kind": "shadow_study"'
expect_stdout '"frames": 4'
tif=$SCRATCH/out/sun/sun_hours_2024-06-21.tif
if [ -f "$tif" ]; then
    info=$(gdalinfo "$tif")
    grep -qF "Size is 60, 60" <<<"$info" || fail "size: $(grep 'Size is' <<<"$info")"
    grep -qF 'ID["EPSG",32725]' <<<"$info" || fail "CRS is not EPSG:32725"
    grep -qF "COMPRESSION=DEFLATE" <<<"$info" || fail "not DEFLATE-compressed"
    grep -qF "Description = sun_hours" <<<"$info" || fail "no band 'sun_hours'"
    grep -qF "Overviews: 30x30" <<<"$info" || fail "no overviews"
    # Inside the footprint (the roof) the sun shines all 6 hours.
    value=$(gdallocationinfo -valonly "$tif" 25 25)
    [ "$value" = "6" ] || fail "the roof gets '$value' h, not 6"
else
    fail "no $tif"
fi
[ "$(find "$SCRATCH/out/sun" -name 'shadow_2024-06-21_*.png' | wc -l)" -eq 4 ] ||
    fail "not 4 frames: $(ls "$SCRATCH/out/sun")"
[ -f "$SCRATCH/out/sun/contact_2024-06-21.png" ] || fail "no contact sheet"
end

project baddate 'shadow_study sun {
    elevation = @dem
    dates = [2024-06-21T10:00:00]
}'
begin "a shadow study date with a time -> located error, nothing written"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse baddate.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "baddate.sylva:5:14: shadow_study 'sun': a date is a plain day"
expect_nothing_written
end

# A flat 12 km DEM at 30 m: a 1 km study at 1 m is allowed (1 M cells), but grown by
# shadow_reach = 5 km it would hold 121 M cells.
gdal_create -q -of GTiff -outsize 400 400 -bands 1 -ot Float32 -burn 10 -a_srs EPSG:32725 \
    -a_ullr 284000 9122000 296000 9110000 "$SCRATCH/flat.tif" || fail "gdal_create failed"
cat >"$SCRATCH/bigreach.sylva" <<'SYLVA'
source flat : raster { file = "flat.tif"; kind = elevation }
shadow_study sun {
    elevation = @flat
    extent = [289500m, 9115500m, 290500m, 9116500m]
    resolution = 1m
    shadow_reach = 5km
    dates = [2024-06-21]
    output = "out/{name}"
}
SYLVA
begin "a caster grid too large for shadow_reach -> located error, nothing written"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse bigreach.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "bigreach.sylva:6:20: shadow_study 'sun': the study's grid grown by shadow_reach has"
expect_nothing_written
end

# A site: a 100 m square east of the footprint; without an extent the study covers the
# square grown by site_margin (290600..290900 x 9115500..9115800, 30 x 30 cells of 10 m),
# the square holds 10 x 10 cell centres. From 09:00 to 15:00 on 21 June the building's
# shadows (30 m, sun 38 deg and more) end 40 m short of the square: 6 h everywhere on it.
cat >"$SCRATCH/square.geojson" <<'JSON'
{"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32725"}},
 "features":[{"type":"Feature","properties":{"name":"square"},"geometry":{"type":"Polygon",
 "coordinates":[[[290700,9115600],[290800,9115600],[290800,9115700],[290700,9115700],[290700,9115600]]]}}]}
JSON
cat >"$SCRATCH/points.geojson" <<'JSON'
{"type":"FeatureCollection","features":[{"type":"Feature","properties":{},
 "geometry":{"type":"Point","coordinates":[-34.9,-7.95]}}]}
JSON
site_study() {
    project "$1" "source town : features { file = \"town.geojson\" }
source square : features { file = \"$2\" }
shadow_study sun {
    elevation = @dem
    resolution = 10m
    screening = [@town]
    site = $3
    site_margin = 100m
    sun_hours_target = 2
    dates = [2024-06-21]
    from = 09:00:00
    to = 15:00:00
    step_minutes = 120
    utc_offset = -3
    output = \"out/{name}\"
}"
}
site_study site square.geojson @square
begin "shadow study with a site: grid around the site, site cells and sun summary"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse site.sylva --json >"$OUT" 2>"$ERR"); RC=$?
expect_rc 0
expect_stdout '"site_cells": 100'
expect_stdout '"site_mean_sun_hours": 6.0'
expect_stdout '"site_share_at_target": 1.0'
expect_stderr "the site (100 cells) gets 6.00 h of sun on average; 100.0 % of it gets at least 2.0 h"
tif=$SCRATCH/out/sun/sun_hours_2024-06-21.tif
info=$(gdalinfo "$tif" 2>&1)
grep -qF "Size is 30, 30" <<<"$info" || fail "size: $(grep 'Size is' <<<"$info")"
grep -qF "Origin = (290600.000000000000000,9115800.000000000000000)" <<<"$info" ||
    fail "origin: $(grep 'Origin' <<<"$info")"
end

site_study sitepoints points.geojson @square
begin "a site of points -> error naming the feature, nothing written"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse sitepoints.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "sitepoints.sylva:9:12: "
expect_stderr "points.geojson: feature 0: a site must be a polygon"
expect_nothing_written
end

site_study siteraster square.geojson @dem
begin "a site that is not a features source -> located error"
(cd "$SCRATCH" && "$SYLVA" analyse siteraster.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "siteraster.sylva:9:12: shadow_study 'sun': the site must be a features source (polygons)"
expect_nothing_written
end

# extent_geo: the corners of the good project's extent in lon/lat (gdaltransform), the
# same grid within a cell (the lon/lat rectangle bows by centimetres in UTM).
corners=$(printf '290150 9115300\n291350 9116380\n' |
    gdaltransform -s_srs EPSG:32725 -t_srs EPSG:4326 | awk '{ printf "%s %s ", $1, $2 }')
read -r w s e n <<<"$corners"
project geo "ztv mast {
    elevation = @dem
    targets = [{ position = [290915m, 9115735m], height = 40m }]
    extent_geo = [geo(${s}deg, ${w}deg), geo(${n}deg, ${e}deg)]
    output = \"out/{name}.tif\"
}
project { crs = \"EPSG:32725\" }"
begin "ztv with extent_geo: the grid of the same extent in metres"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse geo.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 0
size=$(gdalinfo "$SCRATCH/out/mast.tif" 2>&1 | sed -n 's/^Size is \([0-9]*\), \([0-9]*\)$/\1 \2/p')
read -r sx sy <<<"$size"
[ "${sx:-0}" -ge 39 ] && [ "${sx:-0}" -le 41 ] && [ "${sy:-0}" -ge 35 ] && [ "${sy:-0}" -le 37 ] ||
    fail "size '$size', not about 40 x 36"
end

project geoboth "ztv mast {
    elevation = @dem
    targets = [{ position = [290915m, 9115735m], height = 40m }]
    extent = [290150m, 9115300m, 291350m, 9116380m]
    extent_geo = [geo(${s}deg, ${w}deg), geo(${n}deg, ${e}deg)]
}
project { crs = \"EPSG:32725\" }"
begin "extent and extent_geo together -> located error"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse geoboth.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "geoboth.sylva:7:18: ztv 'mast': give either extent or extent_geo, not both"
expect_nothing_written
end

project geofar 'ztv mast {
    elevation = @dem
    targets = [{ position = [290915m, 9115735m], height = 40m }]
    extent_geo = [geo(-8.5deg, -35.5deg), geo(-8.4deg, -35.4deg)]
}
project { crs = "EPSG:32725" }'
begin "extent_geo outside the DEM -> located error"
(cd "$SCRATCH" && "$SYLVA" analyse geofar.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "geofar.sylva:6:18: ztv 'mast': the extent reaches outside the elevation raster"
expect_nothing_written
end

# Resume and shards, as `render` has them: a second --resume run skips both blocks of
# `screened` (the manifest holds their hashes); touching the footprints file reruns the
# two blocks that read it; an edit of one block reruns that block only; --shard 2/2 runs
# the second block only.
begin "analyse --resume skips up-to-date blocks and reruns what changed"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse screened.sylva --resume >"$OUT" 2>"$ERR"); RC=$?
expect_rc 0
[ -f "$SCRATCH/analyse-manifest.json" ] || fail "no analyse-manifest.json"
(cd "$SCRATCH" && "$SYLVA" analyse screened.sylva --resume --json >"$OUT" 2>"$ERR"); RC=$?
expect_rc 0
expect_stderr "ztv 'mast': up to date, skipped (--resume)"
expect_stderr "shadow_study 'sun': up to date, skipped (--resume)"
[ "$(grep -c '"skipped": true' "$OUT")" -eq 2 ] || fail "not both skipped"
sed -i 's/step_minutes = 120/step_minutes = 180/' "$SCRATCH/screened.sylva"
(cd "$SCRATCH" && "$SYLVA" analyse screened.sylva --resume >"$OUT" 2>"$ERR"); RC=$?
expect_rc 0
expect_stderr "ztv 'mast': up to date, skipped (--resume)"
grep -q "shadow_study 'sun': up to date" "$ERR" && fail "the edited shadow study was skipped"
touch -d '2030-01-01' "$SCRATCH/town.geojson"
(cd "$SCRATCH" && "$SYLVA" analyse screened.sylva --resume >"$OUT" 2>"$ERR"); RC=$?
expect_rc 0
grep -q "up to date" "$ERR" && fail "a block was skipped after its footprints changed"
sed -i 's/step_minutes = 180/step_minutes = 120/' "$SCRATCH/screened.sylva"
end

begin "analyse --shard 2/2 runs the second block only; a bad shard is a usage error"
rm -rf "$SCRATCH/out" "$SCRATCH/analyse-manifest.json"
(cd "$SCRATCH" && "$SYLVA" analyse screened.sylva --shard 2/2 >"$OUT" 2>"$ERR"); RC=$?
expect_rc 0
[ -d "$SCRATCH/out/sun" ] || fail "shard 2/2 did not run the shadow study"
[ -f "$SCRATCH/out/mast.tif" ] && fail "shard 2/2 ran the ztv"
(cd "$SCRATCH" && "$SYLVA" analyse screened.sylva --shard 3/2 >"$OUT" 2>"$ERR"); RC=$?
expect_rc 2
expect_stderr "--shard 3/2"
end

# The extent in the project's crs (web Mercator here) is converted to the DEM's UTM 25S:
# the grid is the box around the converted corners, so it holds the UTM extent of `good`.
read -r mw ms _ <<<"$(echo 290150 9115300 | gdaltransform -s_srs EPSG:32725 -t_srs EPSG:3857)"
read -r me mn _ <<<"$(echo 291350 9116380 | gdaltransform -s_srs EPSG:32725 -t_srs EPSG:3857)"
project mercator "ztv mast {
    elevation = @dem
    targets = [{ position = geo(-7.995347deg, -34.896980deg), height = 40m }]
    extent = [${mw}m, ${ms}m, ${me}m, ${mn}m]
    resolution = 30m
    output = \"out/{name}.tif\"
}
project { crs = \"EPSG:3857\" }"
begin "extent in the project's crs (EPSG:3857) -> a grid in the DEM's CRS around it"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse mercator.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 0
origin=$(gdalinfo "$SCRATCH/out/mast.tif" 2>/dev/null | sed -n 's/^Origin = (\(.*\))$/\1/p')
python3 - "$origin" <<'PY' || fail "origin '$origin' is not within 30 m of (290150, 9116380)"
import sys
x, y = (float(v) for v in sys.argv[1].split(","))
sys.exit(0 if abs(x - 290150) < 30 and abs(y - 9116380) < 30 else 1)
PY
end

# Targets from the proposal: turbines (the Olinda model: 80 m hub, 40 m blades, scaled by
# hub_height / 80) placed by an objects source. The tip at twelve o'clock whatever the rotor
# angle: 40 m hub -> 60 m, 30 m hub -> 45 m; the cumulative ZTV equals the one of the same
# two targets written by hand (band checksums).
REPO=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
cp "$REPO/projects/olinda/models/turbine.gltf" "$SCRATCH/turbine.gltf"
cat >"$SCRATCH/turbines.geojson" <<'JSON'
{"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32725"}},
 "features":[
 {"type":"Feature","id":1,"properties":{"hub_height":40,"rotor_angle":37},"geometry":{"type":"Point","coordinates":[290915,9115735]}},
 {"type":"Feature","id":2,"properties":{"hub_height":30,"rotor_angle":200},"geometry":{"type":"Point","coordinates":[290400,9115500]}}]}
JSON
project proposal 'source sites : features { file = "turbines.geojson" }
source turbines : objects {
    features = @sites
    elevation = @dem
    model = "turbine.gltf"
    size_attribute = "hub_height"
    reference_height = 80m
    heading = 120deg
    parts = { rotor = "rotor_angle" }
}
scenario s { layers = [@dem, @turbines] }
ztv farm {
    elevation = @dem
    proposal = [@turbines]
    extent = [290150m, 9115300m, 291350m, 9116380m]
    output = "out/{name}.tif"
}
ztv by_hand {
    elevation = @dem
    targets = [{ position = [290915m, 9115735m], height = 60m },
               { position = [290400m, 9115500m], height = 45m }]
    extent = [290150m, 9115300m, 291350m, 9116380m]
    output = "out/{name}.tif"
}
project { crs = "EPSG:32725" }'

begin "ztv proposal = [@turbines]: blade tips as targets, equal to the same targets by hand"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse proposal.sylva --json >"$OUT" 2>"$ERR"); RC=$?
expect_rc 0
expect_stderr "ztv 'farm': target 1: turbines feature 1, top 60.0 m above its base"
expect_stderr "ztv 'farm': target 2: turbines feature 2, top 45.0 m above its base"
for band in 1 2; do
    a=$(gdalinfo -checksum "$SCRATCH/out/farm.tif" | grep Checksum | sed -n "${band}p")
    b=$(gdalinfo -checksum "$SCRATCH/out/by_hand.tif" | grep Checksum | sed -n "${band}p")
    [ -n "$a" ] && [ "$a" = "$b" ] || fail "band $band differs: '$a' vs '$b'"
done
end

project notobjects 'source sites : features { file = "turbines.geojson" }
ztv farm {
    elevation = @dem
    proposal = [@sites]
}'
begin "a proposal that is not an objects source -> located error, nothing written"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && "$SYLVA" analyse notobjects.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "notobjects.sylva:6:17: ztv 'farm': 'sites' is a features source; proposal targets come from objects sources (placed models)"
expect_nothing_written
end

project notarget 'ztv farm {
    elevation = @dem
}'
begin "a ztv without targets or proposal -> located error"
(cd "$SCRATCH" && "$SYLVA" analyse notarget.sylva >"$OUT" 2>"$ERR"); RC=$?
expect_rc 1
expect_stderr "ztv 'farm' has no target: give \`targets\` or \`proposal\`"
end

# A wall of trees screens a plants source: a row of points 10 m apart, north-south, 90 m
# west of the hill top, each a generated conifer; the screened
# ZTV has canopy cells (no observers under the crowns) and sees less than the bare one.
python3 - "$SCRATCH/row.geojson" <<'PY'
import json, sys
features = [{"type": "Feature", "id": i + 1, "properties": {},
             "geometry": {"type": "Point", "coordinates": [290820, 9115400 + 10 * i]}}
            for i in range(70)]
json.dump({"type": "FeatureCollection",
           "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32725"}},
           "features": features}, open(sys.argv[1], "w"))
PY
project trees 'source row : features { file = "row.geojson" }
source tree : plant_model { preset = conifer; leaves = 300; seed = 3 }
source wall : plants {
    elevation = @dem
    features = @row
    species = { tree = 100% }
    models = [@tree]
    scale = [1, 1]
}
scenario s { layers = [@dem, @wall] }
ztv bare {
    elevation = @dem
    targets = [{ position = [290915m, 9115735m], height = 5m }]
    extent = [290150m, 9115300m, 291350m, 9116380m]
    output = "out/{name}.tif"
}
ztv behind_trees {
    elevation = @dem
    targets = [{ position = [290915m, 9115735m], height = 5m }]
    extent = [290150m, 9115300m, 291350m, 9116380m]
    screening = [@wall]
    output = "out/{name}.tif"
}
project { crs = "EPSG:32725" }'

begin "screening = [@plants]: the trees' crowns screen the ZTV"
rm -rf "$SCRATCH/out"
(cd "$SCRATCH" && SYLVA_CACHE_DIR="$SCRATCH/cache" "$SYLVA" analyse trees.sylva --json >"$OUT" 2>"$ERR"); RC=$?
expect_rc 0
expect_stdout '"canopy_cells": '
bare=$(python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); print(d[0]["visible_cells"], d[1]["visible_cells"], d[1]["canopy_cells"])' "$OUT")
read -r seen_bare seen_screened canopy <<<"$bare"
[ "${canopy:-0}" -ge 23 ] || fail "only '${canopy:-}' canopy cells for a 700 m row of trees"
[ "${seen_screened:-0}" -lt "${seen_bare:-0}" ] || fail "the trees hide nothing: $bare"
end

# `sylva bench analysis --json` (needs the Olinda DEM of scripts/fetch-samples): exactly
# the five keys of issue 19, in order.
if [ -f "$REPO/data/olinda/olinda_dem_utm25s.tif" ]; then
    begin "bench analysis --json: exactly the five keys of issue 19"
    (cd "$REPO" && "$SYLVA" bench analysis --json >"$OUT" 2>"$ERR"); RC=$?
    expect_rc 0
    keys=$(grep -o '"[a-z_0-9]*":' "$OUT" | tr -d '":' | paste -sd ' ')
    expected="suite metrics ztv_cells_per_s gdal_viewshed_cells_per_s ztv_speed_vs_gdal ztv_agreement_gdal cumulative_ztv_20_targets_s"
    [ "$keys" = "$expected" ] || fail "keys are '$keys'"
    end
else
    echo "skip bench analysis: data/olinda/olinda_dem_utm25s.tif absent (run scripts/fetch-samples)"
fi

finish
