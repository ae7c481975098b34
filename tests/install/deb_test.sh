#!/usr/bin/env bash
# install.deb (tests/install/CMakeLists.txt): `cpack -G DEB` in the build folder, then the
# package is unpacked into a scratch root (dpkg -x, as dpkg would lay it under /) and used from
# there: its control fields, its command (a synthesized table fitted back), its Python module
# imported by Debian's python3 from the package's dist-packages, its headers and CMake package.
# Usage: deb_test.sh BUILD SCRATCH VERSION [PYTHON]
set -euo pipefail
build=$1 scratch=$2 version=$3 python=${4:-}
fail() { echo "FAIL: $*" >&2; exit 1; }

rm -rf "$scratch"
mkdir -p "$scratch"
(cd "$build" && cpack -G DEB -B "$scratch/out") > "$scratch/cpack.log" 2>&1 ||
  { cat "$scratch/cpack.log"; fail "cpack -G DEB failed"; }
debs=("$scratch"/out/brdfit_"$version"_*.deb)
[[ -f ${debs[0]} ]] || fail "no brdfit_${version}_<arch>.deb in $scratch/out"
deb=${debs[0]}
echo "package: $deb ($(stat -c %s "$deb") bytes)"

# Control fields: name, version, and Depends computed from the linked shared libraries.
[[ $(dpkg-deb -f "$deb" Package) == brdfit ]] || fail "Package is not brdfit"
[[ $(dpkg-deb -f "$deb" Version) == "$version" ]] || fail "Version is not $version"
depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
[[ $depends == *libc6* && $depends == *libstdc++6* ]] ||
  fail "Depends lacks the C/C++ runtimes (dpkg-shlibdeps did not run?): $depends"
if [[ -n $python ]]; then
  [[ $depends == *"python3 (>= "* && $depends == *python3-numpy* ]] ||
    fail "Depends lacks python3 / python3-numpy: $depends"
fi

# Every file under /usr; the library, its headers (export layer included) and CMake package.
if dpkg-deb -c "$deb" | awk '{print $6}' | grep -v '^\./$' | grep -v '^\./usr/'; then
  fail "files outside /usr"
fi
root=$scratch/root
dpkg -x "$deb" "$root"
for f in usr/bin/brdfit usr/include/brdfit/core/table.h usr/include/brdfit/export/gltf.h \
         usr/lib/libbrdfit_fit.a usr/lib/libbrdfit_export.a usr/lib/cmake/brdfit/brdfitConfig.cmake; do
  [[ -e $root/$f ]] || fail "the package has no /$f"
done
grep -q 'brdfit::export' "$root"/usr/lib/cmake/brdfit/brdfitTargets.cmake ||
  fail "the CMake package exports no brdfit::export"

# The command runs from the package: its version, and a table it writes and fits back.
out=$("$root/usr/bin/brdfit" --version)
[[ $out == "brdfit $version" ]] || fail "packaged brdfit --version printed '$out'"
"$root/usr/bin/brdfit" synth --model lambert+ggx --param ggx.alpha=0.2 --grid 30,30,60 \
  -o "$scratch/t.h5"
"$root/usr/bin/brdfit" fit "$scratch/t.h5" --model lambert+ggx --polish none --json "$scratch/t.json" \
  -o "$scratch/fits.h5" -q
alpha=$(grep -o '"ggx.alpha": [0-9.e-]*' "$scratch/t.json" | awk '{print $2}')
awk -v a="$alpha" 'BEGIN { exit !(a > 0.199 && a < 0.201) }' ||
  fail "the packaged brdfit fitted ggx.alpha '$alpha' to a table of alpha 0.2"
echo "packaged brdfit: synth -> fit recovers ggx.alpha $alpha"

# The module, where Debian's python3 looks (/usr/lib/python3/dist-packages), and only there.
if [[ -n $python ]]; then
  [[ -z $(find "$root" -path '*site-packages*' -print -quit) ]] || fail "a site-packages copy in the package"
  out=$(PYTHONPATH=$root/usr/lib/python3/dist-packages "$python" -c "import brdfit
print(brdfit.__version__ if brdfit.__file__.startswith('$root/usr/lib/python3/dist-packages/') else 'imported ' + brdfit.__file__)")
  [[ $out == "$version" ]] || fail "the packaged module: '$out', expected '$version'"
fi
echo "the .deb installs and runs"
