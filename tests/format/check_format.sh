#!/usr/bin/env bash
# Fails when a tracked C++ file is not clean under the repository's .clang-format
# (clang-format 14, Debian 12's). Lists the files and how to fix them.
#   check_format.sh ROOT
set -u
root="$1"
cd "$root" || exit 2
if ! command -v clang-format >/dev/null 2>&1; then
  echo "clang-format not found (scripts/setup installs it)"
  exit 1
fi
if git rev-parse --git-dir >/dev/null 2>&1; then
  mapfile -t files < <(git ls-files '*.cpp' '*.h')
else
  mapfile -t files < <(find core dsl render bench app tests examples -name '*.cpp' -o -name '*.h')
fi
unclean=()
for file in "${files[@]}"; do
  [ -f "$file" ] || continue
  clang-format --dry-run -Werror "$file" >/dev/null 2>&1 || unclean+=("$file")
done
if [ ${#unclean[@]} -gt 0 ]; then
  printf 'not clean under .clang-format (fix with clang-format -i FILE):\n'
  printf '  %s\n' "${unclean[@]}"
  echo "${#unclean[@]} of ${#files[@]} files not clean"
  exit 1
fi
echo "all ${#files[@]} C++ files clean under .clang-format"
