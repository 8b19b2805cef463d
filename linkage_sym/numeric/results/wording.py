"""How the warnings of a run name its steps (every runtime and force routine words them alike)."""

from __future__ import annotations


def steps_text(first, count: int) -> str:
    """The steps of a warning: the first five, and how many more."""
    return ", ".join(str(int(i)) for i in list(first)[:5]) + (
        f" and {count - 5} more" if count > 5 else "")
