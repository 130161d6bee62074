#!/usr/bin/env python3
"""Execute a notebook of examples/python with nbclient (in the interpreter of a venv
where dpend, nbclient, ipykernel and matplotlib are installed) and check that the
figures it promises were written.

  venv/bin/python scripts/run_notebook.py examples/python/tour.ipynb OUTDIR

The executed notebook goes to OUTDIR/NAME.ipynb, the figures to OUTDIR/ (the
notebook reads $DPEND_NOTEBOOK_OUT). Exit status 1 when a cell fails or a figure is
missing."""
from __future__ import annotations

import os
import pathlib
import sys

import nbformat
from nbclient import NotebookClient
from nbclient.exceptions import CellExecutionError

FIGURES = ["release_angles.png", "energy_error.png", "flip_map.png", "megno_map.png",
           "megno_pixel_run.png", "fit.png"]


def main() -> int:
    if len(sys.argv) != 3:
        print(__doc__, file=sys.stderr)
        return 2
    notebook, outdir = pathlib.Path(sys.argv[1]).resolve(), pathlib.Path(sys.argv[2])
    outdir.mkdir(parents=True, exist_ok=True)
    root = pathlib.Path(__file__).resolve().parents[1]
    os.environ["DPEND_NOTEBOOK_OUT"] = str(outdir.resolve())
    os.environ["DPEND_ROOT"] = str(root)
    nb = nbformat.read(notebook, as_version=4)
    client = NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(outdir.resolve())}})
    try:
        client.execute()
    except CellExecutionError as e:
        print(f"run_notebook: {notebook.name}: a cell failed:\n{e}", file=sys.stderr)
        return 1
    finally:
        nbformat.write(nb, outdir / notebook.name)
    missing = [f for f in FIGURES if not (outdir / f).is_file()]
    if missing:
        print(f"run_notebook: {notebook.name}: no {', '.join(missing)} in {outdir}",
              file=sys.stderr)
        return 1
    print(f"run_notebook: {notebook.name}: {len(nb.cells)} cells ran; figures "
          f"{', '.join(FIGURES)} in {outdir}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
