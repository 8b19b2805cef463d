"""The protocol of the paper reproductions: every script exposes ``items()``, a list of :class:`Item`.

An item is one number (or formula) a source prints, beside what we compute, with a status:

``reproduced``
    the computed value rounds to the printed one: |computed - printed| <= half a unit of the
    printed last digit (the default tolerance, from the printed text itself);
``within input rounding``
    it does not, but the difference is inside the spread that the rounding of the printed
    *inputs* causes; ``tol`` is that spread and ``why`` says how it was obtained;
``erratum``
    the printed value or formula is wrong; ``corrected`` is what it should be, and ``holds`` is
    the derivation's verdict (True: the derivation shows the printed one wrong and the corrected
    one right);
``not reproducible``
    ``why`` says why (a missing figure, a value used as an input, an inconsistency we cannot
    resolve); nothing is checked.

``Item.ok`` is False when a reproduced or within-rounding item drifts beyond its tolerance or an
erratum is no longer shown by its derivation; ``python -m paper_repro`` exits non-zero then.
Sources are numbered as in the README's "Sources" section ([1]-[4]).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

REPRODUCED = "reproduced"
ROUNDING = "within input rounding"
ERRATUM = "erratum"
NOT_REPRODUCIBLE = "not reproducible"
STATUSES = (REPRODUCED, ROUNDING, ERRATUM, NOT_REPRODUCIBLE)

SOURCES = {
    1: "Dang Zuqi and Zhang Qixian, A simplified method for the force analysis of complex planar "
       "multi-bar mechanisms (Beijing Institute of Aeronautics; year not shown in the text)",
    2: "Design of four-bar mechanisms, chapter 2 of a textbook (title, author and year not shown in the text)",
    3: "Song Liqun and Wang Bingle, Mass and acceleration parameter equations of the inertia moment of "
       "planar hinged linkages, and a module 'assembly' balancing algorithm, J. Chongqing Inst. Archit. "
       "Eng. 14(2), 1992",
    4: "Kinematic analysis of planar mechanisms, chapter 3 of a textbook (author, title and year not "
       "shown in the text; not before 2008)",
}


def half_unit(printed: str) -> float:
    """Half a unit of the last printed digit: ``"934.03"`` -> 0.005, ``"451"`` -> 0.5."""
    text = printed.strip().lstrip("+-")
    mantissa = text.lower().split("e")[0]
    exp = int(text.lower().split("e")[1]) if "e" in text.lower() else 0
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 0.5 * 10.0 ** (exp - decimals)


def _number(x):
    if isinstance(x, (int, float)) and not isinstance(x, bool):
        return float(x)
    if isinstance(x, str):
        try:
            return float(x)
        except ValueError:
            return None
    return None


@dataclass(frozen=True)
class Item:
    """One printed value and its reproduction.

    Attributes
    ----------
    source : int
        1-4, the README's Sources number.
    where : str
        Where the source prints it ("sec. 4, eq. 13", "Table 3-1, th1 = 10 deg").
    name : str
        The quantity ("R34t", "aE", "eq. 6, M_uv1").
    printed : str
        As printed (its digits give the default tolerance).
    computed : float or str
    status : str
        One of :data:`STATUSES`.
    tol : float, optional
        Allowed |computed - printed|; default half a unit of the printed last digit for
        ``reproduced``; required for ``within input rounding``.
    why : str
        Reason of the tolerance, the erratum or the failure to reproduce.
    corrected : str
        For an erratum: what the source should print.
    holds : bool, optional
        For an erratum (or any item checked by a derivation rather than by a difference):
        the derivation's verdict.
    unit : str
    """

    source: int
    where: str
    name: str
    printed: str
    computed: object
    status: str
    tol: float | None = None
    why: str = ""
    corrected: str = ""
    holds: bool | None = None
    unit: str = ""

    def __post_init__(self):
        if self.holds is not None:  # a NumPy bool from a derivation becomes a plain one
            object.__setattr__(self, "holds", bool(self.holds))
        if self.status not in STATUSES:
            raise ValueError(f"status: {self.status!r} is not one of {STATUSES}")
        if self.source not in SOURCES:
            raise ValueError(f"source: {self.source} is not one of {sorted(SOURCES)}")
        if self.status == ROUNDING and (self.tol is None or not self.why):
            raise ValueError(f"{self.name}: 'within input rounding' needs the spread (tol) and how it was found (why)")
        if self.status == ERRATUM and self.holds is None:
            raise ValueError(f"{self.name}: an erratum needs the derivation's verdict (holds)")
        if self.status == NOT_REPRODUCIBLE and not self.why:
            raise ValueError(f"{self.name}: say why it is not reproducible")

    @property
    def numeric(self) -> bool:
        return _number(self.printed) is not None and _number(self.computed) is not None

    @property
    def difference(self) -> float | None:
        """computed - printed, for numbers."""
        if not self.numeric:
            return None
        return _number(self.computed) - _number(self.printed)

    @property
    def tolerance(self) -> float | None:
        if self.tol is not None:
            return self.tol
        if self.status == REPRODUCED and _number(self.printed) is not None:
            return half_unit(self.printed)
        return None

    @property
    def ok(self) -> bool:
        """False when the item drifted (see the module docstring)."""
        if self.status in (REPRODUCED, ROUNDING):
            if self.holds is not None and not self.holds:
                return False
            if not self.numeric:
                return bool(self.holds)
            d = self.difference
            return math.isfinite(d) and abs(d) <= self.tolerance * (1 + 1e-12)
        if self.status == ERRATUM:
            return bool(self.holds)
        return True


def _decimals(printed: str) -> int | None:
    if _number(printed) is None or "e" in printed.lower():
        return None
    return len(printed.split(".")[1]) if "." in printed else 0


def _fmt(x, printed: str = "") -> str:
    """``x`` with two more decimals than the printed value has (or 6 significant digits)."""
    n = _number(x)
    if n is None or isinstance(x, str):
        return str(x)
    d = _decimals(printed)
    if d is not None and (n == 0 or 10.0 ** -(d + 2) <= abs(n) < 1e6):
        return f"{n:.{d + 2}f}"
    return f"{n:.3g}" if abs(n) < 1e-3 else f"{n:.6g}"


CELL = 40  # widest cell; longer text (formulas) goes on the lines below the row


def table(items: list[Item]) -> str:
    """A plain-text table of ``items``, grouped by source; long formulas and reasons below each row."""
    out = []
    for src in sorted({it.source for it in items}):
        rows = [it for it in items if it.source == src]
        out.append(f"[{src}] {SOURCES[src]}")
        head = ("where", "item", "printed", "computed", "difference", "tolerance", "status")
        cells, notes, seen = [], [], set()
        for it in rows:
            d, t = it.difference, it.tolerance
            note = []
            printed, computed = it.printed, _fmt(it.computed, it.printed)
            if len(printed) > CELL:
                note.append(f"printed:  {printed}")
                printed = "(below)"
            if len(computed) > CELL:
                note.append(f"computed: {computed}")
                computed = "(below)"
            if it.corrected:
                note.append(f"should read: {it.corrected}")
            if it.why and it.why not in seen:  # a reason shared by several rows is written once
                note.append(it.why)
                seen.add(it.why)
            status = it.status + ("" if it.ok else "  ** DRIFTED **")
            cells.append((it.where, it.name + (f" [{it.unit}]" if it.unit else ""), printed, computed,
                          "" if d is None else f"{d:+.3g}", "" if t is None else f"{t:.2g}", status))
            notes.append(note)
        w = [min(CELL + 6 * (i == 1), max(len(h), *(len(c[i]) for c in cells))) for i, h in enumerate(head)]

        def line(c):
            return "  " + "  ".join(str(v)[:w[i]].ljust(w[i]) for i, v in enumerate(c)).rstrip()

        out.append(line(head))
        out.append("  " + "  ".join("-" * x for x in w))
        for c, note in zip(cells, notes):
            out.append(line(c))
            out.extend("      " + n for n in note)
        counts = {s: sum(it.status == s for it in rows) for s in STATUSES}
        out.append("  " + ", ".join(f"{v} {k}" for k, v in counts.items() if v)
                   + f"; {sum(not it.ok for it in rows)} drifted")
        out.append("")
    return "\n".join(out)
