#!/usr/bin/env bash
# kill -9 during `lyapunov --force` over an existing result: the final path always
# holds the old file or a complete new one.
. "$ROOT/test/reliability/lib.sh"
kill9_series lyapunov --t-end 1 -- \
  lyapunov --t-end 150 --tau 0.002 --vectors 4
finish
