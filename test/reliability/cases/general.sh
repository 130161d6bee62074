# Common bad input on every command: bad numbers (nan, inf, negative, zero, junk
# like 1e or 0x10, an option as the value, a missing value), unknown commands and
# options, and --help of every command. The general
# promise: refused input ends with one line naming the field, exit 2, nothing
# created or changed; --help succeeds. Runs are tiny in case a value is accepted.

# Comparable-looking sweeps of 64 points for sweep-compare (cause 8): a velocity
# grid and a list of 64 initial conditions, both like sweep.h5 (8x8, t_end 1).
(
  cd "$FIXTURES" &&
  "$DPEND" sweep --n 8 --t-end 1 --quiet --axis1 w1 --axis2 w2 --min1 -1 --max1 1 \
    --min2 -1 --max2 1 --output sweep_w.h5 &&
  for i in $(seq 0 63); do echo "0.$i -1.$i 0 0"; done > list64.txt &&
  "$DPEND" sweep --ic-file list64.txt --t-end 1 --quiet --output sweep_list64.h5 &&
  "$DPEND" sweep --n1 64 --n2 1 --t-end 1 --quiet --output sweep_64x1.h5
) > /dev/null 2>&1 || echo "general.sh: could not make the sweep-compare fixtures" >&2

SIM=(simulate --t-end 0.1 --output g.h5)
LYA=(lyapunov --t-end 1 --output g.h5)
DIV=(divergence --t-end 1 --pairs 2 --lyapunov-t 0 --output g.h5)
POI=(poincare --ics 2 --t-end 2 --points 5 --output g.h5)
SWP=(sweep --n 4 --t-end 1 --quiet --output g.h5)
STU=(study --quick --methods rk4 --cases small --no-figures --threads 1 --output g.h5)

# bad numbers, the same for a real option of every command
num_rows() {  # num_rows KEY OPTION FIELD ARGS...
  local k=$1 opt=$2 field=$3; shift 3
  refuse gen-$k-nan       "$field" -- "$@" "$opt" nan
  refuse gen-$k-inf       "$field" -- "$@" "$opt" inf
  refuse gen-$k-neginf    "$field" -- "$@" "$opt" -inf
  refuse gen-$k-negative  "$field" -- "$@" "$opt" -1
  # (an end time of 0 is not documented as refused; every other zero here is)
  [[ $k == *tend ]] || refuse gen-$k-zero "$field" -- "$@" "$opt" 0
  refuse gen-$k-1e        "$field" -- "$@" "$opt" 1e
  refuse gen-$k-hex       "$field" -- "$@" "$opt" 0x10
  refuse gen-$k-junk      "$field" -- "$@" "$opt" 1.0abc
  refuse gen-$k-empty     "$field" -- "$@" "$opt" ''
  refuse gen-$k-option    "$field" -- "$@" "$opt" --force
  refuse gen-$k-missing   "$field" -- "$@" "$opt"
}
num_rows sim-dt      --dt        dt        "${SIM[@]}"
num_rows sim-tend    --t-end     t_end     "${SIM[@]}"
num_rows lya-tau     --tau       tau       "${LYA[@]}"
num_rows div-delta0  --delta0    delta0    "${DIV[@]}"
num_rows poi-tend    --t-end     t_end     "${POI[@]}"
num_rows swp-dt      --dt        dt        "${SWP[@]}"

# integer options: zero, negative, fractional, junk, too large for an integer
int_rows() {  # int_rows KEY OPTION FIELD ARGS...
  local k=$1 opt=$2 field=$3; shift 3
  refuse gen-$k-zero      "$field" -- "$@" "$opt" 0
  refuse gen-$k-negative  "$field" -- "$@" "$opt" -3
  refuse gen-$k-fraction  "$field" -- "$@" "$opt" 1.5
  refuse gen-$k-nan       "$field" -- "$@" "$opt" nan
  refuse gen-$k-huge      "$field" -- "$@" "$opt" 99999999999999999999
  refuse gen-$k-missing   "$field" -- "$@" "$opt"
}
int_rows sim-save    --save-every save_every "${SIM[@]}"
int_rows lya-vectors --vectors   vectors   "${LYA[@]}"
int_rows div-pairs   --pairs     pairs     "${DIV[@]}"
int_rows poi-ics     --ics       ics       "${POI[@]}"
int_rows swp-n       --n         n         "${SWP[@]}"
int_rows stu-threads --threads   threads   "${STU[@]}"

