// The station's HTTP API (docs/station.md) and the page's status line.
// URLs are relative to the page so that the station also works behind a path prefix.

const token = new URLSearchParams(location.search).get('token');

function headers(extra) {
  const h = Object.assign({}, extra);
  // A page opened with ?token= must carry it on every API request as a bearer token.
  if (token) h.Authorization = 'Bearer ' + token;
  return h;
}

export async function getJSON(path) {
  const r = await fetch(path, {headers: headers(), cache: 'no-store'});
  if (!r.ok) throw new Error(`${path}: HTTP ${r.status}`);
  return r.json();
}

// Resolves to {ok:true} or {ok:false, error}; never throws, so callers need no try/catch.
export async function postJSON(path, body) {
  try {
    const r = await fetch(path, {
      method: 'POST',
      headers: headers({'Content-Type': 'application/json'}),
      body: JSON.stringify(body),
    });
    let answer = {};
    try {
      answer = await r.json();
    } catch (e) { /* an empty or non-JSON body */
    }
    if (!r.ok) return {ok: false, error: answer.error || `HTTP ${r.status}`};
    return Object.assign({ok: true}, answer);
  } catch (e) {
    return {ok: false, error: 'no connection'};
  }
}

// Key presses and releases go out one after the other: two requests in flight could reach
// the server in the wrong order and leave a jog key pressed.
let keyChain = Promise.resolve();
export function postKey(name, pressed) {
  keyChain = keyChain.then(async () => {
    const a = await postJSON('api/key', {name, pressed});
    if (!a.ok) status(`key ${name}: ${a.error}`, 'error');
  });
  return keyChain;
}

export async function postRun(body) {
  const a = await postJSON('api/run', body);
  if (!a.ok) status(`${body.action}: ${a.error}`, 'error');
  return a;
}

export async function postSignal(name, value) {
  const a = await postJSON('api/signal', {name, value});
  if (a.ok)
    status(`${name} := ${value}`, 'info');
  else
    status(`${name}: ${a.error}`, 'error');
  return a;
}

let statusTimer = 0;
export function status(text, kind = 'info') {
  const el = document.getElementById('status-line');
  if (!el) return;
  el.textContent = text;
  el.className = 'status ' + kind;
  el.title = text;
  clearTimeout(statusTimer);
  statusTimer = setTimeout(() => {
    el.textContent = '';
    el.className = 'status';
  }, kind === 'error' ? 8000 : 3000);
}

// Cheap DOM updates: the state arrives 30 times a second and most fields do not change.
export function setText(el, text) {
  if (el.textContent !== text) el.textContent = text;
}

export function fmt(v, digits = 3) {
  return typeof v === 'number' && isFinite(v) ? v.toFixed(digits) : '—';
}

export function el(tag, attrs = {}, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === 'class')
      e.className = v;
    else if (k === 'text')
      e.textContent = v;
    else if (k.startsWith('on'))
      e.addEventListener(k.slice(2), v);
    else
      e.setAttribute(k, v);
  }
  for (const c of children)
    if (c != null) e.append(c);
  return e;
}
