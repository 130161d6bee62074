# Files from elsewhere and outputs (issue 24, items 3, 4, 8, 9, 10, 11 and the
# --frames gap of 13): sizes declared by a file are checked before allocation,
# attribute and dataset types before use, the data (not only the config) before
# trust; an output never replaces an input (with or without --force, whatever name
# reaches it); export is linear in the columns and bounded; animate draws only
# trajectories; an unwritable --frames directory is bad input (exit 2).
#
# Fixtures: copies of dpend's own files edited by scripts/h5craft.f90, built here
# with h5fc (libhdf5-dev, which scripts/setup.sh installs). r2f_*.h5 names.

_r2f_tool=$(mktemp -d "${TMPDIR:-/tmp}/r2f-h5craft.XXXXXX")
(
  set -e
  cd "$_r2f_tool"
  h5fc -o h5craft "$ROOT/scripts/h5craft.f90" > build.log 2>&1
  H=$_r2f_tool/h5craft
  cd "$FIXTURES"
  # edit COPY OF: copy OF to COPY, then apply one h5craft edit
  edit() { local to=$1 from=$2; shift 2; cp "$from" "$to"; "$H" "$to" "$@"; }
  # trajectories
  "$DPEND" simulate --t-end 0.2 --output r2f_sim.h5 > /dev/null
  ln r2f_sim.h5 r2f_sim_link.h5
  edit r2f_big.h5      r2f_sim.h5 huge /trajectory/q 1099511627776 2
  edit r2f_bigt.h5     r2f_sim.h5 huge /trajectory/t 1099511627776
  edit r2f_units.h5    r2f_sim.h5 attr-int /trajectory/t units 3
  edit r2f_desc.h5     r2f_sim.h5 attr-int /trajectory/q description 2
  edit r2f_t0.h5       r2f_sim.h5 real /trajectory/t 0 21
  edit r2f_q300.h5     r2f_sim.h5 set /trajectory/q 5 1e300
  edit r2f_tnan.h5     r2f_sim.h5 set /trajectory/t 3 nan
  edit r2f_tbig.h5     r2f_sim.h5 ramp /trajectory/t 21
  "$H" r2f_tbig.h5 set /trajectory/t 21 1e12
  edit r2f_qshape.h5   r2f_sim.h5 real /trajectory/q 0.5 21 3
  edit r2f_tint.h5     r2f_sim.h5 int /trajectory/t 1 21   # integers read as reals: t = 1 1 1 ...
  edit r2f_links.h5    r2f_sim.h5 attr-i0 / links 99
  edit r2f_wide.h5     r2f_sim.h5 real /trajectory/wide 0.5 2 100000
  edit r2f_wide20k.h5  r2f_sim.h5 real /trajectory/wide 0.5 2 20000
  # sweeps: a MEGNO and a lambda1 map of the same 4 x 4 pixels, and edits
  "$DPEND" sweep --n 4 --t-end 1 --indicator megno --output r2f_m.h5 --quiet > /dev/null
  "$DPEND" sweep --n 4 --t-end 2 --indicator lambda1 --output r2f_l.h5 --quiet > /dev/null
  edit r2f_m_nan.h5     r2f_m.h5 real /sweep/megno nan 4 4
  edit r2f_m_inf.h5     r2f_m.h5 real /sweep/megno inf 4 4
  edit r2f_m_neg.h5     r2f_m.h5 real /sweep/megno -1 4 4
  edit r2f_m_huge.h5    r2f_m.h5 huge /sweep/megno 1099511627776 2
  edit r2f_m_nostatus.h5 r2f_m.h5 del /sweep/status
  edit r2f_m_status.h5  r2f_m.h5 int /sweep/status 1 4 3
  edit r2f_m_status9.h5 r2f_m.h5 int /sweep/status 9 4 4
  edit r2f_m_noaxis.h5  r2f_m.h5 del /sweep/axis1
  edit r2f_m_axis.h5    r2f_m.h5 ramp /sweep/axis1 5
  edit r2f_m_tend.h5    r2f_m.h5 attr-real /sweep t_end nan
  edit r2f_m_links.h5   r2f_m.h5 attr-i0 /sweep links 99
  edit r2f_m_tau.h5     r2f_m.h5 attr-real /sweep sqrt_l1_over_g nan
  edit r2f_m_cfgt.h5    r2f_m.h5 attr-sub /sweep config 't_end = 1.0000000000000000E+000' 't_end = NaN'
  edit r2f_m_cfgn.h5    r2f_m.h5 attr-sub /sweep config 'n1 = 4' 'n1 = 99'
  edit r2f_m_units.h5   r2f_m.h5 attr-int /sweep/megno units 4
  edit r2f_s_nostatus.h5 sweep.h5 del /sweep/status
  edit r2f_s_status.h5  sweep.h5 int /sweep/status 1 8 7
  edit r2f_s_noaxis.h5  sweep.h5 del /sweep/axis1
  edit r2f_s_axis.h5    sweep.h5 ramp /sweep/axis1 9
  edit r2f_s_h.h5       sweep.h5 attr-real /sweep h nan
  edit r2f_s_tflip.h5   sweep.h5 real /sweep/t_flip inf 8 8
  edit r2f_s_huge.h5    sweep.h5 huge /sweep/t_flip 1099511627776 2
  edit r2f_s_cfgt.h5    sweep.h5 attr-sub /sweep config 't_end = 1.0000000000000000E+000' 't_end = NaN'
  edit r2f_s_links.h5   sweep.h5 attr-i0 /sweep links 99
  edit r2f_l_list.h5    sweep_list.h5 real /sweep/t_flip nan 3
  printf 't,theta1\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n' > r2f_fit.csv
) > /dev/null 2> "$_r2f_tool/fixtures.err" ||
  { echo "round2_files.sh: could not make the fixtures:" >&2; cat "$_r2f_tool/fixtures.err" >&2
    cat "$_r2f_tool/build.log" >&2 2>/dev/null; }
