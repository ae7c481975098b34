#!/usr/bin/env python3
"""Checks that every #include in a layer folder points down (docs/architecture.md).

The layers and their allowed lower layers are read from the `brdfit_layer(<name> LAYERS ...)`
call in each top-level folder's CMakeLists.txt, the same list CMake links with, so the rule and
the build cannot drift apart. A file in layer L may include "X/..." for a layer X only when X is
L or lies below L (transitively); a quoted path is resolved as the compiler resolves it, so
"../X/..." counts as X, and no layer includes tests/, bench/, fuzz/ or tools/. Also checked: the layer graph has no cycle, a layer's
CMakeLists.txt links no brdfit library outside its allowed set, and the layers that promise no
file I/O (core, fit, factor) include no file-format or file-stream header.

Usage: check_layers.py ROOT        exit 0 if the tree is clean, 1 listing every violation
       check_layers.py --self-test  plants upward includes (one spelt "../"), a file-stream
                                    include and an include of tests/ in a copy of this
                                    repository's layer folders; exits 0 only if all are caught
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

LAYER_CALL = re.compile(r"brdfit_layer\(\s*(\w+)([^)]*)\)", re.S)
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^">]+)[">]', re.M)
LINKED = re.compile(r"\bbrdfit_(\w+)\b")
SOURCE_EXT = (".h", ".cc", ".glsl", ".frag", ".vert")
# Layers that do no file I/O: no file-format library and no file stream may be included.
NO_FILE_IO = {"core", "fit", "factor"}
FILE_IO_HEADERS = re.compile(
    r"^(H5Cpp\.h|hdf5\.h|hdf5_hl\.h|H5.*|Imf.*|OpenEXR/.*|Imath/.*|png\.h|zip\.h|"
    r"tiny_obj_loader\.h|fstream|ifstream|ofstream)$")
# Names of CMake targets that are not layers (helpers every layer may link).
NOT_LAYERS = {"warnings"}
# Folders outside the stack (docs/architecture.md): they may use any layer, no layer uses them.
OUTSIDE_STACK = {"tests", "bench", "fuzz", "tools"}


def included_folder(root, dirpath, inc):
    """The top-level folder an #include names, as the compiler finds it: a quoted path that
    exists relative to the including file's folder first (so "../report/x.h" is report/),
    else relative to the root, the one include directory; ".." for a path leaving the root,
    None for a header of no folder of the root (the standard library, Eigen, ...)."""
    for base in (dirpath, root):
        full = os.path.normpath(os.path.join(base, inc))
        if base == dirpath and not (os.path.exists(full) or inc.startswith(".")):
            continue
        rel = os.path.relpath(full, root)
        if rel == ".." or rel.startswith(".." + os.sep):
            return ".."
        return rel.split(os.sep, 1)[0] if os.sep in rel else None
    return None


def read_layers(root):
    layers = {}
    for entry in sorted(os.listdir(root)):
        cm = os.path.join(root, entry, "CMakeLists.txt")
        if not os.path.isfile(cm):
            continue
        text = open(cm, encoding="utf-8").read()
        m = LAYER_CALL.search(text)
        if not m:
            continue
        if m.group(1) != entry:
            raise SystemExit(f"{cm}: brdfit_layer({m.group(1)}) in folder '{entry}'")
        words = m.group(2).split()
        below, mode = [], None
        for w in words:
            if w in ("LAYERS", "LIBS", "EXECUTABLE", "PYMODULE"):
                mode = w
            elif mode == "LAYERS":
                below.append(w)
        layers[entry] = {"below": below, "cmake": cm, "text": text}
    return layers


def closure(layers):
    """Transitive closure of 'below'; raises on a cycle or an unknown layer."""
    done, out = set(), {}

    def visit(name, stack):
        if name in stack:
            raise SystemExit("layer cycle: " + " -> ".join(stack + [name]))
        if name in done:
            return out[name]
        if name not in layers:
            raise SystemExit(f"unknown layer '{name}' (named by {stack[-1]})")
        allowed = set()
        for b in layers[name]["below"]:
            allowed.add(b)
            allowed |= visit(b, stack + [name])
        done.add(name)
        out[name] = allowed
        return allowed

    for name in layers:
        visit(name, [])
    return out


def check(root):
    layers = read_layers(root)
    if not layers:
        return [f"{root}: no brdfit_layer() call found"], 0
    allowed = closure(layers)
    problems, files = [], 0
    for name, info in layers.items():
        ok = allowed[name] | {name}
        # CMake: no brdfit_<layer> outside the allowed set in this folder's CMakeLists.txt.
        for m in LINKED.finditer(info["text"]):
            other = m.group(1)
            if other in layers and other not in ok:
                problems.append(f"{info['cmake']}: links brdfit_{other}, not below {name}")
        for dirpath, _, names in os.walk(os.path.join(root, name)):
            for fn in sorted(names):
                if not fn.endswith(SOURCE_EXT):
                    continue
                path = os.path.join(dirpath, fn)
                files += 1
                text = open(path, encoding="utf-8", errors="replace").read()
                for m in INCLUDE.finditer(text):
                    inc = m.group(1)
                    line = text.count("\n", 0, m.start()) + 1
                    rel = os.path.relpath(path, root)
                    top = included_folder(root, dirpath, inc)
                    if top == "..":
                        problems.append(f"{rel}:{line}: includes \"{inc}\": a file outside "
                                        "the repository")
                    elif top in layers and top not in ok:
                        problems.append(f"{rel}:{line}: includes \"{inc}\": layer '{top}' is "
                                        f"not below '{name}' (allowed: "
                                        f"{', '.join(sorted(ok))})")
                    elif top in OUTSIDE_STACK:
                        problems.append(f"{rel}:{line}: includes \"{inc}\": '{top}/' is "
                                        "outside the layers (it may use them, not they it)")
                    if name in NO_FILE_IO and FILE_IO_HEADERS.match(inc):
                        problems.append(f"{rel}:{line}: includes <{inc}>: layer '{name}' does "
                                        "no file I/O (docs/architecture.md)")
    return problems, files


def self_test():
    here = os.path.dirname(os.path.abspath(__file__))
    root = os.path.normpath(os.path.join(here, "..", ".."))
    with tempfile.TemporaryDirectory() as tmp:
        layers = read_layers(root)
        for name in layers:
            shutil.copytree(os.path.join(root, name), os.path.join(tmp, name),
                            ignore=shutil.ignore_patterns("*.json", "*.png", "*.exr"))
        clean, _ = check(tmp)
        if clean:
            print("self-test: the unmodified copy already fails:\n  " + "\n  ".join(clean))
            return 1
        planted = os.path.join(tmp, "core", "table.h")
        with open(planted, "a", encoding="utf-8") as f:
            f.write('\n#include "report/html_report.h"\n')
        fio = os.path.join(tmp, "fit", "loss.cc")
        with open(fio, "a", encoding="utf-8") as f:
            f.write("\n#include <fstream>\n")
        # The same upward include spelt relative to the including file, and a layer using a
        # folder outside the stack.
        with open(os.path.join(tmp, "fit", "fitter.h"), "a", encoding="utf-8") as f:
            f.write('\n#include "../report/html_report.h"\n')
        with open(os.path.join(tmp, "factor", "factor.h"), "a", encoding="utf-8") as f:
            f.write('\n#include "tests/factor/factor_test_util.h"\n')
        r = subprocess.run([sys.executable, os.path.abspath(__file__), tmp],
                           capture_output=True, text=True)
        out = r.stdout + r.stderr
        expected = ["core/table.h", "fit/loss.cc", "fit/fitter.h", "factor/factor.h"]
        caught = r.returncode == 1 and all(
            any(line.strip().startswith(e + ":") for line in out.splitlines()) for e in expected)
        print(out.strip())
        print("self-test: " + ("planted includes caught" if caught else "NOT caught"))
        return 0 if caught else 1


def main():
    if len(sys.argv) == 2 and sys.argv[1] == "--self-test":
        return self_test()
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    problems, files = check(sys.argv[1])
    if problems:
        print("check_layers: %d include(s) point the wrong way:" % len(problems))
        for p in problems:
            print("  " + p)
        return 1
    print(f"check_layers: {files} files in {len(read_layers(sys.argv[1]))} layers, "
          "every include points down")
    return 0


if __name__ == "__main__":
    sys.exit(main())
