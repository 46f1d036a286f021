#!/usr/bin/env bash
# Regenerates the option lists in docs/cli.md from the CLI's own help: the text between
# "<!-- help: COMMAND -->" and "<!-- /help -->" becomes the output of 'sfit COMMAND --help'
# ('sfit --help' for COMMAND "sfit"). Run after adding or changing an option:
#   scripts/cli_doc.sh [path/to/sfit]       (default build/apps/sfit/sfit)
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
sfit="${1:-build/apps/sfit/sfit}"
/usr/bin/python3 - "$sfit" docs/cli.md <<'PY'
import re, subprocess, sys
sfit, doc = sys.argv[1], sys.argv[2]
text = open(doc).read()
def help_of(m):
    cmd = m.group(1)
    args = [sfit, "--help"] if cmd == "sfit" else [sfit, cmd, "--help"]
    out = subprocess.run(args, capture_output=True, text=True, check=True).stdout.rstrip()
    return "<!-- help: %s -->\n```text\n%s\n```\n<!-- /help -->" % (cmd, out)
new = re.sub(r"<!-- help: (\S+) -->.*?<!-- /help -->", help_of, text, flags=re.S)
open(doc, "w").write(new)
print("cli_doc: %d option lists in %s" % (len(re.findall(r"<!-- help: ", new)), doc))
PY
