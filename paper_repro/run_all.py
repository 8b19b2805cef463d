"""Every reproducible item of every source, in one table per source.

Run from the repository root:

    python -m paper_repro            (or: python paper_repro/run_all.py)
    python -m paper_repro --only printing_forces --samples 50

For every source (README, "Sources" [1]-[4]) a table of each printed value, the computed one,
their difference, the tolerance and the status (reproduced / within input rounding / erratum /
not reproducible, with the reason below the row); then the self-checks, values no source prints
(linkage_sym against an independent computation, which each row names); see items.py for the two
kinds and what each status means.  The summary counts the two kinds apart, and so do the
reports ``--json PATH`` and ``--markdown PATH`` write (report.py).
The exit status is 1 if any item drifted (a reproduced or within-rounding item beyond its
tolerance, an erratum its derivation no longer shows, a self-check whose two computations
disagree), else 0.

Each script contributes through ``items()`` (or, for a script that has none, the adapter of
adapters.py); SCRIPTS lists them in the order they run.
``--samples`` is passed to the scripts whose ``items`` take it (Monte-Carlo spreads).
"""

from __future__ import annotations

import argparse
import importlib
import inspect
import pathlib
import sys
import time

HERE = pathlib.Path(__file__).resolve().parent
for _p in (str(HERE), str(HERE.parent)):
    if _p not in sys.path:
        sys.path.insert(0, _p)

from adapters import ADAPTERS  # noqa: E402
from items import summary, table  # noqa: E402
from report import to_json, to_markdown  # noqa: E402

SCRIPTS = (
    "printing_mechanism",  # [1] geometry, inertia forces, printing force, the paper's arithmetic
    "printing_forces",  # [1] reactions and the superposition intermediates, against linkage_sym
    "shaper_distances",  # [4] example 3-7, Table 3-1
    "song_wang_errata",  # [3] every erratum, by the derivation
    "song_wang_designs",  # [3] the three designs, simulated
    "four_bar_design",  # [2] design by K, examples 2-9 and 2-10 (items from adapters.py)
    "chapter3_polygons_exercises",  # [4] example 3-1's polygons, exercises (items from adapters.py)
)


def collect(scripts=SCRIPTS, samples: int | None = None, timings: dict | None = None) -> list:
    """The items of ``scripts`` (module names in this folder), in order."""
    out = []
    for name in scripts:
        mod = importlib.import_module(name)
        get = getattr(mod, "items", None) or ADAPTERS[name]  # a script's own items() first
        kwargs = {}
        if samples is not None and "samples" in inspect.signature(get).parameters:
            kwargs["samples"] = samples
        t0 = time.perf_counter()
        got = list(get(**kwargs))
        if timings is not None:
            timings[name] = time.perf_counter() - t0
        out += got
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m paper_repro", description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", action="append", choices=SCRIPTS, help="run only this script (repeatable)")
    ap.add_argument("--samples", type=int, help="Monte-Carlo samples for the rounding spreads (default: each script's own)")
    ap.add_argument("--json", metavar="PATH", type=pathlib.Path,
                    help="also write the report as JSON (printed values and self-checks apart)")
    ap.add_argument("--markdown", metavar="PATH", type=pathlib.Path,
                    help="also write the report as a Markdown page (printed values and self-checks apart)")
    args = ap.parse_args(argv)
    timings = {}
    items = collect(tuple(args.only or SCRIPTS), args.samples, timings)
    print(table(items))
    drifted = [it for it in items if not it.ok]
    print(f"{len(items)} items: {summary(items)}"
          f"  (scripts: {', '.join(f'{k} {v:.1f} s' for k, v in timings.items())})")
    for it in drifted:
        src = f"[{it.source}]" if it.source is not None else "self-check"
        print(f"DRIFTED: {src} {it.where}: {it.name}: printed {it.printed}, computed {it.computed}")
    if args.json:
        args.json.write_text(to_json(items), encoding="utf-8")
    if args.markdown:
        args.markdown.write_text(to_markdown(items), encoding="utf-8")
    return 1 if drifted else 0


if __name__ == "__main__":
    sys.exit(main())
