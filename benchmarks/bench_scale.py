"""Benchmark: 10^6 steps of the Watt six-bar with forces, written in every format.

Run on demand (not part of the tests)::

    python benchmarks/bench_scale.py            # writes benchmarks/results/scale.json
    python benchmarks/bench_scale.py --steps 100000 --formats npz,parquet   # a quicker look

Each format is written by ``linkage-sym analyze SCENE -o FILE`` in a fresh
interpreter (one BLAS thread), which reports its own peak memory
(``ru_maxrss``: the interpreter, NumPy/SciPy and everything the run held at
its peak; checked against its ``VmHWM``, see :func:`run_child`) and the time
of the command alone (interpreter start and imports apart), so steps/s is
``steps / time``.  ``summary`` is the run without
``-o`` (solve and summarise, write nothing): what the writers add on top.

Targets (issue 15): under 1.5 GB peak for every format; at least 100,000
steps/s for npz and Parquet.  The machines are shared: the load average at the
start and end of the run is recorded with the figures.

Checked, so that the figures are of right results: 1000 random steps of each
columnar file (npz, Parquet, CSV) are compared with the same steps solved on
their own by ``Plan.run`` in this process (to 1e-12 of each quantity's largest
magnitude, statuses equal), the JSON file is parsed (strict: no NaN) and
spot-checked the same way, and every file has all 10^6 steps.
"""

from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import argparse  # noqa: E402
import csv  # noqa: E402
import json  # noqa: E402
import platform  # noqa: E402
import shutil  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

import linkage_sym  # noqa: E402
from linkage_sym import output  # noqa: E402
from linkage_sym.examples import example_dict  # noqa: E402
from linkage_sym.numeric.plan import compile_plan  # noqa: E402

HERE = Path(__file__).resolve().parent
FORMATS = ("summary", "npz", "parquet", "csv", "json")
TARGET_PEAK = 1.5 * 2**30
TARGET_RATE = 100_000
CHECKED = 1000

CHILD = r"""
import json, resource, sys, time
from linkage_sym.cli import main
import linkage_sym.output, linkage_sym.numeric.plan  # imports apart from the time
args = sys.argv[1:]
t = time.perf_counter()
code = main(args)
dt = time.perf_counter() - t
hwm = next(int(l.split()[1]) * 1024 for l in open("/proc/self/status") if l.startswith("VmHWM:"))
print(json.dumps({"code": code, "seconds": dt, "vm_hwm": hwm,
                  "peak_rss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024}),
      file=sys.stderr)
"""

BASELINE = r"""
import json, resource, sys
import linkage_sym.cli, linkage_sym.output, linkage_sym.numeric.plan
print(json.dumps({"peak_rss": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024}))
"""


def run_child(args) -> dict:
    """Run ``linkage-sym ARGS`` in a fresh interpreter; its time and peak memory.

    Started by a shell that forks it (not straight from this process): Linux
    carries a process's resident size at ``exec`` over into the new program's
    ``ru_maxrss``, and this process holds the files it checks (a Parquet file's
    columns: about 1 GB), which would count as the next child's peak.  The
    child's ``VmHWM`` (its own address space's high-water mark) is reported
    beside it as the independent measure; the two agree.
    """
    p = subprocess.run(["/bin/sh", "-c", '"$@"; exit $?', "sh", sys.executable, "-c", CHILD, *args],
                       capture_output=True, text=True)
    last = p.stderr.strip().splitlines()[-1]
    rec = json.loads(last)
    if rec["code"] != 0:
        raise SystemExit(f"analyze {' '.join(args)} failed:\n{p.stderr}")
    return rec


def check_columns(whole_cols, read, steps, what):
    """``read(name, idx)`` -> values of the file at steps ``idx`` equal ``whole_cols`` there."""
    for name, expect in whole_cols.items():
        got = np.asarray(read(name), dtype=float)
        scale = np.nanmax(np.abs(expect)) or 1.0
        same_nan = np.array_equal(np.isnan(got), np.isnan(expect))
        err = np.nanmax(np.abs(got - expect)) if not np.isnan(expect).all() else 0.0
        if not (same_nan and err <= 1e-12 * scale):
            raise SystemExit(f"{what}: column {name} differs from Plan.run: {err:.3g}")


def reference(scene, idx):
    """The steps ``idx`` of the sweep solved on their own by ``Plan.run`` (independent of the
    chunks): status and every numeric column."""
    plan = compile_plan(scene)
    q, qd, qdd = plan.sweep()
    res = plan.run({k: v[idx] for k, v in q.items()}, {k: v[idx] for k, v in qd.items()},
                   {k: v[idx] for k, v in qdd.items()})
    cols = {n: np.asarray(v, float) for n, v, _ in res.columns() if n not in ("status", "message")}
    return res.status.tolist(), cols


