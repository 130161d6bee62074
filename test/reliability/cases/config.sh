# Reliability cases: strict --config files (FIFOs, directories, binary files), option
# parsing, export, sweep-compare.
# Sourced by scripts/reliability.sh; FIXTURES is the fixture directory, DPEND the
# binary. Row forms: refuse ID FIELD -- ARGS / fail ID TEXT -- ARGS / succeed ID -- ARGS.

_cfg_bin=${DPEND:-dpend}
_cfg_fx=$FIXTURES

# ---------------------------------------------------------------- fixtures ---
mkfifo "$_cfg_fx/cfg_fifo.nml" 2>/dev/null
printf '&pendulum m1 = 2 /\n&initial q1 = 1 /\n' > "$_cfg_fx/cfg_ok.nml"
printf 'm1 = 2\n&pendulum m2 = 3 /\n' > "$_cfg_fx/cfg_keybefore.nml"
printf '&pendulum m1 = 2 /\n&pendulum m1 = 3 /\n' > "$_cfg_fx/cfg_twice.nml"
# a logical for a number's key (fuzz seed 20261202: n_omega = true was read as nothing)
printf '&integration save_every = true /\n' > "$_cfg_fx/cfg_logical_number.nml"
printf "&integration time_unit = 'hours' /\n" > "$_cfg_fx/cfg_time_unit_bad.nml"
printf "&sweep n1 = 4, n2 = 4, time_unit = 's' /\n" > "$_cfg_fx/cfg_sweep_time_unit.nml"
printf 'm1 = 5\n' > "$_cfg_fx/cfg_nogroup.nml"
printf '! only a comment\n\n' > "$_cfg_fx/cfg_comment.nml"
printf '&integration dt = 1e999 /\n' > "$_cfg_fx/cfg_huge.nml"
printf "&integration dt = 1e-3, t_end = 0.01 /\n&output file = 'o1e999.h5' / ! 1e999\n" > "$_cfg_fx/cfg_huge_quoted.nml"
: > "$_cfg_fx/cfg_empty.nml"
printf '&pendulum m1 = 2 /\nabc\0def\n' > "$_cfg_fx/cfg_nul.nml"
printf '&pendulum m1 = 2 /\n\001\n' > "$_cfg_fx/cfg_ctl.nml"
printf '! caf\351\n&pendulum m1 = 2 /\n' > "$_cfg_fx/cfg_latin1.nml"
printf '! caf\303\251, \316\270 in rad\n&pendulum m1 = 2 /\n' > "$_cfg_fx/cfg_utf8.nml"
printf '&pendulum m1 = 2\n' > "$_cfg_fx/cfg_unclosed.nml"
printf '&pendulum m1 = 2 &initial q1 = 1 /\n' > "$_cfg_fx/cfg_nested.nml"
printf '&pendulum m1 = 2 /\n&end\n' > "$_cfg_fx/cfg_strayend.nml"
printf '&pendulum m1 = 2 &end\n' > "$_cfg_fx/cfg_endterm.nml"
printf '&pendulum m1 = 2 /\n&bogus x = 1 /\n' > "$_cfg_fx/cfg_unknown.nml"
printf '&pendulum m1 = 2 / m2 = 3\n' > "$_cfg_fx/cfg_after.nml"
printf "&output file = 'a/b!&c.h5' /\n" > "$_cfg_fx/cfg_quoted.nml"
printf '&chaos tau = 1 /\n&chaos tau = 2 /\n' > "$_cfg_fx/cfg_chaos_twice.nml"
printf '&sweep n1 = 4 /\n&sweep n2 = 4 /\n' > "$_cfg_fx/cfg_sweep_twice.nml"
printf '&sweep n1 = 4, n2 = 4 /\n&integration t_end = 0.5 /\n' > "$_cfg_fx/cfg_sweep_ok.nml"
printf '&study n_h = 3 /\n&study n_h = 4 /\n' > "$_cfg_fx/cfg_study_twice.nml"
printf '&study n_h = 3 /\n&integration dt = 1e-3 /\n' > "$_cfg_fx/cfg_study_integration.nml"
ln -sf cfg_ok.nml "$_cfg_fx/cfg_link.nml"
ln -sf cfg_loop_b "$_cfg_fx/cfg_loop_a"
ln -sf cfg_loop_a "$_cfg_fx/cfg_loop_b"
ln -sf cfg_missing.nml "$_cfg_fx/cfg_dangling.nml"
{ printf '&pendulum m1 = 2 /\n'; head -c 1100000 /dev/zero | tr '\0' ' '; } > "$_cfg_fx/cfg_big.nml"
printf '&pendulum m1 = 2 /\n' > "$_cfg_fx/cfg_unreadable.nml"
chmod 000 "$_cfg_fx/cfg_unreadable.nml"

