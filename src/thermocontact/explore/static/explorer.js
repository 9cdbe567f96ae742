// thermocontact explore: the page.  It holds the state (its fields, mirrored in the
// URL's query string, whose keys are the keyword names of thermocontact.contact), asks
// the server for each view and draws it in SVG.  It computes nothing: every number
// shown is the server's, carried with its record key and full-precision value
// (data-quantity, data-value).
"use strict";
(() => {
  // The fields, from the server (its adapter names them): the contact's (the keyword
  // names of thermocontact.contact), the closure by temperatures among them, the other
  // tabs', and those always written in the URL (the others when not their default).
  let POINT = [], TEMPERATURES = [], EXTRA = [], ALWAYS = [];
  const TABS = ["contact", "map", "tei", "transient"];
  const SVG = "http://www.w3.org/2000/svg";
  const $ = (id) => document.getElementById(id);
  const field = (name) => document.querySelector(`#inputs [name="${name}"]:not([type=radio]),` +
                                                 `[form=inputs][name="${name}"]`);
  let defaults = {};
  let tab = "contact";
  let contact = null;          // the last contact view drawn
  const jobs = {map: null, transient: null};   // {id, key, view}
  const pending = {};          // kind -> AbortController of the request in flight
  let debounce = null;

  // -- state and URL ---------------------------------------------------------------
  const closure = () => document.querySelector("input[name=closure]:checked").value;

  function readState() {
    const s = {};
    for (const name of [...POINT, ...EXTRA]) {
      const f = field(name);
      s[name] = name === "dundurs" ? (f.checked ? "true" : "false") : f.value.trim();
    }
    if (closure() === "lam") TEMPERATURES.forEach((n) => delete s[n]);
    else delete s.lam;
    return s;
  }

  function setClosure(which) {
    document.querySelector(`input[name=closure][value=${which}]`).checked = true;
    document.querySelectorAll("[data-closure]").forEach((el) => {
      el.hidden = el.dataset.closure !== which;
    });
  }

  function writeFields(values) {
    for (const name of [...POINT, ...EXTRA]) {
      const f = field(name);
      const v = name in values ? values[name] : (defaults[name] ?? "");
      if (name === "dundurs") f.checked = !["false", "0", "no"].includes(String(v).toLowerCase());
      else f.value = v;
    }
    setClosure(TEMPERATURES.some((n) => values[n]) ? "temperatures" : "lam");
  }

  function query(s, extra = {}) {
    const p = new URLSearchParams();
    for (const [k, v] of Object.entries({...s, ...extra})) p.set(k, v);
    return p.toString();
  }

  function writeURL(s) {
    const p = new URLSearchParams();
    for (const [k, v] of Object.entries(s)) {
      if (ALWAYS.includes(k) ? v !== "" : v !== (defaults[k] ?? "")) p.set(k, v);
    }
    if (tab !== "contact") p.set("tab", tab);
    history.replaceState(null, "", "?" + p.toString());
  }

  // -- errors ----------------------------------------------------------------------
  // Each kind of request (contact, tei, code, map, transient) reports the errors of its
  // last answer; the page shows them all, each next to its field, so that one answer's
  // success does not hide another's complaint.
  const errorsBy = {};

  function report(kind, error) {
    if (error) errorsBy[kind] = error;
    else delete errorsBy[kind];
    for (const name of [...POINT, ...EXTRA]) {
      const span = document.querySelector(`[data-error-for="${name}"]`);
      if (span) span.textContent = "";
      const f = field(name);
      if (f) f.removeAttribute("aria-invalid");
    }
    const general = new Set();
    for (const e of Object.values(errorsBy)) {
      let placed = false;
      for (const [name, message] of Object.entries(e.fields || {})) {
        const span = document.querySelector(`[data-error-for="${name}"]`);
        if (!span) continue;
        span.textContent = message;
        field(name).setAttribute("aria-invalid", "true");
        placed = true;
      }
      if (!placed) general.add(e.message);
    }
    $("general").textContent = [...general].join("; ");
  }

  async function ask(kind, url, options = {}) {
    // One request of each kind in flight: a newer one aborts the older.
    if (pending[kind]) pending[kind].abort();
    const ctrl = new AbortController();
    pending[kind] = ctrl;
    try {
      const r = await fetch(url, {...options, signal: ctrl.signal});
      const body = await r.json();
      return ctrl === pending[kind] ? body : null;
    } catch (e) {
      if (e.name === "AbortError") return null;
      return {error: {message: `the server did not answer (${e.message})`, fields: {}}};
    }
  }

  // -- numbers and verdicts ----------------------------------------------------------
  function number(n) {
    const span = document.createElement("span");
    span.className = "number";
    span.dataset.quantity = n.key;
    span.dataset.value = n.value;
    span.textContent = n.text;
    return span;
  }

  function renderNumbers(dl, numbers) {
    dl.replaceChildren();
    for (const n of numbers) {
      const dt = document.createElement("dt");
      dt.textContent = n.label;
      const dd = document.createElement("dd");
      dd.append(number(n));
      dl.append(dt, dd);
    }
  }

  function badge(ok, key, value, text) {
    const span = document.createElement("span");
    span.className = "verdict" + (ok ? "" : " no");
    span.dataset.quantity = key;
    span.dataset.value = value;
    span.textContent = text;
    return span;
  }

  function renderVerdicts(div, v) {
    div.replaceChildren();
    const valid = v.valid.value === "True";
    div.append(badge(valid, "valid", v.valid.value,
                     valid ? "valid single patch"
                       : "no valid single patch" + (v.valid.reason ? `: ${v.valid.reason}` : "")));
    const applicable = v.applicable.value === "True";
    div.append(badge(applicable, "applicable", v.applicable.value,
                     applicable ? "the theory applies" : "the theory does not apply"));
    if (v.converged.value !== "None") {
      div.append(badge(v.converged.value === "True", "converged", v.converged.value,
                       v.converged.value === "True" ? "error target met" : "error target not met"));
    }
    if (v.branches !== 1) {
      div.append(badge(v.branches > 0, "branches", String(v.branches),
                       `${v.branches} half-widths carry the load (the first valid shown)`));
    }
    const notes = [...(v.applicable.reasons || [])];
    if (v.message) notes.push(v.message);
    if (v.under_limits) {
      ["cylinder", "half-plane"].forEach((body, i) => {
        if (v.under_limits[i] === false) notes.push(`the ${body} is over its temperature limit`);
      });
    }
    if (notes.length) {
      const p = document.createElement("p");
      p.className = "reasons";
      p.textContent = notes.join("; ");
      div.append(p);
    }
  }

  // -- plots -------------------------------------------------------------------------
  function svgEl(tag, attrs, parent) {
    const e = document.createElementNS(SVG, tag);
    for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
    if (parent) parent.append(e);
    return e;
  }

  function extent(arrays, log) {
    let lo = Infinity, hi = -Infinity;
    for (const a of arrays) for (const v of a) {
      if (v === null || !isFinite(v) || (log && v <= 0)) continue;
      lo = Math.min(lo, v); hi = Math.max(hi, v);
    }
    if (!isFinite(lo)) return [log ? 1 : 0, log ? 10 : 1];
    if (lo === hi) return log ? [lo / 2, hi * 2] : [lo - 1, hi + 1];
    return [lo, hi];
  }

  function scale(domain, range, log) {
    const f = log ? Math.log10 : (v) => v;
    const [d0, d1] = [f(domain[0]), f(domain[1])];
    const s = (v) => range[0] + (f(v) - d0) / (d1 - d0) * (range[1] - range[0]);
    s.invert = (p) => {
      const t = d0 + (p - range[0]) / (range[1] - range[0]) * (d1 - d0);
      return log ? 10 ** t : t;
    };
    s.ticks = () => {
      if (log) {
        const out = [];
        for (let e = Math.ceil(d0 - 1e-9); e <= d1 + 1e-9; e++) out.push(10 ** e);
        return out;
      }
      const span = domain[1] - domain[0];
      const raw = span / 5, mag = 10 ** Math.floor(Math.log10(raw));
      const step = [1, 2, 5, 10].map((m) => m * mag).find((st) => span / st <= 6);
      const out = [];
      for (let v = Math.ceil(domain[0] / step) * step; v <= domain[1] + step * 1e-9; v += step) {
        out.push(Math.abs(v) < step * 1e-9 ? 0 : v);
      }
      return out;
    };
    return s;
  }

  function tickText(v, log) {
    if (log) {
      const e = Math.round(Math.log10(v));
      return Math.abs(e) <= 3 ? String(10 ** e >= 1 ? 10 ** e : Number((10 ** e).toPrecision(1))) : `1e${e}`;
    }
    return String(Number(v.toPrecision(6)));
  }

  // A plot: axes, grid, series (lines) and markers, in an SVG of viewBox 640 x h.
  function plot(svg, spec) {
    svg.replaceChildren();
    const [, , width, height] = svg.getAttribute("viewBox").split(" ").map(Number);
    const m = {l: 72, r: 16, t: 14, b: 44};
    const xs = spec.series.map((s) => s.x).concat(spec.extraX || []);
    const ys = spec.series.map((s) => s.y).concat(spec.extraY || []);
    const xd = spec.xdomain || extent(xs, spec.xlog);
    let yd = spec.ydomain || extent(ys, spec.ylog);
    if (!spec.ydomain && !spec.ylog && spec.yzero) yd = [Math.min(0, yd[0]), Math.max(0, yd[1])];
    const sx = scale(xd, [m.l, width - m.r], spec.xlog);
    const sy = scale(yd, [height - m.b, m.t], spec.ylog);
    const g = svgEl("g", {class: "axis"}, svg);
    for (const t of sx.ticks()) {
      if (t < Math.min(...xd) - 1e-12 * Math.abs(t) || t > Math.max(...xd) * (1 + 1e-12)) continue;
      svgEl("line", {class: "grid", x1: sx(t), x2: sx(t), y1: m.t, y2: height - m.b}, g);
      svgEl("text", {x: sx(t), y: height - m.b + 16, "text-anchor": "middle"}, g).textContent = tickText(t, spec.xlog);
    }
    for (const t of sy.ticks()) {
      if (t < Math.min(...yd) - 1e-12 * Math.abs(t) || t > Math.max(...yd) * (1 + 1e-12) + 1e-300) continue;
      svgEl("line", {class: "grid", x1: m.l, x2: width - m.r, y1: sy(t), y2: sy(t)}, g);
      svgEl("text", {x: m.l - 6, y: sy(t) + 4, "text-anchor": "end"}, g).textContent = tickText(t, spec.ylog);
    }
    svgEl("path", {d: `M${m.l},${m.t}V${height - m.b}H${width - m.r}`, fill: "none"}, g);
    svgEl("text", {x: (m.l + width - m.r) / 2, y: height - 6, "text-anchor": "middle"}, g).textContent = spec.xlabel;
    svgEl("text", {x: 14, y: (m.t + height - m.b) / 2, "text-anchor": "middle",
                   transform: `rotate(-90 14 ${(m.t + height - m.b) / 2})`}, g).textContent = spec.ylabel;
    if (spec.before) spec.before(svg, sx, sy);
    spec.series.forEach((s, i) => {
      let d = "", pen = "M";
      for (let k = 0; k < s.x.length; k++) {
        const ok = s.x[k] !== null && s.y[k] !== null && isFinite(s.y[k])
          && !(spec.xlog && s.x[k] <= 0) && !(spec.ylog && s.y[k] <= 0);
        if (!ok) { pen = "M"; continue; }
        d += `${pen}${sx(s.x[k]).toFixed(2)},${sy(s.y[k]).toFixed(2)}`;
        pen = "L";
      }
      svgEl("path", {d, class: `series s${s.color ?? i}` + (s.dashed ? " dashed" : "")}, svg);
    });
    // Legend, top right.
    spec.series.forEach((s, i) => {
      if (!s.label) return;
      const y = m.t + 12 + 16 * i, x = width - m.r - 190;
      svgEl("line", {x1: x, x2: x + 22, y1: y - 4, y2: y - 4, class: `series s${s.color ?? i}` + (s.dashed ? " dashed" : "")}, svg);
      svgEl("text", {x: x + 28, y}, svg).textContent = s.label;
    });
    const inside = (v, d) => v >= Math.min(...d) && v <= Math.max(...d);
    for (const mk of spec.markers || []) {
      if (mk.x == null || mk.y == null || !inside(mk.x, xd) || !inside(mk.y, yd)) continue;
      svgEl("circle", {cx: sx(mk.x), cy: sy(mk.y), r: 6, class: "marker"}, svg);
      if (mk.label) svgEl("text", {x: sx(mk.x) + 9, y: sy(mk.y) - 8}, svg).textContent = mk.label;
    }
    return {sx, sy, margin: m, width, height};
  }

  const times = (a, f) => a.map((v) => (v === null ? null : v * f));

  // -- the contact tab ---------------------------------------------------------------
  function renderContact(view) {
    contact = view;
    renderNumbers($("contact-numbers"), view.numbers);
    renderVerdicts($("contact-verdicts"), view.verdicts);
    const c = view.curves;
    const series = [];
    if (c.x) series.push({x: times(c.x, 1e3), y: times(c.pressure, 1e-6), label: "pressure"});
    series.push({x: times(c.hertz_x, 1e3), y: times(c.hertz_pressure, 1e-6), label: "Hertz", dashed: true, color: 3});
    const xdomain = extent(series.map((t) => t.x), false);   // both plots over one x
    plot($("plot-pressure"), {series, xdomain, xlabel: "x, mm (leading edge to the right)",
                              ylabel: "pressure, MPa", yzero: true});
    const temps = c.x ? [
      {x: times(c.x, 1e3), y: c.temperature_cylinder, label: "cylinder's surface", color: 1},
      {x: times(c.x, 1e3), y: c.temperature_half_plane, label: "half-plane's surface", color: 2, dashed: true},
    ] : [];
    plot($("plot-temperature"), {series: temps, xdomain, xlabel: "x, mm",
                                 ylabel: view.verdicts.temperatures});
    if (tab === "contact") setCode(view.code);
    const panel = $("panel-contact");
    panel.dataset.stale = "0";
    panel.dataset.ready = String(Number(panel.dataset.ready) + 1);
  }

  async function updateContact() {
    const s = readState();
    writeURL(s);
    setDownloads(s);
    $("busy").hidden = false;
    const panel = $("panel-contact");
    // Requests sent and the last answered (a test waits for the answer to its change).
    const n = Number(panel.dataset.sent || 0) + 1;
    panel.dataset.sent = String(n);
    const body = await ask("contact", "/api/contact?" + query(s));
    if (body === null) return;   // a newer request is in flight
    $("busy").hidden = true;
    if (body.error) {
      report("contact", body.error);
      panel.dataset.stale = "1";   // the last good picture kept
      panel.dataset.answered = String(n);
      return;
    }
    report("contact", null);
    renderContact(body);
    panel.dataset.answered = String(n);
    if (tab === "tei") updateTei();
    if (tab === "map") { drawMap(); if (jobs.map && jobs.map.key !== mapKey(s)) markMap(); }
    if (tab === "map" || tab === "transient") updateCode();
  }

  function update() {
    clearTimeout(debounce);
    updateContact();
  }

  // -- copy as code, downloads -----------------------------------------------------
  function setCode(code) {
    $("code-command").textContent = code.command;
    $("code-python").textContent = code.python;
  }

  async function updateCode() {
    if (tab === "contact" || tab === "tei") return;   // their views carry their code
    const body = await ask("code", "/api/code?" + query(readState(), {tab}));
    if (body === null) return;
    report("code", body.error || null);   // a bad axis or run field named
    if (!body.error) setCode(body);
  }

  function setDownloads(s) {
    $("download-json").href = "/download/point.json?" + query(s);
    $("download-csv").href = "/download/point.csv?" + query(s);
  }

  // -- the map -------------------------------------------------------------------------
  // What the map depends on: every input but the point's place on its axes.
  function mapKey(s) {
    const k = {...s};
    const axes = [s.x, s.y].map((a) => (a || "").split(":")[0]);
    const moving = (k.speed2 || "0").trim().replace(/[^0-9.eE+-].*$/, "");
    for (const a of axes) if (!(a === "speed" && Number(moving) !== 0)) delete k[a];
    for (const n of ["wavelength", "duration", "steps", "elements"]) delete k[n];
    return JSON.stringify(k);
  }

  function markMap() {
    $("map-status").textContent = "the inputs changed: compute the map again";
    $("panel-map").dataset.stale = "1";
  }

  async function startJob(kind) {
    const s = readState();
    const old = jobs[kind];
    if (old && !old.done) fetch(`/api/jobs/${old.id}/cancel`, {method: "POST"});
    const body = await ask(kind + "-start", "/api/jobs?" + query(s, {kind}), {method: "POST"});
    if (body === null) return;
    if (body.error) {
      report(kind, body.error);
      $(`${kind}-status`).textContent = body.error.message;
      return;
    }
    report(kind, null);
    jobs[kind] = {id: body.job, key: kind === "map" ? mapKey(s) : JSON.stringify(s), done: false};
    $(`${kind}-cancel`).disabled = false;
    $(`download-${kind}`).hidden = true;
    if (kind === "transient") updateCode();
    poll(kind, body.job);
  }

  async function poll(kind, id) {
    const job = jobs[kind];
    if (!job || job.id !== id) return;
    let r;
    try {
      r = await (await fetch(`/api/jobs/${id}`)).json();
    } catch (e) {
      $(`${kind}-status`).textContent = `the server did not answer (${e.message})`;
      return;
    }
    if (jobs[kind] !== job) return;
    const bar = $(`${kind}-progress`);
    if (r.error && !r.status) { $(`${kind}-status`).textContent = r.error.message; return; }
    bar.value = r.total > 0 ? r.done / r.total : 0;
    const secs = `${r.seconds.toFixed(1)} s`;
    if (r.status === "queued") $(`${kind}-status`).textContent = `waiting for a free core (${secs})`;
    if (r.status === "running") {
      let text = `starting (${secs})`;
      if (r.total > 0) {
        text = `computing: ${r.done} of ${r.total} (${secs})`;
        if (r.done > 0 && r.done < r.total) {
          const rate = r.done / r.seconds;   // steps of its progress per second
          text = `computing: ${r.done} of ${r.total}, ${Number(rate.toPrecision(2))} a second, ` +
                 `about ${Math.ceil((r.total - r.done) / rate)} s left (${secs})`;
        }
      }
      $(`${kind}-status`).textContent = text;
    }
    if (r.status === "queued" || r.status === "running") {
      setTimeout(() => poll(kind, id), 250);
      return;
    }
    job.done = true;
    $(`${kind}-cancel`).disabled = true;
    if (r.status === "done") {
      bar.value = 1;
      $(`${kind}-status`).textContent = `done in ${secs}`;
      job.view = r.view;
      const a = $(`download-${kind}`);
      a.href = `/download/${kind}.nc?job=${encodeURIComponent(id)}`;
      a.hidden = false;
      if (kind === "map") { $("panel-map").dataset.stale = "0"; drawMap(); }
      else drawTransient();
      const panel = $(`panel-${kind}`);
      panel.dataset.ready = String(Number(panel.dataset.ready) + 1);
    } else if (r.status === "failed") {
      $(`${kind}-status`).textContent = r.error.message;
      report(kind, r.error);
    } else {
      $(`${kind}-status`).textContent = "cancelled";
    }
  }

  async function cancelJob(kind) {
    const job = jobs[kind];
    if (!job || job.done) return;
    job.done = true;
    await fetch(`/api/jobs/${job.id}/cancel`, {method: "POST"});
    $(`${kind}-cancel`).disabled = true;
    $(`${kind}-status`).textContent = "cancelled";
    $(`${kind}-progress`).value = 0;
  }

  const UNITS = {load: [[1e6, "MN/m"], [1e3, "kN/m"], [1, "N/m"]],
                 speed: [[1, "m/s"], [1e-3, "mm/s"]],
                 radius: [[1, "m"], [1e-3, "mm"]]};
  const LABELS = {load: "load, N/m", speed: "speed, m/s", radius: "radius, m"};

  function withUnit(name, v) {
    const units = UNITS[name];
    const [f, u] = units.find(([f]) => v >= f) || units[units.length - 1];
    return `${Number((v / f).toPrecision(4))}${u}`;
  }

  function drawMap() {
    const job = jobs.map;
    const svg = $("plot-map");
    if (!job || !job.view) { svg.replaceChildren(); return; }
    const v = job.view;
    const edges = (a) => {
      const out = [a[0] ** 1.5 / a[1] ** 0.5];
      for (let i = 0; i + 1 < a.length; i++) out.push(Math.sqrt(a[i] * a[i + 1]));
      out.push(a[a.length - 1] ** 1.5 / a[a.length - 2] ** 0.5);
      return out;
    };
    const ex = edges(v.x.values), ey = edges(v.y.values);
    const inputs = contact ? contact.inputs : {};
    const here = [inputs[v.x.name], inputs[v.y.name]];
    const bx = (v.boundary_x || []).map((c) => c), by = (v.boundary_y || []).map((c) => c);
    const spec = {
      series: bx.map((c, i) => ({x: c, y: by[i], color: 0})),
      xlabel: LABELS[v.x.name], ylabel: LABELS[v.y.name], xlog: true, ylog: true,
      xdomain: [ex[0], ex[ex.length - 1]], ydomain: [ey[0], ey[ey.length - 1]],
      markers: [{x: here[0], y: here[1]}],
      before: (root, sx, sy) => {
        const g = svgEl("g", {class: "cells"}, root);
        v.verdict.forEach((row, j) => row.forEach((code, i) => {
          const r = svgEl("rect", {x: sx(ex[i]), y: sy(ey[j + 1]), width: sx(ex[i + 1]) - sx(ex[i]) + 0.5,
                                   height: sy(ey[j]) - sy(ey[j + 1]) + 0.5, class: `v${code}`}, g);
          svgEl("title", {}, r).textContent = `${withUnit(v.x.name, v.x.values[i])}, ` +
            `${withUnit(v.y.name, v.y.values[j])}: ${v.reasons[j][i]}`;
        }));
      },
    };
    const p = plot(svg, spec);
    svg.querySelectorAll("path.series").forEach((e) => e.setAttribute("class", "boundary"));
    svg.onclick = (ev) => {
      const pt = svg.createSVGPoint();
      pt.x = ev.clientX; pt.y = ev.clientY;
      const q = pt.matrixTransform(svg.getScreenCTM().inverse());
      if (q.x < p.margin.l || q.x > p.width - p.margin.r || q.y < p.margin.t || q.y > p.height - p.margin.b) return;
      field(v.x.name).value = withUnit(v.x.name, p.sx.invert(q.x));
      field(v.y.name).value = withUnit(v.y.name, p.sy.invert(q.y));
      update();
    };
  }

  // -- the TEI ---------------------------------------------------------------------------
  async function updateTei() {
    const s = readState();
    const body = await ask("tei", "/api/tei?" + query(s));
    if (body === null) return;
    const panel = $("panel-tei");
    report("tei", body.error || null);
    if (body.error) { panel.dataset.stale = "1"; return; }
    renderNumbers($("tei-numbers"), body.numbers);
    const div = $("tei-verdicts");
    div.replaceChildren();
    const vd = body.verdicts;
    div.append(badge(!vd.unstable, "stable_at_all_speeds", String(vd.stable_at_all_speeds),
                     vd.stable_at_all_speeds ? "stable at all speeds"
                       : vd.unstable ? "unstable at this sliding speed and wavelength"
                       : "stable at this sliding speed and wavelength"));
    const c = body.curves;
    plot($("plot-tei"), {series: [{x: c.wavelength, y: c.critical_speed, label: "critical speed"}],
                         extraY: [[c.point[1]]], xlog: true, ylog: true,
                         xlabel: "wavelength, m", ylabel: "speed, m/s",
                         markers: [{x: c.point[0], y: c.point[1], label: "sliding speed"}]});
    setCode(body.code);
    panel.dataset.stale = "0";
    panel.dataset.ready = String(Number(panel.dataset.ready) + 1);
  }

  // -- the transient ----------------------------------------------------------------------
  let frame = 0, playing = null;
  const COLORS = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];

  function color(t) {
    const u = Math.max(0, Math.min(1, t)) * (COLORS.length - 1);
    const i = Math.min(COLORS.length - 2, Math.floor(u)), f = u - i;
    return COLORS[i].map((c, k) => c + f * (COLORS[i + 1][k] - c));
  }

  function drawTransient() {
    const v = jobs.transient && jobs.transient.view;
    if (!v) return;
    const canvas = $("spacetime");
    const nt = v.time.length, nx = v.x.length;
    canvas.width = nx; canvas.height = nt;
    const ctx = canvas.getContext("2d");
    const img = ctx.createImageData(nx, nt);
    const pmax = Math.max(...v.pressure.flat().filter((p) => p !== null)) || 1;
    v.pressure.forEach((row, j) => row.forEach((p, i) => {
      const [r, g, b] = color((p || 0) / pmax);
      const k = 4 * (j * nx + i);
      img.data[k] = r; img.data[k + 1] = g; img.data[k + 2] = b; img.data[k + 3] = 255;
    }));
    ctx.putImageData(img, 0, 0);
    v.pmax = pmax; v.image = img;
    const slider = $("transient-frame");
    slider.max = String(nt - 1); slider.disabled = false; $("transient-play").disabled = false;
    showFrame(Math.min(frame, nt - 1));
  }

  function showFrame(j) {
    const v = jobs.transient.view;
    frame = j;
    $("transient-frame").value = String(j);
    const ctx = $("spacetime").getContext("2d");
    ctx.putImageData(v.image, 0, 0);
    ctx.fillStyle = "rgba(255,255,255,0.9)";
    ctx.fillRect(0, j, v.x.length, 1);
    const t = $("transient-time");
    t.dataset.quantity = "time";
    t.dataset.value = v.time_repr[j];
    t.textContent = `t = ${Number((v.time[j] * 1e3).toPrecision(4))} ms`;
    plot($("plot-frame"), {series: [{x: times(v.x, 1e3), y: times(v.pressure[j], 1e-6), label: "pressure"}],
                           xlabel: "x, mm", ylabel: "pressure, MPa", ydomain: [0, v.pmax * 1e-6 * 1.05]});
  }

  function play() {
    const v = jobs.transient && jobs.transient.view;
    if (!v) return;
    if (playing) { clearInterval(playing); playing = null; $("transient-play").textContent = "Play"; return; }
    $("transient-play").textContent = "Pause";
    if (frame >= v.time.length - 1) frame = 0;
    playing = setInterval(() => {
      if (frame >= v.time.length - 1) { play(); return; }
      showFrame(frame + 1);
    }, 60);
  }

  // -- tabs and wiring -------------------------------------------------------------------
  function selectTab(name) {
    tab = TABS.includes(name) ? name : "contact";
    for (const t of TABS) {
      $(`tab-${t}`).setAttribute("aria-selected", String(t === tab));
      $(`panel-${t}`).hidden = t !== tab;
    }
    writeURL(readState());
    if (tab === "contact" && contact) setCode(contact.code);
    if (tab === "tei") updateTei();
    if (tab === "map") {
      updateCode();
      if (!jobs.map) startJob("map");
      else if (jobs.map.key !== mapKey(readState())) markMap();
    }
    if (tab === "transient") updateCode();
  }

  async function start() {
    const setup = await (await fetch("/api/setup")).json();
    ({defaults, point: POINT, temperatures: TEMPERATURES, extra: EXTRA, always: ALWAYS} = setup);
    const list = $("materials");
    for (const name of [...setup.names, ...Object.keys(setup.aliases)].sort()) {
      const o = document.createElement("option");
      o.value = name;
      list.append(o);
    }
    const params = new URLSearchParams(location.search);
    const given = {};
    for (const [k, v] of params) if ([...POINT, ...EXTRA].includes(k)) given[k] = v;
    if (TEMPERATURES.some((n) => given[n]) && !("lam" in given)) given.lam = defaults.lam;
    writeFields(given);
    if (TEMPERATURES.some((n) => params.has(n))) setClosure("temperatures");
    document.querySelectorAll("input[name=closure]").forEach((r) =>
      r.addEventListener("change", () => { setClosure(closure()); update(); }));
    const form = $("inputs");
    form.addEventListener("submit", (e) => { e.preventDefault(); update(); });
    for (const name of [...POINT, ...EXTRA]) {
      const f = field(name);
      f.addEventListener("change", () => {
        if (["x", "y"].includes(name)) { if (jobs.map) markMap(); updateCode(); return; }
        if (["duration", "steps", "elements"].includes(name)) { updateCode(); return; }
        if (name === "wavelength") { updateTei(); return; }
        update();
      });
      f.addEventListener("input", () => {
        clearTimeout(debounce);
        if (POINT.includes(name)) debounce = setTimeout(update, 400);
      });
    }
    for (const t of TABS) $(`tab-${t}`).addEventListener("click", () => selectTab(t));
    $("map-compute").addEventListener("click", () => startJob("map"));
    $("map-cancel").addEventListener("click", () => cancelJob("map"));
    $("transient-run").addEventListener("click", () => startJob("transient"));
    $("transient-cancel").addEventListener("click", () => cancelJob("transient"));
    $("transient-play").addEventListener("click", play);
    $("transient-frame").addEventListener("input", (e) => showFrame(Number(e.target.value)));
    document.querySelectorAll("[data-copy]").forEach((b) => b.addEventListener("click", async () => {
      const text = $(b.dataset.copy).textContent;
      try { await navigator.clipboard.writeText(text); b.textContent = "Copied"; }
      catch (e) {
        const range = document.createRange();
        range.selectNodeContents($(b.dataset.copy));
        getSelection().removeAllRanges(); getSelection().addRange(range);
        b.textContent = "Selected";
      }
      setTimeout(() => { b.textContent = "Copy"; }, 1500);
    }));
    await updateContact();
    selectTab(params.get("tab") || "contact");
    document.body.dataset.started = "1";
  }

  start();
})();
