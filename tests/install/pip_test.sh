#!/usr/bin/env bash
# install.pip (tests/install/CMakeLists.txt): `pip install --no-build-isolation .` into a venv
# made with --system-site-packages (NumPy, setuptools and wheel are Debian's; no package index),
# then `import brdfit` and the `brdfit` command from the venv, and `pip uninstall` removes both.
# setup.py packages this build folder (BRDFIT_CMAKE_BUILD_DIR) instead of compiling the
# project a second time in build-pip/; the fresh-clone route differs only in that configure
# step (docs/python.md, "Installing with pip").
# Usage: pip_test.sh SOURCE BUILD SCRATCH VERSION PYTHON
set -euo pipefail
source=$1 build=$2 scratch=$3 version=$4 python=$5
fail() { echo "FAIL: $*" >&2; exit 1; }

rm -rf "$scratch"
mkdir -p "$scratch"
"$python" -m venv --system-site-packages "$scratch/venv" ||
  fail "$python -m venv failed (Debian python3-venv: scripts/setup-deps.sh installs it)"
venv=$scratch/venv
# The machine's pip configuration (an index, find-links) is not this test's.
export PIP_CONFIG_FILE=/dev/null PIP_NO_INDEX=1 PIP_DISABLE_PIP_VERSION_CHECK=1
BRDFIT_CMAKE_BUILD_DIR=$build "$venv/bin/pip" install --no-build-isolation "$source" \
  > "$scratch/pip.log" 2>&1 || { tail -40 "$scratch/pip.log"; fail "pip install failed"; }
grep -E "Successfully (built|installed)" "$scratch/pip.log"

# From elsewhere than the source or build folder, so that nothing but the venv can be imported.
cd "$scratch"
out=$(env -u PYTHONPATH "$venv/bin/python" -c "import brdfit
print(brdfit.__version__ if brdfit.__file__.startswith('$venv/') else 'imported ' + brdfit.__file__)")
[[ $out == "$version" ]] || fail "the venv's module: '$out', expected '$version'"
[[ -x $venv/bin/brdfit ]] || fail "no executable brdfit in $venv/bin"
out=$(env PATH="$venv/bin:/usr/bin:/bin" brdfit --version)
[[ $out == "brdfit $version" ]] || fail "the venv's brdfit --version printed '$out'"
env -u PYTHONPATH "$venv/bin/python" -c "import brdfit
t = brdfit.synth('lambert+ggx', {'ggx.alpha': 0.3}, grid=(16, 16, 32))
assert t.num_valid > 0, t
print('the venv module synthesized', t)"
# Outside any venv the same python does not see it: the install went into the venv only.
if env -u PYTHONPATH "$python" -c "import brdfit" 2>/dev/null; then
  "$python" -c "import brdfit; print(brdfit.__file__)"
  fail "$python imports a brdfit outside the venv: the test cannot tell where it came from"
fi

"$venv/bin/pip" uninstall -y brdfit > "$scratch/uninstall.log" 2>&1 || fail "pip uninstall failed"
[[ ! -e $venv/bin/brdfit ]] || fail "pip uninstall left $venv/bin/brdfit"
if env -u PYTHONPATH "$venv/bin/python" -c "import brdfit" 2>/dev/null; then
  fail "pip uninstall left the module importable"
fi
echo "pip install and uninstall work"
