"""The global matrix method: every link's equilibrium in one sparse linear system.

This is the method Dang and Zhang contrast theirs with: write the three equilibrium
equations of every moving link, with every joint reaction and driver effort
as unknowns, and solve them all at once.  Here the systems of all the steps
of a sweep form one block-diagonal sparse matrix, factorised once by
SuperLU (:func:`scipy.sparse.linalg.spsolve`).  It shares no solving code
with the closed-form group routines of :mod:`~linkage_sym.numeric.forces.statics`,
which it checks.  Its assembly (:func:`assemble`) also serves, restricted to
a few links, the split of a removed link's reactions in
:mod:`~linkage_sym.numeric.forces.superposition` (other than two revolutes) and the
dense solve of a group no disconnection reduces to dyads; those paths are
checked by the equilibrium and power-balance tests, which share no code
with it.

Unknowns and equations
----------------------
Per joint two unknowns: ``(Rx, Ry)`` for an ``R`` joint, ``(N, M/L)`` for a
``P`` joint (normal force, couple); per gear mesh one, its tooth load ``Fn``
along the line of action (``Geometry.line_of_action``, from gear
``links[0]`` on gear ``links[1]`` at the pitch point: the mesh constraint's
reaction); per cam contact one, its normal force along the contact normal
(``Geometry.contact_normal``, from the cam on the follower at the contact
point); per driver one: ``tau/L`` (``R``) or the
axial force (``P``).  Per link three rows: force balance in x and y, and
moment balance about the link's wrench reference point divided by ``L``
(the mechanism size), so that every entry is of order one.

The same assembly, restricted to one group's links, solves a group that no
disconnection turns into dyads (:func:`solve_dense`).
"""

from __future__ import annotations

import numpy as np

from linkage_sym.model import GROUND


def _layout(scene, joints, drivers):
    cols = {}
    c = 0
    meshes = {j.name for j in scene.joints if j.type in ("G", "cam")}  # one unknown each
    for j in joints:
        cols[j] = c
        c += 1 if j in meshes else 2
    for d in drivers:
        cols["driver:" + d] = c
        c += 1
    return cols, c


def assemble(scene, links, joints, drivers, geo, W, L):
    """Entries of ``A z = b`` for the equilibrium of ``links``.

    Returns
    -------
    entries : list of (row, col, value)
        ``value`` a scalar or an array over the steps.
    b : list of arrays
        Right-hand side per row.
    cols : dict
        Column of each joint (and ``"driver:<joint>"``).
    ncols : int
    """
    cols, ncols = _layout(scene, joints, drivers)
    row_of = {n: 3 * i for i, n in enumerate(links)}
    entries = []
    jdict = {j.name: j for j in scene.joints}

    def put(link, sign, col, fx, fy, px, py, couple):
        if link not in row_of:
            return
        r = row_of[link]
        w = W[link]
        if fx is not None:
            entries.append((r, col, sign * fx))
            entries.append((r + 1, col, sign * fy))
            entries.append((r + 2, col, sign * ((px - w.rx) * fy - (py - w.ry) * fx) / L))
        if couple is not None:
            entries.append((r + 2, col, sign * couple))

    for name in joints:
        j = jdict[name]
        c = cols[name]
        px, py = geo.point(name)
        for link, s in ((j.links[1], 1.0), (j.links[0], -1.0)):
            if j.type == "R":
                put(link, s, c, 1.0, 0.0, px, py, None)
                put(link, s, c + 1, 0.0, 1.0, px, py, None)
            elif j.type == "G":
                ux, uy = geo.line_of_action(name)
                put(link, s, c, ux, uy, px, py, None)
            elif j.type == "cam":  # along the contact normal, at the contact point
                ux, uy = geo.contact_normal(name)
                put(link, s, c, ux, uy, px, py, None)
            else:
                nx, ny, _, _ = geo.normal(name)
                put(link, s, c, nx, ny, px, py, None)
                put(link, s, c + 1, None, None, px, py, 1.0)
    for name in drivers:
        j = jdict[name]
        c = cols["driver:" + name]
        px, py = geo.point(name)
        for link, s in ((j.links[1], 1.0), (j.links[0], -1.0)):
            if j.type == "R":
                put(link, s, c, None, None, px, py, 1.0)
            else:
                _, _, tx, ty = geo.normal(name)
                put(link, s, c, tx, ty, px, py, None)
    b = []
    for n in links:
        w = W[n]
        b += [-w.fx, -w.fy, -w.m / L]
    return entries, b, cols, ncols


