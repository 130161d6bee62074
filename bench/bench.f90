!> dpend-bench: performance figures, one per line as `key: value unit`.
!> Build and run in the release profile:
!>   . scripts/flags.sh; fpm run dpend-bench --profile release --flag "$RELEASE_FLAGS"
program bench
   use, intrinsic :: iso_fortran_env, only: output_unit
   use bench_batch, only: run_batch_benchmarks
   implicit none
   call run_batch_benchmarks(output_unit)
end program bench
