// The JavaScript backend's rate problems, points by level and forces (after evaluator.js).
//
// The hooks of linkage_sym/codegen/evaluator.py's Evaluator for one step at a time, added
// to LinkageEvaluator.Mechanism: the generated `rates` (A's non-zero entries, then B qd)
// solved group block by group block (`rateSystem`, `blockSolve`: a group's block by
// Gaussian elimination with partial pivoting, the coupling to earlier groups subtracted, as
// codegen/blocks.py's BlockSystem; it uses Cramer's rule up to 3x3, the same solution to
// rounding); `A xdd = rhs` with the generated `accelerations`; the generated `points` at
// levels 0, 1, 2 (joints, frame origins) with a link's frame carried to the global origin
// and the traced points rigid with it (`frameMotion`, `rigidPoint`: evaluator.py's
// frame_motion and rigid_point); the loads over the cycle (`loadFactor`: numeric/forces/
// loads.py's load_factor, NumPy's periodic interp); the force blocks A_g F_g = b_g - C_g
// F_later from the last group back (`solveForces`), a gear mesh's flank turned where its
// tooth load pulls (runtime.py's _forces), and the reactions and efforts by joint type
// (`reactions`).
"use strict";

(function (E) {
  const M = E.Mechanism.prototype;

  function luSolve(A, b) {
    // A x = b (A a list of rows) by Gaussian elimination with partial pivoting; NaN where
    // A is singular
    const n = b.length;
    const U = A.map((row) => row.slice());
    const y = b.slice();
    for (let k = 0; k < n; k++) {
      let p = k;
      for (let i = k + 1; i < n; i++) if (Math.abs(U[i][k]) > Math.abs(U[p][k])) p = i;
      if (p !== k) { [U[p], U[k]] = [U[k], U[p]]; [y[p], y[k]] = [y[k], y[p]]; }
      const piv = U[k][k];
      for (let i = k + 1; i < n; i++) {
        const f = U[i][k] / piv;
        if (f === 0) continue;
        for (let j = k; j < n; j++) U[i][j] -= f * U[k][j];
        y[i] -= f * y[k];
      }
    }
    const x = new Array(n);
    for (let i = n - 1; i >= 0; i--) {
      let s = y[i];
      for (let j = i + 1; j < n; j++) s -= U[i][j] * x[j];
      x[i] = s / U[i][i];
    }
    return x;
  }

  M.rateSystem = function (X, Q, QD, CX, SX) {
    // A (dense rows) and B qd from the generated `rates` (Evaluator.rate_entries)
    const art = this.art, m = this.m;
    const out = this.f.rates(X, null, null, Q, QD, null, null, this.P, CX, SX);
    const A = [];
    for (let i = 0; i < m; i++) A.push(new Array(m).fill(0.0));
    art.pattern.forEach(([i, j], k) => { A[i][j] = out[k]; });
    return { A: A, Bqd: out.slice(art.pattern.length) };
  };

  M.blockSolve = function (A, rhs) {
    // A x = rhs, A block lower-triangular: group by group in solving order
    const x = new Array(this.m).fill(0.0);
    for (const g of this.art.groups) {
      const r0 = g.rows[0], r1 = g.rows[1], c0 = g.cols[0], c1 = g.cols[g.cols.length - 1] + 1;
      const B = [], b = [];
      for (let i = r0; i < r1; i++) {
        let s = rhs[i];
        for (let j = 0; j < c0; j++) if (A[i][j] !== 0) s -= A[i][j] * x[j];
        B.push(A[i].slice(c0, c1));
        b.push(s);
      }
      luSolve(B, b).forEach((v, k) => { x[c0 + k] = v; });
    }
    return x;
  };

  M.loadFactor = function (load, Q) {
    // the factor of a load's force and torque at the driver values Q (1 where it does not
    // vary over the cycle): load_factor
    if (load.driver === null) return 1.0;
    const x = Q[this.art.q.indexOf(load.driver)];
    let f = 1.0;
    if (load.table !== null) f = interp(x, load.table[0], load.table[1], load.period);
    if (load.active !== null) {
      const lo = load.active[0], hi = load.active[1];
      let inside;
      if (load.period !== null) {
        // ends included, up to rounding (loads.ACTIVE_END)
        const tol = CONST.ACTIVE_END * load.period;
        let r = (x - lo) % load.period;
        if (r < 0) r += load.period;
        inside = r <= hi - lo + tol || r >= load.period - tol;
      } else {
        const tol = CONST.ACTIVE_END * Math.max(Math.abs(lo), Math.abs(hi), hi - lo);
        inside = x >= lo - tol && x <= hi + tol;
      }
      if (!inside) f = 0.0;
    }
    return f;
  };

  function interp(x, xp, fp, period) {
    // NumPy's interp (with `period`: the abscissae taken modulo it and the table closed)
    if (period !== null) {
      const mod = (v) => { const r = v % period; return r < 0 ? r + period : r; };
      x = mod(x);
      const order = xp.map((v, i) => [mod(v), fp[i], i]).sort((a, b) => a[0] - b[0] || a[2] - b[2]);
      const last = order[order.length - 1], first = order[0];
      xp = [last[0] - period].concat(order.map((r) => r[0]), [first[0] + period]);
      fp = [last[1]].concat(order.map((r) => r[1]), [first[1]]);
    }
    const n = xp.length;
    if (x <= xp[0]) return fp[0];
    if (x >= xp[n - 1]) return fp[n - 1];
    let lo = 0, hi = n - 1; // xp[lo] <= x < xp[hi]
    while (hi - lo > 1) {
      const mid = (lo + hi) >> 1;
      if (xp[mid] <= x) lo = mid; else hi = mid;
    }
    if (x === xp[lo]) return fp[lo];
    const slope = (fp[lo + 1] - fp[lo]) / (xp[lo + 1] - xp[lo]);
    return slope * (x - xp[lo]) + fp[lo];
  }

  M.loadParameters = function (Q, flanks) {
    // P with the loads over the cycle scaled (Evaluator.scaled_loads) and the meshes'
    // flank signs (Evaluator.with_flanks)
    const P = this.P.slice();
    const entries = this.art.load_entries;
    this.model.loads.forEach((ld, i) => {
      if (ld.driver === null || !(String(i) in entries)) return;
      const k = this.loadFactor(ld, Q);
      for (const j of entries[String(i)]) P[j] = P[j] * k;
    });
    if (flanks) {
      const at = this.art.params.length + this.art.sigmas;
      flanks.forEach((s, i) => { P[at + i] = s; });
    }
    return P;
  };

  M.motion = function (X, Q, QD, QDD) {
    // the rates of one solved step: XD, XDD (A xd = B qd, A xdd = rhs) and the generated
    // points at every level with the loads' parameters ({XD, XDD, CX, SX, P, pts})
    const CX = X.map(Math.cos), SX = X.map(Math.sin);
    const { A, Bqd } = this.rateSystem(X, Q, QD, CX, SX);
    const XD = this.blockSolve(A, Bqd);
    let XDD = null;
    if (this.f.accelerations) {
      const rhs = this.f.accelerations(X, XD, null, Q, QD, QDD, null, this.P, CX, SX);
      XDD = this.blockSolve(A, rhs);
    }
    const P = this.loadParameters(Q, null);
    const pts = this.f.points(X, XD, XDD, Q, QD, QDD, null, P, CX, SX);
    return { X: X, XD: XD, XDD: XDD, CX: CX, SX: SX, P: P, Q: Q, QD: QD, QDD: QDD, pts: pts };
  };

  M.rows = function (pts, key) {
    const r = this.art.layout[key];
    return pts.slice(r[0], r[1]);
  };

  M.frameMotion = function (link, st) {
    // the link's frame carried to the global origin: [cr, sr, ox, oy, w, vx, vy, al, ax, ay]
    // (frame_motion; the levels the artifact has)
    const c = this.angleOf[link], fr = this.geometry.frames[link];
    const ct = Math.cos(fr.theta0), s0 = Math.sin(fr.theta0);
    const cr = st.CX[c] * ct + st.SX[c] * s0, sr = st.SX[c] * ct - st.CX[c] * s0;
    const Ux = fr.origin[0], Uy = fr.origin[1];
    const dx = -(cr * Ux - sr * Uy), dy = -(sr * Ux + cr * Uy);
    const o = this.rows(st.pts, "origin:" + link + ":0");
    const m = [cr, sr, o[0] + dx, o[1] + dy];
    if (st.XD !== null && this.art.layout["origin:" + link + ":1"]) {
      const w = st.XD[c], v = this.rows(st.pts, "origin:" + link + ":1");
      m.push(w, v[0] - w * dy, v[1] + w * dx);
      if (st.XDD !== null && this.art.layout["origin:" + link + ":2"]) {
        const al = st.XDD[c], a = this.rows(st.pts, "origin:" + link + ":2");
        m.push(al, a[0] - al * dy - w * w * dx, a[1] + al * dx - w * w * dy);
      }
    }
    return m;
  };

  function rigidPoint(m, at) {
    // a point fixed to a link: [position, velocity, acceleration] (rigid_point)
    const cr = m[0], sr = m[1];
    const rx = cr * at[0] - sr * at[1], ry = sr * at[0] + cr * at[1];
    const out = [[m[2] + rx, m[3] + ry]];
    if (m.length > 4) {
      const w = m[4];
      out.push([m[5] - w * ry, m[6] + w * rx]);
      if (m.length > 7) {
        const al = m[7];
        out.push([m[8] - al * ry - w * w * rx, m[9] + al * rx - w * w * ry]);
      }
    }
    return out;
  }
  E.rigidPoint = rigidPoint;

  M.kinematics = function (st) {
    // {joints: {name: [p, v, a]}, points: {name: [p, v, a]}} of one step's motion
    const joints = {}, points = {};
    const levels = [0, 1, 2].filter((l) => this.art.layout["joint:" + this.model.order[0] + ":" + l]);
    for (const n of this.model.order) joints[n] = levels.map((l) => this.rows(st.pts, "joint:" + n + ":" + l));
    for (const pt of this.model.points) points[pt.name] = rigidPoint(this.frameMotion(pt.link, st), pt.at);
    return { joints: joints, points: points };
  };

  M.solveForces = function (pts) {
    // reactions and efforts (a list over the force names): each group's block from the
    // last group back, b_g - C_g F_later with the later groups' forces (solve_forces)
    const art = this.art;
    const F = new Array(art.force_names.length).fill(0.0);
    for (let gi = art.groups.length - 1; gi >= 0; gi--) {
      const k = art.groups[gi].index, blk = art.forces[gi];
      const Av = this.rows(pts, "A:" + k), b = this.rows(pts, "b:" + k);
      const Cv = this.rows(pts, "C:" + k);
      blk.C.forEach(([i, fi], c) => { b[i] = b[i] - Cv[c] * F[fi]; });
      const n = b.length;
      const A = [];
      for (let i = 0; i < n; i++) A.push(new Array(n).fill(0.0));
      blk.A.forEach(([i, j], c) => { A[i][j] = Av[c]; });
      luSolve(A, b).forEach((v, u) => { F[blk.unknowns[u]] = v; });
    }
    return F;
  };

  M.forces = function (st) {
    // the forces of one step, the meshes' flanks settled as runtime._forces settles them:
    // {F, pts} (null where the artifact has no forces stage)
    const art = this.art;
    if (!art.stages.includes("forces")) return null;
    const fidx = {};
    art.force_names.forEach((n, i) => { fidx[n] = i; });
    const flank = art.flanks.map(() => 1.0);
    let pts = st.pts, F = null;
    for (let it = 0; it < 1 + 2 * flank.length; it++) {
      F = this.solveForces(pts);
      let pulling = false;
      art.flanks.forEach((name, i) => {
        if (F[fidx["Fn_" + this.model.ident[name]]] < 0) { flank[i] = -flank[i]; pulling = true; }
      });
      if (!pulling) break;
      const P = this.loadParameters(st.Q, flank);
      pts = this.f.points(st.X, st.XD, st.XDD, st.Q, st.QD, st.QDD, null, P, st.CX, st.SX);
    }
    return { F: F, pts: pts, fidx: fidx };
  };

  M.reactions = function (st) {
    // {reactions: {joint: [fx, fy, moment]}, driving: {driver: effort}} (Evaluator.reactions):
    // the force of links[0] on links[1], a P joint's normal force and moment, a mesh's
    // tooth load on its line of action; null without a forces stage
    const got = this.forces(st);
    if (got === null) return null;
    const { F, pts, fidx } = got;
    const out = {};
    for (const n of this.model.order) {
      const j = this.model.joints[n], id = this.model.ident[n];
      if (j.type === "R") {
        out[n] = [F[fidx["R_" + id + "x"]], F[fidx["R_" + id + "y"]], 0.0];
      } else if (j.type === "G") {
        const u = this.rows(pts, "mesh:" + n), Fn = F[fidx["Fn_" + id]];
        out[n] = [u[0] * Fn, u[1] * Fn, 0.0];
      } else {
        const u = this.rows(pts, "slide:" + n), Nn = F[fidx["N_" + id]];
        out[n] = [-u[1] * Nn, u[0] * Nn, F[fidx["M_" + id]]];
      }
    }
    const driving = {};
    for (const d of this.model.drivers) driving[d.joint] = F[fidx[(d.kind === "R" ? "tau_" : "f_") + this.model.ident[d.joint]]];
    return { reactions: out, driving: driving };
  };
})(LinkageEvaluator);