rm -rf "$_r2f_tool"

T=(--fps 5 --size 64x64)   # tiny animations

# ---- 3: sizes declared by the file, checked before allocation (was "Error allocating
# 17592186044416 bytes" and a backtrace)
refuse  r2f-export-huge        trajectory/q -- export r2f_big.h5 q
refuse  r2f-export-huge-csv    trajectory/q -- export r2f_big.h5 --csv t q
refuse  r2f-export-huge-t      trajectory/t -- export r2f_bigt.h5 t
refuse  r2f-export-huge-matrix trajectory/q -- export r2f_big.h5 --matrix q
refuse  r2f-ani-huge           trajectory/q -- animate r2f_big.h5 --output a.gif "${T[@]}"
refuse  r2f-ani-huge-t         trajectory/t -- animate r2f_bigt.h5 --output a.gif "${T[@]}"
refuse  r2f-agr-huge           sweep/megno  -- sweep-compare r2f_m_huge.h5 r2f_l.h5 --agreement
refuse  r2f-cmp-huge           sweep/t_flip -- sweep-compare r2f_s_huge.h5 sweep.h5
# ---- 4: attribute and dataset types checked before use (was a segfault, exit 139)
refuse  r2f-list-units-int     units        -- export r2f_units.h5 --list
refuse  r2f-list-desc-int      description  -- export r2f_desc.h5 --list
refuse  r2f-csv-units-int      units        -- export r2f_units.h5 --csv t
refuse  r2f-list-sweep-units   units        -- export r2f_m_units.h5 --list
refuse  r2f-ani-t-int          'does not increase' -- animate r2f_tint.h5 --output a.gif "${T[@]}"
refuse  r2f-ani-links-99       links        -- animate r2f_links.h5 --output a.gif "${T[@]}"
refuse  r2f-ani-q-shape        trajectory   -- animate r2f_qshape.h5 --output a.gif "${T[@]}"
# ---- 8: an output never replaces an input, with or without --force
refuse  r2f-ani-self           input   -- animate r2f_sim.h5 --output r2f_sim.h5 "${T[@]}"
refuse  r2f-ani-self-force     input   -- animate r2f_sim.h5 --output r2f_sim.h5 --force "${T[@]}"
refuse  r2f-ani-self-dot       input   -- animate r2f_sim.h5 --output ./r2f_sim.h5 --force "${T[@]}"
refuse  r2f-ani-hard-link      input   -- animate r2f_sim.h5 --output r2f_sim_link.h5 --force "${T[@]}"
refuse  r2f-ani-overlay-self   input   -- animate existing.h5 --overlay r2f_sim.h5 \
                                          --output r2f_sim.h5 --force "${T[@]}"
refuse  r2f-agr-self-a         input   -- sweep-compare r2f_m.h5 r2f_l.h5 --agreement \
                                          --output r2f_m.h5 --force
refuse  r2f-agr-self-b         input   -- sweep-compare r2f_m.h5 r2f_l.h5 --agreement \
                                          --output r2f_l.h5 --force
refuse  r2f-agr-self-noforce   input   -- sweep-compare r2f_m.h5 r2f_l.h5 --agreement \
                                          --output r2f_m.h5
refuse  r2f-sim-config-self    input   -- simulate --config simulate.nml --t-end 0.1 \
                                          --output simulate.nml --force
refuse  r2f-sweep-icfile-self  input   -- sweep --ic-file list.txt --t-end 1 --quiet \
                                          --output list.txt --force
