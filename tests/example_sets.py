"""Which shipped examples a check applies to.

The gear examples (``G`` joints, issue 20) are left out of checks that run
the symbolic layer, which refuses gear meshes ("the symbolic method does not
support gear meshes yet", tested in ``test_gears.py``), and of checks against
``reference_kinematics.py``, an independent solver of R and P joints only;
``test_gears.py`` checks them against the Willis formula, closed forms and
the equivalent four-bar instead.
"""

from __future__ import annotations

from linkage_sym.examples import example_dict, example_names


def has_meshes(name: str) -> bool:
    """Whether the shipped example ``name`` has a gear mesh."""
    return any(j.get("type") == "G" for j in example_dict(name)["joints"])


def without_meshes() -> list[str]:
    """The shipped examples without gear meshes, sorted."""
    return [n for n in example_names() if not has_meshes(n)]
