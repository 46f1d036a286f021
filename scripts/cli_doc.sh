#!/usr/bin/env bash
# Regenerates the docs made from the CLI itself:
#  - docs/cli.md's option lists: the text between "<!-- help: COMMAND -->" and "<!-- /help -->"
#    becomes the output of 'sfit COMMAND --help' ('sfit --help' for COMMAND "sfit");
#  - docs/options.md: the library's option table, 'sfit options --format markdown'.
# Run after adding or changing an option:
#   scripts/cli_doc.sh [path/to/sfit]          (default build/apps/sfit/sfit)
#   scripts/cli_doc.sh --check [path/to/sfit]  writes nothing; exit 1 if a committed doc differs
#                                              (the CTest test docs_generated runs this)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
check=0
if [ "${1:-}" = "--check" ]; then check=1; shift; fi
sfit="${1:-build/apps/sfit/sfit}"
/usr/bin/python3 - "$sfit" "$check" <<'PY'
import re, subprocess, sys
sfit, check = sys.argv[1], sys.argv[2] == "1"
def run(args):
    return subprocess.run([sfit] + args, capture_output=True, text=True, check=True).stdout
def help_of(m):
    cmd = m.group(1)
    out = run(["--help"] if cmd == "sfit" else [cmd, "--help"]).rstrip()
    return "<!-- help: %s -->\n```text\n%s\n```\n<!-- /help -->" % (cmd, out)
text = open("docs/cli.md").read()
docs = {"docs/cli.md": re.sub(r"<!-- help: (\S+) -->.*?<!-- /help -->", help_of, text, flags=re.S),
        "docs/options.md": run(["options", "--format", "markdown"])}
stale = []
for path, new in docs.items():
    try:
        old = open(path).read()
    except FileNotFoundError:
        old = None
    if old == new:
        continue
    if check:
        stale.append(path)
    else:
        open(path, "w").write(new)
        print("cli_doc: wrote %s" % path)
if stale:
    sys.exit("cli_doc: %s differ from what %s says: run scripts/cli_doc.sh and commit them"
             % (" and ".join(stale), sfit))
print("cli_doc: %s up to date" % ", ".join(docs) if check else "cli_doc: done")
PY
