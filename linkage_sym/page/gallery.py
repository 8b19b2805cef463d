"""A gallery of shipped examples: one page per example and one HTML file linking them.

:func:`write_gallery` writes, into a folder, the page of each example
(:func:`linkage_sym.page.page_html`, in ``pages/<example>.html``) and ``gallery.html``:
each example's title (its scene's name), its one-line description (the heading of its
section in the examples' ``README.md``), a thumbnail (an inline SVG of the assembly
configuration, drawn here from the scene: no picture file, no plotting library) and a
relative link to its page.  Everything is inline; nothing names a network address.

Examples
--------
>>> d = example_descriptions()
>>> d["crank_rocker"]
"the spec's crank-rocker"
>>> from linkage_sym.examples import load_example
>>> svg = thumbnail_svg(load_example("crank_rocker"))
>>> svg.startswith("<svg") and "http" not in svg
True
"""

from __future__ import annotations

import math
import re
from importlib import resources
from pathlib import Path

import numpy as np

from linkage_sym.model import GROUND, Scene

__all__ = ["PALETTE", "THUMBNAIL", "example_descriptions", "gallery_html", "thumbnail_svg",
           "write_gallery"]

PALETTE = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2",
           "#17becf", "#bcbd22", "#7f7f7f")
"""The links' colours, in the order of the scene's links (the page's ``PALETTE``)."""

THUMBNAIL = (240, 160)
"""A thumbnail's width and height (CSS pixels)."""

_HEADING = re.compile(r"^## (\w+)\.json — (.+)$")


def _escape(text: str) -> str:
    return (text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")
            .replace('"', "&quot;"))


def example_descriptions() -> dict[str, str]:
    """Each shipped example's one-line description: the heading of its section in the
    examples' ``README.md`` (``## <name>.json — <description>``), emphasis marks and
    numbered citations removed."""
    text = resources.files("linkage_sym.examples").joinpath("README.md").read_text("utf-8")
    out = {}
    for line in text.splitlines():
        m = _HEADING.match(line)
        if m:
            # emphasis marks and the README's numbered citations ("[4]") removed
            out[m.group(1)] = re.sub(r"\s*\[\d+\]", "", m.group(2).replace("*", "")).strip()
    return out


def _hull(points: list) -> list:
    """The convex hull of ``points`` (counter-clockwise; fewer than three: the points)."""
    p = sorted(set(points))
    if len(p) < 3:
        return p

    def cross(o, a, b):
        return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])

    lower, upper = [], []
    for q in p:
        while len(lower) >= 2 and cross(lower[-2], lower[-1], q) <= 0:
            lower.pop()
        lower.append(q)
    for q in reversed(p):
        while len(upper) >= 2 and cross(upper[-2], upper[-1], q) <= 0:
            upper.pop()
        upper.append(q)
    return lower[:-1] + upper[:-1]


def _outlines(scene: Scene) -> tuple[dict, list, list]:
    """What a thumbnail draws, in scene coordinates: each link's points, the cams' working
    profiles ``(link, ring)`` and the gears' pitch circles ``(link, centre, radius)``."""
    on_link: dict[str, list] = {lk.name: [] for lk in scene.links}
    cams, circles = [], []
    for j in scene.joints:
        if j.type == "G":
            for link, pivot, r in zip(j.links, scene.gear_pivots(j), j.radii):
                circles.append((link, tuple(pivot.at), float(r)))
            continue
        if j.type == "cam":  # the cam's body is its profile; the follower's its element point
            from linkage_sym.numeric.kinematics.cam_profile import CamProfile

            prof = CamProfile(j.cam.profile, j.cam.data)
            (x, y), _, (nx, ny), _ = prof.frame(np.linspace(0.0, 2 * math.pi, 73)[:-1])
            if j.cam.pitch:  # the working profile, a roller's radius inside the pitch curve
                x, y = x - j.cam.radius * nx, y - j.cam.radius * ny
            cams.append((j.links[0], list(zip(x.tolist(), y.tolist()))))
            on_link[j.links[1]].append(tuple(j.at))
            continue
        for link in j.links:
            if link != GROUND:
                on_link[link].append(tuple(j.at))
    return on_link, cams, circles


