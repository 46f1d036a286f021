#!/usr/bin/python3
"""Checks that a Debian package list (scripts/deps/build.txt) suffices to build the CLI.

Proves what scripts/build-and-run.sh promises a bare Debian 12 machine without trusting this
machine's installed packages: every file the CLI's build used outside the source and build
trees must belong to a package of the list or to the recursive Depends/Pre-Depends of those
packages (or to an Essential package, which every Debian system has). The files are read from
the build itself, after it ran:
  - headers:    ninja's dependency records (`ninja -t deps`) of every object the target links
  - libraries:  the target's link inputs (`ninja -t inputs`), its `-lNAME` flags resolved by the
                compiler, and the shared libraries the program loads (`ldd`)
  - tools:      the compiler, ninja, cmake and pkg-config CMake used (CMakeCache.txt)
Each file is mapped to its package with `dpkg-query -S`; the dependency closure comes from
dpkg's status of the installed packages (`dpkg-query -W`), so neither the network nor apt's
package lists are needed.

Why not a clean root (debootstrap/mmdebstrap with only the list installed)? That is the direct
proof, but it downloads and unpacks about 400 packages and builds the CLI from scratch:
minutes of network and CPU per run on a shared CI machine, and no network here beyond apt.
This check reads what the real build used and runs in a few seconds; what it cannot see are
files the build did not record (CMake's own modules and package configs, which belong to
cmake and to the same -dev packages whose headers and libraries are checked).

Usage: scripts/check_build_deps.py [--build DIR] [--target sfit_cli] [--list scripts/deps/build.txt]
Exit 0: every file is covered. Exit 1: the packages missing from the list, with files each.
"""
import argparse
import functools
import os
import re
import subprocess
import sys
from collections import defaultdict


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, capture_output=True, text=True, **kw).stdout


def read_list(path):
    pkgs = []
    with open(path) as f:
        for line in f:
            name = line.split("#", 1)[0].strip()
            if name:
                pkgs.append(name)
    return pkgs


def build_files(build, target, source):
    """Every file outside the source and build trees the target's build used."""
    files = set()
    inputs = run(["ninja", "-C", build, "-t", "inputs", target]).split()
    objects = [i for i in inputs if i.endswith(".o")]
    if not objects:
        sys.exit(f"check_build_deps: ninja lists no objects for {target} in {build}")
    deps = run(["ninja", "-C", build, "-t", "deps"] + objects)
    recorded = 0
    for line in deps.splitlines():
        if line.startswith(" ") and line.strip():
            files.add(line.strip())
        elif "#deps" in line:
            recorded += 1
            if "deps not found" in line or "STALE" in line:
                sys.exit(f"check_build_deps: no current dependency record: {line.strip()}"
                         f" (build {target} first)")
    if recorded < len(objects):
        sys.exit(f"check_build_deps: {len(objects) - recorded} of {len(objects)} objects have no "
                 f"dependency record (build {target} first)")
    files.update(i for i in inputs if i.startswith("/"))  # libraries named by path
    # The link of the target is its last command: its -lNAME flags, resolved as the
    # compiler's linker would, and the program it writes (-o), whose loaded libraries count too.
    link = run(["ninja", "-C", build, "-t", "commands", target]).splitlines()[-1].split()
    link = link[link.index("&&") + 1:] if "&&" in link else link  # ": && c++ ... && :"
    compiler = link[1] if link[0].endswith("ccache") else link[0]
    program = None
    for k, w in enumerate(link):
        if w == "-o" and k + 1 < len(link):
            program = link[k + 1]
        elif w.startswith("-l") and len(w) > 2:
            for ext in (".so", ".a"):
                p = run([compiler, f"-print-file-name=lib{w[2:]}{ext}"]).strip()
                if os.path.isabs(p):
                    files.add(p)
                    break
    if not program or not os.path.exists(os.path.join(build, program)):
        sys.exit(f"check_build_deps: {target} is not built in {build} (no {program})")
    for line in run(["ldd", os.path.join(build, program)]).splitlines():
        m = re.search(r"(/\S+)\s+\(0x", line)
        if m:
            files.add(m.group(1))
    # The tools.
    cache = {}
    with open(os.path.join(build, "CMakeCache.txt")) as f:
        for line in f:
            m = re.match(r"([A-Za-z_]+):[A-Z]+=(.*)$", line.strip())
            if m:
                cache[m.group(1)] = m.group(2)
    for var in ("CMAKE_CXX_COMPILER", "CMAKE_MAKE_PROGRAM", "CMAKE_COMMAND", "PKG_CONFIG_EXECUTABLE",
                "CMAKE_AR", "CMAKE_RANLIB", "CMAKE_LINKER"):
        if cache.get(var, "").startswith("/"):
            files.add(cache[var])
    # Relative paths are the build tree's; absolute ones inside either tree are sfit's own.
    trees = [os.path.realpath(build) + "/", os.path.realpath(source) + "/"]
    out = set()
    for f in files:
        p = os.path.normpath(f if os.path.isabs(f) else os.path.join(build, f))
        if os.path.isabs(f) and not any(os.path.realpath(p).startswith(t) for t in trees):
            out.add(p)
    return out