# sweeps for sweep-compare (small: 8x8, t_end 3, debug build well under a second each)
_cfg_sweep() {  # NAME ARGS...
    local name=$1; shift
    local t=(--t-end 3)   # unless ARGS give their own (an option given twice is refused)
    [[ " $* " == *" --t-end "* ]] && t=()
    (cd "$_cfg_fx" && "$_cfg_bin" sweep --quiet "${t[@]}" "$@" --output "$name" >/dev/null 2>&1)
}
_cfg_sweep cfg_ga.h5 --n 8 --dt 0.01
_cfg_sweep cfg_gb.h5 --n 8 --dt 0.005
_cfg_sweep cfg_g16.h5 --n1 16 --n2 16 --t-end 1
_cfg_sweep cfg_g256.h5 --n1 256 --n2 1 --t-end 1
_cfg_sweep cfg_gw.h5 --n 8 --axis1 w1 --axis2 w2 --min1 -1 --max1 1 --min2 -1 --max2 1
_cfg_sweep cfg_gs.h5 --n 8 --time-unit s
_cfg_sweep cfg_gr.h5 --n 8 --min1 -2
_cfg_sweep cfg_gl.h5 --n 8 --l1 2
_cfg_sweep cfg_gt.h5 --n 8 --t-end 4
printf '0 0 0 0\n0.5 0.5 0 0\n1 1 0 0\n' > "$_cfg_fx/cfg_list.txt"
_cfg_sweep cfg_list.h5 --ic-file cfg_list.txt
# a stored time unit sqrt(l1/g) of 0 and NaN (patched bytes of the attribute)
if command -v python3 >/dev/null 2>&1 && [ -f "$_cfg_fx/cfg_ga.h5" ]; then
    python3 - "$_cfg_fx" <<'PY'
import math, struct, sys
d = sys.argv[1]
b = open(d + '/cfg_ga.h5', 'rb').read()
tau = struct.pack('<d', math.sqrt(1 / 9.8))
if b.count(tau) == 1:
    for value, name in [(0.0, 'cfg_tau0.h5'), (float('nan'), 'cfg_taunan.h5')]:
        open(d + '/' + name, 'wb').write(b.replace(tau, struct.pack('<d', value)))
PY
fi
# an incomplete sweep: killed while it runs (long enough in any build profile)
(
    cd "$_cfg_fx" || exit
    "$_cfg_bin" sweep --quiet --n 48 --block 48 --threads 1 --t-end 300 --stop-at end \
        --output cfg_incomplete.h5 >/dev/null 2>&1 &
    pid=$!
    sleep 1.5
    kill -9 "$pid" 2>/dev/null
    wait "$pid" 2>/dev/null
    # the working file may have another name while the sweep runs
    for f in cfg_incomplete.h5*; do
        [ -f "$f" ] && [ "$f" != cfg_incomplete.h5 ] && mv -f "$f" cfg_incomplete.h5
    done
    true
)

