#!/usr/bin/env bash
# The Python package dpend (pyproject.toml, meson.build, python/): install it into a
# fresh virtual environment with `pip install .`, run one simulation from Python and
# the package's tests (python/tests), whose bitwise comparison with the command line
# runs the release binary given by --dpend.
#
# Usage: scripts/python_package.sh --dpend PATH [--python PYTHON] [--keep DIR]
#                                  [--notebook DIR] [--screenshots DIR]
#   --dpend PATH     the release dpend binary (scripts/dpend's build, e.g.
#                    build/gfortran_*/app/dpend); the tests run it as DPEND_CLI
#   --python PYTHON  the interpreter that makes the venv (default python3; Debian's
#                    /usr/bin/python3 needs the package python3-venv)
#   --keep DIR       make the venv in DIR and keep it (default: a temporary one,
#                    removed at the end)
#   --notebook DIR   also execute examples/python/tour.ipynb (nbclient; with
#                    matplotlib, ipykernel from PyPI) into DIR with its figures
#   --screenshots DIR  the browser test of dpend explore (python/tests/test_explore.py:
#                    Playwright from PyPI, Debian's chromium) saves its screenshots in
#                    DIR (default: pytest's temporary folder)
# Needs PyPI (meson-python, meson, numpy, h5py, xarray, pytest, playwright), gfortran,
# gcc, ninja or PyPI's, the Debian packages of the command line's build (HDF5,
# LAPACK) and chromium (scripts/setup.sh). Exit status: 0 all passed, 1 a step failed, 2 bad usage.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
dpend="" python=python3 keep="" notebook="" screenshots=""
while (($#)); do
  case "$1" in
    --dpend) dpend="${2:?--dpend needs a path}"; shift 2 ;;
    --python) python="${2:?--python needs an interpreter}"; shift 2 ;;
    --keep) keep="${2:?--keep needs a folder}"; shift 2 ;;
    --notebook) notebook="${2:?--notebook needs a folder}"; shift 2 ;;
    --screenshots) screenshots="${2:?--screenshots needs a folder}"; shift 2 ;;
    -h|--help) sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "python_package.sh: unknown argument '$1' (--dpend PATH, --python, --keep," \
         "--notebook, --screenshots)" >&2
       exit 2 ;;
  esac
done
if [[ -z "$dpend" ]]; then
  echo "python_package.sh: --dpend PATH is required (the release dpend binary)" >&2; exit 2
fi
if [[ ! -x "$dpend" ]]; then
  echo "python_package.sh: --dpend '$dpend' is not an executable file" >&2; exit 2
fi
dpend="$(cd "$(dirname "$dpend")" && pwd)/$(basename "$dpend")"
if [[ -n "$notebook" ]]; then   # relative to where the script was started
  mkdir -p "$notebook" && notebook="$(cd "$notebook" && pwd)"
fi
if [[ -n "$screenshots" ]]; then
  mkdir -p "$screenshots" && screenshots="$(cd "$screenshots" && pwd)"
fi
if [[ -n "$keep" ]]; then
  mkdir -p "$(dirname "$keep")" && keep="$(cd "$(dirname "$keep")" && pwd)/$(basename "$keep")"
fi

fail() { echo "python_package.sh: FAILED: $*" >&2; exit 1; }
work="$(mktemp -d "${TMPDIR:-/tmp}/dpend-python.XXXXXX")"
trap 'rm -rf "$work"' EXIT
venv="${keep:-$work/venv}"

echo "python_package.sh: venv $venv ($("$python" --version 2>&1))"
"$python" -m venv "$venv" ||
  fail "$python -m venv (Debian: apt-get install python3-venv)"
py="$venv/bin/python"
"$py" -m pip install --quiet --upgrade pip || fail "pip upgrade in the venv"

echo "python_package.sh: pip install . (builds libdpend.so with meson: a minute or two)"
start=$SECONDS
if ! (cd "$root" && "$py" -m pip install --quiet . > "$work/pip.log" 2>&1); then
  tail -n 60 "$work/pip.log" >&2
  fail "pip install . (log above)"
fi
echo "python_package.sh: pip install . took $((SECONDS - start)) s"
"$py" -m pip install --quiet pytest tqdm playwright || fail "pip install pytest tqdm playwright"

# Outside the checkout, so that the installed package is the one imported.
cd "$work"
echo "python_package.sh: dpend.simulate(q1=0, q2=0, t_end=1).energy[-1] [J]:"
"$py" -c "import dpend; print(float(dpend.simulate(q1=0, q2=0, t_end=1).energy[-1]))" ||
  fail "import dpend and simulate"

echo "python_package.sh: pytest python/tests (DPEND_CLI=$dpend)"
DPEND_CLI="$dpend" DPEND_SCREENSHOTS="$screenshots" \
  "$py" -m pytest -q -p no:cacheprovider "$root/python/tests" || fail "pytest python/tests"
if [[ -n "$notebook" ]]; then
  "$py" -m pip install --quiet nbclient nbformat ipykernel matplotlib ||
    fail "pip install nbclient nbformat ipykernel matplotlib"
  "$py" "$root/scripts/run_notebook.py" "$root/examples/python/tour.ipynb" "$notebook" ||
    fail "examples/python/tour.ipynb"
fi
echo "python_package.sh: all passed"