def check_file(fmt, path, scene, n_steps, rng):
    idx = np.sort(rng.choice(n_steps, CHECKED, replace=False))
    status, cols = reference(scene, idx)
    if fmt == "npz":
        with np.load(path) as z:
            assert len(z["step"]) == n_steps and z["step"][-1] == n_steps - 1
            assert z["status"][idx].tolist() == status
            check_columns(cols, lambda n: z[n][idx], idx, "npz")
    elif fmt == "parquet":
        import pyarrow.parquet as pq

        f = pq.ParquetFile(path)
        assert f.metadata.num_rows == n_steps
        table = pq.read_table(path, columns=["step", "status", *cols]).take(idx)
        assert table.column("step").to_pylist() == idx.tolist()
        assert table.column("status").to_pylist() == status
        check_columns(cols, lambda n: table.column(n).to_numpy(zero_copy_only=False), idx, "parquet")
    elif fmt == "csv":
        wanted = set(idx.tolist())
        rows = {}
        with open(path, newline="") as fh:
            reader = csv.reader(fh)
            names = next(reader)
            count = 0
            for row in reader:
                if count in wanted:
                    rows[count] = row
                count += 1
        assert count == n_steps
        at = {n: k for k, n in enumerate(names)}
        assert [rows[i][at["status"]] for i in idx] == status
        check_columns(cols, lambda n: [float(rows[i][at[n]]) if rows[i][at[n]] else np.nan
                                       for i in idx], idx, "csv")
    elif fmt == "json":
        wanted = set(idx.tolist())
        sample, count = [], 0
        for k, rec in enumerate(json_steps(path)):
            if k in wanted:
                sample.append(rec)
            count += 1
        assert count == n_steps
        assert [s["status"] for s in sample] == status
        driving = np.array([s["driving"]["A"] for s in sample])
        bx = np.array([s["joints"]["B"]["reaction"][0] for s in sample])
        check_columns({"driving.A": cols["driving.A"], "joints.B.reaction.x": cols["joints.B.reaction.x"]},
                      lambda n: driving if n == "driving.A" else bx, idx, "json")


def _refuse(constant):
    raise ValueError(f"{constant} in a strict JSON result")


def json_steps(path, block=2**24):
    """The step records of a result JSON file, one at a time (the file is never whole in
    memory): strict JSON (no NaN), parsed by the standard library's decoder."""
    dec = json.JSONDecoder(parse_constant=_refuse)
    with open(path, encoding="utf-8") as fh:
        buf = fh.read(block)
        start = buf.index('"steps": [') + len('"steps": [')
        buf, pos = buf[start:], 0
        while True:
            while pos < len(buf) and buf[pos] in " ,\n":
                pos += 1
            if pos < len(buf) and buf[pos] == "]":
                return
            try:
                rec, end = dec.raw_decode(buf, pos)
            except json.JSONDecodeError:
                more = fh.read(block)
                if not more:
                    raise
                buf, pos = buf[pos:] + more, 0
                continue
            yield rec
            pos = end
            if pos > block:
                buf, pos = buf[pos:], 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--steps", type=int, default=10**6)
    ap.add_argument("--formats", default=",".join(FORMATS))
    ap.add_argument("--repeats", type=int, default=3, help="runs of npz/parquet/summary (best time)")
    opts = ap.parse_args()
    formats = opts.formats.split(",")
    n = opts.steps
    d = example_dict("watt_sixbar")
    d["drivers"][0]["steps"] = n
    scene = linkage_sym.load_scene(d)
    tmp = Path(tempfile.mkdtemp(prefix="bench_scale_"))
    rng = np.random.default_rng(15)
    try:
        scene_path = tmp / "watt_sixbar.json"
        scene_path.write_text(json.dumps(d))
        base = json.loads(subprocess.run([sys.executable, "-c", BASELINE], capture_output=True,
                                         text=True, check=True).stdout)
        results = {
            "python": sys.version.split()[0],
            "numpy": np.__version__,
            "machine": platform.machine(),
            "processor": platform.processor() or "unknown",
            "cpus": os.cpu_count(),
            "memory_available_bytes": output.available_memory(),
            "load_average_at_start": os.getloadavg()[0],
            "scene": "watt_sixbar (linkage_sym/examples), outputs kinematics, reactions, driving, frame",
            "steps": n,
            "interpreter_with_imports_peak_rss_bytes": base["peak_rss"],
            "targets": {"peak_rss_bytes": TARGET_PEAK, "npz_parquet_steps_per_second": TARGET_RATE},
            "formats": {},
        }
        for fmt in formats:
            path = tmp / f"result.{fmt}"
            args = ["analyze", str(scene_path)] + ([] if fmt == "summary" else ["-o", str(path)])
            runs = [run_child(args) for _ in range(opts.repeats if fmt in ("summary", "npz", "parquet") else 1)]
            best = min(r["seconds"] for r in runs)
            rec = {
                "seconds": best,
                "steps_per_second": n / best,
                "peak_rss_bytes": max(r["peak_rss"] for r in runs),
                "vm_hwm_bytes": max(r["vm_hwm"] for r in runs),
                "runs": len(runs),
            }
            if abs(rec["peak_rss_bytes"] - rec["vm_hwm_bytes"]) > 0.05 * rec["vm_hwm_bytes"]:
                raise SystemExit(f"{fmt}: ru_maxrss {rec['peak_rss_bytes']} and VmHWM "
                                 f"{rec['vm_hwm_bytes']} disagree: a peak not of this run")
            if fmt != "summary":
                rec["file_bytes"] = path.stat().st_size
                check_file(fmt, path, scene, n, rng)
                rec["checked_steps"] = CHECKED
                path.unlink()
            rec["peak_under_target"] = rec["peak_rss_bytes"] < TARGET_PEAK
            if fmt in ("npz", "parquet"):
                rec["rate_meets_target"] = rec["steps_per_second"] >= TARGET_RATE
            results["formats"][fmt] = rec
            print(f"{fmt:8s} {rec['steps_per_second']:10.0f} steps/s  peak "
                  f"{rec['peak_rss_bytes'] / 2**20:7.0f} MB  {rec.get('file_bytes', 0) / 2**20:8.0f} MB file",
                  flush=True)
        results["load_average_at_end"] = os.getloadavg()[0]
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    out = HERE / "results"
    out.mkdir(exist_ok=True)
    name = "scale.json" if n == 10**6 and set(formats) == set(FORMATS) else f"scale_{n}.json"
    (out / name).write_text(json.dumps(results, indent=2) + "\n")
    print(json.dumps(results, indent=2))


if __name__ == "__main__":
    main()
