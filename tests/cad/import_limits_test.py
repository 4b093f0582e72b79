#!/usr/bin/env python3
"""The CAD import is bounded and can be stopped: import_limits_test.py WEFM CYLINDER.step CAD_SAMPLE_DIR

Open CASCADE cannot be interrupted, so `wefm model` and `mesh-model` run the import in a child
process (apps/wefm/child_process.hpp) that is killed at --time-limit or on Ctrl-C. Inputs:
  * a BREP whose header announces 999999999 locations (Open CASCADE took 73 s to refuse one);
  * the sample screw.step with one coordinate changed to 1.E308 (line 414), which keeps Open
    CASCADE busy for more than 10 minutes (BSplCLib::KnotAnalysis); taken from CAD_SAMPLE_DIR and
    copied to a temporary folder. Without it those checks are skipped (the BREP ones still run).
  * the checked-in cylinder.step with one entity name garbled (#12 CART'ESIAN_POINT), on which
    Open CASCADE 7.6 dereferences a null point and crashes (found by fuzz_cad_import).
Checks: exit 7 with a message naming the limit; exit 6 on SIGINT and SIGTERM; a second SIGTERM kills
the tool, and no import process outlives it; a crash inside Open CASCADE is exit 3 naming the signal,
not a crash of the tool. A hang fails by the subprocess timeout (limit + 60 s).
"""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

LIMIT = 3


def run(wefm, args, timeout):
    t0 = time.monotonic()
    p = subprocess.run([wefm, *args], capture_output=True, text=True, timeout=timeout)
    return p, time.monotonic() - t0


def processes_with(marker):
    """Live processes whose command line contains `marker` (the import child is a fork of the tool)."""
    found = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/cmdline", "rb") as f:
                if marker.encode() in f.read():
                    with open(f"/proc/{pid}/stat") as s:
                        if s.read().split(")")[-1].split()[0] != "Z":
                            found.append(int(pid))
        except OSError:
            pass
    return found


def wait_gone(marker, seconds=10):
    end = time.monotonic() + seconds
    while processes_with(marker) and time.monotonic() < end:
        time.sleep(0.1)
    return processes_with(marker)


def check_time_limit(wefm, model, tmp):
    out = os.path.join(tmp, "out_" + os.path.basename(model))
    for command, extra in (("model", ["-o", out]), ("mesh-model", ["-o", out + ".msh", "--size", "1"])):
        p, took = run(wefm, [command, model, *extra, "--time-limit", str(LIMIT), "-q"], LIMIT + 60)
        print(f"{command} {os.path.basename(model)} --time-limit {LIMIT}: exit {p.returncode} after {took:.1f} s")
        if p.returncode == 3:  # Open CASCADE refused it within the limit: also an answer, said as such
            assert os.path.basename(model) in p.stderr, p.stderr
            continue
        assert p.returncode == 7, (command, p.returncode, p.stderr)
        assert "time limit" in p.stderr and os.path.basename(model) in p.stderr, p.stderr
        assert not os.path.exists(os.path.join(out, "index.json")), "a timed-out import wrote an index"
        assert not wait_gone(model), f"an import process outlived {command}"


def check_signals(wefm, model, tmp):
    for sig in (signal.SIGINT, signal.SIGTERM):
        p = subprocess.Popen([wefm, "model", model, "-o", os.path.join(tmp, "sig"), "-q"], stdout=subprocess.PIPE,
                             stderr=subprocess.PIPE, text=True)
        time.sleep(1.0)  # inside Open CASCADE by now
        t0 = time.monotonic()
        p.send_signal(sig)
        _, err = p.communicate(timeout=60)
        print(f"model {os.path.basename(model)}: {signal.Signals(sig).name} -> exit {p.returncode} "
              f"after {time.monotonic() - t0:.2f} s")
        assert p.returncode == 6 and "cancelled" in err, (sig, p.returncode, err)
        assert not wait_gone(model), "an import process outlived the tool"
    # A second signal ends the tool at once; the import child goes with it.
    p = subprocess.Popen([wefm, "model", model, "-o", os.path.join(tmp, "sig2"), "-q"], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    time.sleep(1.0)
    p.send_signal(signal.SIGTERM)
    p.send_signal(signal.SIGTERM)
    p.communicate(timeout=60)
    assert p.returncode in (-signal.SIGTERM, 6), p.returncode
    assert not wait_gone(model), "an import process outlived the tool after a second SIGTERM"


def check_crash(wefm, cylinder, tmp):
    with open(cylinder) as f:
        text = f.read()
    assert "#12 = CARTESIAN_POINT(" in text
    bad = os.path.join(tmp, "null_point.step")
    with open(bad, "w") as f:
        f.write(text.replace("#12 = CARTESIAN_POINT(", "#12 = CART'ESIAN_POINT(", 1))
    for command, extra in (("model", ["-o", os.path.join(tmp, "crash")]), ("mesh-model", ["-o", bad + ".msh", "--size", "2"])):
        p, _ = run(wefm, [command, bad, *extra, "-q"], 120)
        print(f"{command} null_point.step: exit {p.returncode}: {p.stderr.strip()}")
        # Open CASCADE versions that refuse the file instead of crashing answer exit 3 as well.
        assert p.returncode == 3 and "null_point.step" in p.stderr, (command, p.returncode, p.stderr)


def main():
    wefm, cylinder, samples = sys.argv[1], sys.argv[2], sys.argv[3]
    with tempfile.TemporaryDirectory(prefix="wefm_cad_limits_") as tmp:
        check_crash(wefm, cylinder, tmp)
        brep = os.path.join(tmp, "locations.brep")
        with open(brep, "w") as f:
            f.write("DBRep_DrawableShape\n\nCASCADE Topology V1, (c) Matra-Datavision\nLocations 999999999\n")
        check_time_limit(wefm, brep, tmp)
        screw = os.path.join(samples, "screw.step")
        if not os.path.isfile(screw):
            print(f"skipped the STEP checks: {screw} not found")
            return 0
        mutated = os.path.join(tmp, "screw_1e308.step")
        shutil.copyfile(screw, mutated)
        with open(mutated) as f:
            lines = f.readlines()
        assert "2.93633" in lines[413], lines[413]
        lines[413] = lines[413].replace("2.93633", "1.E308")
        with open(mutated, "w") as f:
            f.writelines(lines)
        check_time_limit(wefm, mutated, tmp)
        check_signals(wefm, mutated, tmp)
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
