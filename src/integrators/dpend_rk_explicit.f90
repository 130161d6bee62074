!> Explicit Runge–Kutta methods on (q, q̇): the classical rk4 (fixed step) and the
!> embedded pairs dopri5 and dop853 of Dormand and Prince with step-size control
!> and dense output, following Hairer's codes DOPRI5 and DOP853 (Hairer, Nørsett,
!> Wanner, Solving Ordinary Differential Equations I, 2nd ed., Springer 1993,
!> Sections II.4–II.6 and the Appendix).
!>
!> The adaptive methods share the error norm of Hairer (II.4.11),
!>   err = sqrt( (1/n) Σ (e_i / sk_i)² ),  sk_i = atol + rtol max(|y_i|, |ŷ_i|),
!> the PI ("Lund-stabilized", Gustafsson 1991; Hairer–Wanner II, IV.2) controller
!>   h_new = h / max(1/facmax, min(1/facmin, err^(1/(q+1) - 0.75 β) / (errold^β safety)))
!> with the step rejected when err > 1, the initial-step heuristic HINIT
!> (Hairer et al. II.4, "Starting step size"), and FSAL reuse of f(y_new).
module dpend_rk_explicit
   use dpend_kinds, only: dp
   use dpend_model, only: model_t, max_state, max_dof
   use dpend_integrator, only: integrator_t, stat_ok, stat_nonfinite, stat_step_too_small, &
                               state_ok, integrator_configure
   use dpend_method_options, only: method_options_t
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   implicit none
   private
   public :: rk4_t, rk_adaptive_t, dopri5_t, dop853_t

   !> The classical fourth-order Runge–Kutta method (Kutta 1901; Hairer, Nørsett,
   !> Wanner, Solving ODEs I, Table II.1.2). Dense output: the base Hermite cubic.
   type, extends(integrator_t) :: rk4_t
   contains
      procedure :: step => rk4_step
      procedure :: name => rk4_name
      procedure :: order => rk4_order
   end type rk4_t

   !> Settings and controller memory shared by the embedded pairs.
   type, abstract, extends(integrator_t) :: rk_adaptive_t
      real(dp) :: rtol = 1.0e-9_dp     !! relative tolerance on each component
      real(dp) :: atol = 1.0e-12_dp    !! absolute tolerance [rad, rad/s]
      real(dp) :: safety = 0.9_dp      !! safety factor of the step-size prediction
      real(dp) :: h_max = huge(1.0_dp) !! largest step allowed [s]
      !> Take exactly the given h, without error control (convergence studies).
      logical :: fixed_step = .false.
      !> accepted error of the previous step (PI memory; reset after `clear_step`)
      real(dp) :: err_old = 1.0e-4_dp
      logical :: dense_ready = .false. !! dense-output coefficients of the last step are set
   contains
      procedure :: adaptive => rk_adaptive_adaptive
      procedure :: configure => rk_adaptive_configure
   end type rk_adaptive_t

   !> Dormand–Prince 5(4), "DOPRI5" (Dormand & Prince 1980; Hairer, Nørsett, Wanner,
   !> Solving ODEs I, Table II.5.2): 7 stages, FSAL, local extrapolation, 4th-order
   !> dense output of Shampine (1986) as in CONTD5. PI controller with β = 0.04,
   !> facmin = 0.2, facmax = 10 (the defaults of the code DOPRI5); all settable.
   type, extends(rk_adaptive_t) :: dopri5_t
      real(dp) :: beta = 0.04_dp       !! PI (Lund) stabilization, 0 for a plain I controller
      real(dp) :: facmin = 0.2_dp      !! smallest h_new/h
      real(dp) :: facmax = 10.0_dp     !! largest h_new/h
      real(dp) :: k(max_state, 7) = 0.0_dp     !! stages of the last accepted step
      real(dp) :: cont(max_state, 5) = 0.0_dp  !! dense-output coefficients (CONTD5)
   contains
      procedure :: step => dopri5_step
      procedure :: name => dopri5_name
      procedure :: order => dopri5_order
      procedure :: interpolate => dopri5_interpolate
   end type dopri5_t

   !> Dormand–Prince 8(5,3), "DOP853" (Prince & Dormand 1981; Hairer, Nørsett,
   !> Wanner, Solving ODEs I, Section II.10 and the code DOP853): 12 stages plus
   !> FSAL, error estimate combining the 5th- and 3rd-order embedded solutions,
   !> 7th-order dense output with 3 extra stages as in CONTD8 (computed lazily, on
   !> the first interpolation in a step). Controller: facmin = 0.333, facmax = 6 as
   !> in the code DOP853, but β = 0.04 (DOP853's default is 0; Hairer allows up to
   !> 0.04): on the pendulum it cuts the rejected steps from ~30 % to ~17 % of the
   !> accepted ones at equal cost and smooths the error-versus-rtol curve.
   type, extends(rk_adaptive_t) :: dop853_t
      real(dp) :: beta = 0.04_dp       !! PI (Lund) stabilization, 0 for a plain I controller
      real(dp) :: facmin = 0.333_dp    !! smallest h_new/h
      real(dp) :: facmax = 6.0_dp      !! largest h_new/h
      real(dp) :: k(max_state, 16) = 0.0_dp  !! stages 1–12, f(y_new) as 13, dense 14–16
      real(dp) :: cont(max_state, 8) = 0.0_dp  !! dense-output coefficients (CONTD8)
   contains
      procedure :: step => dop853_step
      procedure :: name => dop853_name
      procedure :: order => dop853_order
      procedure :: interpolate => dop853_interpolate
   end type dop853_t

   ! ---- DOPRI5 (Hairer et al., Table II.5.2; dense output of Shampine 1986) ----
   real(dp), parameter :: p5c2 = 0.2_dp, p5c3 = 0.3_dp, p5c4 = 0.8_dp, &
                          p5c5 = 8.0_dp/9.0_dp
   real(dp), parameter :: p5a21 = 0.2_dp
   real(dp), parameter :: p5a31 = 3.0_dp/40.0_dp, p5a32 = 9.0_dp/40.0_dp
   real(dp), parameter :: p5a41 = 44.0_dp/45.0_dp, p5a42 = -56.0_dp/15.0_dp, &
                          p5a43 = 32.0_dp/9.0_dp
   real(dp), parameter :: p5a51 = 19372.0_dp/6561.0_dp, p5a52 = -25360.0_dp/2187.0_dp, &
                          p5a53 = 64448.0_dp/6561.0_dp, p5a54 = -212.0_dp/729.0_dp
   real(dp), parameter :: p5a61 = 9017.0_dp/3168.0_dp, p5a62 = -355.0_dp/33.0_dp, &
                          p5a63 = 46732.0_dp/5247.0_dp, p5a64 = 49.0_dp/176.0_dp, &
                          p5a65 = -5103.0_dp/18656.0_dp
   real(dp), parameter :: p5a71 = 35.0_dp/384.0_dp, p5a73 = 500.0_dp/1113.0_dp, &
                          p5a74 = 125.0_dp/192.0_dp, p5a75 = -2187.0_dp/6784.0_dp, &
                          p5a76 = 11.0_dp/84.0_dp
   !> b - b̂ (5th minus 4th order weights)
   real(dp), parameter :: p5e1 = 71.0_dp/57600.0_dp, p5e3 = -71.0_dp/16695.0_dp, &
                          p5e4 = 71.0_dp/1920.0_dp, p5e5 = -17253.0_dp/339200.0_dp, &
                          p5e6 = 22.0_dp/525.0_dp, p5e7 = -1.0_dp/40.0_dp
   real(dp), parameter :: p5d1 = -12715105075.0_dp/11282082432.0_dp, &
                          p5d3 = 87487479700.0_dp/32700410799.0_dp, &
                          p5d4 = -10690763975.0_dp/1880347072.0_dp, &
                          p5d5 = 701980252875.0_dp/199316789632.0_dp, &
                          p5d6 = -1453857185.0_dp/822651844.0_dp, &
                          p5d7 = 69997945.0_dp/29380423.0_dp

   ! ---- DOP853 (coefficients of Hairer's code DOP853, version of 2002) ----
   real(dp), parameter :: c2 = 0.526001519587677318785587544488e-01_dp, &
                          c3 = 0.789002279381515978178381316732e-01_dp, &
                          c4 = 0.118350341907227396726757197510e+00_dp, &
                          c5 = 0.281649658092772603273242802490e+00_dp, &
                          c6 = 0.333333333333333333333333333333e+00_dp, &
                          c7 = 0.25e+00_dp, &
                          c8 = 0.307692307692307692307692307692e+00_dp, &
                          c9 = 0.651282051282051282051282051282e+00_dp, &
                          c10 = 0.6e+00_dp, &
                          c11 = 0.857142857142857142857142857142e+00_dp, &
                          c14 = 0.1e+00_dp, c15 = 0.2e+00_dp, &
                          c16 = 0.777777777777777777777777777778e+00_dp
   real(dp), parameter :: b1 = 5.42937341165687622380535766363e-2_dp, &
                          b6 = 4.45031289275240888144113950566e0_dp, &
                          b7 = 1.89151789931450038304281599044e0_dp, &
                          b8 = -5.8012039600105847814672114227e0_dp, &
                          b9 = 3.1116436695781989440891606237e-1_dp, &
                          b10 = -1.52160949662516078556178806805e-1_dp, &
                          b11 = 2.01365400804030348374776537501e-1_dp, &
                          b12 = 4.47106157277725905176885569043e-2_dp
   real(dp), parameter :: bhh1 = 0.244094488188976377952755905512e+00_dp, &
                          bhh2 = 0.733846688281611857341361741547e+00_dp, &
                          bhh3 = 0.220588235294117647058823529412e-01_dp
   real(dp), parameter :: er1 = 0.1312004499419488073250102996e-01_dp, &
                          er6 = -0.1225156446376204440720569753e+01_dp, &
                          er7 = -0.4957589496572501915214079952e+00_dp, &
                          er8 = 0.1664377182454986536961530415e+01_dp, &
                          er9 = -0.3503288487499736816886487290e+00_dp, &
                          er10 = 0.3341791187130174790297318841e+00_dp, &
                          er11 = 0.8192320648511571246570742613e-01_dp, &
                          er12 = -0.2235530786388629525884427845e-01_dp
   real(dp), parameter :: a21 = 5.26001519587677318785587544488e-2_dp, &
                          a31 = 1.97250569845378994544595329183e-2_dp, &
                          a32 = 5.91751709536136983633785987549e-2_dp, &
                          a41 = 2.95875854768068491816892993775e-2_dp, &
                          a43 = 8.87627564304205475450678981324e-2_dp, &
                          a51 = 2.41365134159266685502369798665e-1_dp, &
                          a53 = -8.84549479328286085344864962717e-1_dp, &
                          a54 = 9.24834003261792003115737966543e-1_dp, &
                          a61 = 3.7037037037037037037037037037e-2_dp, &
                          a64 = 1.70828608729473871279604482173e-1_dp, &
                          a65 = 1.25467687566822425016691814123e-1_dp, &
                          a71 = 3.7109375e-2_dp, &
                          a74 = 1.70252211019544039314978060272e-1_dp, &
                          a75 = 6.02165389804559606850219397283e-2_dp, &
                          a76 = -1.7578125e-2_dp
   real(dp), parameter :: a81 = 3.70920001185047927108779319836e-2_dp, &
                          a84 = 1.70383925712239993810214054705e-1_dp, &
                          a85 = 1.07262030446373284651809199168e-1_dp, &
                          a86 = -1.53194377486244017527936158236e-2_dp, &
                          a87 = 8.27378916381402288758473766002e-3_dp, &
                          a91 = 6.24110958716075717114429577812e-1_dp, &
                          a94 = -3.36089262944694129406857109825e0_dp, &
                          a95 = -8.68219346841726006818189891453e-1_dp, &
                          a96 = 2.75920996994467083049415600797e1_dp, &
                          a97 = 2.01540675504778934086186788979e1_dp, &
                          a98 = -4.34898841810699588477366255144e1_dp, &
                          a101 = 4.77662536438264365890433908527e-1_dp, &
                          a104 = -2.48811461997166764192642586468e0_dp, &
                          a105 = -5.90290826836842996371446475743e-1_dp, &
                          a106 = 2.12300514481811942347288949897e1_dp, &
                          a107 = 1.52792336328824235832596922938e1_dp, &
                          a108 = -3.32882109689848629194453265587e1_dp, &
                          a109 = -2.03312017085086261358222928593e-2_dp
   real(dp), parameter :: a111 = -9.3714243008598732571704021658e-1_dp, &
                          a114 = 5.18637242884406370830023853209e0_dp, &
                          a115 = 1.09143734899672957818500254654e0_dp, &
                          a116 = -8.14978701074692612513997267357e0_dp, &
                          a117 = -1.85200656599969598641566180701e1_dp, &
                          a118 = 2.27394870993505042818970056734e1_dp, &
                          a119 = 2.49360555267965238987089396762e0_dp, &
                          a1110 = -3.0467644718982195003823669022e0_dp, &
                          a121 = 2.27331014751653820792359768449e0_dp, &
                          a124 = -1.05344954667372501984066689879e1_dp, &
                          a125 = -2.00087205822486249909675718444e0_dp, &
                          a126 = -1.79589318631187989172765950534e1_dp, &
                          a127 = 2.79488845294199600508499808837e1_dp, &
                          a128 = -2.85899827713502369474065508674e0_dp, &
                          a129 = -8.87285693353062954433549289258e0_dp, &
                          a1210 = 1.23605671757943030647266201528e1_dp, &
                          a1211 = 6.43392746015763530355970484046e-1_dp
   real(dp), parameter :: a141 = 5.61675022830479523392909219681e-2_dp, &
                          a147 = 2.53500210216624811088794765333e-1_dp, &
                          a148 = -2.46239037470802489917441475441e-1_dp, &
                          a149 = -1.24191423263816360469010140626e-1_dp, &
                          a1410 = 1.5329179827876569731206322685e-1_dp, &
                          a1411 = 8.20105229563468988491666602057e-3_dp, &
                          a1412 = 7.56789766054569976138603589584e-3_dp, &
                          a1413 = -8.298e-3_dp
   real(dp), parameter :: a151 = 3.18346481635021405060768473261e-2_dp, &
                          a156 = 2.83009096723667755288322961402e-2_dp, &
                          a157 = 5.35419883074385676223797384372e-2_dp, &
                          a158 = -5.49237485713909884646569340306e-2_dp, &
                          a1511 = -1.08347328697249322858509316994e-4_dp, &
                          a1512 = 3.82571090835658412954920192323e-4_dp, &
                          a1513 = -3.40465008687404560802977114492e-4_dp, &
                          a1514 = 1.41312443674632500278074618366e-1_dp, &
                          a161 = -4.28896301583791923408573538692e-1_dp, &
                          a166 = -4.69762141536116384314449447206e0_dp, &
                          a167 = 7.68342119606259904184240953878e0_dp, &
                          a168 = 4.06898981839711007970213554331e0_dp, &
                          a169 = 3.56727187455281109270669543021e-1_dp, &
                          a1613 = -1.39902416515901462129418009734e-3_dp, &
                          a1614 = 2.9475147891527723389556272149e0_dp, &
                          a1615 = -9.15095847217987001081870187138e0_dp
   real(dp), parameter :: d41 = -0.84289382761090128651353491142e+01_dp, &
                          d46 = 0.56671495351937776962531783590e+00_dp, &
                          d47 = -0.30689499459498916912797304727e+01_dp, &
                          d48 = 0.23846676565120698287728149680e+01_dp, &
                          d49 = 0.21170345824450282767155149946e+01_dp, &
                          d410 = -0.87139158377797299206789907490e+00_dp, &
                          d411 = 0.22404374302607882758541771650e+01_dp, &
                          d412 = 0.63157877876946881815570249290e+00_dp, &
                          d413 = -0.88990336451333310820698117400e-01_dp, &
                          d414 = 0.18148505520854727256656404962e+02_dp, &
                          d415 = -0.91946323924783554000451984436e+01_dp, &
                          d416 = -0.44360363875948939664310572000e+01_dp
   real(dp), parameter :: d51 = 0.10427508642579134603413151009e+02_dp, &
                          d56 = 0.24228349177525818288430175319e+03_dp, &
                          d57 = 0.16520045171727028198505394887e+03_dp, &
                          d58 = -0.37454675472269020279518312152e+03_dp, &
                          d59 = -0.22113666853125306036270938578e+02_dp, &
                          d510 = 0.77334326684722638389603898808e+01_dp, &
                          d511 = -0.30674084731089398182061213626e+02_dp, &
                          d512 = -0.93321305264302278729567221706e+01_dp, &
                          d513 = 0.15697238121770843886131091075e+02_dp, &
                          d514 = -0.31139403219565177677282850411e+02_dp, &
                          d515 = -0.93529243588444783865713862664e+01_dp, &
                          d516 = 0.35816841486394083752465898540e+02_dp
   real(dp), parameter :: d61 = 0.19985053242002433820987653617e+02_dp, &
                          d66 = -0.38703730874935176555105901742e+03_dp, &
                          d67 = -0.18917813819516756882830838328e+03_dp, &
                          d68 = 0.52780815920542364900561016686e+03_dp, &
                          d69 = -0.11573902539959630126141871134e+02_dp, &
                          d610 = 0.68812326946963000169666922661e+01_dp, &
                          d611 = -0.10006050966910838403183860980e+01_dp, &
                          d612 = 0.77771377980534432092869265740e+00_dp, &
                          d613 = -0.27782057523535084065932004339e+01_dp, &
                          d614 = -0.60196695231264120758267380846e+02_dp, &
                          d615 = 0.84320405506677161018159903784e+02_dp, &
                          d616 = 0.11992291136182789328035130030e+02_dp
   real(dp), parameter :: d71 = -0.25693933462703749003312586129e+02_dp, &
                          d76 = -0.15418974869023643374053993627e+03_dp, &
                          d77 = -0.23152937917604549567536039109e+03_dp, &
                          d78 = 0.35763911791061412378285349910e+03_dp, &
                          d79 = 0.93405324183624310003907691704e+02_dp, &
                          d710 = -0.37458323136451633156875139351e+02_dp, &
                          d711 = 0.10409964950896230045147246184e+03_dp, &
                          d712 = 0.29840293426660503123344363579e+02_dp, &
                          d713 = -0.43533456590011143754432175058e+02_dp, &
                          d714 = 0.96324553959188282948394950600e+02_dp, &
                          d715 = -0.39177261675615439165231486172e+02_dp, &
                          d716 = -0.14972683625798562581422125276e+03_dp


contains

   ! ======================================================================== rk4

   !> One rk4 step. States of four components (two degrees of freedom) take the
   !> same statements compiled with fixed sizes (unrolled, in registers); others
   !> the generic ones on stack workspaces.
   subroutine rk4_step(self, model, t, y, h, stat)
      class(rk4_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(inout) :: t         !! time [s]
      real(dp), intent(inout) :: y(:)      !! state (q, q̇)
      real(dp), intent(inout) :: h         !! step [s]
      integer, intent(out) :: stat         !! status
      if (size(y) == 4) then
         call rk4_step_4(self, model, t, y, h, stat)
      else
         call rk4_step_n(self, model, t, y, h, stat)
      end if
   end subroutine rk4_step

   subroutine rk4_step_4(self, model, t, y, h, stat)
      class(rk4_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(inout) :: t         !! time [s]
      real(dp), intent(inout) :: y(4)      !! state (q, q̇)
      real(dp), intent(inout) :: h         !! step [s]
      integer, intent(out) :: stat         !! status
      integer, parameter :: n = 4, m = 2
      real(dp) :: k1(n), k2(n), k3(n), k4(n), ynew(n), ys(n), d(m), cache(2*max_state)
      logical :: ok
      ! the whole cache is passed (assumed size): no query of its size per step
      associate (c => cache)
         include 'dpend_rk4_body.inc'
      end associate
      t = t + h
      self%n_steps = self%n_steps + 1
      stat = stat_ok
   end subroutine rk4_step_4

   subroutine rk4_step_n(self, model, t, y, h, stat)
      class(rk4_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model  !! the system
      real(dp), intent(inout) :: t         !! time [s]
      real(dp), intent(inout) :: y(:)      !! state (q, q̇)
      real(dp), intent(inout) :: h         !! step [s]
      integer, intent(out) :: stat         !! status
      real(dp) :: k1_(max_state), k2_(max_state), k3_(max_state), k4_(max_state)
      real(dp) :: ynew_(max_state), ys_(max_state), d_(max_dof), cache(2*max_state)
      integer :: n, m
      logical :: ok
      n = size(y); m = n/2
      associate (k1 => k1_(:n), k2 => k2_(:n), k3 => k3_(:n), k4 => k4_(:n), &
                 ynew => ynew_(:n), ys => ys_(:n), d => d_(:m), &
                 c => cache)
         include 'dpend_rk4_body.inc'
      end associate
      t = t + h
      self%n_steps = self%n_steps + 1
      stat = stat_ok
   end subroutine rk4_step_n

   pure function rk4_name(self) result(name)
      class(rk4_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = 'rk4'
   end function rk4_name

   pure integer function rk4_order(self)
      class(rk4_t), intent(in) :: self
      rk4_order = 4
   end function rk4_order

   ! ============================================================ shared control

   !> True unless `fixed_step` is set.
   pure logical function rk_adaptive_adaptive(self)
      class(rk_adaptive_t), intent(in) :: self  !! the method
      rk_adaptive_adaptive = .not. self%fixed_step
   end function rk_adaptive_adaptive

   !> Options of the embedded pairs: rtol, atol (0 keeps the default), fixed_step,
   !> and those of every method.
   subroutine rk_adaptive_configure(self, options)
      class(rk_adaptive_t), intent(inout) :: self     !! the method
      type(method_options_t), intent(in) :: options   !! its options
      call integrator_configure(self, options)
      if (options%rtol > 0.0_dp) self%rtol = options%rtol
      if (options%atol > 0.0_dp) self%atol = options%atol
      self%fixed_step = options%fixed_step
   end subroutine rk_adaptive_configure

   !> Stage 1: f(y), reused from the end of the last step when y is that state (FSAL).
   !> Without a recorded step (new trajectory) the controller memory is reset.
   subroutine first_stage(self, model, t, y, k1)
      class(rk_adaptive_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model          !! the system
      real(dp), intent(in) :: t                    !! time [s]
      real(dp), intent(in) :: y(:)                 !! state (q, q̇)
      real(dp), intent(out) :: k1(:)               !! f(t, y)
      integer :: n
      n = size(y)
      if (.not. self%stepped) self%err_old = 1.0e-4_dp
      if (self%stepped .and. self%known_f_new .and. self%n_rec == n) then
         if (all(y == self%y_new(:n)) .and. (model%autonomous() .or. self%t_new == t)) then
            k1 = self%f_new(:n)
            return
         end if
      end if
      call model%field(t, y, k1)
      self%n_rhs = self%n_rhs + 1
   end subroutine first_stage

   !> Weighted sum of squares Σ (e_i/sk_i)², sk_i = atol + rtol max(|y_i|, |ŷ_i|).
   pure real(dp) function weighted_ss(rtol, atol, y, ynew, e)
      real(dp), intent(in) :: rtol, atol          !! tolerances
      real(dp), intent(in) :: y(:), ynew(:), e(:) !! states and error vector
      real(dp) :: y4(4), yn4(4), e4(4)
      integer :: i, n
      ! in blocks of four components, zero-padded (e = 0 adds exactly 0): the sum is
      ! rounded as the fixed-size code of the double pendulum always rounded it,
      ! whatever n (a run-time-length sum is contracted and vectorized differently)
      n = size(y)
      weighted_ss = 0.0_dp
      do i = 1, n, 4
         y4 = 0.0_dp; yn4 = 0.0_dp; e4 = 0.0_dp
         y4(1:min(4, n - i + 1)) = y(i:min(n, i + 3))
         yn4(1:min(4, n - i + 1)) = ynew(i:min(n, i + 3))
         e4(1:min(4, n - i + 1)) = e(i:min(n, i + 3))
         weighted_ss = weighted_ss + sum((e4/(atol + rtol*max(abs(y4), abs(yn4))))**2)
      end do
   end function weighted_ss

   !> Initial step size guess, HINIT of DOPRI5/DOP853 (Hairer et al. I, II.4):
   !> h such that h^order max(‖f‖, ‖f'‖) = 0.01, at most 100 times the Euler guess.
   !> Costs one evaluation of f (counted).
   function hinit(self, model, t, y, f0, order) result(h)
      class(rk_adaptive_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model          !! the system
      real(dp), intent(in) :: t                    !! time [s]
      real(dp), intent(in) :: y(:)                 !! state (q, q̇)
      real(dp), intent(in) :: f0(:)                !! f(t, y)
      integer, intent(in) :: order                 !! order of the method
      real(dp) :: h
      real(dp) :: sk_(max_state), dnf, dny, der2, der12, h1, f1_(max_state), ys_(max_state)
      integer :: n
      n = size(y)
      associate (sk => sk_(:n), f1 => f1_(:n), ys => ys_(:n))
      sk = self%atol + self%rtol*abs(y)
      dnf = sum((f0/sk)**2)
      dny = sum((y/sk)**2)
      if (dnf <= 1.0e-10_dp .or. dny <= 1.0e-10_dp) then
         h = 1.0e-6_dp
      else
         h = 0.01_dp*sqrt(dny/dnf)
      end if
      h = min(h, self%h_max)
      ys = y + h*f0
      call model%field(t + h, ys, f1)
      self%n_rhs = self%n_rhs + 1
      der2 = sqrt(sum(((f1 - f0)/sk)**2))/h
      der12 = max(der2, sqrt(dnf))
      if (der12 <= 1.0e-15_dp) then
         h1 = max(1.0e-6_dp, h*1.0e-3_dp)
      else
         h1 = (0.01_dp/der12)**(1.0_dp/order)
      end if
      h = min(100.0_dp*h, h1, self%h_max)
      end associate
   end function hinit

   !> The decision after an error estimate, shared by dopri5 and dop853 (Hairer's
   !> codes): a non-finite step (`bad`) is retried with h·facmin; err ≤ 1 accepts
   !> the step and proposes hnew by the PI controller, never larger than h right
   !> after a rejection; err > 1 rejects it and shrinks h without PI memory.
   subroutine control_step(self, err, bad, expo, beta, facmin, facmax, h, hnew, rejected, &
                           accepted)
      class(rk_adaptive_t), intent(inout) :: self  !! the method (err_old, n_rejected)
      real(dp), intent(in) :: err                  !! weighted error norm (if not bad)
      logical, intent(in) :: bad                   !! the step overflowed
      real(dp), intent(in) :: expo                 !! 1/(q+1) - 0.75 β
      real(dp), intent(in) :: beta                 !! PI stabilization β
      real(dp), intent(in) :: facmin, facmax       !! bounds of h_new/h
      real(dp), intent(inout) :: h                 !! step tried; retry size if rejected [s]
      real(dp), intent(out) :: hnew                !! proposal for the next step (accepted) [s]
      logical, intent(inout) :: rejected           !! a rejection happened in this step
      logical, intent(out) :: accepted             !! the step is accepted
      accepted = .false.
      hnew = h
      if (bad) then
         ! overflow inside the step: shrink hard and retry
         self%n_rejected = self%n_rejected + 1
         rejected = .true.
         h = facmin*h
         return
      end if
      if (err <= 1.0_dp) then
         accepted = .true.
         hnew = h*pi_factor(err, self%err_old, expo, beta, self%safety, &
                            facmin, facmax)
         self%err_old = max(err, 1.0e-4_dp)
         if (rejected) hnew = sign(min(abs(hnew), abs(h)), h)
         return
      end if
      ! rejected: no growth, no PI memory (Hairer's DOPRI5)
      self%n_rejected = self%n_rejected + 1
      rejected = .true.
      h = h/min(1.0_dp/facmin, err**expo/self%safety)
   end subroutine control_step

   !> Step-size factor h_new/h of the PI controller (see the module header).
   pure real(dp) function pi_factor(err, err_old, expo, beta, safety, facmin, facmax)
      real(dp), intent(in) :: err, err_old    !! current and previous accepted errors
      real(dp), intent(in) :: expo, beta      !! 1/(q+1) - 0.75 β (or 1/8 - 0.2 β), β
      real(dp), intent(in) :: safety          !! safety factor
      real(dp), intent(in) :: facmin, facmax  !! bounds on h_new/h
      real(dp) :: fac
      fac = err**expo/err_old**beta
      pi_factor = 1.0_dp/max(1.0_dp/facmax, min(1.0_dp/facmin, fac/safety))
   end function pi_factor

   !> Common tail of an accepted adaptive step: record, update, count.
   subroutine accept_step(self, t, y, h, ynew, k1, fnew)
      class(rk_adaptive_t), intent(inout) :: self  !! the method
      real(dp), intent(inout) :: t                 !! time [s]
      real(dp), intent(inout) :: y(:)              !! state (q, q̇)
      real(dp), intent(in) :: h                    !! accepted step [s]
      real(dp), intent(in) :: ynew(:)              !! new state
      real(dp), intent(in) :: k1(:)                !! f(y)
      real(dp), intent(in), optional :: fnew(:)    !! f(ynew), if computed
      call self%record_step(size(y), t, y, t + h, ynew, f0=k1, f1=fnew)
      y = ynew
      t = t + h
      self%n_steps = self%n_steps + 1
      self%dense_ready = .false.
   end subroutine accept_step

   !> Step size below roundoff relative to t (or zero)?
   pure logical function too_small(t, h)
      real(dp), intent(in) :: t, h  !! time and step [s]
      too_small = abs(h) < 16.0_dp*epsilon(1.0_dp)*abs(t) .or. abs(h) < tiny(1.0_dp)
   end function too_small

   ! ===================================================================== dopri5

   !> One accepted DOPRI5 step (see `integrator_t%step` for the semantics).
   subroutine dopri5_step(self, model, t, y, h, stat)
      class(dopri5_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model     !! the system
      real(dp), intent(inout) :: t            !! time [s]
      real(dp), intent(inout) :: y(:)         !! state (q, q̇)
      real(dp), intent(inout) :: h            !! step; on return the next proposal [s]
      integer, intent(out) :: stat            !! status
      if (size(y) == 4) then
         call dopri5_step_4(self, model, t, y, h, stat)
      else
         call dopri5_step_n(self, model, t, y, h, stat)
      end if
   end subroutine dopri5_step

   subroutine dopri5_step_4(self, model, t, y, h, stat)
      class(dopri5_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model     !! the system
      real(dp), intent(inout) :: t            !! time [s]
      real(dp), intent(inout) :: y(4)         !! state (q, q̇)
      real(dp), intent(inout) :: h            !! step; on return the next proposal [s]
      integer, intent(out) :: stat            !! status
      integer, parameter :: n = 4
      real(dp) :: k_(n, 7), ynew_(n), e_(n), ys_(n)
      real(dp) :: err, hnew
      logical :: rejected, bad, accepted
      real(dp) :: expo
      include 'dpend_dopri5_body.inc'
   end subroutine dopri5_step_4

   subroutine dopri5_step_n(self, model, t, y, h, stat)
      class(dopri5_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model     !! the system
      real(dp), intent(inout) :: t            !! time [s]
      real(dp), intent(inout) :: y(:)         !! state (q, q̇)
      real(dp), intent(inout) :: h            !! step; on return the next proposal [s]
      integer, intent(out) :: stat            !! status
      real(dp) :: k_(max_state, 7), ynew_(max_state), e_(max_state), ys_(max_state)
      real(dp) :: err, hnew
      integer :: n
      logical :: rejected, bad, accepted
      real(dp) :: expo
      n = size(y)
      include 'dpend_dopri5_body.inc'
   end subroutine dopri5_step_n

   !> 4th-order continuous extension of DOPRI5 (Shampine 1986; CONTD5 in DOPRI5):
   !> y(t_old + θh) = r1 + θ(r2 + (1-θ)(r3 + θ(r4 + (1-θ) r5))).
   subroutine dopri5_interpolate(self, model, t_eval, y_eval)
      class(dopri5_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model     !! the system
      real(dp), intent(in) :: t_eval          !! time [s]
      real(dp), intent(inout) :: y_eval(:)    !! state (q, q̇) at t_eval
      real(dp) :: h, th, th1
      integer :: n
      if (.not. self%stepped) return
      n = self%n_rec
      h = self%t_new - self%t_old
      if (t_eval == self%t_new .or. h == 0.0_dp) then
         y_eval = self%y_new(:n)
         return
      end if
      associate (k => self%k(:n, :), r => self%cont(:n, :))
         if (.not. self%dense_ready) then
            r(:, 1) = self%y_old(:n)
            r(:, 2) = self%y_new(:n) - self%y_old(:n)
            r(:, 3) = h*k(:, 1) - r(:, 2)
            r(:, 4) = r(:, 2) - h*k(:, 7) - r(:, 3)
            r(:, 5) = h*(p5d1*k(:, 1) + p5d3*k(:, 3) + p5d4*k(:, 4) + p5d5*k(:, 5) &
                         + p5d6*k(:, 6) + p5d7*k(:, 7))
            self%dense_ready = .true.
         end if
         th = (t_eval - self%t_old)/h
         th1 = 1.0_dp - th
         y_eval = r(:, 1) + th*(r(:, 2) + th1*(r(:, 3) + th*(r(:, 4) + th1*r(:, 5))))
      end associate
   end subroutine dopri5_interpolate

   pure function dopri5_name(self) result(name)
      class(dopri5_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = 'dopri5'
   end function dopri5_name

   pure integer function dopri5_order(self)
      class(dopri5_t), intent(in) :: self
      dopri5_order = 5
   end function dopri5_order

   ! ===================================================================== dop853

   !> One accepted DOP853 step (see `integrator_t%step` for the semantics).
   subroutine dop853_step(self, model, t, y, h, stat)
      class(dop853_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model     !! the system
      real(dp), intent(inout) :: t            !! time [s]
      real(dp), intent(inout) :: y(:)         !! state (q, q̇)
      real(dp), intent(inout) :: h            !! step; on return the next proposal [s]
      integer, intent(out) :: stat            !! status
      if (size(y) == 4) then
         call dop853_step_4(self, model, t, y, h, stat)
      else
         call dop853_step_n(self, model, t, y, h, stat)
      end if
   end subroutine dop853_step

   subroutine dop853_step_4(self, model, t, y, h, stat)
      class(dop853_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model     !! the system
      real(dp), intent(inout) :: t            !! time [s]
      real(dp), intent(inout) :: y(4)         !! state (q, q̇)
      real(dp), intent(inout) :: h            !! step; on return the next proposal [s]
      integer, intent(out) :: stat            !! status
      integer, parameter :: n = 4
      real(dp) :: k_(n, 13), ynew_(n), inc_(n), e5_(n)
      real(dp) :: e3_(n), ys_(n), err, err5, err3, deno, hnew
      logical :: rejected, bad, accepted
      real(dp) :: expo
      include 'dpend_dop853_body.inc'
   end subroutine dop853_step_4

   subroutine dop853_step_n(self, model, t, y, h, stat)
      class(dop853_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model     !! the system
      real(dp), intent(inout) :: t            !! time [s]
      real(dp), intent(inout) :: y(:)         !! state (q, q̇)
      real(dp), intent(inout) :: h            !! step; on return the next proposal [s]
      integer, intent(out) :: stat            !! status
      real(dp) :: k_(max_state, 13), ynew_(max_state), inc_(max_state), e5_(max_state)
      real(dp) :: e3_(max_state), ys_(max_state), err, err5, err3, deno, hnew
      integer :: n
      logical :: rejected, bad, accepted
      real(dp) :: expo
      n = size(y)
      include 'dpend_dop853_body.inc'
   end subroutine dop853_step_n

   !> 7th-order continuous extension of DOP853 (Hairer et al. I, II.6 and CONTD8):
   !> three extra stages (14–16) are evaluated on the first call within a step.
   subroutine dop853_interpolate(self, model, t_eval, y_eval)
      class(dop853_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model     !! the system
      real(dp), intent(in) :: t_eval          !! time [s]
      real(dp), intent(inout) :: y_eval(:)    !! state (q, q̇) at t_eval
      real(dp) :: h, s, s1, conpar_(max_state)
      integer :: n
      if (.not. self%stepped) return
      n = self%n_rec
      h = self%t_new - self%t_old
      if (t_eval == self%t_new .or. h == 0.0_dp) then
         y_eval = self%y_new(:n)
         return
      end if
      if (.not. self%dense_ready) call dop853_dense(self, model, h)
      associate (r => self%cont(:n, :), conpar => conpar_(:n))
         s = (t_eval - self%t_old)/h
         s1 = 1.0_dp - s
         conpar = r(:, 5) + s*(r(:, 6) + s1*(r(:, 7) + s*r(:, 8)))
         y_eval = r(:, 1) + s*(r(:, 2) + s1*(r(:, 3) + s*(r(:, 4) + s1*conpar)))
      end associate
   end subroutine dop853_interpolate

   !> Dense-output coefficients of the last DOP853 step (3 extra evaluations).
   subroutine dop853_dense(self, model, h)
      class(dop853_t), intent(inout) :: self  !! the method
      class(model_t), intent(in) :: model     !! the system
      real(dp), intent(in) :: h               !! the step [s]
      real(dp) :: ys_(max_state), y_(max_state)
      integer :: n
      n = self%n_rec
      y_(:n) = self%y_old(:n)
      associate (k => self%k(:n, :), r => self%cont(:n, :), y => y_(:n), ys => ys_(:n))
         r(:, 1) = y
         r(:, 2) = self%y_new(:n) - y
         r(:, 3) = h*k(:, 1) - r(:, 2)
         r(:, 4) = r(:, 2) - h*k(:, 13) - r(:, 3)
         ys = y + h*(a141*k(:, 1) + a147*k(:, 7) + a148*k(:, 8) &
                                          + a149*k(:, 9) + a1410*k(:, 10) + a1411*k(:, 11) &
                                          + a1412*k(:, 12) + a1413*k(:, 13))
         call model%field(self%t_old + c14*h, ys, k(:, 14))
         ys = y + h*(a151*k(:, 1) + a156*k(:, 6) + a157*k(:, 7) &
                                          + a158*k(:, 8) + a1511*k(:, 11) + a1512*k(:, 12) &
                                          + a1513*k(:, 13) + a1514*k(:, 14))
         call model%field(self%t_old + c15*h, ys, k(:, 15))
         ys = y + h*(a161*k(:, 1) + a166*k(:, 6) + a167*k(:, 7) &
                                          + a168*k(:, 8) + a169*k(:, 9) + a1613*k(:, 13) &
                                          + a1614*k(:, 14) + a1615*k(:, 15))
         call model%field(self%t_old + c16*h, ys, k(:, 16))
         self%n_rhs = self%n_rhs + 3
         r(:, 5) = h*(d41*k(:, 1) + d46*k(:, 6) + d47*k(:, 7) + d48*k(:, 8) + d49*k(:, 9) &
                      + d410*k(:, 10) + d411*k(:, 11) + d412*k(:, 12) + d413*k(:, 13) &
                      + d414*k(:, 14) + d415*k(:, 15) + d416*k(:, 16))
         r(:, 6) = h*(d51*k(:, 1) + d56*k(:, 6) + d57*k(:, 7) + d58*k(:, 8) + d59*k(:, 9) &
                      + d510*k(:, 10) + d511*k(:, 11) + d512*k(:, 12) + d513*k(:, 13) &
                      + d514*k(:, 14) + d515*k(:, 15) + d516*k(:, 16))
         r(:, 7) = h*(d61*k(:, 1) + d66*k(:, 6) + d67*k(:, 7) + d68*k(:, 8) + d69*k(:, 9) &
                      + d610*k(:, 10) + d611*k(:, 11) + d612*k(:, 12) + d613*k(:, 13) &
                      + d614*k(:, 14) + d615*k(:, 15) + d616*k(:, 16))
         r(:, 8) = h*(d71*k(:, 1) + d76*k(:, 6) + d77*k(:, 7) + d78*k(:, 8) + d79*k(:, 9) &
                      + d710*k(:, 10) + d711*k(:, 11) + d712*k(:, 12) + d713*k(:, 13) &
                      + d714*k(:, 14) + d715*k(:, 15) + d716*k(:, 16))
      end associate
      self%dense_ready = .true.
   end subroutine dop853_dense

   pure function dop853_name(self) result(name)
      class(dop853_t), intent(in) :: self
      character(len=:), allocatable :: name
      name = 'dop853'
   end function dop853_name

   pure integer function dop853_order(self)
      class(dop853_t), intent(in) :: self
      dop853_order = 8
   end function dop853_order
end module dpend_rk_explicit
