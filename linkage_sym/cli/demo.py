"""``linkage-sym demo`` and ``linkage-sym examples``: the shipped example scenes.

``demo`` analyses examples and writes their result, motion diagrams, coupler
curves, efforts, reactions, frame loads and shaking force and moment, and for a
hinged example Song and Wang's (1992) balancing (:func:`demo_balance`); without
``--example``, also the self-contained page of every shipped example and
``gallery.html`` linking them (:mod:`linkage_sym.page.gallery`); ``examples`` lists
them.
"""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

from linkage_sym.cli.common import OptionError, check_outputs as _check_outputs, driver_kinds
from linkage_sym.cli.common import load as _load, stem as _stem

__all__ = ["DEMO_EXAMPLES", "cmd_demo", "cmd_examples", "demo_balance", "register"]

DEMO_EXAMPLES = ("crank_rocker", "shaper")


def cmd_examples(args) -> int:
    from linkage_sym.examples import example_names, example_path

    for name in example_names():
        print(f"{name:28s} {example_path(name)}")
    return 0



def cmd_demo(args) -> int:
    from linkage_sym.examples import example_names, example_path

    names = args.example or list(DEMO_EXAMPLES)
    unknown = [n for n in names if n not in example_names()]
    if unknown:
        raise OptionError(f"--example: unknown {', '.join(map(repr, unknown))}; known examples: "
                          f"{', '.join(example_names())}")
    _check_outputs(folders=[("-o/--output", args.output)])
    from linkage_sym.model import Effects
    from linkage_sym.numeric.plan import compile_plan
    from linkage_sym.numeric.results.result import UNASSEMBLABLE
    from linkage_sym.output.stats import ranges_text, step_ranges
    from linkage_sym.plotting import frame_loads, plot_all

    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    runs = {}  # each example's run: its page's warnings panel opens with its warnings
    for name in names:
        scene = _load(example_path(name))
        stem = _stem(scene)
        analysis = runs[name] = compile_plan(scene).run()
        result = out / f"{stem}_result.json"
        result.write_text(json.dumps(analysis.to_dict()) + "\n")
        files = plot_all(scene, analysis, out)
        # the shaking force and moment: the same motion with inertia as the only effect
        shaking_scene = dataclasses.replace(
            scene,
            effects=Effects(inertia=True, gravity=None, loads=False),
            outputs=("frame",),
        )
        shaking = compile_plan(shaking_scene).run()
        files.append(frame_loads(shaking_scene, shaking, out / f"{stem}_shaking.png"))
        n_ok = int(analysis.ok.sum())
        bad = step_ranges(analysis.status == UNASSEMBLABLE,
                          {k: d["q"] for k, d in analysis.drivers.items()})
        gaps = f" ({ranges_text(UNASSEMBLABLE, bad, driver_kinds(scene))})" if bad.count else ""
        print(f"{name}: {n_ok}/{analysis.n_steps} steps solved{gaps}; wrote")
        print(f"  {result}")
        for f in files:
            print(f"  {f}")
        if all(j.type == "R" for j in scene.joints):
            files = demo_balance(scene, stem, out)
            print(f"{name}: balancing conditions and force-balancing counterweights; wrote")
            for f in files:
                print(f"  {f}")
    if not args.example:  # the demo itself: every shipped example's page, and their gallery
        from linkage_sym.page.gallery import write_gallery

        gallery, *pages = write_gallery(out, example_names(), runs)
        print(f"the page of every shipped example and their gallery (open it in a browser; "
              "nothing is fetched); wrote")
        print(f"  {gallery}")
        print(f"  {len(pages)} pages in {pages[0].parent}")
    print(f"demo output is in {out.resolve()}")
    return 0



def demo_balance(scene, stem, out) -> list:
    """Song and Wang's (1992) balancing of a hinged example: JSON and before/after plots.

    The plots have the names ``balance --plots`` gives them (``<stem>_shaking_force_polar.png``,
    ``<stem>_shaking_moment.png``): one plot, one name."""
    from linkage_sym.balancing.report import balance_document
    from linkage_sym.plotting.balance import shaking_force_polar, shaking_moment_curve

    doc = balance_document(scene)
    path = out / f"{stem}_balance.json"
    path.write_text(json.dumps(doc.report) + "\n")
    return [
        path,
        shaking_force_polar(doc.series, out / f"{stem}_shaking_force_polar.png", title=scene.name),
        shaking_moment_curve(doc.series, out / f"{stem}_shaking_moment.png", title=scene.name),
    ]


def register(sub) -> None:
    """Add the ``demo`` and ``examples`` commands to the ``linkage-sym`` subparsers ``sub``."""
    d = sub.add_parser("demo", help="analyse shipped examples and write plots, and a gallery of "
                                    "every example's page")
    d.add_argument("-o", "--output", default="demo_out", metavar="DIR", help="output folder (default demo_out)")
    d.add_argument(
        "--example", action="append", metavar="NAME",
        help=f"example to run (repeatable; default {', '.join(DEMO_EXAMPLES)}, and then the "
        "gallery of every example's page; `linkage-sym examples` lists them)",
    )
    d.set_defaults(func=cmd_demo)
    e = sub.add_parser("examples", help="list the shipped example scenes")
    e.set_defaults(func=cmd_examples)
