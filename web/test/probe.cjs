// node probe.cjs SPEC.json RESULT.json
// Opens centaur report pages in headless Chromium (Debian's, driven by playwright-core; one launch for every
// page) and records what the browser tests and the benchmark assert on. SPEC:
//   {"chromium": "/usr/bin/chromium", "artifacts": DIR, "pages": [{"name", "file", "times": [t...],
//    "screenshots": {"label": t}, "play_from": t, "play_seconds": S, "runs_switch": {"times": [t...]},
//    "click_plot": fraction of the pitch plot's width, "fps_seconds": S, "reloads": N}]}
// RESULT: {"pages": [{"name", "load_ms", "first_frame_ms", "console_errors", "page_errors", "requests",
//   "runs", "start": {...}, "probes": [{"t", "time", "pelvis", "ghost", "cursor_left", "stats"}],
//   "play": {...}, "switch": [...], "fps_full", "fps_adaptive", "reload_first_frame_ms"}]}
// Modules resolve from NODE_PATH (the build tree's web/node_modules).
'use strict';
const fs = require('fs');
const path = require('path');
const { chromium } = require('playwright-core');

const ARGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-background-networking',
  '--disable-component-update', '--disable-sync', '--no-first-run', '--disable-quic', '--disable-default-apps',
  '--disable-extensions', '--mute-audio', '--no-default-browser-check'];

async function nextFrames(page, n = 2) {
  await page.evaluate((k) => new Promise((resolve) => {
    const step = (i) => (i === 0 ? resolve() : requestAnimationFrame(() => step(i - 1)));
    step(k);
  }), n);
}

async function probeAt(page, t) {
  await page.evaluate((x) => window.centaurReport.seek(x), t);
  await nextFrames(page);
  return page.evaluate(() => {
    const r = window.centaurReport;
    return { time: r.time(), pelvis: r.pelvis(), ghost: r.ghostWaist(), cursor_left: r.cursorLeft('pitch'),
      stats: r.pixelStats() };
  });
}

/** Frames rendered per second while replaying at 1x, at full resolution or with the adaptive resolution. */
async function measureFps(page, seconds, adaptive) {
  await page.evaluate((ad) => {
    const r = window.centaurReport;
    r.setAdaptive(ad);
    r.seek(r.range()[0]);
    r.setSpeed(1);
    r.play();
  }, adaptive);
  await page.waitForTimeout(1000);  // let the adaptive resolution settle
  const before = await page.evaluate(() => ({ frames: window.centaurReport.framesRendered(), now: performance.now() }));
  await page.waitForTimeout(seconds * 1000);
  const after = await page.evaluate(() => {
    const r = window.centaurReport;
    const out = { frames: r.framesRendered(), now: performance.now(), time: r.time(), scale: r.renderScale() };
    r.pause();
    r.setAdaptive(true);
    return out;
  });
  return { fps: (1000 * (after.frames - before.frames)) / (after.now - before.now), frames: after.frames - before.frames,
    seconds: (after.now - before.now) / 1000, scale: after.scale };
}

