// The JavaScript backend of linkage_sym's evaluator of generated code (no library, no network).
//
// linkage_sym.codegen.javascript inlines this file into a page after the helper constants
// (`CONST`) and the generated functions (`GENERATED`, printed by SymPy's JavaScript printer
// from the same derivation as the NumPy runtime's).  It is the NumPy runtime's walk
// (linkage_sym/codegen/evaluator.py, runtime.py) for one driver value at a time:
//
// - the parameters re-read from the joints' assembly positions by the recipes that depend
//   on them (structure/recipes.py: l, beta, x, y, theta0, gamma, delta, p, q, epsilon, xi,
//   eta); the others (masses, loads, gear radii) do not change with a drag and are the
//   Python recipes' values;
// - the assembly-mode signs chosen as the runtime chooses them (the signs whose closed forms
//   reproduce the assembly configuration; an assembly at a dead centre is refused);
// - closed steps by one call; Newton steps by the continuation policy of
//   linkage_sym.numeric.continuation, point by point along a solving path from the assembly
//   configuration (at most 2 degrees or 2 % of the size a point): damped Newton with
//   polishing to the scaled residual TOL, a linear predictor, acceptance only with the
//   assembly's Jacobian-determinant sign and within MAX_CORRECTION of the predictor,
//   bisected sub-steps down to MIN_FRACTION; past a limit or a gap, the re-entry search
//   (seeds around the known configurations and turned by fixed offsets, bounded Newton
//   steps, the nearest root of the assembly's sign).  Simpler than the policy: one point
//   at a time (no batched walk), and no notes (a jump or an ambiguous re-entry is taken
//   silently; the result file's warnings have them);
// - statuses: `unassemblable` where a closed form has no real value, a dyad of two slides
//   has them parallel (to rounding: its joint at infinity) or the continuation fails;
//   `sweep` also gives the passages of such a dyad's joint through infinity (the cross
//   product of its slides changing sign between two path points where the dyad is solved,
//   codegen.parallels' test), which the page words as a warning;
//   `singular` where a group block of A (the rate matrix) has a Hadamard ratio below
//   SCREEN and the dimensionless A's condition number (one-sided Jacobi SVD) exceeds
//   SINGULAR_COND, the runtime's screen and test.
"use strict";

function _coordinate_size() {
  let out = 0.0;
  for (let i = 0; i < arguments.length; i++) out = Math.max(out, Math.abs(arguments[i]));
  return out;
}

function _tangent_sqrt(scale) {
  // sqrt of the product of the factors; a rounding-level miss of a tangency (every negative
  // factor above -TANGENT_ULPS eps scale) is the tangency (0), a real miss NaN
  let prod = 1.0;
  let worst = Infinity;
  for (let i = 1; i < arguments.length; i++) {
    prod = i === 1 ? arguments[i] : prod * arguments[i];
    worst = Math.min(worst, arguments[i]);
  }
  if (prod < 0.0) {
    prod = worst >= -CONST.TANGENT_ULPS * CONST.EPS * scale ? 0.0 : NaN;
  }
  return Math.sqrt(prod);
}

