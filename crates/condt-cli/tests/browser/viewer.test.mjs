// End-to-end test of `condt reconstruct --format html` in a real browser (headless Chromium).
//
//   node viewer.test.mjs CONDT_BINARY [SCREENSHOT.png]
//
// It writes the page and the plain edge list for the shipped data, opens the page from file://,
// clicks a point and two edges, and checks what the details panel says against the edge list
// the same binary writes: the final degree of the point, and whether each edge is in the result.
// Chromium comes from Debian (`/usr/bin/chromium`, or $CHROMIUM), driven by playwright-core.
import { chromium } from "playwright-core";
import { execFileSync } from "node:child_process";
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import assert from "node:assert/strict";

const [binary, screenshot] = process.argv.slice(2);
if (!binary) {
  console.error("usage: node viewer.test.mjs CONDT_BINARY [SCREENSHOT.png]");
  process.exit(2);
}
// Run from the repository's root, so that the page's title is the data's path in it.
const root = resolve(new URL("../../../..", import.meta.url).pathname);
const data = "data/shapes.txt";
const dir = mkdtempSync(join(tmpdir(), "condt-viewer-"));
const page_file = join(dir, "shapes.html");
const edges_file = join(dir, "shapes.edges");
const condt = resolve(binary);
execFileSync(condt, ["reconstruct", data, "--format", "html", "-o", page_file], { cwd: root });
execFileSync(condt, ["reconstruct", data, "-o", edges_file], { cwd: root });

// The result, from the plain output: edges and degrees.
const result = new Set();
const degree = new Map();
for (const line of readFileSync(edges_file, "utf8").split("\n")) {
  if (!line.trim() || line.startsWith("#")) continue;
  const [a, b] = line.trim().split(/\s+/).map(Number);
  result.add(`${Math.min(a, b)}-${Math.max(a, b)}`);
  degree.set(a, (degree.get(a) || 0) + 1);
  degree.set(b, (degree.get(b) || 0) + 1);
}
assert.ok(result.size > 0, "the shipped data reconstructs to some edges");
// What the page's summary and layer switches count, from the same binary's other outputs: the
// curves (txt), the unused points, and the Delaunay edges (the sides of `triangulate`'s
// triangles).
const lines = (args) => execFileSync(condt, args, { cwd: root, encoding: "utf8" })
  .split("\n").filter((l) => l.trim() && !l.startsWith("#"));
