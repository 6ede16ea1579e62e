// voxlab workbench: the page around the WebAssembly viewer (docs/web.md).
//
// The viewer itself is the native one, compiled (web/main_web.cpp); this file
// is only the student's side of the page: the stage's files in an editor,
// saved into the module's file system and compiled by the viewer; the
// handout; the self-check, whose verdicts come from the grader's C++
// (framework/src/grade/self_check.cpp). Nothing here judges an image.
'use strict';

const ROOT = '/voxlab';
const STAGE_FILE = /\.(glsl|frag|vert|cpp|h)$/;
const $ = (id) => document.getElementById(id);

// ?scene=PATH (in the project tree) opens the viewer on that scene instead
// of the stage's first grading scene.
const sceneParam = new URLSearchParams(location.search).get('scene');

var Module = {
  canvas: $('canvas'),
  arguments: sceneParam ? [ROOT + '/' + sceneParam.replace(/^\/+/, '')] : [],
  print: (text) => console.log(text),
  printErr: (text) => console.warn(text),
  postRun: [() => workbench.start()],
  // The viewer stopped (it could not start, or a frame failed): say why on the page.
  voxlabStopped: (message) => {
    $('loading').hidden = false;
    $('loading').textContent = 'voxlab stopped: ' + message + ' (reload the page to start again)';
    $('loading').className = 'bad';
  },
};

