"use strict";
// The condt stage viewer. Reads the JSON block written by crates/condt-io/src/html.rs; draws on
// one canvas.
(function () {
  const started = performance.now();
  const data = JSON.parse(document.getElementById("data").textContent);
  const P = data.points, E = data.edges, n = P.length / 2, m = E.length / 2;
  // Stage layers take the colour the file gives each stage (src/html.rs, STAGE_COLORS).
  const COLORS = { delaunay: "#c4c4c4", result: "#111111" };
  const WIDTH = { delaunay: 1, result: 2.5 };
  const layers = data.layers.map((name, k) => ({
    name, kind: k === 0 ? "delaunay" : data.stageNames[k - 1], edges: [],
    isResult: k === data.layers.length - 1 && k > 0,
    stageColor: k === 0 ? COLORS.delaunay : data.stageColors[k - 1],
  }));
  for (let e = 0; e < m; e++) {
    for (let bits = data.member[e], k = 0; bits > 0; bits >>= 1, k++) if (bits & 1) layers[k].edges.push(e);
  }
  for (const layer of layers) {
    layer.color = layer.isResult ? COLORS.result : layer.stageColor;
    layer.width = layer.isResult ? WIDTH.result : (WIDTH[layer.kind] || 1.5);
    layer.on = layer.kind === "delaunay" || layer.isResult;
    if (layer.isResult) layer.name += " (the result)";
  }
  const pointLayers = [
    { name: "points", color: "#222222", on: true, kind: "points" },
    { name: "unused points (in the result)", color: "#d62728", on: true, kind: "unused" },
  ];
  // What each stage layer shown changed against the stage before it (from the second stage on:
  // the proximity graph is a choice among the Delaunay edges), as the SVG's stage panels draw it.
  // Wide and translucent, under the layers: a halo, told apart from any stage's own line. The
  // removed edges' halo is dashed: green and red alone read alike to a red-green colour-blind
  // eye (an accessibility review; simulated deuteranopia left them 6 CIEDE2000 units apart).
  const changeLayers = [
    { name: "edges a shown stage added", color: "rgba(44,160,44,0.45)", width: 8, on: true, kind: "added", dash: [] },
    { name: "edges a shown stage removed", color: "rgba(214,39,40,0.3)", width: 8, on: true, kind: "removed", dash: [12, 6] },
  ];
  const unused = new Uint8Array(n);
  for (const i of data.unused) unused[i] = 1;
  // Exact duplicates: each later point to the first at its position, which carries the edges.
  const mergedInto = new Map(), copies = new Map();
  for (let k = 0; k < data.merged.length; k += 2) {
    const i = data.merged[k], first = data.merged[k + 1];
    mergedInto.set(i, first);
    if (!copies.has(first)) copies.set(first, []);
    copies.get(first).push(i);
  }
  const stageNames = data.stageNames;

  // Per edge: its second-shortest numbers and its changes, looked up on click.
  const seconds = new Map();
  for (let k = 0; k < data.seconds.length; k += 5) {
    const s = data.seconds;
    seconds.set(s[k] * 2 + s[k + 1], { ratio: s[k + 2], bound: s[k + 3], kept: s[k + 4] === 1 });
  }
  const changes = new Map();
  let repairs = 0;
  for (let k = 0; k < data.changes.length; k += 6) {
    const c = data.changes, e = c[k];
    if (!changes.has(e)) changes.set(e, []);
    const change = { stage: stageNames[c[k + 1]], stageIndex: c[k + 1], added: c[k + 2] === 1, code: c[k + 3], x: c[k + 4], y: c[k + 5] };
    if (change.code === 0) {
      change.selected = data.repairSelected.slice(4 * repairs, 4 * repairs + 4).filter((w) => w >= 0);
      repairs += 1;
    }
    changes.get(e).push(change);
  }
  const resultEdges = new Uint8Array(m);
  for (const k of layers[layers.length - 1].edges) resultEdges[k] = 1;
  // Edges at each point (compressed adjacency).
  const start = new Uint32Array(n + 1);
  for (let k = 0; k < 2 * m; k++) start[E[k] + 1]++;
  for (let i = 0; i < n; i++) start[i + 1] += start[i];
  const fill = start.slice(0, n), incident = new Uint32Array(2 * m);
  for (let k = 0; k < m; k++) { incident[fill[E[2 * k]]++] = k; incident[fill[E[2 * k + 1]]++] = k; }

  const canvas = document.getElementById("canvas");
  const ctx = canvas.getContext("2d");
  const view = { k: 1, ox: 0, oy: 0, fitted: 1, fit: [] };
  let selected = null, pending = false;
  const status = document.getElementById("status");

  function length(k) {
    const a = E[2 * k], b = E[2 * k + 1];
    return Math.hypot(P[2 * a] - P[2 * b], P[2 * a + 1] - P[2 * b + 1]) * data.scale * data.parts;
  }
  const exponent = (x) => Math.abs(x) >= 1e5 || (Math.abs(x) < 1e-3 && x !== 0);
  const fmt = (x) => exponent(x) ? x.toExponential(4) : +x.toPrecision(6) + "";
  // `x` with `d` significant digits.
  const fmtDigits = (x, d) => exponent(x) ? x.toExponential(d - 1) : +x.toPrecision(d) + "";
  // A coordinate with the digits the page's positions hold (7 over the box, POSITION_DIGITS),
  // and no more: UTM metres or degrees to 1e-7 need more than 6 significant digits to tell
  // samples apart, while a digit finer than the positions' resolution is the writing's rounding
  // (700 read back as 700.0001). A coordinate within the resolution of 0 is 0.
  // (The factor first: the scale of a set spanning the doubles times `parts` overflows.)
  const resolution = data.scale * 1e-7 * data.parts;
  const fmtCoordinate = (x) => {
    if (!(resolution > 0)) return String(+x.toPrecision(6));
    if (Math.abs(x) < resolution) return "0";
    const d = Math.min(17, Math.max(1, Math.floor(Math.log10(Math.abs(x) / resolution))));
    return String(+x.toPrecision(d));
  };
  // A length measured on the page's positions: no more digits than their resolution holds
  // (at most 6), where a length of 0.62 in a box 1000 wide is good to four.
  const fmtLength = (x) => {
    if (!(resolution > 0) || x === 0) return fmt(x);
    const d = Math.min(6, Math.max(1, Math.floor(Math.log10(x / resolution))));
    return fmtDigits(x, d);
  };
  // Two numbers with as many digits as tell them apart (a length just above its threshold),
  // seven at least, as the library's explanations (`story_text`) give them.
  const apart = (a, b) => {
    for (let d = 7; ; d++) {
      const [x, y] = [fmtDigits(a, d), fmtDigits(b, d)];
      if (x !== y || a === b || d === 17) return [x, y];
    }
  };
  // A ratio and its bound with three decimals, or as many more as tell them apart (the page
  // holds every digit where nine would read them alike), as `story_text` gives them.
  const ratiosApart = (a, b) => {
    for (let d = 3; ; d++) {
      const [x, y] = [a.toFixed(d), b.toFixed(d)];
      if (x !== y || a === b || d === 17) return [x, y];
    }
  };
  // A zoom by `f`, held to a thousandth of the fitted view out and 10^9 times it in (the
  // positions hold 7 digits of the box: beyond, a pixel is finer than any of them), so that the
  // scale never reaches 0 or infinity, from which no zoom comes back.
  const zoomFactor = (f) => {
    const k = Math.min(view.fitted * 1e9, Math.max(view.fitted * 1e-3, view.k * f));
    return k / view.k;
  };
  const sx = (i) => view.ox + P[2 * i] * view.k;
  const sy = (i) => view.oy - P[2 * i + 1] * view.k;

  function fit() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    let maxX = 0, maxY = 0;
    for (let i = 0; i < n; i++) { maxX = Math.max(maxX, P[2 * i]); maxY = Math.max(maxY, P[2 * i + 1]); }
    // A side without extent (one point, or points on one vertical or horizontal line) takes the
    // other side's, so that the drawing is scaled by what it has and centred on both axes.
    const span = Math.max(maxX, maxY) || 1;
    view.k = 0.92 * Math.min(w / (maxX || span), h / (maxY || span));
    view.fitted = view.k;
    view.ox = (w - maxX * view.k) / 2;
    view.oy = h - (h - maxY * view.k) / 2;
    view.fit = [view.k, view.ox, view.oy];
  }
  // Whether the view is still the last fit's: no pan or zoom since.
  const untouched = () => view.fit.every((value, k) => value === [view.k, view.ox, view.oy][k]);

  function resize() {
    const ratio = window.devicePixelRatio || 1;
    canvas.width = Math.round(canvas.clientWidth * ratio);
    canvas.height = Math.round(canvas.clientHeight * ratio);
    ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  }

  function request() {
    if (!pending) { pending = true; requestAnimationFrame(() => { pending = false; draw(); }); }
  }

  function draw() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    ctx.clearRect(0, 0, w, h);
    const notes = [];
    for (const change of changeLayers) {
      if (!change.on) continue;
      ctx.strokeStyle = change.color;
      ctx.lineWidth = change.width;
      ctx.setLineDash(change.dash);
      ctx.beginPath();
      for (let k = 2; k < layers.length; k++) {
        if (!layers[k].on) continue;
        const now = 1 << k, before = 1 << (k - 1);
        for (let e = 0; e < m; e++) {
          const bits = data.member[e];
          const shown = change.kind === "added" ? (bits & now) && !(bits & before) : (bits & before) && !(bits & now);
          if (!shown) continue;
          ctx.moveTo(sx(E[2 * e]), sy(E[2 * e]));
          ctx.lineTo(sx(E[2 * e + 1]), sy(E[2 * e + 1]));
        }
      }
      ctx.stroke();
    }
    ctx.setLineDash([]);
    for (const layer of layers) {
      if (!layer.on) continue;
      ctx.strokeStyle = layer.color;
      ctx.lineWidth = layer.width;
      ctx.beginPath();
      // Thinning: with many edges, those shorter than half a pixel on screen are not drawn.
      const thin = layer.edges.length > 150000;
      let skipped = 0;
      for (const k of layer.edges) {
        const a = E[2 * k], b = E[2 * k + 1];
        const ax = sx(a), ay = sy(a), bx = sx(b), by = sy(b);
        if ((ax < 0 && bx < 0) || (ax > w && bx > w) || (ay < 0 && by < 0) || (ay > h && by > h)) continue;
        if (thin && Math.abs(ax - bx) + Math.abs(ay - by) < 0.5) { skipped++; continue; }
        ctx.moveTo(ax, ay);
        ctx.lineTo(bx, by);
      }
      ctx.stroke();
      if (skipped > 0) notes.push(`${layer.name}: ${skipped.toLocaleString("en")} of ${layer.edges.length.toLocaleString("en")} edges shorter than half a pixel not drawn; zoom in to see them`);
    }
    const dots = n > 50000;
    if (pointLayers[0].on) {
      ctx.fillStyle = pointLayers[0].color;
      ctx.beginPath();
      for (let i = 0; i < n; i++) {
        const x = sx(i), y = sy(i);
        if (x < -3 || x > w + 3 || y < -3 || y > h + 3) continue;
        if (dots) ctx.rect(x - 0.5, y - 0.5, 1, 1);
        else { ctx.moveTo(x + 2.2, y); ctx.arc(x, y, 2.2, 0, 2 * Math.PI); }
      }
      ctx.fill();
      if (dots) notes.push(`${n.toLocaleString("en")} points drawn as 1-pixel dots`);
    }
    if (pointLayers[1].on) {
      ctx.strokeStyle = pointLayers[1].color;
      ctx.lineWidth = 1.5;
      ctx.beginPath();
      for (const i of data.unused) { const x = sx(i), y = sy(i); ctx.moveTo(x + 4, y); ctx.arc(x, y, 4, 0, 2 * Math.PI); }
      ctx.stroke();
    }
    if (selected) drawSelection();
    const [passes, moved] = data.smoothing;
    if (passes > 0) notes.push(`points where the stages saw them, after ${passes} smoothing pass${passes > 1 ? "es" : ""} (the last moved ${moved.toLocaleString("en")}); each stands for its input point`);
    // Written only when it changes: the line is a live region, which a screen reader would
    // read out again at every frame of a drag.
    const said = notes.join("; ");
    if (status.textContent !== said) status.textContent = said;
  }

  function drawSelection() {
    ctx.lineWidth = 4;
    if (selected.point !== undefined) {
      const i = selected.point;
      for (let s = start[i]; s < start[i + 1]; s++) {
        const k = incident[s], end = E[2 * k] === i ? 0 : 1, code = data.ends[2 * k + end];
        if (code === 0) continue;
        ctx.strokeStyle = code <= 2 ? "#ff7f0e" : "rgba(255,127,14,0.35)";
        ctx.beginPath(); ctx.moveTo(sx(E[2 * k]), sy(E[2 * k])); ctx.lineTo(sx(E[2 * k + 1]), sy(E[2 * k + 1])); ctx.stroke();
      }
      ctx.strokeStyle = "#ff7f0e"; ctx.lineWidth = 2;
      ctx.beginPath(); ctx.arc(sx(i), sy(i), 7, 0, 2 * Math.PI); ctx.stroke();
    } else {
      const k = selected.edge;
      ctx.strokeStyle = "#e0218a";
      ctx.beginPath(); ctx.moveTo(sx(E[2 * k]), sy(E[2 * k])); ctx.lineTo(sx(E[2 * k + 1]), sy(E[2 * k + 1])); ctx.stroke();
    }
  }

  // A grid over the points for picking.
  const cells = Math.max(1, Math.floor(Math.sqrt(n)));
  const grid = new Map();
  for (let i = 0; i < n; i++) {
    const key = Math.min(cells - 1, Math.floor(P[2 * i] * cells)) * cells + Math.min(cells - 1, Math.floor(P[2 * i + 1] * cells));
    if (!grid.has(key)) grid.set(key, []);
    grid.get(key).push(i);
  }
  function pickPoint(mx, my, radius) {
    const wx = (mx - view.ox) / view.k, wy = (view.oy - my) / view.k, r = radius / view.k;
    let best = -1, bestD = radius * radius;
    const cx0 = Math.max(0, Math.floor((wx - r) * cells)), cx1 = Math.min(cells - 1, Math.floor((wx + r) * cells));
    const cy0 = Math.max(0, Math.floor((wy - r) * cells)), cy1 = Math.min(cells - 1, Math.floor((wy + r) * cells));
    for (let cx = cx0; cx <= cx1; cx++) for (let cy = cy0; cy <= cy1; cy++) {
      for (const i of grid.get(cx * cells + cy) || []) {
        const d = (sx(i) - mx) ** 2 + (sy(i) - my) ** 2;
        // Strictly nearer: of exact duplicates the first, which carries their edges.
        if (d < bestD || (d === bestD && (best < 0 || i < best))) { bestD = d; best = i; }
      }
    }
    return best;
  }
  function pickEdge(mx, my, radius) {
    let best = -1, bestD = radius * radius;
    // Every edge drawn: those of the layers shown, and with their switch on the halos of the
    // edges a shown stage removed, which its layer no longer has (a click on such a halo gave
    // nothing: a student's review).
    let shown = 0;
    for (let k = 0; k < layers.length; k++) if (layers[k].on) shown |= 1 << k;
    const halos = [];
    if (changeLayers[1].on) for (let k = 2; k < layers.length; k++) if (layers[k].on) halos.push(k);
    const drawn = (bits) => (bits & shown) !== 0 || halos.some((k) => ((bits >> (k - 1)) & 3) === 1);
    for (let k = 0; k < m; k++) {
      if (!drawn(data.member[k])) continue;
      const ax = sx(E[2 * k]), ay = sy(E[2 * k]), bx = sx(E[2 * k + 1]), by = sy(E[2 * k + 1]);
      const dx = bx - ax, dy = by - ay, l2 = dx * dx + dy * dy;
      const t = l2 > 0 ? Math.max(0, Math.min(1, ((mx - ax) * dx + (my - ay) * dy) / l2)) : 0;
      const d = (ax + t * dx - mx) ** 2 + (ay + t * dy - my) ** 2;
      if (d < bestD) { bestD = d; best = k; }
    }
    return best;
  }

  const details = document.getElementById("details");
  function point(i) {
    // A set wider than the largest double gets a part of its scale, added `parts` times: each
    // sum stays finite, as the point does.
    const at = (k, o) => { const t = P[k] * data.scale; for (let j = 0; j < data.parts; j++) o += t; return o; };
    const x = at(2 * i, data.origin[0]), y = at(2 * i + 1, data.origin[1]);
    return `${i} (${fmtCoordinate(x)}, ${fmtCoordinate(y)})`;
  }
  function endWords(k, end) {
    const code = data.ends[2 * k + end], at = E[2 * k + end];
    if (code === 1) return `shortest at ${at}`;
    if (code === 2) {
      const s = seconds.get(2 * k + end);
      const [ratio, bound] = ratiosApart(s.ratio, s.bound);
      return `second shortest at ${at}, ${s.kept ? "kept" : "dropped"} by the uniformity test: |e2| = ${ratio} |e1| ${s.kept ? "<" : "≥"} ${bound} |e1|`;
    }
    return `rank ${code} at ${at}`;
  }
  function changeWords(c) {
    const verb = c.added ? "added" : "removed";
    const words = [
      () => {
        // The neighbours Algorithm 2 selected at the vertex (not what it was left with).
        const s = c.selected;
        const which = s.length === 0 ? "none" : s.length === 1 ? `its edge to ${s[0]} only` : `its edges to ${s.slice(0, -1).join(", ")} and ${s[s.length - 1]}`;
        return `at vertex ${c.x} (degree ${c.y}), which selected ${which}`;
      },
      () => { const [l, t] = apart(c.x, c.y); return `length ${l} above √T = ${t} (the outlier threshold: T = Q3 + k IQR of the squared lengths)`; },
      () => "given back between two regular passages",
      () => `${c.y.toFixed(2)} times as long as the longest other edge at vertex ${c.x}`,
      () => "with its component (outliers: fewer than 5 of its points clearly apart from other curves, or a closed polygon of 5 or 6)",
      () => "short spur",
      () => "gap closed",
      () => "a given-back component not clearly apart",
      () => "chosen by the baseline",
      () => (c.added
        ? "joined where three or four curves meet (a junction)"
        : "a chord past a junction's sample"),
      () => "a clump: at most half its points pass smoothly",
      () => "by the repair run again without the edges the outlier filter cut",
      () => { const [l, t] = apart(c.x, c.y); return `length ${l} above the spacing floor ${t} (1.5 median edges)`; },
      () => `restored the crossing at ${c.x}`,
      () => (c.added ? "joined at a tip in place of a chord" : "a chord across a tip"),
      () => `part of an outlier tail of ${c.y} point${c.y === 1 ? "" : "s"} cut where it hung from ${c.x}`,
      () => "given back as a curve's last edge, a curve behind it",
      () => (c.added
        ? "joined to put a hooked loose end back in line"
        : "passed a loose end that hooked back beside the curve"),
      () => (c.added
        ? "joined through a tip's samples that had no edges"
        : "a chord across a tip whose samples had no edges"),
      () => `the edge that closed a loop hung on ${c.x}, which the curve runs into less straightly than into the loop's other edge`,
    ];
    const why = c.code >= data.detourCode ? detourWords(c) : words[c.code]();
    return `${c.stage}: ${verb} ${why}`;
  }
  // Codes from `data.detourCode`: a detour through `code - data.detourCode` points between its
  // two ends (as `story_text`).
  function detourWords(c) {
    const points = c.code - data.detourCode;
    const route = points === 0
      ? `the edge between ${c.x} and ${c.y} past a route`
      : `part of a detour through ${points} point${points === 1 ? "" : "s"} between ${c.x} and ${c.y}`;
    return `${route}, beside the route the curve runs into straighter at both`;
  }
  function story(k) {
    const a = data.ends[2 * k], b = data.ends[2 * k + 1];
    const parts = [];
    if (a === 0 || b === 0) parts.push("not a Delaunay edge");
    else if (a >= 3 && b >= 3) parts.push(`not among the two shortest at either end (ranks ${a} and ${b})`);
    else parts.push(endWords(k, 0), endWords(k, 1));
    // A baseline decided the edge (its change, code 8, comes first): the ends are only
    // Algorithm 1's view, told after it.
    const all = changes.get(k) || [];
    const baseline = all.length > 0 && all[0].code === 8 ? all[0] : null;
    if (baseline) parts[0] = `${baseline.added ? "chosen" : "not chosen"} by the ${baseline.stage}; Algorithm 1 would have seen it as: ${parts[0]}`;
    for (const c of baseline ? all.slice(1) : all) parts.push(changeWords(c));
    parts.push(resultEdges[k] ? "kept" : "dropped");
    return parts;
  }
  // Point i's Delaunay edges, by their rank at i (shortest first).
  function ringOf(i) {
    const ring = [];
    for (let s = start[i]; s < start[i + 1]; s++) {
      const k = incident[s], end = E[2 * k] === i ? 0 : 1;
      if (data.ends[2 * k + end] === 0) continue;
      ring.push({ k, other: E[2 * k + 1 - end], rank: data.ends[2 * k + end], end });
    }
    ring.sort((p, q) => p.rank - q.rank);
    return ring;
  }
  function showPoint(i) {
    if (mergedInto.has(i)) {
      const first = mergedInto.get(i);
      showPoint(first);
      details.innerHTML = `<b>Point ${i}</b> is an exact duplicate of point ${first}, merged into it: its edges and fate are ${first}'s.<br>` + details.innerHTML;
      return;
    }
    const ring = ringOf(i);
    const [passes] = data.smoothing;
    let html = `<b>Point ${point(i)}</b>`;
    if (passes > 0) html += ` where the stages saw it, after ${passes} smoothing pass${passes > 1 ? "es" : ""} (its input position may differ)`;
    html += `<br>final degree ${data.degree[i]}${unused[i] ? " (unused)" : ""}`;
    if (copies.has(i)) html += `<br>exact duplicates merged into it: ${copies.get(i).join(", ")}`;
    html += `<table><tr><th>rank</th><th>neighbour</th><th>length</th><th>in result</th></tr>`;
    for (const r of ring) {
      html += `<tr class="${r.rank <= 2 ? "chosen" : ""}"><td>${r.rank}</td><td>${r.other}</td><td>${fmtLength(length(r.k))}</td><td>${resultEdges[r.k] ? "yes" : "no"}</td></tr>`;
    }
    html += "</table>";
    const second = ring.find((r) => r.rank === 2);
    if (second) {
      const s = seconds.get(2 * second.k + second.end);
      const [ratio, bound] = ratiosApart(s.ratio, s.bound);
      html += `<p>Two shortest: to ${ring[0].other} (e1) and ${second.other} (e2). Uniformity test: |e2| = ${ratio} |e1| ${s.kept ? "<" : "≥"} u |e1| with u = ${bound}: e2 ${s.kept ? "kept" : "dropped"}.</p>`;
    } else if (ring.length) {
      html += `<p>One Delaunay neighbour: ${ring[0].other}.</p>`;
    }
    // Each of its edges that a stage added or removed, with the last such stage: why an edge of
    // the proximity graph is not in the result (an unused point's rows said "no" and no more: a
    // student's review); a click on the edge tells its whole story.
    const changed = ring.filter((r) => changes.has(r.k)).map((r) => {
      const all = changes.get(r.k), c = all[all.length - 1];
      return `to ${r.other} ${c.added ? "added" : "removed"} by ${c.stage}`;
    });
    if (changed.length) html += `<p>Last changes of its edges: ${changed.join("; ")}.</p>`;
    details.innerHTML = html;
  }
  function showEdge(k) {
    details.innerHTML = `<b>Edge ${E[2 * k]}–${E[2 * k + 1]}</b>, length ${fmtLength(length(k))}` +
      story(k).map((s) => `<div class="story">${s}</div>`).join("");
  }

  function show(selection) {
    selected = selection;
    if (selected === null) details.textContent = n === 0 ? "No points." : "Click a point or an edge.";
    else if (selected.point !== undefined) showPoint(selected.point);
    else showEdge(selected.edge);
    request();
  }
  // A click selects, unless it ends a drag (the view moved) or is the second of a double
  // click, which restores what the first click replaced and shows everything.
  let beforeClick = null, pressed = null;
  canvas.addEventListener("click", (ev) => {
    if (ev.detail > 1) return;
    if (pressed && Math.hypot(ev.clientX - pressed.x, ev.clientY - pressed.y) > 3) return;
    beforeClick = selected;
    const r = canvas.getBoundingClientRect(), mx = ev.clientX - r.left, my = ev.clientY - r.top;
    const i = pointLayers[0].on ? pickPoint(mx, my, 6) : -1;
    if (i >= 0) { selected = { point: i }; showPoint(i); request(); return; }
    const k = pickEdge(mx, my, 5);
    if (k >= 0) { selected = { edge: k }; showEdge(k); request(); return; }
    show(null);
  });
  let drag = null;
  canvas.addEventListener("mousedown", (ev) => {
    drag = { x: ev.clientX, y: ev.clientY, ox: view.ox, oy: view.oy };
    pressed = { x: ev.clientX, y: ev.clientY };
  });
  window.addEventListener("mouseup", () => { drag = null; });
  window.addEventListener("mousemove", (ev) => {
    if (!drag) return;
    view.ox = drag.ox + ev.clientX - drag.x; view.oy = drag.oy + ev.clientY - drag.y; request();
  });
  canvas.addEventListener("wheel", (ev) => {
    ev.preventDefault();
    const r = canvas.getBoundingClientRect(), mx = ev.clientX - r.left, my = ev.clientY - r.top;
    const f = zoomFactor(Math.exp(-ev.deltaY * 0.0015));
    view.ox = mx - (mx - view.ox) * f; view.oy = my - (my - view.oy) * f; view.k *= f; request();
  }, { passive: false });
  canvas.addEventListener("dblclick", () => { show(beforeClick); fit(); request(); });
  // Keys, where the canvas has the focus (a click or Tab gives it): arrows pan, + and - zoom
  // about the centre, 0 shows everything, n and p select the next and the previous point by its
  // index (without a pointer no point could be picked: a teacher's review), e and E the next and
  // the previous edge of the point last selected so, by rank (no edge could be picked either),
  // their details then announced. Enter selects the point nearest the middle of the view: pan
  // and zoom to a place, then pick there (by index alone, a point among thousands was out of a
  // keyboard's reach: an accessibility review).
  let edgesOf = null;
  // The edge shown was reached by e or E (not clicked since).
  const steppedEdge = () => edgesOf && selected && selected.edge !== undefined &&
    (ringOf(edgesOf.point)[edgesOf.at] || {}).k === selected.edge;
  const stepPoint = (by) => {
    if (n === 0) return;
    const from = selected && selected.point !== undefined ? selected.point : steppedEdge() ? edgesOf.point : null;
    const at = from !== null ? from : by > 0 ? -1 : n;
    const i = (at + by + n) % n;
    selected = { point: i };
    showPoint(i);
  };
  const stepEdge = (by) => {
    if (selected && selected.point !== undefined) {
      const i = mergedInto.has(selected.point) ? mergedInto.get(selected.point) : selected.point;
      edgesOf = { point: i, at: by > 0 ? -1 : 0 };
    } else if (!steppedEdge()) return;
    const ring = ringOf(edgesOf.point);
    if (ring.length === 0) return;
    edgesOf.at = (edgesOf.at + by + ring.length) % ring.length;
    const r = ring[edgesOf.at];
    selected = { edge: r.k };
    showEdge(r.k);
    details.innerHTML += `<p>Edge ${edgesOf.at + 1} of ${ring.length} at point ${edgesOf.point}, rank ${r.rank} there (e and E for the others, n and p for the points).</p>`;
  };
  // A point selected by a key, or the edge's ends, brought on screen if the view has left it
  // (zoomed in, n stepped to a point out of sight).
  const inView = (ends) => {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (ends.every((i) => sx(i) >= 0 && sx(i) <= w && sy(i) >= 0 && sy(i) <= h)) return;
    const x = ends.reduce((t, i) => t + sx(i), 0) / ends.length, y = ends.reduce((t, i) => t + sy(i), 0) / ends.length;
    view.ox += w / 2 - x; view.oy += h / 2 - y;
  };
  const pickMiddle = () => {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    let best = -1, bestD = Infinity;
    for (let i = 0; i < n; i++) {
      if (mergedInto.has(i)) continue;
      const d = (sx(i) - w / 2) ** 2 + (sy(i) - h / 2) ** 2;
      if (d < bestD) { bestD = d; best = i; }
    }
    if (best < 0) return;
    selected = { point: best };
    showPoint(best);
  };
  canvas.addEventListener("keydown", (ev) => {
    const w = canvas.clientWidth, h = canvas.clientHeight, step = 40;
    const zoom = (g) => {
      const f = zoomFactor(g);
      view.ox = w / 2 - (w / 2 - view.ox) * f; view.oy = h / 2 - (h / 2 - view.oy) * f; view.k *= f;
    };
    const moves = {
      ArrowLeft: () => { view.ox += step; }, ArrowRight: () => { view.ox -= step; },
      ArrowUp: () => { view.oy += step; }, ArrowDown: () => { view.oy -= step; },
      "+": () => zoom(1.25), "=": () => zoom(1.25), "-": () => zoom(0.8), "0": () => fit(),
      n: () => stepPoint(1), p: () => stepPoint(-1), e: () => stepEdge(1), E: () => stepEdge(-1),
      Enter: pickMiddle,
    };
    if (!(ev.key in moves) || ev.ctrlKey || ev.metaKey || ev.altKey) return;
    ev.preventDefault();
    moves[ev.key]();
    if ("npeE".includes(ev.key) && selected) inView(selected.point !== undefined ? [selected.point] : [E[2 * selected.edge], E[2 * selected.edge + 1]]);
    request();
  });
  // The canvas changes size with the window, and with the status line above it, which each
  // drawing writes: a long one wraps and takes height from the canvas after the first fit (the
  // drawing was then fitted to a size the canvas no longer had, and a double click fitted it
  // elsewhere). A view not panned or zoomed since its fit is fitted again.
  new ResizeObserver(() => {
    const refit = untouched();
    resize();
    if (refit) fit();
    request();
  }).observe(canvas);

  // Each layer's switch beside its colour: the list is the legend too.
  const layerBox = document.getElementById("layers");
  for (const layer of [...layers, ...changeLayers, ...pointLayers]) {
    const label = document.createElement("label");
    const box = document.createElement("input");
    box.type = "checkbox"; box.checked = layer.on; box.dataset.layer = layer.name;
    box.addEventListener("change", () => { layer.on = box.checked; request(); });
    const mark = document.createElement("span");
    const isPoint = layer.kind === "points" || layer.kind === "unused";
    mark.className = isPoint ? "dot" : changeLayers.includes(layer) ? "swatch change" : "swatch";
    if (layer.kind === "unused") mark.style.border = `2px solid ${layer.color}`;
    else if (layer.dash && layer.dash.length) mark.style.background = `repeating-linear-gradient(90deg, ${layer.color} 0 ${layer.dash[0]}px, transparent 0 ${layer.dash[0] + layer.dash[1]}px)`;
    else mark.style.background = layer.color;
    if (!isPoint) mark.style.height = `${Math.max(2, layer.width * 2)}px`;
    label.append(box, " ", mark, layer.name);
    // Each edge layer's count of edges at its right, which its switch's name says in words:
    // what a screen reader has of the drawing, stage by stage.
    if (layer.edges) {
      const count = document.createElement("span"), words = document.createElement("span");
      count.className = "count";
      words.className = "unseen";
      words.textContent = `${layer.edges.length === 1 ? "edge" : "edges"}: `;
      count.append(words, layer.edges.length.toLocaleString("en"));
      label.append(count);
    }
    layerBox.append(label);
  }

  for (const layer of [...layers, ...changeLayers, ...pointLayers]) layer.initially = layer.on;
  resize();
  fit();
  draw();
  if (n === 0) show(null);
  // For tests and scripts: where things are on screen, and how long the page took.
  window.condtViewer = {
    points: n, edges: m, edgeLayers: layers.length,
    screenOf: (i) => { const r = canvas.getBoundingClientRect(); return [r.left + sx(i), r.top + sy(i)]; },
    edgeIndex: (a, b) => { for (let k = 0; k < m; k++) if (E[2 * k] === Math.min(a, b) && E[2 * k + 1] === Math.max(a, b)) return k; return -1; },
    edgeMidpoint: (k) => { const r = canvas.getBoundingClientRect(); return [r.left + (sx(E[2 * k]) + sx(E[2 * k + 1])) / 2, r.top + (sy(E[2 * k]) + sy(E[2 * k + 1])) / 2]; },
    edgeEnds: (k) => [E[2 * k], E[2 * k + 1]],
    inResult: (k) => resultEdges[k] === 1,
    isDelaunay: (k) => (data.member[k] & 1) === 1,
    // Shows only the edge layer called `name` (no points), or with null the first view's layers.
    only: (name) => {
      const all = [...layers, ...changeLayers, ...pointLayers];
      for (const layer of all) layer.on = name === null ? layer.initially : layer.name === name;
      for (const box of layerBox.querySelectorAll("input")) box.checked = all.find((l) => l.name === box.dataset.layer).on;
      draw();
    },
    loadMs: performance.now() - started,
  };
  document.body.dataset.ready = "true";
})();
