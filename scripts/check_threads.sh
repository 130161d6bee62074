#!/usr/bin/env bash
# Code run by several OpenMP threads at once must not touch gfortran 12's static
# string lengths (docs/architecture.md, "Threads"): a call of a function whose
# result is `character(len=:), allocatable` keeps the result's length in a static
# variable of the caller, named slen.N, so two threads in that caller at once can
# read each other's length (a method name 'rk4' read with length 4: the crash of
# the study in CI on 2026-11-27).
#
# This check reads the release binary: from every OpenMP region (the compiler's
# outlined *._omp_fn.* functions) it follows the direct calls and tail jumps, except
# those made inside a critical section (between GOMP_critical*_start and _end in a
# function's code), and fails if it reaches a function that refers to an slen
# variable outside a critical section. It prints the chain of calls to each one.
# Calls through a procedure pointer or a type-bound procedure (vtable), and the
# hidden _copy and _final calls of allocate(source=) and intent(out), are not
# followed: the models' and methods' numerical code reached that way must not call
# such functions either (the review of a change to it checks). Any critical section
# counts, whatever its name. A binary with no OpenMP region or no visible slen
# reference fails (exit 2): the check would have nothing to see.
#
# Usage: scripts/check_threads.sh [binary]   (default: the release build of dpend)
set -euo pipefail
cd "$(dirname "$0")/.."
bin=${1:-}
if [[ -z "$bin" ]]; then
  . scripts/flags.sh
  log=$(fpm build --profile release --flag "$RELEASE_FLAGS" 2>&1) ||
    { printf '%s\n' "$log" | tail -n 30; echo "check_threads: the release build failed" >&2; exit 2; }
  bin=$(fpm run dpend --profile release --flag "$RELEASE_FLAGS" --runner echo 2> /dev/null |
    tail -n 1)
fi
[[ -x "$bin" ]] || { echo "check_threads: no executable '$bin'" >&2; exit 2; }
command -v objdump > /dev/null || { echo "check_threads: objdump is not installed" >&2; exit 2; }
objdump -d --no-show-raw-insn "$bin" | awk '
  # One function at a time: its instructions, then a walk of its control flow from
  # its entry with the depth of critical sections (so that code the compiler placed
  # after the end call of the section, but inside it, counts as inside).
  function base(s) { sub(/\+0x[0-9a-f]+$/, "", s); return s }
  function noreturn(t) {
    return t ~ /^(_gfortran_(error_stop_string|error_stop_numeric|stop_string|stop_numeric|runtime_error|runtime_error_at|os_error|os_error_at)|abort|exit|__stack_chk_fail)(@plt)?$/
  }
  function walk(   i, d, top, k, cold) {
    cold = (fn ~ /\.cold$/)
    top = 0
    delete seen_at
    if (cold) { for (i = 1; i <= ni; i++) { stack_i[++top] = i; stack_d[top] = 0 } }
    else if (ni > 0) { stack_i[++top] = 1; stack_d[top] = 0 }
    while (top > 0) {
      i = stack_i[top]; d = stack_d[top]; top--
      while (i >= 1 && i <= ni && !((i, d) in seen_at)) {
        seen_at[i, d] = 1
        if (d == 0 && has_slen[i] && !(fn in slen)) slen[fn] = addr[i]
        if (kind[i] == "start") { d = (d < 4) ? d + 1 : d; i++; continue }
        if (kind[i] == "end") { d = (d > 0) ? d - 1 : 0; i++; continue }
        if (kind[i] == "call") {
          if (d == 0) edge(target[i])
          if (noreturn(target[i])) break
          i++; continue
        }
        if (kind[i] == "tail") { if (d == 0) edge(target[i]); break }
        if (kind[i] == "tailcc") { if (d == 0) edge(target[i]); i++; continue }
        if (kind[i] == "jmp") { i = (target[i] in at) ? at[target[i]] : 0; continue }
        if (kind[i] == "jcc") {
          if (target[i] in at) { stack_i[++top] = at[target[i]]; stack_d[top] = d }
          i++; continue
        }
        if (kind[i] == "ijmp") {   # a jump table: any instruction, at this depth
          for (k = 1; k <= ni; k++) { stack_i[++top] = k; stack_d[top] = d }
          break
        }
        if (kind[i] == "ret") break
        i++
      }
    }
  }
  function edge(t) {
    if (t == "" || t == fn || t ~ /@plt$/) return
    if (!((fn, t) in linked)) { linked[fn, t] = 1; out[fn] = out[fn] " " t }
  }
  function finish() {
    if (fn != "") walk()
    ni = 0; delete at; delete kind; delete target; delete has_slen; delete addr
  }
  /^[0-9a-f]+ <.*>:$/ {
    finish()
    fn = $2; sub(/^</, "", fn); sub(/>:$/, "", fn)
    if (fn ~ /\._omp_fn\./) root[fn] = 1
    next
  }
  /^ +[0-9a-f]+:\t/ {
    a = $1; sub(/:$/, "", a)
    ni++; addr[ni] = a; at[a] = ni; kind[ni] = "other"; target[ni] = ""
    has_slen[ni] = ($0 ~ /<slen\./)
    if (has_slen[ni]) n_slen++
    line = $0; sub(/^ +[0-9a-f]+:\t/, "", line)
    sub(/^(notrack|bnd|repz|rep) +/, "", line)
    split(line, w, / +/)
    op = w[1]
    t = ""
    if (line ~ /<[^>]*>/) { t = line; sub(/^[^<]*</, "", t); sub(/>.*$/, "", t) }
    if (op ~ /^call/) {
      if (line ~ /\*/ || t == "") next   # indirect: not followed
      t = base(t)
      if (t ~ /^GOMP_critical(_name)?_start/) kind[ni] = "start"
      else if (t ~ /^GOMP_critical(_name)?_end/) kind[ni] = "end"
      else { kind[ni] = "call"; target[ni] = t }
    } else if (op ~ /^j/) {
      jmp = (op == "jmp" || op == "jmpq")
      if (line ~ /\*/) { kind[ni] = jmp ? "ijmp" : "other"; next }
      if (base(t) != fn) { kind[ni] = jmp ? "tail" : "tailcc"; target[ni] = base(t); next }
      kind[ni] = jmp ? "jmp" : "jcc"; target[ni] = w[2]
    } else if (op ~ /^ret/ || op == "ud2" || op == "hlt") kind[ni] = "ret"
    next
  }
  END {
    finish()
    # nothing to check is a failure: a binary without OpenMP, stripped, or whose
    # references objdump does not name (then no slen is seen at all)
    if (length(root) == 0 || n_slen == 0) {
      printf "check_threads: nothing to check: %d OpenMP regions, %d references to slen variables (a release build with -fopenmp, not stripped, is needed)\n", length(root), n_slen
      exit 2
    }
    n = 0
    for (r in root) { queue[++n] = r; from[r] = "" }
    for (i = 1; i <= n; i++) {
      f = queue[i]
      k = split(out[f], ts, " ")
      for (j = 1; j <= k; j++) if (!(ts[j] in from)) { from[ts[j]] = f; queue[++n] = ts[j] }
    }
    bad = 0
    for (i = 1; i <= n; i++) {
      f = queue[i]
      if (!(f in slen)) continue
      bad++
      path = f
      for (g = from[f]; g != ""; g = from[g]) path = g " -> " path
      print "check_threads: " f " (slen at " slen[f] ") runs in threads: " path
    }
    printf "check_threads: %d functions reached from %d OpenMP regions, %d with a static string length (%d slen references in the binary)\n", n, length(root), bad, n_slen
    exit bad > 0
  }'
