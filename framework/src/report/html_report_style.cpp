// voxlab: the grader's HTML reports' inline style sheet and sorting script.
// Nothing here loads anything from outside the page: system fonts only.
#include "html_text.h"

namespace voxlab::html {

const char* const reportStyleSheet = R"css(
:root {
  --bg: #f3f4f6; --card: #ffffff; --ink: #1f2328; --muted: #656d76; --line: #d8dee4; --head: #1c2430;
  --pass: #1a7f37; --pass-bg: #dafbe1; --fail: #cf222e; --fail-bg: #ffebe9; --warn: #9a6700; --warn-bg: #fff8c5;
  --idle: #57606a; --idle-bg: #eaeef2; --info: #0969da; --info-bg: #ddf4ff; --orange: #bc4c00; --orange-bg: #fff1e5;
}
* { box-sizing: border-box; }
body { margin: 0; background: var(--bg); color: var(--ink);
  font: 15px/1.5 system-ui, -apple-system, "Segoe UI", Roboto, "Noto Sans", "DejaVu Sans", Arial, sans-serif; }
a { color: var(--info); text-decoration: none; }
a:hover { text-decoration: underline; }
code, pre, .path, .stage-id, .scene-name, .check-name {
  font-family: ui-monospace, "SFMono-Regular", "DejaVu Sans Mono", Menlo, Consolas, monospace; }

header.top { display: flex; justify-content: space-between; align-items: flex-end; gap: 32px;
  background: var(--head); color: #f0f3f6; padding: 28px 40px 24px; }
header.top .kicker { text-transform: uppercase; letter-spacing: .12em; font-size: 12px; color: #9aa6b2; }
header.top h1 { margin: 2px 0 4px; font-size: 34px; line-height: 1.15; }
header.top .path { color: #b6c2cf; font-size: 13px; word-break: break-all; }
dl.meta { display: flex; flex-wrap: wrap; gap: 6px 28px; margin: 14px 0 0; }
dl.meta div { display: flex; gap: 8px; }
dl.meta dt { color: #9aa6b2; }
dl.meta dd { margin: 0; }
.total { text-align: right; min-width: 220px; }
.total-score { font-size: 56px; font-weight: 700; line-height: 1; font-variant-numeric: tabular-nums; white-space: nowrap; }
.total-score .of { font-size: 26px; font-weight: 400; color: #9aa6b2; }
.total .percent { color: #b6c2cf; margin: 6px 0 8px; }
.total .bar { width: 100%; height: 8px; background: #39434f; }

main { max-width: 1400px; margin: 0 auto; padding: 24px 16px 8px; }
.card { background: var(--card); border: 1px solid var(--line); border-radius: 8px; padding: 20px 24px;
  margin-bottom: 24px; box-shadow: 0 1px 2px rgba(31, 35, 40, .06); }
.card > h2 { margin: 0 0 12px; font-size: 20px; }
h3 { margin: 22px 0 10px; font-size: 15px; text-transform: uppercase; letter-spacing: .06em; color: var(--muted); }
.sub { color: var(--muted); font-size: 12.5px; }
.message { margin: 8px 0; }
.about { color: var(--muted); margin: 4px 0; }
.about .label { color: var(--ink); font-weight: 600; }
.hint { margin: 6px 0; padding: 6px 10px; border-left: 4px solid #d9a400; background: rgba(217, 164, 0, 0.10); }
.legend { color: var(--muted); font-size: 12.5px; margin: 10px 0 0; }

table { border-collapse: collapse; width: 100%; }
th, td { text-align: left; padding: 7px 10px; border-bottom: 1px solid var(--line); vertical-align: top; }
thead th { font-size: 12.5px; text-transform: uppercase; letter-spacing: .05em; color: var(--muted);
  border-bottom: 2px solid var(--line); }
.num { text-align: right; white-space: nowrap; font-variant-numeric: tabular-nums; }
table.summary td.msg { color: var(--muted); }
table.summary tbody tr:hover, table.gradebook tbody tr:hover { background: #f6f8fa; }

.bar { display: block; height: 5px; background: var(--idle-bg); border-radius: 3px; overflow: hidden;
  margin-top: 5px; min-width: 80px; }
.bar .fill { display: block; height: 100%; }
.fill.full { background: #2da44e; } .fill.partial { background: #d4a72c; } .fill.none { background: var(--fail); }

.badge { display: inline-block; padding: 1px 10px; border-radius: 999px; font-size: 12.5px; font-weight: 600;
  white-space: nowrap; background: var(--idle-bg); color: var(--idle); border: 1px solid rgba(0, 0, 0, .06); }
.st-passed { background: var(--pass-bg); color: var(--pass); }
.st-failed, .st-error { background: var(--fail-bg); color: var(--fail); }
.st-crashed { background: var(--fail); color: #fff; }
.st-compile_error { background: var(--orange-bg); color: var(--orange); }
.st-timeout { background: var(--warn-bg); color: var(--warn); }
.st-not_implemented, .st-blocked { background: var(--idle-bg); color: var(--idle); }
.st-example { background: var(--info-bg); color: var(--info); }

.stage-head { display: flex; align-items: center; gap: 14px; flex-wrap: wrap; }
.stage-head h2 { margin: 0; font-size: 22px; flex: 1 1 auto; }
.stage-id { font-size: 14px; font-weight: 400; color: var(--muted); margin-left: 6px; }
.score { font-variant-numeric: tabular-nums; font-weight: 600; }
.score.big { font-size: 20px; }
.log-box summary, details summary { cursor: pointer; color: var(--muted); }
pre.log { background: #0d1117; color: #e6edf3; padding: 12px 14px; border-radius: 6px; overflow-x: auto;
  font-size: 13px; line-height: 1.45; margin: 6px 0 0; max-height: 480px; overflow-y: auto; }
pre.log .err { color: #ff7b72; } pre.log .warn { color: #e3b341; }

.scene { border-top: 1px solid var(--line); padding: 14px 0 6px; }
.scene:first-of-type { border-top: 0; }
.scene-head { display: flex; align-items: center; gap: 12px; }
.scene-name { font-weight: 600; font-size: 15px; }
.scene-head .score { margin-left: auto; }
.setup { color: var(--muted); font-size: 12.5px; margin: 2px 0 6px; overflow-wrap: anywhere; }
.setup code { color: var(--ink); }
.scene-body { display: flex; flex-wrap: wrap; gap: 16px; margin-top: 8px; align-items: flex-start; }
.figures { display: flex; flex-wrap: wrap; gap: 12px; align-items: flex-start; min-width: 0; max-width: 100%; }
.maps { display: flex; flex-direction: column; gap: 6px; margin-top: 31px; }
.scene-body .metrics { flex: 1 1 300px; display: grid; grid-template-columns: repeat(auto-fill, minmax(150px, 1fr));
  align-content: start; margin-top: 31px; }
.scene-body .metrics .m-label { white-space: normal; }

/* A comparison: the expected image under the student's, split by a slider. */
.compare { min-width: 0; max-width: 100%; }
.compare > input { position: absolute; opacity: 0; width: 1px; height: 1px; margin: 0; pointer-events: none; }
.modes { display: flex; flex-wrap: wrap; gap: 4px; margin-bottom: 6px; }
.modes label { cursor: pointer; user-select: none; font-size: 12.5px; line-height: 1.5; padding: 2px 11px;
  border: 1px solid var(--line); border-radius: 999px; background: #fafbfc; color: var(--muted); }
.modes label:hover { border-color: var(--muted); }
.modes .m-zoom { margin-left: auto; }
.v-split:checked ~ .modes .m-split, .v-expected:checked ~ .modes .m-expected, .v-mine:checked ~ .modes .m-mine,
.v-zoom:checked ~ .modes .m-zoom { background: var(--head); border-color: var(--head); color: #fff; }
.compare > input:focus-visible ~ .modes { outline: 2px solid var(--info); outline-offset: 2px; border-radius: 6px; }
.stack { --split: 50%; position: relative; width: var(--w); max-width: 100%; line-height: 0; background: #000;
  border: 1px solid var(--line); }
.v-zoom:checked ~ .stack { width: calc(2 * var(--w)); }
.stack img { display: block; width: 100%; height: auto; image-rendering: pixelated; image-rendering: crisp-edges; }
.stack .over { position: absolute; top: 0; left: 0; clip-path: inset(0 0 0 var(--split)); }
.stack .divider { position: absolute; top: 0; bottom: 0; left: var(--split); width: 2px; margin-left: -1px;
  background: #fff; box-shadow: 0 0 0 1px rgba(0, 0, 0, .45); pointer-events: none; }
.stack .slider { display: none; position: absolute; top: 0; left: 0; width: 100%; height: 100%; margin: 0;
  opacity: 0; cursor: ew-resize; }
.scripted .stack .slider { display: block; }
.stack .tag { position: absolute; top: 6px; padding: 0 7px; border-radius: 4px; background: rgba(0, 0, 0, .62);
  color: #fff; font-size: 11.5px; font-weight: 600; line-height: 1.7; pointer-events: none; }
.stack .tag.left { left: 6px; } .stack .tag.right { right: 6px; }
.v-expected:checked ~ .stack .over, .v-expected:checked ~ .stack .divider, .v-expected:checked ~ .stack .slider,
.v-expected:checked ~ .stack .tag.right, .v-mine:checked ~ .stack .divider, .v-mine:checked ~ .stack .slider,
.v-mine:checked ~ .stack .tag.left { display: none; }
.v-mine:checked ~ .stack .over { clip-path: none; }
.open { font-size: 12px; color: var(--muted); margin-top: 4px; }
figure { margin: 0; }
figure img { display: block; image-rendering: pixelated; image-rendering: crisp-edges; background: #000;
  border: 1px solid var(--line); }
figcaption { font-size: 12.5px; color: var(--muted); text-align: center; margin-top: 3px; }
.placeholder { display: flex; align-items: center; justify-content: center; text-align: center; padding: 12px;
  min-width: 256px; min-height: 256px; border: 2px dashed var(--line); border-radius: 6px; color: var(--muted);
  font-size: 13px; overflow-wrap: anywhere; overflow: auto;
  background: repeating-linear-gradient(45deg, #fafbfc, #fafbfc 10px, #f3f4f6 10px, #f3f4f6 20px); }
.placeholder.why { color: var(--fail); font-family: ui-monospace, "DejaVu Sans Mono", Menlo, Consolas, monospace;
  font-size: 12px; text-align: left; }
.placeholder.wide { min-width: 0; width: 100%; min-height: 120px; color: var(--fail); font-weight: 600; }

.metrics { display: flex; flex-wrap: wrap; gap: 8px; }
.metric { min-width: 128px; padding: 6px 12px 7px; border: 1px solid var(--line); border-left: 4px solid var(--line);
  border-radius: 6px; background: #fafbfc; }
.m-label { font-size: 12px; color: var(--muted); white-space: nowrap; }
.m-value { font-size: 19px; font-weight: 600; font-variant-numeric: tabular-nums; line-height: 1.3; }
.m-bound { font-size: 12px; color: var(--muted); white-space: nowrap; }
.metric.ok { border-left-color: #2da44e; } .metric.ok .m-value { color: var(--pass); }
.metric.bad { border-color: #ffcecb; border-left-color: var(--fail); background: var(--fail-bg); }
.metric.bad .m-value { color: var(--fail); }
.metric.shown .m-value { color: #424a53; font-weight: 500; }

table.checks .check-name { font-weight: 600; }
table.checks .inputs { color: var(--muted); font-size: 12.5px; margin-top: 4px; }
ul.examples { margin: 6px 0 0; padding-left: 18px; }
ul.examples code { font-size: 12.5px; background: #f6f8fa; padding: 1px 4px; border-radius: 4px;
  overflow-wrap: anywhere; }

.wide-table { overflow-x: auto; }
table.gradebook thead th { cursor: pointer; user-select: none; white-space: nowrap; }
table.gradebook thead th[aria-sort="ascending"]::after { content: " \25B2"; }
table.gradebook thead th[aria-sort="descending"]::after { content: " \25BC"; }
table.gradebook td.cell { font-weight: 600; }
table.gradebook td.total-cell { font-weight: 700; }
.cell-passed { color: var(--pass); } .cell-failed, .cell-error, .cell-crashed { color: var(--fail); }
.cell-compile_error { color: var(--orange); } .cell-timeout { color: var(--warn); }
.cell-not_implemented { color: var(--idle); }
table.gradebook tfoot td { font-weight: 600; border-top: 2px solid var(--line); border-bottom: 0; }
/* Fifteen stages fit 1280 px: names run upwards, the name column stays in view when it does not fit. */
table.gradebook th, table.gradebook td { padding: 6px 6px; }
table.gradebook thead th { vertical-align: bottom; }
table.gradebook th.stage-col { padding: 6px 3px; text-transform: none; letter-spacing: 0; }
table.gradebook th.stage-col .up { display: inline-block; writing-mode: vertical-rl; transform: rotate(180deg);
  font-family: ui-monospace, "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 12px; color: var(--ink); }
table.gradebook .who { position: sticky; left: 0; z-index: 1; background: var(--card); min-width: 200px;
  max-width: 340px; overflow-wrap: anywhere; }
table.gradebook thead .who { text-transform: none; }
table.gradebook tbody tr:hover td.who { background: #f6f8fa; }
table.gradebook td.cell .note { font-size: 10.5px; line-height: 1.15; white-space: normal; margin-top: 2px; }
.probs { margin-top: 3px; font-size: 12.5px; line-height: 1.4; }
.prob { margin-top: 2px; }
.prob b { font-weight: 600; }
.p-compile_error b { color: var(--orange); } .p-crashed b, .p-error b, .p-failed b { color: var(--fail); }
.p-timeout b { color: var(--warn); } .p-not_implemented, .p-not_implemented b { color: var(--muted); font-weight: 400; }
.prob .why { font-family: ui-monospace, "DejaVu Sans Mono", Menlo, Consolas, monospace; font-size: 12px; }

footer { text-align: center; color: var(--muted); font-size: 12.5px; padding: 8px 0 28px; }
@media print { body { background: #fff; } .card { box-shadow: none; break-inside: avoid-page; } }
)css";

// Click a heading to sort by its column (again to reverse): numbers by value,
// anything else alphabetically, from each cell's data-sort.
const char* const sortableTableScript = R"js(
document.querySelectorAll('table.sortable').forEach(function (table) {
  var headings = table.tHead.rows[0].cells;
  Array.prototype.forEach.call(headings, function (heading, column) {
    heading.addEventListener('click', function () {
      var ascending = heading.getAttribute('aria-sort') === 'descending';
      Array.prototype.forEach.call(headings, function (h) { h.removeAttribute('aria-sort'); });
      heading.setAttribute('aria-sort', ascending ? 'ascending' : 'descending');
      var body = table.tBodies[0];
      var rows = Array.prototype.slice.call(body.rows);
      rows.sort(function (a, b) {
        var x = a.cells[column].getAttribute('data-sort') || '', y = b.cells[column].getAttribute('data-sort') || '';
        var nx = parseFloat(x), ny = parseFloat(y);
        var order = (!isNaN(nx) && !isNaN(ny)) ? nx - ny : x.localeCompare(y);
        return ascending ? order : -order;
      });
      rows.forEach(function (row) { body.appendChild(row); });
    });
  });
});
)js";

// The comparisons' sliders: each moves the split of its own stack. Without
// this script the split stays in the middle and the buttons still work.
const char* const compareSliderScript = R"js(
document.documentElement.classList.add('scripted');
document.querySelectorAll('.compare .slider').forEach(function (slider) {
  var stack = slider.parentNode;
  function update() { stack.style.setProperty('--split', slider.value + '%'); }
  slider.addEventListener('input', update);
  update();
});
)js";

}  // namespace voxlab::html
