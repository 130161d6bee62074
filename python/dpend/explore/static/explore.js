// dpend explore: the page. The map (its file's values), a pixel's run (computed by
// the server with the map's settings), the pendulum animated, its angles, energy
// error and, with a second pixel, the separation of the two. Served by
// python/dpend/explore/_server.py; no other script, style or font is loaded.
"use strict";

// viridis, the palette of every map figure (scripts/plot/style.gp)
const VIRIDIS = ["#440154", "#482475", "#414487", "#355f8d", "#2a788e", "#21918c",
  "#22a884", "#44bf70", "#7ad151", "#bddf26", "#fde725"].map(hex =>
  [1, 3, 5].map(k => parseInt(hex.slice(k, k + 2), 16)));
const GREY = [140, 140, 140];
const WHITE = [255, 255, 255];
const COLOURS = ["#1f77b4", "#d62728"];          // run A, run B
const M = { left: 78, right: 120, top: 16, bottom: 52 };   // the map's margins [px]

const S = {
  meta: null, name: null, values: null, range: null,
  cursor: { i: 0, j: 0 }, runs: [null, null], pending: 0,
  frame: 0, playing: false, speed: 1, simTime: 0, last: null, tickets: [0, 0],
  timing: {},
};
window.dpendExplore = S;                          // for tests and benchmarks

const $ = id => document.getElementById(id);

function say(text, error) {
  const m = $("message");
  m.textContent = text;
  m.className = error ? "error" : "";
}

// -- numbers and names ------------------------------------------------------------
function fmt(x, digits) {
  if (x === null || x === undefined || !Number.isFinite(x)) return "none";
  return digits ? Number(x.toPrecision(digits)).toString() : String(x);
}
function axisLabel(axis, units) {
  const m = /^theta(\d+)$/.exec(axis);
  if (m) return `θ${m[1]} [rad] (from hanging)`;
  if (/^q\d+$/.test(axis)) return `${axis} [rad] (from horizontal)`;
  if (axis === "phi") return "φ [rad] (from horizontal)";
  return units && units !== "1" ? `${axis} [${units}]` : axis;
}
// A value as text: a number, or "nan"/"inf"/"-inf" as the server sends them (JSON has
// no such numbers); undefined: the run has no such value.
function valueText(x, map) {
  if (x === undefined) return "(not in the run)";
  if (x === "inf" || x === "-inf") return x;
  if (x === null || x === "nan" || !Number.isFinite(x)) {
    return map.scale === "flip" ? "no flip before t_end" : "none (not integrated or not finite)";
  }
  let text = `${String(x)} ${map.units === "1" ? "" : map.units}`.trim();
  if (map.units === "s") text += ` (${fmt(x / S.meta.tau, 6)} ${S.meta.tau_label})`;
  return text;
}

// -- requests -----------------------------------------------------------------------
async function get(url, kind) {
  const r = await fetch(url);
  if (!r.ok) {
    const line = (await r.text()).split("\n")[0];
    throw new Error(line || `${r.status} ${r.statusText}`);
  }
  return kind === "json" ? r.json() : r.arrayBuffer();
}

// -- the page's state in the URL: #map=NAME&i=I&j=J&i2=I&j2=J&t=SECONDS --------------
const PAGE_KEYS = ["map", "t", "i2", "j2", "speed"];
function readHash() {
  const h = new URLSearchParams(location.hash.slice(1));
  const state = {};
  for (const [k, v] of h) state[k] = v;
  return state;
}
function writeHash() {
  const h = new URLSearchParams();
  h.set("map", S.name);
  if (S.runs[0]) { h.set("i", S.runs[0].i); h.set("j", S.runs[0].j); }
  if (S.runs[1]) { h.set("i2", S.runs[1].i); h.set("j2", S.runs[1].j); }
  if (S.runs[0]) h.set("t", fmt(currentTime(), 6));
  if (S.speed !== 1) h.set("speed", S.speed);
  history.replaceState(null, "", "#" + h.toString());
}

// -- the map --------------------------------------------------------------------------
function mapInfo() { return S.meta.maps.find(m => m.name === S.name); }

