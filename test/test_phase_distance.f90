!> The phase-space distance of the divergence command (`phase_distance`) against an
!> independently known value (written for a mutant of the mutation stage,
!> scripts/check/mutate.sh, docs/testing.md, that passed every earlier test).
!> - divergence_mixed_coordinates: the phase-space distance of the elastic pendulum
!>   (r in m, φ in rad: `angle_coordinates`) wraps the angle difference to (−π, π]
!>   and never the length (mutant divergence-no-wrap: the angles left unwrapped).
module test_phase_distance
   use dpend_kinds, only: dp
   use dpend_elastic, only: elastic_t, elastic_model
   use dpend_divergence, only: phase_distance, angle_coordinates
   use testing, only: unittest_t, new_unittest, check, check_true, error_t
   implicit none
   private
   public :: collect_phase_distance

   real(dp), parameter :: pi = acos(-1.0_dp)

contains

   subroutine collect_phase_distance(tests)
      type(unittest_t), allocatable, intent(out) :: tests(:)
      tests = [new_unittest('divergence_mixed_coordinates', test_mixed_wrap)]
   end subroutine collect_phase_distance

   !> States of the elastic pendulum 2π + 0.1 rad apart in φ and 7 m apart in r:
   !> distance sqrt(7² + 0.1² + |Δrates|²), by the model's own angle mask.
   subroutine test_mixed_wrap(error)
      type(error_t), allocatable, intent(out) :: error  !! set on failure
      type(elastic_t) :: model
      logical, allocatable :: angle(:)
      real(dp) :: qa(2), qb(2), va(2), vb(2)
      model = elastic_model(1.0_dp, 40.0_dp, 1.0_dp, 9.8_dp, error)
      if (allocated(error)) return
      angle = angle_coordinates(model)
      call check_true(error, size(angle) == 2, 'two coordinates')
      if (allocated(error)) return
      call check_true(error, (.not. angle(1)) .and. angle(2), 'r is a length, phi an angle')
      if (allocated(error)) return
      qa = [1.0_dp, -0.5_dp*pi]; va = [0.2_dp, -0.3_dp]
      qb = [8.0_dp, -0.5_dp*pi + 2.0_dp*pi + 0.1_dp]; vb = [0.5_dp, 0.1_dp]
      call check(error, phase_distance(qa, va, qb, vb, angle), &
                 sqrt(7.0_dp**2 + 0.1_dp**2 + 0.3_dp**2 + 0.4_dp**2), &
                 'distance with phi wrapped and r not', rel=1e-14_dp)
      ! every coordinate an angle (no mask): both wrapped
      call check(error, phase_distance(qa, va, qb, vb), &
                 sqrt((7.0_dp - 2.0_dp*pi)**2 + 0.1_dp**2 + 0.3_dp**2 + 0.4_dp**2), &
                 'distance with both wrapped', rel=1e-14_dp)
   end subroutine test_mixed_wrap

end module test_phase_distance
