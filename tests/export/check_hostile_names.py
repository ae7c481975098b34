#!/usr/bin/env python3
"""Hostile material and source names through every `brdfit export` format (docs/reliability.md,
"Names in other languages' files").

A fits JSON whose material and source names carry newlines, carriage returns, U+2028, quotes,
backslashes, backticks, `*/`, `</script>`, `]]>`, `--`, NUL, non-ASCII and a 5,000-character
run, each with a payload that would run (or add a scene element) if it escaped its comment or
string, is exported in every format. Each file must parse in its own language's parser and the
payload must not become code or markup:

- three.js (.mjs): imported by node with the real three.js (tools/gltf, npm); the payload sets
  globalThis.INJECTED if it runs; `brdfit.material` and `brdfit.source` must equal the names;
- Blender (.py): compile(), and no name INJECTED anywhere in its syntax tree;
- Mitsuba (.xml): xml.etree parses it and no element is named `injected`;
- pbrt (.pbrt): check_exports.check_pbrt (tokens, directives, parameters) and no token other
  than comments holds `injected`; pbrt-v4 itself parses it (`pbrt --format`) when
  ../shared/tools/pbrt-v4 is there;
- glTF (.gltf, .glb): JSON parses, the scene's name equals the material name.

Each check fails on a planted escape (the same payload written without escaping), so none can
pass vacuously. Exit 0 ok, 1 a check failed, 77 (ctest SKIP) when node/npm are missing.
"""
import argparse
import ast
import copy
import json
import os
import shutil
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET

from check_exports import check_pbrt, pbrt_tokens
from node_tools import ensure_tools

NAMES = [
    "paint\nglobalThis.INJECTED = 1; //",
    "paint\rglobalThis.INJECTED = 2; //",
    "paint\u2028globalThis.INJECTED = 3; //",
    "paint\u2029globalThis.INJECTED = 3; //",
    "*/ globalThis.INJECTED = 4; /*",
    "q\"uote' back\\slash `tick` ${globalThis.INJECTED = 5}",
    "</script><script>globalThis.INJECTED = 6</script>",
    "]]> --> <injected/> <!-- -",
    "nul\u0000byte\nINJECTED = 7\n#",
    "\n] AttributeEnd NamedMaterial \"injected\" #",
    "\n\f\vINJECTED = 8 #",
    "caf\u00e9 \u65e5\u672c \U0001f3a8",
    "x" * 5000,
]

FORMATS = {"threejs": ".mjs", "blender": ".py", "mitsuba": ".xml", "pbrt": ".pbrt",
           "gltf": ".gltf", "glb": ".glb"}

# Imports each module named on the command line; prints, per module, whether the payload ran
# and the names it states.
RUNNER = r"""
import { pathToFileURL } from 'node:url';
const out = [];
for (const path of process.argv.slice(2)) {
  delete globalThis.INJECTED;
  try {
    const m = await import(pathToFileURL(path).href);
    const mat = m.default();
    out.push({ path, injected: globalThis.INJECTED ?? null, material: m.brdfit.material,
               source: m.brdfit.source, type: mat.type });
  } catch (e) {
    out.push({ path, error: String(e), injected: globalThis.INJECTED ?? null });
  }
}
console.log(JSON.stringify(out));
"""

failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL: " + msg[:400])


def check_python(path, text):
    try:
        tree = ast.parse(text, path)
    except (SyntaxError, ValueError) as e:
        return f"{path}: not Python: {e}"
    if any(isinstance(n, ast.Name) and n.id == "INJECTED" for n in ast.walk(tree)):
        return f"{path}: a name became Python code"
    return None


def check_xml(path, text):
    try:
        root = ET.fromstring(text.encode("utf-8"))
    except ET.ParseError as e:
        return f"{path}: not well-formed XML: {e}"
    if any(el.tag == "injected" for el in root.iter()):
        return f"{path}: a name became an XML element"
    return None


def check_pbrt_text(path, text):
    err = check_pbrt(path, text)
    if err:
        return err
    if any("injected" in t.lower() for t in pbrt_tokens(text)):
        return f"{path}: a name became pbrt scene text"
    return None


def glb_json(path):
    data = open(path, "rb").read()
    length = struct.unpack_from("<I", data, 12)[0]
    return json.loads(data[20:20 + length].decode("utf-8"))


def check_gltf(path, doc, name):
    if doc["scenes"][0]["name"] != name:
        return f"{path}: the scene's name is not the material's"
    return None