# ------------------------------------------------- strict config files: simulate ---
refuse  cfg-sim-keybefore     'outside any namelist group' -- simulate --config cfg_keybefore.nml --output o.h5
refuse  cfg-sim-twice         'appears twice'      -- simulate --config cfg_twice.nml --output o.h5
refuse  cfg-sim-logical-number 'takes a number'   -- simulate --config cfg_logical_number.nml --output o.h5
refuse  cfg-sim-time-unit     "time_unit: 'hours'" -- simulate --config cfg_time_unit_bad.nml --output o.h5
refuse  cfg-swp-time-unit-group 'give it in &integration' -- sweep --config cfg_sweep_time_unit.nml --output o.h5
refuse  cfg-sim-huge-number   'line 1'             -- simulate --config cfg_huge.nml --output o.h5
succeed cfg-sim-huge-in-text  -- simulate --config cfg_huge_quoted.nml --output o.h5
refuse  cfg-sim-nogroup       'outside any'        -- simulate --config cfg_nogroup.nml --output o.h5
refuse  cfg-sim-comment       'no namelist group'  -- simulate --config cfg_comment.nml --output o.h5
refuse  cfg-sim-empty         'no namelist group'  -- simulate --config cfg_empty.nml --output o.h5
refuse  cfg-sim-hdf5          'HDF5 file'          -- simulate --config existing.h5 --output o.h5
refuse  cfg-sim-fifo          'FIFO'               -- simulate --config cfg_fifo.nml --output o.h5
refuse  cfg-sim-dir           'directory'          -- simulate --config dir --output o.h5
refuse  cfg-sim-nul           'not a text file'    -- simulate --config cfg_nul.nml --output o.h5
refuse  cfg-sim-control       'not a text file'    -- simulate --config cfg_ctl.nml --output o.h5
refuse  cfg-sim-latin1        'not a text file'    -- simulate --config cfg_latin1.nml --output o.h5
refuse  cfg-sim-unclosed      'not closed'         -- simulate --config cfg_unclosed.nml --output o.h5
refuse  cfg-sim-nested        'not closed'         -- simulate --config cfg_nested.nml --output o.h5
refuse  cfg-sim-strayend      'closes no group'    -- simulate --config cfg_strayend.nml --output o.h5
refuse  cfg-sim-unknown-group 'unknown namelist group' -- simulate --config cfg_unknown.nml --output o.h5
refuse  cfg-sim-after-slash   'outside any'        -- simulate --config cfg_after.nml --output o.h5
refuse  cfg-sim-missing       'no such file'       -- simulate --config cfg_nope.nml --output o.h5
refuse  cfg-sim-dangling      'no such file'       -- simulate --config cfg_dangling.nml --output o.h5
refuse  cfg-sim-link-loop     'symbolic links'     -- simulate --config cfg_loop_a --output o.h5
refuse  cfg-sim-big           'bytes'              -- simulate --config cfg_big.nml --output o.h5
refuse  cfg-sim-config-empty  'config'             -- simulate --config= --output o.h5
refuse  cfg-sim-config-noval  'config'             -- simulate --config --t-end 1 --output o.h5
refuse  cfg-sim-config-end    'config'             -- simulate --t-end 1 --config
if [ "$(id -u)" != 0 ]; then   # root reads any file
refuse  cfg-sim-unreadable    'cannot be read'     -- simulate --config cfg_unreadable.nml --output o.h5
fi
succeed cfg-sim-utf8-comment  -- simulate --config cfg_utf8.nml --t-end 0.01 --output o.h5
succeed cfg-sim-symlink       -- simulate --config cfg_link.nml --t-end 0.01 --output o.h5
succeed cfg-sim-end-group     -- simulate --config cfg_endterm.nml --t-end 0.01 --output o.h5
succeed cfg-sim-quoted-file   -- simulate --config cfg_quoted.nml --t-end 0.01 --output o.h5
succeed cfg-sim-config-eq     -- simulate --config=cfg_ok.nml --t-end 0.01 --output o.h5

