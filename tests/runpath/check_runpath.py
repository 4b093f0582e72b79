#!/usr/bin/env python3
"""RUNPATH / RPATH of the ELF files we build, stage and install (cmake/wefmRunpath.cmake).

An empty entry (leading, trailing or doubled ':') or a relative one is searched from the current
working directory, so a library planted there would be loaded instead of the real one.

  check_runpath.py elf --readelf R [--file F]... [--list L]... [--tree D]...
      every listed file (must exist; L: a file of paths, one a line) and every ELF executable or shared
      object under the trees: each RUNPATH/RPATH entry must be absolute or $ORIGIN-based.
  check_runpath.py selftest --readelf R --cc CC --work D
      the check above flags libraries linked with an empty, a trailing-empty and a relative entry,
      and passes an $ORIGIN-relative one (so the first check can fail).
  check_runpath.py hijack --readelf R --cc CC --work D --library LIB [--cli CLI [--model STEP]]
                          [--python PY --package P]
      plants a dummy of every library LIB and CLI need in an empty working directory, runs the CLI
      (and `wefm model STEP`, which opens the CAD plugin) and `import wefm` there under
      LD_DEBUG=libs: nothing may be looked up in that directory.
"""
import argparse
import os
import re
import shutil
import subprocess
import sys

ELF_MAGIC = b"\x7fELF"
ET_EXEC, ET_DYN = 2, 3
_ENTRY = re.compile(r"\((RUNPATH|RPATH)\)\s+Library (?:runpath|rpath): \[(.*)\]")


def is_linked_elf(path):
    """An ELF executable or shared object (not an object file or a static archive)."""
    try:
        with open(path, "rb") as f:
            head = f.read(18)
    except OSError:
        return False
    if len(head) < 18 or head[:4] != ELF_MAGIC:
        return False
    little = head[5] == 1
    return int.from_bytes(head[16:18], "little" if little else "big") in (ET_EXEC, ET_DYN)


def bad_entries(value):
    """Entries of a ':'-separated search path that the loader would resolve from the cwd."""
    bad = []
    for entry in value.split(":"):
        if entry == "":
            bad.append("(empty: the current directory)")
        elif not (entry.startswith("/") or re.match(r"^(\$ORIGIN|\$\{ORIGIN\})(/|$)", entry)):
            bad.append("%s (relative: from the current directory)" % entry)
    return bad


def search_paths(readelf, path):
    out = subprocess.run([readelf, "-d", "-W", path], check=True, capture_output=True, text=True).stdout
    return _ENTRY.findall(out)


def check_files(readelf, files):
    """Prints one line per file; returns the number of files with a bad entry."""
    failures = 0
    for path in files:
        paths = search_paths(readelf, path)
        problems = ["%s %s" % (tag, b) for tag, value in paths for b in bad_entries(value)]
        shown = "; ".join("%s [%s]" % p for p in paths) or "no RUNPATH"
        print("%-4s %s: %s" % ("BAD" if problems else "ok", path, shown))
        for p in problems:
            print("       %s" % p)
        failures += bool(problems)
    return failures


def collect(args):
    files = list(args.file)
    for listed in args.list:
        with open(listed) as f:
            files += [line.strip() for line in f if line.strip()]
    missing = [f for f in files if not os.path.isfile(f)]
    for tree in args.tree:
        for root, dirs, names in os.walk(tree):
            dirs[:] = [d for d in dirs if d != "CMakeFiles"]  # compiler probes, object files
            files += [os.path.join(root, n) for n in sorted(names)
                      if not os.path.islink(os.path.join(root, n)) and is_linked_elf(os.path.join(root, n))]
    unique = []
    for f in files:
        if f not in unique and f not in missing:
            unique.append(f)
    return unique, missing


def cmd_elf(args):
    files, missing = collect(args)
    for m in missing:
        print("MISSING %s" % m)
    failures = check_files(args.readelf, files)
    print("%d ELF files checked, %d with an empty or relative entry, %d missing"
          % (len(files), failures, len(missing)))
    return 1 if failures or missing or not files else 0


def build_so(cc, work, name, ldflags, source="int wefm_probe(void) { return 1; }\n"):
    src = os.path.join(work, name + ".c")
    with open(src, "w") as f:
        f.write(source)
    out = os.path.join(work, name)
    subprocess.run([cc, "-shared", "-fPIC", src, "-o", out] + ldflags, check=True)
    return out


def cmd_selftest(args):
    os.makedirs(args.work, exist_ok=True)
    cases = {  # name: (linker flags, expected failure)
        "empty.so": (["-Wl,-rpath,:"], True),
        "trailing.so": (["-Wl,-rpath,/usr/lib:"], True),
        "relative.so": (["-Wl,-rpath,lib"], True),
        "old_rpath.so": (["-Wl,--disable-new-dtags,-rpath,/usr/lib::/lib"], True),
        "origin.so": (["-Wl,-rpath,$ORIGIN/../lib:/usr/lib"], False),
        "none.so": ([], False),
    }
    wrong = 0
    for name, (flags, expect_bad) in cases.items():
        path = build_so(args.cc, args.work, name, flags)
        flagged = check_files(args.readelf, [path]) == 1
        if flagged != expect_bad:
            print("  -> expected %s" % ("BAD" if expect_bad else "ok"))
            wrong += 1
    return 1 if wrong else 0


