// How long the HTML viewer of 100,000 points takes to load in headless Chromium.
//
//   node load_time.mjs CONDT_BINARY [RUNS]
//
// It writes 100,000 points along 20 circles (fixed, with a little jitter), reconstructs them to
// an HTML page with the binary, opens the page from file:// RUNS times (default 5) and prints
// each time from the start of navigation until the viewer is drawn and ready, and the median.
// A measurement for the docs, not a test: it asserts nothing about time.
import { chromium } from "playwright-core";
import { execFileSync } from "node:child_process";
import { mkdtempSync, rmSync, writeFileSync, statSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";

const [binary, runsText] = process.argv.slice(2);
const runs = Number(runsText || 5);
const dir = mkdtempSync(join(tmpdir(), "condt-load-"));
// A small linear congruential generator, so that every run measures the same points.
let state = 12345;
const random = () => (state = (state * 1103515245 + 12345) % 2147483648) / 2147483648;
const lines = [];
for (let c = 0; c < 20; c++) {
  const [cx, cy, r] = [random() * 100, random() * 100, 2 + random() * 8];
  for (let k = 0; k < 5000; k++) {
    const t = (2 * Math.PI * k) / 5000;
    lines.push(`${cx + r * Math.cos(t) + (random() - 0.5) * 2e-4} ${cy + r * Math.sin(t) + (random() - 0.5) * 2e-4}`);
  }
}
const points = join(dir, "p100k.txt");
const page_file = join(dir, "p100k.html");
writeFileSync(points, lines.join("\n") + "\n");
execFileSync(resolve(binary), ["reconstruct", points, "-o", page_file], { stdio: "ignore" });
const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
  args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
const times = [];
for (let k = 0; k < runs; k++) {
  const page = await browser.newPage({ viewport: { width: 1400, height: 850 } });
  const start = Date.now();
  await page.goto("file://" + page_file);
  await page.waitForSelector("body[data-ready=true]", { timeout: 60000 });
  times.push(Date.now() - start);
  await page.close();
}
await browser.close();
const size = statSync(page_file).size;
rmSync(dir, { recursive: true, force: true });
times.sort((a, b) => a - b);
console.log(`100,000 points, page ${(size / 1e6).toFixed(1)} MB; load to ready, ms: ${times.join(", ")}; median ${times[Math.floor(times.length / 2)]} ms`);
