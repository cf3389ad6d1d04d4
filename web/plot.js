// A plot of ticked signals and axis values over the last 30 s of simulated time (Chart.js 3,
// loaded as a classic script: its ES build imports names Debian's package does not ship).
import {el} from './api.js';

const WINDOW_S = 30;
const PALETTE = [
  '#4da3ff', '#f0b429', '#3ecf72', '#ef5350', '#b084f5', '#2fd4ff', '#ff8a50', '#a3d977', '#f78fb3',
  '#c9d1d9'
];

export class Plot {
  constructor(root, model, {onSignalsChanged}) {
    this.root = root;
    this.onSignalsChanged = onSignalsChanged;
    this.series = new Map();  // key -> {label, data, yAxis, colour, stepped}
    this.lastT = -Infinity;
    this.visible = false;
    this.colourIndex = 0;
    this.signalTypes = new Map();

    const side = el('div', {class: 'plot-side'});
    side.append(el('div', {class: 'ps-title', text: 'Axes'}));
    const axes =
        el('table', {class: 'ps-axes'},
           el('tr', {}, el('th'), el('th', {text: 'pos'}), el('th', {text: 'f.err'})));
    for (const a of model.axes || []) {
      const box = (kind) => {
        const c = el('input', {
          type: 'checkbox',
          title: `${a.name} ${kind === 'pos' ? 'machine position' : 'following error'}`
        });
        c.addEventListener(
            'change',
            () => this.toggle(
                `axis:${a.name}:${kind}`, c.checked,
                `${a.name} ${kind === 'pos' ? 'pos' : 'f.err'} [${a.unit || ''}]`,
                kind === 'ferr' ? 'y1' : 'y'));
        return el('td', {}, c);
      };
      axes.append(el('tr', {}, el('th', {text: a.name}), box('pos'), box('ferr')));
    }
    side.append(axes);
    side.append(el('div', {class: 'ps-title', text: 'Signals'}));
    this.signalList = el('div', {class: 'ps-signals'});
    this.datalist = el('datalist', {id: 'plot-signal-names'});
    this.addInput = el(
        'input',
        {list: 'plot-signal-names', placeholder: 'add a signal…', 'aria-label': 'signal to plot'});
    this.addInput.addEventListener('keydown', (e) => {
      if (e.key === 'Enter') this.addFromInput();
    });
    side.append(
        this.signalList,
        el('div', {class: 'ps-add'}, this.addInput,
           el('button',
              {type: 'button', class: 'w-btn', text: 'Add', onclick: () => this.addFromInput()})),
        this.datalist);
    side.append(el('div', {class: 'ps-hint', text: 'or tick \u223f in the signal table'}));
    side.append(
        el('button',
           {type: 'button', class: 'w-btn', text: 'Clear data', onclick: () => this.clearData()}));
    this.renderSignalList();

    const canvas = el('canvas');
    this.chartBox = el('div', {class: 'plot-chart'}, canvas);
    root.append(side, this.chartBox);
    if (!window.Chart) {
      this.chartBox.replaceChildren(
          el('div',
             {class: 'empty', text: 'Chart.js is not available (/vendor/chart.js/chart.min.js).'}));
      return;
    }
    const grid = 'rgba(140,155,170,0.16)', ticks = '#8d9aa8';
    this.chart = new window.Chart(canvas.getContext('2d'), {
      type: 'line',
      data: {datasets: []},
      options: {
        animation: false,
        parsing: false,
        normalized: true,
        responsive: true,
        maintainAspectRatio: false,
        elements: {point: {radius: 0}, line: {borderWidth: 1.5}},
        interaction: {mode: 'nearest', axis: 'x', intersect: false},
        scales: {
          x: {
            type: 'linear',
            title: {display: true, text: 't [s]', color: ticks},
            ticks: {color: ticks},
            grid: {color: grid}
          },
          y: {position: 'left', ticks: {color: ticks}, grid: {color: grid}},
          y1: {
            position: 'right',
            display: false,
            title: {display: true, text: 'following error', color: ticks},
            ticks: {color: ticks},
            grid: {drawOnChartArea: false}
          },
        },
        plugins: {legend: {labels: {color: '#c9d1d9', boxWidth: 12}}, tooltip: {enabled: true}},
      },
    });
    setInterval(() => this.render(), 200);
  }

