// The NC screen: state, mode, program with the current line, modal codes, tool, feed, spindle,
// axes and messages.
import {el, fmt, setText} from './api.js';

export class NcScreen {
  constructor(root, model) {
    this.root = root;
    this.axisUnits = new Map((model.axes || []).map((a) => [a.name, a.unit || '']));
    this.q = (sel) => root.querySelector(sel);
    this.state = this.q('[data-nc-state]');
    this.mode = this.q('#nc-mode');
    this.current = this.q('[data-current-line]');
    this.currentNo = this.q('#nc-line-no');
    this.listing = this.q('#nc-program');
    this.programFile = this.q('#nc-program-file');
    this.modal = this.q('#nc-modal');
    this.toolText = this.q('#nc-tool');
    this.feedCmd = this.q('#nc-feed-cmd');
    this.feedAct = this.q('#nc-feed-act');
    this.spCmd = this.q('#nc-sp-cmd');
    this.spAct = this.q('#nc-sp-act');
    this.feedOvr = this.q('#nc-feed-ovr');
    this.spOvr = this.q('#nc-sp-ovr');
    this.axesBody = this.q('#nc-axes tbody');
    this.messages = this.q('#nc-messages');
    this.lines = (model.program && model.program.lines) || [];
    this.line = -1;
    this.buildProgram(model.program);
    this.axisRows = new Map();
    for (const a of model.axes || []) this.axisRow(a.name);
    this.messagesKey = null;
  }

  buildProgram(program) {
    if (!program) {
      setText(this.programFile, 'no NC program');
      this.listing.append(el('div', {class: 'pl-empty', text: 'This scene has no NC program.'}));
      return;
    }
    setText(this.programFile, (program.file || '').split('/').pop());
    this.programFile.title = program.file || '';
    const frag = document.createDocumentFragment();
    this.lineEls = this.lines.map((text, i) => {
      const comment = text.indexOf(';');
      const code = comment < 0 ? text : text.slice(0, comment);
      const row =
          el('div', {class: 'pl', 'data-line': String(i + 1)},
             el('span', {class: 'pl-no', text: String(i + 1)}),
             el('span', {class: 'pl-code', text: code}),
             comment < 0 ? null : el('span', {class: 'pl-comment', text: text.slice(comment)}));
      frag.append(row);
      return row;
    });
    this.listing.append(frag);
  }

  axisRow(name) {
    const unit = this.axisUnits.get(name) || '';
    const cell = (attrs) =>
        el('td', {class: 'num'}, el('span', attrs), el('span', {class: 'unit', text: unit}));
    const machine = el('span', {class: 'pos', 'data-axis': name, text: '—'});
    const row =
        el('tr', {}, el('th', {text: name}),
           el('td', {class: 'num'}, machine, el('span', {class: 'unit', text: unit})),
           cell({class: 'prog', text: '—'}), cell({class: 'ferr', text: '—'}));
    this.axesBody.append(row);
    const r = {machine, prog: row.querySelector('.prog'), ferr: row.querySelector('.ferr'), row};
    this.axisRows.set(name, r);
    return r;
  }

  update(state) {
    const nc = state.nc;
    this.root.classList.toggle('no-nc', !nc);
    const st = nc ? String(nc.state || '') : 'no NC';
    setText(this.state, st);
    this.state.className = `nc-state st-${st.replace(/\W/g, '')}`;
    setText(this.mode, nc ? String(nc.mode || '—') : '—');
    this.updateLine(nc);
    if (nc) {
      const modal = (nc.modal || []).join(' ');
      if (this.modalText !== modal) {
        this.modalText = modal;
        this.modal.replaceChildren(
            ...(nc.modal || []).map((g) => el('span', {class: 'chip', text: g})));
      }
      const tool = nc.tool || {};
      setText(this.toolText, `T${tool.t ?? '—'}  D${tool.d ?? '—'}`);
      const feed = nc.feed || {}, sp = nc.spindle || {};
      setText(this.feedCmd, fmt(feed.command, 1));
      setText(this.feedAct, fmt(feed.actual, 1));
      // With the headstock in rotary axis mode the status shows lines instead of speeds.
      const shown = sp.shown !== false;
      setText(this.spCmd, shown ? fmt(sp.command, 1) : '\u2014\u2014\u2014');
      setText(this.spAct, shown ? fmt(sp.actual, 1) : '\u2014\u2014\u2014');
      const ovr = nc.override || {};
      setText(this.feedOvr, percent(ovr.feed));
      setText(this.spOvr, percent(ovr.spindle));
    }
    for (const a of state.axes || []) {
      const r = this.axisRows.get(a.name) || this.axisRow(a.name);
      setText(r.machine, fmt(a.machine));
      setText(r.prog, fmt(a.program));
      setText(r.ferr, fmt(a.following_error));
    }
    this.updateMessages(state.messages || []);
  }

  updateLine(nc) {
    const line = nc && Number.isInteger(nc.line) ? nc.line : 0;
    const text =
        line > 0 && line <= this.lines.length ? this.lines[line - 1] : (nc && nc.block) || '';
    if (this.current.getAttribute('data-current-line') !== String(line))
      this.current.setAttribute('data-current-line', String(line));
    setText(this.current, text);
    this.current.title = nc && nc.block ? `block: ${nc.block}` : '';
    setText(this.currentNo, line > 0 ? String(line) : '—');
    if (line === this.line || !this.lineEls) return;
    if (this.lineEls[this.line - 1]) this.lineEls[this.line - 1].classList.remove('current');
    this.line = line;
    const row = this.lineEls[line - 1];
    if (!row) return;
    row.classList.add('current');
    // Scroll the listing only, never the page, and keep some lines of context above.
    const top = row.offsetTop;  // the listing is the rows' offsetParent (position: relative)
    const view = this.listing.clientHeight;
    if (top < this.listing.scrollTop + row.offsetHeight ||
        top > this.listing.scrollTop + view - 2 * row.offsetHeight) {
      this.listing.scrollTop = Math.max(0, top - view / 3);
    }
  }

  updateMessages(messages) {
    const key = JSON.stringify(messages);
    if (key === this.messagesKey) return;
    this.messagesKey = key;
    if (!messages.length) {
      this.messages.replaceChildren(el('div', {class: 'msg-none', text: 'no messages'}));
      return;
    }
    this.messages.replaceChildren(...messages.map(
        (m) =>
            el('div', {class: `msg src-${m.source || 'nc'}`},
               el('span', {class: 'msg-no', text: String(m.number ?? '')}),
               el('span', {class: 'msg-src', text: (m.source || '').toUpperCase()}),
               el('span', {class: 'msg-text', text: m.text || ''}))));
  }
}

// Overrides come as fractions.
function percent(v) {
  return typeof v === 'number' && isFinite(v) ? `${Math.round(v * 100)} %` : '\u2014';
}
