"""Benchmark: the page's time to solve the whole sweep again after a drag, in a real browser.

Run on demand (not part of the tests)::

    python benchmarks/bench_page.py             # writes benchmarks/results/page.json
    python benchmarks/bench_page.py --repeats 11   # a quicker look

For the four-bar (``crank_rocker``), the Watt six-bar (``watt_sixbar``) and the class-III
six-bar (``sixbar_class3``) of ``linkage_sym/examples`` (each a 361-step sweep: a 360-step
cycle and its closing step), the page of ``linkage-sym view`` is opened in headless
Chromium (Selenium) and a ground pivot that is not the driver's is moved by
``window.linkageSym.moveJoint`` -- what a drag does -- back and forth by 1 % of the
mechanism's size, ``--repeats`` times after 5 unrecorded moves; each move is timed inside
the page with ``performance.now()``: the parameters re-derived from the joints' positions,
the assembly modes chosen, every step of the sweep solved (closed forms; the class-III
group by Newton's continuation), the statuses, and the page's tables refreshed.  The median
and the quartiles are recorded, and the same with the drawing of one frame after the move
(``step``: the canvas), with no layer and with every layer the scene has (velocities,
accelerations, forces, instant centres, transmission angles: their values at every step of
the sweep, for the arrows' scales).

Target (issue 30): well under a frame (16 ms) for the dyad mechanisms (the four-bar and
the Watt six-bar).  Where Chromium, its driver or Selenium is missing the script says so
and exits without writing.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent
sys.path.insert(0, str(ROOT))

from linkage_sym.examples import load_example  # noqa: E402
from linkage_sym.page import page_html  # noqa: E402
from tests.support import browser as support  # noqa: E402

MECHANISMS = {"crank_rocker": "four-bar (dyad)", "watt_sixbar": "Watt six-bar (dyads)",
              "sixbar_class3": "class-III six-bar (a Newton group)"}
TARGET_MS = 16.0
WARM = 5

TIMING = """
const [name, x0, y0, dx, n, warm, draw, layers] = arguments;
const api = window.linkageSym;
for (const l of layers) api.setLayer(l, true);
const out = [];
for (let i = 0; i < warm + n; i++) {
  const x = i % 2 ? x0 : x0 + dx;
  const t0 = performance.now();
  const got = api.moveJoint(name, x, y0);
  if (draw) api.step(0);
  const t = performance.now() - t0;
  if (got.error !== null) throw new Error(got.error);
  if (i >= warm) out.push(t);
}
for (const l of layers) api.setLayer(l, false);
return out;
"""


def quartiles(times: list) -> dict:
    q = statistics.quantiles(times, n=4)
    return {"median_ms": statistics.median(times), "q1_ms": q[0], "q3_ms": q[2],
            "min_ms": min(times), "runs": len(times)}


def measure(driver, folder: Path, name: str, repeats: int) -> dict:
    scene = load_example(name)
    path = folder / f"{name}.html"
    path.write_text(page_html(scene))
    driver.get(path.as_uri())
    summary = driver.execute_script("return window.linkageSym.summary()")
    driven = {d.joint for d in scene.drivers}
    pivot = next(j for j in scene.joints if "ground" in j.links and j.type == "R"
                 and j.name not in driven)
    L = scene.characteristic_length()
    args = [pivot.name, pivot.at[0], pivot.at[1], 0.01 * L, repeats, WARM]
    available = driver.execute_script("return window.linkageSym.layersAvailable()")
    every = [n for n, why in available.items() if why is None]
    out = {"mechanism": MECHANISMS[name], "steps": scene.steps, "moved": pivot.name,
           "statuses": summary["counts"]}
    for key, draw, layers in (("solve", False, []), ("solve_and_draw", True, []),
                              ("solve_and_draw_every_layer", True, every)):
        times = driver.execute_script(TIMING, *args, draw, layers)
        out[key] = quartiles(times)
    out["layers"] = every
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=41, help="timed moves per case (default 41)")
    ap.add_argument("--out", default=str(HERE / "results" / "page.json"))
    args = ap.parse_args(argv)
    why = support.missing()
    if why is not None:
        print(f"bench_page: skipped: {why}; nothing written")
        return 0
    driver = support.chromium()
    try:
        version = driver.capabilities.get("browserVersion", "unknown")
        with tempfile.TemporaryDirectory() as tmp:
            results = {name: measure(driver, Path(tmp), name, args.repeats) for name in MECHANISMS}
    finally:
        driver.quit()
    report = {
        "python": platform.python_version(), "machine": platform.machine(),
        "cpus": os.cpu_count(), "load_average_at_start": os.getloadavg()[0],
        "browser": f"headless Chromium {version} (Selenium)",
        "time": "wall time inside the page (performance.now()) of one moveJoint of a ground "
                "pivot by 1 % of the mechanism's size: the whole sweep solved again",
        "target_ms_dyad_mechanisms": TARGET_MS,
        "mechanisms": results,
        "load_average_at_end": os.getloadavg()[0],
    }
    Path(args.out).write_text(json.dumps(report, indent=2) + "\n")
    for name, r in results.items():
        cells = ", ".join(f"{k} {r[k]['median_ms']:.1f} ms (min {r[k]['min_ms']:.1f})" for k in
                          ("solve", "solve_and_draw", "solve_and_draw_every_layer"))
        print(f"{name:14s} ({r['steps']} steps): {cells}")
    print(f"load average {report['load_average_at_start']:.1f} at the start, "
          f"{report['load_average_at_end']:.1f} at the end; written {args.out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
