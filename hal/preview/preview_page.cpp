#include "hal/preview/preview_page.hpp"

namespace depthkey {

namespace {

constexpr std::string_view kPage = R"HTML(<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>depthkey preview</title>
<style>
body { margin: 0; padding: 12px; background: #1b1d1f; color: #e6e6e6; font: 14px sans-serif; }
h1 { font-size: 18px; margin: 0 0 10px 0; }
#stages { display: grid; grid-template-columns: repeat(auto-fill, minmax(320px, 1fr)); gap: 10px; }
figure { margin: 0; background: #000; }
figure img { display: block; width: 100%; aspect-ratio: 4 / 3; object-fit: contain; background: #000; }
figcaption { padding: 4px 6px; background: #2a2d30; }
figure img { cursor: zoom-in; }
/* A tile without a picture (NO SIGNAL's depth, seeds and alpha; the page's
   first moment) says so in a box of the picture's size, not with the
   browser's broken-image icon: data-state is "picture" once one is shown. */
figure:not([data-state="picture"]) img { display: none; }
figure[data-state="picture"] .no-frame { display: none; }
.no-frame { display: flex; align-items: center; justify-content: center; aspect-ratio: 4 / 3; padding: 0 12%; box-sizing: border-box;
            text-align: center; color: #a8a8a8; background: repeating-linear-gradient(45deg, #111 0 12px, #181818 12px 24px); }
/* A tile clicked is shown alone, as large as the window allows; a click again puts it back. */
figure.enlarged { position: fixed; inset: 0; z-index: 10; display: flex; flex-direction: column; background: #000; }
figure.enlarged img { flex: 1; min-height: 0; width: 100%; height: 100%; aspect-ratio: auto; cursor: zoom-out; }
#actions { margin: 10px 0; }
button { font: inherit; padding: 4px 12px; }
.quiet { color: #a8a8a8; }
table { border-collapse: collapse; margin-top: 12px; }
td, th { padding: 3px 10px; border-bottom: 1px solid #333; text-align: left; }
.bad { color: #ff7b5c; } .good { color: #8fd694; }
h2 { font-size: 16px; margin: 14px 0 4px 0; } #setup p { margin: 2px 0; } #setup-next { font-weight: bold; }
</style>
</head>
<body>
<h1>depthkey preview</h1>
<div id="stages">
<figure><img id="img-composite" src="/snapshot/composite.jpg" data-src="/snapshot/composite.jpg" alt="composite"><div class="no-frame">waiting for the first frame…</div><figcaption>recorded composite <span id="cap-composite" class="quiet"></span></figcaption></figure>
<figure><img id="img-lecturer" src="/snapshot/lecturer.jpg" data-src="/snapshot/lecturer.jpg" alt="lecturer layer"><div class="no-frame">waiting for the first frame…</div><figcaption>lecturer layer (transparent over the checkerboard)</figcaption></figure>
<figure><img id="img-board" src="/snapshot/board.jpg" data-src="/snapshot/board.jpg" alt="board picture"><div class="no-frame">waiting for the first frame…</div><figcaption>board picture <span id="cap-board" class="quiet"></span></figcaption></figure>
<figure><img id="img-colour" src="/snapshot/colour.jpg" data-src="/snapshot/colour.jpg" alt="colour"><div class="no-frame">waiting for the first frame…</div><figcaption>colour camera</figcaption></figure>
<figure><img id="img-depth" src="/snapshot/depth.jpg" data-src="/snapshot/depth.jpg" alt="depth"><div class="no-frame">waiting for the first frame…</div><figcaption>depth (false colour, 0.5 m red .. 4 m blue)</figcaption></figure>
<figure><img id="img-seeds" src="/snapshot/seeds.jpg" data-src="/snapshot/seeds.jpg" alt="seeds"><div class="no-frame">waiting for the first frame…</div><figcaption>seeds (lecturer orange, board blue, undecided grey)</figcaption></figure>
<figure><img id="img-alpha" src="/snapshot/alpha.jpg" data-src="/snapshot/alpha.jpg" alt="alpha"><div class="no-frame">waiting for the first frame…</div><figcaption>alpha matte</figcaption></figure>
</div>
<div id="actions"><button id="snapshot" type="button">Save stage pictures</button> <span id="snapshot-result" class="quiet"></span></div>
<table id="status"><tbody><tr><td>status</td><td>loading…</td></tr></tbody></table>
<!-- The first-run path's state (issue 30, docs/first-run.md): status.json's "setup". -->
<h2>setup</h2>
<section id="setup"><p>setup: loading…</p></section>
<script>
"use strict";
function renderSetup(setup) {
  const section = document.createElement("section");
  section.id = "setup";
  const line = (text, ok) => {
    const p = document.createElement("p");
    p.textContent = text;
    p.className = ok ? "good" : "bad";
    section.append(p);
  };
  for (const d of setup.devices)
    line(d.role + ": " + (d.found ? d.name + (d.device ? " (" + d.device + ")" : "") : d.backend + " " + d.device + " NOT found: " + d.next), d.found);
  line("depth calibration: " + setup.depth_calibration.state, setup.depth_calibration.calibrated);
  line("board calibration: " + setup.board_calibration.state, setup.board_calibration.calibrated);
  const next = document.createElement("p");
  next.id = "setup-next";
  next.textContent = setup.ready ? "setup done: record (docs/first-run.md)" : "next: " + setup.next;
  section.append(next);
  document.getElementById("setup").replaceWith(section);
}
</script>
<script>
"use strict";
// ok: true green, false red, undefined plain, null grey (nothing wrong, nothing yet).
function row(name, value, ok) {
  const tr = document.createElement("tr");
  const a = document.createElement("td"), b = document.createElement("td");
  a.textContent = name; b.textContent = value;
  if (ok === null) b.className = "quiet";
  else if (ok !== undefined) b.className = ok ? "good" : "bad";
  tr.append(a, b);
  return tr;
}
// Each tile asks for its stage's next JPEG once the last has come, not for
// an endless MJPEG stream: a browser opens at most 6 connections to a host,
// and seven streams left none for status.json (issue 30). The JPEG is shown
// once whole (a blob), so a request cut short leaves the last picture up.
// At most 4 tiles wait for their JPEG at once: 2 connections stay free for
// status.json and the snapshot button.
let freeConnections = 4;
const waitingTiles = [];
async function withConnection(work) {
  while (freeConnections === 0) await new Promise((resolve) => waitingTiles.push(resolve));
  freeConnections--;
  try { return await work(); } finally {
    freeConnections++;
    const wake = waitingTiles.shift();
    if (wake) wake();
  }
}
// A tile shows its picture only once one has loaded (data-state
// "picture"); until then, and whenever the daemon says it has none (503 and
// why), its placeholder says so. A request cut short keeps the tile as it was.
function noFrame(figure, why) {
  figure.dataset.state = "no-frame";
  figure.querySelector(".no-frame").textContent = why;
}
class NoFrame extends Error {}
for (const img of document.querySelectorAll("#stages img")) {
  const figure = img.closest("figure");
  let n = 0, shown = null;
  const next = async () => {
    try {
      const blob = await withConnection(async () => {
        const r = await fetch(img.dataset.src + "?n=" + (++n), { cache: "no-store" });
        if (!r.ok) throw new NoFrame((await r.text()).trim() || "no frame (HTTP " + r.status + ")");
        return await r.blob();
      });
      const url = URL.createObjectURL(blob);
      img.src = url;
      if (shown) URL.revokeObjectURL(shown);
      shown = url;
      setTimeout(next, 100);
    } catch (e) {
      if (e instanceof NoFrame) noFrame(figure, e.message);
      setTimeout(next, 1000);
    }
  };
  img.addEventListener("load", () => { if (img.naturalWidth > 0) figure.dataset.state = "picture"; });
  img.addEventListener("error", () => noFrame(figure, "no " + img.id.replace("img-", "") + " frame yet"));
  // The first picture is the <img>'s own (the page's load waits for it).
  let first = true;
  const start = (delay) => { if (first) { first = false; setTimeout(next, delay); } };
  img.addEventListener("load", () => start(100));
  img.addEventListener("error", () => start(1000));
}
for (const figure of document.querySelectorAll("#stages figure"))
  figure.querySelector("img").addEventListener("click", () => figure.classList.toggle("enlarged"));
document.addEventListener("keydown", (e) => {
  if (e.key === "Escape")
    for (const f of document.querySelectorAll("figure.enlarged")) f.classList.remove("enlarged");
});
document.getElementById("snapshot").addEventListener("click", async () => {
  const out = document.getElementById("snapshot-result");
  out.textContent = "saving…"; out.className = "quiet";
  try {
    const r = await fetch("/snapshot", { method: "POST", headers: { "X-Depthkey-Snapshot": "1" }, cache: "no-store" });
    out.textContent = (await r.text()).trim();
    out.className = r.ok ? "good" : "bad";
  } catch (e) {
    out.textContent = "unreachable: " + e; out.className = "bad";
  }
});
function ms(value) { return value === null ? "-" : value.toFixed(1) + " ms"; }
async function refresh() {
  const body = document.createElement("tbody");
  try {
    const s = await (await fetch("/status.json", { cache: "no-store" })).json();
    renderSetup(s.setup);
    for (const d of s.devices)
      body.append(row(d.role + " (" + d.name + ")", d.state + ", " + d.fps.toFixed(1) + " fps, " +
                      d.frames + " frames, " + d.dropped + " dropped, " + d.faults + " faults, " +
                      d.reconnects + " reconnects", d.state === "streaming"));
    body.append(row("board (" + s.board.source + ")", s.board.text, s.board.state === "streaming" && s.board.geometry));
    document.getElementById("cap-composite").textContent = s.board.geometry
      ? "(board geometry " + s.board.width + "x" + s.board.height + ")" : "(camera geometry: board not calibrated)";
    document.getElementById("cap-board").textContent = "(" + s.board.source + ", " + s.board.state + ")";
    body.append(row("output", s.output.fps.toFixed(1) + " fps, " + s.output.frames + " frames"));
    body.append(row("keying", "median " + ms(s.keying.median_ms) + ", p99 " + ms(s.keying.p99_ms) + ", max " +
                    ms(s.keying.max_ms) + "; " + s.keying.shed + " frames shed" + (s.keying.shed > 0 ? " (box too slow)" : ""), s.keying.shed === 0));
    if (s.live_score)
      body.append(row("live score (against the truth)",
                      "IoU " + s.live_score.recent.iou.toFixed(3) + ", BF " + s.live_score.recent.bf.toFixed(3) +
                      " over 5 s; IoU " + s.live_score.since_start.iou.toFixed(3) + ", BF " +
                      s.live_score.since_start.bf.toFixed(3) + " since start (" + s.live_score.since_start.frames +
                      " frames); " + s.output.board_only + " board-only frames", s.output.board_only === 0));
    body.append(row("pairing", s.pairing.paired + " paired, " + s.pairing.unpaired + " unpaired"));
    body.append(row("calibration", s.calibration.calibrated ? "loaded " + s.calibration.file
                                                             : "not calibrated", s.calibration.calibrated));
    body.append(row("depth arrival (after its capture stamp)", ms(s.depth_arrival_ms)));
    const o = s.depth_offset;
    // The daemon's text says measured, applied and why; held is no fault
    // (every start holds until the estimates agree): grey, not red; green
    // once an offset is in use.
    body.append(row("depth offset (" + o.state + ")",
                    o.text ? o.text : "measured " + ms(o.measured_ms) + ", applied " + ms(o.applied_ms),
                    o.state === "applied" || o.state === "set" ? true : null));
    const readers = s.readers.composite + s.readers.lecturer + s.readers.board_lecturer;
    body.append(row("readers", "composite " + s.readers.composite + ", lecturer " + s.readers.lecturer +
                    ", board-geometry lecturer " + s.readers.board_lecturer +
                    (readers === 0 && !s.readers.ever_attached ? " (no recorder has attached yet)" : ""),
                    readers > 0 ? true : s.readers.ever_attached ? false : null));
    if (s.webcam.device !== "")
      body.append(row("webcam (" + s.webcam.device + ")", s.webcam.state + ", " + s.webcam.frames + " frames, " +
                      s.webcam.dropped + " dropped, " + s.webcam.faults + " faults, " +
                      s.webcam.reconnects + " reconnects", s.webcam.state === "writing"));
    body.append(row("preview", s.preview.clients + " streams, " + s.preview.encode_ms.toFixed(1) + " ms per JPEG"));
    body.append(row("uptime", Math.round(s.uptime_s) + " s"));
    body.append(row("version", s.version));
    body.append(row("config", s.config_path));
    if (s.errors.length === 0)
      body.append(row("recent errors", "none", true));
    for (const e of s.errors)
      body.append(row("error at " + new Date(e.unix_time_s * 1000).toLocaleTimeString(),
                      e.message + (e.count > 1 ? " (" + e.count + " times)" : ""), false));
  } catch (e) {
    // Keep the last figures, marked stale.
    const last = document.getElementById("status").tBodies[0];
    body.append(row("status", "unreachable: " + e + " (the figures below are the last ones)", false));
    if (last) for (const tr of [...last.rows].filter((r) => r.cells[0].textContent !== "status")) body.append(tr);
  }
  document.getElementById("status").replaceChildren(body);
}
refresh();
setInterval(refresh, 1000);
</script>
</body>
</html>
)HTML";

} // namespace

std::string_view previewPageHtml()
{
	return kPage;
}

} // namespace depthkey
