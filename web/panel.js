// The operator panel: every machine key of the model as a button that is held while pressed,
// every selector (override switch) as a choice of its positions.
import {el, postJSON, postKey, status} from './api.js';

// Groups by name pattern, first match wins; a key no pattern knows goes to "Other", so that
// every key of the model is on the panel.
const GROUPS = [
  {id: 'mode', title: 'Mode', re: /^m(AUTO|MANU|MDI|REF|EDIT|JOGM\d*)$/i},
  {id: 'program', title: 'Program', re: /^m(START|STOP|RESET|SBL|BSL|DRY|CYCLE|HOLD|FEEDHOLD)/i},
  {id: 'jog', title: 'Jog', re: /^m(JG|JOG|MG|HW|INC)/i},
  {id: 'spindle', title: 'Spindle', re: /^m(A\d+CM\d+|SP|S\d|M\d+$)/i},
  {id: 'restart', title: 'Restart', re: /^m(REPOS|RESTA|RaR)/i},
  {
    id: 'machine',
    title: 'Machine',
    re: /^m(COOLANT|DOOR|TAILSTOCK|CHUCK|CLAMP|LIGHT|CONVEYOR|QUILL)/i
  },
  {id: 'other', title: 'Other', re: /./},
];

const LABELS = {
  mAUTO: 'AUTO',
  mMANU: 'MANUAL',
  mSTART: 'CYCLE\nSTART',
  mSTOP: 'FEED\nHOLD',
  mRESET: 'RESET',
  mSBL: 'SINGLE\nBLOCK',
  mREPOS: 'REPOS',
  mRESTA: 'BLOCK\nRESTART',
  mRaR_OFF: 'RaR\nOFF',
  mCOOLANT: 'COOLANT',
  mDOOR: 'DOOR',
  mTAILSTOCK: 'QUILL',
  mMGPOS: 'TURRET\n+',
  mMGNEG: 'TURRET\n\u2212',
};

function label(name) {
  if (LABELS[name]) return LABELS[name];
  let m = /^mJG(POS|NEG)_(\w+)$/.exec(name);
  if (m) return `${m[2]} ${m[1] === 'POS' ? '+' : '\u2212'}`;
  m = /^mJOGM(\d)$/.exec(name);
  if (m) return `JOG\nbit ${m[1]}`;
  m = /^mA(\d+)CM(\d+)$/.exec(name);
  if (m) return `M${m[2]}\nA${m[1]}`;
  return name.replace(/^m/, '');
}

// Jog keys in axis pairs, minus before plus, as on a real panel.
function jogOrder(a, b) {
  const k = (n) => {
    const m = /^mJG(POS|NEG)_(\w+)$/.exec(n);
    return m ? `0${m[2]}${m[1] === 'NEG' ? 0 : 1}` : `1${n}`;
  };
  return k(a) < k(b) ? -1 : k(a) > k(b) ? 1 : 0;
}

const LED_KEYS = ['mAUTO', 'mMANU', 'mSTART', 'mSTOP'];

export class OperatorPanel {
  constructor(root, keys, handwheelAxes = [], selectors = []) {
    this.root = root;
    this.buttons = new Map();
    this.selectors = new Map();
    const groups = GROUPS.map((g) => ({...g, keys: []}));
    for (const k of keys) groups.find((g) => g.re.test(k)).keys.push(k);
    const jog = groups.find((g) => g.id === 'jog');
    jog.keys.sort(jogOrder);
    for (const g of groups) {
      if (!g.keys.length) continue;
      const box =
          el('div', {class: `keygroup kg-${g.id}`}, el('div', {class: 'kg-title', text: g.title}));
      const grid = el('div', {class: 'kg-keys'});
      for (const k of g.keys) grid.append(this.button(k));
      box.append(grid);
      root.append(box);
    }
    if (selectors.length) root.append(this.overrides(selectors));
    if (handwheelAxes.length) root.append(this.handwheel(handwheelAxes));
    // A key must not stay pressed when the page loses the pointer or the focus.
    window.addEventListener('blur', () => this.releaseAll());
    document.addEventListener('visibilitychange', () => {
      if (document.hidden) this.releaseAll();
    });
  }

