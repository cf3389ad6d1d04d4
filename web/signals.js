// The signal monitor: every gateway signal with its live value, filters, writes, and a tick to
// plot it.
import {el, getJSON, postSignal, status} from './api.js';

const DIRECTIONS = {
  plc_to_nc: 'PLC \u2192 NC',
  nc_to_plc: 'NC \u2192 PLC',
  machine_to_plc: 'machine \u2192 PLC',
  plc_to_machine: 'PLC \u2192 machine',
};
const POLL_MS = 400;

export class SignalMonitor {
  constructor(root, {onValues, onPlotToggle, isPlotted}) {
    this.root = root;
    this.onValues = onValues;
    this.onPlotToggle = onPlotToggle;
    this.isPlotted = isPlotted;
    this.rows = new Map();
    this.wanted = () => false;
    this.timer = 0;
    this.busy = false;

    this.filter = el('input', {
      type: 'search',
      placeholder: 'filter by name…',
      class: 'filter',
      'aria-label': 'filter signals by name'
    });
    this.area = el('select', {'aria-label': 'area'}, el('option', {value: '', text: 'all areas'}));
    this.dir =
        el('select', {'aria-label': 'direction'}, el('option', {value: '', text: 'all directions'}),
           ...Object.entries(DIRECTIONS).map(([v, t]) => el('option', {value: v, text: t})));
    this.writableOnly = el('input', {type: 'checkbox'});
    this.count = el('span', {class: 'count'});
    for (const c of [this.filter, this.area, this.dir, this.writableOnly])
      c.addEventListener('input', () => this.applyFilter());
    root.append(
        el('div', {class: 'toolbar'}, this.filter, this.area, this.dir,
           el('label', {class: 'check'}, this.writableOnly, ' writable'), this.count));
    this.tbody = el('tbody');
    this.table =
        el('table', {class: 'grid signals'},
           el('thead', {},
              el('tr', {}, el('th', {class: 'c-plot', title: 'plot', text: '\u223f'}),
                 el('th', {text: 'Signal'}), el('th', {text: 'Area'}),
                 el('th', {text: 'Direction'}), el('th', {text: 'Type'}),
                 el('th', {class: 'num', text: 'Value'}), el('th', {text: 'Write'}))),
           this.tbody);
    this.scroller = el('div', {class: 'scroll'}, this.table);
    root.append(this.scroller);
    this.tbody.append(
        el('tr', {}, el('td', {colspan: '7', class: 'empty', text: 'loading signals…'})));
  }

  // Polls only while someone looks: the monitor or a plot of signals.
  setWanted(fn) {
    this.wanted = fn;
    this.kick();
  }

  kick() {
    if (!this.timer && !this.busy && this.wanted()) this.poll();
  }

  async poll() {
    this.timer = 0;
    if (!this.wanted()) return;
    this.busy = true;
    let wait = POLL_MS;
    try {
      const a = await getJSON('api/signals');
      this.update(a.signals || []);
    } catch (e) {
      wait = 1000;  // the state poll reports the connection
    }
    this.busy = false;
    this.timer = setTimeout(() => this.poll(), wait);
  }

  update(signals) {
    if (signals.length !== this.rows.size || signals.some((s) => !this.rows.has(s.name)))
      this.build(signals);
    const values = new Map();
    for (const s of signals) {
      values.set(s.name, s.value);
      const r = this.rows.get(s.name);
      const text = formatValue(s.value, s.type);
      if (r.valueText !== text) {
        const first = r.valueText === undefined;
        r.valueText = text;
        r.value.textContent = text;
        if (!first) {
          // restart the highlight's animation
          r.row.classList.remove('changed');
          void r.row.offsetWidth;
          r.row.classList.add('changed');
        }
      }
    }
    this.onValues(values, signals);
  }

