#!/usr/bin/env python3
"""The repository stands on its own: comments and docs cite only what a reader can look up.

Fails (exit 1, one file:line per finding) on references to documents that are not in the
repository: the project's internal "seed" documents (seed 000 .. seed 004, their numbered
sphere steps, bare seed numbers such as "000 eq. 74"), the seed digest, reference.md,
design.md, ../shared/docs and ../shared/seeds, and the digest's disagreement numbers written
as standalone D1 .. D29 tokens in a comment or a doc. Cite the paper, the public tutorial
(docs/models.md lists them) or the project's own docs/*.md instead, or state the fact.

Usage:
  check_external_refs.py <repository root>   check the tree; exit 0 if clean, 1 otherwise
  check_external_refs.py --self-test         plant a reference in a temporary tree and show
                                             that the check finds it and passes a clean file

Scans *.h *.cc *.md *.glsl *.frag *.vert *.py *.sh *.cmake *.txt *.json, skipping .git,
build*/ folders, fuzz/corpus, fuzz/regressions, fuzz/library-findings and this script.
Python 3 standard library only.
"""

import io
import os
import re
import subprocess
import sys
import tempfile
import tokenize

EXTENSIONS = ('.h', '.cc', '.md', '.glsl', '.frag', '.vert', '.py', '.sh', '.cmake', '.txt',
              '.json')
C_LIKE = ('.h', '.cc', '.glsl', '.frag', '.vert')
HASH_COMMENTS = ('.sh', '.cmake')
EXCLUDED_PREFIXES = ('fuzz/corpus/', 'fuzz/regressions/', 'fuzz/library-findings/')
SELF = 'tests/architecture/check_external_refs.py'  # names every pattern it looks for

# Checked on every line (comments, docs and string literals alike). Separators are required
# ("seed 004", "seeds 001/003", "seed-002"), so identifiers such as kSeed004, Seed000GgxCode
# and file names such as seed000_ggx_spot.json pass, as do RNG and fuzz seeds ("--seed 7",
# "seed 1", "fuzz seeds").
LINE_PATTERNS = (
    ('seed document', re.compile(r'\bseeds?[ -]+0{2}[0-4]\b', re.IGNORECASE)),
    ('seed document', re.compile(r'\b0{2}[0-4] ?(?:§|eqs?\.|Sphere\b|code\b|table\b)')),
    ('seed document', re.compile(r'\(0{2}[0-4](?:(?:[,/]| ?[-–] ?) ?0{2}[0-4])*[,)]')),
    ('seed document', re.compile(r'\bSphere\(\d+\)')),
    ('seed digest', re.compile(r'\bseeds?-digest\b|\bdigest §', re.IGNORECASE)),
    ('reference.md', re.compile(r'\breference\.md\b')),
    ('design.md', re.compile(r'\bdesign\.md\b')),
    ('shared docs', re.compile(r'\bshared/(?:docs|seeds)\b')),
)
# Checked in comment and doc text only: "D" alone is the NDF, and D2 may be code.
DISAGREEMENT = re.compile(r'(?<![\w.])D(?:[1-9]|1\d|2\d)(?![\w.])')

# Strings that are behaviour: printed to users or written into output files, which must stay
# byte-identical. Each entry is (path, exact text on the line, why). An entry whose file
# exists but no longer holds the text is reported, so the list cannot go stale.
ALLOWED = (
    # Empty: no user-visible string cites an outside document any more.
)


def c_comments(text):
    """(line number, comment text) of // and /* */ comments, skipping string, raw-string
    and character literals (and C++14 digit separators)."""
    out = []
    i, n, line = 0, len(text), 1

    def emit(start, end, first_line):
        for k, part in enumerate(text[start:end].split('\n')):
            out.append((first_line + k, part))

    while i < n:
        c = text[i]
        if c == '\n':
            line += 1
            i += 1
        elif text.startswith('//', i):
            end = text.find('\n', i)
            end = n if end < 0 else end
            emit(i + 2, end, line)
            i = end
        elif text.startswith('/*', i):
            end = text.find('*/', i + 2)
            end = n if end < 0 else end
            emit(i + 2, end, line)
            line += text.count('\n', i, end)
            i = end + 2
        elif c == 'R' and text.startswith('"', i + 1) and not (i and (text[i - 1].isalnum() and
                                                                    text[i - 1] not in 'uUL8')):
            open_paren = text.find('(', i + 2)
            delim = text[i + 2:open_paren] if open_paren >= 0 else ''
            end = text.find(')' + delim + '"', open_paren + 1) if open_paren >= 0 else -1
            end = n if end < 0 else end + len(delim) + 2
            line += text.count('\n', i, end)
            i = end
        elif c == '"' or (c == "'" and not (i and text[i - 1].isalnum() and i + 1 < n and
                                             text[i + 1].isalnum())):
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            i = j + 1 if j < n and text[j] == c else j
        else:
            i += 1
    return out


def python_comments(text):
    try:
        tokens = tokenize.generate_tokens(io.StringIO(text).readline)
        return [(t.start[0], t.string) for t in tokens if t.type == tokenize.COMMENT]
    except (tokenize.TokenError, SyntaxError, IndentationError):
        return hash_comments(text)


def hash_comments(text):
    out = []
    for number, line in enumerate(text.split('\n'), 1):
        m = re.search(r'(?:^|\s)#', line)
        if m:
            out.append((number, line[m.end():]))
    return out