# ------------------------------------------- strict config files: other commands ---
refuse  cfg-lya-twice         'appears twice'      -- lyapunov --config cfg_twice.nml --output o.h5
refuse  cfg-lya-fifo          'FIFO'               -- lyapunov --config cfg_fifo.nml --output o.h5
refuse  cfg-lya-chaos-twice   'appears twice'      -- lyapunov --config cfg_chaos_twice.nml --output o.h5
refuse  cfg-div-hdf5          'HDF5 file'          -- divergence --config existing.h5 --output o.h5
refuse  cfg-div-keybefore     'outside any'        -- divergence --config cfg_keybefore.nml --output o.h5
refuse  cfg-poi-dir           'directory'          -- poincare --config dir --output o.h5
refuse  cfg-poi-comment       'no namelist group'  -- poincare --config cfg_comment.nml --output o.h5
refuse  cfg-swp-fifo          'FIFO'               -- sweep --config cfg_fifo.nml --output o.h5
refuse  cfg-swp-hdf5          'HDF5 file'          -- sweep --config sweep.h5 --output o.h5
refuse  cfg-swp-sweep-twice   'appears twice'      -- sweep --config cfg_sweep_twice.nml --output o.h5
refuse  cfg-swp-keybefore     'outside any'        -- sweep --config cfg_keybefore.nml --output o.h5
refuse  cfg-swp-binary        'not a text file'    -- sweep --config cfg_nul.nml --output o.h5
succeed cfg-swp-config-ok     -- sweep --config cfg_sweep_ok.nml --quiet --output o.h5
refuse  cfg-std-fifo          'FIFO'               -- study --config cfg_fifo.nml --output o/s.h5
refuse  cfg-std-hdf5          'HDF5 file'          -- study --config existing.h5 --output o/s.h5
refuse  cfg-std-study-twice   'appears twice'      -- study --config cfg_study_twice.nml --output o/s.h5
refuse  cfg-std-integration   'reads only time_unit' -- study --config cfg_study_integration.nml --output o/s.h5
refuse  cfg-std-dir           'directory'          -- study --config dir --output o/s.h5
refuse  cfg-std-nogroup       'outside any'        -- study --config cfg_nogroup.nml --output o/s.h5

# ---------------------------------------------------------------- options ---
refuse  cfg-opt-sim-unknown-end 'unknown option'   -- simulate --t-end 0.01 --output o.h5 --bogus
refuse  cfg-opt-sim-unknown-first 'unknown option' -- simulate --bogus --t-end 0.01 --output o.h5
refuse  cfg-opt-lya-unknown-end 'unknown option'   -- lyapunov --output o.h5 --bogus
refuse  cfg-opt-div-unknown-end 'unknown option'   -- divergence --output o.h5 --bogus
refuse  cfg-opt-poi-unknown-end 'unknown option'   -- poincare --output o.h5 --bogus
refuse  cfg-opt-lya-same-energy 'unknown option'   -- lyapunov --output o.h5 --same-energy
refuse  cfg-opt-swp-unknown-end 'unknown option'   -- sweep --n 4 --output o.h5 --zzz
refuse  cfg-opt-std-unknown-end 'unknown option'   -- study --output o/s.h5 --zzz
refuse  cfg-opt-sim-force-yes  'takes no value'    -- simulate --t-end 0.01 --output o.h5 --force=yes
refuse  cfg-opt-lya-force-yes  'takes no value'    -- lyapunov --output o.h5 --force=yes
refuse  cfg-opt-div-same-energy-yes 'takes no value' -- divergence --output o.h5 --same-energy=yes
refuse  cfg-opt-swp-quiet-yes  'takes no value'    -- sweep --n 4 --output o.h5 --quiet=yes
refuse  cfg-opt-swp-lyapunov-1 'takes no value'    -- sweep --n 4 --output o.h5 --lyapunov=1
refuse  cfg-opt-std-quick-yes  'takes no value'    -- study --output o/s.h5 --quick=yes
refuse  cfg-opt-std-nofig-yes  'takes no value'    -- study --output o/s.h5 --no-figures=no
refuse  cfg-opt-sim-dt-end     'needs a value'     -- simulate --output o.h5 --dt
refuse  cfg-opt-sim-dt-mid     'needs a value'     -- simulate --dt --t-end 1 --output o.h5
refuse  cfg-opt-poi-energy-end 'needs a value'     -- poincare --output o.h5 --energy
refuse  cfg-opt-swp-n-end      'needs a value'     -- sweep --output o.h5 --n
refuse  cfg-opt-sim-output-end 'needs a value'     -- simulate --t-end 0.01 -o
succeed cfg-opt-sim-equals     -- simulate --t-end=0.01 --dt=1e-3 --output=o.h5
succeed cfg-opt-sim-any-order  -- simulate --output o.h5 --force --t-end 0.01 --method rk4
refuse  cfg-std-cases-comma    '--cases'           -- study --output o/s.h5 --cases ,
refuse  cfg-std-cases-double   '--cases'           -- study --output o/s.h5 --cases small,,mixed
refuse  cfg-std-cases-trailing '--cases'           -- study --output o/s.h5 --cases small,
refuse  cfg-std-cases-empty    '--cases'           -- study --output o/s.h5 --cases=
refuse  cfg-std-methods-comma  '--methods'         -- study --output o/s.h5 --methods ,
refuse  cfg-std-methods-lead   '--methods'         -- study --output o/s.h5 --methods ,rk4
refuse  cfg-std-cases-noval    'needs a value'     -- study --output o/s.h5 --cases

