#!/usr/bin/env bash
# Run the test suites in the debug profile (all runtime checks, FP traps) and in
# the release profile. Usage: scripts/test.sh [SUITE or SUITE/TEST ...] (any number;
# docs/testing.md)
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/flags.sh
echo "== debug profile: $DEBUG_FLAGS"
# Zero compiler warnings is the norm (docs/architecture.md, "Warnings"): the files
# compiled now (all of them on a fresh checkout) are checked; fpm shows warnings
# only with --verbose.
log=$(mktemp)
trap 'rm -f "$log"' EXIT
fpm build --tests --flag "$DEBUG_FLAGS" --verbose > "$log" 2>&1 || { tail -n 40 "$log"; exit 1; }
if grep -q -E '(Warning|warning):' "$log"; then
  grep -B 5 -E '(Warning|warning):' "$log" | grep -v '^ + '
  echo "debug build: compiler warnings (fix them, or see docs/architecture.md, Warnings)"
  exit 1
fi
fpm test --flag "$DEBUG_FLAGS" -- "$@"
echo "== release profile: $RELEASE_FLAGS"
fpm build --profile release --flag "$RELEASE_FLAGS"
fpm test --profile release --flag "$RELEASE_FLAGS" -- "$@"
