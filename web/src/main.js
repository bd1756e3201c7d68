// The report page: parses the embedded data (docs/report.md), builds the 3D view, the controls, the plots and
// the metadata panel, and replays the selected run. window.centaurReport is the page's small API (seek, play,
// run selection, read-backs) used by the browser tests and the benchmark.
import css from './page.css';
import uplotCss from 'uplot/dist/uPlot.min.css';
import * as THREE from 'three';
import { View3D } from './view3d.js';
import { Plots } from './plots.js';
import { showMetadata } from './panel.js';
import { channels, float32, locate } from './decode.js';

const SPEEDS = [0.1, 0.25, 0.5, 1, 2];
const FORCE_SCALES = [0.00025, 0.0005, 0.001, 0.002];  // [m/N]

function layout(data) {
  const style = document.createElement('style');
  style.textContent = uplotCss + '\n' + css;
  document.head.appendChild(style);
  document.body.insertAdjacentHTML('beforeend', `
<header><h1></h1><label id="run-label">run <select id="run"></select></label></header>
<main>
 <section>
  <div id="view"><canvas id="canvas"></canvas>
   <div id="legend"></div><div id="clock"></div></div>
  <div id="controls">
   <button id="play">Play</button>
   <label>speed <select id="speed">${SPEEDS.map((s) => `<option value="${s}"${s === 1 ? ' selected' : ''}>${s}x</option>`).join('')}</select></label>
   <input id="slider" type="range" step="0.001">
   <label><input id="follow" type="checkbox" checked> follow robot</label>
   <label><input id="show-ghost" type="checkbox" checked> plan (ghost)</label>
   <label><input id="show-forces" type="checkbox" checked> forces</label>
   <label>arrows <select id="force-scale">${FORCE_SCALES.map((s) => `<option value="${s}"${s === 0.001 ? ' selected' : ''}>${s * 1000} m/kN</option>`).join('')}</select></label>
  </div>
  <div id="plots"></div>
 </section>
 <aside id="meta"></aside>
</main>`);
  document.querySelector('header h1').textContent = data.title;
}

/** Decoded arrays of one run, built when the run is first shown. */
function decodeRun(run) {
  const d = { t0: run.t_start, t1: run.t_end };
  if (run.frames) {
    d.frameT = float32(run.frames.t);
    d.pose = channels(run.frames.pose);
    d.poseStride = run.frames.pose.channels;
    d.force = channels(run.frames.force);
    d.forceStride = run.frames.force.channels;
  }
  if (run.ghost) {
    d.ghostT = float32(run.ghost.t);
    d.ghost = channels(run.ghost.pose);
  }
  return d;
}

class Report {
  constructor(data) {
    this.data = data;
    layout(data);
    this.$ = (id) => document.getElementById(id);
    this.view = new View3D(this.$('canvas'), data.scene);
    this.plots = new Plots(this.$('plots'), (t) => this.seek(t));
    this.decoded = new Map();
    this.time = 0;
    this.playing = false;
    this.speed = 1;
    this.forceScale = 0.001;
    this.errors = [];
    this.firstFrameMs = null;
    this.adaptive = true;
    this.tmpA = new THREE.Vector3();
    this.tmpB = new THREE.Vector3();
    this.bindControls();
    // First frame first: the 3D view of run 0 is drawn before the plots and the panel are built.
    this.selectRun(0, false);
    this.view.render();
    this.view.renderer.getContext().finish();  // the frame is drawn, not only queued
    this.firstFrameMs = performance.now();
    this.ready = false;
    setTimeout(() => { this.showDetails(); this.ready = true; }, 0);
    window.addEventListener('resize', () => { this.view.dirty = true; this.plots.resize(); });
    this.lastTick = null;
    requestAnimationFrame((ts) => this.tick(ts));
  }

  /** Plots and metadata of the current run. */
  showDetails() {
    this.plots.show(this.run);
    showMetadata(this.$('meta'), this.run);
    this.plots.setTime(this.time);
  }

  bindControls() {
    const select = this.$('run');
    this.data.runs.forEach((r, i) => select.add(new Option(r.label, String(i))));
    if (this.data.runs.length < 2) this.$('run-label').style.display = 'none';
    select.addEventListener('change', () => this.selectRun(Number(select.value)));
    this.$('play').addEventListener('click', () => (this.playing ? this.pause() : this.play()));
    this.$('speed').addEventListener('change', (e) => { this.speed = Number(e.target.value); });
    this.$('slider').addEventListener('input', (e) => this.seek(Number(e.target.value)));
    for (const id of ['follow', 'show-ghost', 'show-forces']) this.$(id).addEventListener('change', () => this.apply());
    this.$('force-scale').addEventListener('change', (e) => { this.forceScale = Number(e.target.value); this.apply(); });
    window.addEventListener('keydown', (e) => {
      if (e.code === 'Space' && e.target.tagName !== 'INPUT' && e.target.tagName !== 'SELECT') {
        e.preventDefault();
        this.playing ? this.pause() : this.play();
      }
    });
  }