# ----------------------------------------------------------------- export ---
succeed cfg-exp-help           -- export --help
succeed cfg-exp-help-late      -- export existing.h5 --help
refuse  cfg-exp-nothing        'needs a file'      -- export
refuse  cfg-exp-one-arg        'needs a file'      -- export existing.h5
refuse  cfg-exp-unknown-end    'unknown option'    -- export existing.h5 /t --bogus
refuse  cfg-exp-matrix-value   'takes no value'    -- export sweep.h5 --matrix=1 /sweep/t_flip
refuse  cfg-exp-scale-subnormal 'SCALE'            -- export sweep.h5 --matrix /sweep/energy0 /sweep/axis1 /sweep/axis2 1e-310
refuse  cfg-exp-scale-overflow 'SCALE'             -- export sweep.h5 --matrix /sweep/energy0 /sweep/axis1 /sweep/axis2 1e-307
refuse  cfg-exp-scale-zero     'SCALE'             -- export sweep.h5 --matrix /sweep/energy0 /sweep/axis1 /sweep/axis2 0
refuse  cfg-exp-scale-negative 'SCALE'             -- export sweep.h5 --matrix /sweep/energy0 /sweep/axis1 /sweep/axis2 -1
succeed cfg-exp-scale-above-one                    -- export sweep.h5 --matrix /sweep/energy0 /sweep/axis1 /sweep/axis2 2.5
succeed cfg-exp-scale-huge                         -- export sweep.h5 --matrix /sweep/energy0 /sweep/axis1 /sweep/axis2 1e300
refuse  cfg-exp-scale-nan      'SCALE'             -- export sweep.h5 --matrix /sweep/energy0 /sweep/axis1 /sweep/axis2 nan
succeed cfg-exp-scale-small    -- export sweep.h5 --matrix /sweep/t_flip /sweep/axis1 /sweep/axis2 1e-300
succeed cfg-exp-matrix-first   -- export --matrix sweep.h5 /sweep/t_flip
refuse  cfg-exp-matrix-args    '--matrix'          -- export sweep.h5 --matrix /sweep/t_flip /sweep/axis1
refuse  cfg-exp-fifo           'FIFO'              -- export cfg_fifo.nml /t
refuse  cfg-exp-dir            'directory'         -- export dir /t
refuse  cfg-exp-missing        'no such file'      -- export cfg_nope.h5 /t
refuse  cfg-exp-text           'HDF5'              -- export cfg_ok.nml /t
refuse  cfg-exp-no-dataset     'no such dataset'   -- export existing.h5 /nope

