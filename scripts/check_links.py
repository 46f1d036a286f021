#!/usr/bin/python3
"""Every relative link of README.md and docs/*.md names a file the repository tracks (git
ls-files; and, with #anchor, a heading of that file), so a reader who clones the project can
follow it: not a file beside the clone, nor one only a build makes.

    scripts/check_links.py [REPO]      exit 0 when all hold, 1 with one line per broken link
"""

import glob
import os
import re
import subprocess
import sys

root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), ".."))
LINK = re.compile(r"!?\[[^\]]*\]\(([^)\s]+)\)")


def anchors(path):
    """GitHub's heading anchors: lower case, punctuation dropped, spaces as hyphens."""
    out = set()
    in_code = False
    for line in open(path, encoding="utf-8"):
        if line.lstrip().startswith("```"):
            in_code = not in_code
        m = None if in_code else re.match(r"#+\s+(.*)", line)
        if m:
            a = re.sub(r"[^\w\- ]", "", m.group(1).strip().lower()).replace(" ", "-")
            out.add(a)
    return out


tracked = [f for f in subprocess.run(["git", "-C", root, "ls-files"], capture_output=True,
                                     text=True, check=True).stdout.split("\n") if f]


def is_tracked(full):
    """A tracked file, or a folder holding one."""
    rel = os.path.relpath(full, root)
    return rel == "." or any(t == rel or t.startswith(rel + "/") for t in tracked)


bad = []
files = [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md")))
for f in files:
    in_code = False
    for n, line in enumerate(open(f, encoding="utf-8"), 1):
        if line.lstrip().startswith("```"):
            in_code = not in_code
        if in_code:
            continue
        for target in LINK.findall(line):
            if re.match(r"[a-z]+:", target):  # http:, https:, mailto:
                continue
            path, _, anchor = target.partition("#")
            full = os.path.normpath(os.path.join(os.path.dirname(f), path)) if path else f
            rel = os.path.relpath(f, root)
            if not os.path.exists(full) or not is_tracked(full):
                bad.append(f"{rel}:{n}: {target}: no such file in the repository")
            elif anchor and full.endswith(".md") and anchor not in anchors(full):
                bad.append(f"{rel}:{n}: {target}: no such heading")
for b in bad:
    print(b)
print(f"{len(files)} files, {len(bad)} broken links", file=sys.stderr)
sys.exit(1 if bad else 0)