def unpack(scene, z, cols, joints, drivers, geo, L):
    """Reactions ``{joint: (fx, fy, m)}`` and efforts from solution rows ``z`` (K, ncols)."""
    jdict = {j.name: j for j in scene.joints}
    reactions, efforts = {}, {}
    for name in joints:
        c = cols[name]
        if jdict[name].type == "R":
            reactions[name] = (z[:, c], z[:, c + 1], np.zeros(z.shape[0]))
        elif jdict[name].type in ("G", "cam"):
            ux, uy = (geo.line_of_action(name) if jdict[name].type == "G"
                      else geo.contact_normal(name))
            reactions[name] = (z[:, c] * ux, z[:, c] * uy, np.zeros(z.shape[0]))
        else:
            nx, ny, _, _ = geo.normal(name)
            N = z[:, c]
            reactions[name] = (N * nx, N * ny, L * z[:, c + 1])
    for name in drivers:
        c = cols["driver:" + name]
        efforts[name] = L * z[:, c] if jdict[name].type == "R" else z[:, c]
    return reactions, efforts


def _rhs(b, K):
    """Right-hand sides as a (K, rows) array."""
    rhs = np.stack(np.broadcast_arrays(*[np.asarray(x, dtype=float) for x in b]), axis=-1)
    return np.broadcast_to(rhs, (K, len(b)))


def dense_system(entries, b, nrows, ncols, K):
    """``(A, rhs)`` of shapes (K, nrows, ncols) and (K, nrows) from :func:`assemble`'s output."""
    A = np.zeros((K, nrows, ncols))
    for r, c, v in entries:
        A[:, r, c] += v
    return A, _rhs(b, K)


def solve_dense(scene, links, joints, drivers, geo, W, L, K):
    """Solve one group's equilibrium (its ``links``) as a batch of small dense systems.

    Used for groups that no disconnection reduces to dyads.  Returns
    ``(reactions, efforts)`` like the group routines.
    """
    entries, b, cols, ncols = assemble(scene, links, joints, drivers, geo, W, L)
    A, rhs = dense_system(entries, b, 3 * len(links), ncols, K)
    z = np.linalg.solve(A, rhs[..., None])[..., 0]
    return unpack(scene, z, cols, joints, drivers, geo, L)


def solve_global(scene, geo, W, L, K):
    """All reactions and efforts of the mechanism from one sparse solve over ``K`` steps.

    Returns
    -------
    reactions : dict of str to (fx, fy, m)
    efforts : dict of str to array
    """
    links = list(scene.link_names)
    joints = [j.name for j in scene.joints]
    drivers = [d.joint for d in scene.drivers]
    entries, b, cols, ncols = assemble(scene, links, joints, drivers, geo, W, L)
    nrows = 3 * len(links)
    if nrows != ncols:  # pragma: no cover - validation refuses such scenes
        raise ValueError(f"{nrows} equilibrium equations for {ncols} unknowns")
    steps = np.arange(K)
    rows_i, cols_i, vals = [], [], []
    for r, c, v in entries:
        rows_i.append(r + nrows * steps)
        cols_i.append(c + ncols * steps)
        vals.append(np.broadcast_to(np.asarray(v, dtype=float), (K,)))
    import scipy.sparse as sp  # on use: only --method global loads SciPy's sparse solver
    from scipy.sparse.linalg import spsolve

    A = sp.csc_matrix(
        (np.concatenate(vals), (np.concatenate(rows_i), np.concatenate(cols_i))),
        shape=(nrows * K, ncols * K),
    )
    z = spsolve(A, _rhs(b, K).reshape(-1)).reshape(K, ncols)
    return unpack(scene, z, cols, joints, drivers, geo, L)


def frame_wrench(scene, geo, reactions, efforts):
    """Force and moment (about the origin) that the moving links put on the ground.

    Written out from the ground joints' reactions and the efforts of drivers
    mounted on the ground, independently of the group routines' bookkeeping.
    """
    fx = fy = m = 0.0
    for j in scene.joints:
        if GROUND not in j.links:
            continue
        rx, ry, rm = reactions[j.name]
        e = efforts.get(j.name)
        if e is not None:
            if j.type == "R":
                rm = rm + e
            else:
                _, _, tx, ty = geo.normal(j.name)
                rx, ry = rx + e * tx, ry + e * ty
        # the ground receives +reaction when it is links[1], -reaction when links[0]
        s = 1.0 if j.links[1] == GROUND else -1.0
        px, py = geo.point(j.name)
        fx = fx + s * rx
        fy = fy + s * ry
        m = m + s * (px * ry - py * rx + rm)
    return fx, fy, m
