#!/usr/bin/env python3
"""`wefm batch --shard I/N` and `--skip-existing`: batch_scale_tests.py WEFM_BINARY CASE.

Sharding: the N shards of a batch are disjoint, cover it, differ in size by one face at most, do not
depend on the order of a list file, and write the bytes a whole run writes. Skipping: a face whose
OBJ and report exist from an earlier run is not flattened again (its files are left untouched) and
shows as "skipped"; a face with a missing, unparsable or failed report is flattened again.
Standard library only.
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_tests  # noqa: E402
import meshes  # noqa: E402
from cli_tests import check, run  # noqa: E402

NAMES = ["c", "a", "e", "b", "g", "d", "f"]


def make_faces(tmp):
    """Seven small faces (differently curved, so their outputs differ) in tmp/in."""
    d = os.path.join(tmp, "in")
    os.makedirs(d)
    meshes_by_name = {}
    for k, name in enumerate(NAMES):
        V, T = meshes.patch(nx=4 + k % 3, ny=4)
        V = [(x, y, z * (1 + 0.2 * k)) for x, y, z in V]
        meshes.write_obj(os.path.join(d, name + ".obj"), V, T)
        meshes_by_name[name] = (V, T)
    return d, meshes_by_name


def summary(path):
    return {row["name"]: row for row in json.load(open(path))}


def read(path):
    with open(path, "rb") as f:
        return f.read()


def case_shard(tmp):
    d, faces = make_faces(tmp)
    whole = os.path.join(tmp, "whole")
    run("batch", d, "-o", whole, "-j", "2", "-q", expect=0)
    listed = os.path.join(tmp, "list.txt")
    with open(listed, "w") as f:  # the same faces, another order
        f.write("".join(os.path.join(d, name + ".obj") + "\n" for name in reversed(sorted(NAMES))))
    n = 3
    for source in (d, listed):
        seen = {}
        for i in range(n):
            out = os.path.join(tmp, "shards", os.path.basename(source), str(i))
            js = out + ".json"
            run("batch", source, "-o", out, "-j", "2", "-q", "--shard", f"{i}/{n}", "--summary-json", js, expect=0)
            rows = summary(js)
            for name in rows:
                check(name not in seen, f"{name} in shards {seen.get(name)} and {i}")
                seen[name] = i
                V, T = faces[name]
                cli_tests.check_uv_obj(os.path.join(out, name + ".obj"), V, T)
                check(read(os.path.join(out, name + ".obj")) == read(os.path.join(whole, name + ".obj")),
                      f"shard {i}: {name}.obj differs from the whole run's")
            written = sorted(f[:-4] for f in os.listdir(out) if f.endswith(".obj"))
            check(written == sorted(rows), f"shard {i} wrote {written}, its summary lists {sorted(rows)}")
        check(sorted(seen) == sorted(NAMES), f"{source}: shards cover {sorted(seen)}, not {sorted(NAMES)}")
        sizes = [list(seen.values()).count(i) for i in range(n)]
        check(max(sizes) - min(sizes) <= 1, f"{source}: shard sizes {sizes}")
        if source == d:
            by_dir = dict(seen)
        else:
            check(seen == by_dir, f"a list file in another order shards differently: {seen} vs {by_dir}")
    # More shards than faces: an empty shard is not an error and writes nothing.
    empty = os.path.join(tmp, "empty")
    p = run("batch", d, "-o", empty, "-q", "--shard", f"{len(NAMES)}/{len(NAMES) + 1}", expect=0)
    check("0 faces" in p.stdout, f"an empty shard's summary:\n{p.stdout}")
    check(not os.path.exists(empty) or os.listdir(empty) == [], f"an empty shard wrote {os.listdir(empty)}")
    # Bad shards are usage errors before any work, and the message says I is 0-based.
    for bad in ["3/3", "-1/3", "1", "a/b", "0/0", "1/2/3", "1.0/2", "0/-2"]:
        out = os.path.join(tmp, "bad")
        p = run("batch", d, "-o", out, "--shard", bad, expect=2)
        check("--shard" in p.stderr, f"--shard {bad!r}: the message does not name the option:\n{p.stderr}")
        check(not os.path.exists(out), f"--shard {bad!r} created the output folder")
    p = run("batch", d, "-o", os.path.join(tmp, "bad"), "--shard", "3/3", expect=2)
    check("0-based" in p.stderr and "0..2" in p.stderr, f"--shard 3/3 message:\n{p.stderr}")


def case_skip_existing(tmp):
    d, faces = make_faces(tmp)
    with open(os.path.join(d, "broken.obj"), "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nf 1 2 7\n")
    out = os.path.join(tmp, "out")
    js = os.path.join(tmp, "summary.json")
    first = run("batch", d, "-o", out, "-j", "2", "-q", "--summary-json", js)
    check(first.returncode not in (0, 2), f"the broken face did not fail the batch: exit {first.returncode}")
    before = summary(js)
    stat = {n: os.stat(os.path.join(out, n + ".obj")) for n in NAMES}
    # A removed report and a report cut short: those two faces are flattened again.
    os.remove(os.path.join(out, "a.json"))
    with open(os.path.join(out, "b.json"), "r+") as f:
        f.truncate(20)
    p = run("batch", d, "-o", out, "-j", "2", "--skip-existing", "--summary-json", js)
    check(p.returncode == first.returncode, f"resumed batch exit {p.returncode}, the first run's {first.returncode}")
    rows = summary(js)
    for name in NAMES:
        obj = os.path.join(out, name + ".obj")
        now = os.stat(obj)
        same_file = (now.st_ino, now.st_mtime_ns) == (stat[name].st_ino, stat[name].st_mtime_ns)
        if name in ("a", "b"):
            check(rows[name]["status"] == "ok", f"{name} (report missing or cut) not flattened again: {rows[name]}")
            check(not same_file, f"{name}.obj was not rewritten")
            json.load(open(os.path.join(out, name + ".json")))
        else:
            check(rows[name]["status"] == "skipped" and rows[name]["exit_code"] == 0, f"{name}: {rows[name]}")
            check(same_file, f"{name}.obj was rewritten although its outputs existed")
            check(rows[name]["triangles"] == len(faces[name][1]), f"{name}: triangles {rows[name]['triangles']}")
            check(rows[name]["score"] == before[name]["score"], f"{name}: score {rows[name]} vs {before[name]}")
            check(f"{name}: skipped (outputs exist)" in p.stderr, f"no progress line for skipped {name}:\n{p.stderr}")
    check(rows["broken"]["status"] not in ("ok", "skipped"), f"a failed face was skipped: {rows['broken']}")
    check(f"({len(NAMES) - 2} skipped: outputs exist)" in p.stdout, f"summary line:\n{p.stdout}")
    # A report that says the face failed (written by hand here) does not count as done.
    with open(os.path.join(out, "c.json"), "w") as f:
        json.dump({"status": "failed", "exit_code": 3}, f)
    run("batch", d, "-o", out, "-q", "--skip-existing", "--summary-json", js)
    check(summary(js)["c"]["status"] == "ok", f"c with a failed report: {summary(js)['c']}")
    # Without the flag every output is written again.
    run("batch", d, "-o", out, "-q", "--summary-json", js)
    check(all(summary(js)[n]["status"] == "ok" for n in NAMES), f"without --skip-existing: {summary(js)}")
    kept = [n for n in NAMES if (lambda s: (s.st_ino, s.st_mtime_ns))(os.stat(os.path.join(out, n + ".obj")))
            == (stat[n].st_ino, stat[n].st_mtime_ns)]
    check(not kept, f"{kept} kept without --skip-existing")


CASES = dict(shard=case_shard, skip_existing=case_skip_existing)


if __name__ == "__main__":
    sys.exit(cli_tests.run_cases(CASES, "batch_scale_tests.py"))
