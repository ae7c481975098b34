#!/usr/bin/env python3
"""`brdfit export` checked by real tools (docs/exports.md):

- every fit of tests/export/data/fits.json in every format, through the CLI: exit 0, and
  "approximate" on stderr exactly when the file says so;
- Mitsuba 3 XML is well-formed (xml.etree) and a scene: <scene version="3.0.0">, the
  blendbsdf with id brdfit-material, a shape referencing it;
- pbrt-v4 text passes a tokenizer and a directive/parameter check (known directives, "type name"
  parameters with bracketed values of that type, NamedMaterial and mix materials defined);
- every .gltf and .glb passes the Khronos glTF-Validator (npm gltf-validator, pinned in
  tools/gltf/package-lock.json, installed with `npm ci` into the work folder) with no errors;
- the Blender script compiles as Python (compile(); Blender 3.4 runs Python 3.10, and
  export.blender_render runs it in Blender), the three.js module passes `node --check`;
- each check fails on a planted defect (a "--" in an XML comment, an unclosed pbrt bracket, a
  glTF accessor past its buffer, a Python and a JS syntax error), so none of them can pass
  vacuously.
Exit 0 ok, 1 a check failed, 77 (ctest SKIP) when node/npm are missing.
"""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

from node_tools import ensure_tools

FORMATS = {"gltf": ".gltf", "glb": ".glb", "mitsuba": ".xml", "pbrt": ".pbrt", "blender": ".py",
           "threejs": ".mjs"}
PBRT_DIRECTIVES = {"Scale", "LookAt", "Camera", "Film", "Sampler", "Integrator", "WorldBegin",
                   "LightSource", "MakeNamedMaterial", "NamedMaterial", "AttributeBegin",
                   "AttributeEnd", "Shape"}
PBRT_TYPES = {"integer", "float", "point2", "vector2", "point3", "vector3", "normal", "normal3",
              "spectrum", "rgb", "blackbody", "bool", "string", "texture", "point", "vector",
              "color"}
failures = []


def fail(msg):
    failures.append(msg)
    print("FAIL: " + msg)


def check_mitsuba(path, text):
    try:
        root = ET.fromstring(text.encode("utf-8"))
    except ET.ParseError as e:
        return f"{path}: not well-formed XML: {e}"
    if root.tag != "scene" or root.get("version") != "3.0.0":
        return f"{path}: root is not <scene version=\"3.0.0\">"
    ids = {b.get("id") for b in root.findall("bsdf")}
    if "brdfit-material" not in ids:
        return f"{path}: no <bsdf id=\"brdfit-material\">"
    refs = [r.get("id") for s in root.findall("shape") for r in s.findall("ref")]
    if "brdfit-material" not in refs:
        return f"{path}: no shape references brdfit-material"
    blend = [b for b in root.findall("bsdf") if b.get("id") == "brdfit-material"][0]
    if blend.get("type") != "blendbsdf" or len(blend.findall("bsdf")) != 2:
        return f"{path}: brdfit-material is not a blendbsdf of two BSDFs"
    return None


def pbrt_tokens(text):
    tokens, i = [], 0
    while i < len(text):
        c = text[i]
        if c.isspace():
            i += 1
        elif c == "#":
            while i < len(text) and text[i] != "\n":
                i += 1
        elif c == '"':
            j = text.find('"', i + 1)
            if j < 0 or "\n" in text[i:j]:
                raise ValueError(f"unterminated string at offset {i}")
            tokens.append(text[i:j + 1])
            i = j + 1
        elif c in "[]":
            tokens.append(c)
            i += 1
        else:
            m = re.match(r'[^\s\[\]"#]+', text[i:])
            tokens.append(m.group(0))
            i += len(m.group(0))
    return tokens


