#!/usr/bin/env bash
# Special reliability test: one resolution of every setting, seen from the files.
# For every model and body kind, every command that takes it, and quantities of the
# model, a run is given the quantity once through a flag and once through each
# namelist group that holds it (&pendulum, &model). Each run's file must record the
# value given (its attribute of the quantity: the root's, the sweep's /sweep or the
# study's /config), and the run's own numbers must equal those of the run given the
# value the other way, bit for bit (the energy at t = 0 of the chaos commands, the
# trajectory's energies, a sweep's map of energies, a fit's estimates, a study's
# reference energies). A capability a model lacks is refused the same way whichever
# way the value came. Environment (set by the reliability runner): DPEND, ROOT,
# SCRATCH (the cwd). Exit 0: pass, other: fail. One line per command and quantity.
set -uo pipefail
: "${DPEND:?DPEND must name the dpend binary}" "${ROOT:?}" "${SCRATCH:?}"
cd "$SCRATCH" || exit 1
failures=0 checked=0
pass() { checked=$((checked + 1)); }
fail() { failures=$((failures + 1)); printf 'FAIL %s\n' "$1"; }
# attr FILE NAME: the attribute NAME of /, /sweep or /config (first found), as text
attr() {
  local g v
  for g in / /sweep /config; do
    v=$(h5dump -m %.17g -a "${g%/}/$2" "$1" 2>/dev/null | sed -n '/DATA {/,/}/p' | sed -n 's/^ *([0-9,]*): *//p' |
        tr -d ' \n')
    [[ -n $v ]] && { printf '%s' "$v"; return; }
  done
}
# same VALUE_GIVEN RECORDED: the numbers agree (a list "2,1" against "2,1")
same() {
  awk -v a="$1" -v b="$2" 'BEGIN { n = split(a, x, ","); m = split(b, y, ",")
    if (n != m) exit 1
    for (i = 1; i <= n; i++) { d = x[i] - y[i]; if (d < 0) d = -d
      s = (x[i] < 0 ? -x[i] : x[i]); if (d > 1e-12 * (s > 1 ? s : 1)) exit 1 }
    exit 0 }'
}
# numbers FILE COMMAND: the run's own numbers, as text
numbers() {
  case $2 in
    simulate) h5dump -d /trajectory/energy "$1" 2>/dev/null | sed -n '/DATA {/,/}/p' ;;
    sweep) h5dump -d /sweep/energy0 -d /sweep/final/q1 "$1" 2>/dev/null | sed -n '/DATA {/,/}/p' ;;
    fit) h5dump -d /fit/estimate "$1" 2>/dev/null | sed -n '/DATA {/,/}/p' ;;
    study) h5dump -A /config "$1" > /dev/null 2>&1; attr "$1" g ;;
    *) attr "$1" energy0 ;;
  esac
}

