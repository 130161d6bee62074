# shellcheck shell=bash
# Shared by the plot scripts (source it: . "$here/lib/output.sh"). Two rules:
#
# 1. No file or directory name, and no text read from an HDF5 file, is ever pasted
#    into gnuplot code or a shell string: names reach gnuplot only as data, through
#    `gnuplot -c SCRIPT.gp ARG1 ...` (ARG1.. inside the script), made absolute first
#    (so that none starts with '-', '<', '|' or '~', which gnuplot or a program would
#    read as an option, a pipe or a home directory); titles are escaped for gnuplot's
#    enhanced text as data (plot_enhanced).
# 2. Figures are written into a temporary directory with a unique name inside the
#    target directory and moved into place (one rename each) only after gnuplot has
#    succeeded; on failure the temporaries are removed and the old figures are kept.
#
#   plot_init NAME                 this script's name for messages; traps for cleanup
#   plot_dpend                     sets `dpend`: $DPEND, or the release binary (built
#                                  once, not at every call as scripts/dpend would)
#   plot_abs VAR PATH              VAR := PATH made absolute (no subshell: a name ending
#                                  in a newline stays intact)
#   plot_dir VAR PATH              VAR := the directory part of PATH ('.' if none)
#   plot_base VAR PATH             VAR := the last component of PATH
#   plot_enhanced VAR TEXT         VAR := TEXT with gnuplot's enhanced-text markup
#                                  escaped and control characters shown as '?'
#   plot_number VAR VALUE WHAT     VAR := VALUE if it is a number (or inf/nan), else
#                                  exit 2 naming WHAT
#   plot_tmpdir                    sets `tmp`: a private scratch directory (removed at exit)
#   plot_begin DIR NAME...         create DIR if needed; refuse (exit 2) if DIR/NAME exists
#                                  and is not a regular file; sets `figdir`, the unique
#                                  temporary directory DIR/.dpend-plot.XXXXXX where
#                                  gnuplot writes figdir/NAME
#   plot_run COMMAND...            run COMMAND (gnuplot -c ...); on success move every
#                                  figdir/NAME to DIR/NAME, else remove figdir, keep the
#                                  old figures and exit 1
#                                  (and append figdir/keys.txt, the key entries drawn,
#                                  to $DPEND_PLOT_KEYS if set: the figure test)
#   plot_discard                   remove figdir (also done at exit)

plot_name=plot
figdir=""
fig_target=""
fig_names=()
tmp=""

plot_cleanup() {
  [[ -n "$figdir" ]] && rm -rf -- "$figdir"
  [[ -n "$tmp" ]] && rm -rf -- "$tmp"
  return 0
}

plot_init() {
  plot_name=$1
  trap plot_cleanup EXIT
  trap 'exit 129' HUP
  trap 'exit 130' INT
  trap 'exit 143' TERM
}

plot_fail() { # plot_fail STATUS MESSAGE
  printf '%s: %s\n' "$plot_name" "$2" >&2
  exit "$1"
}

plot_abs() {
  case $2 in
    /*) printf -v "$1" '%s' "$2" ;;
    *) printf -v "$1" '%s/%s' "$PWD" "$2" ;;
  esac
}

plot_dir() {
  local p=$2
  while [[ $p == */ && $p != / ]]; do p=${p%/}; done
  if [[ $p != */* ]]; then printf -v "$1" '%s' .; return; fi
  p=${p%/*}
  while [[ $p == */ ]]; do p=${p%/}; done
  [[ -n $p ]] || p=/
  printf -v "$1" '%s' "$p"
}

plot_base() {
  local p=$2
  while [[ $p == */ && $p != / ]]; do p=${p%/}; done
  [[ $p == / ]] || p=${p##*/}
  printf -v "$1" '%s' "$p"
}

plot_enhanced() {
  local s=$2 c
  s=${s//[[:cntrl:]]/?}
  s=${s//\\/\\\\}
  for c in _ ^ '{' '}' @ '&' '~'; do s=${s//"$c"/\\$c}; done
  printf -v "$1" '%s' "$s"
}

plot_number() {
  local v=$2
  if [[ ! $v =~ ^[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eEdD][-+]?[0-9]+)?$ &&
        ! ${v,,} =~ ^[-+]?(inf|infinity|nan)$ ]]; then
    plot_fail 2 "$3 is not a number: '$v'"
  fi
  v=${v//[dD]/e}
  printf -v "$1" '%s' "$v"
}

plot_tmpdir() {
  local t
  t=$(mktemp -d) || plot_fail 1 "cannot create a temporary directory"
  plot_abs tmp "$t"
}

plot_dpend() {
  if [[ -n "${DPEND:-}" ]]; then
    dpend=$DPEND
    return
  fi
  local root
  root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
  # shellcheck source-path=SCRIPTDIR source=../flags.sh
  . "$root/scripts/flags.sh"
  (cd "$root" && fpm build --profile release --flag "$RELEASE_FLAGS" >/dev/null 2>&1) ||
    plot_fail 1 "release build failed"
  dpend=$(cd "$root" && fpm run dpend --profile release --flag "$RELEASE_FLAGS" \
    --runner echo 2>/dev/null | tail -n 1)
  [[ "$dpend" == /* ]] || dpend="$root/$dpend"
}

plot_begin() {
  local dir name t
  plot_abs dir "$1"
  shift
  mkdir -p -- "$dir" || plot_fail 1 "cannot create the directory '$dir'"
  for name in "$@"; do
    if [[ -L "$dir/$name" || (-e "$dir/$name" && ! -f "$dir/$name") ]]; then
      plot_fail 2 "'$dir/$name' exists and is not a regular file; not replaced"
    fi
  done
  t=$(mktemp -d -- "$dir/.dpend-plot.XXXXXX") ||
    plot_fail 1 "cannot write in '$dir' (creating a temporary directory failed)"
  figdir=$t
  fig_target=$dir
  fig_names=("$@")
}

plot_discard() {
  [[ -n "$figdir" ]] && rm -rf -- "$figdir"
  figdir=""
}

plot_run() {
  local name
  if ! "$@"; then
    plot_discard
    plot_fail 1 "gnuplot failed; no figure written, the old ones (if any) are kept"
  fi
  for name in "${fig_names[@]}"; do
    if [[ ! -s "$figdir/$name" ]]; then
      plot_discard
      plot_fail 1 "gnuplot wrote no $name; no figure written, the old ones are kept"
    fi
  done
  for name in "${fig_names[@]}"; do
    mv -f -T -- "$figdir/$name" "$fig_target/$name" ||
      { plot_discard; plot_fail 1 "cannot move the new $name into '$fig_target'"; }
  done
  # the key entries the figures drew (figdir/keys.txt, scripts/plot/style.gp), for the
  # figure test: appended to $DPEND_PLOT_KEYS when it names a file
  if [[ -n "${DPEND_PLOT_KEYS:-}" && -f "$figdir/keys.txt" ]]; then
    cat -- "$figdir/keys.txt" >> "$DPEND_PLOT_KEYS" ||
      { plot_discard; plot_fail 1 "cannot append the key entries to '$DPEND_PLOT_KEYS'"; }
  fi
  rm -f -- "$figdir/keys.txt"
  rmdir -- "$figdir" 2>/dev/null || rm -rf -- "$figdir"
  figdir=""
}