def check_pbrt(path, text):
    try:
        t = pbrt_tokens(text)
    except ValueError as e:
        return f"{path}: {e}"
    defined, used, mixes, i = set(), [], [], 0
    while i < len(t):
        d = t[i]
        if d not in PBRT_DIRECTIVES:
            return f"{path}: unknown directive {d!r}"
        i += 1
        if d in ("LookAt", "Scale"):
            n = 9 if d == "LookAt" else 3
            vals = t[i:i + n]
            if len(vals) != n or any(not re.fullmatch(r"-?[0-9.eE+-]+", v) for v in vals):
                return f"{path}: {d} needs {n} numbers"
            i += n
            continue
        if d in ("WorldBegin", "AttributeBegin", "AttributeEnd"):
            continue
        if i >= len(t) or not t[i].startswith('"'):
            return f"{path}: {d} needs a quoted name"
        name = t[i][1:-1]
        i += 1
        if d == "MakeNamedMaterial":
            defined.add(name)
        if d == "NamedMaterial":
            used.append(name)
            continue
        while i < len(t) and t[i].startswith('"'):
            decl = t[i][1:-1].split()
            if len(decl) != 2 or decl[0] not in PBRT_TYPES:
                return f"{path}: bad parameter declaration {t[i]}"
            i += 1
            if i >= len(t) or t[i] != "[":
                return f"{path}: parameter {t[i - 1]} without [ values ]"
            j = t.index("]", i) if "]" in t[i:] else -1
            if j < 0:
                return f"{path}: unclosed [ after {t[i - 1]}"
            vals = t[i + 1:j]
            if "[" in vals or not vals:
                return f"{path}: bad values of {decl[1]}"
            ty = decl[0]
            for v in vals:
                ok = (v.startswith('"') if ty in ("string", "texture") else
                      v in ("true", "false") if ty == "bool" else
                      re.fullmatch(r"-?[0-9]*\.?[0-9]+([eE][-+]?[0-9]+)?", v) is not None)
                if not ok:
                    return f"{path}: {v!r} is not a {ty} ({decl[1]})"
            if name and d == "MakeNamedMaterial" and decl[1] == "materials":
                mixes += [v[1:-1] for v in vals]
            i = j + 1
    for n in used + mixes:
        if n not in defined:
            return f"{path}: material {n!r} used but not defined"
    if t.count("AttributeBegin") != t.count("AttributeEnd"):  # tokens: not inside comments
        return f"{path}: AttributeBegin/End unbalanced"
    return None


def check_python(path, text):
    try:
        compile(text, path, "exec")
    except SyntaxError as e:
        return f"{path}: not Python: {e}"
    return None


def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, text=True, **kw)


