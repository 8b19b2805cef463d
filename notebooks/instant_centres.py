# ---
# jupyter:
#   jupytext:
#     formats: py:percent
#     text_representation:
#       extension: .py
#       format_name: percent
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---


# %% [markdown]
# # Instant centres of a crank-rocker, checked by hand
#
# Kept as text (jupytext py:percent); `tests/paper/test_notebooks.py` executes it.
#
# The kinematics textbook chapter (README, Sources [4], section 3-2) finds velocities by
# instant centres: a mechanism of $N$ links has $N(N-1)/2$ of them (eq. 3-5), the primary
# ones at the joints, the others by Kennedy's three-centre theorem. `linkage_sym.centres`
# computes them from a solved sweep; a scene that lists `"instant_centres"` in its `outputs`
# gets them in its result too (an extension of the scene format). Links are numbered as in
# the chapter's figures: the ground 1, then the scene's links in order (crank 2, coupler 3,
# rocker 4).

# %%
# %matplotlib inline
import json
from importlib.resources import files

import numpy as np

import linkage_sym
from linkage_sym.centres import centrodes, instant_centres, textbook_numbers

d = json.loads(files("linkage_sym.examples").joinpath("crank_rocker.json").read_text())
d["outputs"] = d["outputs"] + ["instant_centres"]
scene = linkage_sym.load_scene(d)
res = linkage_sym.analyze(scene)
ic = res.instant_centres
num = textbook_numbers(ic.links)
print(f"{len(ic.pairs)} = {len(ic.links)}·{len(ic.links) - 1}/2 instant centres")
assert len(ic.pairs) == len(ic.links) * (len(ic.links) - 1) // 2

# %% [markdown]
# ## One step
# At step 40 (crank at 40°) every centre is finite. Each is listed with how Kennedy's
# construction found it; the result's JSON record of that step carries the same centres.

# %%
k = 40
name = {pair: "P%d%d" % (num[pair[0]], num[pair[1]]) for pair in ic.pairs}
for p, pair in enumerate(ic.pairs):
    print(f"{name[pair]}  {pair[0]}-{pair[1]}  ({ic.position[k, p, 0] * 1e3:.4f}, "
          f"{ic.position[k, p, 1] * 1e3:.4f}) mm  {ic.source[p]}")
record = json.loads(res.to_json())["steps"][k]["instant_centres"]
print(record[1])
assert not ic.at_infinity[k].any() and not ic.undefined[k].any()
P = {name[pair]: ic.position[k, p] for p, pair in enumerate(ic.pairs)}
assert np.allclose(record[1]["position"], P["P13"])
# the API gives the same centres for any analysis
assert np.array_equal(instant_centres(scene, res).position[k], ic.position[k], equal_nan=True)

# %% [markdown]
# ## P13 lies on the lines AB and CD
# The coupler's centre relative to the ground, P13, is on the line of P12 (`A`) and P23
# (`B`), and on the line of P14 (`D`) and P34 (`C`): Kennedy's theorem. We check both with the
# cross product, and rebuild P13 as the intersection of the two lines by hand.

# %%
A, B, C, D = (res.joints[j].position[k] for j in "ABCD")


def cross(u, v):
    return u[0] * v[1] - u[1] * v[0]


L = np.linalg.norm(D - A)
print("distance of P13 from line AB: %.1e m, from line CD: %.1e m"
      % (cross(B - A, P["P13"] - A) / np.linalg.norm(B - A),
         cross(C - D, P["P13"] - D) / np.linalg.norm(C - D)))
assert abs(cross(B - A, P["P13"] - A)) / np.linalg.norm(B - A) < 1e-12 * L
assert abs(cross(C - D, P["P13"] - D)) / np.linalg.norm(C - D) < 1e-12 * L
s = cross(D - A, C - D) / cross(B - A, C - D)  # A + s (B - A) on line CD
assert np.allclose(A + s * (B - A), P["P13"], atol=1e-12 * L)
# and P24 on the lines AD and BC
assert abs(cross(D - A, P["P24"] - A)) < 1e-12 * L * L
assert abs(cross(C - B, P["P24"] - B)) < 1e-12 * L * L

# %% [markdown]
# ## Velocities rebuilt from the centres
# A link turning about its centre relative to the ground moves each of its points at
# $v = \omega \times (r - P_{1j})$. The crank's $\omega_2$ is the driver's speed; the shared
# centres give the others: P23 moves with links 2 and 3, so
# $\omega_3 = \omega_2\, |P_{12}P_{23}| / |P_{13}P_{23}|$ with the sign of the order of
# the points, and likewise through P24 for the rocker. Then $v_B$, $v_C$ and the traced
# point's velocity, against the solver's.

# %%
def rot90(u):
    return np.array([-u[1], u[0]])


def ratio(p1i, p1j, pij):
    """omega_j / omega_i from the centres P1i, P1j and Pij (signed, along their line)."""
    u = pij - p1i
    return np.dot(pij - p1i, u) / np.dot(pij - p1j, u)


w2 = res.drivers["A"]["qd"][k]
w3 = w2 * ratio(P["P12"], P["P13"], P["P23"])
w4 = w2 * ratio(P["P12"], P["P14"], P["P24"])
Ppt = res.points["P"].position[k]
rebuilt = {"B": w2 * rot90(B - P["P12"]), "C": w4 * rot90(C - P["P14"]),
           "P": w3 * rot90(Ppt - P["P13"])}
solver = {"B": res.joints["B"].velocity[k], "C": res.joints["C"].velocity[k],
          "P": res.points["P"].velocity[k]}
print("omega: coupler %.9f (solver %.9f), rocker %.9f (solver %.9f) rad/s"
      % (w3, res.links["coupler"].omega[k], w4, res.links["rocker"].omega[k]))
V = max(np.linalg.norm(v) for v in solver.values())
for j in rebuilt:
    print(f"v_{j}: centres {rebuilt[j]}, solver {solver[j]}")
    assert np.linalg.norm(rebuilt[j] - solver[j]) < 1e-12 * V
assert np.isclose(w3, res.links["coupler"].omega[k], rtol=1e-12)
assert np.isclose(w4, res.links["rocker"].omega[k], rtol=1e-12)
# C also moves with the coupler about P13
assert np.linalg.norm(w3 * rot90(C - P["P13"]) - solver["C"]) < 1e-12 * V

# %% [markdown]
# ## Pictures
# The linkage at the step with every centre and the three-centre lines Kennedy's
# construction used; then the fixed and moving centrodes of the coupler (the only floating
# link), the moving one drawn where the coupler is at the step, touching the fixed one at P13.
# The plotting functions write PNG files; we write them to a temporary folder.

# %%
import tempfile  # noqa: E402
from pathlib import Path  # noqa: E402

from IPython.display import Image, display  # noqa: E402

from linkage_sym.plotting.centres import centres_figure, centrodes_figure  # noqa: E402

tmp = Path(tempfile.mkdtemp())
cd = centrodes(scene, res, ic)
print("floating links:", list(cd))
display(Image(filename=str(centres_figure(scene, res, ic, k, tmp / "centres.png"))))
display(Image(filename=str(centrodes_figure(scene, res, ic, k, cd, tmp / "centrodes.png"))))

# %% [markdown]
# The fixed centrode is the path of P13 over the sweep: at the step it passes through the
# centre found above.

# %%
fixed = cd["coupler"].fixed
print("closest point of the fixed centrode to P13: %.1e m"
      % np.nanmin(np.linalg.norm(fixed - P["P13"], axis=1)))
assert np.nanmin(np.linalg.norm(fixed - P["P13"], axis=1)) < 1e-12 * L
