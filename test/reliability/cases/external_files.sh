# Files from elsewhere and outputs: sizes declared by a file are checked before allocation,
# attribute and dataset types before use, the data (not only the config) before
# trust; an output never replaces an input (with or without --force, whatever name
# reaches it); export is linear in the columns and bounded; animate draws only
# trajectories; an unwritable --frames directory is bad input (exit 2).
#
# Fixtures: copies of dpend's own files edited by scripts/check/h5craft.f90, built here
# with h5fc (libhdf5-dev, which scripts/setup.sh installs). ext_*.h5 names.

_ext_tool=$(mktemp -d "${TMPDIR:-/tmp}/ext-h5craft.XXXXXX")
(
  set -e
  cd "$_ext_tool"
  h5fc -o h5craft "$ROOT/scripts/check/h5craft.f90" > build.log 2>&1
  H=$_ext_tool/h5craft
  cd "$FIXTURES"
  # edit COPY OF: copy OF to COPY, then apply one h5craft edit
  edit() { local to=$1 from=$2; shift 2; cp "$from" "$to"; "$H" "$to" "$@"; }
  # trajectories
  "$DPEND" simulate --t-end 0.2 --output ext_sim.h5 > /dev/null
  ln ext_sim.h5 ext_sim_link.h5
  edit ext_big.h5      ext_sim.h5 huge /trajectory/q 1099511627776 2
  edit ext_bigt.h5     ext_sim.h5 huge /trajectory/t 1099511627776
  edit ext_units.h5    ext_sim.h5 attr-int /trajectory/t units 3
  edit ext_desc.h5     ext_sim.h5 attr-int /trajectory/q description 2
  edit ext_t0.h5       ext_sim.h5 real /trajectory/t 0 21
  edit ext_q300.h5     ext_sim.h5 set /trajectory/q 5 1e300
  edit ext_tnan.h5     ext_sim.h5 set /trajectory/t 3 nan
  edit ext_tbig.h5     ext_sim.h5 ramp /trajectory/t 21
  "$H" ext_tbig.h5 set /trajectory/t 21 1e12
  edit ext_qshape.h5   ext_sim.h5 real /trajectory/q 0.5 21 3
  edit ext_tint.h5     ext_sim.h5 int /trajectory/t 1 21   # integers read as reals: t = 1 1 1 ...
  edit ext_links.h5    ext_sim.h5 attr-i0 / links 99
  edit ext_wide.h5     ext_sim.h5 real /trajectory/wide 0.5 2 100000
  edit ext_wide20k.h5  ext_sim.h5 real /trajectory/wide 0.5 2 20000
  # sweeps: a MEGNO and a lambda1 map of the same 4 x 4 pixels, and edits
  "$DPEND" sweep --n 4 --t-end 1 --indicator megno --output ext_m.h5 --quiet > /dev/null
  "$DPEND" sweep --n 4 --t-end 2 --indicator lambda1 --output ext_l.h5 --quiet > /dev/null
  edit ext_m_nan.h5     ext_m.h5 real /sweep/megno nan 4 4
  edit ext_m_inf.h5     ext_m.h5 real /sweep/megno inf 4 4
  edit ext_m_neg.h5     ext_m.h5 real /sweep/megno -1 4 4
  edit ext_m_huge.h5    ext_m.h5 huge /sweep/megno 1099511627776 2
  edit ext_m_nostatus.h5 ext_m.h5 del /sweep/status
  edit ext_m_status.h5  ext_m.h5 int /sweep/status 1 4 3
  edit ext_m_status9.h5 ext_m.h5 int /sweep/status 9 4 4
  edit ext_m_noaxis.h5  ext_m.h5 del /sweep/axis1
  edit ext_m_axis.h5    ext_m.h5 ramp /sweep/axis1 5
  edit ext_m_tend.h5    ext_m.h5 attr-real /sweep t_end nan
  edit ext_m_links.h5   ext_m.h5 attr-i0 /sweep links 99
  edit ext_m_tau.h5     ext_m.h5 attr-real /sweep sqrt_l1_over_g nan
  edit ext_m_cfgt.h5    ext_m.h5 attr-sub /sweep config 't_end = 1.0000000000000000E+000' 't_end = NaN'
  edit ext_m_cfgn.h5    ext_m.h5 attr-sub /sweep config 'n1 = 4' 'n1 = 99'
  edit ext_m_units.h5   ext_m.h5 attr-int /sweep/megno units 4
  edit ext_s_nostatus.h5 sweep.h5 del /sweep/status
  edit ext_s_status.h5  sweep.h5 int /sweep/status 1 8 7
  edit ext_s_noaxis.h5  sweep.h5 del /sweep/axis1
  edit ext_s_axis.h5    sweep.h5 ramp /sweep/axis1 9
  edit ext_s_h.h5       sweep.h5 attr-real /sweep h nan
  edit ext_s_tflip.h5   sweep.h5 real /sweep/t_flip inf 8 8
  edit ext_s_huge.h5    sweep.h5 huge /sweep/t_flip 1099511627776 2
  edit ext_s_cfgt.h5    sweep.h5 attr-sub /sweep config 't_end = 1.0000000000000000E+000' 't_end = NaN'
  edit ext_s_links.h5   sweep.h5 attr-i0 /sweep links 99
  edit ext_l_list.h5    sweep_list.h5 real /sweep/t_flip nan 3
  printf 't,theta1\n0,0.1\n0.1,0.09\n0.2,0.06\n0.3,0.02\n0.4,-0.03\n' > ext_fit.csv
) > /dev/null 2> "$_ext_tool/fixtures.err" ||
  { echo "external_files.sh: could not make the fixtures:" >&2; cat "$_ext_tool/fixtures.err" >&2
    cat "$_ext_tool/build.log" >&2 2>/dev/null; }
