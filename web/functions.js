// The control's functions as the operator reads them beside the program: the REPOS screen
// (repositioning manual 2.2), the headstock (C-axis manual 2.3: spindle or rotary axis mode,
// the changeover, ROTMOD/SPMOD and their acknowledgements, clutch K), block search (its HLI
// state), the probe's switches and latches and the machine data pages of fast measurement.
// Rebuilt from each state where it changed; the markup is small.

const fmt = (v, d = 3) => (typeof v === 'number' ? v.toFixed(d) : v == null ? '—' : String(v));
const esc = (s) => String(s).replace(
    /[&<>"]/g, (c) => ({'&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;'}[c]));
const flag = (on, text) => `<span class="fn-flag ${on ? 'on' : ''}">${esc(text)}</span>`;

export class Functions {
  constructor(root) {
    this.root = root;
    this.root.innerHTML = `
      <div class="fn-grid">
        <section class="fn-card" data-fn="repos"><h3>REPOS screen</h3><div class="fn-body"></div></section>
        <section class="fn-card" data-fn="headstock"><h3>Headstock</h3><div class="fn-body"></div></section>
        <section class="fn-card" data-fn="block-search"><h3>Block search</h3><div class="fn-body"></div></section>
        <section class="fn-card" data-fn="probe"><h3>Probe</h3>
          <div class="fn-switches"></div><div class="fn-body"></div></section>
        <section class="fn-card fn-wide" data-fn="measuring-pages"><h3>Measuring pages</h3>
          <div class="fn-body"></div></section>
      </div>`;
    this.body = (name) => this.root.querySelector(`[data-fn="${name}"] .fn-body`);
    this.last = {};
  }

  // Only what changed is redrawn: the state comes 30 times a second.
  update(state) {
    this.draw('repos', state.repos, (r) => this.repos(r));
    this.draw('headstock', state.headstock, (h) => this.headstock(h));
    this.draw('block-search', state.block_search, (b) => this.blockSearch(b));
    this.draw('probe', state.probe, (p) => this.probe(p));
    this.drawInto(
        this.root.querySelector('.fn-switches'), 'probe-switches', state.probe_switches,
        (l) => this.probeSwitches(l));
    this.draw('measuring-pages', state.measuring_pages, (m) => this.measuringPages(m));
  }

  drawInto(node, name, data, render) {
    const key = JSON.stringify(data ?? null);
    if (this.last[name] === key) return;
    this.last[name] = key;
    node.innerHTML = data && data.length ? render(data) : '';
  }

  draw(name, data, render) {
    const key = JSON.stringify(data ?? null);
    if (this.last[name] === key) return;
    this.last[name] = key;
    this.body(name).innerHTML = data ? render(data) : '<span class="muted">—</span>';
  }

  repos(r) {
    const head = [
      flag(r.function && r.function !== 'none', r.function || 'no function'),
      flag(r.allowed, 'REPOS allowed'), flag(r.conditions_restored, 'CREST'),
      flag(r.left_contour, 'left contour'), flag(r.subroutine, 'subroutine')
    ].join(' ');
    const rows = Object.entries(r.axes || {})
                     .map(
                         ([name, a]) => `<tr>
        <td class="mono">${esc(name)}</td><td class="num">${fmt(a.final)}</td>
        <td class="num">${fmt(a.command)}</td><td class="num">${fmt(a.to_go)}</td>
        <td class="adj">${
                             a.relevant === false ? '' :
                                 a.adjust         ? '&#9650; adjust' :
                                                    '&#10003;'}</td></tr>`)
                     .join('');
    const sp = r.spindle || {};
    return `<div class="fn-flags">${head}</div>
      <table class="grid fn-table"><thead><tr><th>Axis</th><th class="num">end value</th>
        <th class="num">command</th><th class="num">to go</th><th>adjust</th></tr></thead>
        <tbody>${rows}</tbody></table>
      <div class="fn-kv">
        <span>S: M${fmt(sp.command_m, 0)} ${fmt(sp.command_rpm, 1)} rpm (actual M${
        fmt(sp.actual_m, 0)} ${fmt(sp.actual_rpm, 1)})${sp.adjust ? ' &#9650; adjust' : ''}</span>
        <span>F ${fmt(r.F, 1)} &times;${fmt(r.feed_override, 2)}</span>
        <span>${esc(r.program || '—')} line ${fmt(r.line, 0)}</span>
        <span>T${fmt(r.T, 0)} D${fmt(r.D, 0)}</span>
        <span>M ${(r.M || []).join(' ')}</span>
        <span>G ${(r.G || []).map((g) => String(g).padStart(2, '0')).join(' ')}</span>
      </div>`;
  }

  headstock(h) {
    const signals = Object.entries(h.signals || {}).map(([n, v]) => flag(v, n)).join(' ');
    const clutches =
        Object.entries(h.clutches || {}).map(([n, s]) => `${esc(n)}: <b>${esc(s)}</b>`).join(', ');
    return `<div class="fn-kv">
        <span>mode <b>${esc(h.mode)}</b></span><span>target ${esc(h.target)}</span>
        ${h.busy ? '<span class="warn">changing over</span>' : ''}
        <span>${esc(h.axis)} ${fmt(h.position)} deg</span>
        <span>clutch ${clutches || '—'}</span></div>
      <div class="fn-flags">${signals}</div>`;
  }

  // One edge latches every measuring axis: the latches of one instant are one row.
  probe(p) {
    const rows = new Map();
    for (const l of p.latches || []) {
      const key = `${fmt(l.t)} ${l.edge || ''}`;
      if (!rows.has(key)) rows.set(key, {t: l.t, edge: l.edge, axes: []});
      rows.get(key).axes.push(`${esc(l.drive)} ${fmt(l.value)}`);
    }
    const body = [...rows.values()]
                     .reverse()
                     .map((r) => `<tr><td class="num">${fmt(r.t)}</td><td>${esc(r.edge || '')}</td>
        <td class="mono">${r.axes.join(' &nbsp; ')}</td></tr>`)
                     .join('');
    const point = Array.isArray(p.point) ?
        ` &middot; touched at (${p.point.map((c) => fmt(c * 1000, 2)).join(', ')}) mm` :
        '';
    return `<div class="fn-kv"><span>last: ${esc(p.drive)} = ${fmt(p.value)} at t = ${fmt(p.t)} s${
        point}</span></div>
      <table class="grid fn-table" data-probe-latches><thead><tr><th class="num">t (s)</th>
        <th>edge</th><th>latched values (mm | deg)</th></tr></thead><tbody>${body}</tbody></table>`;
  }

  // The switch of each stylus (its input) and its ready message, as the PLC reads them.
  probeSwitches(list) {
    return `<div class="fn-flags" data-probe-switches>${
        list.map(
                (p) => `${flag(p.on, `${p.contact || p.pin} (T${p.t})`)}${
                    p.ready_input ? flag(p.ready, p.ready_input) : ''}`)
            .join(' ')}</div>`;
  }

  // The machine data pages of fast measurement (MTD): per page its set rows, one column per
  // element, the element's designation as the column's title.
  measuringPages(pages) {
    const num = (v) => (Number.isInteger(v) ? String(v) : fmt(v, 4));
    return pages
        .map((page) => {
          const head =
              page.elements.map((d, i) => `<th class="num" title="${esc(d)}">${i + 1}</th>`)
                  .join('');
          const rows =
              page.rows
                  .map(
                      (r) =>
                          `<tr><td>${[r.lv1, r.lv2].filter((v) => v != null).join('/') || ''}</td>${
                              r.values.map((v) => `<td class="num">${num(v)}</td>`).join('')}</tr>`)
                  .join('');
          return `<details class="fn-page" data-measuring-page="${esc(page.name)}" ${
              page.rows.length && page.name !== 'ZWISCHENSPEICHERPAGE' ? 'open' : ''}>
            <summary>${esc(page.name)} (${page.number}) &middot; ${page.rows.length} rows</summary>
            <div class="fn-scroll"><table class="grid fn-table"><thead><tr><th>LV</th>${head}</tr>
            </thead><tbody>${rows}</tbody></table></div></details>`;
        })
        .join('');
  }

  blockSearch(b) {
    const rest = Object.entries(b)
                     .filter(([k]) => k !== 'state' && k !== 'active')
                     .map(
                         ([k, v]) => `<span>${esc(k)} ${
                             esc(typeof v === 'object'   ? JSON.stringify(v) :
                                     Number.isInteger(v) ? String(v) :
                                                           fmt(v))}</span>`)
                     .join('');
    return `<div class="fn-flags">${flag(b.active, b.state || '—')}</div><div class="fn-kv">${
        rest}</div>`;
  }
}
