"""The run's report as data (JSON) and as a Markdown page: printed values and self-checks apart.

``python -m paper_repro --json report.json --markdown report.md`` writes both.  Each keeps the
two kinds of items (items.py) apart: the values a source prints, counted by status and listed
source by source with the source's author, title and year and where it prints each value; and
the self-checks (no printed value: linkage_sym against an independent computation), counted and
listed with the computation each is compared with.
"""

from __future__ import annotations

import json
import math

from items import AGREES, PRINTED, SELF_CHECK, SOURCES, STATUSES, Item, _fmt, summary


def _plain(x):
    """A JSON value for a computed value: text stays text, a number becomes a float (NaN, inf as text)."""
    if isinstance(x, str):
        return x
    try:
        v = float(x)
    except (TypeError, ValueError):
        return str(x)
    return v if math.isfinite(v) else str(v)


def item_record(it: Item) -> dict:
    """One item as a dict of plain values (the JSON report's rows).

    Parameters
    ----------
    it : Item

    Returns
    -------
    dict
        ``kind``, ``where``, ``name``, ``computed``, ``status``, ``ok`` and ``why`` for every
        item; a printed item adds ``source`` (its number and citation), ``printed``,
        ``difference``, ``tolerance`` and, for an erratum, ``corrected``; a self-check adds
        ``against``.
    """
    rec = {"kind": it.kind, "where": it.where, "name": it.name, "unit": it.unit,
           "computed": _plain(it.computed), "status": it.status, "ok": it.ok, "why": it.why}
    if it.kind == PRINTED:
        rec.update(source=it.source, citation=SOURCES[it.source], printed=it.printed,
                   difference=None if it.difference is None else _plain(it.difference),
                   tolerance=None if it.tolerance is None else _plain(it.tolerance))
        if it.corrected:
            rec["corrected"] = it.corrected
    else:
        rec["against"] = it.against
    return rec


def report_dict(items: list[Item]) -> dict:
    """The JSON report: counts and lists of the printed values and of the self-checks, apart.

    Parameters
    ----------
    items : list of Item

    Returns
    -------
    dict
        ``summary`` (the runner's one line), ``printed`` (``count``, ``by_status``,
        ``sources``: number to citation, ``items``), ``self_checks`` (``count``, ``agree``,
        ``items``) and ``drifted`` (the rows that drifted, of either kind).
    """
    printed = [it for it in items if it.kind == PRINTED]
    checks = [it for it in items if it.kind == SELF_CHECK]
    return {
        "summary": summary(items),
        "printed": {"count": len(printed),
                    "by_status": {s: sum(it.status == s for it in printed) for s in STATUSES},
                    "sources": {str(k): v for k, v in SOURCES.items() if any(it.source == k for it in printed)},
                    "items": [item_record(it) for it in printed]},
        "self_checks": {"count": len(checks), "agree": sum(it.ok for it in checks),
                        "items": [item_record(it) for it in checks]},
        "drifted": [item_record(it) for it in items if not it.ok],
    }


def to_json(items: list[Item]) -> str:
    """:func:`report_dict` as indented JSON text."""
    return json.dumps(report_dict(items), indent=1, ensure_ascii=False) + "\n"


def _cell(text) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def to_markdown(items: list[Item]) -> str:
    """The report as a Markdown page: a summary, then one table per source, then the self-checks.

    Parameters
    ----------
    items : list of Item

    Returns
    -------
    str
    """
    rep = report_dict(items)
    p, c = rep["printed"], rep["self_checks"]
    out = ["# Paper reproductions", "", rep["summary"], "",
           f"## Printed values ({p['count']})", "",
           "Values a source prints, beside what linkage_sym computes. "
           + ", ".join(f"{n} {s}" for s, n in p["by_status"].items() if n) + ".", ""]
    printed = [it for it in items if it.kind == PRINTED]
    for src in sorted({it.source for it in printed}):
        rows = [it for it in printed if it.source == src]
        out += [f"### [{src}] {SOURCES[src]}", "",
                "| where | item | printed | computed | difference | tolerance | status |",
                "|---|---|---|---|---|---|---|"]
        for it in rows:
            d, t = it.difference, it.tolerance
            out.append("| " + " | ".join(_cell(x) for x in (
                it.where, it.name + (f" [{it.unit}]" if it.unit else ""), it.printed, _fmt(it.computed, it.printed),
                "" if d is None else f"{d:+.3g}", "" if t is None else f"{t:.2g}",
                it.status + ("" if it.ok else " **DRIFTED**"))) + " |")
        out.append("")
    checks = [it for it in items if it.kind == SELF_CHECK]
    out += [f"## Self-checks ({c['count']}, {c['agree']} agree)", "",
            "Values no source prints (procedures worked on our own numbers, exercises without printed "
            "answers): linkage_sym against an independent computation. They test the code, not a source.", "",
            "| where | item | computed | against | status |", "|---|---|---|---|---|"]
    for it in checks:
        out.append("| " + " | ".join(_cell(x) for x in (
            it.where, it.name + (f" [{it.unit}]" if it.unit else ""), _fmt(it.computed), it.against,
            (AGREES if it.ok else "**DRIFTED**"))) + " |")
    out.append("")
    return "\n".join(out)
