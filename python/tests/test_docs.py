"""Runs the ```python blocks of docs/python.md, in order, in one namespace (in a scratch
folder): the documented session must work as written."""
import os
import re

DOC = os.path.join(os.path.dirname(__file__), "..", "..", "docs", "python.md")


def test_docs_python_md_runs(tmp_path, monkeypatch, capsys):
    blocks = re.findall(r"```python\n(.*?)```", open(DOC, encoding="utf-8").read(), re.S)
    assert len(blocks) >= 6
    monkeypatch.chdir(tmp_path)
    ns = {}
    for i, code in enumerate(blocks):
        exec(compile(code, f"docs/python.md block {i + 1}", "exec"), ns)
    out = capsys.readouterr().out
    assert "--cutoff must be in (0, 90]" in out
