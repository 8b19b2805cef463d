// The instant centres of one solved step on the page: Kennedy's construction, filled from the
// velocity fields (linkage_sym/centres: kennedy.py, kennedy_lines.py, velocity.py, table.py,
// for one step at a time; LAYER_CONST holds their constants, read from those modules).
//
// Kennedy: the primary centres from the joints (an R joint's pin, a mesh's pitch point, a
// slide's point at infinity normal to it, a pin shared by several links), then rounds of the
// circle diagram, each closing every pair two three-centre lines reach, the pair of lines
// whose intersection has the smallest estimated error taken (homogeneous points in the frame
// scaled about the assembly's centre by the mechanism's size), then the derived centres
// intersected again with every line there is.  A pair no round reaches is filled from the
// velocity fields (v_i(p) = v_j(p)); two links at rest relative to each other have no
// centre (`undefined`) unless they share a pin.  Not ported: the weakest-angle bookkeeping
// and cam contacts (a page refuses cams).  One difference: the velocity method's size is
// this step's spread of the joints about their mean (Python's is the largest over the
// sweep); it decides only where two links count as at rest or a centre as at infinity.
"use strict";

const PageCentres = (function () {
  const K = LAYER_CONST;
  const NAN3 = [NaN, NaN, NaN];

  const finite = (p) => p !== null && Number.isFinite(p[0]) && Number.isFinite(p[1]);
  const finite3 = (h) => Number.isFinite(h[0]) && Number.isFinite(h[1]) && Number.isFinite(h[2]);
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const norm2 = (x, y) => Math.sqrt(x * x + y * y);
  const norm3 = (h) => Math.sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);

  function unit(h) {
    const n = norm3(h);
    return n > 0 ? [h[0] / n, h[1] / n, h[2] / n] : NAN3;
  }

  function snap(h) {
    // unit homogeneous points, those beyond FAR sizes exactly at infinity
    h = unit(h);
    if (Math.abs(h[2]) * K.FAR <= norm2(h[0], h[1])) h = [h[0], h[1], 0.0];
    return unit(h);
  }

  function relative(h, err) {
    const w = Math.abs(h[2]);
    return w > 0 ? err / Math.max(1.0, norm2(h[0], h[1]) / w) : err;
  }

  function toGlobal(h, c, L) {
    return h[2] !== 0 && finite3(h) ? [c[0] + L * h[0] / h[2], c[1] + L * h[1] / h[2]] : [NaN, NaN];
  }

  function line(ha, pa, hb, pb, c, L) {
    // the three-centre line through two centres (scaled frame): [nx, ny, c0], [0, 0, 1] for
    // the line at infinity, NaN where they span no line (kennedy_lines._line)
    const fa = finite(pa), fb = finite(pb);
    const ia = finite3(ha) && !fa, ib = finite3(hb) && !fb;
    const d = fa && fb ? [pb[0] - pa[0], pb[1] - pa[1]] : fa ? [hb[0], hb[1]] : [ha[0], ha[1]];
    const span = norm2(d[0], d[1]);
    const anchor = fa ? pa : pb;
    const nx = -d[1] / span, ny = d[0] / span;
    const c0 = -(nx * (anchor[0] - c[0]) + ny * (anchor[1] - c[1])) / L;
    if ((fa && fb && span > K.DEGENERATE * L) || (fa && ib) || (ia && fb)) return [nx, ny, c0];
    if (ia && ib && Math.abs(ha[0] * hb[1] - ha[1] * hb[0]) > K.DEGENERATE) return [0.0, 0.0, 1.0];
    return NAN3;
  }

  function lineError(pa, ea, pb, eb) {
    // how far a line through centres at pa, pb (scaled frame; NaN at infinity) may be off
    // (kennedy_lines._line_error): {q, e0, slope, atInf}
    const fa = finite(pa), fb = finite(pb);
    const slopeFF = (ea + eb) / norm2(pa[0] - pb[0], pa[1] - pb[1]);
    return {
      q: fa ? pa : pb,
      e0: fa && fb ? Math.max(ea, eb) : fa ? ea : eb,
      slope: fa && fb ? slopeFF : fa ? eb : fb ? ea : Math.max(ea, eb),
      atInf: !fa && !fb,
    };
  }

  function intersectBest(d, i, j, ks) {
    // centre P_ij from the best pair of three-centre lines (kennedy_lines.intersect_best)
    const { H, PG, E, c, L } = d;
    const scaled = (p) => [(p[0] - c[0]) / L, (p[1] - c[1]) / L];
    const lines = ks.map((k) => line(H[i][k], PG[i][k], H[k][j], PG[k][j], c, L));
    const model = ks.map((k) => lineError(scaled(PG[i][k]), E[i][k], scaled(PG[k][j]), E[k][j]));
    let bestR = Infinity, best = null;
    for (let a = 0; a < ks.length; a++) {
      for (let b = a + 1; b < ks.length; b++) {
        const la = lines[a], lb = lines[b], ma = model[a], mb = model[b];
        const meet = cross(la, lb);
        let valid = norm3(meet) > K.DEGENERATE;
        const h = snap(meet);
        const na = norm2(la[0], la[1]), nb = norm2(lb[0], lb[1]);
        let sin = Math.abs(la[0] * lb[1] - la[1] * lb[0]) / (na * nb);
        sin = Math.min(ma.atInf || mb.atInf ? 1.0 : sin, 1.0);
        const X = [h[0] / h[2], h[1] / h[2]];
        const off = ma.e0 + ma.slope * norm2(X[0] - ma.q[0], X[1] - ma.q[1]) +
          mb.e0 + mb.slope * norm2(X[0] - mb.q[0], X[1] - mb.q[1]);
        const err = h[2] !== 0 ? off / sin : ma.atInf ? mb.slope : mb.atInf ? ma.slope : Math.max(ma.slope, mb.slope);
        const sense = Math.sign(la[0] * lb[0] + la[1] * lb[1]);
        const apart = Math.abs(la[2] / na - sense * lb[2] / nb);
        const slack = ma.e0 + ma.slope * norm2(ma.q[0], ma.q[1]) + mb.e0 + mb.slope * norm2(mb.q[0], mb.q[1]);
        const twoLines = ma.atInf || mb.atInf || apart > K.DISTINCT * slack;
        const rel = relative(h, err);
        valid = valid && (h[2] === 0 ? twoLines : rel <= K.UNCERTAIN);
        const r = valid ? rel : Infinity;
        if (r < bestR) {
          bestR = r;
          best = { h: h, err: err, via: [ks[a], ks[b]] };
        }
      }
    }
    return best !== null ? best : { h: NAN3, err: NaN, via: [-1, -1] };
  }

  function pins(model) {
    // groups of R joints that are one pin: at one assembly point exactly, on a common link
    // (or both on the ground) (kennedy._joint_pins)
    const rj = model.order.filter((n) => model.joints[n].type === "R");
    const parent = rj.map((_, i) => i);
    const root = (a) => { while (parent[a] !== a) a = parent[a] = parent[parent[a]]; return a; };
    for (let a = 0; a < rj.length; a++) {
      for (let b = a + 1; b < rj.length; b++) {
        const ja = model.joints[rj[a]], jb = model.joints[rj[b]];
        const shared = ja.links.some((l) => l !== "ground" && jb.links.includes(l));
        const close = ja.at[0] === jb.at[0] && ja.at[1] === jb.at[1];
        const bothGround = ja.links.includes("ground") && jb.links.includes("ground");
        if (close && (shared || bothGround)) parent[root(a)] = root(b);
      }
    }
    const groups = {};
    rj.forEach((n, a) => { (groups[root(a)] = groups[root(a)] || []).push(n); });
    return Object.values(groups).filter((g) => g.length > 1);
  }

  function kennedy(model, step, L) {
    // the circle diagram of one step: step.joints {name: [x, y]}, step.rotation(link)
    const names = ["ground"].concat(model.link_names);
    const n = names.length, idx = {};
    names.forEach((nm, i) => { idx[nm] = i; });
    const ats = model.order.map((nm) => model.joints[nm].at);
    const c = [ats.reduce((s, p) => s + p[0], 0) / ats.length, ats.reduce((s, p) => s + p[1], 0) / ats.length];
    const grid = (v) => names.map(() => names.map(() => v));
    const d = { H: grid(NAN3), PG: grid([NaN, NaN]), E: grid(NaN), via: grid([-1, -1]), c: c, L: L };
    const known = grid(false), source = {}, pinned = new Set();
    const put = (a, b, h, err, what, at) => {
      d.H[a][b] = d.H[b][a] = h;
      if (at) d.PG[a][b] = d.PG[b][a] = at;
      d.E[a][b] = d.E[b][a] = err;
      known[a][b] = known[b][a] = true;
      source[Math.min(a, b) + "," + Math.max(a, b)] = what;
    };
    const point = (p) => [snap([(p[0] - c[0]) / L, (p[1] - c[1]) / L, 1.0]),
      K.ROUNDING * (1.0 + norm2(p[0], p[1]) / L)];
    for (const type of ["R", "G"]) { // pins first, then the meshes' pitch points
      for (const nm of model.order) {
        const j = model.joints[nm];
        if (j.type !== type) continue;
        const a = idx[j.links[0]], b = idx[j.links[1]];
        if (known[a][b]) continue;
        const at = step.joints[nm];
        put(a, b, ...point(at), type === "R" ? "joint " + nm : "pitch point of mesh " + nm, at);
        if (type === "R") pinned.add(Math.min(a, b) + "," + Math.max(a, b));
      }
    }
    for (const nm of model.order) { // slides: at infinity, normal to the slide
      const j = model.joints[nm];
      if (j.type !== "P") continue;
      const a = idx[j.links[0]], b = idx[j.links[1]];
      if (known[a][b]) continue;
      const th = j.axis + step.rotation(j.links[0]);
      put(a, b, [-Math.sin(th), Math.cos(th), 0.0], K.ROUNDING * (1.0 + Math.abs(th)), "joint " + nm + " (slide)");
    }
    for (const group of pins(model)) {
      const members = [...new Set(group.flatMap((nm) => model.joints[nm].links.map((l) => idx[l])))].sort((x, y) => x - y);
      const at = step.joints[group[0]];
      for (const a of members) for (const b of members) {
        if (a < b && !known[a][b]) {
          put(a, b, ...point(at), "pin of joints " + group.join(", "), at);
          pinned.add(a + "," + b);
        }
      }
    }
    const through = (i, j) => names.map((_, k) => k).filter((k) => k !== i && k !== j && known[i][k] && known[k][j]);
    const take = (i, j, got) => {
      d.H[i][j] = d.H[j][i] = got.h;
      d.PG[i][j] = d.PG[j][i] = toGlobal(got.h, c, L);
      d.E[i][j] = d.E[j][i] = got.err;
      d.via[i][j] = d.via[j][i] = got.via;
    };
    const derived = [];
    for (;;) { // rounds of the circle diagram
      const found = [];
      for (let i = 0; i < n; i++) for (let j = i + 1; j < n; j++) {
        if (known[i][j]) continue;
        const ks = through(i, j);
        if (ks.length >= 2) found.push([i, j, ks]);
      }
      if (!found.length) break;
      for (const [i, j, ks] of found) take(i, j, intersectBest(d, i, j, ks));
      for (const [i, j] of found) {
        known[i][j] = known[j][i] = true;
        source[i + "," + j] = "three-centre lines";
        derived.push([i, j]);
      }
    }
    for (let round = 0; round < n; round++) { // refined with the lines of later centres
      let improved = false;
      for (const [i, j] of derived) {
        const got = intersectBest(d, i, j, through(i, j));
        const old = d.E[i][j];
        const better = Number.isFinite(got.err) && !(relative(got.h, got.err) >= relative(d.H[i][j], old)) &&
          !(Math.abs(got.err - old) <= 1e-3 * Math.abs(old));
        if (better) { improved = true; take(i, j, got); }
      }
      if (!improved) break;
    }
    return { names: names, H: d.H, PG: d.PG, via: d.via, source: source, pinned: pinned };
  }

  function velocityCentre(vi, vj, c, Lv, speed) {
    // where two links' velocity fields agree (velocity.velocity_centres): {position} or
    // {at_infinity, direction} or {undefined}
    const dw = vj.w - vi.w, dv = [vj.v[0] - vi.v[0], vj.v[1] - vi.v[1]];
    const dvn = norm2(dv[0], dv[1]);
    if (Math.abs(dw) * Lv + dvn <= K.REST * speed) return { undefined: true };
    if (Math.abs(dw) * Lv * K.VELOCITY_FAR <= dvn) return { at_infinity: true, direction: [-dv[1] / dvn, dv[0] / dvn] };
    return { position: [c[0] - dv[1] / dw, c[1] + dv[0] / dw] };
  }

  function canonical(u) {
    // a direction with its larger component positive (the sign is free)
    const big = Math.abs(u[0]) >= Math.abs(u[1]) ? u[0] : u[1];
    return big < 0 ? [-u[0], -u[1]] : u;
  }

  function instantCentres(model, step, motion, L) {
    // every pair's centre at one ok step (table.instant_centres): {"a,b": record}, the
    // records of the result's instant_centres ({position} | {at_infinity, direction} |
    // {undefined}; method "velocity" where filled from the velocity fields), and the
    // three-centre lines Kennedy used ({centre: "a,b", via: [link, link]})
    const k = kennedy(model, step, L);
    const names = k.names;
    const js = model.order.map((nm) => step.joints[nm]);
    const c = [js.reduce((s, p) => s + p[0], 0) / js.length, js.reduce((s, p) => s + p[1], 0) / js.length];
    const Lv = Math.max(...js.map((p) => norm2(p[0] - c[0], p[1] - c[1]))) || 1.0;
    const field = names.map((nm) => {
      if (nm === "ground") return { w: 0.0, v: [0.0, 0.0] };
      const m = motion(nm); // [cr, sr, ox, oy, w, vx, vy]
      const r = [c[0] - m[2], c[1] - m[3]];
      return { w: m[4], v: [m[5] - m[4] * r[1], m[6] + m[4] * r[0]] };
    });
    const speed = Math.max(...field.map((f) => Math.abs(f.w) * Lv + norm2(f.v[0], f.v[1])));
    const out = {}, lines = [];
    for (let i = 0; i < names.length; i++) {
      for (let j = i + 1; j < names.length; j++) {
        const key = names[i] + "," + names[j], pair = i + "," + j;
        const vel = velocityCentre(field[i], field[j], c, Lv, speed);
        let rec;
        if (vel.undefined && !k.pinned.has(pair)) {
          rec = { undefined: true };
        } else if (finite3(k.H[i][j])) {
          const h = k.H[i][j];
          if (h[2] === 0) {
            const nn = norm2(h[0], h[1]);
            rec = { at_infinity: true, direction: canonical([h[0] / nn, h[1] / nn]) };
          } else {
            rec = { position: k.PG[i][j].slice() };
          }
          if (k.via[i][j][0] >= 0) lines.push({ centre: key, via: k.via[i][j].map((v) => names[v]) });
        } else {
          rec = vel.at_infinity ? { at_infinity: true, direction: canonical(vel.direction) } :
            { position: vel.position };
          rec.method = "velocity";
        }
        rec.links = [names[i], names[j]];
        rec.source = k.source[pair] || "unreachable";
        out[key] = rec;
      }
    }
    return { centres: out, lines: lines };
  }

  return { instantCentres: instantCentres, kennedy: kennedy };
})();