const LinkageEvaluator = (function () {
  const TWO_PI = 2 * Math.PI;

  function wrap(a) {
    // (a + pi) mod 2 pi - pi, as NumPy's % (the sign of the divisor)
    const t = (a + Math.PI) % TWO_PI;
    return (t < 0 ? t + TWO_PI : t) - Math.PI;
  }

  // -- small dense linear algebra ------------------------------------------------------
  function luSolve(J, r) {
    // J x = r by Gaussian elimination with partial pivoting; returns {x, det} (x null when
    // J is singular)
    const n = r.length;
    const A = J.map((row) => row.slice());
    const b = r.slice();
    let det = 1.0;
    for (let k = 0; k < n; k++) {
      let p = k;
      for (let i = k + 1; i < n; i++) if (Math.abs(A[i][k]) > Math.abs(A[p][k])) p = i;
      if (p !== k) {
        [A[p], A[k]] = [A[k], A[p]];
        [b[p], b[k]] = [b[k], b[p]];
        det = -det;
      }
      const piv = A[k][k];
      det *= piv;
      if (piv === 0 || !Number.isFinite(piv)) return { x: null, det: det };
      for (let i = k + 1; i < n; i++) {
        const f = A[i][k] / piv;
        if (f === 0) continue;
        for (let j = k; j < n; j++) A[i][j] -= f * A[k][j];
        b[i] -= f * b[k];
      }
    }
    const x = new Array(n);
    for (let i = n - 1; i >= 0; i--) {
      let s = b[i];
      for (let j = i + 1; j < n; j++) s -= A[i][j] * x[j];
      x[i] = s / A[i][i];
    }
    return { x: x, det: det };
  }

  function det(J) {
    return luSolve(J, new Array(J.length).fill(0)).det;
  }

  function norm(v) {
    let s = 0;
    for (const a of v) s += a * a;
    return Math.sqrt(s);
  }

  function maxAbsDiff(a, b) {
    let m = 0;
    for (let i = 0; i < a.length; i++) m = Math.max(m, Math.abs(a[i] - b[i]));
    return m;
  }

  function singularValues(M) {
    // one-sided Jacobi (Hestenes): the columns orthogonalised by rotations; their norms are
    // the singular values, to the relative accuracy of the matrix's columns
    const m = M.length;
    const n = M[0].length;
    const U = M.map((row) => row.slice());
    for (let sweep = 0; sweep < 60; sweep++) {
      let rotated = false;
      for (let p = 0; p < n - 1; p++) {
        for (let q = p + 1; q < n; q++) {
          let a = 0, b = 0, c = 0;
          for (let i = 0; i < m; i++) {
            a += U[i][p] * U[i][p];
            b += U[i][q] * U[i][q];
            c += U[i][p] * U[i][q];
          }
          if (c === 0 || Math.abs(c) <= 1e-15 * Math.sqrt(a * b)) continue;
          rotated = true;
          const zeta = (b - a) / (2 * c);
          const t = Math.sign(zeta || 1) / (Math.abs(zeta) + Math.sqrt(1 + zeta * zeta));
          const cs = 1 / Math.sqrt(1 + t * t);
          const sn = cs * t;
          for (let i = 0; i < m; i++) {
            const up = U[i][p], uq = U[i][q];
            U[i][p] = cs * up - sn * uq;
            U[i][q] = sn * up + cs * uq;
          }
        }
      }
      if (!rotated) break;
    }
    const out = [];
    for (let j = 0; j < n; j++) {
      let s = 0;
      for (let i = 0; i < m; i++) s += U[i][j] * U[i][j];
      out.push(Math.sqrt(s));
    }
    return out.sort((x, y) => y - x);
  }

  // -- the scene's geometry and the parameters' recipes ------------------------------------
  class Geometry {
    // what the recipes read: the joints' assembly positions (the only thing a drag changes)
    // and the link frames' joints (linkage_sym.structure.parameters.link_frames' choice)
    constructor(model) {
      this.model = model;
      this.frames = {};
      for (const [link, uv] of Object.entries(model.frames)) {
        const U = model.joints[uv[0]].at;
        let th = 0.0;
        if (uv[1] !== null) {
          const V = model.joints[uv[1]].at;
          th = Math.atan2(V[1] - U[1], V[0] - U[0]);
        }
        this.frames[link] = { origin: [U[0], U[1]], theta0: th };
      }
      let L = 0.0;
      const pts = model.order.map((n) => model.joints[n].at);
      for (let i = 0; i < pts.length; i++)
        for (let j = i + 1; j < pts.length; j++)
          L = Math.max(L, Math.sqrt((pts[i][0] - pts[j][0]) ** 2 + (pts[i][1] - pts[j][1]) ** 2));
      this.L = L || 1.0;
    }
    at(joint) { return this.model.joints[joint].at; }
    theta0(link) { return link === "ground" ? 0.0 : this.frames[link].theta0; }
    local(link, p) {
      const f = this.frames[link];
      const dx = p[0] - f.origin[0], dy = p[1] - f.origin[1];
      const c = Math.cos(f.theta0), s = Math.sin(f.theta0);
      return [c * dx + s * dy, -s * dx + c * dy];
    }
    direction(a, b) { return Math.atan2(b[1] - a[1], b[0] - a[0]); }
  }

  function wrapRecipe(a) { return Math.atan2(Math.sin(a), Math.cos(a)); }

  // one function a recipe kind (structure/recipes.py): tag, args -> value
  const RECIPES = {
    l: (g, link, joint) => { const p = g.local(link, g.at(joint)); return Math.hypot(p[0], p[1]); },
    beta: (g, link, joint) => { const p = g.local(link, g.at(joint)); return Math.atan2(p[1], p[0]); },
    x: (g, joint) => g.at(joint)[0],
    y: (g, joint) => g.at(joint)[1],
    theta0: (g, link) => g.frames[link].theta0,
    gamma: (g, joint) => {
      const j = g.model.joints[joint];
      return wrapRecipe(j.axis - g.theta0(j.links[0]));
    },
    delta: (g, joint, toward) => {
      const j = g.model.joints[joint];
      return wrapRecipe(g.direction(j.at, g.at(toward)) - g.theta0(j.links[1]));
    },
    p: (g, link) => g.local(link, g.model.links[link].com)[0],
    q: (g, link) => g.local(link, g.model.links[link].com)[1],
    epsilon: (g, joint) => {
      const j = g.model.joints[joint];
      return wrapRecipe(g.direction(g.at(j.pivots[0]), g.at(j.pivots[1])) - g.theta0(j.carrier));
    },
    xi: (g, load) => { const ld = g.model.loads[load]; return g.local(ld.link, ld.at)[0]; },
    eta: (g, load) => { const ld = g.model.loads[load]; return g.local(ld.link, ld.at)[1]; },
  };

  function parameters(model, g) {
    // P: each parameter by its recipe (the model's value where the recipe reads no joint
    // position), then the signs (1 until chosen), then the flanks
    const P = model.params.map((p) => {
      const r = RECIPES[p.recipe[0]];
      return r === undefined ? p.value : r(g, ...p.recipe.slice(1));
    });
    for (let i = 0; i < model.sigmas + model.flanks; i++) P.push(1.0);
    return P;
  }

  function driverQ0(model) {
    // each driver's value in the assembly configuration (an R driver's representative
    // nearest its start: structure.parameters.driver_q0)
    return model.drivers.map((d) => {
      if (d.kind !== "R") return 0.0;
      const j = model.joints[d.joint].at, t = model.joints[d.toward].at;
      const phi = Math.atan2(t[1] - j[1], t[0] - j[0]);
      return phi + TWO_PI * Math.round((d.start - phi) / TWO_PI);
    });
  }

  class SceneError extends Error {}

  // -- the mechanism ----------------------------------------------------------------------
  class Mechanism {
    // the generated functions of one topology bound to the joints' assembly positions
    constructor(art, functions, model) {
      this.art = art;
      this.f = functions;
      this.model = model;
      this.m = art.x.length;
      this.isAngle = art.x.map((n) => n.startsWith("theta_"));
      this.geometry = new Geometry(model);
      this.L = this.geometry.L;
      this.P = parameters(model, this.geometry);
      this.q0 = driverQ0(model);
      this.x0 = new Array(this.m).fill(0.0);
      this.angleOf = {};
      for (const link of Object.keys(model.frames)) {
        const c = art.x.indexOf("theta_" + model.ident[link]);
        this.angleOf[link] = c;
        this.x0[c] = this.geometry.frames[link].theta0;
      }
      this.lim = model.drivers.map((d) =>
        d.kind === "R" ? CONST.MAX_ANGLE_STEP : CONST.MAX_SLIDE_STEP * this.L);
      this.zeros = new Array(this.m).fill(0.0);
      this.qzeros = new Array(art.q.length).fill(0.0);
      this.fzeros = new Array(art.force_names.length).fill(0.0);
      this.groupOf = {};
      for (const g of art.groups) for (const c of g.cols) this.groupOf[c] = g.index;
      this.chooseBranches();
      this.newton = {};
      for (const st of art.steps) if (st.kind === "newton") this.newton[st.group] = this.newtonProblem(st);
    }

    call(name, X, Q, P, CX, SX) {
      return this.f[name](X, this.zeros, this.zeros, Q, this.qzeros, this.qzeros, this.fzeros,
        P || this.P, CX || null, SX || null);
    }

    chooseBranches() {
      // the assembly-mode signs whose closed forms reproduce the assembly configuration
      // (codegen.runtime.CompiledMechanism._choose_branches)
      const art = this.art, k = art.sigmas, n = art.params.length;
      if (k === 0) return;
      const errs = [];
      for (let combo = 0; combo < (1 << k); combo++) {
        const P = this.P.slice();
        for (let i = 0; i < k; i++) P[n + i] = (combo >> (k - 1 - i)) & 1 ? -1.0 : 1.0;
        let err = 0.0;
        for (const st of art.steps) {
          if (st.kind !== "closed") continue;
          const out = this.call(st.function, this.x0.slice(), this.q0, P);
          st.x.forEach((c, j) => {
            const d = this.isAngle[c] ? wrap(out[j] - this.x0[c]) : (out[j] - this.x0[c]) / this.L;
            err = Math.max(err, Number.isFinite(d) ? Math.abs(d) : Infinity);
          });
        }
        errs.push(err);
      }
      let best = 0;
      errs.forEach((e, i) => { if (e < errs[best]) best = i; });
      if (!(errs[best] <= CONST.ASSEMBLY_MATCH))
        throw new SceneError("joints: the joints' positions cannot be assembled by the closed forms " +
          "of this mechanism (error " + errs[best].toPrecision(3) + ")");
      for (let i = 0; i < k; i++) {
        const flipped = best ^ (1 << (k - 1 - i));
        if (errs[flipped] <= CONST.ASSEMBLY_MATCH) {
          const g = art.groups.find((gr) => gr.sigma === n + i);
          throw new SceneError("joints: the assembly configuration is a singular position of the " +
            g.label + " (" + g.links.join(", ") + "): its assembly mode is undefined; " +
            "move the joints off the dead-centre position");
        }
      }
      for (let i = 0; i < k; i++) this.P[n + i] = (best >> (k - 1 - i)) & 1 ? -1.0 : 1.0;
    }

    // -- Newton groups: the continuation policy (numeric.continuation) ---------------------
    newtonProblem(step) {
      const g = this.art.groups.find((gr) => gr.index === step.group);
      const scale = step.x.map((c) => (this.isAngle[c] ? 1.0 : this.L));
      const rows = this.art.rows_length.slice(g.rows[0], g.rows[1]);
      const rowScale = rows.map((isLen) => (isLen ? 1.0 / this.L : 1.0));
      const f = this.f[step.function];
      const n = step.x.length;
      const self = this;
      return {
        step: step, group: g, n: n, scale: scale,
        angles: step.x.map((c) => this.isAngle[c]),
        evaluate(u, ctx) {
          const X = ctx.X.slice();
          step.x.forEach((c, k) => { X[c] = u[k] * scale[k]; });
          const out = f(X, null, null, ctx.Q, null, null, null, self.P, null, null);
          const r = new Array(n), J = [];
          for (let i = 0; i < n; i++) {
            r[i] = out[i] * rowScale[i];
            const row = new Array(n);
            for (let j = 0; j < n; j++) row[j] = out[n + i * n + j] * rowScale[i] * scale[j];
            J.push(row);
          }
          return { r: r, J: J };
        },
        blend(a, b, t) {
          return {
            Q: a.Q.map((v, i) => (1 - t) * v + t * b.Q[i]),
            X: a.X.map((v, i) => (v === null ? null : (1 - t) * v + t * b.X[i])),
          };
        },
      };
    }

    solvePath(Qpath) {
      // positions at every point of a solving path (point 0: the assembly configuration's
      // driver values): [{X, failed}] with failed the first failing group's index or -1
      const art = this.art;
      const walks = {};
      for (const g of Object.keys(this.newton)) walks[g] = { last: null, before: null, stop: null, sign: null };
      const out = [];
      for (let i = 0; i < Qpath.length; i++) {
        const Q = Qpath[i];
        const X = new Array(this.m).fill(null);
        const cross = {}; // the dyads of two slides: the cross product of their slides
        let failed = -1;
        for (const st of art.steps) {
          if (failed >= 0) break;
          if (st.kind === "closed") {
            const v = this.call(st.function, X, Q);
            st.x.forEach((c, j) => { X[c] = v[j]; });
            for (const c of st.x) if (!Number.isFinite(X[c])) { failed = this.groupOf[c]; break; }
            const par = this.parallelAt(st, X, Q, cross);
            if (par >= 0 && (failed < 0 || par < failed)) failed = par;
          } else {
            const u = this.newtonAt(this.newton[st.group], walks[st.group], i, { Q: Q, X: X.slice() });
            if (u === null) failed = st.group;
            else st.x.forEach((c, k) => { X[c] = u[k] * this.newton[st.group].scale[k]; });
          }
        }
        out.push({ X: X, failed: failed, Q: Q, cross: cross });
      }
      return out;
    }

    parallelAt(st, X, Q, cross) {
      // the first dyad of two slides solved by closed step `st` whose slides are parallel to
      // rounding (codegen.parallels: its joint at infinity): its group, else -1; each such
      // dyad's cross product recorded in `cross` (group -> value)
      let CX = null, SX = null, first = -1;
      for (const [g, , , ] of this.art.parallels || []) {
        const cols = this.art.groups.find((gr) => gr.index === g).cols;
        if (!cols.every((c) => st.x.includes(c))) continue;
        if (CX === null) {
          CX = X.map((v, c) => (v === null || !this.isAngle[c] ? null : Math.cos(v)));
          SX = X.map((v, c) => (v === null || !this.isAngle[c] ? null : Math.sin(v)));
        }
        const c = this.call("parallels_" + g, X, Q, null, CX, SX)[0];
        cross[g] = c;
        if (Math.abs(c) <= this.art.parallel_tol && first < 0) first = g;
      }
      return first;
    }

    passages(sol) {
      // the passages of the joints of dyads of two slides through infinity along a solved
      // path (codegen.parallels.two_slides' test, on this walk's own numbers): the cross
      // product of the slides changes sign between two consecutive path points where the
      // dyad is solved (its coordinates numbers, its slides not parallel); each as
      // {title, slides, joint, before, after (path point indices), at: after}, dyad by dyad
      // in the artifact's order, then along the path
      const out = [];
      for (const [g, a, b, joint] of this.art.parallels || []) {
        const group = this.art.groups.find((gr) => gr.index === g);
        let last = null, side = null;
        sol.forEach((s, i) => {
          const c = s.cross[g];
          const solved = Number.isFinite(c) && Math.abs(c) > this.art.parallel_tol &&
            group.cols.every((col) => Number.isFinite(s.X[col]));
          if (!solved) return;
          if (last !== null && (c > 0) !== side)
            out.push({ title: group.label + " (" + group.links.join(", ") + ")", slides: [a, b],
              joint: joint, before: last, after: i });
          last = i; side = c > 0;
        });
      }
      return out;
    }

    newtonAt(pb, w, i, ctx) {
      // one path point of one Newton group (continuation.Walk.step, simpler at re-entry)
      const uAsm = pb.step.x.map((c, k) => this.x0[c] / pb.scale[k]);
      if (w.sign === null) w.sign = Math.sign(det(pb.evaluate(uAsm, ctx).J));
      let u = null, ok = false;
      if (i === 0) {
        const got = newton(pb, uAsm.slice(), ctx);
        ok = got.res <= CONST.TOL && Math.sign(det(got.J)) === w.sign;
        u = got.u;
      } else if (w.last !== null && w.last.i === i - 1) {
        const got = continueTo(pb, w.last.u, w.last.ctx, ctx, w.sign, w.before);
        ok = got.t === null;
        u = got.u;
        w.stop = ok ? null : got.u;
      }
      let jumped = false;
      if (!ok) {
        // no continuous path from the last solved point (a gap, or a limit or singular
        // position passed): the roots near the known configurations, in the assembly's
        // determinant sign, the nearest taken (continuation.Walk.search_from, roots_near)
        const ref = w.stop !== null ? w.stop : (w.last !== null ? w.last.u : uAsm);
        const others = (w.last !== null ? [w.last.u] : []).concat([uAsm]);
        const same = rootsNear(pb, ctx, ref, others, w.sign);
        if (same.length) {
          u = same[0]; ok = true; jumped = true;
        }
      }
      if (!ok) {
        w.before = null;
        return null;
      }
      const continued = i > 0 && w.last !== null && w.last.i === i - 1 && !jumped;
      w.before = continued ? w.last.u : null;
      w.last = { i: i, u: u, ctx: ctx };
      return u;
    }

    // -- statuses and points ----------------------------------------------------------------
    status(X, Q, CX, SX) {
      // ok or singular (the runtime's screen: a group block's Hadamard ratio below SCREEN,
      // then the dimensionless A's condition number against SINGULAR_COND)
      const art = this.art, m = this.m;
      if (!CX) { CX = X.map(Math.cos); SX = X.map(Math.sin); }
      const out = this.f.rates(X, null, null, Q, this.qzeros, null, null, this.P, CX, SX);
      if (this.screenBlocks === undefined) {
        // each group block of more than one row: its entries of A as (row, column, index)
        this.screenBlocks = [];
        for (const g of art.groups) {
          const r0 = g.rows[0], r1 = g.rows[1], c0 = g.cols[0], c1 = g.cols[g.cols.length - 1] + 1;
          if (r1 - r0 === 1) continue;
          const entries = [];
          art.pattern.forEach(([i, j], k) => {
            if (i >= r0 && i < r1 && j >= c0 && j < c1) entries.push([i - r0, j - c0, k]);
          });
          this.screenBlocks.push({ n: r1 - r0, entries: entries });
        }
      }
      let screened = false;
      for (const blk of this.screenBlocks) {
        const n = blk.n, B = [];
        for (let i = 0; i < n; i++) B.push(new Array(n).fill(0.0));
        for (const [i, j, k] of blk.entries) B[i][j] = out[k];
        const d = Math.abs(n === 2 ? B[0][0] * B[1][1] - B[0][1] * B[1][0] : det(B));
        let rows = 1.0, cols = 1.0;
        for (let i = 0; i < n; i++) {
          let sr = 0, sc = 0;
          for (let j = 0; j < n; j++) { sr += B[i][j] * B[i][j]; sc += B[j][i] * B[j][i]; }
          rows *= sr; cols *= sc;
        }
        const ratio = d / Math.sqrt(Math.max(rows, cols));
        if (!(ratio >= CONST.SCREEN)) screened = true;
      }
      if (!screened) return { status: "ok", condition: null };
      const A = [];
      for (let i = 0; i < m; i++) A.push(new Array(m).fill(0.0));
      art.pattern.forEach(([i, j], k) => { A[i][j] = out[k]; });
      const As = A.map((row, i) => row.map((v, j) =>
        v * (art.rows_length[i] ? 1.0 / this.L : 1.0) * (art.cols_length[j] ? this.L : 1.0)));
      let cond = Infinity;
      if (As.every((row) => row.every(Number.isFinite))) {
        const sv = singularValues(As);
        cond = sv[0] / sv[sv.length - 1];
      }
      return { status: cond <= CONST.SINGULAR_COND ? "ok" : "singular", condition: cond };
    }

    points(X, Q, CX, SX) {
      // {joints: {name: [x, y]}, points: {name: [x, y]}} from the points function (level 0;
      // position_points, its first rows, where the artifact has it)
      const art = this.art, model = this.model;
      if (!CX) { CX = X.map(Math.cos); SX = X.map(Math.sin); }
      const out = this.call(this.f.position_points ? "position_points" : "points", X, Q, null, CX, SX);
      const rows = (key) => out.slice(art.layout[key][0], art.layout[key][1]);
      const joints = {};
      for (const n of model.order) joints[n] = rows("joint:" + n + ":0");
      const points = {};
      for (const pt of model.points) {
        // the link's frame carried to the global origin, then the point rigid with it
        // (codegen.evaluator.frame_motion and rigid_point, level 0)
        const c = this.angleOf[pt.link], fr = this.geometry.frames[pt.link];
        const ct = Math.cos(fr.theta0), st = Math.sin(fr.theta0);
        const cr = CX[c] * ct + SX[c] * st, sr = SX[c] * ct - CX[c] * st;
        const o = rows("origin:" + pt.link + ":0");
        const dx = -(cr * fr.origin[0] - sr * fr.origin[1]), dy = -(sr * fr.origin[0] + cr * fr.origin[1]);
        const rx = cr * pt.at[0] - sr * pt.at[1], ry = sr * pt.at[0] + cr * pt.at[1];
        points[pt.name] = [o[0] + dx + rx, o[1] + dy + ry];
      }
      return { joints: joints, points: points };
    }

    pathTo(Qsteps) {
      // the solving path from the assembly configuration through the steps (numeric.engine.
      // sweep.solving_path): point 0 the assembly, at most `lim` per driver between points;
      // returns the path and each step's index on it.  As there, every interval between two
      // steps is cut into as many points as the widest one needs (the points the Python run
      // walks, so that a warning names the same driver values)
      const D = this.q0.length;
      const path = [];
      const at = [];
      const points = (a, b) => {
        let n = 1;
        for (let d = 0; d < D; d++) n = Math.max(n, Math.ceil(Math.abs(b[d] - a[d]) / this.lim[d]));
        return n;
      };
      let nRef = 1;
      for (let s = 1; s < Qsteps.length; s++) nRef = Math.max(nRef, points(Qsteps[s - 1], Qsteps[s]));
      let prev = this.q0;
      path.push(this.q0.slice());
      Qsteps.forEach((Q, s) => {
        const n = s === 0 ? points(prev, Q) : nRef;
        for (let k = 1; k < n; k++) path.push(prev.map((v, d) => v + (Q[d] - v) * (k / n)));
        path.push(Q.slice());
        at.push(path.length - 1);
        prev = Q;
      });
      return { path: path, at: at };
    }

    solveSteps(Qsteps) {
      // every step: {status, message, joints, points, X, Q}
      return this.sweep(Qsteps).steps;
    }

    sweep(Qsteps) {
      // the steps (solveSteps), the solving path (driver values at each point), each step's
      // point on it, and the passages through infinity along it (passages)
      const { path, at } = this.pathTo(Qsteps);
      const sol = this.solvePath(path);
      const steps = at.map((k) => {
        const s = sol[k];
        if (s.failed >= 0) {
          const g = this.art.groups.find((gr) => gr.index === s.failed);
          // worded as the NumPy runtime words it (the continuation's reasons are not kept); a
          // dyad of two slides that are parallel at this point says so (codegen.parallels)
          const title = g.label + " (" + g.links.join(", ") + ")";
          const par = (this.art.parallels || []).find(([pg]) => pg === s.failed);
          const c = par ? s.cross[s.failed] : NaN;
          const message = par && Math.abs(c) <= this.art.parallel_tol ?
            title + ": the slides of joints " + par[1] + " and " + par[2] + " are parallel" :
            title + " cannot be assembled" + (g.closed ? ": its closed form has no real solution" :
              ": no configuration in the assembly mode is reached continuously");
          return { status: "unassemblable", message: message,
            joints: {}, points: {}, X: s.X, Q: s.Q };
        }
        const CX = s.X.map(Math.cos), SX = s.X.map(Math.sin);
        const st = this.status(s.X, s.Q, CX, SX);
        const pts = this.points(s.X, s.Q, CX, SX);
        return { status: st.status, message: st.status === "singular" ?
          "singular position: condition number " + st.condition.toPrecision(3) : null,
          joints: pts.joints, points: pts.points, X: s.X, Q: s.Q };
      });
      return { steps: steps, path: path, at: at, passages: this.passages(sol) };
    }
  }

  function newton(pb, u, ctx) {
    // damped Newton with polishing (continuation.roots.newton)
    let { r, J } = pb.evaluate(u, ctx);
    let res = norm(r);
    const history = [];
    let polished = 0, last = Infinity;
    for (let it = 0; it < CONST.MAX_ITER; it++) {
      history.push(res);
      if (it >= CONST.STALL_ITER && res > CONST.TOL && res > 0.5 * history[history.length - CONST.STALL_ITER]) break;
      if (res <= CONST.TOL) {
        if (polished && (last <= CONST.POLISH_FLOOR || polished >= CONST.MAX_POLISH)) break;
        polished += 1;
      }
      const d = luSolve(J, r).x;
      if (d === null || !d.every(Number.isFinite)) return { u: u, res: Infinity, J: J };
      let step = 1.0, un, got, resn;
      for (;;) {
        un = u.map((v, k) => v - step * d[k]);
        got = pb.evaluate(un, ctx);
        resn = norm(got.r);
        if (resn < res || res <= CONST.TOL || step < 1e-4) break;
        step *= 0.5;
      }
      if (res <= CONST.TOL && !(resn <= res)) break;
      if (res <= CONST.TOL) last = Math.max(...d.map(Math.abs));
      u = un; r = got.r; J = got.J; res = resn;
    }
    return { u: u, res: res, J: J };
  }

  // -- the re-entry search (continuation.roots: roots_near and its pieces) ---------------
  function turnedSeeds(u, angles) {
    // u with its angles turned by fixed offsets over the circle (a golden-ratio sequence)
    const phi = (Math.sqrt(5.0) - 1) / 2;
    const idx = [];
    angles.forEach((a, i) => { if (a) idx.push(i); });
    const out = [];
    for (let m = 1; m <= CONST.TURNED_SEEDS; m++) {
      const v = u.slice();
      idx.forEach((i, k) => {
        const f = (m * phi * (1 + k) + 0.5 * k) % 1.0;
        v[i] += 2 * Math.PI * (f - 0.5);
      });
      out.push(v);
    }
    return out;
  }

  function project(pb, u, ctx) {
    // u with its lengths fitted to its angles (least squares: the normal equations)
    const lin = [];
    pb.angles.forEach((a, i) => { if (!a) lin.push(i); });
    if (!lin.length) return u;
    const { r, J } = pb.evaluate(u, ctx);
    const N = lin.map((a) => lin.map((b) => J.reduce((s, row) => s + row[a] * row[b], 0)));
    const g = lin.map((a) => -J.reduce((s, row, i) => s + row[a] * r[i], 0));
    const d = luSolve(N, g).x;
    if (d === null || !d.every(Number.isFinite)) return u;
    const v = u.slice();
    lin.forEach((i, k) => { v[i] += d[k]; });
    return v;
  }

  function searchNewton(pb, u, ctx) {
    // undamped Newton with steps bounded to SEARCH_STEP from one seed; the root or null
    let res0 = null;
    for (let it = 0; it < CONST.SEARCH_ITER; it++) {
      const { r, J } = pb.evaluate(u, ctx);
      const res = norm(r);
      if (res0 === null) res0 = Math.max(res, 1.0);
      if (res <= CONST.TOL) return u;
      if (!Number.isFinite(res) || res > 1e6 * res0 || !J.every((row) => row.every(Number.isFinite))) return null;
      const sol = luSolve(J, r);
      if (sol.x === null || !Number.isFinite(sol.det) || sol.det === 0) return null;
      const length = Math.max(...sol.x.map(Math.abs));
      const scale = length > CONST.SEARCH_STEP ? CONST.SEARCH_STEP / length : 1.0;
      u = u.map((v, k) => v - scale * sol.x[k]);
    }
    return null;
  }

  function nearestTurns(u, ref, angles) {
    return u.map((v, i) => (angles[i] ? v - TWO_PI * Math.round((v - ref[i]) / TWO_PI) : v));
  }

  function rootsNear(pb, ctx, ref, others, sign) {
    // the roots of the assembly's sign found from seeds around ref, nearest first
    const seeds = [ref].concat(others, turnedSeeds(ref, pb.angles)).map((v) => project(pb, v, ctx));
    const found = [];
    for (const seed of seeds) {
      const hit = searchNewton(pb, seed.slice(), ctx);
      if (hit === null) continue;
      const got = newton(pb, hit, ctx); // polish
      if (!(got.res <= CONST.TOL)) continue;
      const u = nearestTurns(got.u, ref, pb.angles);
      if (!found.some((z) => maxAbsDiff(u, z.u) <= CONST.SAME_ROOT)) found.push({ u: u, J: got.J });
    }
    const angleDistance = (u) => u.reduce((m, v, i) => (pb.angles[i] ? Math.max(m, Math.abs(v - ref[i])) : m), 0);
    const key = (u) => [Math.round(angleDistance(u) * 1e9) / 1e9, maxAbsDiff(u, ref)];
    found.sort((a, b) => {
      const ka = key(a.u), kb = key(b.u);
      return ka[0] - kb[0] || ka[1] - kb[1];
    });
    return found.filter((f) => Math.sign(det(f.J)) === sign).map((f) => f.u);
  }

  function accept(got, sign, seed) {
    return got.res <= CONST.TOL && Math.sign(det(got.J)) === sign &&
      maxAbsDiff(got.u, seed) <= CONST.MAX_CORRECTION;
  }

  function continueTo(pb, u0, a, b, sign, before) {
    // continuation of the root u0 at inputs a to inputs b (continuation.roots.continue_to)
    let seed = before === null ? u0 : u0.map((v, k) => 2 * v - before[k]);
    let got = newton(pb, seed.slice(), b);
    if (accept(got, sign, seed)) return { u: got.u, t: null };
    let t = 0.0, dt = 0.5, u = u0, slope = null;
    while (t < 1.0) {
      const t1 = Math.min(1.0, t + dt);
      seed = slope === null ? u : u.map((v, k) => v + slope[k] * (t1 - t));
      const ctx = t1 === 1.0 ? b : pb.blend(a, b, t1);
      got = newton(pb, seed.slice(), ctx);
      if (accept(got, sign, seed)) {
        slope = got.u.map((v, k) => (v - u[k]) / (t1 - t));
        u = got.u; t = t1;
        dt = Math.min(2 * dt, 0.5);
        continue;
      }
      dt *= 0.5;
      if (dt < CONST.MIN_FRACTION) return { u: u, t: t };
    }
    return { u: u, t: null };
  }

  return { Mechanism: Mechanism, SceneError: SceneError, Geometry: Geometry, singularValues: singularValues };
})();
