#!/usr/bin/env python3
"""End-to-end tests of how `wefm` writes its outputs and stops: output_tests.py WEFM_BINARY CASE.

  full_disk    every kind of output to /dev/full fails with exit 3 and the errno; a regular file that
               cannot be written whole (RLIMIT_FSIZE, a full disk in miniature) leaves the previous
               file and no temporary; /dev/null works
  collisions   outputs that are an input or each other (also through links and other spellings), and
               empty names, are refused with exit 2 before any work; batch names of folders given as
               "dir/" are the folder's name
  signals      SIGINT and SIGTERM at random moments of flatten, mesh and batch: exit 6 or a complete
               run, never a partial output; a second signal ends the process and leaves no temporary
  time_limit   --time-limit: exit 7 with previous outputs kept; bad values are usage errors
  permissions  a replaced output keeps the permission bits of the file it replaces
"""
import glob
import json
import os
import random
import resource
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_tests  # noqa: E402
import meshes  # noqa: E402
from cli_tests import Failure, check, run  # noqa: E402


def temporaries(folder):
    return glob.glob(os.path.join(folder, ".*.tmp-*"))


def write_patch(tmp, name="p.obj", n=6):
    V, T = meshes.patch(n, n)
    src = os.path.join(tmp, name)
    meshes.write_obj(src, V, T)
    return src, V, T


def old_file(path, text="OLD CONTENT\n"):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    return text


def content(path):
    with open(path) as f:
        return f.read()


def run_limited(args, fsize):
    """wefm with RLIMIT_FSIZE: writes past `fsize` bytes fail with EFBIG (SIGXFSZ ignored)."""
    def limit():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (fsize, fsize))
    return subprocess.run([cli_tests.WEFM, *map(str, args)], capture_output=True, text=True, timeout=120,
                          preexec_fn=limit)


def case_full_disk(tmp):
    src, V, T = write_patch(tmp)
    out = os.path.join(tmp, "o.obj")
    for opt, target in [("-o", "/dev/full"), ("--report", "/dev/full"), ("--svg", "/dev/full"),
                        ("--write-topology", "/dev/full")]:
        args = ["flatten", src, "-q"] + (["-o", out] if opt != "-o" else []) + [opt, target]
        p = run(*args, expect=3)
        check("/dev/full" in p.stderr and "No space left" in p.stderr, f"{opt} /dev/full: message {p.stderr!r}")
    p = run("flatten", src, "-q", "-o", "/dev/null", "--report", "/dev/null", "--svg", "/dev/null", expect=0)
    # batch --summary-json
    d = os.path.join(tmp, "in")
    os.makedirs(d)
    write_patch(d, "a.obj")
    p = run("batch", d, "-o", os.path.join(tmp, "bout"), "-q", "--summary-json", "/dev/full", expect=3)
    check("No space left" in p.stderr, f"batch --summary-json /dev/full: {p.stderr!r}")
    # mesh -o (the library's wefm_domain_mesh_write_obj) and its other outputs
    for opt in ["-o", "--domain-obj", "--report", "--svg"]:
        args = ["mesh", src, "--size", "0.2", "-q", "-o", os.path.join(tmp, "m.obj")]
        if opt == "-o":
            args[args.index("-o") + 1] = "/dev/full"
        else:
            args += [opt, "/dev/full"]
        p = run(*args, expect=3)
        check("No space left" in p.stderr, f"mesh {opt} /dev/full: {p.stderr!r}")
    # A regular file that cannot be written whole: the previous one stays, no temporary is left.
    big_src, _, _ = write_patch(tmp, "big.obj", 40)
    for opt in ["-o", "--report", "--svg", "--write-topology"]:
        target = os.path.join(tmp, "lim", "t" + opt.strip("-").replace("-", "_"))
        old = old_file(target)
        args = ["flatten", big_src, "-q"] + (["-o", os.path.join(tmp, "lim", "o.obj")] if opt != "-o" else [])
        # The OBJ of 3000 triangles is ~150 KB, the report ~5 KB: 2000 bytes fit none of them.
        p = run_limited(args + [opt, target], 2000)
        check(p.returncode == 3, f"{opt} over RLIMIT_FSIZE: exit {p.returncode}\n{p.stderr}")
        check(content(target) == old, f"{opt}: the previous file was changed")
        check("File too large" in p.stderr, f"{opt}: message {p.stderr!r}")
        check(not temporaries(os.path.dirname(target)), f"{opt}: temporaries left {temporaries(os.path.dirname(target))}")
    # The same for the library's own writer (wefm mesh -o).
    target = os.path.join(tmp, "lim", "mesh.obj")
    old = old_file(target)
    p = run_limited(["mesh", big_src, "--size", "0.05", "-q", "-o", target, "--domain-obj", os.path.join(tmp, "d.obj")], 2000)
    check(p.returncode == 3 and content(target) == old, f"mesh -o over RLIMIT_FSIZE: exit {p.returncode}, file changed?")
    check(not temporaries(os.path.join(tmp, "lim")), "mesh -o left a temporary")
    # A symbolic link to an output is followed: the file it names is replaced, the link stays.
    real = os.path.join(tmp, "real.obj")
    old_file(real)
    link = os.path.join(tmp, "link.obj")
    os.symlink(real, link)
    run("flatten", src, "-q", "-o", link, expect=0)
    check(os.path.islink(link) and content(real).startswith("# wefm"), "the link was replaced or its file not written")


