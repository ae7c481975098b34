"""The npm tools of tests/export (tools/gltf: glTF-Validator, three.js), installed once per build
folder with `npm ci` from the committed package-lock.json."""
import json
import os
import shutil
import subprocess

FILES = ("package.json", "package-lock.json", "validate.cjs", "render_three.cjs")


def ensure_tools(src, dest):
    """Copies tools/gltf into dest and runs `npm ci` there unless every locked package is
    installed at its locked version. Returns ("ok" | "absent" | "failed", message): absent when
    node or npm is not installed (the caller skips), failed when npm ci fails (the caller fails)."""
    npm = shutil.which("npm")
    if not shutil.which("node") or not npm:
        return "absent", "node/npm not installed (scripts/setup-deps.sh installs them)"
    os.makedirs(dest, exist_ok=True)
    for f in FILES:
        shutil.copy(os.path.join(src, f), dest)
    lock = json.load(open(os.path.join(src, "package-lock.json")))
    current = True
    for key, pkg in lock["packages"].items():
        if not key:
            continue
        have = os.path.join(dest, key, "package.json")
        if not os.path.exists(have) or json.load(open(have)).get("version") != pkg["version"]:
            current = False
    if not current:
        r = subprocess.run([npm, "ci", "--no-audit", "--no-fund"], cwd=dest, capture_output=True,
                           text=True)
        if r.returncode != 0:
            return "failed", f"npm ci in {dest} failed: {r.stdout}{r.stderr}"
    return "ok", ""
