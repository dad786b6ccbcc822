// hkf's live view: the events of /events (Server-Sent Events, one JSON object each) drawn as they come.
"use strict";

const token = document.querySelector('meta[name="hkf-token"]').content;
const WINDOW_S = 10;
const AXES = ["pitch", "yaw", "roll"];
const COLOURS = { filtered: "#ffffff", mesh_pnp: "#4fc3f7", whenet: "#ffb74d" };
const traces = { filtered: [] }; // per source: [t_s, pitch, yaw, roll]
let newest = 0; // s: the newest sample's time
let lastStatus = null;
let knobTouched = false; // the knob shows the node's value until the player turns it

const $ = (id) => document.getElementById(id);
const fixed = (v, digits, unit) => (v === null || v === undefined ? "-" : v.toFixed(digits) + unit);

function keep(source, utime, pitch, yaw, roll) {
  const t = utime / 1e6;
  (traces[source] = traces[source] || []).push([t, pitch, yaw, roll]);
  newest = Math.max(newest, t);
  for (const s of Object.keys(traces)) {
    while (traces[s].length && traces[s][0][0] < newest - WINDOW_S) traces[s].shift();
  }
}

function onRaw(e) {
  if (e.valid) keep(e.model, e.utime, e.pitch, e.yaw, e.roll);
}

function onPose(e) {
  if (e.extrapolated) return;
  keep("filtered", e.utime, e.pitch, e.yaw, e.roll);
  $("state").textContent = e.status;
  $("state").className = e.status;
  AXES.forEach((a, i) => { $(a).textContent = fixed(e.from_center[i], 1, "\u00b0"); });
  ["x", "y", "z"].forEach((a, i) => { $(a).textContent = e.z > 0 ? fixed(e.position_from_center[i], 1, " cm") : "-"; });
  $("latency").textContent = fixed(e.latency_ms, 0, " ms");
}

function onStatus(e) {
  window.latestStatus = e; // for a look from the browser's console (and the browser test)
  const bar = $("rest-fill"), text = $("rest-text");
  bar.style.width = (100 * (e.progress || 0)).toFixed(0) + "%";
  if (e.rest === "RESTING") {
    const left = Math.max(0, (1 - e.progress) * e.rest_time);
    const moved = lastStatus && e.spoiled > lastStatus.spoiled;
    text.textContent = "Look at the screen's centre and keep still: " + left.toFixed(1) + " s" + (moved ? " (you moved: again)" : "");
    text.className = moved ? "moved" : "";
  } else if (e.rest === "MEASURED") {
    text.textContent = "Rest measured.";
    text.className = "";
  } else {
    text.textContent = "No rest asked for.";
  }
  // the rest's own wander, before the stillness scales it: its largest spread beyond noise, bounded (hkf_rest.h)
  const measured = Math.min(0.3, Math.max(0, ...e.rest_spread.map((v, i) => v - e.rest_noise[i])));
  $("wander-text").textContent = "Wander in use " + fixed(e.wander, 3, " deg\u00b2") + (e.wander_measured
    ? " = the rest's " + fixed(measured, 3, " deg\u00b2") + " \u00d7 stillness " + fixed(e.stillness, 2, "")
    : " (the built-in: no rest measured yet)");
  if (!knobTouched && e.stillness !== null) {
    $("stillness").value = e.stillness;
    $("stillness-value").textContent = e.stillness.toFixed(2);
  }
  $("commands").textContent = "hkf-filter took " + e.commands + " commands; settings saved " + e.settings_saved +
    " times" + (e.settings_unsaved ? ", " + e.settings_unsaved + " saves failed (see hkf-filter's log)" : "");
  if (!lastStatus || e.rest !== "RESTING" || e.spoiled !== lastStatus.spoiled) lastStatus = e;
}

function onLine(e) {
  $("line").textContent = e.text;
  const rate = /camera +([0-9.]+) fps/.exec(e.text);
  $("rate").textContent = rate ? rate[1] + " fps" : "-";
}

// One picture fetched at a time: while one loads, only the newest announced is kept to fetch next (a slow
// phone, or the burst of a new stream's replay, never queues up requests).
let pictureLoading = false, pictureNext = null;
function fetchPicture(n) {
  if (pictureLoading) {
    pictureNext = n;
    return;
  }
  pictureLoading = true;
  $("camera").src = "picture.jpg?n=" + n;
}
function pictureDone() {
  pictureLoading = false;
  if (pictureNext !== null) {
    const n = pictureNext;
    pictureNext = null;
    fetchPicture(n);
  }
}

function onPicture(e) {
  fetchPicture(e.n);
  $("camera-note").textContent = "frame " + e.seq;
}

function draw() {
  const canvas = $("traces"), g = canvas.getContext("2d");
  const w = canvas.width, h = canvas.height / 3;
  g.clearRect(0, 0, canvas.width, canvas.height);
  AXES.forEach((axis, i) => {
    const all = Object.values(traces).flat().map((p) => p[i + 1]);
    const lo = Math.min(-10, ...all), hi = Math.max(10, ...all);
    const y = (v) => i * h + 6 + (h - 12) * (hi - v) / (hi - lo);
    g.fillStyle = "#9aa3ad";
    g.font = "12px sans-serif";
    g.fillText(axis + " (" + lo.toFixed(0) + " to " + hi.toFixed(0) + "\u00b0)", 4, i * h + 14);
    for (const [source, points] of Object.entries(traces)) {
      g.strokeStyle = COLOURS[source] || "#aed581";
      g.lineWidth = source === "filtered" ? 2 : 1;
      g.beginPath();
      points.forEach((p, k) => {
        const x = w * (1 - (newest - p[0]) / WINDOW_S);
        k ? g.lineTo(x, y(p[i + 1])) : g.moveTo(x, y(p[i + 1]));
      });
      g.stroke();
    }
  });
  $("legend").innerHTML = "";
  for (const source of Object.keys(traces)) {
    const item = document.createElement("span");
    item.style.color = COLOURS[source] || "#aed581";
    item.textContent = source === "filtered" ? "\u2501 filtered" : "\u2500 raw " + source;
    $("legend").appendChild(item);
  }
  requestAnimationFrame(draw);
}

async function command(verb) {
  try {
    const answer = await fetch("command/" + verb, { method: "POST", headers: { "X-HKF-Token": token } });
    $("answer").textContent = verb.split("?")[0] + ": " + (await answer.text()).trim();
  } catch (err) {
    $("answer").textContent = verb.split("?")[0] + ": " + err;
  }
}

function connect() {
  const events = new EventSource("events");
  const handlers = { raw: onRaw, pose: onPose, status: onStatus, line: onLine, picture: onPicture };
  events.onopen = () => { $("connection").textContent = "live"; $("connection").className = "on"; };
  events.onerror = () => { $("connection").textContent = "reconnecting"; $("connection").className = "off"; };
  events.onmessage = (m) => {
    const e = JSON.parse(m.data);
    if (handlers[e.t]) handlers[e.t](e);
  };
}

$("camera").addEventListener("load", pictureDone);
$("camera").addEventListener("error", pictureDone);
$("recenter").addEventListener("click", () => command("recenter"));
$("reset").addEventListener("click", () => command("reset"));
$("save").addEventListener("click", () => command("save"));
$("stillness").addEventListener("input", () => {
  knobTouched = true;
  $("stillness-value").textContent = Number($("stillness").value).toFixed(2);
});
$("stillness").addEventListener("change", () => command("stillness?value=" + $("stillness").value));
connect();
requestAnimationFrame(draw);
