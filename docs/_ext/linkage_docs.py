"""Pages of the documentation generated from the package itself, before Sphinx reads sources.

- ``reference/cli.md``: the command-line reference, walked from ``linkage_sym.cli.build_parser``
  (every command, sub-command and option, with its help text and usage line), so that it cannot
  drift from the parser.
- ``gallery/``: a page per shipped example (``linkage_sym.examples``): its description, the
  pictures of ``linkage_sym.plotting.plot_all`` (the plots ``linkage-sym demo`` writes), a GIF of
  its motion and its scene file.  The pictures are made again only when the scene file is newer
  than them, so a rebuild after a text change takes seconds.

- ``derived/crank_rocker.md``: the four-bar's derived equations, the page
  ``linkage-sym derive crank_rocker.json --markdown`` writes (``$$`` math for ``dollarmath``).

All are written into the source folder (and listed in ``.gitignore``), as plain MyST pages.
"""

from __future__ import annotations

import argparse
import json
import re
from pathlib import Path

# characters CommonMark gives a meaning to inside running text: escaped with a backslash
_MARKDOWN = re.compile(r"([\\`*_\[\]<>|{}#$~])")

# the animations stay small: a few frames at a modest size (a GIF is a few hundred kB)
GIF_FRAMES = 24


def escape(text: str) -> str:
    """``text`` as literal MyST inline text (every CommonMark special character escaped)."""
    return _MARKDOWN.sub(r"\\\1", " ".join(text.split()))


def _write_if_changed(path: Path, text: str) -> None:
    # an unchanged page keeps its time stamp, so Sphinx does not read it again
    if not path.exists() or path.read_text() != text:
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text)


# ---------------------------------------------------------------- command line


def _option_rows(parser: argparse.ArgumentParser) -> list[str]:
    formatter = parser._get_formatter()
    rows = []
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction) or action.help == argparse.SUPPRESS:
            continue
        if action.option_strings:
            names = ", ".join(f"`{s}`" for s in action.option_strings)
            if action.nargs != 0:
                metavar = formatter._format_args(action, action.dest.upper())
                names += f" `{metavar}`"
        else:
            names = f"`{formatter._format_args(action, action.dest)}`"
        names = names.replace("|", "\\|")  # a pipe inside a table cell, even in code
        help_text = formatter._expand_help(action) if action.help else ""
        rows.append(f"| {names} | {escape(help_text)} |")
    return rows


def _command_section(name: str, parser: argparse.ArgumentParser, level: int) -> list[str]:
    lines = [f"{'#' * level} `{name}`", ""]
    if parser.description:
        lines += [escape(parser.description), ""]
    lines += ["```text", parser.format_usage().strip(), "```", ""]
    rows = _option_rows(parser)
    if rows:
        lines += ["| argument | meaning |", "| --- | --- |", *rows, ""]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub_name, sub in action.choices.items():
                lines += _command_section(f"{name} {sub_name}", sub, min(level + 1, 4))
    return lines


def cli_page() -> str:
    """The command-line reference as a MyST page, from the parser ``linkage-sym`` runs."""
    from linkage_sym.cli import build_parser

    parser = build_parser()
    lines = [
        "# Command-line reference", "",
        "Generated from the argument parser of `linkage-sym` (`linkage_sym.cli.build_parser`) "
        "when the documentation is built: every command, sub-command and option below is the "
        "one the program accepts (`linkage-sym COMMAND --help` prints the same text).", "",
    ]
    lines += ["```text", parser.format_usage().strip(), "```", "",
              "| argument | meaning |", "| --- | --- |", *_option_rows(parser), ""]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                lines += _command_section(f"linkage-sym {name}", sub, 2)
    lines += ["## Exit status", "", "```text", (parser.epilog or "").strip(), "```", ""]
    return "\n".join(lines)


# ---------------------------------------------------------------- gallery


def _stale(scene_file: Path, stamp: Path) -> bool:
    return not stamp.exists() or stamp.stat().st_mtime < scene_file.stat().st_mtime


