// softplc web monitor: plain JavaScript, no framework, no build step.
// Reads /api/tree (the variable tree, a level at a time), /api/events (the
// live state as server-sent events: only the values this page watches) and
// changes values through /api/write, /api/force and /api/unforce.
"use strict";

const client = Math.random().toString(36).slice(2, 10) + Date.now().toString(36);
const rows = new Map(); // path -> {el, item}
const expanded = new Set(); // paths of the open tree nodes
const trend = new Map(); // path -> {color, points: [[wall ms, value]]}
const COLORS = ["#1f5fbf", "#c62828", "#1a7f37", "#8e44ad", "#d35400", "#00838f", "#6d4c41", "#455a64"];
let info = { writable: [], online_change: false, control: false, period_s: 0.25 };
let generation = null;
let selected = null;
let lastForced = {};
let watchTimer = null;

const $ = (id) => document.getElementById(id);

function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) {
    if (k === "class") e.className = v;
    else if (k.startsWith("on")) e.addEventListener(k.slice(2), v);
    else if (k === "text") e.textContent = v;
    else e.setAttribute(k, v);
  }
  for (const c of children) e.append(c);
  return e;
}

async function api(method, url, body) {
  const options = { method, headers: {} };
  if (body !== undefined) {
    options.headers["Content-Type"] = "application/json";
    options.body = JSON.stringify(body);
  }
  let response;
  try {
    response = await fetch(url, options);
  } catch (err) {
    return { ok: false, status: 0, data: { error: "the PLC does not answer: " + err } };
  }
  let data = {};
  try { data = await response.json(); } catch (_) { /* not JSON */ }
  return { ok: response.ok, status: response.status, data };
}

function message(text, kind) {
  const m = $("message");
  m.textContent = text;
  m.className = kind;
  m.hidden = false;
  clearTimeout(message.timer);
  if (kind === "info") message.timer = setTimeout(() => { m.hidden = true; }, 4000);
}

// ------------------------------------------------------------------ the tree

async function loadChildren(path, container, offset) {
  const r = await api("GET", "/api/tree?path=" + encodeURIComponent(path) + "&offset=" + (offset || 0));
  if (!r.ok) { message(r.data.error || ("tree: HTTP " + r.status), "error"); return; }
  for (const item of r.data.children) container.append(makeNode(item));
  if (r.data.more > 0) {
    const next = (offset || 0) + r.data.children.length;
    const more = el("div", { class: "more muted" }, `… ${r.data.more} more `);
    more.append(el("button", { type: "button", onclick: () => { more.remove(); loadChildren(path, container, next).then(scheduleWatch); } }, "show more"));
    container.append(more);
  }
}

function makeNode(item) {
  const leaf = item.kind === "var";
  const node = el("div", { class: "node" });
  const toggle = el("span", { class: "toggle", text: leaf ? "" : "▸" });
  const size = item.kind === "array" ? ` (${item.size})` : "";
  const row = el("div", { class: "row", "data-path": item.path, "data-kind": item.kind, title: item.path },
    el("span", { class: "name" }, toggle, item.name),
    el("span", { class: "type", text: item.type + size }),
    el("span", { class: "value" }),
    el("span", { class: "forced-mark", title: "forced", text: "F" }));
  const children = el("div", { class: "children", hidden: "" });
  node.append(row, children);
  if (leaf) {
    rows.set(item.path, { el: row, item });
    row.addEventListener("click", () => select(item, row));
    applyForced(item.path);
  } else {
    const open = async () => {
      if (children.hidden) {
        children.hidden = false;
        toggle.textContent = "▾";
        expanded.add(item.path);
        if (!children.childElementCount) await loadChildren(item.path, children, 0);
      } else {
        children.hidden = true;
        toggle.textContent = "▸";
        expanded.delete(item.path);
      }
      scheduleWatch();
    };
    row.addEventListener("click", open);
    node.open = open;
  }
  return node;
}

async function buildTree() {
  rows.clear();
  const tree = $("tree");
  tree.textContent = "";
  await loadChildren("", tree, 0);
  // after an online change: open again what was open, parents first
  for (const path of [...expanded].sort((a, b) => a.length - b.length)) {
    const row = tree.querySelector(`.row[data-path="${CSS.escape(path)}"]`);
    expanded.delete(path);
    if (row) await row.parentElement.open();
  }
  scheduleWatch();
}

function visibleLeaves() {
  const out = [];
  for (const [path, r] of rows) if (isShown(r.el)) out.push(path);
  return out;
}