def owners(paths):
    """path -> package, for the paths dpkg knows (exact paths; no wildcards in them)."""
    found = {}
    paths = [p for p in paths if not re.search(r"[*?\[\]]", p)]
    for k in range(0, len(paths), 500):
        chunk = paths[k:k + 500]
        r = subprocess.run(["dpkg-query", "-S"] + chunk, capture_output=True, text=True)
        for line in r.stdout.splitlines():
            if line.startswith("diversion by"):
                continue
            pkgs, _, path = line.partition(": ")
            if path in chunk:
                found[path] = pkgs.split(",")[0].strip().split(":")[0]
    return found


def candidates(path):
    """The spellings dpkg may have recorded for `path`: as given, with symlinks resolved, and
    both sides of Debian's merged /usr (/lib and /usr/lib are one directory)."""
    out = []
    for p in (path, os.path.realpath(path)):
        out.append(p)
        for a, b in (("/usr/lib/", "/lib/"), ("/usr/bin/", "/bin/"), ("/usr/sbin/", "/sbin/"),
                     ("/usr/lib64/", "/lib64/")):
            if p.startswith(a):
                out.append(b + p[len(a):])
            elif p.startswith(b):
                out.append(a + p[len(b):])
    return list(dict.fromkeys(out))


def map_packages(files):
    package = {}
    pending = {f: candidates(f) for f in files}
    for rnd in range(max(len(c) for c in pending.values()) if pending else 0):
        ask = {f: c[rnd] for f, c in pending.items() if rnd < len(c) and f not in package}
        found = owners(sorted(set(ask.values())))
        for f, p in ask.items():
            if p in found:
                package[f] = found[p]
    return package


@functools.lru_cache(maxsize=None)
def dpkg_status():
    fmt = "${Package}\t${Status}\t${Essential}\t${Provides}\t${Depends}\t${Pre-Depends}\n"
    return tuple(run(["dpkg-query", "-W", "-f", fmt]).splitlines())


def closure(roots):
    """The installed packages `roots` need: recursive Depends and Pre-Depends (every installed
    alternative of an 'a | b' group, and the installed providers of a virtual package), plus
    the Essential packages."""
    installed, provides, essential = {}, defaultdict(set), set()
    for line in dpkg_status():
        name, status, ess, prov, dep, pre = (line.split("\t") + [""] * 6)[:6]
        if not status.endswith(" installed"):
            continue
        deps = []
        for group in filter(None, (g.strip() for g in (dep + "," + pre).split(","))):
            deps.append([re.split(r"[\s(:]", alt.strip())[0] for alt in group.split("|")])
        installed[name] = deps
        if ess == "yes":
            essential.add(name)
        for p in filter(None, (x.strip() for x in prov.split(","))):
            provides[re.split(r"[\s(:]", p)[0]].add(name)
    missing = [r for r in roots if r not in installed and not provides.get(r)]
    seen, todo = set(), list(roots) + sorted(essential)
    while todo:
        p = todo.pop()
        if p in seen:
            continue
        seen.add(p)
        for q in (provides.get(p, set()) | ({p} if p in installed else set())):
            seen.add(q)
            for group in installed.get(q, []):
                todo.extend(a for a in group if a in installed or a in provides)
    return seen, missing


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    source = os.path.dirname(here)
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(source, "build"))
    ap.add_argument("--target", default="sfit_cli")
    ap.add_argument("--list", default=os.path.join(here, "deps", "build.txt"))
    a = ap.parse_args()

    roots = read_list(a.list)
    allowed, missing = closure(roots)
    if missing:
        sys.exit(f"check_build_deps: {a.list} names packages not installed here, so the build "
                 f"cannot show they suffice: {' '.join(missing)}")
    files = build_files(a.build, a.target, source)
    package = map_packages(files)
    unowned = sorted(f for f in files if f not in package)
    outside = defaultdict(list)
    for f, p in package.items():
        if p not in allowed:
            outside[p].append(f)
    print(f"check_build_deps: {a.target}: {len(files)} system files from "
          f"{len(set(package.values()))} packages; {os.path.relpath(a.list, source)} and its "
          f"dependencies: {len(allowed)} packages")
    for f in unowned:
        print(f"  not from any Debian package: {f}")
    for p in sorted(outside):
        ex = sorted(outside[p])
        print(f"  {p}: not in {os.path.basename(a.list)} nor a dependency of it "
              f"({len(ex)} files, e.g. {', '.join(ex[:3])})")
    if unowned or outside:
        # The fewest to add: those no other missing package depends on.
        first = [p for p in sorted(outside)
                 if p not in closure([q for q in outside if q != p])[0]]
        print(f"check_build_deps: FAILED: add {' '.join(first) or 'the packages'} "
              f"(the rest follow as their dependencies) to {a.list}")
        return 1
    print("check_build_deps: every header, library and tool is covered")
    return 0


if __name__ == "__main__":
    sys.exit(main())