function colourScale(map, values) {
  let lo = Infinity, hi = -Infinity;
  for (const v of values) if (Number.isFinite(v)) {
    const w = map.scale === "flip" ? v / S.meta.tau : v;
    if ((map.scale === "log" || map.scale === "flip") && !(w > 0)) continue;
    if (w < lo) lo = w; if (w > hi) hi = w;
  }
  if (map.scale === "flip") { lo = 0.3; hi = Math.max(S.meta.t_end / S.meta.tau, 0.31); }
  if (map.scale === "megno") { lo = 0; hi = 4; }
  if (map.scale === "log") { lo = Math.max(lo, 1e-16); if (!(hi > lo)) hi = lo * 10; }
  if (!Number.isFinite(lo)) { lo = 0; hi = 1; }
  if (!(hi > lo)) hi = lo + 1;
  const log = map.scale === "flip" || map.scale === "log";
  return { lo, hi, log };
}
function colourOf(v, map) {
  if (v === null || !Number.isFinite(v)) return map.scale === "flip" ? WHITE : GREY;
  const r = S.range;
  let w = map.scale === "flip" ? v / S.meta.tau : v;
  let f = r.log ? (Math.log(Math.max(w, r.lo)) - Math.log(r.lo)) / (Math.log(r.hi) - Math.log(r.lo))
    : (w - r.lo) / (r.hi - r.lo);
  f = Math.min(1, Math.max(0, f)) * (VIRIDIS.length - 1);
  const k = Math.min(Math.floor(f), VIRIDIS.length - 2), u = f - k;
  return VIRIDIS[k].map((c, n) => Math.round(c + u * (VIRIDIS[k + 1][n] - c)));
}
function plotBox() {
  const c = $("map");
  const w = c.width - M.left - M.right, h = c.height - M.top - M.bottom;
  const side = Math.min(w, h);
  return { x: M.left, y: M.top, w: side, h: side };
}
function niceTicks(lo, hi, n) {
  const span = hi - lo;
  if (!(span > 0)) return [lo];
  const step0 = span / n, p = Math.pow(10, Math.floor(Math.log10(step0)));
  const step = [1, 2, 2.5, 5, 10].map(s => s * p).find(s => s >= step0);
  const out = [];
  for (let k = Math.ceil(lo / step); k * step <= hi + 1e-9 * span; k++) out.push(k * step);
  return out;
}
function extent(values) {
  const n = values.length, lo = values[0], hi = values[n - 1];
  const d = n > 1 ? (hi - lo) / (n - 1) : 1;
  return { lo: lo - d / 2, hi: hi + d / 2, d };
}
function drawMap() {
  const c = $("map"), g = c.getContext("2d"), meta = S.meta, map = mapInfo();
  g.clearRect(0, 0, c.width, c.height);
  const b = plotBox();
  c.dataset.box = [b.x, b.y, b.w, b.h].join(",");   // the plot's box [canvas px] (tests)
  const img = g.createImageData(meta.n1, meta.n2);
  for (let j = 0; j < meta.n2; j++) for (let i = 0; i < meta.n1; i++) {
    const rgb = colourOf(S.values[j * meta.n1 + i], map);
    const k = ((meta.n2 - 1 - j) * meta.n1 + i) * 4;
    img.data[k] = rgb[0]; img.data[k + 1] = rgb[1]; img.data[k + 2] = rgb[2]; img.data[k + 3] = 255;
  }
  const off = document.createElement("canvas");
  off.width = meta.n1; off.height = meta.n2;
  off.getContext("2d").putImageData(img, 0, 0);
  g.imageSmoothingEnabled = false;
  g.drawImage(off, b.x, b.y, b.w, b.h);
  g.strokeStyle = "#333"; g.strokeRect(b.x, b.y, b.w, b.h);
  // axes: ticks in the file's units
  g.fillStyle = "#222"; g.font = "12px 'DejaVu Sans', sans-serif";
  const ex = extent(meta.values1), ey = extent(meta.values2);
  g.textAlign = "center"; g.textBaseline = "top";
  for (const t of niceTicks(ex.lo, ex.hi, 6)) {
    const x = b.x + (t - ex.lo) / (ex.hi - ex.lo) * b.w;
    g.fillRect(x, b.y + b.h, 1, 5); g.fillText(fmt(t, 4), x, b.y + b.h + 7);
  }
  g.fillText(axisLabel(meta.axis1, meta.units1), b.x + b.w / 2, b.y + b.h + 26);
  g.textAlign = "right"; g.textBaseline = "middle";
  for (const t of niceTicks(ey.lo, ey.hi, 6)) {
    const y = b.y + b.h - (t - ey.lo) / (ey.hi - ey.lo) * b.h;
    g.fillRect(b.x - 5, y, 5, 1); g.fillText(fmt(t, 4), b.x - 7, y);
  }
  g.save(); g.translate(14, b.y + b.h / 2); g.rotate(-Math.PI / 2); g.textAlign = "center";
  g.fillText(axisLabel(meta.axis2, meta.units2), 0, 0); g.restore();
  drawColourBar(g, b, map);
  drawMarks(g, b);
}
function drawColourBar(g, b, map) {
  const x = b.x + b.w + 16, w = 16, r = S.range;
  for (let k = 0; k < b.h; k++) {
    const f = 1 - k / (b.h - 1);
    const w0 = r.log ? Math.exp(Math.log(r.lo) + f * (Math.log(r.hi) - Math.log(r.lo))) : r.lo + f * (r.hi - r.lo);
    const rgb = colourOf(map.scale === "flip" ? w0 * S.meta.tau : w0, map);
    g.fillStyle = `rgb(${rgb[0]},${rgb[1]},${rgb[2]})`; g.fillRect(x, b.y + k, w, 1);
  }
  g.strokeStyle = "#333"; g.strokeRect(x, b.y, w, b.h);
  g.fillStyle = "#222"; g.textAlign = "left"; g.textBaseline = "middle";
  const ticks = r.log ? logTicks(r.lo, r.hi) : niceTicks(r.lo, r.hi, 5);
  for (const t of ticks) {
    const f = r.log ? (Math.log(t) - Math.log(r.lo)) / (Math.log(r.hi) - Math.log(r.lo)) : (t - r.lo) / (r.hi - r.lo);
    const y = b.y + b.h - f * b.h;
    g.fillRect(x + w, y, 4, 1); g.fillText(r.log ? t.toExponential(0) : fmt(t, 3), x + w + 6, y);
  }
  const unit = map.scale === "flip" ? `[${S.meta.tau_label}]` : (map.units === "1" ? "" : `[${map.units}]`);
  g.save(); g.translate(x + w + 58, b.y + b.h / 2); g.rotate(-Math.PI / 2); g.textAlign = "center";
  g.fillText(`${map.name} ${unit}`, 0, 0); g.restore();
}
function logTicks(lo, hi) {
  const out = [], a = Math.ceil(Math.log10(lo)), z = Math.floor(Math.log10(hi));
  const every = Math.max(1, Math.ceil((z - a + 1) / 6));
  for (let e = a; e <= z; e += every) out.push(Math.pow(10, e));
  return out;
}
function cellRect(b, i, j) {
  const w = b.w / S.meta.n1, h = b.h / S.meta.n2;
  return { x: b.x + i * w, y: b.y + (S.meta.n2 - 1 - j) * h, w, h };
}
function drawMarks(g, b) {
  const c = cellRect(b, S.cursor.i, S.cursor.j);
  g.lineWidth = 2; g.strokeStyle = "#000";
  g.strokeRect(c.x - 2, c.y - 2, c.w + 4, c.h + 4);
  g.strokeStyle = "#fff"; g.strokeRect(c.x - 4, c.y - 4, c.w + 8, c.h + 8);
  S.runs.forEach((run, k) => {
    if (!run) return;
    const r = cellRect(b, run.i, run.j), cx = r.x + r.w / 2, cy = r.y + r.h / 2;
    g.strokeStyle = COLOURS[k]; g.lineWidth = 3;
    g.beginPath(); g.arc(cx, cy, Math.max(6, r.w), 0, 2 * Math.PI); g.stroke();
  });
  g.lineWidth = 1;
}
function pixelAt(ev) {
  // the canvas' content box: without its border (clientLeft/Top), scaled by CSS size
  const c = $("map"), rect = c.getBoundingClientRect(), b = plotBox();
  const x = (ev.clientX - rect.left - c.clientLeft) * c.width / c.clientWidth;
  const y = (ev.clientY - rect.top - c.clientTop) * c.height / c.clientHeight;
  const i = Math.floor((x - b.x) / b.w * S.meta.n1);
  const j = S.meta.n2 - 1 - Math.floor((y - b.y) / b.h * S.meta.n2);
  if (i < 0 || j < 0 || i >= S.meta.n1 || j >= S.meta.n2) return null;
  return { i, j };
}
function showPixel(p) {
  const meta = S.meta, map = mapInfo(), v = S.values[p.j * meta.n1 + p.i];
  const hover = $("hover");
  hover.textContent = "";
  const at = document.createElement("span");
  const unit = u => (u && u !== "1" ? ` ${u}` : "");
  at.textContent = `pixel (${p.i}, ${p.j}): ${axisLabel(meta.axis1, meta.units1).split(" [")[0]} = ` +
    `${fmt(meta.values1[p.i], 10)}${unit(meta.units1)}, ${axisLabel(meta.axis2, meta.units2).split(" [")[0]} = ` +
    `${fmt(meta.values2[p.j], 10)}${unit(meta.units2)}; ${map.name} = `;
  const value = document.createElement("span");
  value.id = "hover-value";
  value.dataset.value = Number.isFinite(v) ? String(v) : "NaN";
  value.textContent = valueText(Number.isFinite(v) ? v : null, map);
  hover.append(at, value);
  hover.dataset.i = p.i; hover.dataset.j = p.j;
}