refuse  r2f-fit-data-self      input   -- fit r2f_fit.csv --output r2f_fit.csv --force
# ---- 9: sweep-compare checks the data, not only the config attribute
refuse  r2f-agr-all-nan        sweep/megno  -- sweep-compare r2f_m_nan.h5 r2f_l.h5 --agreement
refuse  r2f-agr-inf            sweep/megno  -- sweep-compare r2f_m_inf.h5 r2f_l.h5 --agreement
refuse  r2f-agr-negative       sweep/megno  -- sweep-compare r2f_m_neg.h5 r2f_l.h5 --agreement
refuse  r2f-agr-no-status      sweep/status -- sweep-compare r2f_m_nostatus.h5 r2f_l.h5 --agreement
refuse  r2f-agr-status-short   sweep/status -- sweep-compare r2f_m_status.h5 r2f_l.h5 --agreement
refuse  r2f-agr-status-9       sweep/status -- sweep-compare r2f_m_status9.h5 r2f_l.h5 --agreement
refuse  r2f-agr-no-axis1       axis1        -- sweep-compare r2f_m_noaxis.h5 r2f_l.h5 --agreement
refuse  r2f-agr-axis1-long     axis1        -- sweep-compare r2f_m_axis.h5 r2f_l.h5 --agreement
refuse  r2f-agr-tend-nan       t_end        -- sweep-compare r2f_m_tend.h5 r2f_l.h5 --agreement
refuse  r2f-agr-links-99       links        -- sweep-compare r2f_m_links.h5 r2f_l.h5 --agreement
refuse  r2f-agr-tau-nan        sqrt_l1_over_g -- sweep-compare r2f_m_tau.h5 r2f_l.h5 --agreement
refuse  r2f-agr-cfg-tend-nan   t_end        -- sweep-compare r2f_m_cfgt.h5 r2f_l.h5 --agreement
refuse  r2f-agr-cfg-n1         n1           -- sweep-compare r2f_m_cfgn.h5 r2f_l.h5 --agreement
refuse  r2f-cmp-no-status      sweep/status -- sweep-compare r2f_s_nostatus.h5 sweep.h5
refuse  r2f-cmp-status-short   sweep/status -- sweep-compare sweep.h5 r2f_s_status.h5
refuse  r2f-cmp-no-axis1       axis1        -- sweep-compare r2f_s_noaxis.h5 sweep.h5
refuse  r2f-cmp-axis1-long     axis1        -- sweep-compare r2f_s_axis.h5 sweep.h5
refuse  r2f-cmp-h-nan          'attribute h' -- sweep-compare r2f_s_h.h5 sweep.h5
refuse  r2f-cmp-tflip-inf      t_flip       -- sweep-compare r2f_s_tflip.h5 sweep.h5
refuse  r2f-cmp-cfg-tend-nan   t_end        -- sweep-compare r2f_s_cfgt.h5 r2f_s_cfgt.h5
refuse  r2f-cmp-links-99       links        -- sweep-compare r2f_s_links.h5 sweep.h5
succeed r2f-cmp-list-no-flips                -- sweep-compare r2f_l_list.h5 sweep_list.h5
succeed r2f-agr-ok                           -- sweep-compare r2f_m.h5 r2f_l.h5 --agreement \
                                                --output r2f_agr.h5
# ---- 10: export --csv is linear in the columns (a (2, 100000) dataset took > 100 s)
succeed r2f-csv-wide-100k      -- export r2f_wide.h5 --csv wide
succeed r2f-csv-wide-20k       -- export r2f_wide20k.h5 --csv /trajectory/wide
succeed r2f-plain-wide-100k    -- export r2f_wide.h5 wide
# ---- 11: animate draws only trajectories; --matrix takes a 2-D dataset
refuse  r2f-ani-t-constant     'does not increase' -- animate r2f_t0.h5 --output a.gif "${T[@]}"
refuse  r2f-ani-q-1e300        trajectory/q -- animate r2f_q300.h5 --output a.gif "${T[@]}"
refuse  r2f-ani-t-nan          non-finite   -- animate r2f_tnan.h5 --output a.gif "${T[@]}"
refuse  r2f-ani-t-1e12         trajectory/t -- animate r2f_tbig.h5 --output a.gif "${T[@]}"
refuse  r2f-ani-overlay-t0     'does not increase' -- animate r2f_sim.h5 --overlay r2f_t0.h5 \
                                                      --output a.gif "${T[@]}"
refuse  r2f-matrix-1d          'rank 1'     -- export r2f_sim.h5 --matrix t
refuse  r2f-matrix-1d-energy   'rank 1'     -- export r2f_sim.h5 --matrix energy
# ---- 13: --frames where nothing can be created is bad input (exit 2, was 1). CI runs
# as root, where a mode-0555 directory still takes files and no read-only mount can
# be made; /proc and /sys refuse new files to root too.
refuse  r2f-ani-frames-proc    frames -- animate r2f_sim.h5 --output a.gif --frames /proc "${T[@]}"
refuse  r2f-ani-frames-sys     frames -- animate r2f_sim.h5 --output a.gif --frames /sys "${T[@]}"
