// The operator station's page: loads the model once, then follows /api/state and wires the
// 3D view, the operator panel, the NC screen, the signal monitor, the plot and the event log.
import {getJSON, postRun, setText, status} from './api.js';
import {EventLog} from './events.js';
import {Functions} from './functions.js';
import {NcScreen} from './ncscreen.js';
import {OperatorPanel} from './panel.js';
import {Plot} from './plot.js';
import {SignalMonitor} from './signals.js';

const MIN_STATE_INTERVAL_MS = 33;  // at most ~30 states a second
const RETRY_MS = 1000;

const $ = (sel) => document.querySelector(sel);

async function main() {
  let model;
  for (;;) {
    try {
      model = await getJSON('api/model');
      break;
    } catch (e) {
      connection(false, String(e.message || e));
      await sleep(RETRY_MS);
    }
  }
  document.title = `vmt · ${model.scene || 'operator station'}`;
  setText($('#scene-name'), model.scene || '—');
  setText($('#pace'), model.pace || '—');
  $('#pace').className = `badge plain pace-${model.pace}`;
  if (model.pace === 'external') {
    // the external PLC keeps the clock: the server refuses run control (409)
    for (const b of [...document.querySelectorAll('[data-run]'), $('[data-speed]')]) {
      b.disabled = true;
      b.title = 'the external PLC is the clock: the page cannot pace the run';
    }
  }
  setText($('#n-signals'), model.signals_count != null ? String(model.signals_count) : '');
  // A replay (vmt view) is watched, not operated: a time slider instead of the keys.
  const replay = model.pace === 'replay';
  const seek = $('[data-seek]');
  let seeking = false;
  if (replay) {
    seek.hidden = false;
    seek.max = String(model.end_s || 1);
    seek.addEventListener('input', () => {
      seeking = true;
    });
    seek.addEventListener('change', () => {
      seeking = false;
      postRun({action: 'seek', t: Number(seek.value)});
    });
    // ?t=SECONDS opens the replay at that time (a failing golden picture links there).
    const at = Number(new URLSearchParams(location.search).get('t'));
    if (at > 0) postRun({action: 'seek', t: Math.min(at, model.end_s || at)});
  }

  const panel = new OperatorPanel(
      $('#operator-panel'), model.keys || [], model.handwheel_axes || [], model.selectors || []);
  if (replay)
    for (const b of document.querySelectorAll(
             '[data-key], [data-handwheel], [data-handwheel-axis], [data-selector]')) {
      b.disabled = true;
      b.title = 'a replay is watched, not operated';
    }
  const nc = new NcScreen($('#nc'), model);
  const functions = new Functions($('#functions'));
  const tabs = new Tabs();
  const plot = new Plot($('#plot'), model, {
    onSignalsChanged: (name, on) => {
      monitor.setPlotted(name, on);
      monitor.kick();
    }
  });
  const monitor = new SignalMonitor($('#signals'), {
    onValues: (values, signals) => plot.sampleSignals(values, signals),
    onPlotToggle: (name, on) => plot.toggleSignal(name, on),
    isPlotted: (name) => plot.isPlotted(name),
  });
  // The monitor polls while it is seen, and while signals are plotted (the plot needs their
  // values even when another tab is in front).
  monitor.setWanted(() => !document.hidden && (tabs.current === 'signals' || plot.hasSignals()));
  const events = new EventLog($('#events'), {
    onCount: (n) => setText($('#n-events'), String(n)),
    onSelect: (e) => {
      status(
          `event at t = ${typeof e.t === 'number' ? e.t.toFixed(3) : e.t} s: ${e.event}`, 'info');
      // in a replay an event takes the run to its time
      if (replay && typeof e.t === 'number') postRun({action: 'seek', t: e.t});
    },
  });
  tabs.onChange = (name) => {
    plot.setVisible(name === 'plot');
    if (name === 'events') events.shown();
    monitor.kick();
  };
  tabs.show(stored('vmt.tab') || 'signals');
  document.addEventListener('visibilitychange', () => monitor.kick());

  let lastRun = null;
  const speed = $('[data-speed]');
  const runBody = (action) => (action === 'run' ? {action, speed: Number(speed.value)} : {action});
  for (const b of document.querySelectorAll('[data-run]')) {
    b.addEventListener('click', () => postRun(runBody(b.dataset.run)));
  }
  // A new speed while running takes effect at once; while paused, at the next Run.
  speed.addEventListener('change', () => {
    if (lastRun === 'running') postRun(runBody('run'));
  });
  $('#tools-size').addEventListener('click', () => {
    const big = document.body.classList.toggle('tools-big');
    $('#tools-size').innerHTML = big ? '&#8597; Shrink' : '&#8597; Enlarge';
  });

  // The 3D view last: without WebGL the rest of the station still works.
  let view = null;
  try {
    const {MachineView} = await import('./view3d.js');
    view = new MachineView($('#view'), $('canvas[data-view="machine"]'), model);
  } catch (e) {
    console.error(e);
    $('#view').append(Object.assign(
        document.createElement('div'),
        {className: 'empty', textContent: `3D view unavailable: ${e.message || e}`}));
  }

  // for the console and for tests: the page's parts, read-only by convention
  window.vmtStation = {model, view, nc, panel, plot, monitor, events};

  const apply = (state) => {
    lastRun = state.run;
    setText($('[data-time]'), typeof state.t === 'number' ? state.t.toFixed(3) : '—');
    if (replay && !seeking && typeof state.t === 'number') seek.value = String(state.t);
    setText($('#cycle'), String(state.cycle ?? '—'));
    const run = $('#run-state');
    setText(run, state.run || '—');
    run.className = `badge run-${state.run}`;
    for (const b of document.querySelectorAll('[data-run]'))
      b.classList.toggle(
          'active',
          b.dataset.run ===
              (state.run === 'running'    ? 'run' :
                   state.run === 'paused' ? 'pause' :
                                            ''));
    if (view) view.update(state);
    nc.update(state);
    if (tabs.current === 'functions') functions.update(state);
    panel.update(state);
    plot.sampleState(state);
    if (typeof state.events === 'number') events.announce(state.events);
  };

  // One request in flight at a time; the next as soon as the answer is in, at most ~30 a second.
  for (;;) {
    const started = performance.now();
    try {
      const state = await getJSON('api/state');
      connection(true);
      // {} until the simulation has published its first frame
      if (typeof state.t === 'number') apply(state);
    } catch (e) {
      connection(false, String(e.message || e));
      await sleep(RETRY_MS);
      continue;
    }
    const wait = MIN_STATE_INTERVAL_MS - (performance.now() - started);
    if (wait > 0) await sleep(wait);
  }
}