// -- a pixel's run ----------------------------------------------------------------------
async function runPixel(i, j, second, extra) {
  S.timing = { click: performance.now() };
  const which = second ? 1 : 0, ticket = (S.tickets[which] = (S.tickets[which] || 0) + 1);
  const q = new URLSearchParams({ i, j });
  if (extra) for (const [k, v] of Object.entries(extra)) q.set(k, v);
  say(`running pixel (${i}, ${j}) with the map's settings…`);
  S.pending++;
  try {
    const run = await get(`api/pixel?${q}`, "json");
    if (ticket !== S.tickets[which]) return null;   // a later click of this slot won
    S.timing.received = performance.now();
    if (!second) { S.runs = [run, S.runs[1]]; S.frame = 0; S.simTime = 0; }
    else S.runs[1] = run;
    if (!second && S.runs[1] && S.runs[1].frames !== run.frames) S.runs[1] = null;
    const secs = run.seconds.sweep + run.seconds.simulate;
    say(`pixel (${run.i}, ${run.j}) run in ${fmt(secs, 3)} s (value ${fmt(run.seconds.sweep, 2)} s, ` +
      `motion ${fmt(run.seconds.simulate, 2)} s; ${run.frames} frames, every ${run.save_every}. step)`);
    showValues(); setupPlayer(); drawMap(); drawAll();
    S.timing.firstFrame = performance.now();
    writeHash();
    if (!second) play(true);
    return run;
  } catch (e) {
    if (ticket === S.tickets[which]) say(e.message, true);
    return null;
  } finally {
    S.pending--;
    document.body.dataset.pending = S.pending;
  }
}
function showValues() {
  const body = $("values").tBodies[0];
  body.textContent = "";
  const names = S.meta.maps.map(m => m.name);
  S.runs.forEach((run, k) => {
    if (!run) return;
    for (const name of names) {
      const map = S.meta.maps.find(m => m.name === name);
      const a = run.map[name], b = run.run[name];
      const tr = document.createElement("tr");
      if (name === S.name) tr.id = k === 0 ? "value-row" : "value-row-b";
      const same = run.same[name] === true;           // compared bit by bit by the server
      const numbers = typeof a === "number" && typeof b === "number";
      const cells = [`${k ? "second: " : ""}${name} (${run.i}, ${run.j})`, valueText(a, map), valueText(b, map),
        same ? "the same, to the bit" :
          (numbers ? `differs by ${fmt(Math.abs(a - b), 3)}${a !== 0 ? ` (${fmt(Math.abs(a - b) / Math.abs(a), 2)} relative)` : ""}` :
            "differs") + (S.meta.gpu ? " (a GPU map; the run is on the CPU)" : "")];
      cells.forEach((text, n) => {
        const td = document.createElement("td");
        td.textContent = text;
        if (n === 1 || n === 2) { td.className = "num"; td.dataset.value = n === 1 ? String(a) : String(b); }
        if (n === 3) td.className = same ? "same" : "differ";
        tr.append(td);
      });
      body.append(tr);
    }
  });
  const d = $("downloads");
  d.hidden = !S.runs[0];
  if (S.runs[0]) {
    const q = `i=${S.runs[0].i}&j=${S.runs[0].j}`;
    $("download-h5").href = `api/run.h5?${q}`; $("download-csv").href = `api/run.csv?${q}`;
  }
  $("download-b").hidden = !S.runs[1];
  if (S.runs[1]) {
    const q = `i=${S.runs[1].i}&j=${S.runs[1].j}`;
    $("download-h5-b").href = `api/run.h5?${q}`; $("download-csv-b").href = `api/run.csv?${q}`;
  }
}

