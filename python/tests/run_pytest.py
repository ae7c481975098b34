"""ctest's entry to the pytest suite (tests/python/CMakeLists.txt): skips (exit 77) with the
reason when pytest or NumPy is missing for this interpreter, else runs python/tests."""
import os
import sys

try:
    import numpy  # noqa: F401
    import pytest
except ImportError as e:
    print(f"SKIPPED: {sys.executable} lacks {e.name} (Debian python3-pytest, python3-numpy; "
          "scripts/setup-deps.sh)")
    sys.exit(77)

sys.exit(pytest.main(["-q", "-p", "no:cacheprovider", os.path.dirname(os.path.abspath(__file__))]))
