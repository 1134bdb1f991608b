#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-3.0-or-later
# Fails (exit 1) if any C++ file differs from .clang-format; `--fix` rewrites them in place.
set -euo pipefail
cd "$(dirname "$0")/.."
files=$(git ls-files 'src/*.cpp' 'src/*.hpp' 'tests/*.cpp' 'tests/*.hpp' 'data_tools/*.cpp' 'python/*.cpp' 'python/*.hpp')
if [ "${1:-}" = "--fix" ]; then
  clang-format -i $files
  exit 0
fi
bad=0
for f in $files; do
  if ! clang-format --dry-run --Werror "$f" >/dev/null 2>&1; then echo "needs formatting: $f"; bad=1; fi
done
exit $bad