function isShown(e) {
  for (let p = e.parentElement; p; p = p.parentElement) if (p.hidden) return false;
  return e.isConnected;
}

function scheduleWatch() {
  clearTimeout(watchTimer);
  watchTimer = setTimeout(sendWatch, 50);
}

async function sendWatch() {
  const paths = [...new Set([...visibleLeaves(), ...trend.keys()])];
  const r = await api("POST", "/api/watch", { client, paths });
  if (r.status === 429) setTimeout(scheduleWatch, 1000); // the server's rate of watches: again later
  if (r.ok && Object.keys(r.data.errors).length) message(Object.values(r.data.errors).join("\n"), "error");
}

// ------------------------------------------------------------------ editing

function select(item, row) {
  if (selected) selected.row.classList.remove("selected");
  selected = { item, row };
  row.classList.add("selected");
  $("editor").hidden = false;
  $("edit-path").textContent = item.path;
  $("edit-type").textContent = item.type;
  const slot = $("edit-input-slot");
  slot.textContent = "";
  let input;
  if (item.type === "BOOL") {
    input = el("select", { id: "edit-value" }, el("option", { text: "TRUE" }), el("option", { text: "FALSE" }));
  } else if (item.values) {
    input = el("select", { id: "edit-value" }, ...item.values.map((v) => el("option", { text: v })));
  } else {
    input = el("input", { id: "edit-value", type: "text", placeholder: "value", spellcheck: "false" });
    input.addEventListener("keydown", (e) => { if (e.key === "Enter") change("write"); });
  }
  const current = row.querySelector(".value").textContent;
  if (current !== "") input.value = current;
  slot.append(input);
}

async function change(op) {
  if (!selected) return;
  const path = selected.item.path;
  const body = { path };
  if (op !== "unforce") body.value = $("edit-value").value;
  const r = await api("POST", "/api/" + op, body);
  if (r.ok) message(`${op} ${r.data.path}${op === "unforce" ? "" : " := " + body.value}`, "info");
  else message(r.data.error || `${op} ${path}: HTTP ${r.status}`, "error");
}

function applyForced(path) {
  const r = rows.get(path);
  if (r) r.el.classList.toggle("forced", Object.prototype.hasOwnProperty.call(lastForced, path));
}

// ------------------------------------------------------------------ the live state

function showState(s) {
  $("cycle").textContent = "scan " + s.cycle;
  $("time").textContent = "t = " + (s.time_ns / 1e9).toFixed(2) + " s";
  $("safe").hidden = !s.outputs_safe;
  if (generation !== null && s.generation !== generation) buildTree();
  generation = s.generation;
  for (const [path, value] of Object.entries(s.values)) {
    const r = rows.get(path);
    if (!r) continue;
    const text = format(value);
    const cell = r.el.querySelector(".value");
    if (cell.textContent !== text) cell.textContent = text;
  }
  const before = lastForced;
  lastForced = s.forced;
  for (const path of new Set([...Object.keys(before), ...Object.keys(s.forced)])) applyForced(path);
  showForced(s.forced);
  showTasks(s.tasks, s.faults, s.fault_count);
  showDrivers(s.drivers);
  addTrend(s.numbers);
  addLog(s.log);
}

function format(value) {
  if (value === true) return "TRUE";
  if (value === false) return "FALSE";
  if (typeof value === "number") return Number.isInteger(value) ? String(value) : String(+value.toPrecision(7));
  if (typeof value === "string") return value;
  return JSON.stringify(value);
}

function showForced(forced) {
  const paths = Object.keys(forced);
  const badge = $("forced-count");
  badge.hidden = paths.length === 0;
  badge.textContent = paths.length + " FORCED";
  const list = $("forced-list");
  const key = JSON.stringify(forced);
  if (list.dataset.key === key) return;
  list.dataset.key = key;
  list.textContent = "";
  list.className = paths.length ? "" : "muted";
  if (!paths.length) { list.textContent = "nothing forced"; return; }
  for (const path of paths) {
    list.append(el("div", { class: "forced-item" },
      el("span", { class: "forced-mark", style: "visibility: visible", text: "F" }),
      `${path} = ${format(forced[path])}`,
      el("button", { type: "button", onclick: async () => {
        const r = await api("POST", "/api/unforce", { path });
        if (!r.ok) message(r.data.error || "unforce: HTTP " + r.status, "error");
      } }, "unforce")));
  }
}

const ms = (ns) => (ns / 1e6).toFixed(3);

