// node web/test/bench.cjs BUILD_DIR WORK_DIR [REPEATS]   (NODE_PATH=BUILD_DIR/web/node_modules)
// The report benchmark (docs/benchmarks.md, "HTML report"): plans both jumps, simulates a 5 s squat jump and runs
// the 8-run comparison into WORK_DIR (once; reused when present), then
//   - generation time and size: `centaur report` of the squat jump (with its plan) and of the 8 logs, REPEATS
//     times each, interleaved;
//   - in headless Chromium (probe.cjs): time to first frame (navigation start to the first WebGL frame) of
//     REPEATS fresh loads, and the replay frame rate at 1x, at full resolution and with the adaptive resolution.
// Prints medians (min-max). The machine is shared: run it twice and compare.
'use strict';
const { execFileSync } = require('child_process');
const fs = require('fs');
const path = require('path');

const [build, work, repeatsArg] = process.argv.slice(2);
if (!build || !work) {
  console.error('usage: node bench.cjs BUILD_DIR WORK_DIR [REPEATS]');
  process.exit(2);
}
const repeats = Number(repeatsArg || 5);
const centaur = path.join(build, 'src/cli/centaur');
const f = (name) => path.join(work, name);
const sh = (args) => execFileSync(centaur, args, { stdio: ['ignore', 'pipe', 'inherit'] }).toString();

function median(v) {
  const s = [...v].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : 0.5 * (s[m - 1] + s[m]);
}
const stat = (v, digits = 2) => `${median(v).toFixed(digits)} (${Math.min(...v).toFixed(digits)}-${Math.max(...v).toFixed(digits)})`;

fs.mkdirSync(work, { recursive: true });
if (!fs.existsSync(f('primitives.h5'))) {
  sh(['plan', 'squat-jump', '--out', f('primitives.h5')]);
  sh(['plan', 'half-squat-jump', '--out', f('primitives.h5'), '--append']);
}
if (!fs.existsSync(f('jump.h5'))) {
  sh(['simulate', 'squat-jump', '--primitive', f('primitives.h5'), '--stabilizer', 'raibert', '--out', f('jump.h5')]);
}
if (!fs.existsSync(f('compare/report.html'))) sh(['compare', '--out', f('compare'), '--primitives', f('primitives.h5')]);
const logs = fs.readdirSync(f('compare')).filter((n) => /^(squat|half-squat)-jump-.*\.h5$/.test(n)).sort()
  .map((n) => f(path.join('compare', n)));

const gen = { jump: { s: [], bytes: 0 }, compare: { s: [], bytes: 0 } };
for (let i = 0; i < repeats; i++) {
  for (const [key, args] of [['jump', ['report', f('jump.h5'), '--primitive', f('primitives.h5'), '--out', f('jump.html')]],
    ['compare', ['report', ...logs, '--primitive', f('primitives.h5'), '--out', f('compare.html')]]]) {
    const out = sh([...args, '--json']).trim().split('\n');
    const j = JSON.parse(out[out.length - 1]);
    gen[key].s.push(j.generation_s);
    gen[key].bytes = j.bytes;
    gen[key].runs = j.runs;
  }
}
const spec = { chromium: '/usr/bin/chromium', artifacts: f('screenshots'), pages: [
  { name: 'jump', file: f('jump.html'), reloads: repeats, fps_seconds: 5 },
  { name: 'compare', file: f('compare.html'), reloads: repeats, fps_seconds: 5 }] };
fs.writeFileSync(f('bench-spec.json'), JSON.stringify(spec));
execFileSync(process.execPath, [path.join(__dirname, 'probe.cjs'), f('bench-spec.json'), f('bench-result.json')],
  { stdio: 'inherit' });
const result = JSON.parse(fs.readFileSync(f('bench-result.json'), 'utf8'));
console.log(`chromium ${result.browser}, launch ${result.launch_ms} ms`);
for (const page of result.pages) {
  const g = gen[page.name];
  const first = [page.first_frame_ms, ...page.reload_first_frame_ms].map((x) => x / 1000);
  console.log(`${page.name}: ${g.runs} run(s), ${(g.bytes / 1e6).toFixed(2)} MB, generation ${stat(g.s)} s, ` +
    `first frame ${stat(first)} s, replay ${page.fps_full.fps.toFixed(1)} fps full resolution, ` +
    `${page.fps_adaptive.fps.toFixed(1)} fps adaptive (scale ${page.fps_adaptive.scale})`);
}