  build(signals) {
    this.rows.clear();
    this.tbody.replaceChildren();
    const areas = [...new Set(signals.map((s) => s.area))].sort();
    const keep = this.area.value;
    this.area.replaceChildren(
        el('option', {value: '', text: 'all areas'}),
        ...areas.map((a) => el('option', {value: a, text: a})));
    this.area.value = areas.includes(keep) ? keep : '';
    const frag = document.createDocumentFragment();
    for (const s of signals) {
      const plot = el('input', {type: 'checkbox', title: `plot ${s.name}`});
      plot.checked = this.isPlotted(s.name);
      plot.disabled = s.type === 'STRING';
      plot.addEventListener('change', () => this.onPlotToggle(s.name, plot.checked));
      const value = el('td', {class: 'num val'});
      const row = el(
          'tr', {}, el('td', {class: 'c-plot'}, plot), el('td', {class: 'name', text: s.name}),
          el('td', {text: s.area}),
          el('td', {class: `dir d-${s.direction}`, text: DIRECTIONS[s.direction] || s.direction}),
          el('td', {class: 'type', text: s.type}), value,
          // the server takes numbers and booleans only
          el('td', {class: 'write'}, s.writable && s.type !== 'STRING' ? this.writer(s) : null));
      frag.append(row);
      this.rows.set(s.name, {row, value, plot, s, key: s.name.toLowerCase()});
    }
    this.tbody.append(frag);
    this.applyFilter();
  }

  writer(s) {
    const input = el('input', {
      class: 'w-in',
      placeholder: s.type === 'BOOL' ? '0/1' : s.type.toLowerCase(),
      'aria-label': `value for ${s.name}`
    });
    const send = async () => {
      const v = parseValue(input.value, s.type);
      if (v === undefined) {
        status(`${s.name}: "${input.value}" is not a ${s.type}`, 'error');
        return;
      }
      const a = await postSignal(s.name, v);
      if (a.ok) input.value = '';
    };
    input.addEventListener('keydown', (e) => {
      if (e.key === 'Enter') send();
    });
    const parts =
        [input, el('button', {class: 'w-btn', type: 'button', text: 'Set', onclick: send})];
    if (s.type === 'BOOL') {
      parts.push(el('button', {
        class: 'w-btn',
        type: 'button',
        text: 'Toggle',
        title: 'write the inverse of the live value',
        onclick: () => {
          const r = this.rows.get(s.name);
          postSignal(s.name, r && r.valueText === '1' ? 0 : 1);
        }
      }));
    }
    return el('span', {class: 'w'}, ...parts);
  }

  applyFilter() {
    const f = this.filter.value.trim().toLowerCase();
    const area = this.area.value, dir = this.dir.value, writable = this.writableOnly.checked;
    let shown = 0;
    for (const r of this.rows.values()) {
      const ok = (!f || r.key.includes(f)) && (!area || r.s.area === area) &&
          (!dir || r.s.direction === dir) && (!writable || r.s.writable);
      if (r.row.hidden === ok) r.row.hidden = !ok;
      if (ok) shown++;
    }
    this.count.textContent = `${shown} of ${this.rows.size}`;
  }

  setPlotted(name, on) {
    const r = this.rows.get(name);
    if (r) r.plot.checked = on;
  }
}

export function formatValue(v, type) {
  if (v === true) return '1';
  if (v === false) return '0';
  if (v == null) return '—';
  if (type === 'REAL' && typeof v === 'number') return String(Number(v.toPrecision(7)));
  return String(v);
}

function parseValue(text, type) {
  const t = text.trim();
  if (type === 'BOOL') {
    if (/^(1|true|on|yes)$/i.test(t)) return 1;
    if (/^(0|false|off|no)$/i.test(t)) return 0;
    return undefined;
  }
  if (t === '') return undefined;
  const n = Number(t);
  if (!isFinite(n)) return undefined;
  if (type === 'REAL') return n;
  return Number.isInteger(n) ? n : undefined;
}
