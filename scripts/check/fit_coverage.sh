#!/usr/bin/env bash
# The coverage fit of bodies (docs/fit.md, "A pendulum with bobs: the coverage
# fit"): a two-link pendulum with bobs (general bodies), sigma = 0.01 rad, 300
# samples over 6 s; the fit of d2, I2, g, c1, c2 on 50 seeded noisy series and on
# the noise-free series. Prints the noise-free error and the coverage of the 95 %
# intervals per parameter, and fails when a coverage is below 90 % or the
# noise-free error above 1e-7.
#   scripts/check/fit_coverage.sh [SERIES]     (SERIES: noisy series, default 50, 1..1000)
# Runs the test fit_params/bob_coverage of the release build (CI runs it with one
# noisy series in the debug suite).
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
series="${1:-50}"
[[ $# -le 1 && "$series" =~ ^[0-9]{1,4}$ ]] && ((series >= 1 && series <= 1000)) ||
  { echo "usage: $0 [SERIES]  (SERIES: a count in [1, 1000], got '${1:-}')" >&2; exit 2; }
cd "$root"
# shellcheck source=flags.sh
. scripts/flags.sh
DPEND_FIT_SERIES="$series" fpm test --profile release --flag "$RELEASE_FLAGS" \
  -- fit_params/bob_coverage 2>&1 | grep -v '^\[' 