const workbench = {
  stage: '',
  student: 1,
  file: '',
  edits: {},  // path -> text not yet saved
  errorLines: new Set(),  // lines of the open file the compiler named
  ready: false,

  tree() { return ROOT + (this.student ? '/assignments' : '/reference'); },
  stageDir() { return this.tree() + '/' + this.stage; },
  exists(path) { try { Module.FS.stat(path); return true; } catch (e) { return false; } },
  read(path) { return Module.FS.readFile(path, { encoding: 'utf8' }); },

  start() {
    if ($('loading').className !== 'bad') $('loading').hidden = true;  // (unless the viewer could not start)
    if (!this.exists(ROOT + '/reference')) $('tree').options[1].disabled = true;  // a student release
    this.fillStages();
    this.fillDatasets();
    for (const b of document.querySelectorAll('#tabs button')) b.onclick = () => this.showTab(b.dataset.tab);
    $('stage').onchange = () => this.openStage($('stage').value);
    $('tree').onchange = () => { this.student = Number($('tree').value); this.openStage(this.stage); };
    $('compile').onclick = () => this.compile();
    $('download').onclick = () => this.saveToDisk();
    $('open').onchange = (e) => this.openFromDisk(e.target.files[0]);
    $('run-check').onclick = () => this.selfCheck();
    $('why-native').onclick = (e) => { e.preventDefault(); $('why-native-text').hidden = false; };
    const editor = $('editor');
    editor.oninput = () => { this.edits[this.path()] = editor.value; this.numberLines(); };
    editor.onscroll = () => { $('gutter').scrollTop = editor.scrollTop; };
    editor.onkeydown = (e) => this.editorKey(e);
    document.addEventListener('keydown', (e) => {
      if ((e.ctrlKey || e.metaKey) && e.key === 's') { e.preventDefault(); this.compile(); }
    });
    // The viewer draws at the canvas's size as the page lays it out.
    new ResizeObserver(() => {
      const c = Module.canvas;
      Module.ccall('vx_resize', null, ['number', 'number'], [Math.round(c.clientWidth), Math.round(c.clientHeight)]);
    }).observe(Module.canvas);
    this.openStage($('stage').value, !sceneParam);
    this.ready = true;
  },

  // The bundled volumes; choosing one opens it in the view.
  fillDatasets() {
    const dir = ROOT + '/datasets';
    for (const f of Module.FS.readdir(dir).filter((f) => /\.(nrrd|fld|dat)$/.test(f)).sort())
      $('dataset').add(new Option(f, `${dir}/${f}`));
    $('dataset').onchange = () => {
      if ($('dataset').value) Module.ccall('vx_open', null, ['string'], [$('dataset').value]);
      else this.openStage(this.stage);
    };
  },

  // Every stage folder with a grading.json, in teaching order.
  fillStages() {
    const base = ROOT + '/assignments';
    const stages = Module.FS.readdir(base).filter((d) => this.exists(`${base}/${d}/grading.json`)).map((d) => {
      const m = JSON.parse(this.read(`${base}/${d}/grading.json`));
      return { name: d, title: m.title || d, order: m.order || 0 };
    });
    stages.sort((a, b) => a.order - b.order || a.name.localeCompare(b.name));
    $('stage').innerHTML = '';
    for (const s of stages) $('stage').add(new Option(`${s.order}. ${s.title}`, s.name));
    const wanted = new URLSearchParams(location.search).get('stage');
    if (wanted && stages.some((s) => s.name === wanted)) $('stage').value = wanted;
  },

  // Opens a stage's files and handout; `show` also puts its first grading
  // scene in the view.
  openStage(stage, show = true) {
    this.stage = stage;
    const files = Module.FS.readdir(this.stageDir()).filter((f) => STAGE_FILE.test(f)).sort();
    $('files').innerHTML = '';
    for (const f of files) {
      const b = document.createElement('button');
      b.textContent = f;
      b.onclick = () => this.openFile(f);
      $('files').appendChild(b);
    }
    this.openFile(files[0] || '');
    this.showHandout();
    $('check-summary').textContent = '';
    $('check-table').innerHTML = '';
    if (!show) return;
    const error = Module.ccall('vx_show_stage', 'string', ['string', 'number'], [stage, this.student]);
    this.setStatus(error || `showing ${stage}'s first grading scene, drawn by ${this.student ? 'your files' : 'the reference'}`, !!error);
  },

  path() { return this.stageDir() + '/' + this.file; },

  openFile(name) {
    this.file = name;
    this.errorLines = new Set();
    for (const b of $('files').children) b.classList.toggle('on', b.textContent === name);
    const p = this.path();
    $('editor').value = name ? (this.edits[p] ?? this.read(p)) : '';
    this.numberLines();
  },

  // Line numbers, with the lines the compiler complained about marked.
  numberLines() {
    const n = $('editor').value.split('\n').length;
    $('gutter').innerHTML = Array.from({ length: n }, (_, i) =>
      (this.errorLines.has(i + 1) ? `<span class="bad-line">${i + 1}</span>` : `${i + 1}`)).join('\n');
  },

  editorKey(e) {
    if (e.key !== 'Tab') return;
    e.preventDefault();
    document.execCommand('insertText', false, '    ');
  },

  // Writes the file where the viewer reads it, has the viewer compile it,
  // and shows what the compiler said once a frame has been drawn with it.
  compile() {
    if (!this.file) return;
    const p = this.path();
    Module.FS.writeFile(p, $('editor').value);
    delete this.edits[p];
    if (/\.(cpp|h)$/.test(this.file)) {
      this.showErrors(['C++ stages are compiled by the native build only; this page draws with the version compiled into it.']);
      return;
    }
    Module.ccall('vx_reload', null, [], []);
    this.afterFrames(2, () => {
      const error = Module.ccall('vx_error', 'string', [], []);
      this.showErrors(error ? error.split('\n') : []);
    });
  },

  afterFrames(count, then) {
    const target = (Module.voxlabFrames || 0) + count;
    const wait = () => ((Module.voxlabFrames || 0) >= target ? then() : requestAnimationFrame(wait));
    requestAnimationFrame(wait);
  },

  // The line of the open file a compiler's line names, or 0.
  lineOfOpenFile(message) {
    const m = message.match(/([\w./-]+):(\d+)/);
    return m && m[1].endsWith(this.stage + '/' + this.file) ? Number(m[2]) : 0;
  },

  // Compiler lines name files as stage/file:line; a line of the open file
  // selects that line in the editor when clicked.
  showErrors(lines) {
    const list = $('errors');
    list.innerHTML = '';
    this.errorLines = new Set(lines.map((l) => this.lineOfOpenFile(l)).filter((n) => n > 0));
    this.numberLines();
    if (!lines.length) {
      const ok = document.createElement('li');
      ok.className = 'ok';
      ok.textContent = `${this.file}: compiled, the view shows it`;
      list.appendChild(ok);
      this.setStatus('compiled', false);
      return;
    }
    for (const line of lines) {
      const li = document.createElement('li');
      li.textContent = line;
      const n = this.lineOfOpenFile(line);
      if (n) li.onclick = () => this.selectLine(n);
      list.appendChild(li);
    }
    this.setStatus('not compiled: the view keeps the last shader that compiled', true);
  },

  selectLine(n) {
    const editor = $('editor');
    const lines = editor.value.split('\n');
    const start = lines.slice(0, n - 1).reduce((sum, l) => sum + l.length + 1, 0);
    editor.focus();
    editor.setSelectionRange(start, start + (lines[n - 1] || '').length);
    editor.scrollTop = Math.max(0, (n - 5) * parseFloat(getComputedStyle(editor).lineHeight));
  },

  setStatus(text, bad) {
    $('status').textContent = text;
    $('status').classList.toggle('bad', bad);
  },

  async saveToDisk() {
    const text = $('editor').value;
    if (window.showSaveFilePicker) {  // the File System Access API (Chromium)
      try {
        const handle = await window.showSaveFilePicker({ suggestedName: this.file });
        const out = await handle.createWritable();
        await out.write(text);
        await out.close();
        return;
      } catch (e) {
        if (e.name === 'AbortError') return;
      }
    }
    const a = document.createElement('a');
    a.href = URL.createObjectURL(new Blob([text], { type: 'text/plain' }));
    a.download = this.file;
    a.click();
    URL.revokeObjectURL(a.href);
  },

  async openFromDisk(file) {
    if (!file) return;
    $('editor').value = await file.text();
    this.edits[this.path()] = $('editor').value;
    this.numberLines();
    this.setStatus(`${file.name} loaded into ${this.file}: Save and compile to see it`, false);
  },

  showTab(name) {
    for (const b of document.querySelectorAll('#tabs button')) b.classList.toggle('on', b.dataset.tab === name);
    for (const t of document.querySelectorAll('.tab')) t.classList.toggle('on', t.id === name);
  },

  showHandout() {
    const readme = this.stageDir() + '/README.md';
    $('handout').innerHTML = this.exists(readme) ? markdown(this.read(readme)) : '<p>This stage has no handout.</p>';
  },

  selfCheck() {
    $('check-summary').textContent = 'rendering the grading scenes...';
    $('check-table').innerHTML = '';
    setTimeout(() => {  // let the message paint first: the check blocks the page while it renders
      const result = JSON.parse(Module.ccall('vx_self_check', 'string', ['string', 'number'], [this.stage, this.student]));
      this.showCheck(result);
    }, 20);
  },

  showCheck(r) {
    const summary = $('check-summary');
    if (!r.scenes) { summary.textContent = r.message; summary.className = 'error'; return; }
    summary.className = r.status;
    summary.textContent = `${r.stage}: ${r.status}, ${r.score.toFixed(2)} / ${r.max_score} from the scenes` +
      (r.checks_native_only ? ` (${r.checks_native_only} function check(s) run only in voxlab check)` : '');
    const table = $('check-table');
    table.innerHTML = '<tr><th>scene</th><th>verdict</th><th>expected</th><th>yours</th><th>FLIP</th><th>difference</th></tr>';
    for (const s of r.scenes) {
      const row = table.insertRow();
      row.dataset.scene = s.name;
      row.dataset.status = s.status;
      row.insertCell().textContent = s.name.replace(/_/g, '_\u200b');  // long names break after an underscore
      const verdict = row.insertCell();
      verdict.innerHTML = `<b class="${s.status}">${s.status}</b><br>`;
      verdict.append(s.message || '');
      for (const key of ['expected', 'submission', 'flip', 'difference']) {
        const cell = row.insertCell();
        const path = s.images && s.images[key];
        if (!path) continue;
        const img = document.createElement('img');
        img.src = URL.createObjectURL(new Blob([Module.FS.readFile(path)], { type: 'image/png' }));
        img.title = path;
        cell.appendChild(img);
      }
    }
  },
};

// The handouts' Markdown, by markdown-it (web/page: pinned in its lock
// file, copied into the page at build time as markdown-it.min.js): tables,
// lists, code and emphasis as GitHub shows them. Raw HTML stays text. A link
// to another file of the repository has nowhere to go in the page, so it
// keeps only its text; web addresses and anchors stay links.
const handoutMarkdown = window.markdownit ? window.markdownit({ html: false, linkify: false, typographer: false }) : null;

function markdown(text) {
  if (!handoutMarkdown) return `<pre>${text.replace(/&/g, '&amp;').replace(/</g, '&lt;')}</pre>`;
  const holder = document.createElement('div');
  holder.innerHTML = handoutMarkdown.render(text);
  for (const a of holder.querySelectorAll('a[href]'))
    if (!/^(https?:|#)/.test(a.getAttribute('href'))) a.replaceWith(...a.childNodes);
  return holder.innerHTML;
}
