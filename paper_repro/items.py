"""The protocol of the paper reproductions: every script exposes ``items()``, a list of :class:`Item`.

Every item declares its *kind*, and the two kinds are counted and listed apart:

``printed`` (:data:`PRINTED`)
    a number (or formula) a source prints, beside what we compute: the item names the source
    (``source``, a key of :data:`SOURCES`, which gives author, title and year) and where it is
    printed (``where``: table, equation, page, example);
``self-check`` (:data:`SELF_CHECK`)
    a value no source prints (a procedure worked on our own numbers, an exercise without a
    printed answer): linkage_sym against an independent computation, which ``against`` names.
    It claims no source and no printed value (``printed`` is :data:`NONE`); its status is
    :data:`AGREES`, and it drifts when the two computations part.

A printed item has one of these statuses:

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

``Item.ok`` is False when a reproduced or within-rounding item drifts beyond its tolerance, an
erratum is no longer shown by its derivation or a self-check's two computations disagree;
``python -m paper_repro`` exits non-zero then.  :func:`kind_problems` lists what is wrong with an
item's declaration of its kind (a printed item without its printed value and source, a
self-check that claims one); :class:`Item` refuses such an item.
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
"""The statuses of a printed item."""
AGREES = "agrees"
"""The status of a self-check: linkage_sym and the independent computation agree."""

PRINTED = "printed"
SELF_CHECK = "self-check"
KINDS = (PRINTED, SELF_CHECK)
NONE = "(none)"
"""The printed column of a self-check: no source prints the value."""

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


def kind_problems(kind, source, where, printed, status, against) -> list[str]:
    """What is wrong with an item's declaration of its kind; empty when nothing is.

    Parameters
    ----------
    kind : str
        :data:`PRINTED` or :data:`SELF_CHECK`.
    source : int or None
        A key of :data:`SOURCES` for a printed item; None for a self-check.
    where : str
        Where the source prints the value (a printed item must say).
    printed : str
        The printed value; :data:`NONE` for a self-check.
    status : str
        One of :data:`STATUSES` for a printed item; :data:`AGREES` for a self-check.
    against : str
        A self-check's independent computation; empty for a printed item.

    Returns
    -------
    list of str
        One sentence per problem.

    Examples
    --------
    >>> kind_problems(PRINTED, 4, "Table 3-1", "0.10107", REPRODUCED, "")
    []
    >>> kind_problems(SELF_CHECK, 4, "exercise 3-5", NONE, AGREES, "a closed form")
    ['a self-check claims no source, but names [4]']
    """
    out = []
    if kind == PRINTED:
        if source not in SOURCES:
            out.append(f"a printed item names its source: {source!r} is not one of {sorted(SOURCES)}")
        if not where.strip():
            out.append("a printed item says where the source prints it")
        if not printed.strip() or printed == NONE:
            out.append("a printed item records the printed value")
        if status not in STATUSES:
            out.append(f"a printed item's status is one of {STATUSES}, not {status!r}")
        if against:
            out.append("a printed item is compared with its source, not with another computation (against)")
    elif kind == SELF_CHECK:
        if source is not None:
            out.append(f"a self-check claims no source, but names [{source}]")
        if printed != NONE:
            out.append(f"a self-check has no printed value ({NONE!r}), not {printed!r}")
        if status != AGREES:
            out.append(f"a self-check's status is {AGREES!r}, not {status!r}")
        if not against.strip():
            out.append("a self-check names the independent computation it is compared with (against)")
    else:
        out.append(f"kind: {kind!r} is not one of {KINDS}")
    return out


@dataclass(frozen=True)
class Item:
    """One value and its check: a printed value reproduced, or a self-check.

    Attributes
    ----------
    kind : str
        :data:`PRINTED` (the value a source prints) or :data:`SELF_CHECK` (no source prints
        it: linkage_sym against an independent computation); see :func:`kind_problems`.
    source : int or None
        1-4, the README's Sources number, for a printed item; None for a self-check.
    where : str
        Where the source prints it ("sec. 4, eq. 13", "Table 3-1, th1 = 10 deg"); for a
        self-check, which problem it is ("exercise 3-5 (phi1 = 45 deg)").
    name : str
        The quantity ("R34t", "aE", "eq. 6, M_uv1").
    printed : str
        As printed (its digits give the default tolerance); :data:`NONE` for a self-check.
    computed : float or str
    status : str
        One of :data:`STATUSES` for a printed item, :data:`AGREES` for a self-check.
    tol : float, optional
        Allowed |computed - printed|; default half a unit of the printed last digit for
        ``reproduced``; required for ``within input rounding``.
    why : str
        Reason of the tolerance, the erratum or the failure to reproduce.
    corrected : str
        For an erratum: what the source should print.
    holds : bool, optional
        For an erratum (or any item checked by a derivation rather than by a difference):
        the derivation's verdict; for a self-check, whether the two computations agree.
    unit : str
    against : str
        For a self-check: the independent computation linkage_sym is compared with.
    """

    kind: str
    source: int | None
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
    against: str = ""

    def __post_init__(self):
        if self.holds is not None:  # a NumPy bool from a derivation becomes a plain one
            object.__setattr__(self, "holds", bool(self.holds))
        if self.status not in STATUSES + (AGREES,):
            raise ValueError(f"status: {self.status!r} is not one of {STATUSES + (AGREES,)}")
        problems = kind_problems(self.kind, self.source, self.where, self.printed, self.status, self.against)
        if problems:
            raise ValueError(f"{self.name}: " + "; ".join(problems))
        if self.status == ROUNDING and (self.tol is None or not self.why):
            raise ValueError(f"{self.name}: 'within input rounding' needs the spread (tol) and how it was found (why)")
        if self.status == ERRATUM and self.holds is None:
            raise ValueError(f"{self.name}: an erratum needs the derivation's verdict (holds)")
        if self.status == NOT_REPRODUCIBLE and not self.why:
            raise ValueError(f"{self.name}: say why it is not reproducible")
        if self.status == AGREES and self.holds is None:
            raise ValueError(f"{self.name}: a self-check needs the comparison's verdict (holds)")

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
            return bool(math.isfinite(d) and abs(d) <= self.tolerance * (1 + 1e-12))
        if self.status in (ERRATUM, AGREES):
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


def _rows(rows: list[Item], self_check: bool):
    """The cells and the notes below each row of one section of :func:`table`."""
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
        name = it.name + (f" [{it.unit}]" if it.unit else "")
        if self_check:
            against = it.against
            if len(against) > CELL:
                note.insert(0, f"against:  {against}")
                against = "(below)"
            cells.append((it.where, name, computed, against, status))
        else:
            cells.append((it.where, name, printed, computed, "" if d is None else f"{d:+.3g}",
                          "" if t is None else f"{t:.2g}", status))
        notes.append(note)
    return cells, notes


def _section(title: str, rows: list[Item], self_check: bool) -> list[str]:
    head = (("where", "item", "computed", "against", "status") if self_check else
            ("where", "item", "printed", "computed", "difference", "tolerance", "status"))
    cells, notes = _rows(rows, self_check)
    w = [min(CELL + 6 * (i == 1), max(len(h), *(len(c[i]) for c in cells))) for i, h in enumerate(head)]

    def line(c):
        return "  " + "  ".join(str(v)[:w[i]].ljust(w[i]) for i, v in enumerate(c)).rstrip()

    out = [title, line(head), "  " + "  ".join("-" * x for x in w)]
    for c, note in zip(cells, notes):
        out.append(line(c))
        out.extend("      " + n for n in note)
    statuses = (AGREES,) if self_check else STATUSES
    counts = {("agree" if s == AGREES else s): sum(it.status == s for it in rows) for s in statuses}
    out.append("  " + ", ".join(f"{v} {k}" for k, v in counts.items() if v)
               + f"; {sum(not it.ok for it in rows)} drifted")
    out.append("")
    return out


def table(items: list[Item]) -> str:
    """A plain-text table of ``items``: the printed values source by source, then the self-checks.

    Long formulas, reasons and the self-checks' independent computations go below each row.
    """
    out = []
    printed = [it for it in items if it.kind == PRINTED]
    for src in sorted({it.source for it in printed}):
        out += _section(f"[{src}] {SOURCES[src]}", [it for it in printed if it.source == src], False)
    checks = [it for it in items if it.kind == SELF_CHECK]
    if checks:
        out += _section("Self-checks: values no source prints (procedures on our own numbers, exercises without "
                        "printed answers), linkage_sym against an independent computation", checks, True)
    return "\n".join(out)


def summary(items: list[Item]) -> str:
    """One line: the printed values and the self-checks counted apart, by status, and the drifted.

    Examples
    --------
    >>> it = Item(PRINTED, 4, "Table 3-1", "sE", "0.10107", 0.1010686, REPRODUCED)
    >>> sc = Item(SELF_CHECK, None, "exercise 3-5", "omega2", NONE, 1.0, AGREES, holds=True, against="a closed form")
    >>> summary([it, sc])
    '1 printed values (1 reproduced); 1 self-checks (1 agree); 0 drifted'
    """
    printed = [it for it in items if it.kind == PRINTED]
    checks = [it for it in items if it.kind == SELF_CHECK]
    by_status = ", ".join(f"{n} {s}" for s in STATUSES if (n := sum(it.status == s for it in printed)))
    agree = sum(it.ok for it in checks)
    return (f"{len(printed)} printed values ({by_status or 'none'}); {len(checks)} self-checks ({agree} agree); "
            f"{sum(not it.ok for it in items)} drifted")