head -n 60 "$ROOT/data/fit_mass_length.csv" > fit.csv
EL=(--model elastic --q 1.2,-1)
EL_AXES=(--axis1 r --axis2 phi --min1 1 --max1 1.4 --min2 -1 --max2 1 --indicator megno)
# the commands, each with the tiny run it makes (OUT is replaced by the file's name)
declare -A RUN=(
  [simulate]="simulate --t-end 0.2 --output OUT"
  [lyapunov]="lyapunov --t-end 1 --output OUT"
  [indicators]="indicators --t-end 1 --output OUT"
  [divergence]="divergence --t-end 0.5 --output-dt 0.1 --lyapunov-t 0 --output OUT"
  [poincare]="poincare --t-end 5 --output OUT"
  [sweep]="sweep --n 2 --t-end 0.5 --quiet --output OUT"
  [fit]="fit fit.csv --output OUT"
)
ORDER=(simulate lyapunov indicators divergence poincare sweep fit)
# A kind: NAME|EXTRA FLAGS (the model and body, every way)|QUANTITY|FLAGS|&pendulum TEXT
#         |&model TEXT|ATTRIBUTE=VALUE ... (what the file must record)
KINDS=(
  "rods m1|--q1 0.3|m1|--m1 2|m1 = 2|name='pendulum', m = 2, 1|m1=2 m2=1"
  "rods g|--q1 0.3|g|--g 9.5|g = 9.5|name='pendulum', g = 9.5|g=9.5"
  "rods l2|--q1 0.3|l2|--l2 0.8|l2 = 0.8|name='pendulum', l = 1, 0.8|l1=1 l2=0.8"
  "point masses m2|--q1 0.3 --body point|m2|--m2 0.5|m2 = 0.5|name='pendulum', m = 1, 0.5|m2=0.5 com2=1 inertia2=0"
  "bodies com2|--q1 0.3 --inertia 0.08,0.03|com|--com 0.5,0.4|com = 0.5, 0.4|name='pendulum', com = 0.5, 0.4|com1=0.5 com2=0.4 inertia2=0.03"
  "chain of 3 m|--links 3 --q 0.3,0.2,0.1|m|--m 1,2,3|m = 1, 2, 3|name='pendulum', links = 3, m = 1, 2, 3|m=1,2,3"
  "rods damping|--q1 0.3|damping|--damping 0.1,0.05|damping = 0.1, 0.05|name='pendulum', damping = 0.1, 0.05|c1=0.1 c2=0.05"
  "bodies inertia|--q1 0.3 --com 0.5,0.4|inertia|--inertia 0.08,0.03|inertia = 0.08, 0.03|name='pendulum', inertia = 0.08, 0.03|inertia1=0.08 inertia2=0.03 com2=0.4"
  "elastic k|--model elastic --q 1.2,-1|k|--k 30||name='elastic', k = 30|k=30"
  "elastic g|--model elastic --q 1.2,-1|g|--g 9.5|g = 9.5|name='elastic', g = 9.5|g=9.5"
  "elastic l0|--model elastic --q 1.2,-1|l0|--l0 0.9||name='elastic', l0 = 0.9|l0=0.9"
)
for kind in "${KINDS[@]}"; do
  IFS='|' read -r label extra qty flags pend model expect <<< "$kind"
  read -r -a EXTRA <<< "$extra"
  read -r -a FLAGS <<< "$flags"
  ways=(flag)
  [[ -n $pend ]] && { printf '&pendulum %s /\n' "$pend" > "p_$qty.nml"; ways+=(pendulum); }
  [[ -n $model ]] && { printf '&model %s /\n' "$model" > "m_$qty.nml"; ways+=(model); }
  for cmd in "${ORDER[@]}"; do
    [[ $cmd == fit && $extra == *elastic* ]] && continue   # the fit data are the pendulum's
    [[ $cmd == fit && $extra == *links* ]] && continue
    read -r -a base <<< "${RUN[$cmd]}"
    # the sweep of the elastic pendulum has no default axes
    more=(); [[ $cmd == sweep && $extra == *elastic* ]] && more=("${EL_AXES[@]}")
    # fit takes no initial state: the data give it
    args=("${EXTRA[@]}")
    if [[ $cmd == fit ]]; then
      args=(); for a in "${EXTRA[@]}"; do case $a in --q1|0.3) ;; *) args+=("$a") ;; esac; done
    fi
    ref_rc="" ref_nums="" ref_way=""
    for way in "${ways[@]}"; do
      out="$cmd-$qty-$way.h5"
      cmdline=("${base[@]/OUT/$out}" "${args[@]}" "${more[@]}")
      case $way in
        flag) cmdline+=("${FLAGS[@]}") ;;
        pendulum) cmdline+=(--config "p_$qty.nml") ;;
        model) cmdline+=(--config "m_$qty.nml") ;;
      esac
      rc=0
      "$DPEND" "${cmdline[@]}" > "$out.log" 2>&1 < /dev/null || rc=$?
      what="$label, $cmd, $way"
      if [[ -z $ref_rc ]]; then ref_rc=$rc; ref_way=$way
      elif [[ $rc != "$ref_rc" ]]; then
        fail "$what: exit $rc, but $ref_rc given as $ref_way: $(tail -n 1 "$out.log")"; continue
      fi
      if [[ $rc == 2 ]]; then pass; continue; fi   # refused alike: a capability it lacks
      if [[ $rc != 0 ]]; then fail "$what: exit $rc: $(tail -n 1 "$out.log")"; continue; fi
      for kv in $expect; do
        k=${kv%%=*} v=${kv#*=} got=$(attr "$out" "$k")
        same "$v" "$got" || fail "$what: the file records $k = '$got', given $v"
      done
      nums=$(numbers "$out" "$cmd")
      [[ -n $nums ]] || { fail "$what: no numbers to compare in $out"; continue; }
      if [[ -z $ref_nums ]]; then ref_nums=$nums
      elif [[ $nums != "$ref_nums" ]]; then fail "$what: its numbers differ from the run given it as $ref_way"
      else pass; fi
    done
  done
done
# the study (pendulum parameters only): g as a flag, in &pendulum and in &model
printf '&pendulum g = 9.5 /\n' > study_p.nml
printf "&model name='pendulum', g = 9.5 /\n" > study_m.nml
S=(study --quick --no-figures --methods rk4,verlet)
ref=""
for way in flag pendulum model; do
  case $way in flag) a=(--g 9.5) ;; pendulum) a=(--config study_p.nml) ;; model) a=(--config study_m.nml) ;; esac
  if "$DPEND" "${S[@]}" "${a[@]}" --output "study-$way.h5" > "study-$way.log" 2>&1 < /dev/null; then
    got=$(attr "study-$way.h5" g)
    same 9.5 "$got" || fail "study, $way: /config records g = '$got', given 9.5"
    h5dump -d /references "study-$way.h5" > /dev/null 2>&1
    nums=$(h5ls -r "study-$way.h5" | awk '{print $1}' | grep -m 3 -E 'energy|error' |
           while read -r d; do h5dump -d "$d" "study-$way.h5" | sed -n '/DATA {/,/}/p'; done)
    if [[ -z $ref ]]; then ref=$nums
    elif [[ $nums != "$ref" ]]; then fail "study, $way: its numbers differ from the run given g as a flag"
    else pass; fi
  else
    fail "study, $way: exit status: $(tail -n 1 "study-$way.log")"
  fi
done
printf 'ok   %s runs agreed with the runs given the same values another way\n' "$checked"
exit $((failures > 0))