function showTasks(tasks, faults, count) {
  const body = $("tasks").tBodies[0];
  for (const t of tasks) {
    let tr = body.querySelector(`tr[data-task="${CSS.escape(t.name)}"]`);
    if (!tr) {
      tr = el("tr", { "data-task": t.name }, el("td", { text: t.name }));
      for (let i = 0; i < 8; i++) tr.append(el("td"));
      body.append(tr);
    }
    const cells = tr.cells;
    const texts = [t.interval_ns === null ? "free" : +(t.interval_ns / 1e6).toPrecision(6) + " ms",
      String(t.cycles), ms(t.last_ns), ms(t.mean_ns), ms(t.max_ns), ms(t.jitter_max_ns), String(t.overruns)];
    texts.forEach((text, i) => { if (cells[i + 1].textContent !== text) cells[i + 1].textContent = text; });
    cells[7].className = t.overruns ? "state-bad" : "";
    // the state cell is drawn again only when it changes, so that its Restart button stays put
    const state = cells[8];
    if (state.dataset.fault !== String(t.fault)) {
      state.dataset.fault = String(t.fault);
      state.textContent = "";
      if (t.fault) {
        state.className = "text fault";
        state.append("FAULT: " + t.fault + " ");
        if (info.control) state.append(el("button", { type: "button", class: "restart", onclick: restart }, "Restart"));
      } else {
        state.className = "state-ok";
        state.textContent = "running";
      }
    }
  }
  const f = $("faults");
  const key = count + JSON.stringify(faults.slice(-5));
  if (f.dataset.key === key) return;
  f.dataset.key = key;
  f.textContent = "";
  if (count) {
    f.append(el("div", { class: "fault", text: `${count} runtime fault(s) since the start; the latest:` }));
    for (const line of faults.slice(-5)) f.append(el("div", { class: "fault", text: line }));
  }
}

async function restart() {
  const r = await api("POST", "/api/restart", {});
  if (r.ok) message("restarting " + r.data.restarting.join(", "), "info");
  else message(r.data.error || "restart: HTTP " + r.status, "error");
}

function showDrivers(drivers) {
  const box = $("drivers");
  const key = JSON.stringify(drivers);
  if (box.dataset.key === key) return;
  box.dataset.key = key;
  box.textContent = "";
  for (const d of drivers) {
    const div = el("div", { class: "driver", "data-driver": d.name },
      el("div", {}, el("span", { class: "dot " + (d.ok ? "ok" : "bad") }), el("b", { text: d.name }), " ", d.message));
    const details = d.details || {};
    if (Array.isArray(details.nodes)) div.append(nodeTable(details.nodes));
    for (const [k, v] of Object.entries(details)) {
      if (k !== "nodes") div.append(el("div", { class: "muted", text: `${k}: ${typeof v === "object" ? JSON.stringify(v) : v}` }));
    }
    box.append(div);
  }
}

function nodeTable(nodes) {
  const table = el("table", { class: "grid" },
    el("thead", {}, el("tr", {}, ...["node", "id", "state", "NMT", "boots", "EMCY", "error"].map((h) => el("th", { text: h })))));
  const body = el("tbody");
  for (const n of nodes) {
    const bad = n.state !== "OPERATIONAL";
    body.append(el("tr", {},
      el("td", { text: n.name }), el("td", { text: String(n.id) }),
      el("td", { class: bad ? "state-bad" : "state-ok", text: n.state }),
      el("td", { text: n.nmt || "–" }), el("td", { text: String(n.boots) }),
      el("td", { text: String(n.emergencies) }), el("td", { class: "text", text: n.error || "" })));
    for (const e of (n.emcy || []).slice(-3)) {
      const code = "0x" + e.code.toString(16).toUpperCase().padStart(4, "0");
      body.append(el("tr", {}, el("td", { class: "text emcy", colspan: "7",
        text: `t=${(e.time_ns / 1e9).toFixed(3)}s EMCY ${code} reg 0x${e.register.toString(16).padStart(2, "0")} [${e.data}] ${e.text || ""}` })));
    }
  }
  table.append(body);
  return table;
}

// ------------------------------------------------------------------ trend

function addToTrend(path) {
  if (trend.has(path) || trend.size >= COLORS.length) return;
  const used = new Set([...trend.values()].map((t) => t.color));
  trend.set(path, { color: COLORS.find((c) => !used.has(c)), points: [] });
  showLegend();
  scheduleWatch();
}

function showLegend() {
  const legend = $("trend-legend");
  legend.textContent = "";
  legend.className = trend.size ? "" : "muted";
  if (!trend.size) legend.textContent = "select a variable and press Trend";
  for (const [path, t] of trend) {
    legend.append(el("span", { class: "item" }, el("span", { class: "swatch", style: "background:" + t.color }), path + " ",
      el("button", { type: "button", title: "remove", onclick: () => { trend.delete(path); showLegend(); drawTrend(); scheduleWatch(); } }, "×")));
  }
}