async function probePage(browser, spec, artifacts) {
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const page = await context.newPage();
  const url = 'file://' + path.resolve(spec.file);
  const out = { name: spec.name, console_errors: [], page_errors: [], requests: [], probes: [] };
  page.on('console', (m) => { if (m.type() === 'error') out.console_errors.push(m.text()); });
  page.on('pageerror', (e) => out.page_errors.push(String(e)));
  await context.route('**/*', (route) => {
    const u = route.request().url();
    if (u === url) return route.continue();
    out.requests.push(u);
    return route.abort();
  });
  const t0 = Date.now();
  await page.goto(url, { waitUntil: 'load' });
  await page.waitForFunction(() => window.centaurReport && window.centaurReport.ready(), null, { timeout: 60000 });
  out.load_ms = Date.now() - t0;
  out.first_frame_ms = await page.evaluate(() => window.centaurReport.firstFrameMs());
  out.runs = await page.evaluate(() => window.centaurReport.runs());
  out.plots = await page.evaluate(() => window.centaurReport.plotIds());
  await page.evaluate(() => window.centaurReport.pause());
  for (const t of spec.times || []) out.probes.push(Object.assign({ t }, await probeAt(page, t)));
  for (const [label, t] of Object.entries(spec.screenshots || {})) {
    await probeAt(page, t);
    await page.screenshot({ path: path.join(artifacts, `${spec.name}-${label}.png`) });
  }
  if (spec.play_seconds) {  // the replay advances and the cursor with it
    const a = await probeAt(page, spec.play_from);
    await page.evaluate(() => { window.centaurReport.setSpeed(1); window.centaurReport.play(); });
    await page.waitForTimeout(spec.play_seconds * 1000);
    const b = await page.evaluate(() => {
      const r = window.centaurReport;
      r.pause();
      return { time: r.time(), cursor_left: r.cursorLeft('pitch') };
    });
    out.play = { before: { time: a.time, cursor_left: a.cursor_left }, after: b };
  }
  if (spec.click_plot) {  // a click in the pitch plot seeks the replay to the clicked time
    await page.evaluate(() => window.centaurReport.seek(window.centaurReport.range()[0]));
    const over = page.locator('.plot[data-plot="pitch"] .u-over');
    const box = await over.boundingBox();
    await over.click({ position: { x: spec.click_plot * box.width, y: 0.5 * box.height } });
    await nextFrames(page);
    out.click = await page.evaluate(() => ({ time: window.centaurReport.time(), range: window.centaurReport.range(),
      cursor_left: window.centaurReport.cursorLeft('pitch') }));
    out.click.width = box.width;
  }
  if (spec.runs_switch) {
    out.switch = [];
    for (let i = 0; i < out.runs.length; i++) {
      await page.evaluate((k) => window.centaurReport.selectRun(k), i);
      const probes = [];
      for (const t of spec.runs_switch.times) probes.push(Object.assign({ t }, await probeAt(page, t)));
      const run = await page.evaluate(() => window.centaurReport.currentRun());
      const title = await page.evaluate(() => document.getElementById('run').selectedOptions[0].textContent);
      await page.screenshot({ path: path.join(artifacts, `${spec.name}-run${i}.png`) });
      out.switch.push({ run, title, probes });
    }
  }
  if (spec.fps_seconds) {
    out.fps_full = await measureFps(page, spec.fps_seconds, false);
    out.fps_adaptive = await measureFps(page, spec.fps_seconds, true);
  }
  if (spec.reloads) {  // time to first frame of fresh loads
    out.reload_first_frame_ms = [];
    for (let i = 0; i < spec.reloads; i++) {
      await page.reload({ waitUntil: 'load' });
      await page.waitForFunction(() => window.centaurReport && window.centaurReport.firstFrameMs() !== null,
        null, { timeout: 60000 });
      out.reload_first_frame_ms.push(await page.evaluate(() => window.centaurReport.firstFrameMs()));
    }
  }
  await context.close();
  return out;
}

async function main() {
  const spec = JSON.parse(fs.readFileSync(process.argv[2], 'utf8'));
  const artifacts = spec.artifacts || path.dirname(process.argv[3]);
  fs.mkdirSync(artifacts, { recursive: true });
  const t0 = Date.now();
  const browser = await chromium.launch({ executablePath: spec.chromium || '/usr/bin/chromium', args: ARGS });
  const result = { launch_ms: Date.now() - t0, browser: browser.version(), pages: [] };
  try {
    for (const p of spec.pages) result.pages.push(await probePage(browser, p, artifacts));
  } finally {
    await browser.close();
  }
  fs.writeFileSync(process.argv[3], JSON.stringify(result, null, 1));
}

main().catch((e) => {
  console.error(e && e.stack ? e.stack : String(e));
  process.exit(1);
});