def thumbnail_svg(scene: Scene, size: tuple[int, int] = THUMBNAIL) -> str:
    """An inline SVG of ``scene`` in its assembly configuration: each link the hull of its
    joints in its colour, cam profiles and rollers, gears' pitch circles, sliders' blocks,
    ground pivots and joints."""
    w, h = size
    on_link, cams, circles = _outlines(scene)
    pts = [j.at for j in scene.joints] + [p for _, ring in cams for p in ring]
    pts += [(c[0] + s * r, c[1] + s * r) for _, c, r in circles for s in (-1, 1)]
    xs, ys = [p[0] for p in pts], [p[1] for p in pts]
    span = max(max(xs) - min(xs), max(ys) - min(ys), 1e-9)
    s = 0.86 * min(w / max(max(xs) - min(xs), 0.05 * span), h / max(max(ys) - min(ys), 0.05 * span))
    cx, cy = (min(xs) + max(xs)) / 2, (min(ys) + max(ys)) / 2

    def at(p):
        return w / 2 + (p[0] - cx) * s, h / 2 - (p[1] - cy) * s

    def xy(p):
        x, y = at(p)
        return f"{x:.1f},{y:.1f}"

    colour = {lk.name: PALETTE[i % len(PALETTE)] for i, lk in enumerate(scene.links)}
    out = [f'<svg viewBox="0 0 {w} {h}" width="{w}" height="{h}" role="img" '
           f'aria-label="{_escape(scene.name)} in its assembly configuration">',
           f'<rect width="{w}" height="{h}" fill="#fbfbf8"/>']
    for link, ring in cams:
        out.append(f'<polygon points="{" ".join(xy(p) for p in ring)}" fill="{colour[link]}" '
                   f'fill-opacity="0.3" stroke="{colour[link]}" stroke-width="1.2"/>')
    for link, c, r in circles:
        col = "#888" if link == GROUND else colour[link]
        x, y = at(c)
        out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{r * s:.1f}" fill="none" '
                   f'stroke="{col}" stroke-width="1.2"/>')
    for link, ps in on_link.items():
        hull = _hull(ps)
        if not hull:
            continue
        tag = "polygon" if len(hull) > 2 else "polyline"
        out.append(f'<{tag} points="{" ".join(xy(p) for p in hull)}" fill="{colour[link]}" '
                   f'fill-opacity="{0.2 if tag == "polygon" else 0}" stroke="{colour[link]}" '
                   'stroke-width="3" stroke-linejoin="round" stroke-linecap="round"/>')
    for j in scene.joints:
        x, y = at(j.at)
        if j.type == "cam" and j.cam.follower == "roller" and j.cam.radius > 0:
            out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{j.cam.radius * s:.1f}" '
                       f'fill="#fff" stroke="{colour[j.links[1]]}" stroke-width="1.2"/>')
        if j.type == "P":  # the block
            out.append(f'<rect x="{x - 5:.1f}" y="{y - 3.5:.1f}" width="10" height="7" '
                       'fill="#ddd" stroke="#333"/>')
        if j.type != "R":
            continue
        if GROUND in j.links:
            out.append(f'<path d="M{x:.1f},{y:.1f} l-4,7 h8 z" fill="#666"/>')
        out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="2.2" fill="#fff" stroke="#222"/>')
    for p in scene.points:
        x, y = at(p.at)
        out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="1.8" fill="#c05"/>')
    out.append("</svg>")
    return "\n".join(out)


