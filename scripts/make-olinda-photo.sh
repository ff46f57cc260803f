#!/usr/bin/env bash
# Renders the stand-in "photograph" of the Olinda viewpoint pack (projects/olinda/photos/
# vp1.jpg): the `today` scenario from camera vp1 (views block viewpoint_photo), written as
# a JPEG with the EXIF a camera would write: FocalLengthIn35mmFilm 41 (vp1's 53.5 degrees
# on a 820 x 260 frame, 35 mm equivalent by the diagonal) and DateTimeOriginal. No real
# photograph of the site exists; the stand-in lets the photomontage workflow run end to end.
# Usage: scripts/make-olinda-photo.sh [path/to/sylva]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
sylva=${1:-$root/build/bin/sylva}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$sylva" render "$root/projects/olinda/olinda.sylva" --views viewpoint_photo --out "$work"
mkdir -p "$root/projects/olinda/photos"
oiiotool "$work/vp1_photo_standin.png" --ch R,G,B \
    --attrib:type=int Exif:FocalLengthIn35mmFilm 41 \
    --attrib Exif:DateTimeOriginal "2024:09:15 08:30:00" \
    --attrib Make "Sylva stand-in" \
    -o "$root/projects/olinda/photos/vp1.jpg"
echo "wrote $root/projects/olinda/photos/vp1.jpg"
