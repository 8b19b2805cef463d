"""The LaTeX fragment of the derived equations parses, balances and is wired to the CLI.

No TeX is installed on CI: every math environment (``equation``, ``align``,
their ``pmatrix`` matrices, and inline ``$...$``) is parsed with
``latex2mathml``, a pure-Python LaTeX-math parser; a real ``pdflatex`` run is
added when one is on PATH.
"""

import re
import shutil
import subprocess
import sys
from collections import Counter

import mpmath as mp
import numpy as np
import pytest
import sympy as sp

import linkage_sym.examples
from linkage_sym.cli import main
from linkage_sym.examples import example_dict, example_names, load_example
from tests.support.example_sets import symbolic_examples
from linkage_sym.symbolic import derive
from linkage_sym.symbolic.latex import latex_document, standalone

latex2mathml = pytest.importorskip("latex2mathml.converter")

MATH_ENVS = ("equation", "equation*", "align", "align*")
ENV = re.compile(r"\\begin\{(" + "|".join(re.escape(e) for e in MATH_ENVS) + r")\}(.*?)\\end\{\1\}", re.S)
DROP = re.compile(r"\\label\{[^}]*\}|\\nonumber|\\notag")


# derives every example (about 50 s on a loaded 2-core machine): the tests using it are
# marked slow, or the first of them in the fast lane would pay it
@pytest.fixture(scope="module")
def documents():
    return {n: latex_document(derive(load_example(n), forces=True)) for n in symbolic_examples()}


def convert(tex: str) -> str:
    """MathML of ``tex``; an unknown command would come back as the text ``\\name``."""
    mathml = latex2mathml.convert(tex)
    assert "\\" not in mathml.replace("\\\\", ""), f"unknown command in: {tex[:200]}"
    return mathml


def math_pieces(doc: str):
    """Every display row (aligned rows one by one) and every inline formula."""
    for env, body in ENV.findall(doc):
        body = DROP.sub("", body)
        # split rows at the top level only (not inside a matrix)
        rows, depth, cur = [], 0, ""
        for tok in re.split(r"(\\begin\{\w+\}|\\end\{\w+\}|\\\\)", body):
            if tok.startswith("\\begin"):
                depth += 1
            elif tok.startswith("\\end"):
                depth -= 1
            elif tok == "\\\\" and depth == 0 and env.startswith("align"):
                rows.append(cur)
                cur = ""
                continue
            cur += tok
        rows.append(cur)
        for r in rows:
            yield env, r.replace("&=", "=").replace("&\\quad", "\\quad")
    text = ENV.sub("", doc)
    for m in re.finditer(r"(?<!\\)\$(.+?)(?<!\\)\$", text, re.S):
        yield "inline", m.group(1)


def test_the_parser_reads_matrices():
    mathml = convert(r"\begin{pmatrix} a & \theta^{0}_{\mathrm{C\_g}} \\ \dot{s}_{C} & 0 \end{pmatrix}")
    assert mathml.count("<mtr>") == 2 and mathml.count("<mtd>") == 4
    with pytest.raises(Exception):
        latex2mathml.convert(r"\begin{pmatrix} a & b \end{pmatri")
    with pytest.raises(Exception):
        latex2mathml.convert(r"\frac{a}{")


@pytest.mark.parametrize("name", symbolic_examples())  # the symbolic layer refuses cams
@pytest.mark.slow
def test_every_formula_parses(documents, name):
    doc = documents[name]
    n = 0
    for env, tex in math_pieces(doc):
        assert tex.strip(), env
        assert tex.count("{") == tex.count("}"), tex[:200]
        assert not re.search(r"_\{[^{}]*\}_\{", tex), f"double subscript: {tex[:200]}"
        convert(tex)
        n += 1
    assert n > 20


@pytest.mark.parametrize("name", symbolic_examples())  # the symbolic layer refuses cams
@pytest.mark.slow
def test_environments_balance_and_labels_are_unique(documents, name):
    doc = documents[name]
    assert "\\documentclass" not in doc
    stack = []
    for kind, env in re.findall(r"\\(begin|end)\{([^}]*)\}", doc):
        if kind == "begin":
            stack.append(env)
        else:
            assert stack and stack.pop() == env, env
    assert not stack
    labels = re.findall(r"\\label\{([^}]*)\}", doc)
    dup = [k for k, c in Counter(labels).items() if c > 1]
    assert not dup
    assert all(lab.startswith("eq:") for lab in labels)
    eqs = derive(load_example(name), forces=True)
    # one numbered complex loop equation and two projections per loop; every section
    assert len([lab for lab in labels if ":loop-" in lab]) == 3 * len(eqs.loops)
    assert any(lab.endswith(":velocity") for lab in labels)
    assert any(lab.endswith(":acceleration") for lab in labels)
    assert sum(":forces-" in lab for lab in labels) == len(eqs.groups)
    assert any(lab.endswith(":frame-moment") for lab in labels)
    for s in eqs.parameters:
        assert escape(eqs.table.params[s.name].meaning) in doc
    if not all(g.closed for g in eqs.groups):
        assert "found numerically" in doc