def _make_pictures(name: str, scene_file: Path, folder: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    from linkage_sym.numeric.plan import compile_plan
    from linkage_sym.plotting import plot_all
    from linkage_sym.scene import load_scene

    for old in folder.glob("*"):
        old.unlink()
    folder.mkdir(parents=True, exist_ok=True)
    scene = load_scene(scene_file)
    analysis = compile_plan(scene).run()
    pictures = [p.name for p in plot_all(scene, analysis, folder, prefix=name)]
    from linkage_sym.plotting.animation import animate

    animate(scene, analysis, frames=GIF_FRAMES, dpi=60).save(folder / f"{name}.gif")
    (folder / "pictures.json").write_text(json.dumps(pictures))


def gallery_pages(srcdir: Path) -> None:
    """Write ``gallery/index.md`` and one page per shipped example (pictures when stale)."""
    from linkage_sym.examples import example_dict, example_names, example_path
    from linkage_sym.page.gallery import example_descriptions

    descriptions = example_descriptions()

    gallery = srcdir / "gallery"
    entries = []
    for name in example_names():
        scene_file = example_path(name)
        folder = gallery / "_files" / name
        if _stale(scene_file, folder / "pictures.json"):
            _make_pictures(name, scene_file, folder)
        pictures = json.loads((folder / "pictures.json").read_text())
        data = example_dict(name)
        title = data.get("name", name)
        # the one-line description of the examples' README.md (the page gallery's own)
        description = descriptions[name]
        rel_scene = Path("..", "..", "linkage_sym", "examples", scene_file.name)
        lines = [f"# {escape(title)}", "", escape(description), "",
                 f"`linkage_sym.load_example(\"{name}\")`; on the command line: "
                 f"`linkage-sym demo --example {name} -o out`.", "",
                 "## Motion", "", f"![{escape(title)} in motion](_files/{name}/{name}.gif)", "",
                 "## Pictures", ""]
        for picture in pictures:
            lines += [f"![{picture}](_files/{name}/{picture})", ""]
        lines += ["## Scene file", "", f"```{{literalinclude}} {rel_scene.as_posix()}",
                  ":language: json", "```", ""]
        _write_if_changed(gallery / f"{name}.md", "\n".join(lines))
        entries.append((name, title, description))
    index = ["# Gallery of the shipped examples", "",
             "Every scene shipped in `linkage_sym/examples/`, analysed when the documentation is "
             "built: its motion, the plots `linkage-sym demo` writes and its scene file.", "",
             "```{toctree}", ":hidden:", "", *[n for n, _, _ in entries], "```", "",
             "| example | what it is |", "| --- | --- |"]
    index += [f"| [{escape(t)}]({n}.md) | {escape(d)} |" for n, t, d in entries]
    _write_if_changed(gallery / "index.md", "\n".join(index) + "\n")


# ---------------------------------------------------------------- derived equations


def derived_page(example: str = "crank_rocker") -> str:
    """The derived equations of a shipped example as a MyST page: the Markdown of
    ``linkage-sym derive SCENE --markdown``, with a line saying so under its title."""
    from linkage_sym.examples import load_example
    from linkage_sym.symbolic import derive
    from linkage_sym.symbolic.markdown import markdown_document

    title, rest = markdown_document(derive(load_example(example))).split("\n", 1)
    note = (f"Generated when the documentation is built: `linkage-sym derive "
            f"linkage_sym/examples/{example}.json --markdown` prints this page (`--latex` the same "
            "equations as LaTeX, with a TikZ figure of each vector loop). The symbols are "
            "explained in [the symbolic layer](../symbolic.md).")
    return "\n".join([title, "", note, rest])


def _module_headings_as_rubrics(app, what, name, obj, options, lines) -> None:
    """A module docstring's numpydoc headings (``Examples`` over dashes) as rubrics, as numpydoc
    renders them in a function's docstring: as sections, every module's ``Examples`` would be
    one more label ``examples`` of the site."""
    if what != "module":
        return
    for i in range(len(lines) - 1):
        title, rule = lines[i].strip(), lines[i + 1].strip()
        if title and rule and set(rule) == {"-"} and len(rule) == len(title):
            lines[i], lines[i + 1] = f".. rubric:: {title}", ""


def _generate(app) -> None:
    srcdir = Path(app.srcdir)
    _write_if_changed(srcdir / "reference" / "cli.md", cli_page())
    gallery_pages(srcdir)
    _write_if_changed(srcdir / "derived" / "crank_rocker.md", derived_page("crank_rocker"))


def setup(app):
    """Register the page generators with Sphinx."""
    app.connect("builder-inited", _generate)
    app.connect("autodoc-process-docstring", _module_headings_as_rubrics)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1"}
