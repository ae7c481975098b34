"""brdfit.__version__ and `brdfit --version` are the CMake project version."""
import os
import re

import brdfit


def test_versions_agree_with_cmake(cli):
    root = os.path.join(os.path.dirname(__file__), "..", "..")
    text = open(os.path.join(root, "CMakeLists.txt"), encoding="utf-8").read()
    version = re.search(r"project\(brdfit VERSION ([0-9.]+)", text).group(1)
    assert brdfit.__version__ == version
    assert cli("--version").stdout.strip() == f"brdfit {version}"
