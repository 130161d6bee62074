!> The method registry: one record per integration method, the one place where the
!> facts about a method are written — its name and order, its properties, the
!> study's default step and tolerance ranges, its relative cost, its plot group
!> and colour, a one-line description. The factory (`dpend_methods`) builds the
!> methods named here, `dpend methods` prints this table (and, with
!> `--plot-styles`, the colours and groups for scripts/plot_study.sh), the study
!> takes its default ranges and costs from it, the bench its lists of methods.
!>
!> To add a method: its module, one record below (in the order of `dpend methods`),
!> and one `case` in `new_integrator` (dpend_methods) that allocates it. The unit
!> test `registry` checks that every record builds and that the built method
!> reports the order and properties written here.
module dpend_method_registry
   use dpend_kinds, only: dp
   implicit none
   private
   public :: method_info_t, plot_group_t, method_table, plot_groups
   public :: n_methods, method_index, method_names, field_method_names

   !> Everything dpend knows about one method besides its code.
   type :: method_info_t
      character(len=10) :: name = ''     !! as given to --method
      integer :: order = 0               !! classical order of convergence
      logical :: adaptive = .false.      !! error-controlled steps (rtol, atol)
      logical :: implicit = .false.      !! a step solves equations (else explicit)
      logical :: symplectic = .false.    !! symplectic map on (q, p)
      logical :: symmetric = .false.     !! time-symmetric (self-adjoint)
      !> needs a model with a Hamiltonian structure (`needs_hamiltonian()` of the built
      !> method): refuses damped and driven models
      logical :: hamiltonian = .false.
      !> advances canonical (q, p) on Hamiltonian models (`canonical()`), (q, q̇) on the
      !> others if it accepts them (the Gauss methods)
      logical :: canonical = .false.
      !> Kahan-compensated update that can be switched off (the roundoff experiment)
      logical :: compensated = .false.
      logical :: omega = .false.         !! has Tao's binding constant ω (--omega)
      real(dp) :: h_min = 0.0_dp         !! study: smallest step of the sweep [s]
      real(dp) :: h_max = 0.0_dp         !! study: largest step of the sweep [s]
      real(dp) :: rtol_min = 0.0_dp      !! study: smallest tolerance (0: no sweep)
      real(dp) :: rtol_max = 0.0_dp      !! study: largest tolerance
      !> rough cost of one step with energy monitoring [s] (release build, one core),
      !> used by the study only to schedule the longest jobs first and for the ETA
      real(dp) :: cost = 2.0e-6_dp
      character(len=8) :: group = ''     !! plot group (panel), a `plot_groups` id
      character(len=7) :: colour = '#7f7f7f'  !! plot colour, #rrggbb
      character(len=64) :: description = ''   !! one line
   end type method_info_t

   !> A group of methods drawn in one panel of the study's figures.
   type :: plot_group_t
      character(len=8) :: id = ''        !! as in method_info_t%group
      character(len=48) :: title = ''    !! panel title
   end type plot_group_t

   integer, parameter :: n_methods = 13  !! methods in the table

   ! Study ranges: chosen so that the fixed-step sweep is in the asymptotic regime
   ! and above roundoff on the three default cases (errors 1e-13 … 1e-4 at
   ! t_short = 1 s); dopri5 and dop853 are also swept over tolerances.

   !> The methods, in the order of `dpend methods`.
   type(method_info_t), parameter :: method_table(n_methods) = [ &
      method_info_t(name='rk4', order=4, h_min=1.0e-3_dp, h_max=4.0e-3_dp, &
                    cost=0.3e-6_dp, group='rk', colour='#d62728', &
                    description='classical Runge-Kutta, 4 stages'), &
      method_info_t(name='dopri5', order=5, adaptive=.true., &
                    h_min=2.0e-3_dp, h_max=8.0e-3_dp, rtol_min=1.0e-12_dp, &
                    rtol_max=1.0e-7_dp, cost=0.6e-6_dp, group='rk', colour='#ff7f0e', &
                    description='Dormand-Prince 5(4), dense output of order 4'), &
      method_info_t(name='dop853', order=8, adaptive=.true., &
                    h_min=1.2e-2_dp, h_max=3.2e-2_dp, rtol_min=1.0e-13_dp, &
                    rtol_max=1.0e-8_dp, cost=1.2e-6_dp, group='rk', colour='#8c564b', &
                    description='Dormand-Prince 8(5,3), dense output of order 7'), &
      method_info_t(name='midpoint', order=2, implicit=.true., symplectic=.true., &
                    symmetric=.true., canonical=.true., compensated=.true., &
                    h_min=2.5e-3_dp, h_max=1.0e-2_dp, cost=1.2e-6_dp, group='gauss', &
                    colour='#9ecae1', description='implicit midpoint rule (Gauss, 1 stage)'), &
      method_info_t(name='gauss4', order=4, implicit=.true., symplectic=.true., &
                    symmetric=.true., canonical=.true., compensated=.true., &
                    h_min=5.0e-3_dp, h_max=2.0e-2_dp, cost=1.6e-6_dp, group='gauss', &
                    colour='#4292c6', description='Gauss-Legendre collocation, 2 stages'), &
      method_info_t(name='gauss6', order=6, implicit=.true., symplectic=.true., &
                    symmetric=.true., canonical=.true., compensated=.true., &
                    h_min=1.0e-2_dp, h_max=3.0e-2_dp, cost=2.0e-6_dp, group='gauss', &
                    colour='#08519c', description='Gauss-Legendre collocation, 3 stages'), &
      method_info_t(name='gauss8', order=8, implicit=.true., symplectic=.true., &
                    symmetric=.true., canonical=.true., compensated=.true., &
                    h_min=1.5e-2_dp, h_max=4.0e-2_dp, cost=2.8e-6_dp, group='gauss', &
                    colour='#08306b', description='Gauss-Legendre collocation, 4 stages'), &
      method_info_t(name='verlet', order=2, implicit=.true., symplectic=.true., &
                    symmetric=.true., hamiltonian=.true., canonical=.true., &
                    compensated=.true., h_min=2.5e-3_dp, h_max=1.0e-2_dp, cost=1.6e-6_dp, &
                    group='verlet', colour='#a1d99b', &
                    description='generalised Stormer-Verlet (leapfrog), implicit in H'), &
      method_info_t(name='yoshida4', order=4, implicit=.true., symplectic=.true., &
                    symmetric=.true., hamiltonian=.true., canonical=.true., &
                    compensated=.true., h_min=5.0e-3_dp, h_max=2.0e-2_dp, cost=4.5e-6_dp, &
                    group='verlet', colour='#41ab5d', &
                    description='triple jump of verlet (Yoshida)'), &
      method_info_t(name='comp6', order=6, implicit=.true., symplectic=.true., &
                    symmetric=.true., hamiltonian=.true., canonical=.true., &
                    compensated=.true., h_min=1.0e-2_dp, h_max=3.0e-2_dp, cost=12.0e-6_dp, &
                    group='verlet', colour='#006d2c', &
                    description='9-stage composition of verlet (Kahan-Li)'), &
      method_info_t(name='comp8', order=8, implicit=.true., symplectic=.true., &
                    symmetric=.true., hamiltonian=.true., canonical=.true., &
                    compensated=.true., h_min=1.5e-2_dp, h_max=3.5e-2_dp, cost=22.0e-6_dp, &
                    group='verlet', colour='#00441b', &
                    description='17-stage composition of verlet (Kahan-Li)'), &
      method_info_t(name='tao2', order=2, symplectic=.true., symmetric=.true., &
                    hamiltonian=.true., canonical=.true., compensated=.true., &
                    omega=.true., h_min=1.0e-3_dp, h_max=4.0e-3_dp, cost=0.35e-6_dp, &
                    group='tao', colour='#bc80bd', &
                    description="Tao's explicit method in extended phase space"), &
      method_info_t(name='tao4', order=4, symplectic=.true., symmetric=.true., &
                    hamiltonian=.true., canonical=.true., compensated=.true., &
                    omega=.true., h_min=1.0e-3_dp, h_max=4.0e-3_dp, cost=1.0e-6_dp, &
                    group='tao', colour='#6a3d9a', &
                    description='triple jump of tao2')]

   !> The plot groups, in the order of the study's panels.
   type(plot_group_t), parameter :: plot_groups(4) = [ &
      plot_group_t('rk', 'explicit Runge-Kutta (fixed steps)'), &
      plot_group_t('gauss', 'Gauss-Legendre (implicit, symplectic)'), &
      plot_group_t('verlet', 'Störmer-Verlet and its compositions'), &
      plot_group_t('tao', 'Tao (explicit, extended phase space)')]

contains

   !> Position of method `name` in `method_table`; 0 if there is none.
   pure integer function method_index(name) result(i)
      character(len=*), intent(in) :: name  !! method name
      do i = 1, n_methods
         if (trim(method_table(i)%name) == name) return
      end do
      i = 0
   end function method_index

   !> The names of the table, space separated, in its order (accepted by --method).
   pure function method_names() result(names)
      character(len=:), allocatable :: names
      integer :: i
      names = trim(method_table(1)%name)
      do i = 2, n_methods
         names = names//' '//trim(method_table(i)%name)
      end do
   end function method_names

   !> The methods that accept models without a Hamiltonian (damped, driven), as
   !> "rk4, dopri5, …, gauss6 or gauss8" for messages.
   pure function field_method_names() result(names)
      character(len=:), allocatable :: names
      integer :: i, last
      last = 0
      do i = 1, n_methods
         if (.not. method_table(i)%hamiltonian) last = i
      end do
      names = ''
      do i = 1, n_methods
         if (method_table(i)%hamiltonian) cycle
         if (len(names) > 0) then
            if (i == last) then
               names = names//' or '
            else
               names = names//', '
            end if
         end if
         names = names//trim(method_table(i)%name)
      end do
   end function field_method_names
end module dpend_method_registry
