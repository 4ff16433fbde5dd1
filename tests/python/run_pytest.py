"""ctest's entry point for the Python tests: exits 77 (ctest: Skipped) when pytest, numpy or the
built isodel module cannot be imported, so a missing dependency never passes silently; otherwise
runs pytest on the given files and returns its status."""
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
    print(f"skipped: the isodel module cannot be imported ({e}); is PYTHONPATH the build's python/ folder?")
    sys.exit(SKIP)

status = pytest.main(["-q", "-p", "no:cacheprovider", *sys.argv[1:]])
sys.exit(int(status))