def main():
    ap = argparse.ArgumentParser()
    for a in ("--brdfit", "--fits", "--tools", "--work"):
        ap.add_argument(a, required=True)
    ap.add_argument("--pbrt", default="")
    o = ap.parse_args()
    shutil.rmtree(o.work, ignore_errors=True)
    os.makedirs(o.work)
    tools = os.path.join(o.work, "..", "node-tools")
    status, why = ensure_tools(o.tools, tools)
    if status == "failed":
        print("FAIL: " + why)
        return 1
    # The modules live below the tools folder so that `import 'three'` resolves to its
    # node_modules.
    mods = os.path.join(tools, "hostile-modules")
    shutil.rmtree(mods, ignore_errors=True)
    os.makedirs(mods)

    base = json.load(open(o.fits))
    template = [f for f in base["fits"] if f["model"] == "lambert+ggx"][0]
    # One fits file per name: a name with NUL cannot be passed as --material.
    fits_files = []
    for i, name in enumerate(NAMES):
        f = copy.deepcopy(template)
        f["material"] = name
        f["source"] = name + f" ({i}).h5"
        doc = copy.deepcopy(base)
        doc["fits"] = [f]
        fits_files.append(os.path.join(o.work, f"hostile-fits-{i}.json"))
        with open(fits_files[-1], "w", encoding="utf-8") as fh:
            json.dump(doc, fh, ensure_ascii=False)

    modules = {}
    for i, name in enumerate(NAMES):
        for fmt, ext in FORMATS.items():
            out = os.path.join(mods if fmt == "threejs" else o.work, f"name{i}{ext}")
            r = subprocess.run([o.brdfit, "export", fits_files[i], "--format", fmt, "-o", out],
                               capture_output=True)
            if r.returncode != 0:
                fail(f"export name {i} {fmt}: exit {r.returncode}: {r.stderr[-300:]!r}")
                continue
            if fmt == "glb":
                err = check_gltf(out, glb_json(out), name)
            else:
                text = open(out, encoding="utf-8").read()
                err = (check_python(out, text) if fmt == "blender" else
                       check_xml(out, text) if fmt == "mitsuba" else
                       check_pbrt_text(out, text) if fmt == "pbrt" else
                       check_gltf(out, json.loads(text), name) if fmt == "gltf" else None)
            if err:
                fail(err)
            if fmt == "threejs":
                modules[out] = (name, name + f" ({i}).h5")
            if fmt == "pbrt" and o.pbrt and os.path.exists(o.pbrt):
                r = subprocess.run([o.pbrt, "--format", out], capture_output=True)
                if r.returncode != 0:
                    fail(f"{out}: pbrt-v4 does not parse it: {r.stderr[-300:]!r}")

    # Planted escapes: the checks catch the payloads when they are not escaped.
    if check_python("planted", "# x\nINJECTED = 7\n") is None:
        fail("the Python check passed a name that became code")
    if check_xml("planted", "<scene><!-- a --><injected/></scene>") is None:
        fail("the XML check passed a name that became an element")
    planted_js = os.path.join(mods, "planted.mjs")
    with open(planted_js, "w") as fh:
        fh.write("// source table: paint\nglobalThis.INJECTED = 1; //\n"
                 "export const brdfit = { material: 'm', source: 's' };\n"
                 "export default function createMaterial() { return { type: 'x' }; }\n")

    if status == "absent":
        print("SKIP three.js modules: " + why)
        return 1 if failures else 77
    runner = os.path.join(mods, "run.mjs")
    with open(runner, "w") as fh:
        fh.write(RUNNER)
    r = subprocess.run([shutil.which("node"), runner, planted_js] + sorted(modules),
                       capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"node: exit {r.returncode}: {r.stderr[-500:]}")
    else:
        results = {x["path"]: x for x in json.loads(r.stdout)}
        if results[planted_js]["injected"] is None:
            fail("the three.js check passed a name that became code")
        for path, (name, source) in modules.items():
            x = results[path]
            if x.get("error"):
                fail(f"{path}: node cannot import it: {x['error']}")
            elif x["injected"] is not None:
                fail(f"{path}: a name ran as JavaScript (INJECTED = {x['injected']})")
            elif x["material"] != name or x["source"] != source:
                fail(f"{path}: the names do not round-trip: {x['material']!r}")
            elif x["type"] != "ShaderMaterial":
                fail(f"{path}: createMaterial() made a {x['type']}")
    print(f"{len(NAMES)} hostile names x {len(FORMATS)} formats: {len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