# one bad value of each kind on other options
refuse gen-sim-q1-nan        q1        -- "${SIM[@]}" --q1 nan
refuse gen-sim-w2-inf        w2        -- "${SIM[@]}" --w2 inf
refuse gen-sim-m1-zero       m1        -- "${SIM[@]}" --m1 0
refuse gen-sim-l2-negative   l2        -- "${SIM[@]}" --l2 -1
refuse gen-sim-g-junk        g         -- "${SIM[@]}" --g 9.8x
refuse gen-sim-method        method    -- "${SIM[@]}" --method bogus
refuse gen-sim-method-empty  method    -- "${SIM[@]}" --method ''
refuse gen-sim-rtol-nan      rtol      -- "${SIM[@]}" --method dopri5 --rtol nan
refuse gen-sim-atol-neg      atol      -- "${SIM[@]}" --method dopri5 --atol -1e-9
refuse gen-sim-omega-zero    omega     -- "${SIM[@]}" --method tao2 --omega 0
refuse gen-sim-outdt-neg     output_dt -- "${SIM[@]}" --output-dt -1
refuse gen-sim-config-none   config    -- "${SIM[@]}" --config nothere.nml
refuse gen-sim-config-dir    config    -- "${SIM[@]}" --config dir
refuse gen-lya-batches-zero  batches   -- "${LYA[@]}" --batches 0
refuse gen-lya-vectors-5     vectors   -- "${LYA[@]}" --vectors 5
refuse gen-div-spacing-neg   spacing   -- "${DIV[@]}" --pair-spacing -1
refuse gen-div-outdt-zero    output_dt -- "${DIV[@]}" --output-dt 0
refuse gen-div-fit-nan       fit_start -- "${DIV[@]}" --fit-start nan
refuse gen-poi-link-3        link      -- "${POI[@]}" --section-link 3
refuse gen-poi-dir-2         direction -- "${POI[@]}" --section-direction 2
refuse gen-poi-energy-nan    energy    -- "${POI[@]}" --energy nan
refuse gen-poi-points-zero   points    -- "${POI[@]}" --points 0
refuse gen-swp-min1-nan      min1      -- "${SWP[@]}" --min1 nan
refuse gen-swp-max2-inf      max2      -- "${SWP[@]}" --max2 inf
refuse gen-swp-n1-junk       n1        -- "${SWP[@]}" --n1 4x
refuse gen-swp-axis          axis1     -- "${SWP[@]}" --axis1 bogus
refuse gen-swp-unit          time_unit -- "${SWP[@]}" --time-unit hours
refuse gen-sim-unit          time_unit -- "${SIM[@]}" --time-unit S
refuse gen-lya-unit          time_unit -- "${LYA[@]}" --time-unit natural,s
succeed gen-div-unit-natural          -- "${DIV[@]}" --time-unit natural
refuse gen-swp-stop          stop_at   -- "${SWP[@]}" --stop-at never
refuse gen-swp-block-zero    block     -- "${SWP[@]}" --block 0
succeed gen-swp-threads-zero          -- "${SWP[@]}" --threads 0   # 0: all CPUs
refuse gen-swp-threads-big   threads   -- "${SWP[@]}" --threads 1025
refuse gen-swp-angles        angles    -- sweep --ic-file list.txt --t-end 1 --quiet --output g.h5 --ic-angles x
[ -e "$FIXTURES/ic.fifo" ] || mkfifo "$FIXTURES/ic.fifo"
refuse gen-swp-ic-fifo       ic_file   -- sweep --ic-file ic.fifo --t-end 1 --quiet --output g.h5
refuse gen-swp-ic-dir        ic_file   -- sweep --ic-file dir --t-end 1 --quiet --output g.h5
refuse gen-swp-ic-missing    ic_file   -- sweep --ic-file nope.txt --t-end 1 --quiet --output g.h5
refuse gen-swp-icfile-none   nothere   -- sweep --ic-file nothere.txt --t-end 1 --quiet --output g.h5
refuse gen-stu-cases-comma   cases     -- "${STU[@]/small/,}"
refuse gen-stu-cases-empty   cases     -- study --quick --methods rk4 --cases '' --no-figures --output g.h5
refuse gen-stu-cases-bogus   cases     -- study --quick --methods rk4 --cases bogus --no-figures --output g.h5
refuse gen-stu-methods-bogus methods   -- study --quick --methods bogus --cases small --no-figures --output g.h5
refuse gen-stu-methods-comma method    -- study --quick --methods , --cases small --no-figures --output g.h5
refuse gen-stu-m1-nan        m1        -- "${STU[@]}" --m1 nan