def escape(s):
    # the LaTeX's text escapes the meanings use: an underscore, an arrow as math
    return s.replace("_", r"\_").replace("->", r"\ensuremath{\to}")


def test_notation_of_the_kinematics_chapter():
    doc = latex_document(derive(load_example("slider_crank_offset"), forces=True))
    for piece in (r"\theta_{\mathrm{crank}}", r"\omega_{\mathrm{connecting\_rod}}",
                  r"\alpha_{\mathrm{slider}}", r"\dot{s}_{\mathrm{C\_guide}}", r"\dot{q}_{A}",
                  r"\ddot{q}_{A}", r"l_{AB}", r"\theta^{0}_{\mathrm{slider}}", r"\sigma_{2}",
                  r"e^{i \theta_{\mathrm{crank}}}", r"\tau_{A}", r"R_{A,x}", r"N_{\mathrm{C\_guide}}"):
        assert piece in doc, piece
    # no raw SymPy names left (theta_crank, omega_..., sdot_..., qdot_...)
    assert not re.search(r"(?<![\\\w])(theta|omega|alpha|sdot|qdot|qddot|sigma)_", doc)


@pytest.mark.skipif(not (shutil.which("pdflatex") or shutil.which("latex")), reason="no TeX on PATH")
@pytest.mark.slow
def test_compiles_with_tex(tmp_path, documents):
    exe = shutil.which("pdflatex") or shutil.which("latex")
    for name in ("crank_rocker", "sixbar_class3"):
        (tmp_path / f"{name}.tex").write_text(documents[name])
    (tmp_path / "main.tex").write_text(
        "\\documentclass{article}\n\\usepackage{amsmath}\n\\setcounter{MaxMatrixCols}{20}\n"
        "\\begin{document}\n\\input{crank_rocker}\n\\input{sixbar_class3}\n\\end{document}\n"
    )
    p = subprocess.run([exe, "-interaction=nonstopmode", "-halt-on-error", "main.tex"],
                       cwd=tmp_path, capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, p.stdout[-3000:]


def test_cli_derive_latex_writes_a_file(tmp_path, capsys):
    out = tmp_path / "eqs.tex"
    scene = tmp_path / "s.json"
    import json

    scene.write_text(json.dumps(example_dict("crank_rocker")))
    assert main(["derive", str(scene), "--latex", "-o", str(out)]) == 0
    text = out.read_text()
    assert r"\begin{equation}" in text and r"\label{eq:crank-rocker:loop-D}" in text
    capsys.readouterr()
    assert main(["derive", str(scene), "--numeric"]) == 0
    plain = capsys.readouterr().out
    assert "theta_crank" in plain and "l_AB" not in plain and "A =" in plain


@pytest.mark.slow
def test_cli_derive_invalid_scene_exits_2_and_writes_nothing(tmp_path):
    import json

    d = example_dict("crank_rocker")
    d["links"][0]["mass"] = -1.0
    scene = tmp_path / "bad.json"
    scene.write_text(json.dumps(d))
    out = tmp_path / "eqs.tex"
    p = subprocess.run([sys.executable, "-m", "linkage_sym", "derive", str(scene), "--latex",
                        "-o", str(out)], capture_output=True, text=True)
    assert p.returncode == 2
    assert "links[0].mass" in p.stderr
    assert not out.exists()


# -- a textbook author's document --------------------------------------------------------------

MAX_EQUATION_CHARS = 250


def _equation_lines(doc):
    """Every line of every equation and align row, without its label."""
    out = []
    for block in re.findall(r"\\begin\{(?:equation|align\*?)\}\n(.*?)\n\\end\{", doc, re.S):
        for line in block.splitlines():
            out.append(re.sub(r"\s*\\label\{[^}]*\}|\s*\\nonumber|\s*\\\\$", "", line))
    return out


@pytest.mark.slow
def test_the_four_bar_has_no_equation_longer_than_250_characters(documents):
    """Named intermediates (outer joints, d, a, h, the inner joint; the centres of mass's
    accelerations) keep every equation of the shipped four-bar readable."""
    lines = _equation_lines(documents["crank_rocker"])
    longest = max(lines, key=len)
    assert len(longest) < MAX_EQUATION_CHARS, longest
    doc = documents["crank_rocker"]
    for piece in (r"d_{2} &= \sqrt{\Delta x_{2}^{2} + \Delta y_{2}^{2}}", r"h_{2} &=", r"a_{2} &=",
                  r"x_{C} &= x_{B} +", r"a^{G}_{\mathrm{coupler},x} &="):
        assert piece in doc, piece
    # the square root of the half-chord is written once, not in every angle
    # (Heron's factor written positive terms first: l_BC + l_CD - d_2, not -d_2 + l_BC + l_CD)
    assert doc.count(r"\sqrt{\left(l_{BC} + l_{CD} - d_{2}\right)") == 1


@pytest.mark.slow
@pytest.mark.parametrize("name", symbolic_examples())  # the symbolic layer refuses cams
def test_the_named_positions_are_the_closed_forms(name):
    """Substituting the intermediates back gives the closed forms the code is generated
    from: compared in 30-digit mpmath (1e-25) at the scene's parameter values and the
    driver values of solved steps, in both assembly modes."""
    scene = load_example(name)
    eqs = derive(scene, forces=True)
    defs = {}
    for s, e in eqs.position_steps:
        defs[s] = e.xreplace(defs)
    nested = eqs.nested_closed_forms()
    res = linkage_sym.analyze(scene)
    ok = np.flatnonzero(res.status == "ok")
    steps = ok[:: max(1, len(ok) // 3)][:3]  # three solved steps spread over the sweep
    values = eqs.parameter_values()
    rng = np.random.default_rng(7)
    for s, e in eqs.closed_forms:
        a, b = defs[s], nested[s]
        free = sorted(a.free_symbols | b.free_symbols, key=str)
        fa, fb = (sp.lambdify(free, v, "mpmath") for v in (a, b))
        with mp.workdps(30):
            for i in steps:
                for sign in (1, -1):
                    vals = []
                    for f in free:
                        if f in values:
                            vals.append(mp.mpf(values[f]))
                        elif f in eqs.q:
                            d = scene.drivers[eqs.q.index(f)]
                            vals.append(mp.mpf(float(res.drivers[d.joint]["q"][i])))
                        elif f in eqs.sigmas:
                            vals.append(mp.mpf(sign))
                        else:  # a coordinate of a Newton group
                            vals.append(mp.mpf(rng.uniform(-3, 3)))
                    va, vb = _real_or_none(fa, vals), _real_or_none(fb, vals)
                    assert (va is None) == (vb is None), (name, s, i)
                    if va is None:
                        continue  # not real (that mode unassemblable here), on both sides
                    assert abs(va - vb) <= mp.mpf("1e-25") * max(1, abs(vb)), (name, s, i)


def _real_or_none(f, vals):
    """``f(*vals)``, or None where mpmath meets a complex intermediate (atan2 refuses it)."""
    try:
        v = f(*vals)
    except (TypeError, AttributeError):
        return None
    return None if isinstance(v, mp.mpc) else v


@pytest.mark.slow
def test_sources_are_cited_as_bibliography_entries(documents):
    doc = documents["crank_rocker"]
    keys = set(re.findall(r"\\cite(?:\[[^]]*\])?\{([^}]*)\}", doc))
    assert keys == {"linkagesym-kinematics"}
    assert "seed" not in doc.lower()
    full = standalone(doc)
    for key in keys:
        assert rf"\bibitem{{{key}}}" in full
    assert full.startswith(r"\documentclass") and full.rstrip().endswith(r"\end{document}")


def test_the_symbol_table_gives_every_symbol_a_meaning_and_a_unit():
    eqs = derive(load_example("slider_crank_offset"), forces=True)
    doc = latex_document(eqs, symbols=True)
    table = re.search(r"\\begin\{longtable\}\{lll\}\n(.*?)\\end\{longtable\}", doc, re.S).group(1)
    rows = [r for r in table.splitlines()[1:] if r.strip()]
    assert len(rows) == 3 * len(eqs.x) + 3 * len(eqs.q) + len(eqs.sigmas) + len(eqs.parameters) \
        + len(eqs.intermediates) + len(eqs.force_intermediates) + 2 * len(eqs.F) + len(eqs.E)
    for r in rows:
        sym, meaning, unit = (c.strip() for c in r.rstrip("\\ ").split(" & "))
        assert sym.startswith("$") and meaning and unit, r
    assert r"$l_{AB}$ & distance" in doc and "& m \\\\" in doc and r"& N\,m \\" in doc


@pytest.mark.skipif(not shutil.which("pdflatex"), reason="no pdflatex on PATH")
def test_the_standalone_document_compiles(tmp_path):
    eqs = derive(load_example("crank_rocker"), forces=True)
    (tmp_path / "eqs.tex").write_text(standalone(latex_document(eqs, symbols=True)))
    for _ in range(2):  # twice: citations and labels resolved
        p = subprocess.run(["pdflatex", "-interaction=nonstopmode", "-halt-on-error", "eqs.tex"],
                           cwd=tmp_path, capture_output=True, text=True, timeout=120)
        assert p.returncode == 0, p.stdout[-3000:]
    log = (tmp_path / "eqs.log").read_text()
    assert "undefined" not in log.lower(), [ln for ln in log.splitlines() if "ndefined" in ln]


def test_cli_derive_standalone_and_symbols(tmp_path):
    out = tmp_path / "eqs.tex"
    src = str(linkage_sym.examples.example_path("crank_rocker"))
    assert main(["derive", src, "--latex", "--standalone", "--symbols", "-o", str(out)]) == 0
    text = out.read_text()
    assert text.startswith(r"\documentclass") and r"\begin{longtable}" in text
    assert main(["derive", src, "--standalone", "-o", str(tmp_path / "x.tex")]) == 2
    assert not (tmp_path / "x.tex").exists()
