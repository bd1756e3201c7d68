// The metadata panel: the run's numbers (outcome, pitch, torque ratio, wall contact ...), the plan's solver
// outcome, and both effective configurations (collapsible).

function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
  for (const c of children) e.append(c);
  return e;
}

function formatValue(value, unit) {
  if (value === null || value === undefined) return '-';
  if (typeof value === 'number') {
    const text = Math.abs(value) >= 1000 || value === 0 ? value.toFixed(0) : value.toPrecision(4);
    return unit ? `${text} ${unit}` : text;
  }
  return String(value);
}

function table(rows) {
  const t = el('table');
  for (const [label, value, cls] of rows) {
    const v = el('td', { class: `v ${cls || ''}` }, value);
    t.append(el('tr', {}, el('td', {}, label), v));
  }
  return t;
}

function outcomeClass(text) {
  if (text === 'success' || text === 'solved') return 'good';
  return 'bad';
}

function config(title, yaml) {
  return el('details', {}, el('summary', {}, title), el('pre', {}, yaml || '(none)'));
}

/** Fill `aside` with the metadata of `run`. */
export function showMetadata(aside, run) {
  aside.textContent = '';
  aside.append(el('h2', {}, run.kind === 'log' ? 'Run' : 'Plan'));
  const rows = [];
  if (run.kind === 'log') {
    rows.push(['scenario', run.scenario]);
    for (const m of run.metrics.items) {
      const cls = m.key === 'outcome' ? outcomeClass(m.value) : '';
      rows.push([m.label, formatValue(m.value, m.unit), cls]);
    }
    aside.append(table(rows));
    if (run.metrics.source === 'log') {
      aside.append(el('p', { class: 'note' }, 'This log has no summary from the simulator: the numbers are computed from its datasets.'));
    }
    aside.append(el('p', { class: 'note' }, `log: ${run.log}`));
  }
  if (run.plan) {
    const p = run.plan;
    aside.append(el('h2', {}, 'Primitive'));
    aside.append(table([
      ['name', p.name],
      ['solver status', p.solve_status, outcomeClass(p.solve_status)],
      ['iterations', String(p.solve_iterations)],
      ['final cost', formatValue(p.final_cost, '')],
      ['max constraint violation', formatValue(p.max_constraint_violation, '')],
      ['solve time', formatValue(p.solve_time_s, 's')],
      ['duration', formatValue(p.duration_s, 's')],
      ['planned flight', formatValue(p.flight_time_s, 's')],
      ['planned apex (waist)', formatValue(p.apex_height_m, 'm')],
    ]));
    aside.append(el('p', { class: 'note' }, `file: ${p.file}`));
  } else if (run.kind === 'log') {
    aside.append(el('p', { class: 'note' }, 'No primitive given: no ghost (centaur report LOG --primitive F.h5).'));
  }
  if (run.kind === 'log') aside.append(config('Effective configuration of the run', run.config_yaml));
  if (run.plan) aside.append(config('Effective configuration of the plan', run.plan.config_yaml));
}
