#!/usr/bin/env python3
"""Stops `wefm flatten` at random moments while it rewrites an existing good output, and checks that
the output is, every time, either the old file or the complete new one (apps/wefm/output_file.hpp).

    kill_rewrite.py WEFM [--triangles N] [--kills K] [--seed S] [--signals term,term2,kill] [--keep DIR]

The old file is the face flattened at s = 0, the new one at s = 1, so the two differ in every vt
line. Each run copies the old file into place, starts `wefm flatten --s 1` on it and sends, after a
random delay within the measured length of a whole run (counted from the moment every thread of
the tool holds or handles SIGTERM, read from /proc: before that the loader, not the tool, is
running; output_tests.wait_for_handlers), one of: SIGTERM (a clean stop: exit 6 or,
when it came too late, 0), two SIGTERMs (the second ends the process at once) or SIGKILL. After a
SIGTERM no temporary file may remain either; after a SIGKILL one may (nothing can remove it), but
the target is still whole. ctest runs it on a mid-size face with a few kills; the closing check of
issue 29 runs it with --triangles 2000000 --kills 10.
"""
import argparse
import glob
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_tests  # noqa: E402
import meshes  # noqa: E402
from output_tests import wait_for_handlers  # noqa: E402  (every thread holds or handles SIGTERM)


def grid_for(triangles):
    # patch(n, n) has 2 (n-1)^2 triangles.
    n = max(3, int(round((triangles / 2) ** 0.5)) + 1)
    return n, n


def flatten(wefm, src, out, s, extra=()):
    t0 = time.monotonic()
    p = subprocess.run([wefm, "flatten", src, "-o", out, "--s", str(s), "-q", *extra], capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"reference run failed ({p.returncode}): {p.stderr}")
    return time.monotonic() - t0


def leftovers(folder, name):
    return glob.glob(os.path.join(folder, "." + name + ".tmp-*"))


def one_run(wefm, src, target, old, new, mode, delay):
    shutil.copyfile(old, target)
    p = subprocess.Popen([wefm, "flatten", src, "-o", target, "--s", "1", "-q"], stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, text=True)
    wait_for_handlers(p)
    time.sleep(delay)
    if mode == "kill":
        p.send_signal(signal.SIGKILL)
    else:
        p.send_signal(signal.SIGTERM)
        if mode == "term2":
            time.sleep(random.uniform(0, 0.05))
            if p.poll() is None:
                p.send_signal(signal.SIGTERM)
    _, err = p.communicate()
    with open(target, "rb") as f:
        got = f.read()
    state = "old" if got == old_bytes(old) else "new" if got == old_bytes(new) else None
    problems = []
    if state is None:
        problems.append(f"target is neither the old nor the new file ({len(got)} bytes)")
    if mode == "term" and p.returncode not in (0, 6):
        problems.append(f"exit {p.returncode} after one SIGTERM, expected 6 (or 0 when it came too late)\n{err}")
    if mode == "term" and p.returncode == 6 and "SIGTERM" not in err:
        problems.append(f"exit 6 without saying why:\n{err}")
    if mode != "kill" and leftovers(os.path.dirname(target), os.path.basename(target)):
        problems.append(f"temporary files left: {leftovers(os.path.dirname(target), os.path.basename(target))}")
    for t in leftovers(os.path.dirname(target), os.path.basename(target)):
        os.unlink(t)  # after a SIGKILL: expected, cleared for the next run
    return state, p.returncode, problems


_cache = {}


def old_bytes(path):
    if path not in _cache:
        with open(path, "rb") as f:
            _cache[path] = f.read()
    return _cache[path]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("wefm")
    ap.add_argument("--triangles", type=int, default=60000)
    ap.add_argument("--kills", type=int, default=6)
    ap.add_argument("--seed", type=int, default=None)
    ap.add_argument("--signals", default="term,term2,kill")
    ap.add_argument("--keep", default=None, help="work in this folder and keep it (default: a temporary one)")
    a = ap.parse_args()
    cli_tests.WEFM = os.path.abspath(a.wefm)  # the executable wait_for_handlers waits for
    seed = a.seed if a.seed is not None else random.randrange(1 << 30)
    random.seed(seed)
    modes = a.signals.split(",")
    work = a.keep or tempfile.mkdtemp(prefix="wefm_kill_rewrite_")
    os.makedirs(work, exist_ok=True)
    try:
        V, T = meshes.patch(*grid_for(a.triangles))
        src = os.path.join(work, "face.obj")
        meshes.write_obj(src, V, T)
        old, new = os.path.join(work, "old.obj"), os.path.join(work, "new.obj")
        flatten(a.wefm, src, old, 0)
        t_full = flatten(a.wefm, src, new, 1)
        if old_bytes(old) == old_bytes(new):
            sys.exit("the s = 0 and s = 1 layouts are the same file: the test could not tell them apart")
        print(f"{len(T)} triangles, a whole run {t_full:.2f} s, seed {seed}")
        target = os.path.join(work, "out", "uv.obj")
        os.makedirs(os.path.dirname(target), exist_ok=True)
        failed = 0
        for k in range(a.kills):
            mode = modes[k % len(modes)]
            # Counted from the moment the tool holds SIGTERM (wait_for_handlers).
            delay = random.uniform(0.0, 1.1 * t_full)
            state, code, problems = one_run(a.wefm, src, target, old, new, mode, delay)
            print(f"kill {k + 1}: {mode:5s} after {delay:6.3f} s -> exit {code}, target is the {state} file"
                  + ("" if not problems else "  FAIL: " + "; ".join(problems)))
            failed += bool(problems)
        return 1 if failed else 0
    finally:
        if not a.keep:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
