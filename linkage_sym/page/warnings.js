// The page's warnings panel: what the Python run of the scene as built said (BUILT, embedded
// by linkage_sym.page.page_html; null when the page was written without a run), and after
// every change what the page's own evaluator finds for the current geometry, worded here
// from its solution as the Python messages word it (no Python code runs in the page):
//
// - how many steps cannot be assembled, how many are singular, and which
//   (linkage_sym.page.warnings.status_lines; steps named as numeric.results.wording.steps_text);
// - each passage of a dyad of two slides' joint through infinity between two points of the
//   solving path (numeric.continuation.messages.parallel_note, reported at the step that
//   sees it as step_warnings does; driver values as wording.driver_number words them).
//
// The run's other warnings (condition numbers of ok steps, force superpositions, friction,
// gear flanks, the Newton groups' assembly-mode jumps, values left out of the file) the page
// does not compute: they are shown "from the scene as built", and greyed as possibly stale
// once the mechanism differs from it.
const PageWarnings = (function () {
  "use strict";
  const RAD_TO_DEG = 180.0 / Math.PI; // Python's math.degrees: x * (180 / pi)

  function stepsText(first, count) {
    // numeric.results.wording.steps_text: the first five, and how many more
    return first.slice(0, 5).join(", ") + (count > 5 ? " and " + (count - 5) + " more" : "");
  }

  function g6(v) {
    // Python's format(v, ".6g"): six significant digits, trailing zeros dropped, an
    // exponent (two digits at least) below 1e-4 or from 1e6
    if (v === 0) return Object.is(v, -0) ? "-0" : "0";
    if (!Number.isFinite(v)) return Number.isNaN(v) ? "nan" : (v > 0 ? "inf" : "-inf");
    const [mant, e] = v.toExponential(5).split("e");
    const exp = parseInt(e, 10);
    const strip = (t) => (t.includes(".") ? t.replace(/0+$/, "").replace(/\.$/, "") : t);
    if (exp < -4 || exp >= 6)
      return strip(mant) + "e" + (exp < 0 ? "-" : "+") + String(Math.abs(exp)).padStart(2, "0");
    return strip(v.toFixed(5 - exp));
  }

  function driverNumber(value, kind) {
    // numeric.results.wording.driver_number: an R driver's angle in degrees, a P driver's
    // slide in m; a value that shows as zero shows as 0
    let text = g6(kind === "R" ? value * RAD_TO_DEG : value);
    if (Number(text) === 0) text = text.replace(/^-/, "");
    return text + (kind === "R" ? "°" : " m");
  }

  function driverValues(drivers, Q) {
    return drivers.map((d, i) => d.joint + " = " + driverNumber(Q[i], d.kind)).join(", ");
  }

  function statusLines(statuses) {
    const which = (s) => statuses.map((v, k) => (v === s ? k : -1)).filter((k) => k >= 0);
    const out = [];
    const bad = which("unassemblable"), sing = which("singular");
    if (bad.length) out.push(bad.length + " step(s) cannot be assembled (steps " + stepsText(bad, bad.length) + ")");
    if (sing.length) out.push(sing.length + " step(s) are singular positions (steps " +
      stepsText(sing, sing.length) + "): their velocities and accelerations have no unique solution");
    return out;
  }

  function passageText(p, run, drivers) {
    // the first step at or after the path point past the passage (step_warnings)
    const at = run.at;
    let k = 0;
    while (k < at.length && at[k] < p.after) k++;
    if (k >= at.length) return null; // on the way to the first step only: no step sees it
    let where = at[k] === p.after ? "step " + k : "step " + k + " (reached from step " + (k - 1) + ")";
    if (k === 0 && at[0] !== p.after) where = "step 0 (reached from the assembly configuration)";
    return p.title + ": the slides of joints " + p.slides[0] + " and " + p.slides[1] +
      " become parallel between " + driverValues(drivers, run.path[p.before]) + " and " +
      driverValues(drivers, run.path[p.after]) + ": joint " + p.joint +
      " passes through infinity there; at " + where + " it is on the far side of its slides";
  }

  function found(run, drivers) {
    // the page's own warnings of a solved sweep {steps, path, at, passages}
    const out = statusLines(run.steps.map((s) => s.status));
    for (const p of run.passages) {
      const text = passageText(p, run, drivers);
      if (text !== null) out.push(text);
    }
    return out;
  }

  function create(opts) {
    // opts: {built (list or null), drivers, panel, list, source}
    const built = opts.built;
    let shown = [], own = [], changed = false;

    function update(ownNow, changedNow) {
      own = ownNow; changed = changedNow;
      if (built !== null && !changed) {
        // the scene as built: the Python run's, each saying whether the page recomputes it
        shown = built.map((t) => ({ text: t, origin: "python", recomputed: own.includes(t), stale: false }));
      } else {
        shown = own.map((t) => ({ text: t, origin: "page", recomputed: true, stale: false }));
        if (built !== null)
          for (const t of built) if (!own.includes(t) && !isPageKind(t))
            shown.push({ text: t, origin: "python", recomputed: false, stale: true });
      }
      render();
    }

    function isPageKind(text) {
      // a line of a kind the page recomputes, no longer found: it no longer holds
      return /^\d+ step\(s\) (cannot be assembled|are singular positions) \(steps /.test(text) ||
        / passes through infinity there; at step \d+/.test(text);
    }

    function render() {
      opts.panel.hidden = shown.length === 0;
      opts.list.innerHTML = "";
      for (const w of shown) {
        const li = document.createElement("li");
        if (w.stale) li.className = "stale";
        const span = document.createElement("span");
        span.textContent = w.text; // scene names are text, never markup
        li.appendChild(span);
        const tag = w.origin === "page" ? null : w.stale ? "for the scene as built: may no longer hold" :
          w.recomputed ? "the page's evaluator finds it too" : "from the scene as built; the page does not recompute it";
        if (tag !== null) {
          const t = document.createElement("span");
          t.className = "tag"; t.textContent = "(" + tag + ")";
          li.appendChild(t);
        }
        opts.list.appendChild(li);
      }
      opts.source.textContent = built !== null && !changed ?
        "From linkage_sym's Python run of the scene this page was built from. After a change " +
        "(a drag, a typed value) the page lists what its own evaluator finds: steps that cannot " +
        "be assembled or are singular, joints passing through infinity." :
        (own.length ? "Found by this page's evaluator for the current geometry: steps that " +
          "cannot be assembled or are singular, joints passing through infinity." :
          "This page's evaluator finds no step that cannot be assembled or is singular and no " +
          "joint passing through infinity for the current geometry.") +
        (shown.some((w) => w.stale) ? " Greyed: the Python run's other warnings for the scene " +
          "as built, which the page cannot recompute." : "");
    }

    return {
      update: update,
      value: () => ({ shown: shown.map((w) => Object.assign({}, w)), page: own.slice(),
        built: built === null ? null : built.slice(), changed: changed }),
    };
  }

  return { create: create, found: found, driverNumber: driverNumber, stepsText: stepsText };
})();
