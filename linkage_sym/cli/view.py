"""``linkage-sym view``: one self-contained HTML page that solves the mechanism as you drag it.

::

    linkage-sym view SCENE.json -o PAGE.html

The page (:mod:`linkage_sym.page`) needs no network: its script, the functions the symbolic
layer prints in JavaScript and the evaluator that walks them are inline.  Its layers
(velocities, accelerations, reactions and driving efforts, instant centres, transmission
angles) are checkboxes on the page, off until ticked.  Its warnings panel opens with the
warnings of a Python run of the scene (:func:`linkage_sym.analyze`, made here; where that
run fails, the page is written without it, saying why on standard error, and the panel
opens with what the page's evaluator finds).  A scene the
symbolic layer does not derive (a cam contact) is refused with the joint named; nothing is
written.
"""

from __future__ import annotations

import sys

from linkage_sym.cli.common import OptionError, check_outputs, emit, load
from linkage_sym.errors import SceneError

__all__ = ["cmd_view", "register"]

SUFFIXES = (".html", ".htm")


def cmd_view(args) -> int:
    out = args.output
    if out not in (None, "-") and not out.lower().endswith(SUFFIXES):
        raise OptionError(f"-o/--output: {out!r}: the page is an HTML file: give a name ending "
                          "in .html (or -o - for standard output)")
    check_outputs(files=[("-o/--output", out)])
    scene = load(args.scene)
    import linkage_sym
    from linkage_sym.page import page_html

    try:  # the run whose warnings the page opens with
        run = linkage_sym.analyze(scene)
    except SceneError as err:  # e.g. an assembly at a dead centre: a drag on the page fixes it
        run = None
        why = "; ".join(err.problems)
        print(f"note: the Python run of the scene fails ({why}); the page's warnings panel "
              "opens with what its own evaluator finds", file=sys.stderr)
    emit(out, page_html(scene, run))
    return 0


def register(sub) -> None:
    """Add the ``view`` command to the ``linkage-sym`` subparsers ``sub``."""
    v = sub.add_parser(
        "view", help="write one self-contained HTML page that solves the mechanism live "
                     "(drag joints, type lengths, play the sweep; velocity, acceleration, force, "
                     "instant-centre and transmission-angle layers)")
    v.add_argument("scene", help="scene JSON file")
    v.add_argument("-o", "--output", required=True,
                   help="the page to write (.html; - for standard output)")
    v.set_defaults(func=cmd_view)
