"""The warnings a page opens with: those of a Python run of the scene it was built from.

The page (:mod:`linkage_sym.page`) has a warnings panel.  Opened, it lists what a Python run
of the scene as built said (:func:`built_warnings` of the run its caller made: the command
line's ``view`` runs :func:`linkage_sym.analyze`; the page itself runs no Python solver):
first how many steps cannot be assembled or are singular (:func:`status_lines`), then the
run's ``warnings``.  After each change in the browser the page's own script
(``warnings.js``) words what its evaluator finds for the current geometry -- those status
lines, and each passage of a dyad of two slides' joint through infinity, as
:func:`~linkage_sym.numeric.continuation.messages.parallel_note` words it -- and keeps the
run's other warnings (condition numbers, force superpositions, friction, gear flanks, the
Newton groups' assembly-mode jumps) marked as from the scene as built: it cannot recompute
them.

Examples
--------
>>> import numpy as np
>>> status_lines(np.array(["ok", "unassemblable", "unassemblable", "singular", "ok"]))
['2 step(s) cannot be assembled (steps 1, 2)', '1 step(s) are singular positions (steps 3): \
their velocities and accelerations have no unique solution']
"""

from __future__ import annotations

import numpy as np

from linkage_sym.numeric.results.result import SINGULAR, UNASSEMBLABLE
from linkage_sym.numeric.results.wording import steps_text

__all__ = ["built_warnings", "status_lines"]


def status_lines(status) -> list[str]:
    """The lines on a sweep's steps that cannot be assembled and that are singular: how many,
    and which (the first five, as the run's warnings name steps:
    :func:`~linkage_sym.numeric.results.wording.steps_text`); none where every step is ``ok``.

    Parameters
    ----------
    status : array_like of str
        Each step's status.
    """
    status = np.asarray(status)
    out = []
    bad = np.flatnonzero(status == UNASSEMBLABLE)
    if len(bad):
        out.append(f"{len(bad)} step(s) cannot be assembled (steps {steps_text(bad, len(bad))})")
    sing = np.flatnonzero(status == SINGULAR)
    if len(sing):
        out.append(f"{len(sing)} step(s) are singular positions (steps {steps_text(sing, len(sing))}): their "
                   "velocities and accelerations have no unique solution")
    return out


def built_warnings(analysis) -> list[str]:
    """What the page's warnings panel shows when it opens: :func:`status_lines` of the run's
    statuses, then its ``warnings``.

    Parameters
    ----------
    analysis : Analysis
        A Python run of the scene the page is built from (:func:`linkage_sym.analyze`).
    """
    return status_lines(analysis.status) + [str(w) for w in analysis.warnings]
