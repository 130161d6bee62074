!> The front end of `dpend sweep` and `dpend sweep-compare` (app/main.f90 parses with
!> dpend_sweep_config, runs the engine, prints the closing line): the names the
!> front ends and the benchmarks use, from the engine in src/engines/ (setup, blocks
!> and run: dpend_sweep_engine; file layout: dpend_sweep_layout; resume and
!> verification: dpend_sweep_resume; comparison: dpend_sweep_compare; design in
!> docs/sweep.md, layout in docs/hdf5-layout.md).
module dpend_sweep
   use dpend_sweep_setup, only: sweep_setup_t, sweep_summary_t, build_setup, &
      block_initial_conditions, block_range, summary_text
   use dpend_sweep_engine, only: compute_block, run_sweep
   use dpend_sweep_compare, only: compare_sweeps, config_value, open_sweep_file, &
      check_sweep_data
   use dpend_sweep_resume, only: open_output
   use dpend_sweep_layout, only: write_block, finalize_file, working_file
   implicit none
   private
   public :: sweep_setup_t, build_setup, block_initial_conditions, compute_block
   public :: run_sweep, sweep_summary_t, compare_sweeps, summary_text
   public :: config_value, open_sweep_file, check_sweep_data
   ! the pieces of run_sweep, shared with the MPI sweep (mpi/, docs/mpi.md)
   public :: block_range, open_output, write_block, finalize_file, working_file
end module dpend_sweep
