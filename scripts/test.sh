#!/usr/bin/env bash
# Run the test suites in the debug profile (all runtime checks, FP traps) and in
# the release profile. Usage: scripts/test.sh [suite or suite/test]
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/flags.sh
echo "== debug profile: $DEBUG_FLAGS"
fpm build --flag "$DEBUG_FLAGS"
fpm test --flag "$DEBUG_FLAGS" -- "$@"
echo "== release profile: $RELEASE_FLAGS"
fpm build --profile release --flag "$RELEASE_FLAGS"
fpm test --profile release --flag "$RELEASE_FLAGS" -- "$@"
