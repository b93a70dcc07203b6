#!/usr/bin/env bash
# Static analysis of wardmap's own sources (not tests/): cppcheck (about 10 s) and clang-tidy with
# the checks of .clang-tidy (about 15 min on 2 cores). Installs what it needs
# (scripts/setup.sh --deps-only --with-lint: the project's packages, cppcheck, clang-tidy) and
# configures build/ for its compile_commands.json. Exit 1 when either tool reports anything.
#   scripts/lint.sh            both tools
#   scripts/lint.sh --quick    cppcheck only
# A finding that is not a defect gets a NOLINTNEXTLINE(check): reason (clang-tidy) or a
# `// cppcheck-suppress id` line with its reason, next to the code; whole checks are left out in
# .clang-tidy, each with its reason.
set -euo pipefail
cd "$(dirname "$0")/.."
QUICK=0
for a in "$@"; do
  case "$a" in
    --quick) QUICK=1 ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) echo "lint.sh: unknown option '$a' (see --help)" >&2; exit 2 ;;
  esac
done
scripts/setup.sh --deps-only --with-lint
DIRS=(slam semantics mot hdp sim apps bench)
JOBS=$(nproc 2>/dev/null || echo 2)
status=0

echo "== cppcheck (warning, portability)"
if ! cppcheck --enable=warning,portability --std=c++17 --language=c++ -I. -j"$JOBS" --quiet \
     --inline-suppr --suppress=missingIncludeSystem --suppress=missingInclude --error-exitcode=1 "${DIRS[@]}"; then
  status=1
fi

if [ $QUICK -eq 0 ]; then
  echo "== clang-tidy (.clang-tidy; log build/clang-tidy.log)"
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
  regex="^$(pwd)/($(IFS='|'; echo "${DIRS[*]}"))/"
  run-clang-tidy -p build -j "$JOBS" -quiet "$regex" >build/clang-tidy.log 2>&1 || true
  # run-clang-tidy prints each file's command and clang's "N warnings generated" (system headers,
  # filtered out); what is left are findings in our files.
  findings=$(sed 's/\x1b\[[0-9;]*m//g' build/clang-tidy.log | grep -E "^/.*: (warning|error):" | sort -u || true)
  if [ -n "$findings" ]; then
    echo "$findings"
    echo "clang-tidy: $(echo "$findings" | wc -l) findings"
    status=1
  else
    echo "clang-tidy: no findings"
  fi
fi
exit $status