  selectRun(i, details = true) {
    this.index = i;
    this.run = this.data.runs[i];
    if (!this.decoded.has(i)) this.decoded.set(i, decodeRun(this.run));
    this.d = this.decoded.get(i);
    this.$('run').value = String(i);
    const slider = this.$('slider');
    slider.min = String(this.d.t0);
    slider.max = String(this.d.t1);
    this.view.world.robot.visible = !!this.run.frames;
    this.view.world.setStatic(this.run.static_pose || []);
    this.view.setContactCount(this.run.frames ? this.run.frames.force_slots.length : 0);
    if (this.run.frames) {  // blob shadows: pelvis and contact bodies (height above ground dims them)
      const f = this.run.frames;
      this.view.setShadowBodies([0, ...f.force_slots], [[0.42, 0.26], ...f.force_radius.map((r) => [1.1 * r, 1.1 * r])]);
    } else {
      this.view.setShadowBodies([], []);
    }
    if (this.run.ghost) this.view.ghost.configure(this.run.ghost);
    this.view.lastFollow = null;
    if (details) this.showDetails();
    this.legend();
    this.seek(Math.min(Math.max(this.time, this.d.t0), this.d.t1));
  }

  legend() {
    const kN = (0.5 / this.forceScale / 1000).toFixed(1);
    this.$('legend').innerHTML = (this.run.frames ? '<span class="swatch" style="background:#d0342c"></span>measured contact force<br>' : '')
      + (this.run.ghost ? '<span class="swatch" style="background:#2f6fd6;opacity:.6"></span>plan: template + planned force<br>' : '')
      + `arrow 0.5 m = ${kN} kN`;
  }

  play() {
    if (this.time >= this.d.t1) this.seek(this.d.t0);
    this.playing = true;
    this.$('play').textContent = 'Pause';
  }

  pause() {
    this.playing = false;
    this.$('play').textContent = 'Play';
  }

  seek(t) {
    this.time = Math.min(Math.max(t, this.d.t0), this.d.t1);
    this.apply();
  }

  /** Pose everything for the current time; the next animation frame renders it. */
  apply() {
    const t = this.time, d = this.d, v = this.view;
    if (this.run.frames) this.poseRobot(t);
    const showGhost = !!this.run.ghost && this.$('show-ghost').checked;
    v.ghost.object.visible = showGhost;
    if (showGhost) {
      const { k, a } = locate(d.ghostT, t);
      const k1 = Math.min(k + 1, d.ghostT.length - 1);
      const g = a < 0.5 ? k : k1;  // the plan's samples are 10 ms apart: nearest sample
      v.ghost.set(d.ghost, 31 * g, this.forceScale, this.$('show-forces').checked);
      if (!this.run.frames) v.follow(v.ghost.waist.position, this.$('follow').checked);
    }
    this.$('slider').value = String(t);
    this.$('clock').textContent = `t = ${t.toFixed(3)} s`;
    this.plots.setTime(t);
    v.dirty = true;
  }

  poseRobot(t) {
    const d = this.d, v = this.view, w = v.world;
    const { k, a } = locate(d.frameT, t);
    const k1 = Math.min(k + 1, d.frameT.length - 1);
    const s = d.poseStride, p = d.pose;
    const blended = this.blend || (this.blend = new Float64Array(s));
    for (let i = 0; i < s; i += 7) {
      const o0 = k * s + i, o1 = k1 * s + i;
      for (let c = 0; c < 3; c++) blended[i + c] = p[o0 + c] + a * (p[o1 + c] - p[o0 + c]);
      const dot = p[o0 + 3] * p[o1 + 3] + p[o0 + 4] * p[o1 + 4] + p[o0 + 5] * p[o1 + 5] + p[o0 + 6] * p[o1 + 6];
      const sign = dot < 0 ? -1 : 1;
      for (let c = 3; c < 7; c++) blended[i + c] = (1 - a) * p[o0 + c] + a * sign * p[o1 + c];
    }
    for (let b = 0; b < w.moving; b++) w.setPose(b, blended, 7 * b);
    const showForces = this.$('show-forces').checked;
    const fs = d.forceStride, f = d.force, slots = this.run.frames.force_slots;
    for (let c = 0; c < slots.length; c++) {
      const o0 = k * fs + 3 * c, o1 = k1 * fs + 3 * c;
      const fx = f[o0] + a * (f[o1] - f[o0]), fy = f[o0 + 1] + a * (f[o1 + 1] - f[o0 + 1]);
      const fz = f[o0 + 2] + a * (f[o1 + 2] - f[o0 + 2]);
      const norm = Math.hypot(fx, fy, fz);
      const arrow = v.forceArrows[c];
      if (!showForces || norm < 1.0) {
        arrow.set(this.tmpA, this.tmpB, 0);
        continue;
      }
      this.tmpB.set(fx / norm, fy / norm, fz / norm);
      this.tmpA.copy(w.bodies[slots[c]].position).addScaledVector(this.tmpB, -this.run.frames.force_radius[c]);
      arrow.set(this.tmpA, this.tmpB, norm * this.forceScale);
    }
    v.follow(w.bodies[0].position, this.$('follow').checked);
  }