// -- the player ---------------------------------------------------------------------------
function currentTime() { const r = S.runs[0]; return r ? r.t[S.frame] : 0; }
function setupPlayer() {
  const r = S.runs[0], slider = $("time");
  slider.max = r.frames - 1; slider.disabled = false; slider.value = S.frame;
  $("play").disabled = false;
  $("separation").hidden = !S.runs[1];
}
function frameAt(t) {
  const ts = S.runs[0].t;
  let lo = 0, hi = ts.length - 1;
  while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (ts[mid] <= t) lo = mid; else hi = mid - 1; }
  return lo;
}
function play(on) {
  S.playing = on && !!S.runs[0];
  $("play").textContent = S.playing ? "pause" : "play";
  S.last = null;
  if (S.playing) requestAnimationFrame(tick);
}
function tick(now) {
  if (!S.playing) return;
  const r = S.runs[0];
  if (S.last !== null) S.simTime += (now - S.last) / 1000 * S.speed;
  S.last = now;
  if (S.simTime >= r.t[r.t.length - 1]) { S.simTime = r.t[r.t.length - 1]; S.playing = false; $("play").textContent = "play"; }
  S.frame = frameAt(S.simTime);
  $("time").value = S.frame;
  drawAll();
  if (S.playing) requestAnimationFrame(tick);
}
function drawAll() {
  if (!S.runs[0]) return;
  drawPendulum();
  const r = S.runs[0], t = r.t[S.frame];
  $("clock").textContent = `t = ${fmt(t, 5)} s = ${fmt(t / S.meta.tau, 5)} ${S.meta.tau_label}`;
  const tf = r.run.t_flip;
  const names = r.coordinates.join(", ");
  const what = (r.model === "pendulum" ? `angles ${names} [rad] (from horizontal)` : `coordinates ${names} (SI)`) +
    (r.t[r.t.length - 1] > 40 * S.meta.tau ? `, 40 ${S.meta.tau_label} around t` : "");
  drawSeries($("angles"), what, S.runs.map(run => run &&
    run.coordinates.map((_, k) => run.q.filter((_, n) => n % run.coordinates.length === k))), false,
    tf !== undefined && tf !== null ? tf : null, 40 * S.meta.tau);
  drawSeries($("energy"), "energy change E − E0 [J]",
    S.runs.map(run => run && [run.energy_change]), false, null);
  if (S.runs[1]) {
    const a = S.runs[0], b = S.runs[1], n = a.coordinates.length;
    const sep = a.t.map((_, f) => {
      let s = 0;
      for (let k = 0; k < n; k++) { const d = a.q[f * n + k] - b.q[f * n + k]; s += d * d; }
      return Math.sqrt(s);
    });
    drawSeries($("separation"), "separation |q_A − q_B| [rad] (log)", [[sep], null], true, null);
    $("separation").dataset.drawn = "1";
  }
}
function drawPendulum() {
  const c = $("pendulum"), g = c.getContext("2d");
  g.clearRect(0, 0, c.width, c.height);
  const ext = Math.max(...S.runs.filter(Boolean).map(r => r.extent)) * 1.1 || 1;
  const s = (c.width / 2) / ext, ox = c.width / 2, oy = c.height / 2;
  const X = x => ox + x * s, Y = y => oy - y * s;
  g.strokeStyle = "#ccc"; g.beginPath(); g.moveTo(0, oy); g.lineTo(c.width, oy); g.stroke();
  S.runs.forEach((run, k) => {
    if (!run) return;
    const f = Math.min(S.frame, run.frames - 1), n = run.npoints, P = run.points;
    const px = p => X(P[(f * n + p) * 2]), py = p => Y(P[(f * n + p) * 2 + 1]);
    // the tip's recent path
    g.strokeStyle = COLOURS[k]; g.globalAlpha = 0.25; g.lineWidth = 1; g.beginPath();
    for (let h = Math.max(0, f - 150); h <= f; h++) {
      const x = X(P[(h * n + n - 1) * 2]), y = Y(P[(h * n + n - 1) * 2 + 1]);
      if (h === Math.max(0, f - 150)) g.moveTo(x, y); else g.lineTo(x, y);
    }
    g.stroke(); g.globalAlpha = k ? 0.75 : 1;
    const points = run.body.startsWith("point") || run.style === "spring";
    for (let p = 1; p < n; p++) {
      g.strokeStyle = COLOURS[k];
      if (run.style === "spring") coil(g, px(p - 1), py(p - 1), px(p), py(p));
      else {
        g.lineWidth = points ? 2 : 7; g.lineCap = "round";
        g.beginPath(); g.moveTo(px(p - 1), py(p - 1)); g.lineTo(px(p), py(p)); g.stroke();
      }
      if (points) { g.fillStyle = COLOURS[k]; g.beginPath(); g.arc(px(p), py(p), 9, 0, 2 * Math.PI); g.fill(); }
    }
    g.fillStyle = "#333"; g.beginPath(); g.arc(px(0), py(0), 4, 0, 2 * Math.PI); g.fill();
    g.globalAlpha = 1; g.lineWidth = 1;
  });
  g.fillStyle = "#222"; g.font = "12px 'DejaVu Sans', sans-serif"; g.textAlign = "left";
  S.runs.forEach((run, k) => {
    if (!run) return;
    g.fillStyle = COLOURS[k];
    g.fillText(`${k ? "B" : "A"}: pixel (${run.i}, ${run.j})`, 8, 16 + 16 * k);
  });
}
function coil(g, x0, y0, x1, y1) {
  const dx = x1 - x0, dy = y1 - y0, L = Math.hypot(dx, dy), turns = 12, w = 7;
  const ux = dx / L, uy = dy / L;
  g.lineWidth = 2; g.beginPath(); g.moveTo(x0, y0);
  for (let k = 1; k < 2 * turns; k++) {
    const a = 0.08 + 0.84 * k / (2 * turns), side = k % 2 ? w : -w;
    g.lineTo(x0 + ux * L * a - uy * side, y0 + uy * L * a + ux * side);
  }
  g.lineTo(x1, y1); g.stroke();
}
// A plot against time of the runs' series (sets[k]: run k's series), over the whole
// run or, with `window` seconds, a window around the current time.
function drawSeries(c, title, sets, logY, mark, window) {
  const g = c.getContext("2d"), run = S.runs[0];
  g.clearRect(0, 0, c.width, c.height);
  const m = { l: 56, r: 10, t: 18, b: 22 }, w = c.width - m.l - m.r, h = c.height - m.t - m.b;
  const t = run.t, end = t[t.length - 1] || 1;
  let t0 = 0, t1 = end;
  if (window && window < end) {
    t0 = Math.min(Math.max(0, t[S.frame] - window / 2), end - window); t1 = t0 + window;
  }
  let lo = Infinity, hi = -Infinity;
  sets.forEach(set => set && set.forEach(ys => ys.forEach((v, f) => {
    if (t[f] < t0 || t[f] > t1) return;
    if (v === null || !Number.isFinite(v) || (logY && !(v > 0))) return;
    const y = logY ? Math.log10(v) : v;
    if (y < lo) lo = y; if (y > hi) hi = y;
  })));
  if (!Number.isFinite(lo)) { lo = 0; hi = 1; }
  if (!(hi > lo)) { hi = lo + 1; lo -= 1; }
  const X = x => m.l + (x - t0) / (t1 - t0) * w, Y = y => m.t + h - ((logY ? Math.log10(y) : y) - lo) / (hi - lo) * h;
  g.fillStyle = "#222"; g.font = "11px 'DejaVu Sans', sans-serif";
  g.textAlign = "left"; g.fillText(title, m.l, 12);
  g.strokeStyle = "#999"; g.strokeRect(m.l, m.t, w, h);
  g.textAlign = "right"; g.textBaseline = "middle";
  for (const v of niceTicks(lo, hi, 4)) {
    const small = v !== 0 && Math.abs(v) < 1e-3;   // 1e-6, not 0.000001
    g.fillText(logY ? `1e${fmt(v, 3)}` : (small ? v.toExponential(1) : fmt(v, 3)), m.l - 4,
      m.t + h - (v - lo) / (hi - lo) * h);
  }
  g.textAlign = "center"; g.textBaseline = "top";
  for (const v of niceTicks(t0, t1, 6)) g.fillText(fmt(v, 4), X(v), m.t + h + 3);
  g.save(); g.beginPath(); g.rect(m.l, m.t, w, h); g.clip();
  sets.forEach((set, k) => {
    if (!set) return;
    set.forEach((ys, n) => {
      g.strokeStyle = COLOURS[k]; g.globalAlpha = n ? 0.55 : 1; g.setLineDash(k ? [5, 3] : []);
      g.beginPath();
      let started = false;
      ys.forEach((v, f) => {
        if (t[f] < t0 - (t1 - t0) / w || t[f] > t1 + (t1 - t0) / w) { started = false; return; }
        if (v === null || !Number.isFinite(v) || (logY && !(v > 0))) { started = false; return; }
        if (!started) { g.moveTo(X(t[f]), Y(v)); started = true; } else g.lineTo(X(t[f]), Y(v));
      });
      g.stroke();
    });
  });
  g.setLineDash([]); g.globalAlpha = 1;
  if (mark !== null && mark >= t0 && mark <= t1) {
    g.strokeStyle = "#888"; g.setLineDash([3, 3]); g.beginPath();
    g.moveTo(X(mark), m.t); g.lineTo(X(mark), m.t + h); g.stroke(); g.setLineDash([]);
    const right = X(mark) > m.l + w - 30;
    g.textAlign = right ? "right" : "left"; g.fillStyle = "#555";
    g.fillText("flip", X(mark) + (right ? -3 : 3), m.t + 2);
  }
  g.strokeStyle = "#000"; g.beginPath(); g.moveTo(X(t[S.frame]), m.t); g.lineTo(X(t[S.frame]), m.t + h); g.stroke();
  g.restore();
}

