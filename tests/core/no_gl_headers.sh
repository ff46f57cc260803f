#!/usr/bin/env bash
# sylva_core must stay CPU-only: no GL, EGL, OSMesa, GLFW or glad header may be
# included anywhere under its folders (core/ except core/render and core/app).
set -u
root="$1"
hits=$(grep -rnE '#\s*include\s*[<"](GL/|GLES|EGL/|GLFW/|glad/|epoxy/)' \
  "$root/core" --include='*.h' --include='*.cpp' \
  | grep -v "^$root/core/render/" | grep -v "^$root/core/app/")
if [ -n "$hits" ]; then
  echo "GL headers reachable from sylva_core:"
  echo "$hits"
  echo "0 passed, 1 failed"
  exit 1
fi
echo "1 passed, 0 failed"
