#!/usr/bin/env bash
# kill -9 during `simulate --force` over an existing result: the final path always
# holds the old file or a complete new one.
. "$ROOT/test/reliability/lib.sh"
kill9_series simulate --t-end 0.1 -- \
  simulate --t-end 150 --dt 1e-3 --save-every 1
finish
