// The page's layers: velocity and acceleration arrows of the joints and traced points,
// reactions and driving efforts, instant centres with their three-centre lines, the
// transmission angles; each toggled by a checkbox, all off until ticked.
//
// The values come from the evaluator (evaluator_rates.js: the generated `rates`,
// `accelerations` and `points`, the force blocks) and PageCentres (centres.js); the arrows
// of a layer have one scale over the sweep, as the animations' (plotting/animation.py):
// the longest ARROW_SHARE of the mechanism's size, the largest driving torque a curved
// arrow of TORQUE_SWEEP degrees; the page states each scale.
"use strict";

const PageLayers = (function () {
  const ARROW_SHARE = 0.35;
  const TORQUE_SWEEP = 300.0;
  const LAYERS = [["velocity", "velocities"], ["acceleration", "accelerations"],
    ["forces", "reactions and driving efforts"], ["centres", "instant centres"],
    ["transmission", "transmission angles"]];
  const COLORS = { velocity: "#00838f", acceleration: "#c2185b", reactions: "#1a1a1a",
    driving: "#e65100", transmission: "#6a1b9a", primary: "#444", kennedy: "#795548",
    fromVelocity: "#1565c0" };

  function pairs(obj) { return Object.entries(obj); }

  // -- values ---------------------------------------------------------------------------
  function values(mech, model, step, centres = true, forces = true) {
    // one solved step's layers (window.linkageSym.layers): the rates at the drivers'
    // speeds and accelerations of the scene (the instant centres unless `centres` is
    // false: a drag needs the other values at every step, for the scales, and the centres
    // of the step drawn); at a step that is not ok, only its status
    const out = { status: step.status, message: step.message || null,
      velocities: { joints: {}, points: {} }, accelerations: { joints: {}, points: {} },
      reactions: null, reaction_moments: null, driving: null, centres: {}, lines: [],
      transmission_deg: {} };
    if (step.status !== "ok") return out;
    const QD = model.drivers.map((d) => d.speed), QDD = model.drivers.map((d) => d.acceleration);
    const st = mech.motion(step.X, step.Q, QD, QDD);
    const kin = mech.kinematics(st);
    for (const [level, key] of [[1, "velocities"], [2, "accelerations"]]) {
      for (const [n, v] of pairs(kin.joints)) if (v[level]) out[key].joints[n] = v[level];
      for (const [n, v] of pairs(kin.points)) if (v[level]) out[key].points[n] = v[level];
    }
    const r = forces ? mech.reactions(st) : null;
    if (r !== null) {
      out.reactions = {}; out.reaction_moments = {};
      for (const [n, f] of pairs(r.reactions)) { out.reactions[n] = [f[0], f[1]]; out.reaction_moments[n] = f[2]; }
      out.driving = r.driving;
    }
    const joints = {};
    for (const [n, v] of pairs(kin.joints)) joints[n] = v[0];
    const rotation = (link) => (link === "ground" ? 0.0 : step.X[mech.angleOf[link]] - mech.geometry.frames[link].theta0);
    out.centresOf = () => PageCentres.instantCentres(model, { joints: joints, rotation: rotation },
      (link) => mech.frameMotion(link, st), mech.L);
    if (centres) {
      const ic = out.centresOf();
      out.centres = ic.centres;
      out.lines = ic.lines;
    }
    for (const [inner, e1, e2] of model.dyads) {
      const J = joints[inner], u = [joints[e1][0] - J[0], joints[e1][1] - J[1]];
      const v = [joints[e2][0] - J[0], joints[e2][1] - J[1]];
      const g = Math.atan2(Math.abs(u[0] * v[1] - u[1] * v[0]), u[0] * v[0] + u[1] * v[1]);
      out.transmission_deg[inner] = g * 180 / Math.PI;
    }
    out.points = kin.points;
    out.joints = joints;
    out.rotation = rotation;
    return out;
  }

  function availability(model, art) {
    // {layer: null (available) or why not}
    if (model.cams) { // cams.js ports the position solvers only
      const camWhy = "a cam mechanism's page solves its positions only (the numeric solvers " +
        "ported, no derived rates)";
      return { velocity: camWhy, acceleration: camWhy, forces: camWhy, centres: camWhy,
        transmission: camWhy };
    }
    const stages = art.stages;
    const noRates = "the scene's equations were derived without velocities";
    return {
      velocity: stages.includes("velocity") ? null : noRates,
      acceleration: stages.includes("acceleration") ? null : noRates,
      forces: model.forces_left_out ? model.forces_left_out : stages.includes("forces") ? null :
        "the scene gives no masses, inertias or loads: no force acts on its links",
      centres: stages.includes("velocity") ? null : noRates,
      transmission: model.dyads.length ? null : "the mechanism has no RRR dyad",
    };
  }

  // -- the layers of a page -------------------------------------------------------------
  function create(env) {
    // env: {model, ctx, canvas, toCanvas, mechanism(), cycle(), redraw()}
    const { model, ctx } = env;
    const on = {};
    let cache = null; // per step of the sweep, made when a layer is on
    let scales = null;
    const why = availability(model, model.artifact);
    const boxes = {};

    function reset(keepScales = false) {
      // a new sweep: its values are computed again when drawn; the scales too, unless a
      // drag is going on (the arrows keep their scales until it ends, and only the step
      // drawn is computed while it lasts)
      cache = null;
      if (!keepScales) scales = null;
    }

    function stepValues(k) {
      const mech = env.mechanism();
      if (cache === null) cache = new Array(env.cycle().length).fill(null);
      if (cache[k] === null) cache[k] = values(mech, model, env.cycle()[k], false, Boolean(on.forces));
      return cache[k];
    }

    function largest(get) {
      let big = 0.0;
      env.cycle().forEach((s, k) => {
        if (s.status !== "ok") return;
        for (const v of get(stepValues(k))) {
          const n = Array.isArray(v) ? Math.hypot(v[0], v[1]) : Math.abs(v);
          if (Number.isFinite(n)) big = Math.max(big, n);
        }
      });
      return big;
    }

    function computeScales() {
      // drawing length (m) per unit of each arrow layer: its largest value over the sweep
      // ARROW_SHARE sizes long; degrees of sweep per N·m of driving torque
      const mech = env.mechanism();
      const reach = ARROW_SHARE * mech.L;
      const per = (big, full) => (big > 0 ? full / big : 0.0);
      const vecs = (key) => (s) => Object.values(s[key].joints).concat(Object.values(s[key].points));
      const out = {};
      if (on.velocity) out.velocity = per(largest(vecs("velocities")), reach);
      if (on.acceleration) out.acceleration = per(largest(vecs("accelerations")), reach);
      if (on.forces && why.forces === null) {
        out.reactions = per(largest((s) => Object.values(s.reactions || {})), reach);
        const kinds = (kind) => (s) => model.drivers.filter((d) => d.kind === kind).map((d) => s.driving[d.joint]);
        if (model.drivers.some((d) => d.kind === "R")) out.torque = per(largest(kinds("R")), TORQUE_SWEEP);
        if (model.drivers.some((d) => d.kind === "P")) out.force = per(largest(kinds("P")), reach);
      }
      return out;
    }

    function fmt(v) { return Number(v.toPrecision(3)).toString(); }

    function scaleText() {
      const s = scales, lines = [];
      if (!s) return lines;
      if ("velocity" in s) lines.push(["velocity", "velocity: 1 m/s drawn " + fmt(s.velocity) + " m long"]);
      if ("acceleration" in s) lines.push(["acceleration", "acceleration: 1 m/s² drawn " + fmt(s.acceleration) + " m long"]);
      if ("reactions" in s) lines.push(["reactions", "reactions: 1 N drawn " + fmt(s.reactions) + " m long"]);
      if ("torque" in s) lines.push(["driving", "driving torque: 1 N·m drawn " + fmt(s.torque) + "° of arc"]);
      if ("force" in s) lines.push(["driving", "driving force: 1 N drawn " + fmt(s.force) + " m long"]);
      return lines;
    }

    function showScales() {
      const el = document.getElementById("layer-scales");
      if (el) el.textContent = scaleText().map((l) => l[1]).join(" · ");
    }

    function setLayer(name, value) {
      if (!(name in why)) throw new Error("no layer named " + JSON.stringify(name));
      if (value && why[name] !== null) throw new Error("layer " + name + " is not available: " + why[name]);
      on[name] = Boolean(value);
      if (boxes[name]) boxes[name].checked = on[name];
      scales = null;
      cache = null; // the forces are computed only while their layer is on
      if (!LAYERS.some(([n]) => on[n])) showScales();
      env.redraw();
    }

    function setup() {
      const status = document.getElementById("status");
      const div = document.createElement("div");
      div.className = "layers";
      div.id = "layers";
      const head = document.createElement("span");
      head.textContent = "Layers:";
      div.appendChild(head);
      const notes = [];
      for (const [name, label] of LAYERS) {
        const lab = document.createElement("label");
        const box = document.createElement("input");
        box.type = "checkbox"; box.id = "layer-" + name;
        box.checked = false;
        if (why[name] !== null) {
          box.disabled = true;
          lab.title = why[name];
          lab.className = "off";
          notes.push(label + ": " + why[name]);
        }
        box.addEventListener("change", () => setLayer(name, box.checked));
        boxes[name] = box;
        lab.append(box, " " + label);
        div.appendChild(lab);
      }
      status.after(div);
      const sc = document.createElement("p");
      sc.id = "layer-scales"; sc.className = "hint";
      div.after(sc);
      if (notes.length) {
        const p = document.createElement("p");
        p.id = "layer-notes"; p.className = "hint";
        p.textContent = "Not available: " + notes.join("; ");
        sc.after(p);
      }
    }

    // -- drawing ---------------------------------------------------------------------------
    function arrow(p, v, scale, colour, width) {
      if (!p || !v || !Number.isFinite(v[0]) || !Number.isFinite(v[1])) return;
      const L = env.mechanism().L;
      if (Math.hypot(v[0], v[1]) * scale <= 1e-9 * L) return;
      const [x0, y0] = env.toCanvas(p);
      const [x1, y1] = env.toCanvas([p[0] + v[0] * scale, p[1] + v[1] * scale]);
      const a = Math.atan2(y1 - y0, x1 - x0), len = Math.hypot(x1 - x0, y1 - y0);
      const head = Math.min(10, 0.4 * len);
      ctx.strokeStyle = colour; ctx.fillStyle = colour; ctx.lineWidth = width || 2;
      ctx.beginPath(); ctx.moveTo(x0, y0);
      ctx.lineTo(x1 - 0.8 * head * Math.cos(a), y1 - 0.8 * head * Math.sin(a)); ctx.stroke();
      ctx.beginPath(); ctx.moveTo(x1, y1);
      ctx.lineTo(x1 - head * Math.cos(a - 0.35), y1 - head * Math.sin(a - 0.35));
      ctx.lineTo(x1 - head * Math.cos(a + 0.35), y1 - head * Math.sin(a + 0.35));
      ctx.closePath(); ctx.fill();
    }

    function label(text, p, colour, dx, dy) {
      const [x, y] = env.toCanvas(p);
      ctx.font = "12px sans-serif"; ctx.lineWidth = 4; ctx.strokeStyle = "#fbfbf8"; ctx.fillStyle = colour;
      ctx.strokeText(text, x + (dx || 6), y + (dy || -6));
      ctx.fillText(text, x + (dx || 6), y + (dy || -6));
    }

    function drawArrows(v, key) {
      const s = v[key === "velocity" ? "velocities" : "accelerations"];
      for (const [n, vec] of pairs(s.joints)) arrow(v.joints[n], vec, scales[key], COLORS[key]);
      for (const [n, vec] of pairs(s.points)) arrow(v.points[n][0], vec, scales[key], COLORS[key]);
    }

    function drawForces(v) {
      for (const [n, f] of pairs(v.reactions)) arrow(v.joints[n], f, scales.reactions, COLORS.reactions, 2.4);
      const L = env.mechanism().L;
      for (const d of model.drivers) {
        const value = v.driving[d.joint], p = v.joints[d.joint];
        if (!Number.isFinite(value)) continue;
        if (d.kind === "R") {
          const sweep = value * scales.torque * Math.PI / 180, r = 0.12 * L;
          const [cx, cy] = env.toCanvas(p), rp = env.toCanvas([p[0] + r, p[1]])[0] - cx;
          if (Math.abs(sweep) > 1e-6) {
            ctx.strokeStyle = COLORS.driving; ctx.fillStyle = COLORS.driving; ctx.lineWidth = 2.2;
            ctx.beginPath(); ctx.arc(cx, cy, rp, 0, -sweep, sweep > 0); ctx.stroke();
            const ex = cx + rp * Math.cos(sweep), ey = cy - rp * Math.sin(sweep);
            const t = Math.sign(sweep), tx = -Math.sin(sweep) * t, ty = -Math.cos(sweep) * t;
            ctx.beginPath(); ctx.moveTo(ex + 9 * tx, ey + 9 * ty);
            ctx.lineTo(ex - 4 * ty, ey + 4 * tx); ctx.lineTo(ex + 4 * ty, ey - 4 * tx); ctx.closePath(); ctx.fill();
          }
          label("T " + d.joint + " = " + fmt(value) + " N·m", p, COLORS.driving, 14, 34);
        } else {
          const j = model.joints[d.joint], a = j.axis + v.rotation(j.links[0]);
          arrow(p, [value * Math.cos(a), value * Math.sin(a)], scales.force, COLORS.driving, 2.4);
          label("F " + d.joint + " = " + fmt(value) + " N", p, COLORS.driving, 14, 34);
        }
      }
    }

    function centreNumber() {
      const num = {};
      ["ground"].concat(model.link_names).forEach((n, i) => { num[n] = i + 1; });
      const sep = model.link_names.length + 1 < 10 ? "" : ",";
      return (a, b) => "P" + num[a] + sep + num[b];
    }

    function drawCentres(v) {
      const L = env.mechanism().L, name = centreNumber();
      const at = (a, b) => v.centres[a + "," + b] || v.centres[b + "," + a];
      ctx.setLineDash([6, 4]); ctx.strokeStyle = COLORS.kennedy; ctx.lineWidth = 1; ctx.globalAlpha = 0.6;
      for (const ln of v.lines) { // P_ik, P_kj and P_ij on one line, for each third link k
        const target = v.centres[ln.centre];
        if (!target.position) continue;
        const [a, b] = target.links;
        for (const k of ln.via) {
          const ends = [at(a, k), at(k, b)];
          const pts = [target.position].concat(ends.filter((e) => e.position).map((e) => e.position));
          const inf = ends.find((e) => e.at_infinity);
          let u;
          if (inf) u = inf.direction;
          else {
            u = [pts[1][0] - pts[0][0], pts[1][1] - pts[0][1]];
            const n = Math.hypot(u[0], u[1]); u = n > 0 ? [u[0] / n, u[1] / n] : [1, 0];
          }
          const t = pts.map((p) => (p[0] - pts[0][0]) * u[0] + (p[1] - pts[0][1]) * u[1]);
          const lo = Math.min(...t), hi = Math.max(...t), span = Math.max(hi - lo, 0.3 * L);
          const p0 = env.toCanvas([pts[0][0] + (lo - 0.1 * span) * u[0], pts[0][1] + (lo - 0.1 * span) * u[1]]);
          const p1 = env.toCanvas([pts[0][0] + (hi + 0.1 * span) * u[0], pts[0][1] + (hi + 0.1 * span) * u[1]]);
          ctx.beginPath(); ctx.moveTo(p0[0], p0[1]); ctx.lineTo(p1[0], p1[1]); ctx.stroke();
        }
      }
      ctx.setLineDash([]); ctx.globalAlpha = 1.0;
      const off = [], groups = [];
      for (const rec of Object.values(v.centres)) {
        const nm = name(rec.links[0], rec.links[1]);
        if (rec.undefined) continue;
        if (rec.at_infinity) { off.push(nm + " at infinity"); continue; }
        const [x, y] = env.toCanvas(rec.position);
        if (!(x >= 0 && x <= env.canvas.width && y >= 0 && y <= env.canvas.height)) { off.push(nm + " off the drawing"); continue; }
        const colour = rec.method === "velocity" ? COLORS.fromVelocity :
          rec.source === "three-centre lines" ? COLORS.kennedy : COLORS.primary;
        ctx.strokeStyle = "#fff"; ctx.fillStyle = colour; ctx.lineWidth = 1.5;
        ctx.beginPath(); ctx.arc(x, y, 5, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
        const g = groups.find((gr) => Math.hypot(gr.x - x, gr.y - y) < 14);
        if (g) g.text += ", " + nm; else groups.push({ x: x, y: y, text: nm, colour: colour, p: rec.position });
      }
      for (const g of groups) label(g.text, g.p, g.colour, 7, 14);
      if (off.length) {
        ctx.font = "12px sans-serif"; ctx.fillStyle = "#444"; ctx.textAlign = "right";
        ctx.fillText(off.join("; "), env.canvas.width - 10, env.canvas.height - 10);
        ctx.textAlign = "left";
      }
    }

    function drawTransmission(v) {
      const L = env.mechanism().L;
      for (const [inner, e1, e2] of model.dyads) {
        const J = v.joints[inner], g = v.transmission_deg[inner];
        if (!Number.isFinite(g)) continue;
        const a1 = Math.atan2(v.joints[e1][1] - J[1], v.joints[e1][0] - J[0]);
        const a2 = Math.atan2(v.joints[e2][1] - J[1], v.joints[e2][0] - J[0]);
        const ccw = ((a2 - a1) % (2 * Math.PI) + 2 * Math.PI) % (2 * Math.PI) <= Math.PI;
        const [start, stop] = ccw ? [a1, a2] : [a2, a1];
        const [cx, cy] = env.toCanvas(J), rp = 0.14 * L * (env.toCanvas([J[0] + 1, J[1]])[0] - cx);
        ctx.strokeStyle = COLORS.transmission; ctx.lineWidth = 3;
        ctx.beginPath(); ctx.arc(cx, cy, rp, -start, -stop, true); ctx.stroke();
        const mid = start + 0.5 * (((stop - start) % (2 * Math.PI) + 2 * Math.PI) % (2 * Math.PI));
        const at = [J[0] + 1.35 * 0.14 * L * Math.cos(mid), J[1] + 1.35 * 0.14 * L * Math.sin(mid)];
        label("γ " + inner + " = " + g.toFixed(1) + "°", at, COLORS.transmission, -30, 4);
      }
    }

    function drawScales() {
      const lines = scaleText();
      ctx.font = "12px sans-serif"; ctx.textAlign = "right";
      lines.forEach(([key, text], i) => {
        ctx.fillStyle = COLORS[key];
        ctx.fillText(text, env.canvas.width - 10, 18 + 16 * i);
      });
      ctx.textAlign = "left";
    }

    function draw(k) {
      // the layers ticked, over step k of the sweep (an ok step)
      if (!LAYERS.some(([n]) => on[n]) || env.mechanism() === null) return;
      const s = env.cycle()[k];
      if (!s || s.status !== "ok") return;
      if (scales === null) { scales = computeScales(); showScales(); }
      const v = stepValues(k);
      if (on.centres) {
        if (v.centresOf) { const ic = v.centresOf(); v.centres = ic.centres; v.lines = ic.lines; v.centresOf = null; }
        drawCentres(v);
      }
      if (on.transmission) drawTransmission(v);
      if (on.velocity) drawArrows(v, "velocity");
      if (on.acceleration) drawArrows(v, "acceleration");
      if (on.forces && v.reactions) drawForces(v);
      drawScales();
    }

    setup();
    return {
      reset: reset, draw: draw, setLayer: setLayer,
      available: () => Object.assign({}, why),
      scales: () => { if (scales === null && env.mechanism() !== null) scales = computeScales(); return Object.assign({}, scales); },
      values: (step) => {
        const v = values(env.mechanism(), model, step);
        delete v.rotation; delete v.points; delete v.joints; delete v.centresOf;
        return v;
      },
    };
  }

  return { create: create, values: values, LAYERS: LAYERS.map((l) => l[0]) };
})();