# ---------------------------------------------------------- sweep-compare ---
succeed cfg-cmp-ok             -- sweep-compare cfg_ga.h5 cfg_gb.h5
succeed cfg-cmp-rel-first      -- sweep-compare --rel 0.05 cfg_ga.h5 cfg_gb.h5
succeed cfg-cmp-rel-middle     -- sweep-compare cfg_ga.h5 --rel 0.05 cfg_gb.h5
succeed cfg-cmp-rel-equals     -- sweep-compare cfg_ga.h5 cfg_gb.h5 --rel=0.05
succeed cfg-cmp-help           -- sweep-compare --help
refuse  cfg-cmp-rel-noval      'needs a value'     -- sweep-compare cfg_ga.h5 cfg_gb.h5 --rel
refuse  cfg-cmp-rel-zero       '--rel'             -- sweep-compare cfg_ga.h5 cfg_gb.h5 --rel 0
refuse  cfg-cmp-rel-huge       '--rel'             -- sweep-compare cfg_ga.h5 cfg_gb.h5 --rel 1e308
refuse  cfg-cmp-unknown        'unknown option'    -- sweep-compare cfg_ga.h5 cfg_gb.h5 --bogus
refuse  cfg-cmp-one-file       'two files'         -- sweep-compare cfg_ga.h5
refuse  cfg-cmp-three-files    'two files'         -- sweep-compare cfg_ga.h5 cfg_gb.h5 cfg_gw.h5
refuse  cfg-cmp-shape          'shape'             -- sweep-compare cfg_g16.h5 cfg_g256.h5
refuse  cfg-cmp-axes           'axis1'             -- sweep-compare cfg_ga.h5 cfg_gw.h5
refuse  cfg-cmp-grid-list      'initial'           -- sweep-compare cfg_ga.h5 cfg_list.h5
refuse  cfg-cmp-list-grid      'initial'           -- sweep-compare cfg_list.h5 cfg_ga.h5
refuse  cfg-cmp-time-unit      'time_unit'         -- sweep-compare cfg_ga.h5 cfg_gs.h5
refuse  cfg-cmp-range          'min1'              -- sweep-compare cfg_ga.h5 cfg_gr.h5
refuse  cfg-cmp-l1             'l1'                -- sweep-compare cfg_ga.h5 cfg_gl.h5
refuse  cfg-cmp-t-end          't_end'             -- sweep-compare cfg_ga.h5 cfg_gt.h5
refuse  cfg-cmp-fifo           'FIFO'              -- sweep-compare cfg_ga.h5 cfg_fifo.nml
refuse  cfg-cmp-dir            'directory'         -- sweep-compare dir cfg_ga.h5
refuse  cfg-cmp-not-sweep      'not a dpend sweep' -- sweep-compare cfg_ga.h5 existing.h5
refuse  cfg-cmp-text           'not an HDF5'       -- sweep-compare cfg_ga.h5 cfg_ok.nml
refuse  cfg-cmp-missing        'no such file'      -- sweep-compare cfg_ga.h5 cfg_nope.h5
if [ -f "$_cfg_fx/cfg_tau0.h5" ]; then
refuse  cfg-cmp-tau-zero       'sqrt_l1_over_g'    -- sweep-compare cfg_ga.h5 cfg_tau0.h5
refuse  cfg-cmp-tau-nan        'sqrt_l1_over_g'    -- sweep-compare cfg_taunan.h5 cfg_ga.h5
fi
if [ -f "$_cfg_fx/cfg_incomplete.h5" ]; then
refuse  cfg-cmp-incomplete     'not complete'      -- sweep-compare cfg_incomplete.h5 cfg_incomplete.h5
fi