  /**
   * Adaptive resolution: while playing, if the last 12 frames came slower than 30 per second (software WebGL, a
   * busy machine), render at 3/4 then 1/2 resolution; paused, always at full resolution.
   */
  adapt(ts) {
    const v = this.view;
    if (!this.playing || !this.adaptive) {
      this.frameStamps = [];
      if (v.scale !== 1) v.setScale(1);
      return;
    }
    const s = this.frameStamps || (this.frameStamps = []);
    s.push(ts);
    if (s.length < 12) return;
    const interval = (s[s.length - 1] - s[0]) / (s.length - 1);
    s.length = 0;
    if (interval > 1000 / 30 && v.scale > 0.5) v.setScale(v.scale - 0.25);
  }

  tick(ts) {
    if (this.playing && this.lastTick !== null) {
      const next = this.time + this.speed * Math.min(0.1, (ts - this.lastTick) / 1000);
      if (next >= this.d.t1) {
        this.seek(this.d.t1);
        this.pause();
      } else {
        this.seek(next);
      }
    }
    this.lastTick = ts;
    this.adapt(ts);
    if (this.view.dirty) this.view.render();
    requestAnimationFrame((t) => this.tick(t));
  }
}

function start() {
  const t0 = performance.now();
  const data = JSON.parse(document.getElementById('centaur-report-data').textContent);
  const t1 = performance.now();
  const report = new Report(data);
  report.timing = { start_ms: t0, parsed_ms: t1, built_ms: performance.now() };
  window.centaurReport = api(report);
}

/** The page's API for tests and the benchmark (read-only views and the same actions as the controls). */
function api(r) {
  return {
    version: r.data.viewer,
    runs: () => r.data.runs.map((x) => x.label),
    selectRun: (i) => { const s = document.getElementById('run'); s.value = String(i); s.dispatchEvent(new Event('change')); },
    currentRun: () => r.index,
    seek: (t) => r.seek(t),
    time: () => r.time,
    play: () => r.play(),
    pause: () => r.pause(),
    setSpeed: (s) => { r.speed = s; },
    setAdaptive: (on) => { r.adaptive = !!on; },
    renderScale: () => r.view.scale,
    range: () => [r.d.t0, r.d.t1],
    firstFrameMs: () => r.firstFrameMs,
    ready: () => r.ready,
    timing: () => Object.assign({ first_frame_ms: r.firstFrameMs }, r.timing),
    framesRendered: () => r.view.frames,
    renderNow: () => r.view.render(),
    pelvis: () => (r.run.frames ? r.view.world.bodies[0].position.toArray() : null),
    ghostWaist: () => (r.run.ghost ? r.view.ghost.waist.position.toArray() : null),
    cursorLeft: (id) => r.plots.cursorLeft(id),
    plotIds: () => r.plots.plots.map((p) => p.id),
    pixelStats: () => pixelStats(r.view),
  };
}

/** Render now and read the canvas back: mean and spread of the luminance, and a 32 x 18 thumbnail. */
function pixelStats(view) {
  view.render();
  const gl = view.renderer.getContext();
  const w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
  const px = new Uint8Array(4 * w * h);
  gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
  const TW = 32, TH = 18, thumb = new Float64Array(TW * TH), count = new Float64Array(TW * TH);
  let sum = 0, sq = 0;
  for (let y = 0; y < h; y++) {
    for (let x = 0; x < w; x++) {
      const i = 4 * (y * w + x);
      const l = 0.2126 * px[i] + 0.7152 * px[i + 1] + 0.0722 * px[i + 2];
      sum += l;
      sq += l * l;
      const c = Math.floor((y * TH) / h) * TW + Math.floor((x * TW) / w);
      thumb[c] += l;
      count[c]++;
    }
  }
  const n = w * h;
  const mean = sum / n;
  return {
    width: w, height: h, mean, std: Math.sqrt(Math.max(0, sq / n - mean * mean)),
    thumb: Array.from(thumb, (v, i) => v / Math.max(1, count[i])),
  };
}

window.addEventListener('error', (e) => { (window.centaurReportErrors ||= []).push(String(e.message)); });
if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', start); else start();
