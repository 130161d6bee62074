#!/usr/bin/env python3
"""The library's sources and version for meson.build (run at configure time).

Usage: meson_sources.py ROOT sources   -> every src/**/*.f90 and src/**/*.c, one a
                                          line, sorted, relative to ROOT; src/gpu/
                                          (the optional CUDA path and its host copy
                                          for the tests) left out.
       meson_sources.py ROOT dirs      -> the folders under src/ that hold sources
                                          (include directories for the .inc files).
       meson_sources.py ROOT version   -> the version of fpm.toml.
A file added under src/ is picked up at the next configure (pip install . always
configures afresh; a meson build directory needs `meson setup --reconfigure`).
"""
import pathlib
import re
import sys

EXCLUDED = ("gpu",)          # folders directly under src/ left out


def sources(root: pathlib.Path) -> list[str]:
    src = root / "src"
    found = []
    for path in src.rglob("*"):
        rel = path.relative_to(src)
        if rel.parts[0] in EXCLUDED or not path.is_file():
            continue
        if path.suffix in (".f90", ".c"):
            found.append(path.relative_to(root).as_posix())
    return sorted(found)


def main() -> int:
    root = pathlib.Path(sys.argv[1]).resolve()
    what = sys.argv[2]
    if what == "sources":
        print("\n".join(sources(root)))
    elif what == "dirs":
        print("\n".join(sorted({str(pathlib.PurePosixPath(s).parent) for s in sources(root)})))
    elif what == "version":
        text = (root / "fpm.toml").read_text()
        m = re.search(r'^version\s*=\s*"([^"]+)"', text, re.M)
        if not m:
            print("meson_sources.py: no version in fpm.toml", file=sys.stderr)
            return 1
        print(m.group(1))
    else:
        print(f"meson_sources.py: unknown request {what!r}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
