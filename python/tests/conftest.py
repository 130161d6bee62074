"""The tests of the installed package dpend (pip install .; scripts/python_package.sh).
They build nothing: `import dpend` must find the installed package."""
import pytest

import dpend


def pytest_sessionstart(session):
    """One clear line, not a failure per test, when the installed library lacks the
    C interface (src/capi/): `pip install .` from a checkout that has it."""
    try:
        dpend._library.function("dpend_run")
    except (OSError, RuntimeError) as e:
        pytest.exit(f"python/tests: {e}", returncode=1)
