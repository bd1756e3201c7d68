// The plots under the 3D view (uPlot): one per plot of the run, a shared hover cursor, a red replay cursor at the
// current time, and a click that seeks the replay to the clicked time.
import uPlot from 'uplot';
import { float32 } from './decode.js';

function seriesOptions(s) {
  return {
    label: s.label,
    stroke: s.color,
    width: s.dash ? 1.2 : 1.5,
    dash: s.dash ? [6, 4] : undefined,
    points: { show: false },
    value: (u, v) => (v == null ? '-' : v.toFixed(Math.abs(v) >= 100 ? 0 : 2)),
  };
}

export class Plots {
  /** `container`: the element holding the plots; `onSeek(t)` is called on a click in a plot. */
  constructor(container, onSeek) {
    this.container = container;
    this.onSeek = onSeek;
    this.plots = [];
  }

  /** Replace the plots by those of `run` (the page's run object). */
  show(run) {
    for (const p of this.plots) p.u.destroy();
    this.container.textContent = '';
    this.plots = [];
    for (const spec of run.plots) {
      const box = document.createElement('div');
      box.className = 'plot';
      box.dataset.plot = spec.id;
      this.container.appendChild(box);
      const t = float32(spec.t);
      const data = [t, ...spec.series.map((s) => float32(s.data))];
      const opts = {
        title: spec.title + (spec.unit && spec.unit !== '-' ? ` [${spec.unit}]` : ''),
        width: this.width(),
        height: 190,
        scales: { x: { time: false } },
        axes: [{ label: 't [s]' }, { size: 60 }],
        cursor: { sync: { key: 'centaur' }, drag: { x: true, y: false } },
        legend: { live: true },
        series: [{ label: 't [s]', value: (u, v) => (v == null ? '-' : v.toFixed(3)) },
          ...spec.series.map(seriesOptions)],
      };
      const u = new uPlot(opts, data, box);
      const cursor = document.createElement('div');
      cursor.className = 'replay-cursor';
      u.over.appendChild(cursor);
      u.over.addEventListener('click', (e) => {
        if (u.select.width > 2) return;  // the end of a drag-zoom, not a click
        const tc = u.posToVal(e.offsetX, 'x');
        if (Number.isFinite(tc)) this.onSeek(tc);
      });
      this.plots.push({ id: spec.id, u, cursor, t: 0, x: 0, width: u.over.clientWidth });
    }
  }

  width() { return Math.max(300, this.container.clientWidth - 8); }

  resize() {
    for (const p of this.plots) {
      p.u.setSize({ width: this.width(), height: 190 });
      p.width = p.u.over.clientWidth;
      this.place(p);
    }
  }

  /** Move every replay cursor to time t [s]. */
  setTime(t) {
    for (const p of this.plots) {
      p.t = t;
      this.place(p);
    }
  }

  /** Moves the cursor with a transform only (no layout): the replay calls this every animation frame. */
  place(p) {
    const x = p.u.valToPos(p.t, 'x');
    const inside = Number.isFinite(x) && x >= 0 && x <= p.width;
    p.x = Number.isFinite(x) ? x : 0;
    p.cursor.style.visibility = inside ? 'visible' : 'hidden';
    p.cursor.style.left = `${Math.round(p.x)}px`;
  }

  /** Position [CSS px from the plotting area's left] of the replay cursor of plot `id` (test hook). */
  cursorLeft(id) {
    const p = this.plots.find((q) => q.id === id);
    return p ? p.x : null;
  }
}