  toggle(key, on, label, yAxis = 'y', stepped = false) {
    if (on && !this.series.has(key)) {
      this.series.set(
          key,
          {label, data: [], yAxis, stepped, colour: PALETTE[this.colourIndex++ % PALETTE.length]});
    } else if (!on) {
      this.series.delete(key);
    }
    if (key.startsWith('sig:')) {
      this.renderSignalList();
      this.onSignalsChanged(key.slice(4), on);
    }
    this.dirty = true;
  }

  isPlotted(name) {
    return this.series.has(`sig:${name}`);
  }
  hasSignals() {
    return [...this.series.keys()].some((k) => k.startsWith('sig:'));
  }

  toggleSignal(name, on) {
    const type = this.signalTypes.get(name);
    this.toggle(`sig:${name}`, on, name, 'y', type === 'BOOL' || type === 'INT' || type === 'DINT');
  }

  addFromInput() {
    const name = this.addInput.value.trim();
    if (!name) return;
    if (this.signalTypes.size && !this.signalTypes.has(name)) {
      this.addInput.classList.add('bad');
      return;
    }
    this.addInput.classList.remove('bad');
    this.addInput.value = '';
    this.toggleSignal(name, true);
  }

  renderSignalList() {
    const names =
        [...this.series.keys()].filter((k) => k.startsWith('sig:')).map((k) => k.slice(4));
    this.signalList.replaceChildren(
        ...(names.length ? names.map(
                               (n) => el(
                                   'div', {class: 'ps-sig'}, el('span', {
                                     class: 'swatch',
                                     style: `background:${this.series.get(`sig:${n}`).colour}`
                                   }),
                                   el('span', {class: 'ps-name', text: n, title: n}), el('button', {
                                     type: 'button',
                                     class: 'x',
                                     title: `stop plotting ${n}`,
                                     text: '\u00d7',
                                     onclick: () => this.toggle(`sig:${n}`, false)
                                   }))) :
                           [el('div', {class: 'ps-hint', text: 'none'})]));
  }

  clearData() {
    for (const s of this.series.values()) s.data = [];
    this.dirty = true;
  }

  sampleState(state) {
    const t = state.t;
    if (typeof t !== 'number') return;
    if (t < this.lastT) this.clearData();  // a new run
    if (t === this.lastT) return;
    this.lastT = t;
    for (const a of state.axes || []) {
      const pos = this.series.get(`axis:${a.name}:pos`);
      if (pos) push(pos.data, t, a.machine);
      const ferr = this.series.get(`axis:${a.name}:ferr`);
      if (ferr) push(ferr.data, t, a.following_error);
    }
  }

  // Signals carry no time of their own: they are placed at the latest state's time.
  sampleSignals(values, signals) {
    if (this.signalTypes.size !== signals.length) {
      this.signalTypes = new Map(signals.map((s) => [s.name, s.type]));
      this.datalist.replaceChildren(
          ...signals.filter((s) => s.type !== 'STRING').map((s) => el('option', {value: s.name})));
    }
    if (!isFinite(this.lastT)) return;
    for (const [key, s] of this.series) {
      if (!key.startsWith('sig:')) continue;
      let v = values.get(key.slice(4));
      if (v === true) v = 1;
      if (v === false) v = 0;
      if (typeof v === 'number') push(s.data, this.lastT, v);
    }
  }

  setVisible(v) {
    this.visible = v;
    this.dirty = true;
    if (v) this.render();
  }

  render() {
    if (!this.chart || !this.visible) return;
    const t = isFinite(this.lastT) ? this.lastT : 0;
    for (const s of this.series.values()) {
      while (s.data.length && s.data[0].x < t - WINDOW_S) s.data.shift();
    }
    // The same dataset objects each time: Chart.js keeps a legend click's hiding on them.
    const datasets = [...this.series.values()].map((s) => {
      if (!s.ds)
        s.ds = {
          label: s.label,
          borderColor: s.colour,
          backgroundColor: s.colour,
          yAxisID: s.yAxis,
          stepped: s.stepped
        };
      s.ds.data = s.data;
      return s.ds;
    });
    const opts = this.chart.options.scales;
    opts.x.min = Math.max(0, t - WINDOW_S);
    opts.x.max = Math.max(t, WINDOW_S / 6);
    opts.y1.display = datasets.some((d) => d.yAxisID === 'y1');
    this.chart.data.datasets = datasets;
    this.chart.update('none');
  }
}

function push(data, t, v) {
  if (typeof v !== 'number' || !isFinite(v)) return;
  data.push({x: t, y: v});
  // bounds memory when the plot is hidden for long
  if (data.length > 20000) data.splice(0, data.length - 20000);
}
