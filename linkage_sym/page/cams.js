// The page of a mechanism with cam contacts: a JavaScript port of the numeric layer's solvers
// of its groups (linkage_sym.page.cam_model says which) and the cam's drawing.
//
// The symbolic layer does not derive cam contacts, so such a page has no generated functions:
// it reads MODEL (linkage_sym.page.cam_model.cam_page_model) and solves, in the solving order
// of MODEL.groups, as the numeric layer does (numeric/kinematics/closed_form.py InputSolver,
// numeric/kinematics/cams.py CamSolver, cam_profile.py CamProfile):
// - an input link: its driver's value on its known link;
// - an RRR dyad: its closed form (two circles' intersection) on the assembly side;
// - a cam follower on its pivot or slide: one equation f(u) = 0 in the profile parameter u
//   (the roller centre or knife point at the arm's length from the pivot or on the slide's
//   line; a flat face's normal at the face's distance or along the slide), its up-crossings
//   bracketed on a grid of GRID intervals (the one nearest the previous path point's where
//   there are several) and bisected BISECTIONS times, the branch the sign of f' at the
//   assembly configuration; the steps it cannot reach or follow unassemblable with the
//   numeric layer's reasons;
// - the profile exactly as the numeric layer evaluates it: a circle, or SciPy's periodic
//   cubic splines (their breakpoints and coefficients are MODEL's data), evaluated as SciPy's
//   PPoly does;
// - the singularity screen: where the cosine of a contact's pressure angle is below SCREEN,
//   the dimensionless condition number of the constraint Jacobian (numeric/kinematics/
//   constraints.py rows of R and P joints, drivers and the contact's replacement row; the
//   evaluator's one-sided Jacobi SVD) against SINGULAR_COND.
// A drag re-solves with the profile fixed (it is data on the cam, in the scene's frame of the
// assembly configuration): a ground pivot moves (the cam then turns about another point of its
// profile, or the follower's pivot moves); the contact point does not.
const LinkageCams = (function () {
  "use strict";
  const E = LinkageEvaluator;
  const TWO_PI = 2 * Math.PI;
  const OUTLINE = 721; // plotting.cam_drawing.PROFILE_SAMPLES

  function mod2pi(u) {
    const t = u % TWO_PI;
    return t < 0 ? t + TWO_PI : t;
  }

  function ppoly(s, v, d) {
    // SciPy's PPoly at v (its derivative of order d): the interval x[i] <= v < x[i+1]
    // (extrapolated by the first and last pieces), the power sum in v - x[i]
    const x = s.x, c = s.c, n = x.length - 1, k = c.length;
    let i;
    if (!(v >= x[0])) i = 0;
    else if (v >= x[n]) i = n - 1;
    else {
      let lo = 0, hi = n;
      while (hi - lo > 1) {
        const mid = (lo + hi) >> 1;
        if (x[mid] <= v) lo = mid; else hi = mid;
      }
      i = lo;
    }
    const t = v - x[i];
    let res = 0.0, z = 1.0;
    for (let kp = 0; kp < k; kp++) {
      let pre = 1.0;
      for (let m = kp; m > kp - d; m--) pre *= m;
      res += c[k - kp - 1][i] * z * pre;
      if (kp < k - 1 && kp >= d) z *= t;
    }
    return res;
  }

  // -- a profile (numeric.kinematics.cam_profile.CamProfile) -------------------------------
  class Profile {
    constructor(d, grid) { this.d = d; this.grid = grid; }

    evaluate(u) {
      // [x, y, x', y', x'', y''] at u
      u = mod2pi(u);
      const d = this.d;
      if (d.kind === "circle") {
        const c = Math.cos(u), s = Math.sin(u), R = d.R;
        return [d.centre[0] + R * c, d.centre[1] + R * s, -R * s, R * c, -R * c, -R * s];
      }
      if (d.kind === "polar") {
        const v = mod2pi(u - d.phi0);
        const r = ppoly(d.r, v, 0), r1 = ppoly(d.r, v, 1), r2 = ppoly(d.r, v, 2);
        const c = Math.cos(u), s = Math.sin(u);
        return [d.centre[0] + r * c, d.centre[1] + r * s, r1 * c - r * s, r1 * s + r * c,
          r2 * c - 2 * r1 * s - r * c, r2 * s + 2 * r1 * c - r * s];
      }
      return [ppoly(d.x, u, 0), ppoly(d.y, u, 0), ppoly(d.x, u, 1), ppoly(d.y, u, 1),
        ppoly(d.x, u, 2), ppoly(d.y, u, 2)];
    }

    frame(u) {
      // point, unit tangent, outward unit normal, curvature
      const [x, y, x1, y1, x2, y2] = this.evaluate(u);
      const speed = Math.hypot(x1, y1);
      const tx = x1 / speed, ty = y1 / speed;
      return { x: x, y: y, tx: tx, ty: ty, nx: ty, ny: -tx, kappa: (x1 * y2 - y1 * x2) / speed ** 3 };
    }

    gridPoints() {
      if (!this._grid) {
        this._grid = [];
        for (let k = 0; k < this.grid; k++) {
          const u = k * (TWO_PI / this.grid);
          const e = this.evaluate(u);
          this._grid.push([u, e[0], e[1]]);
        }
      }
      return this._grid;
    }

    nearest(px, py) {
      // the parameter of the profile point nearest (px, py): the grid, then Newton
      let best = Infinity, u = 0.0;
      for (const [g, x, y] of this.gridPoints()) {
        const d2 = (x - px) ** 2 + (y - py) ** 2;
        if (d2 < best) { best = d2; u = g; }
      }
      const step = TWO_PI / this.grid;
      for (let it = 0; it < 30; it++) {
        const [x, y, x1, y1, x2, y2] = this.evaluate(u);
        const g = (x - px) * x1 + (y - py) * y1;
        const dg = x1 * x1 + y1 * y1 + (x - px) * x2 + (y - py) * y2;
        const du = Math.min(step, Math.max(-step, dg > 0 ? -g / dg : 0.0));
        u += du;
        if (Math.abs(du) <= 1e-15 * TWO_PI) break;
      }
      return mod2pi(u);
    }

    support(mx, my) {
      // the parameter of the point of a convex profile farthest in the direction (mx, my)
      let best = -Infinity, u = 0.0;
      for (const [g, x, y] of this.gridPoints()) {
        const h = x * mx + y * my;
        if (h > best) { best = h; u = g; }
      }
      const step = TWO_PI / this.grid;
      for (let it = 0; it < 30; it++) {
        const e = this.evaluate(u);
        const g = mx * e[2] + my * e[3];
        const dg = mx * e[4] + my * e[5];
        const du = Math.min(step, Math.max(-step, dg < 0 ? -g / dg : 0.0));
        u += du;
        if (Math.abs(du) <= 1e-15 * TWO_PI) break;
      }
      return mod2pi(u);
    }
  }

  // -- link states: global = R(th) X + d, X in the assembly configuration -----------------
  function pose(th, dx, dy, c, s) {
    return { th: th, c: c === undefined ? Math.cos(th) : c, s: s === undefined ? Math.sin(th) : s, dx: dx, dy: dy };
  }
  const still = () => pose(0.0, 0.0, 0.0, 1.0, 0.0);
  const rot = (st, X) => [st.c * X[0] - st.s * X[1], st.s * X[0] + st.c * X[1]];
  const rotInv = (st, v) => [st.c * v[0] + st.s * v[1], -st.s * v[0] + st.c * v[1]];
  const point = (st, X) => { const r = rot(st, X); return [st.dx + r[0], st.dy + r[1]]; };
  const toLocal = (st, p) => rotInv(st, [p[0] - st.dx, p[1] - st.dy]);

  // -- a cam follower (numeric.kinematics.cams.CamSolver) -------------------------------------
  class CamGroup {
    constructor(mech, g) {
      const model = mech.model;
      this.g = g;
      this.L = mech.L;
      this.K = mech.constants;
      this.geo = model.cams[g.joint];
      this.profile = mech.profiles[g.joint];
      this.pivot = model.joints[g.pivot];
      this.P0 = model.joints[g.joint].at;
      this.Y = this.pivot.at;
      this.flat = this.geo.kind === "flat";
      this.case = (this.flat ? "flat" : "point") + "-" + this.pivot.type;
      if (this.pivot.type === "P") {
        this.a0 = [Math.cos(this.pivot.axis), Math.sin(this.pivot.axis)];
        const m = this.geo.m0;
        if (this.flat && Math.abs(m[0] * this.a0[0] + m[1] * this.a0[1]) < 1e-9)
          throw new E.SceneError("joints: the flat face of cam contact '" + g.joint + "' is parallel to " +
            "the slide of joint '" + g.pivot + "': the cam cannot move the follower along it");
      } else {
        this.l = Math.hypot(this.P0[0] - this.Y[0], this.P0[1] - this.Y[1]);
        if (this.l === 0.0 && !this.flat)
          throw new E.SceneError("joints: the follower's point of cam contact '" + g.joint +
            "' is on its pivot '" + g.pivot + "': the cam cannot turn it");
        if (this.flat) {
          const m = this.geo.m0;
          this.d = m[0] * (this.P0[0] - this.Y[0]) + m[1] * (this.P0[1] - this.Y[1]);
        }
      }
      this.sigma = this.assemblySign();
    }

    params(S) {
      const c = S[this.geo.cam], k = S[this.g.known];
      const Y = point(k, this.Y);
      const p = { Y: Y };
      if (this.pivot.type === "R") p.Yc = toLocal(c, Y);
      else {
        p.a = rot(k, this.a0);
        p.ac = rotInv(c, p.a);
        p.b = point(k, this.P0); // the element point with the slide at zero
        p.bc = toLocal(c, p.b);
        if (this.flat) p.mc = rotInv(c, rot(k, this.geo.m0));
      }
      return p;
    }

    f(u, p) {
      const fr = this.profile.frame(u), rho = this.geo.rho;
      if (this.case === "point-R") {
        const qx = fr.x + rho * fr.nx - p.Yc[0], qy = fr.y + rho * fr.ny - p.Yc[1];
        return (qx * qx + qy * qy - this.l ** 2) / this.L;
      }
      if (this.case === "point-P")
        return p.ac[0] * (fr.y + rho * fr.ny - p.bc[1]) - p.ac[1] * (fr.x + rho * fr.nx - p.bc[0]);
      if (this.case === "flat-R")
        return (fr.nx * (fr.x - p.Yc[0]) + fr.ny * (fr.y - p.Yc[1]) - this.d) / this.L;
      return fr.nx * p.mc[1] - fr.ny * p.mc[0];
    }

    assemblySign() {
      const S = {};
      S[this.g.known] = still(); S[this.geo.cam] = still();
      const p = this.params(S);
      this.u0 = this.flat ? this.profile.support(this.geo.m0[0], this.geo.m0[1])
        : this.profile.nearest(this.P0[0], this.P0[1]);
      const h = 1e-6;
      const s = Math.sign(this.f(this.u0 + h, p) - this.f(this.u0 - h, p));
      if (!s)
        throw new E.SceneError("joints: cam contact '" + this.g.joint + "' is singular in the assembly " +
          "configuration (the follower's path is tangent to the profile there): its branch is undefined");
      return s;
    }

    position(S, walk) {
      // the follower's pose at one path point; its failure reason (0: none) and indicator
      const p = this.params(S), K = this.K, n = K.GRID;
      const h = TWO_PI / n;
      const F = [];
      for (let k = 0; k <= n; k++) F.push(this.sigma * this.f(k === n ? TWO_PI : k * h, p));
      const ups = [];
      for (let k = 0; k < n; k++) if (F[k] <= 0 && F[k + 1] > 0) ups.push(k);
      let lo = ups.length ? ups[0] * h : 0.0, hi = ups.length ? (ups[0] + 1) * h : h;
      if (ups.length > 1) { // several contacts: the one nearest the previous path point's
        const prev = walk.lo === null ? this.u0 : walk.lo;
        let best = Infinity;
        for (const k of ups) {
          const x = k * h - prev;
          const dist = Math.abs(Math.atan2(Math.sin(x), Math.cos(x)));
          if (dist < best) { best = dist; lo = k * h; }
        }
        hi = lo + h;
      }
      walk.lo = lo;
      for (let it = 0; it < K.BISECTIONS; it++) {
        const mid = 0.5 * (lo + hi);
        if (this.sigma * this.f(mid, p) > 0) hi = mid; else lo = mid;
      }
      const u = 0.5 * (lo + hi);
      const fr = this.profile.frame(u), rho = this.geo.rho, c = S[this.geo.cam], k = S[this.g.known];
      let th, s = 0.0;
      if (this.case === "point-R") {
        const q = point(c, [fr.x + rho * fr.nx, fr.y + rho * fr.ny]);
        th = Math.atan2(q[1] - p.Y[1], q[0] - p.Y[0]) -
          Math.atan2(this.P0[1] - this.Y[1], this.P0[0] - this.Y[0]);
      } else if (this.case === "flat-R") {
        const m = rot(c, [fr.nx, fr.ny]);
        th = Math.atan2(m[1], m[0]) - Math.atan2(this.geo.m0[1], this.geo.m0[0]);
      } else {
        th = k.th;
        if (this.case === "point-P")
          s = p.ac[0] * (fr.x + rho * fr.nx - p.bc[0]) + p.ac[1] * (fr.y + rho * fr.ny - p.bc[1]);
        else
          s = (p.mc[0] * (fr.x - p.bc[0]) + p.mc[1] * (fr.y - p.bc[1])) /
            (p.mc[0] * p.ac[0] + p.mc[1] * p.ac[1]);
      }
      let why = ups.length ? 0 : 1;
      const found = ups.length > 0, kappa = fr.kappa;
      if (this.geo.kind === "roller" && !this.geo.pitch) {
        // the roller cannot reach a concave part tighter than itself (it rests on two)
        const qx = fr.x + rho * fr.nx, qy = fr.y + rho * fr.ny;
        const e = this.profile.evaluate(this.profile.nearest(qx, qy));
        const inside = Math.hypot(qx - e[0], qy - e[1]) < rho * (1.0 - 1e-9);
        if (found && ((kappa < 0 && 1 + rho * kappa <= 0) || inside)) why = 2;
      } else if (this.geo.kind === "roller") {
        if (found && kappa > 0 && this.geo.radius * kappa >= 1) why = 3;
      } else if (this.flat) {
        if (found && kappa * this.L < K.STRAIGHT) why = 4;
      }
      if (this.pivot.type === "R") {
        const st = pose(why === 0 ? th : NaN, 0.0, 0.0);
        const r = rot(st, this.Y);
        st.dx = p.Y[0] - r[0]; st.dy = p.Y[1] - r[1];
        S[this.g.link] = st;
      } else {
        s = why === 0 ? s : NaN;
        S[this.g.link] = pose(th + 0.0 * s, k.dx + s * p.a[0], k.dy + s * p.a[1]);
      }
      this.why = why; this.kappa = kappa;
      return why === 0 ? Math.abs(this.cosPressure(S)[0]) : NaN;
    }

    contact(S) {
      // the contact at the states S: parameter, point C, normal N, tangent, curvature, the
      // follower's element point P (the contact point for a flat face); global vectors
      const c = S[this.geo.cam], f = S[this.geo.follower];
      let u, P = null;
      if (this.flat) {
        const l = rotInv(c, rot(f, this.geo.m0));
        u = this.profile.support(l[0], l[1]);
      } else {
        P = point(f, this.P0);
        const l = toLocal(c, P);
        u = this.profile.nearest(l[0], l[1]);
      }
      const fr = this.profile.frame(u);
      const C = point(c, [fr.x, fr.y]);
      const N = rot(c, [fr.nx, fr.ny]);
      return { u: u, C: C, N: N, T: rot(c, [fr.tx, fr.ty]), kappa: fr.kappa, P: this.flat ? C : P };
    }

    cosPressure(S) {
      // cos and sin of the angle between the contact normal and the velocity direction of
      // the follower's element point in its own motion
      const ct = this.contact(S), k = S[this.g.known];
      let v;
      if (this.pivot.type === "P") v = rot(k, this.a0);
      else {
        const Y = point(k, this.Y);
        const dx = ct.P[0] - Y[0], dy = ct.P[1] - Y[1];
        const r = Math.hypot(dx, dy) || 1.0;
        v = [-dy / r, dx / r];
      }
      return [ct.N[0] * v[0] + ct.N[1] * v[1], ct.N[0] * v[1] - ct.N[1] * v[0]];
    }

    failure() {
      const name = this.g.joint, kappa = this.kappa, r = kappa ? Math.abs(1.0 / kappa) : Infinity;
      const g4 = (v) => Number(v.toPrecision(4)).toString();
      if (this.why === 2)
        return "cam contact " + name + ": the roller (radius " + this.geo.radius + " m) cannot reach the " +
          "profile's contact: a concave part of the profile is tighter than the roller there (radius of " +
          "curvature " + g4(r) + " m at the contact point, or the roller resting on two points of it): undercut";
      if (this.why === 3)
        return "cam contact " + name + ": the pitch curve's radius of curvature " + g4(r) + " m is smaller " +
          "than the roller's radius " + this.geo.radius + " m at the contact: the working profile is undercut there";
      if (this.why === 4)
        return "cam contact " + name + ": the profile is not convex at the contact (curvature " + g4(kappa) +
          " 1/m): a flat face cannot follow it there";
      return "cam contact " + name + ": the follower on '" + this.g.pivot + "' cannot reach the cam's profile " +
        "(no contact position on its branch)";
    }

    jac(S, link) {
      // the replacement's row (numeric.kinematics.cams.CamContact.jac)
      const ct = this.contact(S), st = S[link], N = ct.N;
      const straight = Math.abs(ct.kappa) * this.L < this.K.STRAIGHT;
      const rc = 1.0 / (straight ? 1.0 : ct.kappa);
      const Kc = [ct.C[0] - rc * N[0], ct.C[1] - rc * N[1]];
      const X = this.flat || link === this.geo.cam ? Kc : ct.P;
      const sign = (link === this.geo.follower) !== this.flat ? 1.0 : -1.0;
      const rx = X[0] - st.dx, ry = X[1] - st.dy;
      return [[sign * N[0], sign * N[1], sign * (-N[0] * ry + N[1] * rx)]];
    }
  }

  // -- an RRR dyad (numeric.kinematics.closed_form.DyadSolver, loci.circle_circle) ------------
  class DyadRRR {
    constructor(mech, g) {
      const at = (n) => mech.model.joints[n].at;
      this.g = g;
      [this.E0, this.J0, this.E1] = g.joints.map(at);
      const [E0, J0, E1] = [this.E0, this.J0, this.E1];
      this.r = [Math.hypot(J0[0] - E0[0], J0[1] - E0[1]), Math.hypot(J0[0] - E1[0], J0[1] - E1[1])];
      const cross = (E1[0] - E0[0]) * (J0[1] - E0[1]) - (E1[1] - E0[1]) * (J0[0] - E0[0]);
      if (Math.abs(cross) <= mech.constants.ASSEMBLY_TOL * ((E1[0] - E0[0]) ** 2 + (E1[1] - E0[1]) ** 2))
        throw new E.SceneError("joints: the assembly configuration is a singular position of the dyad RRR (" +
          g.links.join(", ") + "): its assembly mode is undefined; move the joints' `at` points off the " +
          "dead-centre position");
      this.sigma = cross > 0 ? 1.0 : -1.0;
    }

    position(S) {
      // the two circles' intersection on the assembly side (Heron's half-chord, a rounding-level
      // miss of a tangency taken as the tangency); the links' poses; the indicator
      const C0 = point(S[this.g.known[0]], this.E0), C1 = point(S[this.g.known[1]], this.E1);
      const [r1, r2] = this.r;
      let ex = C1[0] - C0[0], ey = C1[1] - C0[1];
      const d = Math.hypot(ex, ey);
      const f1 = r1 + r2 - d, f2 = d + r1 - r2, f3 = d - r1 + r2;
      let prod = f1 * f2 * f3 * (r1 + r2 + d);
      if (prod < 0) {
        const size = Math.max(Math.abs(r1), Math.abs(r2), ...C0.map(Math.abs), ...C1.map(Math.abs));
        prod = Math.min(f1, f2, f3) >= -CONST.TANGENT_ULPS * CONST.EPS * size ? 0.0 : NaN;
      }
      const h = Math.sqrt(prod) / (2.0 * d), a = (d * d + r1 * r1 - r2 * r2) / (2.0 * d);
      ex /= d; ey /= d;
      const Y = [C0[0] + a * ex - this.sigma * h * ey, C0[1] + a * ey + this.sigma * h * ex];
      [C0, C1].forEach((C, i) => {
        const v = [Y[0] - C[0], Y[1] - C[1]], E = i === 0 ? this.E0 : this.E1;
        const v0 = [this.J0[0] - E[0], this.J0[1] - E[1]];
        const cr = v0[0] * v[1] - v0[1] * v[0], dt = v0[0] * v[0] + v0[1] * v[1];
        const scale = 1.0 / (Math.hypot(v0[0], v0[1]) * Math.hypot(v[0], v[1]));
        const st = pose(Math.atan2(cr, dt), 0.0, 0.0, dt * scale, cr * scale);
        const rr = rot(st, this.J0);
        st.dx = Y[0] - rr[0]; st.dy = Y[1] - rr[1];
        S[this.g.links[i]] = st;
      });
      this.d = d;
      return Math.abs(h * d / (r1 * r2));
    }

    failure() {
      const [e0, , e1] = this.g.joints, [b0, b1] = this.g.links, [r0, r1] = this.r;
      const g6 = (v) => Number(v.toPrecision(6)).toString();
      return "dyad RRR (" + b0 + ", " + b1 + "): joints " + e0 + " and " + e1 + " are " + g6(this.d) +
        " m apart, outside the reach [" + g6(Math.abs(r0 - r1)) + ", " + g6(r0 + r1) + "] m of links " +
        b0 + " and " + b1;
    }
  }

  // -- the mechanism -------------------------------------------------------------------------
  class Mechanism {
    // what page.js reads of a mechanism: L, angleOf, geometry.frames, solveSteps
    constructor(model) {
      this.model = model;
      this.constants = model.cam_constants;
      const pts = model.order.map((n) => model.joints[n].at);
      let L = 0.0;
      for (let i = 0; i < pts.length; i++)
        for (let j = i + 1; j < pts.length; j++)
          L = Math.max(L, Math.hypot(pts[i][0] - pts[j][0], pts[i][1] - pts[j][1]));
      this.L = L || 1.0;
      this.links = Object.keys(model.links);
      this.angleOf = {};
      this.geometry = { frames: {} };
      this.links.forEach((n, i) => { this.angleOf[n] = i; this.geometry.frames[n] = { theta0: 0.0 }; });
      this.profiles = {};
      for (const [n, c] of Object.entries(model.cams)) this.profiles[n] = new Profile(c.profile, this.constants.GRID);
      this.q0 = model.drivers.map((d) => {
        if (d.kind !== "R") return 0.0;
        const j = model.joints[d.joint].at, t = model.joints[d.toward].at;
        const phi = Math.atan2(t[1] - j[1], t[0] - j[0]);
        return phi + TWO_PI * Math.round((d.start - phi) / TWO_PI);
      });
      this.lim = model.drivers.map((d) =>
        d.kind === "R" ? CONST.MAX_ANGLE_STEP : CONST.MAX_SLIDE_STEP * this.L);
      this.groups = model.groups.map((g) =>
        (g.kind === "cam" ? new CamGroup(this, g) : g.kind === "dyad" ? new DyadRRR(this, g) : g));
      this.outlines = {};
    }

    solveSteps(Qsteps) {
      // every step: {status, message, joints, points, X, Q, S}
      const { path, at } = E.Mechanism.prototype.pathTo.call(this, Qsteps);
      const walks = this.groups.map(() => ({ lo: null }));
      const sol = path.map((Q) => this.solvePoint(Q, walks));
      return at.map((k) => this.result(sol[k]));
    }

    solvePoint(Q, walks) {
      const S = { ground: still() };
      let failed = -1, ind = Infinity, why = null;
      this.groups.forEach((g, gi) => {
        if (failed >= 0) return;
        if (g instanceof CamGroup || g instanceof DyadRRR) {
          const got = g.position(S, walks[gi]);
          if (!Number.isFinite(got)) { failed = gi; why = g.failure(); }
          else ind = Math.min(ind, got);
          return;
        }
        const j = this.model.joints[g.joint], k = S[g.known];
        const di = this.model.drivers.findIndex((d) => d.joint === g.joint), qq = Q[di];
        if (j.type === "R") {
          const st = pose(k.th + g.sign * (qq - this.q0[di]), 0.0, 0.0);
          const Y = point(k, j.at), r = rot(st, j.at);
          st.dx = Y[0] - r[0]; st.dy = Y[1] - r[1];
          S[g.link] = st;
        } else {
          const u = rot(k, [Math.cos(j.axis), Math.sin(j.axis)]);
          S[g.link] = pose(k.th, k.dx + g.sign * qq * u[0], k.dy + g.sign * qq * u[1], k.c, k.s);
        }
      });
      for (const n of this.links) if (!(n in S)) S[n] = pose(NaN, NaN, NaN);
      return { S: S, Q: Q, failed: failed, why: why, ind: ind };
    }

    jacobian(S) {
      // the dimensionless constraint Jacobian (numeric.kinematics.constraints.jacobian)
      const m = this.model, L = this.L, rows = [];
      const col = {};
      this.links.forEach((n, i) => { col[n] = 3 * i; });
      const add = (parts, isLength) => {
        // parts: [[link, [a, b, c]]] for one row
        const row = new Array(3 * this.links.length).fill(0.0);
        for (const [link, v] of parts) {
          if (!(link in col)) continue;
          for (let t = 0; t < 3; t++) row[col[link] + t] += v[t] * (t < 2 ? L : 1.0) * (isLength ? 1.0 / L : 1.0);
        }
        rows.push(row);
      };
      const cams = {};
      for (const g of this.groups) if (g instanceof CamGroup) cams[g.g.joint] = g;
      for (const name of m.order) {
        const j = m.joints[name], [a, b] = j.links;
        if (j.type === "cam") {
          const g = cams[name];
          add([a, b].filter((n) => n in col).map((n) => [n, g.jac(S, n)[0]]), true);
          continue;
        }
        if (j.type === "R") {
          const ra = rot(S[a], j.at), rb = rot(S[b], j.at);
          add([[a, [1, 0, -ra[1]]], [b, [-1, 0, rb[1]]]], true);
          add([[a, [0, 1, ra[0]]], [b, [0, -1, -rb[0]]]], true);
        } else {
          const n0 = rot(S[a], [-Math.sin(j.axis), Math.cos(j.axis)]);
          const Dx = S[b].dx - S[a].dx, Dy = S[b].dy - S[a].dy;
          add([[a, [0, 0, -1]], [b, [0, 0, 1]]], false);
          add([[a, [-n0[0], -n0[1], -n0[1] * Dx + n0[0] * Dy]], [b, [n0[0], n0[1], 0]]], true);
        }
        const d = m.drivers.find((dr) => dr.joint === name);
        if (d === undefined) continue;
        if (j.type === "R") add([[a, [0, 0, -1]], [b, [0, 0, 1]]], false);
        else {
          const u = rot(S[a], [Math.cos(j.axis), Math.sin(j.axis)]);
          const Dx = S[b].dx - S[a].dx, Dy = S[b].dy - S[a].dy;
          add([[a, [-u[0], -u[1], -u[1] * Dx + u[0] * Dy]], [b, [u[0], u[1], 0]]], true);
        }
      }
      return rows;
    }

    result(s) {
      const m = this.model;
      const X = this.links.map((n) => s.S[n].th);
      if (s.failed >= 0)
        return { status: "unassemblable", message: s.why, joints: {}, points: {}, X: X, Q: s.Q, S: s.S };
      let status = "ok", message = null;
      if (s.ind < CONST.SCREEN) {
        const J = this.jacobian(s.S);
        let cond = Infinity;
        if (J.every((row) => row.every(Number.isFinite))) {
          const sv = E.singularValues(J);
          cond = sv[0] / sv[sv.length - 1];
        }
        if (!(cond <= CONST.SINGULAR_COND)) {
          status = "singular";
          message = "singular position: condition number " + cond.toPrecision(3);
        }
      }
      const joints = {}, points = {};
      for (const n of m.order) joints[n] = point(s.S[m.joints[n].links[1]], m.joints[n].at);
      for (const g of this.groups) if (g instanceof CamGroup) joints[g.g.joint] = g.contact(s.S).C;
      for (const pt of m.points) points[pt.name] = point(s.S[pt.link], pt.at);
      return { status: status, message: message, joints: joints, points: points, X: X, Q: s.Q, S: s.S };
    }

    // -- drawing (page.js calls these where a mechanism has them) ------------------------------
    outline(name) {
      // the working profile (and a pitch curve) in the cam's frame: plotting.cam_drawing.cam_outline
      if (!(name in this.outlines)) {
        const c = this.model.cams[name], pr = this.profiles[name];
        const working = [], pitch = [];
        for (let k = 0; k < OUTLINE; k++) {
          const fr = pr.frame(k * TWO_PI / (OUTLINE - 1));
          pitch.push([fr.x, fr.y]);
          working.push(c.pitch ? [fr.x - c.radius * fr.nx, fr.y - c.radius * fr.ny] : [fr.x, fr.y]);
        }
        this.outlines[name] = { working: working, pitch: c.pitch ? pitch : null };
      }
      return this.outlines[name];
    }

    states(st) {
      // the link states of a drawn state (the assembly configuration: every link still)
      if (st.S) return st.S;
      const S = { ground: still() };
      for (const n of this.links) S[n] = still();
      return S;
    }

    hullPoints(st) {
      // the points a link's drawn outline takes besides its joints: a follower's element point
      const S = this.states(st), out = {};
      for (const [n, c] of Object.entries(this.model.cams)) {
        const P = point(S[c.follower], this.model.joints[n].at);
        if (Number.isFinite(P[0])) (out[c.follower] = out[c.follower] || []).push(P);
      }
      return out;
    }

    extent(cycle) {
      // points the view must hold: each cam's profile at every step (a few samples)
      const out = [];
      const states = cycle.length ? cycle.filter((s) => s.S) : [{}];
      for (const n of Object.keys(this.model.cams)) {
        const ring = this.outline(n).working;
        for (const st of states.length ? states : [{}]) {
          const c = this.states(st)[this.model.cams[n].cam];
          for (let k = 0; k < ring.length; k += 24) out.push(point(c, ring[k]));
        }
      }
      return out;
    }

    faceSpan(name, cycle) {
      // where a flat face must reach along itself from its point: the contact's travel on it,
      // and 8 % of the size beyond (plotting.cam_drawing.face_span)
      const c = this.model.cams[name], at = this.model.joints[name].at;
      const u = [Math.cos(c.face), Math.sin(c.face)];
      let lo = 0.0, hi = 0.0;
      for (const s of cycle) {
        if (!s.S || !s.joints[name]) continue;
        const f = s.S[c.follower], C = s.joints[name];
        const local = toLocal(f, C);
        const t = (local[0] - at[0]) * u[0] + (local[1] - at[1]) * u[1];
        if (Number.isFinite(t)) { lo = Math.min(lo, t); hi = Math.max(hi, t); }
      }
      return [lo - 0.08 * this.L, hi + 0.08 * this.L];
    }

    draw(ctx, st, toCanvas, scale, colour, cycle) {
      // each cam's profile on its cam (filled), its pitch curve dashed, and the follower's
      // roller or flat face, as the pictures draw them (plotting.cam_drawing.draw_cam)
      const S = this.states(st);
      for (const [n, c] of Object.entries(this.model.cams)) {
        const cs = S[c.cam], fs = S[c.follower], o = this.outline(n);
        if (Number.isFinite(cs.th) && Number.isFinite(cs.dx)) {
          const col = colour(c.cam);
          ctx.beginPath();
          o.working.forEach((p, i) => { const [x, y] = toCanvas(point(cs, p)); if (i) ctx.lineTo(x, y); else ctx.moveTo(x, y); });
          ctx.closePath();
          ctx.fillStyle = col + "4d"; ctx.fill();
          ctx.strokeStyle = col; ctx.lineWidth = 1.8; ctx.stroke();
          if (o.pitch) {
            ctx.setLineDash([4, 3]); ctx.lineWidth = 0.8; ctx.beginPath();
            o.pitch.forEach((p, i) => { const [x, y] = toCanvas(point(cs, p)); if (i) ctx.lineTo(x, y); else ctx.moveTo(x, y); });
            ctx.stroke(); ctx.setLineDash([]);
          }
        }
        if (!Number.isFinite(fs.th) || !Number.isFinite(fs.dx)) continue;
        const at = this.model.joints[n].at;
        const [px, py] = toCanvas(point(fs, at));
        if (c.kind === "roller") {
          ctx.fillStyle = "#fff"; ctx.strokeStyle = colour(c.follower); ctx.lineWidth = 1.8;
          ctx.beginPath(); ctx.arc(px, py, c.radius * scale, 0, TWO_PI); ctx.fill(); ctx.stroke();
        } else if (c.kind === "flat") {
          const u = [Math.cos(c.face), Math.sin(c.face)];
          if (!this.spans) this.spans = {};
          if (!(n in this.spans)) this.spans[n] = this.faceSpan(n, cycle);
          const [lo, hi] = this.spans[n];
          const a = toCanvas(point(fs, [at[0] + lo * u[0], at[1] + lo * u[1]]));
          const b = toCanvas(point(fs, [at[0] + hi * u[0], at[1] + hi * u[1]]));
          ctx.strokeStyle = "#262626"; ctx.lineWidth = 2.2; ctx.lineCap = "butt";
          ctx.beginPath(); ctx.moveTo(a[0], a[1]); ctx.lineTo(b[0], b[1]); ctx.stroke();
        }
      }
    }
  }

  return { Mechanism: Mechanism, Profile: Profile, ppoly: ppoly };
})();