rm -rf "$_ext_tool"

T=(--fps 5 --size 64x64)   # tiny animations

# ---- sizes declared by the file, checked before allocation (was "Error allocating
# 17592186044416 bytes" and a backtrace)
refuse  ext-export-huge        trajectory/q -- export ext_big.h5 q
refuse  ext-export-huge-csv    trajectory/q -- export ext_big.h5 --csv t q
refuse  ext-export-huge-t      trajectory/t -- export ext_bigt.h5 t
refuse  ext-export-huge-matrix trajectory/q -- export ext_big.h5 --matrix q
refuse  ext-ani-huge           trajectory/q -- animate ext_big.h5 --output a.gif "${T[@]}"
refuse  ext-ani-huge-t         trajectory/t -- animate ext_bigt.h5 --output a.gif "${T[@]}"
refuse  ext-agr-huge           sweep/megno  -- sweep-compare ext_m_huge.h5 ext_l.h5 --agreement
refuse  ext-cmp-huge           sweep/t_flip -- sweep-compare ext_s_huge.h5 sweep.h5
# ---- attribute and dataset types checked before use (was a segfault, exit 139)
refuse  ext-list-units-int     units        -- export ext_units.h5 --list
refuse  ext-list-desc-int      description  -- export ext_desc.h5 --list
refuse  ext-csv-units-int      units        -- export ext_units.h5 --csv t
refuse  ext-list-sweep-units   units        -- export ext_m_units.h5 --list
refuse  ext-ani-t-int          'does not increase' -- animate ext_tint.h5 --output a.gif "${T[@]}"
refuse  ext-ani-links-99       links        -- animate ext_links.h5 --output a.gif "${T[@]}"
refuse  ext-ani-q-shape        trajectory   -- animate ext_qshape.h5 --output a.gif "${T[@]}"
# ---- an output never replaces an input, with or without --force
refuse  ext-ani-self           input   -- animate ext_sim.h5 --output ext_sim.h5 "${T[@]}"
refuse  ext-ani-self-force     input   -- animate ext_sim.h5 --output ext_sim.h5 --force "${T[@]}"
refuse  ext-ani-self-dot       input   -- animate ext_sim.h5 --output ./ext_sim.h5 --force "${T[@]}"
refuse  ext-ani-hard-link      input   -- animate ext_sim.h5 --output ext_sim_link.h5 --force "${T[@]}"
refuse  ext-ani-overlay-self   input   -- animate existing.h5 --overlay ext_sim.h5 \
                                          --output ext_sim.h5 --force "${T[@]}"
refuse  ext-agr-self-a         input   -- sweep-compare ext_m.h5 ext_l.h5 --agreement \
                                          --output ext_m.h5 --force
refuse  ext-agr-self-b         input   -- sweep-compare ext_m.h5 ext_l.h5 --agreement \
                                          --output ext_l.h5 --force
refuse  ext-agr-self-noforce   input   -- sweep-compare ext_m.h5 ext_l.h5 --agreement \
                                          --output ext_m.h5
refuse  ext-sim-config-self    input   -- simulate --config simulate.nml --t-end 0.1 \
                                          --output simulate.nml --force
refuse  ext-sweep-icfile-self  input   -- sweep --ic-file list.txt --t-end 1 --quiet \
                                          --output list.txt --force