def comment_lines(rel, text):
    """(line number, text) pairs where a disagreement number would be a reference."""
    name = os.path.basename(rel)
    if rel.endswith(C_LIKE):
        return c_comments(text)
    if rel.endswith('.py'):
        return python_comments(text)
    if rel.endswith(HASH_COMMENTS) or name == 'CMakeLists.txt':
        return hash_comments(text)
    if rel.endswith(('.md', '.txt')):
        return list(enumerate(text.split('\n'), 1))
    return []  # .json: data, no comments


def files(root):
    for dirpath, dirnames, filenames in os.walk(root):
        rel_dir = os.path.relpath(dirpath, root).replace(os.sep, '/')
        rel_dir = '' if rel_dir == '.' else rel_dir + '/'
        dirnames[:] = sorted(d for d in dirnames
                             if d != '.git' and not d.startswith('build') and
                             not (rel_dir + d + '/').startswith(EXCLUDED_PREFIXES))
        for name in sorted(filenames):
            rel = rel_dir + name
            if name.endswith(EXTENSIONS) and rel != SELF:
                yield rel


def check(root):
    findings, used, scanned = [], set(), 0
    for rel in files(root):
        with open(os.path.join(root, rel), encoding='utf-8', errors='replace') as f:
            text = f.read()
        scanned += 1
        lines = text.split('\n')
        hits = {}
        for number, line in enumerate(lines, 1):
            for kind, pattern in LINE_PATTERNS:
                if pattern.search(line):
                    hits.setdefault(number, set()).add(kind)
        for number, part in comment_lines(rel, text):
            if DISAGREEMENT.search(part):
                hits.setdefault(number, set()).add('disagreement number')
        for number in sorted(hits):
            line = lines[number - 1]
            allowed = [k for k, (path, snippet, _) in enumerate(ALLOWED)
                       if path == rel and snippet in line]
            if allowed:
                used.update(allowed)
                continue
            findings.append('%s:%d: %s: %s' % (rel, number, ', '.join(sorted(hits[number])),
                                               line.strip()))
    for k, (path, snippet, why) in enumerate(ALLOWED):
        if k not in used and os.path.exists(os.path.join(root, path)):
            findings.append('%s: allow-list entry no longer matches (%s): %s' %
                            (path, why, snippet))
    return scanned, findings


def self_test():
    planted = ('// GGX D as printed in seed 004 Sphere(13) (D21); see seeds-digest §2.14\n'
               '// and reference.md §5.\n')
    clean = ('Run `brdfit fit --seed 7`; seed 1 is the default and the fuzz seeds live in\n'
             'fuzz/corpus. D = alpha^2 / (pi ((n.h)^2 (alpha^2 - 1) + 1)^2), GL_TEXTURE_2D,\n'
             'kSeed004, Seed000GgxCode, data/scenes/seed000_ggx_spot.json, 1,458,000 cells.\n')
    with tempfile.TemporaryDirectory() as tmp:
        for rel, text in (('models/planted.h', planted), ('docs/clean.md', clean),
                          ('fuzz/corpus/scene/ignored.json', '{"note": "seed 000"}\n'),
                          ('build-asan/ignored.h', '// seed 000\n')):
            os.makedirs(os.path.dirname(os.path.join(tmp, rel)), exist_ok=True)
            with open(os.path.join(tmp, rel), 'w', encoding='utf-8') as f:
                f.write(text)
        run = subprocess.run([sys.executable, os.path.abspath(__file__), tmp],
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             universal_newlines=True)
    out = run.stdout
    problems = []
    if run.returncode != 1:
        problems.append('exit status %d, want 1' % run.returncode)
    kinds = {}  # "path:line" -> the kinds the check reported for it
    for line in out.split('\n'):
        parts = line.split(': ', 2)
        if len(parts) == 3:
            kinds[parts[0].rstrip(':')] = set(parts[1].split(', '))
    want = {'models/planted.h:1': {'seed document', 'seed digest', 'disagreement number'},
            'models/planted.h:2': {'reference.md'}}
    for where, expected in sorted(want.items()):
        if not expected <= kinds.get(where, set()):
            problems.append('%s: want %s, got %s' % (where, sorted(expected),
                                                     sorted(kinds.get(where, set()))))
    for unwanted in ('clean.md', 'ignored'):
        if unwanted in out:
            problems.append('false positive in ' + unwanted)
    if problems:
        print('check_external_refs --self-test: FAILED\n  ' + '\n  '.join(problems))
        print('output of the check:\n' + out)
        return 1
    print('check_external_refs --self-test: ok (planted references found, clean and excluded '
          'files passed)')
    return 0


def main(argv):
    if len(argv) != 2 or argv[1] in ('-h', '--help'):
        print(__doc__.strip())
        return 0 if len(argv) == 2 else 2
    if argv[1] == '--self-test':
        return self_test()
    root = argv[1]
    if not os.path.isdir(root):
        print('check_external_refs: %s: not a directory' % root)
        return 2
    scanned, findings = check(root)
    if findings:
        print('\n'.join(findings))
        print('check_external_refs: %d files, %d external reference(s): cite the paper, the '
              'tutorial (docs/models.md) or docs/*.md instead' % (scanned, len(findings)))
        return 1
    print('check_external_refs: %d files, no external references' % scanned)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