def case_collisions(tmp):
    src, V, T = write_patch(tmp)
    before = content(src)
    o = os.path.join(tmp, "o.obj")
    os.symlink(src, os.path.join(tmp, "link.obj"))
    os.link(src, os.path.join(tmp, "hard.obj"))
    spelled = os.path.join(tmp, ".", "sub", "..", "p.obj")
    os.makedirs(os.path.join(tmp, "sub"))
    cases = [["-o", src], ["-o", o, "--report", src], ["-o", o, "--svg", src], ["-o", o, "--write-topology", src],
             ["-o", o, "--report", o], ["-o", o, "--svg", os.path.join(tmp, "x.svg"), "--report", os.path.join(tmp, "x.svg")],
             ["-o", os.path.join(tmp, "link.obj")], ["-o", os.path.join(tmp, "hard.obj")], ["-o", spelled],
             ["-o", ""], ["-o", o, "--report", ""], ["-o", o, "--svg", ""]]
    for extra in cases:
        p = run("flatten", src, *extra, expect=2)
        check(p.stderr.strip(), f"flatten {extra}: exit 2 without a message")
        check(content(src) == before, f"flatten {extra}: the input was changed")
        check(not os.path.exists(o), f"flatten {extra}: wrote an output")
    p = run("flatten", src, "-o", o, "--report", o, expect=2)
    check("same file" in p.stderr, f"message: {p.stderr!r}")
    seams = os.path.join(tmp, "p.seam")
    open(seams, "w").close()
    run("flatten", src, "--seams", seams, "-o", seams, expect=2)
    # Two outputs that do not exist yet, spelt differently.
    run("flatten", src, "-o", os.path.join(tmp, "new", "a.obj"), "--report", os.path.join(tmp, "new", ".", "a.obj"), expect=2)
    # mesh: -o against --domain-obj and the input.
    run("mesh", src, "--size", "0.2", "-o", o, "--domain-obj", o, expect=2)
    run("mesh", src, "--size", "0.2", "-o", src, expect=2)
    check(content(src) == before, "mesh overwrote its input")
    # batch: outputs into the input folder over the inputs, a summary over an input, -o "".
    d = os.path.join(tmp, "in")
    os.makedirs(d)
    a, _, _ = write_patch(d, "a.obj")
    a_before = content(a)
    run("batch", d, "-o", d, expect=2)
    run("batch", d, "-o", os.path.join(tmp, "bo"), "--summary-json", a, expect=2)
    run("batch", d, "-o", "", expect=2)
    check(content(a) == a_before, "batch overwrote an input")
    # A list of face folders written "dir/" and "dir/.": the outputs are named after the folder.
    for k in ("f1", "f2"):
        os.makedirs(os.path.join(tmp, "faces", k))
        write_patch(os.path.join(tmp, "faces", k), "face.obj")
    lst = os.path.join(tmp, "list.txt")
    with open(lst, "w") as f:
        f.write(os.path.join(tmp, "faces", "f1") + "/\n" + os.path.join(tmp, "faces", "f2") + "/.\n")
    bo = os.path.join(tmp, "bo2")
    run("batch", lst, "-o", bo, "-q", expect=0)
    names = sorted(os.listdir(bo))
    check(names == ["f1.json", "f1.obj", "f2.json", "f2.obj"], f"batch outputs of dir/ entries: {names}")


