// The event log: every event of the run, newest at the bottom, a filter, and a selected event.
import {el, getJSON} from './api.js';

const POLL_MS = 250;
const MAX_ROWS = 2000;    // rows in the DOM; the filter searches all events kept
const MAX_KEPT = 200000;  // events kept in memory

export class EventLog {
  constructor(root, {onSelect, onCount}) {
    this.root = root;
    this.onSelect = onSelect || (() => {});
    this.onCount = onCount || (() => {});
    this.events = [];       // {e, text, lower, index}
    this.dropped = 0;       // events before the kept ones
    this.received = 0;      // how many the server has given (the next "from")
    this.announced = null;  // the total the state reported
    this.selected = null;

    this.filter = el('input', {
      type: 'search',
      class: 'filter',
      placeholder: 'filter (substring of the event\u2019s JSON)…',
      'aria-label': 'filter events'
    });
    this.filter.addEventListener('input', () => this.rerender());
    this.count = el('span', {class: 'count'});
    this.follow = el('button', {
      type: 'button',
      class: 'w-btn follow',
      text: '\u2193 follow',
      title: 'scroll to the newest event',
      onclick: () => this.scrollToEnd()
    });
    root.append(el('div', {class: 'toolbar'}, this.filter, this.count, this.follow));
    this.list = el('div', {class: 'scroll evlist', role: 'log'});
    // Follows the newest event until the user scrolls up; a hidden tab has no scroll events.
    this.following = true;
    this.list.addEventListener('scroll', () => {
      if (!this.list.clientHeight) return;
      this.following = this.atBottom();
      this.follow.classList.toggle('on', !this.following);
    });
    this.list.addEventListener('click', (e) => {
      const row = e.target.closest('.ev');
      if (row) this.select(Number(row.dataset.index));
    });
    this.detail = el('div', {class: 'evdetail', text: 'click an event to see it whole'});
    root.append(this.list, this.detail);
    this.poll();
  }

  // The state says how many events there are; ask only when there are new ones.
  announce(total) {
    this.announced = total;
  }

  async poll() {
    let wait = POLL_MS;
    try {
      if (this.announced === null || this.announced !== this.received) {
        const a = await getJSON(`api/events?from=${this.received}`);
        if (a.total < this.received) {
          this.reset();  // the server started a new run
        } else {
          // events the server no longer keeps are skipped: "first" is its oldest
          if (typeof a.first === 'number' && a.first > this.received) this.received = a.first;
          this.add(a.events || [], a.total);
        }
        if (this.received < a.total && (a.events || []).length) {
          setTimeout(() => this.poll(), 0);
          return;
        }
      }
    } catch (e) {
      wait = 1000;  // the state poll reports the connection
    }
    setTimeout(() => this.poll(), wait);
  }

  reset() {
    this.events = [];
    this.dropped = 0;
    this.received = 0;
    this.selected = null;
    this.list.replaceChildren();
  }

  add(events, total) {
    if (!events.length) return;
    const f = this.filter.value.trim().toLowerCase();
    const frag = document.createDocumentFragment();
    for (const e of events) {
      const text = JSON.stringify(e);
      const item = {e, text, lower: text.toLowerCase(), index: this.received++};
      this.events.push(item);
      if (!f || item.lower.includes(f)) frag.append(this.row(item));
    }
    if (this.events.length > MAX_KEPT) {
      const n = this.events.length - MAX_KEPT;
      this.events.splice(0, n);
      this.dropped += n;
    }
    this.list.append(frag);
    while (this.list.childElementCount > MAX_ROWS) this.list.firstElementChild.remove();
    if (this.following)
      this.scrollToEnd();
    else
      this.follow.classList.add('on');
    this.updateCount();
  }

  row(item) {
    const {t, event, ...rest} = item.e;
    const body = Object.entries(rest)
                     .map(([k, v]) => `${k}=${typeof v === 'string' ? v : JSON.stringify(v)}`)
                     .join('  ');
    const r = el(
        'div',
        {class: `ev k-${String(event).replace(/\W/g, '')}`, 'data-index': String(item.index)},
        el('span', {class: 'ev-t', text: typeof t === 'number' ? t.toFixed(3) : String(t ?? '')}),
        el('span', {class: 'ev-kind', text: String(event ?? '')}),
        el('span', {class: 'ev-body', text: body}));
    if (item.index === this.selected) r.classList.add('sel');
    return r;
  }

  rerender() {
    const f = this.filter.value.trim().toLowerCase();
    const rows = [];
    for (let i = this.events.length - 1; i >= 0 && rows.length < MAX_ROWS; i--) {
      const item = this.events[i];
      if (!f || item.lower.includes(f)) rows.push(this.row(item));
    }
    this.list.replaceChildren(...rows.reverse());
    this.scrollToEnd();
    this.updateCount();
  }

  updateCount() {
    const f = this.filter.value.trim().toLowerCase();
    const shown = f ? this.events.reduce((n, it) => n + (it.lower.includes(f) ? 1 : 0), 0) :
                      this.events.length + this.dropped;
    this.count.textContent = f ? `${shown} of ${this.received} events` : `${this.received} events`;
    this.onCount(this.received);
  }

  select(index) {
    const item = this.events[index - this.dropped];
    if (!item) return;
    for (const r of this.list.querySelectorAll('.ev.sel')) r.classList.remove('sel');
    const row = this.list.querySelector(`.ev[data-index="${index}"]`);
    if (row) row.classList.add('sel');
    this.selected = index;
    const t = item.e.t;
    this.detail.replaceChildren(
        el('span', {class: 'evd-t', text: `t = ${typeof t === 'number' ? t.toFixed(3) : t} s`}),
        el('span', {class: 'evd-no', text: `#${index}`}), el('code', {text: item.text}));
    this.onSelect(item.e, index);
  }

  atBottom() {
    return this.list.scrollTop + this.list.clientHeight >= this.list.scrollHeight - 8;
  }

  scrollToEnd() {
    this.following = true;
    this.list.scrollTop = this.list.scrollHeight;
    this.follow.classList.remove('on');
  }

  shown() {
    if (this.following) this.scrollToEnd();
  }
}
