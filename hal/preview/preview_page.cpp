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
table { border-collapse: collapse; margin-top: 12px; }
td, th { padding: 3px 10px; border-bottom: 1px solid #333; text-align: left; }
.bad { color: #ff7b5c; } .good { color: #8fd694; }
h2 { font-size: 16px; margin: 14px 0 4px 0; } #setup p { margin: 2px 0; } #setup-next { font-weight: bold; }
</style>
</head>
<body>
<h1>depthkey preview</h1>
<div id="stages">
<figure><img id="img-composite" src="/stream/composite.mjpg" alt="composite"><figcaption>composite</figcaption></figure>
<figure><img id="img-colour" src="/stream/colour.mjpg" alt="colour"><figcaption>colour camera</figcaption></figure>
<figure><img id="img-depth" src="/stream/depth.mjpg" alt="depth"><figcaption>depth (false colour, 0.5 m red .. 4 m blue)</figcaption></figure>
<figure><img id="img-seeds" src="/stream/seeds.mjpg" alt="seeds"><figcaption>seeds (lecturer orange, board blue, undecided grey)</figcaption></figure>
<figure><img id="img-alpha" src="/stream/alpha.mjpg" alt="alpha"><figcaption>alpha matte</figcaption></figure>
</div>
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
function row(name, value, ok) {
  const tr = document.createElement("tr");
  const a = document.createElement("td"), b = document.createElement("td");
  a.textContent = name; b.textContent = value;
  if (ok !== undefined) b.className = ok ? "good" : "bad";
  tr.append(a, b);
  return tr;
}
async function refresh() {
  const body = document.createElement("tbody");
  try {
    const s = await (await fetch("/status.json", { cache: "no-store" })).json();
    renderSetup(s.setup);
    for (const d of s.devices)
      body.append(row(d.role + " (" + d.name + ")", d.state + ", " + d.fps.toFixed(1) + " fps, " +
                      d.frames + " frames, " + d.dropped + " dropped, " + d.faults + " faults, " +
                      d.reconnects + " reconnects", d.state === "streaming"));
    body.append(row("output", s.output.fps.toFixed(1) + " fps, " + s.output.frames + " frames"));
    if (s.live_score)
      body.append(row("live score (against the truth)",
                      "IoU " + s.live_score.recent.iou.toFixed(3) + ", BF " + s.live_score.recent.bf.toFixed(3) +
                      " over 5 s; IoU " + s.live_score.since_start.iou.toFixed(3) + ", BF " +
                      s.live_score.since_start.bf.toFixed(3) + " since start (" + s.live_score.since_start.frames +
                      " frames); " + s.output.board_only + " board-only frames", s.output.board_only === 0));
    body.append(row("pairing", s.pairing.paired + " paired, " + s.pairing.unpaired + " unpaired"));
    body.append(row("calibration", s.calibration.calibrated ? "loaded " + s.calibration.file
                                                             : "not calibrated", s.calibration.calibrated));
    body.append(row("depth latency", s.depth_latency_ms.toFixed(1) + " ms"));
    body.append(row("depth offset", s.depth_offset.text, s.depth_offset.state !== "held"));
    body.append(row("readers", "composite " + s.readers.composite + ", lecturer " + s.readers.lecturer +
                    ", board-geometry lecturer " + s.readers.board_lecturer,
                    s.readers.composite + s.readers.lecturer + s.readers.board_lecturer > 0));
    if (s.webcam.device !== "")
      body.append(row("webcam (" + s.webcam.device + ")", s.webcam.state + ", " + s.webcam.frames + " frames, " +
                      s.webcam.dropped + " dropped, " + s.webcam.faults + " faults, " +
                      s.webcam.reconnects + " reconnects", s.webcam.state === "writing"));
    body.append(row("preview", s.preview.clients + " streams, " + s.preview.encode_ms.toFixed(1) + " ms per JPEG"));
    body.append(row("uptime", Math.round(s.uptime_s) + " s"));
  } catch (e) {
    body.append(row("status", "unreachable: " + e, false));
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