def start(args):
    return subprocess.Popen([cli_tests.WEFM, *map(str, args)], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)


def wait_for_handlers(p, limit=30.0):
    """Until every thread of the process catches or blocks SIGINT and SIGTERM (SigCgt, SigBlk in /proc:
    the tool blocks them across its huge-page re-exec, and a blocked signal waits for the handlers),
    or it has ended.
    Before main() a signal ends the process by default, which says nothing about the tool; on a
    loaded machine the loader alone can take longer than any fixed delay."""
    want = (1 << (signal.SIGINT - 1)) | (1 << (signal.SIGTERM - 1))
    tool = os.path.realpath(cli_tests.WEFM)
    t0 = time.monotonic()
    while p.poll() is None and time.monotonic() - t0 < limit:
        try:
            # Between fork and exec the child is still this Python, whose masks say nothing about the tool.
            if os.path.realpath(f"/proc/{p.pid}/exe") != tool:
                time.sleep(0.002)
                continue
            # Every thread: the libraries start threads of their own before main() (OpenBLAS's pool),
            # with the signals open; until main() has held them and re-executed, a signal can land on
            # one of those and end the process by default. Handlers (SigCgt) are the process's.
            ready = True
            for tid in os.listdir(f"/proc/{p.pid}/task"):
                try:
                    with open(f"/proc/{p.pid}/task/{tid}/status") as f:
                        masks = {l.split(":")[0]: int(l.split()[1], 16) for l in f if l.startswith(("SigCgt:", "SigBlk:"))}
                except OSError:
                    continue  # that thread has ended
                ready = ready and (masks.get("SigCgt", 0) | masks.get("SigBlk", 0)) & want == want
        except (OSError, ValueError):
            return
        if ready:
            return
        time.sleep(0.002)


def case_signals(tmp):
    src, V, T = write_patch(tmp, "big.obj", 120)  # ~28k triangles: a run of a few tenths of a second
    rng = random.Random(int.from_bytes(os.urandom(4), "little"))
    d = os.path.join(tmp, "in")
    os.makedirs(d)
    for k in range(4):
        write_patch(d, f"f{k}.obj", 60)
    out = os.path.join(tmp, "out")
    commands = {
        "flatten": ["flatten", src, "-o", os.path.join(out, "f.obj"), "--report", os.path.join(out, "f.json"), "--s", "1"],
        "mesh": ["mesh", src, "--size", "0.01", "-o", os.path.join(out, "m.obj"), "--report", os.path.join(out, "m.json")],
        "batch": ["batch", d, "-o", os.path.join(out, "b"), "-j", "2", "--summary-json", os.path.join(out, "b.json")],
    }
    for name, args in commands.items():
        t0 = time.monotonic()
        p = run(*args, "-q", expect=0)
        whole = time.monotonic() - t0
        outputs = [args[i + 1] for i, a in enumerate(args) if a in ("-o", "--report", "--summary-json")]
        for sig in (signal.SIGINT, signal.SIGTERM, signal.SIGINT, signal.SIGTERM):
            for path in outputs:
                if os.path.isfile(path):
                    old_file(path)
            # Counted from when the handlers are in place: before that no handler can exist yet. Within
            # the first 3 s at most: a sanitizer build runs ten times slower, and the stages that
            # matter (reading, solving, meshing, writing) all start by then on this face.
            delay = rng.uniform(0.0, min(3.0, max(0.1, whole)))
            p = start([*args, "-q"])
            wait_for_handlers(p)
            time.sleep(delay)
            p.send_signal(sig)
            _, err = p.communicate(timeout=120)
            what = f"{name}: {signal.Signals(sig).name} after {delay:.3f} of {whole:.3f} s"
            check(p.returncode in (0, 6), f"{what}: exit {p.returncode}\n{err}")
            if p.returncode == 6:
                check("cancelled" in err, f"{what}: exit 6 without saying so: {err!r}")
            for path in outputs:
                if os.path.isfile(path):
                    text = content(path)
                    check(text == "OLD CONTENT\n" or text.startswith(("# wefm", "{", "[")), f"{what}: {path} is partial")
                    if p.returncode == 0:
                        check(text != "OLD CONTENT\n", f"{what}: exit 0 but {path} was not written")
            for folder in {os.path.dirname(x) for x in outputs}:
                check(not temporaries(folder), f"{what}: temporaries left {temporaries(folder)}")
    # A second signal ends the process at once (killed by the signal), still without a partial file.
    big2, _, _ = write_patch(tmp, "big2.obj", 300)  # ~180k triangles: the OBJ takes a while to write
    target = os.path.join(out, "second.obj")
    for _ in range(3):
        old = old_file(target)
        p = start(["flatten", big2, "-o", target, "--s", "0", "-q"])
        wait_for_handlers(p)
        time.sleep(rng.uniform(0.05, 0.6))
        p.send_signal(signal.SIGTERM)
        p.send_signal(signal.SIGTERM)
        p.communicate(timeout=120)
        check(p.returncode in (0, 6, -signal.SIGTERM), f"two SIGTERMs: exit {p.returncode}")
        text = content(target)
        check(text == old or text.startswith("# wefm"), "two SIGTERMs left a partial file")
        check(not temporaries(out), f"two SIGTERMs left temporaries {temporaries(out)}")