class Tabs {
  constructor() {
    this.buttons = [...document.querySelectorAll('.tabs [data-tab]')];
    this.panes = [...document.querySelectorAll('[data-pane]')];
    this.current = null;
    this.onChange = () => {};
    for (const b of this.buttons) b.addEventListener('click', () => this.show(b.dataset.tab));
  }

  show(name) {
    if (!this.buttons.some((b) => b.dataset.tab === name)) name = this.buttons[0].dataset.tab;
    this.current = name;
    for (const b of this.buttons) {
      b.classList.toggle('on', b.dataset.tab === name);
      b.setAttribute('aria-selected', String(b.dataset.tab === name));
    }
    for (const p of this.panes) p.hidden = p.dataset.pane !== name;
    stored('vmt.tab', name);
    this.onChange(name);
  }
}

let connected = null;
function connection(ok, why = '') {
  if (ok === connected) return;
  connected = ok;
  const c = $('#conn');
  c.textContent = ok ? 'connected' : 'disconnected';
  c.className = `conn ${ok ? 'ok' : 'down'}`;
  c.title = ok ? 'connected to vmt' : `no answer from vmt (${why}); retrying every second`;
  document.body.classList.toggle('disconnected', !ok);
}

// localStorage may be refused (privacy settings): the page then just forgets the tab.
function stored(key, value) {
  try {
    if (value === undefined) return localStorage.getItem(key);
    localStorage.setItem(key, value);
  } catch (e) { /* not kept */
  }
  return null;
}

function sleep(ms) {
  return new Promise((r) => setTimeout(r, ms));
}

main().catch((e) => {
  console.error(e);
  const f = $('#fatal');
  f.hidden = false;
  f.textContent = `The station failed: ${e.message || e}`;
});