_STYLE = """body { font-family: system-ui, -apple-system, "Segoe UI", Roboto, sans-serif; margin: 0;
  color: #222; background: #f3f3ef; }
header { padding: 12px 18px; background: #2b3a42; color: #fff; }
header h1 { font-size: 22px; margin: 0 0 4px; }
header p { margin: 0; font-size: 14px; opacity: 0.8; }
main { display: grid; grid-template-columns: repeat(auto-fill, minmax(260px, 1fr)); gap: 14px;
  padding: 16px; }
a.card { display: block; background: #fff; border: 1px solid #ddd; padding: 10px;
  color: inherit; text-decoration: none; }
a.card:hover { border-color: #0a66c2; }
a.card h2 { font-size: 16px; margin: 6px 0 2px; color: #0a66c2; }
a.card p { font-size: 13px; margin: 2px 0; }
a.card .file { color: #666; font-size: 12px; }
svg { display: block; width: 100%; height: auto; border: 1px solid #eee; }"""


def gallery_html(items: list[dict]) -> str:
    """The gallery: one card per item (``name``, ``title``, ``description``, ``href`` (a
    relative link), ``svg`` (an inline thumbnail) and ``facts`` (a short line)), in order."""
    cards = []
    for it in items:
        cards.append(
            f'<a class="card" href="{_escape(it["href"])}" id="{_escape(it["name"])}">\n'
            f'{it["svg"]}\n<h2>{_escape(it["title"])}</h2>\n'
            f'<p>{_escape(it["description"])}</p>\n'
            f'<p class="file">{_escape(it["name"])}.json · {_escape(it["facts"])}</p>\n</a>')
    return "\n".join([
        "<!DOCTYPE html>", '<html lang="en">', "<head>", '<meta charset="utf-8">',
        '<meta name="viewport" content="width=device-width, initial-scale=1">',
        '<meta name="generator" content="linkage_sym">',
        "<title>linkage_sym examples</title>", f"<style>\n{_STYLE}\n</style>", "</head>",
        "<body>", "<header><h1>linkage_sym examples</h1><p>Each page solves its mechanism in "
        "the browser (play, drag a ground pivot, download the edited scene); nothing is "
        "fetched.</p></header>", "<main>", *cards, "</main>", "</body>", "</html>", ""])


def _facts(scene: Scene) -> str:
    kinds = {"G": "gear meshes", "cam": "cam contacts"}
    extra = sorted({kinds[j.type] for j in scene.joints if j.type in kinds})
    drivers = len(scene.drivers)
    return ", ".join([f"{len(scene.links)} moving links", f"{len(scene.joints)} joints",
                      f"{drivers} driver{'s' if drivers != 1 else ''}", *extra])


def write_gallery(folder: Path, names: list[str], runs: dict | None = None) -> list[Path]:
    """Write the pages of the shipped examples ``names`` (``folder/pages/<name>.html``) and
    ``folder/gallery.html`` linking them; the paths written, the gallery first.

    ``runs``: a Python run of each example (name -> :func:`linkage_sym.analyze` of it), whose
    warnings its page's panel opens with (:func:`~linkage_sym.page.page_html`); an example
    without one opens with what its page's evaluator finds.

    Raises
    ------
    KeyError
        An example without its description in the examples' ``README.md``.
    """
    from linkage_sym.examples import load_example
    from linkage_sym.page import page_html

    descriptions = example_descriptions()
    missing = [n for n in names if n not in descriptions]
    if missing:
        raise KeyError(f"no description of example(s) {', '.join(missing)} in the examples' "
                       "README.md (a heading '## <name>.json — <description>')")
    pages = Path(folder) / "pages"
    pages.mkdir(parents=True, exist_ok=True)
    items, written = [], []
    for name in names:
        scene = load_example(name)
        path = pages / f"{name}.html"
        path.write_text(page_html(scene, (runs or {}).get(name)), encoding="utf-8")
        written.append(path)
        items.append({"name": name, "title": scene.name, "description": descriptions[name],
                      "href": f"pages/{name}.html", "svg": thumbnail_svg(scene),
                      "facts": _facts(scene)})
    gallery = Path(folder) / "gallery.html"
    gallery.write_text(gallery_html(items), encoding="utf-8")
    return [gallery, *written]