def main():
    ap = argparse.ArgumentParser()
    for a in ("--brdfit", "--fits", "--golden", "--tools", "--work"):
        ap.add_argument(a, required=True)
    o = ap.parse_args()
    shutil.rmtree(o.work, ignore_errors=True)
    os.makedirs(o.work)
    fits = json.load(open(o.fits))["fits"]
    gltfs, modules = [], []
    for f in fits:
        for fmt, ext in FORMATS.items():
            out = os.path.join(o.work, f"{f['material']}-{f['model']}{ext}")
            r = run([o.brdfit, "export", o.fits, "--format", fmt, "--material", f["material"],
                     "--model", f["model"], "-o", out])
            if r.returncode != 0:
                fail(f"export {f['material']} {f['model']} {fmt}: exit {r.returncode}: {r.stderr}")
                continue
            if fmt in ("gltf", "glb"):
                gltfs.append(out)
            if fmt == "glb":
                continue
            text = open(out, encoding="utf-8").read()
            if fmt == "threejs":
                modules.append(out)
            # A Blender script also states its (always approximate) Principled material, after.
            own = text.split("# material brdfit-principled")[0] if fmt == "blender" else text
            if ("approximate" in r.stderr) != ("approximate" in own):
                fail(f"{out}: stderr and file disagree on approximate")
            if "brdfit 0.1.0" not in text or f["source"] not in text:
                fail(f"{out}: no version or source table stated")
            err = check_mitsuba(out, text) if fmt == "mitsuba" else \
                check_pbrt(out, text) if fmt == "pbrt" else \
                check_python(out, text) if fmt == "blender" else None
            if err:
                fail(err)
    for g in sorted(os.listdir(o.golden)):
        p = os.path.join(o.golden, g)
        if g.endswith(".xml") and (e := check_mitsuba(p, open(p).read())):
            fail(e)
        if g.endswith(".pbrt") and (e := check_pbrt(p, open(p).read())):
            fail(e)
        if g.endswith(".gltf"):
            json.load(open(p))
    # Bad input is refused with the file named.
    r = run([o.brdfit, "export", o.fits, "--format", "gltf", "--material", "red-phenolic",
             "--model", "ward", "-o", os.path.join(o.work, "x.gltf")])
    if r.returncode != 2 or "ward" not in r.stderr:
        fail(f"an absent model: exit {r.returncode}, {r.stderr!r}")
    r = run([o.brdfit, "export", o.fits, "--format", "gltf", "--material", "red-phenolic",
             "-o", os.path.join(o.work, "x.bin")])
    if r.returncode != 2 or "same file" not in r.stderr:
        fail(f"a .gltf named .bin: exit {r.returncode}, {r.stderr!r}")
    # Planted defects.
    good_xml = open(os.path.join(o.golden, "gold-metallic-paint.xml")).read()
    if check_mitsuba("planted", good_xml.replace("<!--\n", "<!-- a -- b\n", 1)) is None:
        fail("the XML check passed a '--' inside a comment")
    good_pbrt = open(os.path.join(o.golden, "gold-metallic-paint.pbrt")).read()
    if check_pbrt("planted", good_pbrt.replace("\"float amount\" [", "\"float amount\" ", 1)) is None:
        fail("the pbrt check passed a parameter without [")
    if check_pbrt("planted", good_pbrt.replace("NamedMaterial \"brdfit-material\"\n  Shape",
                                               "NamedMaterial \"nothing\"\n  Shape")) is None:
        fail("the pbrt check passed an undefined material")

    good_py = open(os.path.join(o.work, "red-phenolic-lambert+ggx.py")).read()
    if check_python("planted", good_py.replace("def build_scene(", "def build_scene((", 1)) is None:
        fail("the Python check passed a syntax error")

    # The Khronos glTF-Validator.
    tools = os.path.join(o.work, "..", "node-tools")
    status, why = ensure_tools(o.tools, tools)
    if status == "failed":
        fail(why)
        return 1
    if status == "absent":
        print("SKIP glTF-Validator: " + why)
        return 1 if failures else 77
    node = shutil.which("node")
    for m in modules:
        r = run([node, "--check", m])
        if r.returncode != 0:
            fail(f"{m}: node --check: {r.stderr}")
    planted_js = os.path.join(o.work, "planted.mjs")
    open(planted_js, "w").write(open(modules[0]).read().replace("export default function",
                                                                 "export default function (", 1))
    if run([node, "--check", planted_js]).returncode == 0:
        fail("node --check passed a JS syntax error")
    r = run([node, os.path.join(tools, "validate.cjs")] + gltfs)
    print(r.stdout, end="")
    if r.returncode != 0:
        fail(f"glTF-Validator found errors (exit {r.returncode}): {r.stderr}")
    # Planted: an accessor reading past its buffer view must be an error.
    bad = os.path.join(o.work, "planted.gltf")
    g = json.load(open(gltfs[0]))
    g["accessors"][0]["count"] *= 2
    json.dump(g, open(bad, "w"))
    r = run([node, os.path.join(tools, "validate.cjs"), bad])
    if r.returncode != 1:
        fail(f"the validator passed a planted defect: {r.stdout}")
    print(f"{len(gltfs)} glTF files validated, {len(modules)} three.js modules checked; "
          f"{len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