  // The override switches (the model's selectors): a position is set, as the panel's rotary
  // switch is turned, and the PLC makes it the NC's override.
  overrides(selectors) {
    const rows = selectors.map((s) => {
      const m = /^m(FOVR|SOVR)_?(\w*)$/.exec(s.name);
      const title =
          m ? (m[1] === 'FOVR' ? 'feed' : `spindle ${m[2]}`.trim()) : s.name.replace(/^m/, '');
      const select =
          el('select', {'data-selector': s.name, title: s.name},
             ...s.positions.map((p) => el('option', {value: String(p), text: `${p} %`})));
      select.value = String(s.initial);
      select.addEventListener('change', () => {
        select.dataset.pending = select.value;
        postJSON('api/signal', {name: s.name, value: Number(select.value)}).then((a) => {
          if (!a.ok) status(`${s.name}: ${a.error}`, 'error');
        });
      });
      this.selectors.set(s.name, select);
      return el('label', {class: 'ovr-row'}, el('span', {class: 'ovr-name', text: title}), select);
    });
    return el(
        'div', {class: 'keygroup kg-override'}, el('div', {class: 'kg-title', text: 'Override'}),
        ...rows);
  }

  // The handwheel (manual mode, jog mode "handwheel"): counts for the chosen axis, as a
  // detent wheel gives them; the mouse wheel over it turns it a count per notch.
  handwheel(axes) {
    const axis =
        el('select', {class: 'hw-axis', 'data-handwheel-axis': '', title: 'handwheel axis'},
           ...axes.map((a) => el('option', {value: a, text: a})));
    const turn = (counts) => postJSON('api/handwheel', {axis: axis.value, counts}).then((a) => {
      if (!a.ok) status(`handwheel: ${a.error}`, 'error');
    });
    const buttons = [-10, -1, 1, 10].map((n) => el('button', {
                                           class: 'key hw',
                                           type: 'button',
                                           'data-handwheel': String(n),
                                           text: n > 0 ? `+${n}` : `\u2212${- n}`,
                                           onclick: () => turn(n)
                                         }));
    const box = el(
        'div', {class: 'keygroup kg-handwheel'}, el('div', {class: 'kg-title', text: 'Handwheel'}),
        el('div', {class: 'hw-row'}, axis, ...buttons));
    box.addEventListener('wheel', (e) => {
      e.preventDefault();
      turn(e.deltaY < 0 ? 1 : -1);
    }, {passive: false});
    return box;
  }

  button(name) {
    const lines = label(name).split('\n');
    const b =
        el('button', {class: 'key', 'data-key': name, title: name, type: 'button'},
           el('span', {class: 'led'}),
           el('span', {class: 'key-label'}, ...lines.flatMap((l, i) => (i ? [el('br'), l] : [l]))),
           el('span', {class: 'key-name', text: name}));
    b.classList.add(`key-${name.replace(/[^A-Za-z0-9_]/g, '')}`);
    if (LED_KEYS.includes(name)) b.classList.add('has-led');
    const press = () => {
      if (b.classList.contains('held')) return;
      b.classList.add('held');
      postKey(name, true);
    };
    const release = () => {
      if (!b.classList.contains('held')) return;
      b.classList.remove('held');
      postKey(name, false);
    };
    b.addEventListener('pointerdown', (e) => {
      if (e.button !== 0) return;
      e.preventDefault();  // no focus steal, no text selection, no emulated mouse events
      press();
    });
    for (const ev of ['pointerup', 'pointerleave', 'pointercancel'])
      b.addEventListener(ev, release);
    b.addEventListener('keydown', (e) => {
      if ((e.key === ' ' || e.key === 'Enter') && !e.repeat) {
        e.preventDefault();
        press();
      }
    });
    b.addEventListener('keyup', (e) => {
      if (e.key === ' ' || e.key === 'Enter') {
        e.preventDefault();
        release();
      }
    });
    b.addEventListener('blur', release);
    b.addEventListener('contextmenu', (e) => e.preventDefault());  // a long touch is a held key
    b.release = release;
    this.buttons.set(name, b);
    return b;
  }

  releaseAll() {
    for (const b of this.buttons.values()) b.release();
  }

  // The LEDs show what the NC reports, not what was pressed.
  update(state) {
    const nc = state.nc || {};
    const lit = {
      mAUTO: nc.mode === 'automatic',
      mMANU: nc.mode === 'manual',
      mSTART: nc.state === 'running',
      mSTOP: nc.state === 'hold',
    };
    for (const [name, on] of Object.entries(lit)) {
      const b = this.buttons.get(name);
      if (b && b.classList.contains('lit') !== on) b.classList.toggle('lit', on);
    }
    // A switch shows where the run has it, once the position just chosen has been taken.
    for (const [name, v] of Object.entries(state.selectors || {})) {
      const select = this.selectors.get(name);
      if (!select || document.activeElement === select) continue;
      if (select.dataset.pending && select.dataset.pending !== String(v)) continue;
      delete select.dataset.pending;
      if (select.value !== String(v)) select.value = String(v);
    }
  }
}
