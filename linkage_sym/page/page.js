// The page of one mechanism: drawing, controls, editing, and window.linkageSym.
// Reads MODEL, GENERATED and LinkageEvaluator (linkage_sym.codegen.javascript's script), and
// BUILT and PageWarnings (the warnings panel: warnings.js).
(function () {
  "use strict";
  const E = LinkageEvaluator;
  const COINCIDENT = 1e-12; // structure.parameters.COINCIDENT: joints at one point move together
  const PALETTE = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2",
    "#17becf", "#bcbd22", "#7f7f7f"];
  const CYCLE_SECONDS = 4.0; // one sweep at speed 1

  const model = JSON.parse(JSON.stringify(MODEL)); // edited in place by drags and lengths
  const drivers = model.drivers;
  const steps = Math.max(2, drivers.length ? drivers[0].steps : 2);
  const sweep = [];
  // the driver values as NumPy's linspace gives them (k * step + start, the last the stop),
  // so that a warning names the values the Python run names
  for (let k = 0; k < steps; k++)
    sweep.push(drivers.map((d) => (k === steps - 1 && steps > 1 ? d.stop :
      k * ((d.stop - d.start) / (steps - 1)) + d.start)));
  const builtScene = JSON.stringify(MODEL.scene); // the scene as built (BUILT's)
  // the gears' pivots: fixed by the meshes' pitch radii (a drag would break the mesh)
  const gearPivots = new Set();
  for (const n of model.order) if (model.joints[n].type === "G") model.joints[n].pivots.forEach((p) => gearPivots.add(p));
  const linkColour = {};
  Object.keys(model.links).forEach((n, i) => { linkColour[n] = PALETTE[i % PALETTE.length]; });

  let mech = null;   // the mechanism of the current geometry (null when it cannot be built)
  let problem = null; // why not
  let cycle = [];    // the solved sweep
  let found = [];    // the warnings the page's evaluator finds for it (warnings.js)
  let index = 0, playing = true, speed = 1.0, lastTime = null, editing = false;
  let view = null;   // world -> canvas transform
  let dragging = null;

  const $ = (id) => document.getElementById(id);
  const canvas = $("view");
  const ctx = canvas.getContext("2d");
  // the layers (layers.js): off until a box is ticked
  const layerView = PageLayers.create({ model: model, ctx: ctx, canvas: canvas,
    toCanvas: (p) => toCanvas(p), mechanism: () => mech, cycle: () => cycle, redraw: () => draw() });
  // the warnings panel: the Python run's until the mechanism changes, then the page's own
  const warningView = PageWarnings.create({ built: BUILT, drivers: drivers, panel: $("warnings"),
    list: $("warnings-list"), source: $("warnings-source") });

  // -- solving --------------------------------------------------------------------------
  function rebuild(tables = true) {
    try {
      // a mechanism with cam contacts: the numeric layer's solvers ported (cams.js)
      mech = model.cams ? new LinkageCams.Mechanism(model) : new E.Mechanism(model.artifact, GENERATED, model);
      problem = null;
      // the steps, and the solving path's passages through infinity (cams.js has none)
      const run = mech.sweep ? mech.sweep(sweep) : { steps: mech.solveSteps(sweep), passages: [] };
      cycle = run.steps;
      found = PageWarnings.found(run, drivers);
    } catch (err) {
      if (!(err instanceof E.SceneError)) throw err;
      mech = null;
      problem = err.message;
      cycle = [];
      found = [];
    }
    warningView.update(found, JSON.stringify(model.scene) !== builtScene);
    view = null;
    layerView.reset(!tables); // while a drag goes on, the arrows keep their scales
    if (tables) refreshTables(); // a drag refreshes them once, when it ends
    showStatus();
  }

  function driverArray(q) {
    if (typeof q === "number") return [q];
    if (Array.isArray(q)) return q.slice();
    return drivers.map((d) => q[d.joint]);
  }

  function solve(q) {
    if (mech === null) return { status: "error", message: problem, joints: {}, points: {} };
    const got = mech.solveSteps([driverArray(q)])[0];
    return { status: got.status, message: got.message, joints: got.joints, points: got.points };
  }

  function layers(q) {
    // the layers' values at the driver values q (as solve reads them), the drivers at the
    // scene's speeds and accelerations
    if (mech === null) throw new Error(problem);
    return layerView.values(mech.solveSteps([driverArray(q)])[0]);
  }

  function sceneJSON() {
    return JSON.parse(JSON.stringify(model.scene));
  }

  function setJoint(name, x, y) {
    model.joints[name].at = [x, y];
    const rec = model.scene.joints.find((j) => j.name === name);
    rec.at = [x, y];
  }

  function moveJoint(name, x, y, tables = true) {
    // a drag: the joint's assembly position, with every joint at the same point
    if (!(name in model.joints)) throw new Error("no joint named " + JSON.stringify(name));
    if (model.joints[name].type === "cam")
      throw new Error("joint " + JSON.stringify(name) + " is a cam contact: its point lies on the " +
        "cam's profile, which is fixed data on the cam; it does not move");
    const moved = together(name);
    const pivot = moved.find((n) => gearPivots.has(n));
    if (pivot !== undefined)
      throw new Error("joint " + JSON.stringify(pivot) + " is a gear's pivot: its distance " +
        "from the meshing gear's pivot is the sum (or difference) of their pitch radii; it does not move");
    for (const n of moved) setJoint(n, x, y);
    rebuild(tables);
    return summary();
  }

  function together(name) {
    // the joint and every joint at the same point (a pin of three links is two joints)
    const at = model.joints[name].at;
    const L = mech !== null ? mech.L : 1.0;
    return model.order.filter((n) => {
      const p = model.joints[n].at;
      return n === name || Math.hypot(p[0] - at[0], p[1] - at[1]) <= COINCIDENT * L;
    });
  }

  function movable(name) {
    return model.joints[name].type !== "G" && model.joints[name].type !== "cam" &&
      !together(name).some((n) => gearPivots.has(n));
  }

  function summary() {
    const counts = {};
    for (const s of cycle) counts[s.status] = (counts[s.status] || 0) + 1;
    return { error: problem, counts: counts };
  }

  // -- drawing --------------------------------------------------------------------------
  function pose() {
    // what is drawn: the assembly configuration while editing, else the current step
    if (editing || mech === null) {
      const joints = {};
      for (const n of model.order) joints[n] = model.joints[n].at;
      return { status: "assembly", joints: joints, points: {}, X: null };
    }
    return cycle[index];
  }

  function fit() {
    let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
    const add = (p) => {
      if (!p || !Number.isFinite(p[0]) || !Number.isFinite(p[1])) return;
      x0 = Math.min(x0, p[0]); x1 = Math.max(x1, p[0]);
      y0 = Math.min(y0, p[1]); y1 = Math.max(y1, p[1]);
    };
    for (const n of model.order) add(model.joints[n].at);
    for (const s of cycle) {
      for (const p of Object.values(s.joints)) add(p);
      for (const p of Object.values(s.points)) add(p);
    }
    if (mech !== null && mech.extent) mech.extent(cycle).forEach(add);
    for (const g of gears()) {
      const c = model.joints[g.pivot].at;
      add([c[0] - g.r, c[1] - g.r]); add([c[0] + g.r, c[1] + g.r]);
    }
    const w = canvas.width, h = canvas.height;
    const span = Math.max(x1 - x0, y1 - y0, 1e-9);
    const s = 0.85 * Math.min(w / Math.max(x1 - x0, 0.05 * span), h / Math.max(y1 - y0, 0.05 * span));
    view = { s: s, cx: (x0 + x1) / 2, cy: (y0 + y1) / 2 };
  }

  function toCanvas(p) {
    return [canvas.width / 2 + (p[0] - view.cx) * view.s, canvas.height / 2 - (p[1] - view.cy) * view.s];
  }

  function toWorld(px, py) {
    return [view.cx + (px - canvas.width / 2) / view.s, view.cy - (py - canvas.height / 2) / view.s];
  }

  function gears() {
    // each gear of a mesh: its link, pitch radius and pivot joint
    const out = [];
    model.scene.joints.forEach((j) => {
      if (j.type !== "G") return;
      const pivots = model.joints[j.name].pivots;
      j.links.forEach((link, i) => out.push({ link: link, r: j.radii[i], pivot: pivots[i] }));
    });
    return out;
  }

  function rotation(link, state) {
    if (link === "ground" || !state.X || mech === null) return 0.0;
    return state.X[mech.angleOf[link]] - mech.geometry.frames[link].theta0;
  }

  function hull(pts) {
    const p = pts.slice().sort((a, b) => a[0] - b[0] || a[1] - b[1]);
    if (p.length < 3) return p;
    const cross = (o, a, b) => (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]);
    const lower = [], upper = [];
    for (const q of p) {
      while (lower.length >= 2 && cross(lower[lower.length - 2], lower[lower.length - 1], q) <= 0) lower.pop();
      lower.push(q);
    }
    for (const q of p.slice().reverse()) {
      while (upper.length >= 2 && cross(upper[upper.length - 2], upper[upper.length - 1], q) <= 0) upper.pop();
      upper.push(q);
    }
    return lower.slice(0, -1).concat(upper.slice(0, -1));
  }

  function draw() {
    if (view === null) fit();
    const w = canvas.width, h = canvas.height;
    ctx.fillStyle = "#fbfbf8";
    ctx.fillRect(0, 0, w, h);
    drawGrid();
    drawTraces();
    const st = pose();
    let jp = st.joints;
    if (st.status === "unassemblable") {
      // the frame says so; the ground stays drawn, nothing that moves is
      ctx.fillStyle = "#b00020";
      ctx.font = "16px sans-serif";
      ctx.fillText("this step cannot be assembled: " + (st.message || ""), 16, 28);
      jp = {};
      for (const n of model.order)
        if (model.joints[n].links.includes("ground") && model.joints[n].type !== "G") jp[n] = model.joints[n].at;
    }
    const lw = Math.max(3, Math.min(10, 0.012 * Math.min(w, h)));
    // gears: pitch circles with a spoke that turns with the gear
    for (const g of gears()) {
      const c = jp[g.pivot];
      if (!c) continue;
      const [px, py] = toCanvas(c);
      const colour = g.link === "ground" ? "#888" : linkColour[g.link];
      ctx.strokeStyle = colour; ctx.lineWidth = 2;
      ctx.beginPath(); ctx.arc(px, py, g.r * view.s, 0, 2 * Math.PI); ctx.stroke();
      if (g.link !== "ground") {
        const a = rotation(g.link, st);
        ctx.beginPath(); ctx.moveTo(px, py);
        ctx.lineTo(px + g.r * view.s * Math.cos(a), py - g.r * view.s * Math.sin(a)); ctx.stroke();
      }
    }
    // cams: the profile on the cam, the follower's roller or face (cams.js)
    const camDrawn = mech !== null && mech.draw && st.status !== "unassemblable";
    if (camDrawn) mech.draw(ctx, st, toCanvas, view.s, (link) => linkColour[link], cycle);
    const extra = camDrawn ? mech.hullPoints(st) : {};
    // links: the hull of their joints (a cam's contact point: the follower's element point)
    for (const link of Object.keys(model.links)) {
      const pts = model.order.filter((n) => model.joints[n].links.includes(link) &&
        model.joints[n].type !== "G" && model.joints[n].type !== "cam")
        .map((n) => jp[n]).concat(extra[link] || []).filter((p) => p && Number.isFinite(p[0]));
      if (!pts.length) continue;
      const hp = hull(pts).map(toCanvas);
      ctx.strokeStyle = linkColour[link];
      ctx.fillStyle = linkColour[link] + "33";
      ctx.lineWidth = lw; ctx.lineJoin = "round"; ctx.lineCap = "round";
      ctx.beginPath();
      hp.forEach(([x, y], i) => (i ? ctx.lineTo(x, y) : ctx.moveTo(x, y)));
      if (hp.length > 2) { ctx.closePath(); ctx.fill(); }
      ctx.stroke();
    }
    // prismatic joints: the slide and the block
    for (const n of model.order) {
      const j = model.joints[n];
      if (j.type !== "P" || !jp[n]) continue;
      const a = j.axis + rotation(j.links[0], st);
      const [px, py] = toCanvas(jp[n]);
      const half = 0.25 * (mech ? mech.L : 1) * view.s;
      ctx.strokeStyle = "#555"; ctx.lineWidth = 1.5; ctx.setLineDash([6, 4]);
      ctx.beginPath(); ctx.moveTo(px - half * Math.cos(a), py + half * Math.sin(a));
      ctx.lineTo(px + half * Math.cos(a), py - half * Math.sin(a)); ctx.stroke();
      ctx.setLineDash([]);
      ctx.save(); ctx.translate(px, py); ctx.rotate(-a);
      ctx.fillStyle = "#ddd"; ctx.strokeStyle = "#333"; ctx.lineWidth = 2;
      ctx.fillRect(-2.2 * lw, -1.4 * lw, 4.4 * lw, 2.8 * lw); ctx.strokeRect(-2.2 * lw, -1.4 * lw, 4.4 * lw, 2.8 * lw);
      ctx.restore();
    }
    // ground pivots and joints
    for (const n of model.order) {
      const j = model.joints[n];
      if (j.type === "G" || !jp[n]) continue;
      const [px, py] = toCanvas(jp[n]);
      if (j.links.includes("ground") && j.type === "R") {
        ctx.fillStyle = "#666";
        ctx.beginPath(); ctx.moveTo(px, py); ctx.lineTo(px - 1.6 * lw, py + 2.6 * lw);
        ctx.lineTo(px + 1.6 * lw, py + 2.6 * lw); ctx.closePath(); ctx.fill();
        ctx.strokeStyle = "#666"; ctx.lineWidth = 1;
        for (let k = -2; k <= 2; k++) {
          ctx.beginPath(); ctx.moveTo(px + k * 0.8 * lw, py + 2.6 * lw);
          ctx.lineTo(px + k * 0.8 * lw - 0.7 * lw, py + 3.4 * lw); ctx.stroke();
        }
      }
      if (j.type === "R") {
        ctx.fillStyle = "#fff"; ctx.strokeStyle = "#222"; ctx.lineWidth = 2;
        ctx.beginPath(); ctx.arc(px, py, 0.75 * lw, 0, 2 * Math.PI); ctx.fill(); ctx.stroke();
      }
    }
    // labels last, with a light halo, so that no link hides them
    // (joints drawn at one point share one label: "O, O4")
    ctx.font = "bold 13px sans-serif"; ctx.lineWidth = 4; ctx.strokeStyle = "#fbfbf8"; ctx.fillStyle = "#222";
    const labels = [];
    for (const n of model.order) {
      if (model.joints[n].type === "G" || !jp[n]) continue;
      const [px, py] = toCanvas(jp[n]);
      const near = labels.find((l) => Math.hypot(l.px - px, l.py - py) < 1.0);
      if (near) near.text += ", " + n; else labels.push({ px: px, py: py, text: n });
    }
    for (const l of labels) {
      ctx.strokeText(l.text, l.px + 1.1 * lw, l.py - 1.1 * lw);
      ctx.fillText(l.text, l.px + 1.1 * lw, l.py - 1.1 * lw);
    }
    if (editing) { // the handles a drag takes
      ctx.strokeStyle = "#0a66c2"; ctx.lineWidth = 2;
      for (const n of model.order) {
        if (!movable(n) || !jp[n]) continue;
        const [px, py] = toCanvas(jp[n]);
        ctx.beginPath(); ctx.arc(px, py, 1.5 * lw, 0, 2 * Math.PI); ctx.stroke();
      }
    }
    for (const [n, p] of Object.entries(st.points)) {
      const [px, py] = toCanvas(p);
      ctx.fillStyle = "#000";
      ctx.beginPath(); ctx.arc(px, py, 0.45 * lw, 0, 2 * Math.PI); ctx.fill();
      ctx.font = "12px sans-serif"; ctx.lineWidth = 4; ctx.strokeStyle = "#fbfbf8";
      ctx.strokeText(n, px + lw, py + lw); ctx.fillText(n, px + lw, py + lw);
    }
    if (!editing) layerView.draw(index);
  }

  function drawGrid() {
    // a light grid of round lengths, with its spacing written in a corner
    const span = canvas.width / view.s;
    const step = Math.pow(10, Math.floor(Math.log10(span / 4)));
    const [x0, y1] = toWorld(0, 0), [x1, y0] = toWorld(canvas.width, canvas.height);
    ctx.strokeStyle = "#ececec"; ctx.lineWidth = 1;
    for (let x = Math.ceil(x0 / step) * step; x <= x1; x += step) {
      const [px] = toCanvas([x, 0]);
      ctx.beginPath(); ctx.moveTo(px, 0); ctx.lineTo(px, canvas.height); ctx.stroke();
    }
    for (let y = Math.ceil(y0 / step) * step; y <= y1; y += step) {
      const [, py] = toCanvas([0, y]);
      ctx.beginPath(); ctx.moveTo(0, py); ctx.lineTo(canvas.width, py); ctx.stroke();
    }
    ctx.fillStyle = "#999"; ctx.font = "12px sans-serif";
    ctx.fillText("grid " + step.toPrecision(1) + " m", 10, canvas.height - 10);
  }

  function drawTraces() {
    if (!cycle.length) return;
    const traced = model.order.filter((n) => !model.joints[n].links.includes("ground") && model.joints[n].type !== "G");
    const series = traced.map((n) => ({ colour: "#9aa", get: (s) => s.joints[n] }))
      .concat(model.points.map((p) => ({ colour: "#c05", get: (s) => s.points[p.name] })));
    for (const tr of series) {
      ctx.strokeStyle = tr.colour; ctx.lineWidth = tr.colour === "#c05" ? 1.8 : 1.0;
      ctx.beginPath();
      let open = false;
      for (const s of cycle) {
        const p = s.status === "unassemblable" ? null : tr.get(s);
        if (!p) { open = false; continue; }
        const [x, y] = toCanvas(p);
        if (open) ctx.lineTo(x, y); else ctx.moveTo(x, y);
        open = true;
      }
      ctx.stroke();
    }
  }

  // -- controls ---------------------------------------------------------------------------
  function driverText(k) {
    return drivers.map((d, i) => {
      const v = sweep[k][i];
      return d.joint + " = " + (d.kind === "R" ? (v * 180 / Math.PI).toFixed(1) + "°" : v.toFixed(4) + " m");
    }).join(", ");
  }

  function showStatus() {
    const el = $("status");
    if (problem !== null) {
      el.className = "bad";
      el.textContent = problem;
      return;
    }
    const s = summary().counts;
    const st = editing ? null : cycle[index];
    const parts = Object.entries(s).map(([k, v]) => v + " " + k);
    el.className = st && st.status !== "ok" ? "bad" : "";
    el.textContent = (editing ? "editing the assembly configuration" :
      "step " + (index + 1) + "/" + steps + ": " + driverText(index) + " · " + st.status +
      (st.message ? " (" + st.message + ")" : "")) + " · sweep: " + parts.join(", ");
    $("slider").value = String(index);
  }

  function cell(text) {
    const td = document.createElement("td");
    td.textContent = text; // scene names are text, never markup
    return td;
  }

  function fmt(v) { return Number(v.toPrecision(6)).toString(); }

  function refreshTables() {
    const jt = $("joints");
    jt.innerHTML = "";
    for (const n of model.order) {
      const j = model.joints[n];
      const tr = document.createElement("tr");
      tr.append(cell(n), cell(j.type));
      [0, 1].forEach((c) => {
        const td = document.createElement("td");
        const inp = document.createElement("input");
        inp.type = "number"; inp.step = "any"; inp.value = fmt(j.at[c]);
        if (!movable(n)) {
          inp.disabled = true;
          inp.title = j.type === "cam" ? "a cam contact: on the cam's profile, fixed data on the cam" :
            "a gear's pivot (or a mesh): fixed by the pitch radii";
        }
        inp.setAttribute("aria-label", n + (c ? " y" : " x"));
        inp.addEventListener("change", () => {
          const v = parseFloat(inp.value);
          if (!Number.isFinite(v)) return;
          const p = j.at.slice(); p[c] = v;
          moveJoint(n, p[0], p[1]);
        });
        td.appendChild(inp); tr.appendChild(td);
      });
      jt.appendChild(tr);
    }
    const lt = $("lengths");
    lt.innerHTML = "";
    for (const link of ["ground"].concat(Object.keys(model.links))) {
      const js = model.order.filter((n) => model.joints[n].links.includes(link) && model.joints[n].type !== "G");
      for (let a = 0; a < js.length; a++) {
        for (let b = a + 1; b < js.length; b++) {
          const A = model.joints[js[a]].at, B = model.joints[js[b]].at;
          const d = Math.hypot(B[0] - A[0], B[1] - A[1]);
          if (d <= 1e-12 || !movable(js[b])) continue;
          const tr = document.createElement("tr");
          tr.append(cell(link), cell(js[a] + "–" + js[b]));
          const td = document.createElement("td");
          const inp = document.createElement("input");
          inp.type = "number"; inp.step = "any"; inp.min = "0"; inp.value = fmt(d);
          inp.setAttribute("aria-label", "length " + js[a] + "–" + js[b]);
          inp.addEventListener("change", () => {
            const v = parseFloat(inp.value);
            if (!(v > 0)) return;
            // the second joint moves along the line from the first
            moveJoint(js[b], A[0] + (B[0] - A[0]) * v / d, A[1] + (B[1] - A[1]) * v / d);
          });
          td.appendChild(inp); tr.appendChild(td); lt.appendChild(tr);
        }
      }
    }
  }

  function tick(t) {
    if (playing && !editing && cycle.length && lastTime !== null) {
      const adv = ((t - lastTime) / 1000) * speed * (steps / CYCLE_SECONDS);
      tick.acc = (tick.acc || 0) + adv;
      const whole = Math.floor(tick.acc);
      if (whole > 0) {
        tick.acc -= whole;
        index = (index + whole) % steps;
        showStatus();
      }
    }
    lastTime = t;
    draw();
    requestAnimationFrame(tick);
  }

  function pick(ev) {
    const r = canvas.getBoundingClientRect();
    const px = (ev.clientX - r.left) * (canvas.width / r.width);
    const py = (ev.clientY - r.top) * (canvas.height / r.height);
    return [px, py];
  }

  function setup() {
    $("title").textContent = model.name;
    if (model.cams) { // what a drag can do to a cam mechanism, said where the hints are
      const note = document.createElement("p");
      note.className = "hint"; note.id = "cam-note";
      note.textContent = "Cam contacts (" + Object.keys(model.cams).join(", ") + "): the cam's " +
        "profile is fixed data on the cam, so the contact point does not move and no length " +
        "edits the profile; a dragged ground pivot re-solves the sweep (the cam turns about " +
        "another point of its profile, or the follower turns or slides elsewhere). Edit a " +
        "profile in the scene file.";
      document.querySelector("aside > .hint").after(note); // under the joints' hint
      document.querySelector("header .by").textContent = "solved in this page by linkage_sym's " +
        "numeric cam solver, ported to JavaScript (the symbolic layer derives no cam contact)";
    }
    const slider = $("slider");
    slider.max = String(steps - 1);
    slider.addEventListener("input", () => { index = parseInt(slider.value, 10); playing = false; $("play").textContent = "Play"; showStatus(); });
    $("play").addEventListener("click", () => {
      playing = !playing;
      $("play").textContent = playing ? "Pause" : "Play";
    });
    $("speed").addEventListener("change", () => { speed = parseFloat($("speed").value); });
    $("edit").addEventListener("change", () => {
      editing = $("edit").checked;
      $("play").disabled = editing;
      showStatus();
    });
    $("download").addEventListener("click", () => {
      const blob = new Blob([JSON.stringify(sceneJSON(), null, 2) + "\n"], { type: "application/json" });
      const a = document.createElement("a");
      a.href = URL.createObjectURL(blob);
      a.download = (model.name || "scene").replace(/[^A-Za-z0-9_.-]+/g, "_") + ".json";
      document.body.appendChild(a); a.click(); a.remove();
      setTimeout(() => URL.revokeObjectURL(a.href), 1000);
    });
    canvas.addEventListener("pointerdown", (ev) => {
      const [px, py] = pick(ev);
      // while editing every joint's assembly position; otherwise the ground pivots
      // (where the drawn position is the assembly one)
      let best = null, bestD = 12;
      for (const n of model.order) {
        const j = model.joints[n];
        if (!movable(n)) continue;
        if (!editing && !(j.links.includes("ground"))) continue;
        const [x, y] = toCanvas(j.at);
        const d = Math.hypot(x - px, y - py);
        if (d < bestD) { best = n; bestD = d; }
      }
      if (best !== null) { dragging = best; canvas.setPointerCapture(ev.pointerId); }
    });
    canvas.addEventListener("pointermove", (ev) => {
      if (dragging === null) return;
      const [px, py] = pick(ev);
      const keep = view;
      const [x, y] = toWorld(px, py);
      moveJoint(dragging, x, y, false);
      view = keep; // the view stays put while dragging
    });
    canvas.addEventListener("pointerup", () => {
      if (dragging !== null) { refreshTables(); layerView.reset(); }
      dragging = null; view = null;
    });
    rebuild();
    requestAnimationFrame(tick);
  }

  window.linkageSym = {
    solve: solve,
    moveJoint: (name, x, y) => moveJoint(name, x, y),
    scene: sceneJSON,
    summary: summary,
    warnings: () => warningView.value(),
    layers: layers,
    setLayer: (name, on) => layerView.setLayer(name, on),
    layerScales: () => layerView.scales(),
    layersAvailable: () => layerView.available(),
    step: (k) => { index = k; playing = false; showStatus(); draw(); },
    canvasPoint: (name) => { if (view === null) fit(); return toCanvas(model.joints[name].at); },
  };
  setup();
})();