# sweep-compare (options in any order, incomparable sweeps refused)
refuse  gen-cmp-one-file     files     -- sweep-compare sweep.h5
refuse  gen-cmp-no-file      nothere   -- sweep-compare sweep.h5 nothere.h5
refuse  gen-cmp-not-sweep    existing  -- sweep-compare sweep.h5 existing.h5
refuse  gen-cmp-dir          dir       -- sweep-compare sweep.h5 dir
refuse  gen-cmp-rel-nan      rel       -- sweep-compare sweep.h5 sweep.h5 --rel nan
refuse  gen-cmp-rel-neg      rel       -- sweep-compare sweep.h5 sweep.h5 --rel -1
refuse  gen-cmp-rel-junk     rel       -- sweep-compare sweep.h5 sweep.h5 --rel 1e
refuse  gen-cmp-rel-missing  rel       -- sweep-compare sweep.h5 sweep.h5 --rel
refuse  gen-cmp-grid-list64  list      -- sweep-compare sweep.h5 sweep_list64.h5
refuse  gen-cmp-theta-w      axis      -- sweep-compare sweep.h5 sweep_w.h5
refuse  gen-cmp-8x8-64x1     shape     -- sweep-compare sweep.h5 sweep_64x1.h5
refuse  gen-cmp-unknown      bogus     -- sweep-compare sweep.h5 sweep.h5 --bogus
succeed gen-cmp-self         -- sweep-compare sweep.h5 sweep.h5
succeed gen-cmp-rel-first    -- sweep-compare --rel 0.1 sweep.h5 sweep.h5
succeed gen-cmp-rel-middle   -- sweep-compare sweep.h5 --rel 0.1 sweep.h5

# export
refuse  gen-exp-nothing      file      -- export
refuse  gen-exp-no-dataset   dataset   -- export existing.h5
refuse  gen-exp-no-file      nothere   -- export nothere.h5 /trajectory/t
refuse  gen-exp-not-h5       list.txt  -- export list.txt /t
refuse  gen-exp-no-such      /nothere  -- export existing.h5 /nothere
refuse  gen-exp-scale-zero   scale     -- export sweep.h5 --matrix /sweep/t_flip /sweep/axis1 /sweep/axis2 0
refuse  gen-exp-scale-nan    scale     -- export sweep.h5 --matrix /sweep/t_flip /sweep/axis1 /sweep/axis2 nan
refuse  gen-exp-unknown      bogus     -- export existing.h5 --bogus

# unknown commands and options (an unknown flag at the end is
# not "needs a value"; --force=yes is not an unknown option --force)
refuse  gen-cmd-unknown      bogus     -- bogus
refuse  gen-cmd-empty        command   -- ''
refuse  gen-cmd-option       bogus     -- --bogus
refuse  gen-sim-unknown      bogus     -- "${SIM[@]}" --bogus 1
refuse  gen-sim-unknown-end  bogus     -- "${SIM[@]}" --bogus
refuse  gen-sim-force-yes    force     -- "${SIM[@]}" --force=yes
refuse  gen-sim-stray-word   stray     -- "${SIM[@]}" stray
refuse  gen-lya-unknown-end  bogus     -- "${LYA[@]}" --bogus
refuse  gen-div-unknown-end  bogus     -- "${DIV[@]}" --bogus
refuse  gen-poi-unknown-end  bogus     -- "${POI[@]}" --bogus
refuse  gen-swp-unknown-end  bogus     -- "${SWP[@]}" --bogus
refuse  gen-stu-unknown-end  bogus     -- "${STU[@]}" --bogus

# --help of every command succeeds (export --help once exited 2)
succeed gen-help             -- --help
succeed gen-help-short       -- -h
succeed gen-version          -- version
succeed gen-methods          -- methods
for c in simulate lyapunov divergence poincare sweep sweep-compare study export; do
  succeed gen-help-$c        -- $c --help
  succeed gen-h-$c           -- $c -h
done