def case_time_limit(tmp):
    src, V, T = write_patch(tmp, "big.obj", 120)
    out = os.path.join(tmp, "out", "o.obj")
    old = old_file(out)
    for cmd in (["flatten", src, "-o", out, "--s", "2"], ["mesh", src, "--size", "0.004", "-o", out]):
        p = run(*cmd, "--time-limit", "0.001", "-q", expect=7)
        check("time limit" in p.stderr, f"{cmd[0]}: message {p.stderr!r}")
        check(content(out) == old, f"{cmd[0]}: the previous output was changed")
    d = os.path.join(tmp, "in")
    os.makedirs(d)
    for k in range(3):
        write_patch(d, f"f{k}.obj", 40)
    p = run("batch", d, "-o", os.path.join(tmp, "bo"), "--time-limit", "0.001", "-q", expect=7)
    for bad in ["0", "-1", "abc", "nan", "inf", ""]:
        run("flatten", src, "-o", out, "--time-limit", bad, expect=2)
    run("flatten", src, "-o", out, "--time-limit", "600", "-q", expect=0)
    check(content(out).startswith("# wefm"), "a run within its time limit did not write")
    h = run("flatten", "--help", expect=0).stdout
    check("--time-limit" in h and "7  time limit" in h, "--help does not document --time-limit and exit 7")


def case_permissions(tmp):
    src, V, T = write_patch(tmp)
    out = os.path.join(tmp, "out", "o.obj")
    report = os.path.join(tmp, "out", "r.json")
    for path in (out, report):
        old_file(path)
        os.chmod(path, 0o640)
    run("flatten", src, "-o", out, "--report", report, "-q", expect=0)
    for path in (out, report):
        check(content(path) != "OLD CONTENT\n", f"{path} was not replaced")
        mode = os.stat(path).st_mode & 0o7777
        check(mode == 0o640, f"{os.path.basename(path)}: mode {oct(mode)} after replacing a 0640 file")
    fresh = os.path.join(tmp, "out", "fresh.obj")
    old_mask = os.umask(0o022)
    try:
        run("flatten", src, "-o", fresh, "-q", expect=0)
    finally:
        os.umask(old_mask)
    mode = os.stat(fresh).st_mode & 0o7777
    check(mode == 0o644, f"a new output has mode {oct(mode)} under umask 022")


CASES = dict(full_disk=case_full_disk, collisions=case_collisions, signals=case_signals, time_limit=case_time_limit,
             permissions=case_permissions)


if __name__ == "__main__":
    sys.exit(cli_tests.run_cases(CASES, "output_tests.py"))