const curves = lines(["reconstruct", data, "-q"]).map((l) => l.split(/\s+/)[0]);
const unusedCount = lines(["reconstruct", data, "--format", "unused", "-q"]).length;
const delaunay = new Set();
for (const l of lines(["triangulate", data, "-q"])) {
  const [a, b, c] = l.trim().split(/\s+/).map(Number);
  for (const [p, q] of [[a, b], [b, c], [a, c]]) delaunay.add(`${Math.min(p, q)}-${Math.max(p, q)}`);
}
const inputPoints = readFileSync(join(root, data), "utf8").split("\n").filter((l) => l.trim() && !l.startsWith("#")).length;

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
let failed = false;
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 850 } });
  const problems = [];
  page.on("pageerror", (e) => problems.push(String(e)));
  page.on("console", (m) => { if (m.type() === "error") problems.push(m.text()); });
  page.on("request", (r) => { if (!r.url().startsWith("file:")) problems.push(`fetched ${r.url()}`); });
  await page.goto("file://" + page_file);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20000 });
  const details = () => page.innerText("#details");

  // The drawing is fitted to the canvas as it is: after the first drawing writes the status line
  // (which wraps in a narrow window and takes height from the canvas), and after the window
  // changes size, unless the view was panned or zoomed. Pressing 0 fits it again: nothing moves.
  const frames = () => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const fittedAsIs = async (size) => {
    await frames();
    const shown = await page.evaluate(() => window.condtViewer.screenOf(0));
    await page.focus("#canvas");
    await page.keyboard.press("0");
    await frames();
    const fitted = await page.evaluate(() => window.condtViewer.screenOf(0));
    assert.ok(Math.abs(shown[0] - fitted[0]) < 1 && Math.abs(shown[1] - fitted[1]) < 1,
      `fitted to the canvas as it is (${size}): ${shown} against ${fitted}`);
  };
  await fittedAsIs("on loading");
  for (const [width, height] of [[640, 500], [320, 640], [1400, 850]]) {
    await page.setViewportSize({ width, height });
    await fittedAsIs(`${width} x ${height}`);
    // Reflow (WCAG 1.4.10: 320 pixels wide, as 1280 at 400 %): nothing scrolls sideways and
    // the drawing keeps the width with the panel under it (the panel took the whole width and
    // the drawing none).
    const laid = await page.evaluate(() => {
      const c = document.getElementById("canvas").getBoundingClientRect();
      const a = document.querySelector("aside").getBoundingClientRect();
      return { wide: document.documentElement.scrollWidth - document.documentElement.clientWidth,
        canvas: [c.width, c.height], under: a.top >= c.bottom - 1 };
    });
    assert.equal(laid.wide, 0, `no sideways scrolling at ${width} pixels`);
    if (width <= 640) {
      assert.ok(laid.under && laid.canvas[0] >= width - 1 && laid.canvas[1] >= 150,
        `the drawing across the window and the panel under it at ${width} pixels: ${JSON.stringify(laid)}`);
    }
  }

  // Every edge layer has a colour swatch beside its switch, each stage its own (the page draws a
  // layer in its swatch's colour).
  const swatches = await page.$$eval("#layers .swatch:not(.change)", (marks) =>
    marks.map((m) => [m.parentElement.textContent, getComputedStyle(m).backgroundColor]));
  const layerCount = await page.evaluate(() => window.condtViewer.edgeLayers);
  assert.equal(swatches.length, layerCount, "a swatch per edge layer");
  for (const [name, color] of swatches) {
    assert.ok(color && color !== "rgba(0, 0, 0, 0)", `layer "${name}" has a colour`);
  }
  const stageColors = swatches.slice(1, -1).map(([, color]) => color);
  // Two switches more: what a shown stage added and removed, in the SVG's colours.
  const changes = await page.$$eval("#layers .swatch.change", (marks) => marks.map((m) => m.parentElement.textContent));
  assert.deepEqual(changes, [" edges a shown stage added", " edges a shown stage removed"]);
  assert.equal(new Set(stageColors).size, stageColors.length, `stage colours differ: ${swatches}`);

  // For a screen reader: a title and a language; the drawing described by the result's counts,
  // which agree with the other outputs; each layer's switch named by its layer and its count of
  // edges; the status line and the details announced as they change.
  assert.equal(await page.title(), `condt: ${data}`);
  assert.equal(await page.getAttribute("html", "lang"), "en");
  const closedCount = curves.filter((c) => c === "closed").length;
  const grouped = (count) => count.toLocaleString("en"); // the page groups thousands so
  const summary = `The result: ${grouped(inputPoints)} points, ${grouped(result.size)} edges in ` +
    `${curves.length} curves (${closedCount} closed, ${curves.length - closedCount} open), ` +
    `${grouped(unusedCount)} unused.`;
  const described = await page.$eval("#canvas", (c) => c.getAttribute("aria-describedby").split(" ")
    .map((id) => document.getElementById(id).textContent));
  assert.equal(described[0], summary, "the drawing's text alternative");
  assert.match(described[1], /Enter selects the point nearest the middle of the view/);
  // An application, whose keys a screen reader passes on (an image's stay in its browse mode).
  assert.match(await page.locator("main").ariaSnapshot(), /- application "The points, their Delaunay/);
  const tree = await page.locator("#layers").ariaSnapshot();
  const named = [...tree.matchAll(/checkbox "([^"]*)"/g)].map((m) => m[1]);
  const switches = await page.$$eval("#layers input", (boxes) => boxes.map((b) => b.dataset.layer));
  assert.equal(named.length, switches.length, `every switch has a name: ${tree}`);
  named.forEach((name, k) => assert.ok(name.startsWith(switches[k]), `${switches[k]} is named "${name}"`));
  assert.match(tree, /^- group "Layers"/, tree);
  const edgesOf = (layer) => {
    const count = named.find((s) => s.startsWith(layer)).match(/ edges?: ([\d,]+)$/);
    assert.ok(count, `the switch of ${layer} says its count of edges: ${named}`);
    return Number(count[1].replace(/,/g, ""));
  };
  assert.equal(edgesOf("Delaunay triangulation"), delaunay.size, "the triangulation's count of edges");
  assert.equal(edgesOf(switches[layerCount - 1]), result.size, "the result's count of edges");
  assert.ok(switches[layerCount - 1].endsWith("(the result)"), switches[layerCount - 1]);
  assert.equal(await page.getAttribute("#status", "role"), "status");
  assert.equal(await page.getAttribute("#details", "aria-live"), "polite");
  // Keyboard: Tab from the top of the page reaches the drawing, with a ring of 2 pixels or
  // more, then every layer's switch in order, and then leaves the page (no trap); Space
  // switches a layer.
  await page.click("h1"); // Tab goes on from there
  const order = [];
  for (let k = 0; k <= switches.length + 1; k++) {
    await page.keyboard.press("Tab");
    order.push(await page.evaluate(() => {
      const e = document.activeElement;
      if (!e || e === document.body) return null;
      const s = getComputedStyle(e);
      return { id: e.id || e.dataset.layer, ring: s.outlineStyle !== "none" && parseFloat(s.outlineWidth) >= 2 };
    }));
  }
  assert.deepEqual(order.map((f) => f && f.id), ["canvas", ...switches, null], "the Tab order");
  assert.ok(order[0].ring, "a visible focus ring on the drawing");
  await page.focus(`input[data-layer="${switches[1]}"]`);
  await page.keyboard.press("Space");
  assert.ok(await page.isChecked(`input[data-layer="${switches[1]}"]`), "Space switched a layer on");
  await page.keyboard.press("Space");
  // Enter on the drawing selects the point nearest the middle of the view (a point among
  // thousands was out of a keyboard's reach, by index alone), after a pan too.
  const nearestMiddle = () => page.evaluate(() => {
    const v = window.condtViewer, r = document.getElementById("canvas").getBoundingClientRect();
    const d = JSON.parse(document.getElementById("data").textContent), later = new Set();
    for (let k = 0; k < d.merged.length; k += 2) later.add(d.merged[k]);
    let best = -1, bestD = Infinity;
    for (let i = 0; i < v.points; i++) {
      const [x, y] = v.screenOf(i), dist = (x - r.left - r.width / 2) ** 2 + (y - r.top - r.height / 2) ** 2;
      if (!later.has(i) && dist < bestD) { bestD = dist; best = i; }
    }
    return best;
  });
  await page.focus("#canvas");
  for (const keys of [[], ["ArrowLeft", "ArrowLeft", "ArrowUp", "+", "+"]]) {
    for (const key of keys) await page.keyboard.press(key);
    await page.keyboard.press("Enter");
    assert.match(await details(), new RegExp(`^Point ${await nearestMiddle()} \\(`), `Enter after ${keys}`);
  }
  // Zoomed in, n brings the point it selects into view (it stepped to points out of sight).
  for (let k = 0; k < 12; k++) await page.keyboard.press("+");
  for (let k = 0; k < 3; k++) {
    await page.keyboard.press("n");
    const i = Number((await details()).match(/^Point (\d+) \(/)[1]);
    const [px, py] = await page.evaluate((i) => window.condtViewer.screenOf(i), i);
    const r = await page.$eval("#canvas", (c) => c.getBoundingClientRect().toJSON());
    assert.ok(px >= r.left && px <= r.right && py >= r.top && py <= r.bottom, `point ${i} in view: ${px}, ${py}`);
  }
  await page.keyboard.press("0");
  await page.evaluate(() => document.activeElement.blur());
  await frames();
  // Colour is not all that tells the halos apart (green and red read alike to a red-green
  // colour-blind eye): along the middle of an edge a stage removed, its halo has gaps (dashes),
  // where the layer before, which has the edge, draws it without. Measured on the canvas's
  // pixels, that stage's layer and the halo alone on.
  const halo = await page.evaluate(() => {
    const v = window.condtViewer, d = JSON.parse(document.getElementById("data").textContent);
    const canvas = document.getElementById("canvas"), r = canvas.getBoundingClientRect();
    const longest = () => {
      let best = null;
      for (let k = 0; k < v.edges; k++) for (let s = 2; s < v.edgeLayers; s++) {
        const now = (d.member[k] >> s) & 1, before = (d.member[k] >> (s - 1)) & 1;
        if (!before || now) continue;
        const [a, b] = v.edgeEnds(k).map((i) => v.screenOf(i)), length = Math.hypot(a[0] - b[0], a[1] - b[1]);
        if (!best || length > best.length) best = { k, s, a, b, length };
      }
      return best;
    };
    const gaps = (edge, s, name) => {
      v.only(s === d.layers.length - 1 ? d.layers[s] + " (the result)" : d.layers[s]);
      for (const box of document.querySelectorAll("#layers input")) {
        if (box.dataset.layer === name) { box.checked = true; box.dispatchEvent(new Event("change")); }
      }
      return new Promise((done) => requestAnimationFrame(() => {
        const ctx = canvas.getContext("2d"), ratio = canvas.width / r.width;
        let empty = 0;
        for (let t = 0.2; t <= 0.8; t += 0.6 / 120) {
          const x = (edge.a[0] + t * (edge.b[0] - edge.a[0]) - r.left) * ratio, y = (edge.a[1] + t * (edge.b[1] - edge.a[1]) - r.top) * ratio;
          if (ctx.getImageData(Math.round(x), Math.round(y), 1, 1).data[3] === 0) empty++;
        }
        done(empty);
      }));
    };
    const removed = longest();
    return (async () => removed && {
      length: removed.length, stage: d.layers[removed.s],
      halo: await gaps(removed, removed.s, "edges a shown stage removed"),
      before: await gaps(removed, removed.s - 1, null),
    })();
  });
  assert.ok(halo && halo.length > 60, `an edge a stage removed, long on screen: ${JSON.stringify(halo)}`);
  assert.ok(halo.halo >= 10, `the removed edge's halo is dashed: ${JSON.stringify(halo)}`);
  assert.equal(halo.before, 0, `the layer before draws it whole: ${JSON.stringify(halo)}`);
  await page.evaluate(() => window.condtViewer.only(null));
  // In a high-contrast mode the legend keeps its colours (every swatch was painted over).
  await page.emulateMedia({ forcedColors: "active" });
  const forced = await page.$$eval("#layers .swatch:not(.change)", (marks) => marks.map((m) => getComputedStyle(m).backgroundColor));
  assert.deepEqual(forced, swatches.map(([, color]) => color), "swatches in forced colours");
  await page.emulateMedia({ forcedColors: "none" });

  // A point of the result: the panel shows its ring, the test and the degree the edge list has.
  const chosen = [...degree.keys()].sort((a, b) => a - b)[0];
  let [x, y] = await page.evaluate((i) => window.condtViewer.screenOf(i), chosen);
  await page.mouse.click(x, y);
  let text = await details();
  assert.match(text, new RegExp(`Point ${chosen} \\(`));
  // The details are on screen without scrolling the side panel.
  const box = await page.$eval("#details", (e) => { const r = e.getBoundingClientRect(); return [r.top, r.bottom]; });
  assert.ok(box[0] >= 0 && box[0] < 850 / 2, `details start on screen: ${box}`);
  // A drag (here from the selected point) pans and keeps the selection; so does a double
  // click on empty canvas, which shows everything again.
  const before = await page.evaluate((i) => window.condtViewer.screenOf(i), chosen);
  await page.mouse.move(x, y);
  await page.mouse.down();
  await page.mouse.move(x + 60, y + 40, { steps: 5 });
  await page.mouse.up();
  const after = await page.evaluate((i) => window.condtViewer.screenOf(i), chosen);
  assert.ok(Math.abs(after[0] - before[0] - 60) < 1 && Math.abs(after[1] - before[1] - 40) < 1, "the drag panned");
  assert.equal(await details(), text, "a drag keeps the selection");
  const corner = await page.$eval("#canvas", (c) => { const r = c.getBoundingClientRect(); return [r.left + 3, r.top + 3]; });
  await page.mouse.dblclick(corner[0], corner[1]);
  assert.equal(await details(), text, "a double click keeps the selection");
  const fitted = await page.evaluate((i) => window.condtViewer.screenOf(i), chosen);
  assert.ok(Math.abs(fitted[0] - before[0]) < 1 && Math.abs(fitted[1] - before[1]) < 1, "the double click showed everything again");
  // Keys on the focused canvas: + zooms in about the centre, 0 shows everything again.
  await page.keyboard.press("+");
  const zoomed = await page.evaluate((i) => window.condtViewer.screenOf(i), chosen);
  assert.ok(Math.abs(zoomed[0] - before[0]) + Math.abs(zoomed[1] - before[1]) > 1, "+ zoomed");
  await page.keyboard.press("0");
  const reset = await page.evaluate((i) => window.condtViewer.screenOf(i), chosen);
  assert.ok(Math.abs(reset[0] - before[0]) < 1 && Math.abs(reset[1] - before[1]) < 1, "0 showed everything");
  // n and p step through the points by index from the one selected, without a pointer (a
  // teacher's review: no point could be picked by keyboard), and wrap around.
  const count = await page.evaluate(() => JSON.parse(document.getElementById("data").textContent).points.length / 2);
  await page.keyboard.press("n");
  assert.match(await details(), new RegExp(`^Point ${(chosen + 1) % count} \\(`), "n selected the next point");
  await page.keyboard.press("p");
  await page.keyboard.press("p");
  assert.match(await details(), new RegExp(`^Point ${(chosen - 1 + count) % count} \\(`), "p the previous, wrapping");
  await page.keyboard.press("n");
  assert.equal(await details(), text, "back to the point chosen");
  // e and E step through that point's Delaunay edges by their rank there, each with its story
  // (no edge could be picked without a pointer either), and n goes on from the point.
  const ring = await page.evaluate((i) => {
    const d = JSON.parse(document.getElementById("data").textContent);
    const ranked = [];
    for (let k = 0; k < d.edges.length / 2; k++) {
      for (const end of [0, 1]) {
        if (d.edges[2 * k + end] === i && d.ends[2 * k + end] > 0) ranked.push([d.ends[2 * k + end], d.edges[2 * k + 1 - end]]);
      }
    }
    return ranked.sort((a, b) => a[0] - b[0]).map((r) => r[1]);
  }, chosen);
  const edgeTold = (other) => new RegExp(`^Edge (${chosen}–${other}|${other}–${chosen})\\b`);
  await page.keyboard.press("e");
  let stepped = await details();
  assert.match(stepped, edgeTold(ring[0]), `e: the shortest edge at ${chosen}: ${stepped}`);
  assert.match(stepped, new RegExp(`Edge 1 of ${ring.length} at point ${chosen}, rank 1 there`), stepped);
  assert.match(stepped, /(kept|dropped)\s*Edge 1 of/, `its story: ${stepped}`);
  await page.keyboard.press("e");
  assert.match(await details(), edgeTold(ring[1]), "e again: the second shortest");
  await page.keyboard.press("E");
  await page.keyboard.press("E");
  assert.match(await details(), edgeTold(ring[ring.length - 1]), "E wraps to the longest");
  await page.keyboard.press("n");
  assert.match(await details(), new RegExp(`^Point ${(chosen + 1) % count} \\(`), "n goes on from the point");
  await page.keyboard.press("p");
  assert.equal(await details(), text, "and p comes back to it");
  [x, y] = before;
  assert.match(text, new RegExp(`final degree ${degree.get(chosen)}\\b`));
  assert.match(text, /Two shortest: to \d+ \(e1\) and \d+ \(e2\)\. Uniformity test: \|e2\| = [\d.]+ \|e1\|/);
  console.log(`point ${chosen}: ${text.slice(0, 120)}...`);
  // Its coordinates, to the page's precision (7 digits over the box): shifted to UTM-like
  // metres, neighbouring samples a few units apart must still read apart (6 significant digits
  // showed 5.0000e+5 for both). Without smoothing passes the page shows the input positions.
  const input = readFileSync(join(root, data), "utf8").split("\n")
    .filter((l) => l.trim() && !l.startsWith("#")).map((l) => l.trim().split(/[\s,]+/).map(Number));
  const shifted = input.map(([px, py]) => [px + 500000, py + 4000000]);
  const shifted_file = join(dir, "shifted.txt");
  writeFileSync(shifted_file, shifted.map((p) => p.join(" ")).join("\n") + "\n");
  execFileSync(condt, ["reconstruct", shifted_file, "--no-smooth", "--format", "html", "-o", page_file]);
  await page.goto("file://" + page_file);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20000 });
  const span = Math.max(...input.map((p) => p[0])) - Math.min(...input.map((p) => p[0]));
  for (const i of [chosen]) {
    [x, y] = await page.evaluate((i) => window.condtViewer.screenOf(i), i);
    await page.mouse.click(x, y);
    const shown = (await details()).match(new RegExp(`Point ${i} \\(([^,]+), ([^)]+)\\)`));
    assert.ok(shown, `point ${i} shows its coordinates`);
    assert.ok(Math.abs(Number(shown[1]) - shifted[i][0]) <= span * 1e-6, `x of ${i}: ${shown[1]}`);
    assert.ok(Math.abs(Number(shown[2]) - shifted[i][1]) <= span * 1e-6, `y of ${i}: ${shown[2]}`);
  }
  execFileSync(condt, ["reconstruct", data, "--format", "html", "-o", page_file], { cwd: root });
  await page.goto("file://" + page_file);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20000 });

  // The shipped data repeats a point: a click there picks the first, which carries the edges,
  // and says which duplicates were merged into it.
  const merged = await page.evaluate(() => JSON.parse(document.getElementById("data").textContent).merged);
  assert.ok(merged.length >= 2, `a duplicate in ${data}: ${merged}`);
  const [copy, first] = merged;
  [x, y] = await page.evaluate((i) => window.condtViewer.screenOf(i), first);
  await page.mouse.click(x, y);
  text = await details();
  assert.match(text, new RegExp(`Point ${first} \\(`), text);
  assert.match(text, new RegExp(`exact duplicates merged into it: ${copy}\\b`), text);

  // An unused point whose edges a stage removed says which stage, edge by edge (its rows said
  // "no" and no more), as the removed edge's story does.
  const outlier = await page.evaluate(() => {
    const data = JSON.parse(document.getElementById("data").textContent), v = window.condtViewer;
    for (const i of data.unused) {
      for (let k = 0; k < v.edges; k++) {
        if ((data.member[k] & 2) && v.edgeEnds(k).includes(i)) return [i, v.edgeEnds(k).find((j) => j !== i)];
      }
    }
    return null;
  });
  assert.ok(outlier, `an unused point of ${data} had an edge in the proximity graph`);
  [x, y] = await page.evaluate((i) => window.condtViewer.screenOf(i), outlier[0]);
  await page.mouse.click(x, y);
  text = await details();
  assert.match(text, new RegExp(`Point ${outlier[0]} \\(`), text);
  const removal = text.match(new RegExp(`Last changes of its edges: (?:.*; )?to ${outlier[1]} removed by ([^;.]+)`));
  assert.ok(removal, `the unused point ${outlier[0]} says which stage removed its edge to ${outlier[1]}: ${text}`);
  console.log(`unused point ${outlier[0]}: ${removal[0]}`);

  // An edge of the result and a Delaunay edge that is not: each panel ends with the verdict.
  const edges = await page.evaluate(() => {
    const found = { kept: null, dropped: null };
    const v = window.condtViewer;
    for (let k = 0; k < v.edges; k++) {
      const [a, b] = v.edgeEnds(k);
      const kept = v.inResult(k);
      if (kept && !found.kept) found.kept = [a, b, k];
      if (!kept && v.isDelaunay(k) && !found.dropped) found.dropped = [a, b, k];
    }
    return found;
  });
  for (const [name, [a, b, k]] of Object.entries(edges)) {
    // Show only the Delaunay layer so that the click cannot land on a point instead.
    await page.evaluate(() => window.condtViewer.only("Delaunay triangulation"));
    [x, y] = await page.evaluate((k) => window.condtViewer.edgeMidpoint(k), k);
    await page.mouse.click(x, y);
    text = await details();
    assert.match(text, new RegExp(`Edge ${a}–${b}`), `${name}: ${text}`);
    const verdict = result.has(`${a}-${b}`) ? "kept" : "dropped";
    assert.equal(verdict, name, `the edge list and the page agree on ${a}-${b}`);
    assert.ok(text.trim().endsWith(verdict), `${name}: ${text}`);
    console.log(`edge ${a}-${b}: ${text}`);
  }
  assert.deepEqual(problems, [], "no script errors and nothing fetched");
  if (screenshot) {
    await page.evaluate(() => window.condtViewer.only(null));
    [x, y] = await page.evaluate((i) => window.condtViewer.screenOf(i), chosen);
    await page.mouse.click(x, y);
    await page.screenshot({ path: screenshot });
  }
  // A length just above its threshold reads apart from it, with the library's seven digits at
  // least (the page kept six, and showed "3.14146 above √T = 3.14146"): a regular 200-gon
  // whose point 199 sits 1e-6 further out, and a far point whose long edges make the IQR rule
  // (at k = 0) fire, which then cuts 199's two edges, a hair above the others.
  const gon = [];
  for (let k = 0; k < 200; k++) {
    const r = k === 199 ? 100 + 1e-6 : 100, t = (2 * Math.PI * k) / 200;
    gon.push(`${r * Math.cos(t)} ${r * Math.sin(t)}`);
  }
  const gon_file = join(dir, "gon.txt"), gon_page = join(dir, "gon.html");
  gon.push("1000 0");
  writeFileSync(gon_file, gon.join("\n") + "\n");
  execFileSync(condt, ["reconstruct", gon_file, "--paper", "--outliers-first", "--iqr", "0",
    "--format", "html", "-o", gon_page, "-q"]);
  await page.goto("file://" + gon_page);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20000 });
  const cut = await page.evaluate(() => {
    const v = window.condtViewer;
    for (let k = 0; k < v.edges; k++) {
      const [a, b] = v.edgeEnds(k);
      if (a === 0 && b === 199) return k;
    }
    return -1;
  });
  assert.ok(cut >= 0, "edge 0-199 is on the page");
  // The proximity graph alone: the polygon's sides, no chord of its triangulation beside them.
  await page.evaluate(() => window.condtViewer.only("ConDT proximity graph"));
  [x, y] = await page.evaluate((k) => window.condtViewer.edgeMidpoint(k), cut);
  await page.mouse.click(x, y);
  text = await details();
  const told = text.match(/length ([\d.]+) above √T = ([\d.]+)/);
  assert.ok(told, `the cut is told: ${text}`);
  // And what T is, for a learner who has not read Algorithm 3 (a viewer review).
  assert.match(text, /√T = [\d.]+ \(the outlier threshold: T = Q3 \+ k IQR of the squared lengths\)/);
  assert.ok(told[1] !== told[2] && Number(told[1]) > Number(told[2]), `apart: ${told[0]}`);
  assert.ok(told[2].replace(/[.]/, "").length >= 7, `seven digits at least: ${told[0]}`);
  // The layer of the stage that cut it, with the halos of what a shown stage removed: a click
  // on the cut edge's halo tells its story, though that layer no longer has the edge (it fell
  // through to a neighbouring side, or to nothing: a student's review).
  await page.evaluate(() => window.condtViewer.only("after outlier removal"));
  await page.check('input[data-layer="edges a shown stage removed"]');
  [x, y] = await page.evaluate((k) => window.condtViewer.edgeMidpoint(k), cut);
  await page.mouse.click(x, y);
  text = await details();
  assert.match(text, /^Edge 0–199\b/, `the halo of the cut edge: ${text}`);
  assert.match(text, /IQR outliers: removed length [\d.]+ above √T/, `the halo of the cut edge: ${text}`);
  // Without the halos' switch there is nothing drawn there to click.
  await page.uncheck('input[data-layer="edges a shown stage removed"]');
  await page.mouse.click(x, y);
  assert.doesNotMatch(await details(), /^Edge 0–199\b/, "no halo, no edge 0-199");
  // Zooming stops short of a scale no zoom comes back from (the page's scale reached infinity
  // after enough notches, every position then NaN).
  await page.evaluate(() => window.condtViewer.only(null));
  await page.locator("#canvas").focus();
  for (let i = 0; i < 200; i++) await page.keyboard.press("+");
  for (let i = 0; i < 400; i++) await page.keyboard.press("-");
  const far = await page.evaluate(() => window.condtViewer.screenOf(0));
  assert.ok(far.every(Number.isFinite), `positions after zooming: ${far}`);
  // Coordinates of a set spanning the doubles read as themselves, not 0 (the resolution of the
  // page's positions overflowed to infinity).
  const wide_file = join(dir, "wide.txt"), wide_page = join(dir, "wide.html");
  writeFileSync(wide_file, "1.7e308 0\n-1.7e308 0\n0 1e308\n");
  execFileSync(condt, ["reconstruct", wide_file, "--format", "html", "-o", wide_page, "-q"]);
  await page.goto("file://" + wide_page);
  await page.waitForSelector("body[data-ready=true]", { timeout: 20000 });
  [x, y] = await page.evaluate(() => window.condtViewer.screenOf(0));
  await page.mouse.click(x, y);
  text = await details();
  const at = text.match(/Point 0 \(([^,]+), ([^)]+)\)/);
  assert.ok(at && Math.abs(Number(at[1]) / 1.7e308 - 1) < 1e-6, `point 0's x: ${text.slice(0, 80)}`);

  // A set without extent on one side (one point; points on a vertical line) is drawn centred on
  // both axes, not from the canvas's corner.
  for (const [name, text] of [["one", "5 7\n"], ["vertical", "3 0\n3 1e-9\n3 2e-9\n3 3e-9\n"]]) {
    const input = join(dir, `${name}.txt`);
    const page_of = join(dir, `${name}.html`);
    writeFileSync(input, text);
    execFileSync(condt, ["reconstruct", input, "--format", "html", "-o", page_of, "-q"]);
    await page.goto("file://" + page_of);
    await page.waitForSelector("body[data-ready=true]", { timeout: 20000 });
    const [[x0, y0], [x1, y1], box] = await page.evaluate((last) => {
      const v = window.condtViewer;
      const r = document.querySelector("canvas").getBoundingClientRect();
      return [v.screenOf(0), v.screenOf(last), [r.left + r.width / 2, r.top + r.height / 2]];
    }, text.trim().split("\n").length - 1);
    const [cx, cy] = box;
    assert.ok(Math.abs(x0 - cx) < 1 && Math.abs(x1 - cx) < 1, `${name}: x ${x0}, ${x1} at the centre ${cx}`);
    assert.ok(Math.abs((y0 + y1) / 2 - cy) < 1, `${name}: y ${y0}, ${y1} around the centre ${cy}`);
  }
  // Printed, the canvas keeps its picture's shape (the screen's bitmap was stretched to the
  // page's box: circles printed as ellipses) and the legend its colours.
  await page.emulateMedia({ media: "print" });
  const printed = await page.evaluate(() => [getComputedStyle(document.querySelector("canvas")).objectFit,
    getComputedStyle(document.querySelector("#layers .swatch")).printColorAdjust]);
  assert.deepEqual(printed, ["contain", "exact"], "print styles");
  await page.emulateMedia({ media: "screen" });
  // Without JavaScript the page says so, with the result's counts, and shows no panel the
  // script would fill ("Click a point or an edge." over an empty canvas).
  const noScript = await browser.newContext({ javaScriptEnabled: false });
  const still = await noScript.newPage();
  await still.goto("file://" + gon_page);
  const shown = await still.innerText("body");
  assert.match(shown, /The result: 201 points, \d+ edges? in \d+ curves? \(\d+ closed, \d+ open\), \d+ unused\./, shown);
  assert.match(shown, /JavaScript, which is off/, shown);
  assert.doesNotMatch(shown, /Click a point|Layers|Drag or arrow keys/, shown);
  await noScript.close();
  assert.deepEqual(problems, [], "the pages raised no error and fetched nothing");
  console.log("viewer test passed");
} catch (e) {
  failed = true;
  console.error(e);
} finally {
  await browser.close();
  rmSync(dir, { recursive: true, force: true });
}
process.exit(failed ? 1 : 0);
