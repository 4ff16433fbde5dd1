"""ctest's entry point for the Python tests: exits 77 (ctest: Skipped) when pytest or numpy cannot
be imported, so a missing dependency never passes silently; otherwise runs pytest on the given
files and returns its status. A module that was built (ISODEL_PYTHON_MODULE_BUILT=1, set by
tests/python/CMakeLists.txt) but does not import is a failure, not a skip."""
import os
import sys

SKIP = 77

try:
    import pytest
    import numpy  # noqa: F401
except ImportError as e:
    print(f"skipped: {e}")
    sys.exit(SKIP)
try:
    import isodel  # noqa: F401
except ImportError as e:
    built = os.environ.get("ISODEL_PYTHON_MODULE_BUILT") == "1"
    print(f"{'FAILED' if built else 'skipped'}: the isodel module cannot be imported ({e}); "
          "is PYTHONPATH the build's python/ folder?")
    sys.exit(1 if built else SKIP)

status = pytest.main(["-q", "-p", "no:cacheprovider", *sys.argv[1:]])
sys.exit(int(status))