// -- loading and events ------------------------------------------------------------------
async function loadMap(name) {
  const buffer = await get(`api/values?${new URLSearchParams({ name })}`);
  S.name = name;
  S.values = new Float64Array(buffer);
  S.range = colourScale(mapInfo(), S.values);
  $("mapname").value = name;
  drawMap();
}
function wire() {
  const c = $("map");
  c.addEventListener("mousemove", ev => { const p = S.values && pixelAt(ev); if (p) showPixel(p); });
  c.addEventListener("click", ev => {
    const p = S.values && pixelAt(ev);
    if (!p) return;
    S.cursor = p; showPixel(p); drawMap(); c.focus();
    runPixel(p.i, p.j, ev.shiftKey && !!S.runs[0]);
  });
  c.addEventListener("keydown", ev => {
    if (!S.values) return;                        // the map is still loading
    const moves = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] };
    if (moves[ev.key]) {
      const [di, dj] = moves[ev.key], step = ev.ctrlKey ? 10 : 1;
      S.cursor = { i: Math.min(S.meta.n1 - 1, Math.max(0, S.cursor.i + di * step)),
                   j: Math.min(S.meta.n2 - 1, Math.max(0, S.cursor.j + dj * step)) };
      showPixel(S.cursor); drawMap(); ev.preventDefault();
    } else if (ev.key === "Enter") {
      runPixel(S.cursor.i, S.cursor.j, ev.shiftKey && !!S.runs[0]); ev.preventDefault();
    }
  });
  c.addEventListener("focus", () => { if (S.values) showPixel(S.cursor); });
  $("mapname").addEventListener("change", async ev => {
    try { await loadMap(ev.target.value); showValues(); writeHash(); } catch (e) { say(e.message, true); }
  });
  $("play").addEventListener("click", () => {
    if (!S.runs[0]) return;
    if (!S.playing && S.frame >= S.runs[0].frames - 1) { S.frame = 0; S.simTime = 0; }
    play(!S.playing);
  });
  $("time").addEventListener("input", ev => {
    if (!S.runs[0]) return;
    play(false); S.frame = Number(ev.target.value); S.simTime = S.runs[0].t[S.frame];
    drawAll(); writeHash();
  });
  $("speed").addEventListener("change", ev => { S.speed = Number(ev.target.value); writeHash(); });
  window.addEventListener("beforeunload", () => play(false));
}
async function start() {
  wire();
  try {
    S.meta = await get("api/map", "json");
  } catch (e) { say(e.message, true); return; }
  const meta = S.meta;
  $("file").textContent = meta.file;
  document.title = `dpend explore: ${meta.file}`;
  $("setup").textContent = `${meta.n1} × ${meta.n2}, ${meta.axis1} × ${meta.axis2}, model ${meta.model}` +
    `${meta.model === "pendulum" ? `, ${meta.links} links` : ""}, rk4 to t_end = ${fmt(meta.t_end, 6)} s` +
    ` (${fmt(meta.t_end / meta.tau, 6)} ${meta.tau_label}), ${meta.n_steps} steps; ${meta.device}`;
  $("config").textContent = meta.config.join("\n");
  for (const m of meta.maps) {
    const o = document.createElement("option");
    o.value = m.name; o.textContent = `${m.name}: ${m.label}`;
    $("mapname").append(o);
  }
  const h = readHash();
  S.cursor = { i: Math.floor(meta.n1 / 2), j: Math.floor(meta.n2 / 2) };
  try { await loadMap(h.map !== undefined ? h.map : meta.maps[0].name); }
  catch (e) {
    try { await loadMap(meta.maps[0].name); } catch (e2) { say(e2.message, true); return; }
    say(e.message, true);
  }
  if (h.speed !== undefined && [...$("speed").options].some(o => o.value === h.speed)) {
    S.speed = Number(h.speed); $("speed").value = h.speed;
  }
  if (h.i !== undefined || h.j !== undefined) {
    const extra = {};
    for (const [k, v] of Object.entries(h)) if (!PAGE_KEYS.includes(k) && k !== "i" && k !== "j") extra[k] = v;
    const run = await runPixel(h.i === undefined ? "" : h.i, h.j === undefined ? "" : h.j, false, extra);
    if (run) {
      S.cursor = { i: run.i, j: run.j };
      if (h.i2 !== undefined) await runPixel(h.i2, h.j2 === undefined ? "" : h.j2, true);
      const t = Number(h.t);
      if (h.t !== undefined && Number.isFinite(t) && t >= 0) {
        play(false); S.simTime = t; S.frame = frameAt(t); $("time").value = S.frame;
      }
      drawMap(); drawAll(); writeHash();
    }
  }
  document.body.dataset.ready = "1";
}
start();
