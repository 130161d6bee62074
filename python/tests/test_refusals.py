"""The refusals of the reliability suite through the package: every `refuse` row of
the case files below (test/reliability/cases/, rows read by bash as the suite reads
them) whose command the library runs raises ValueError with the command line's one
line, word for word, and writes nothing. Needs DPEND_CLI (the command's line is
taken from the binary itself)."""
from __future__ import annotations

import os
import pathlib
import subprocess

import pytest

import dpend

CLI = os.environ.get("DPEND_CLI")
pytestmark = pytest.mark.skipif(not CLI, reason="DPEND_CLI names no dpend binary")

ROOT = pathlib.Path(__file__).resolve().parents[2]
CASE_FILES = ["strict_parse.sh", "limits.sh"]
LIBRARY_COMMANDS = {"simulate", "lyapunov", "indicators", "divergence", "poincare", "fit",
                    "sweep"}
# Rows about the output path, which the library sets itself.
OUTPUT_FIELDS = {"output", "force"}

# bash reads a case file as scripts/reliability.sh does, with `refuse` printing its
# row (ID, field, then the arguments, NUL-separated, a row ended by \x01).
READER = r"""
set -u
refuse() { [ $# -ge 3 ] && [ "$3" = "--" ] || return 0
           local id=$1 field=$2; shift 3; printf '%s\0' "$id" "$field" "$@" >&3
           printf '\1\0' >&3; }
fail() { :; }
succeed() { :; }
cd "$FIXTURES" && . "$CASE" 3>&1 > /dev/null 2>&1
"""


def _rows(case: str, fixtures: pathlib.Path):
    env = dict(os.environ, FIXTURES=str(fixtures), DPEND=CLI, ROOT=str(ROOT),
               CASE=str(ROOT / "test" / "reliability" / "cases" / case))
    out = subprocess.run(["bash", "-c", READER], env=env, capture_output=True,
                         check=False).stdout
    row: list = []
    for word in out.split(b"\0"):
        if word == b"\1":
            yield [w.decode("utf-8", "surrogateescape") for w in row]
            row = []
        elif word or row:
            row.append(word)


def _library_args(args):
    """The row's arguments without the output options the library sets itself."""
    rest, skip = [], False
    for a in args[1:]:
        if skip:
            skip = False
            continue
        if a in ("--output", "-o"):
            skip = True
            continue
        if a in ("--force", "--quiet") or a.startswith("--output="):
            continue
        rest.append(a)
    return rest


@pytest.mark.parametrize("case", CASE_FILES)
def test_refusals_are_the_command_lines(case, tmp_path):
    fixtures = tmp_path / "fixtures"
    fixtures.mkdir()
    rows = list(_rows(case, fixtures))
    assert rows, f"no refuse rows read from {case}"
    checked = 0
    for row in rows:
        row_id, field, args = row[0], row[1], row[2:]
        if not args or args[0] not in LIBRARY_COMMANDS or field in OUTPUT_FIELDS:
            continue
        if "--help" in args:
            continue
        done = subprocess.run([CLI, *args], cwd=fixtures, capture_output=True, check=False)
        assert done.returncode == 2, f"{row_id}: the command exited {done.returncode}"
        line = done.stderr.decode("utf-8", "replace").rstrip("\n")
        before = sorted(p.name for p in fixtures.iterdir())
        cwd = os.getcwd()
        os.chdir(fixtures)
        try:
            with pytest.raises(ValueError) as info:
                dpend.run(args[0], *_library_args(args))
        finally:
            os.chdir(cwd)
        assert str(info.value) == line, f"{row_id}: {info.value!s} != {line}"
        assert sorted(p.name for p in fixtures.iterdir()) == before, f"{row_id}: wrote a file"
        checked += 1
    assert checked >= 10, f"{case}: only {checked} rows checked"