function addTrend(numbers) {
  const now = Date.now();
  const keep = 300_000;
  for (const [path, t] of trend) {
    if (path in numbers) t.points.push([now, numbers[path]]);
    while (t.points.length && t.points[0][0] < now - keep) t.points.shift();
  }
  drawTrend();
}

function drawTrend() {
  const canvas = $("trend");
  const ctx = canvas.getContext("2d");
  const W = canvas.width, H = canvas.height, L = 48, R = 8, T = 8, B = 20;
  ctx.clearRect(0, 0, W, H);
  const windowMs = Number($("trend-window").value) * 1000;
  const now = Date.now();
  let lo = Infinity, hi = -Infinity;
  for (const t of trend.values()) for (const [x, y] of t.points) if (x >= now - windowMs) { lo = Math.min(lo, y); hi = Math.max(hi, y); }
  if (lo === Infinity) { lo = 0; hi = 1; }
  if (hi === lo) { hi += 1; lo -= 1; }
  const pad = (hi - lo) * 0.05; lo -= pad; hi += pad;
  const px = (x) => L + (W - L - R) * (1 - (now - x) / windowMs);
  const py = (y) => T + (H - T - B) * (1 - (y - lo) / (hi - lo));
  ctx.strokeStyle = "#d9dde5"; ctx.fillStyle = "#6b7280"; ctx.font = "11px sans-serif"; ctx.lineWidth = 1;
  for (let i = 0; i <= 4; i++) {
    const y = lo + (hi - lo) * i / 4;
    ctx.beginPath(); ctx.moveTo(L, py(y)); ctx.lineTo(W - R, py(y)); ctx.stroke();
    ctx.fillText(String(+y.toPrecision(4)), 2, py(y) + 4);
  }
  for (let s = 0; s <= 4; s++) {
    const x = now - windowMs * s / 4;
    ctx.fillText(`-${Math.round(windowMs * s / 4000)}s`, px(x) - 12, H - 4);
  }
  ctx.lineWidth = 2;
  for (const t of trend.values()) {
    ctx.strokeStyle = t.color;
    ctx.beginPath();
    let first = true;
    for (const [x, y] of t.points) {
      if (x < now - windowMs) continue;
      if (first) { ctx.moveTo(px(x), py(y)); first = false; } else ctx.lineTo(px(x), py(y));
    }
    ctx.stroke();
  }
}

// ------------------------------------------------------------------ log

function addLog(records) {
  if (!records || !records.length) return;
  const box = $("log");
  const atBottom = box.scrollTop + box.clientHeight >= box.scrollHeight - 4;
  for (const r of records) {
    const time = new Date(r.time * 1000).toLocaleTimeString();
    box.append(el("div", { class: r.level, text: `${time} ${r.level} ${r.name}: ${r.message}` }));
  }
  while (box.childElementCount > 500) box.firstElementChild.remove();
  if (atBottom) box.scrollTop = box.scrollHeight;
}

// ------------------------------------------------------------------ start

function connect() {
  const events = new EventSource("/api/events?client=" + client);
  events.addEventListener("open", () => {
    $("link").textContent = "live";
    $("link").className = "link up";
    sendWatch(); // again after a reconnection: the server forgot this page
  });
  events.addEventListener("error", () => {
    $("link").textContent = "disconnected";
    $("link").className = "link down";
  });
  events.addEventListener("state", (e) => showState(JSON.parse(e.data)));
}

async function main() {
  const r = await api("GET", "/api/info");
  if (r.ok) info = r.data;
  const button = $("online-change");
  button.hidden = !info.online_change;
  button.addEventListener("click", async () => {
    button.disabled = true;
    message("online change: compiling…", "info");
    const c = await api("POST", "/api/online-change", {});
    button.disabled = false;
    if (c.ok) message(c.data.lines.join("\n"), c.data.applied ? "info" : "error");
    else message(c.data.error || "online change: HTTP " + c.status, "error");
  });
  $("do-write").addEventListener("click", () => change("write"));
  $("do-force").addEventListener("click", () => change("force"));
  $("do-unforce").addEventListener("click", () => change("unforce"));
  $("do-trend").addEventListener("click", () => { if (selected) addToTrend(selected.item.path); });
  $("trend-window").addEventListener("change", drawTrend);
  await buildTree();
  connect();
}

main();