def needed(readelf, path):
    out = subprocess.run([readelf, "-d", "-W", path], check=True, capture_output=True, text=True).stdout
    return re.findall(r"\(NEEDED\)\s+Shared library: \[(.*)\]", out)


def plant_dummies(args, work):
    """A dummy of every library our files need, in `work`; each leaves a marker file if loaded."""
    sonames = set()
    for path in [args.library] + ([args.cli] if args.cli else []):
        sonames.update(s for s in needed(args.readelf, path) if not s.startswith("ld-linux"))
    source = ('#include <stdio.h>\n__attribute__((constructor)) static void planted(void) {\n'
              '  FILE* f = fopen("%s", "w"); if (f) fclose(f); }\n' % os.path.join(work, "LOADED"))
    for soname in sorted(sonames):
        build_so(args.cc, work, soname, ["-Wl,-soname," + soname], source)
    return sorted(sonames)


def cwd_lookups(log_text, work):
    """Lines of an LD_DEBUG=libs log where the loader tried a file relative to or inside `work`."""
    hits = []
    for line in log_text.splitlines():
        m = re.search(r"trying file=(\S+)", line)
        if m and (not m.group(1).startswith("/") or m.group(1).startswith(work + "/")):
            hits.append(line.strip())
    return hits


def run_probe(label, cmd, env, work):
    log = os.path.join(work, "ld-debug")
    env = dict(env, LD_DEBUG="libs", LD_DEBUG_OUTPUT=log)
    proc = subprocess.run(cmd, cwd=work, env=env, capture_output=True, text=True)
    text = ""
    for name in os.listdir(work):
        if name.startswith("ld-debug"):
            with open(os.path.join(work, name)) as f:
                text += f.read()
            os.remove(os.path.join(work, name))
    hits = cwd_lookups(text, work)
    loaded = os.path.exists(os.path.join(work, "LOADED"))
    print("%-4s %s: exit %d, %d lookups in the working directory%s"
          % ("BAD" if hits or loaded else "ok", label, proc.returncode, len(hits),
             ", a planted library was loaded" if loaded else ""))
    # The plain name first: that is the file the loader would open in the working directory.
    for h in sorted(hits, key=lambda line: "/" in line.split("file=")[1])[:5]:
        print("       " + h)
    if not text:
        print("BAD  %s: no LD_DEBUG output (the probe did not run?)\n%s" % (label, proc.stderr))
        return 1
    return 1 if hits or loaded else 0


def cmd_hijack(args):
    work = os.path.realpath(args.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for name in ("library", "cli", "package"):  # the probes run in `work`
        if getattr(args, name):
            setattr(args, name, os.path.abspath(getattr(args, name)))
    planted = plant_dummies(args, work)
    print("planted in %s: %s" % (work, " ".join(planted)))
    env = {k: v for k, v in os.environ.items() if k not in ("LD_LIBRARY_PATH", "WEFM_LIBRARY")}
    failures = 0
    if args.cli:
        failures += run_probe("wefm --version", [args.cli, "--version"], env, work)
    if args.cli and args.model:  # the CAD plugin is opened by a model command only
        failures += run_probe("wefm model (CAD plugin)",
                              [args.cli, "model", os.path.abspath(args.model), "-o", "model-out", "-q"],
                              env, work)
    if args.python:
        failures += run_probe("import wefm (staged package)", [args.python, "-c", "import wefm"],
                              dict(env, PYTHONPATH=args.package), work)
        failures += run_probe("import wefm (WEFM_LIBRARY=%s)" % args.library,
                              [args.python, "-c", "import wefm"],
                              dict(env, PYTHONPATH=args.package, WEFM_LIBRARY=args.library), work)
    return 1 if failures else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = parser.add_subparsers(dest="command", required=True)
    elf = sub.add_parser("elf")
    elf.add_argument("--file", action="append", default=[])
    elf.add_argument("--list", action="append", default=[])
    elf.add_argument("--tree", action="append", default=[])
    selftest = sub.add_parser("selftest")
    hijack = sub.add_parser("hijack")
    for p in (elf, selftest, hijack):
        p.add_argument("--readelf", default="readelf")
    for p in (selftest, hijack):
        p.add_argument("--cc", required=True)
        p.add_argument("--work", required=True)
    hijack.add_argument("--library", required=True)
    hijack.add_argument("--cli")
    hijack.add_argument("--model")
    hijack.add_argument("--python")
    hijack.add_argument("--package")
    args = parser.parse_args()
    return {"elf": cmd_elf, "selftest": cmd_selftest, "hijack": cmd_hijack}[args.command](args)


if __name__ == "__main__":
    sys.exit(main())