refuse  ext-fit-data-self      input   -- fit ext_fit.csv --output ext_fit.csv --force
# ---- sweep-compare checks the data, not only the config attribute
refuse  ext-agr-all-nan        sweep/megno  -- sweep-compare ext_m_nan.h5 ext_l.h5 --agreement
refuse  ext-agr-inf            sweep/megno  -- sweep-compare ext_m_inf.h5 ext_l.h5 --agreement
refuse  ext-agr-negative       sweep/megno  -- sweep-compare ext_m_neg.h5 ext_l.h5 --agreement
refuse  ext-agr-no-status      sweep/status -- sweep-compare ext_m_nostatus.h5 ext_l.h5 --agreement
refuse  ext-agr-status-short   sweep/status -- sweep-compare ext_m_status.h5 ext_l.h5 --agreement
refuse  ext-agr-status-9       sweep/status -- sweep-compare ext_m_status9.h5 ext_l.h5 --agreement
refuse  ext-agr-no-axis1       axis1        -- sweep-compare ext_m_noaxis.h5 ext_l.h5 --agreement
refuse  ext-agr-axis1-long     axis1        -- sweep-compare ext_m_axis.h5 ext_l.h5 --agreement
refuse  ext-agr-tend-nan       t_end        -- sweep-compare ext_m_tend.h5 ext_l.h5 --agreement
refuse  ext-agr-links-99       links        -- sweep-compare ext_m_links.h5 ext_l.h5 --agreement
refuse  ext-agr-tau-nan        sqrt_l1_over_g -- sweep-compare ext_m_tau.h5 ext_l.h5 --agreement
refuse  ext-agr-cfg-tend-nan   t_end        -- sweep-compare ext_m_cfgt.h5 ext_l.h5 --agreement
refuse  ext-agr-cfg-n1         n1           -- sweep-compare ext_m_cfgn.h5 ext_l.h5 --agreement
refuse  ext-cmp-no-status      sweep/status -- sweep-compare ext_s_nostatus.h5 sweep.h5
refuse  ext-cmp-status-short   sweep/status -- sweep-compare sweep.h5 ext_s_status.h5
refuse  ext-cmp-no-axis1       axis1        -- sweep-compare ext_s_noaxis.h5 sweep.h5
refuse  ext-cmp-axis1-long     axis1        -- sweep-compare ext_s_axis.h5 sweep.h5
refuse  ext-cmp-h-nan          'attribute h' -- sweep-compare ext_s_h.h5 sweep.h5
refuse  ext-cmp-tflip-inf      t_flip       -- sweep-compare ext_s_tflip.h5 sweep.h5
refuse  ext-cmp-cfg-tend-nan   t_end        -- sweep-compare ext_s_cfgt.h5 ext_s_cfgt.h5
refuse  ext-cmp-links-99       links        -- sweep-compare ext_s_links.h5 sweep.h5
succeed ext-cmp-list-no-flips                -- sweep-compare ext_l_list.h5 sweep_list.h5
succeed ext-agr-ok                           -- sweep-compare ext_m.h5 ext_l.h5 --agreement \
                                                --output ext_agr.h5
# ---- export --csv is linear in the columns (a (2, 100000) dataset took > 100 s)
succeed ext-csv-wide-100k      -- export ext_wide.h5 --csv wide
succeed ext-csv-wide-20k       -- export ext_wide20k.h5 --csv /trajectory/wide
succeed ext-plain-wide-100k    -- export ext_wide.h5 wide
# ---- animate draws only trajectories; --matrix takes a 2-D dataset
refuse  ext-ani-t-constant     'does not increase' -- animate ext_t0.h5 --output a.gif "${T[@]}"
refuse  ext-ani-q-1e300        trajectory/q -- animate ext_q300.h5 --output a.gif "${T[@]}"
refuse  ext-ani-t-nan          non-finite   -- animate ext_tnan.h5 --output a.gif "${T[@]}"
refuse  ext-ani-t-1e12         trajectory/t -- animate ext_tbig.h5 --output a.gif "${T[@]}"
refuse  ext-ani-overlay-t0     'does not increase' -- animate ext_sim.h5 --overlay ext_t0.h5 \
                                                      --output a.gif "${T[@]}"
refuse  ext-matrix-1d          'rank 1'     -- export ext_sim.h5 --matrix t
refuse  ext-matrix-1d-energy   'rank 1'     -- export ext_sim.h5 --matrix energy
# ---- --frames where nothing can be created is bad input (exit 2, was 1). CI runs
# as root, where a mode-0555 directory still takes files and no read-only mount can
# be made; /proc and /sys refuse new files to root too.
refuse  ext-ani-frames-proc    frames -- animate ext_sim.h5 --output a.gif --frames /proc "${T[@]}"
refuse  ext-ani-frames-sys     frames -- animate ext_sim.h5 --output a.gif --frames /sys "${T[@]}"
