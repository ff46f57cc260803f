#!/usr/bin/env bash
# Renders the stand-in "photographs" of the Olinda viewpoint pack (projects/olinda/photos/
# vp1.jpg, vp2.jpg, vp3.jpg): the `today` scenario from cameras vp1, vp2 and vp3 (views block
# viewpoint_photo), each written as a JPEG with the EXIF a camera would write:
# FocalLengthIn35mmFilm 41 (the cameras' 53.5 degrees on a 820 x 260 frame, 35 mm
# equivalent by the diagonal) and DateTimeOriginal. No real photograph of the site exists
# (and none can be fetched here); the stand-ins let the photomontage workflow run end to
# end and say so in their EXIF Make ("Sylva stand-in").
# Usage: scripts/make-olinda-photo.sh [path/to/sylva]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
sylva=${1:-$root/build/bin/sylva}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$sylva" render "$root/projects/olinda/olinda.sylva" --views viewpoint_photo --out "$work"
mkdir -p "$root/projects/olinda/photos"
for viewpoint in vp1 vp2 vp3; do
    oiiotool "$work/${viewpoint}_photo_standin.png" --ch R,G,B \
        --attrib:type=int Exif:FocalLengthIn35mmFilm 41 \
        --attrib Exif:DateTimeOriginal "2024:09:15 08:30:00" \
        --attrib Make "Sylva stand-in" \
        -o "$root/projects/olinda/photos/$viewpoint.jpg"
    echo "wrote $root/projects/olinda/photos/$viewpoint.jpg"
done
