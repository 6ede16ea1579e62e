// voxlab workbench in a real browser: Debian's chromium, headless, WebGL 2
// on SwiftShader, driven by playwright-core (which downloads no browser).
//
//   node web/test/browser_test.mjs SITE_DIR OUT_DIR [NATIVE_REFERENCE NATIVE_STUB]
//
// Serves SITE_DIR (build-web/site) from a local port and checks, with a
// screenshot of each step in OUT_DIR:
//   1. the first frame comes, and the canvas shows a volume: a good share of
//      its pixels differ from the background (decoded from the screenshot
//      itself, not from anything the page reports);
//   2. a syntax error typed into a stage file shows the compiler's message
//      at that file and line, and the view keeps drawing;
//   3. an edit that compiles changes the image;
//   4. the self-check of the reference passes every scene, and of the
//      starter's stub fails every scene;
//   5. a NRRD file dropped on the image is loaded, and 6. so is a bundled
//      dataset chosen in the page's list;
// and that the MIP handout's table is rendered as a table (markdown-it),
// that "your files" are the pristine starter code, that the self-check's
// table fits the bench at 1400 px, and that no resource the page asks for
// is missing (404).
// With the report.json of the native `voxlab check --stage mip` of the
// reference and of the stub (tools/setup_web.sh --test makes them), each
// scene's verdict in the page must be the native one: the same status, and
// for the stub the same verdict line (the same metrics to the digits shown).
// OUT_DIR/results.json holds the figures (first-frame time, self-check
// scores and metrics). Exit status 0 when every check passed.
import { createServer } from 'node:http';
import { readFile, writeFile, mkdir } from 'node:fs/promises';
import { extname, join, normalize } from 'node:path';
import { inflateSync } from 'node:zlib';
import { chromium } from 'playwright-core';

const [site, out, nativeReference, nativeStub] = process.argv.slice(2);
if (!site || !out) {
  console.error('usage: node browser_test.mjs SITE_DIR OUT_DIR');
  process.exit(2);
}
await mkdir(out, { recursive: true });

const types = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.wasm': 'application/wasm' };
const server = createServer(async (req, res) => {
  const path = normalize(decodeURIComponent(new URL(req.url, 'http://x').pathname)).replace(/^(\.\.[/\\])+/, '');
  try {
    const body = await readFile(join(site, path === '/' ? 'index.html' : path));
    res.writeHead(200, { 'Content-Type': types[extname(path)] || 'application/octet-stream' });
    res.end(body);
  } catch {
    res.writeHead(404).end();
  }
});
await new Promise((ok) => server.listen(0, '127.0.0.1', ok));
const base = `http://127.0.0.1:${server.address().port}/`;

const failures = [];
const results = {};
const check = (ok, what) => { console.log(`${ok ? 'ok  ' : 'FAIL'} ${what}`); if (!ok) failures.push(what); };

// A PNG (8-bit RGB or RGBA, not interlaced, as Chromium writes them) as
// {width, height, rgba}.
function decodePng(buf) {
  let pos = 8, width = 0, height = 0, channels = 4;
  const idat = [];
  while (pos < buf.length) {
    const len = buf.readUInt32BE(pos), type = buf.toString('latin1', pos + 4, pos + 8), data = buf.subarray(pos + 8, pos + 8 + len);
    if (type === 'IHDR') { width = data.readUInt32BE(0); height = data.readUInt32BE(4); channels = data[9] === 6 ? 4 : 3; }
    if (type === 'IDAT') idat.push(data);
    pos += 12 + len;
  }
  const raw = inflateSync(Buffer.concat(idat)), stride = width * channels, px = Buffer.alloc(height * stride);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)], line = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let x = 0; x < stride; ++x) {
      const a = x >= channels ? px[y * stride + x - channels] : 0, b = y ? px[(y - 1) * stride + x] : 0;
      const c = x >= channels && y ? px[(y - 1) * stride + x - channels] : 0;
      const p = a + b - c, pa = Math.abs(p - a), pb = Math.abs(p - b), pc = Math.abs(p - c);
      const pred = [0, a, b, (a + b) >> 1, pa <= pb && pa <= pc ? a : pb <= pc ? b : c][filter];
      px[y * stride + x] = (line[x] + pred) & 255;
    }
  }
  return { width, height, channels, px };
}

// The share of pixels of `img` farther than `levels` from `other` (an
// image of the same size) or from the colour `other` (an [r, g, b]).
function shareDifferent(img, other, levels) {
  let n = 0;
  for (let i = 0; i < img.width * img.height; ++i)
    for (let c = 0; c < 3; ++c) {
      const want = Array.isArray(other) ? other[c] : other.px[i * other.channels + c];
      if (Math.abs(img.px[i * img.channels + c] - want) > levels) { ++n; break; }
    }
  return n / (img.width * img.height);
}

const browser = await chromium.launch({
  executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
  args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1400, height: 860 } });
  const errors = [], missing = [];
  page.on('pageerror', (e) => errors.push(e.message));
  page.on('response', (r) => { if (r.status() >= 400) missing.push(`${r.status()} ${r.url()}`); });
  if (process.env.VOXLAB_WEB_TEST_VERBOSE) page.on('console', (m) => console.log('console:', m.text().slice(0, 200)));
  const frames = () => page.evaluate(() => Module.voxlabFrames || 0);
  const waitFrames = async (n) => {
    const target = (await frames()) + n;
    await page.waitForFunction((t) => (Module.voxlabFrames || 0) >= t, target, { timeout: 60000 });
  };
  const canvasShot = async (name) => {
    const png = await page.locator('#canvas').screenshot({ path: join(out, name) });
    return decodePng(png);
  };

  // 1. The first frame of bonsai composite, the frame rate after it, then
  //    mip's first grading scene: a volume on screen.
  const start = Date.now();
  await page.goto(base + 'index.html?stage=mip&scene=datasets/scenes/bonsai_composite.json');
  await page.waitForFunction(() => window.Module && Module.voxlabFrames >= 1, null, { timeout: 120000 });
  results.first_frame_ms = Date.now() - start;
  await page.waitForFunction(() => typeof workbench !== 'undefined' && workbench.ready, null, { timeout: 60000 });
  // (The viewer renders again only when something changes; the render
  //  time is the one its status line shows.)
  await waitFrames(5);
  results.composite_render_ms = await page.evaluate(() => Module.ccall('vx_render_ms', 'number', [], []));
  results.canvas = await page.evaluate(() => [Module.canvas.width, Module.canvas.height]);
  const composite = await canvasShot('0-bonsai-composite.png');
  check(shareDifferent(composite, [composite.px[0], composite.px[1], composite.px[2]], 24) > 0.05,
    `bonsai composite drawn: first frame ${results.first_frame_ms} ms after loading began, then ` +
    `${results.composite_render_ms.toFixed(0)} ms a render at ${results.canvas.join('x')}`);
  await page.selectOption('#tree', '0');  // the reference draws mip's first grading scene
  await waitFrames(3);
  const first = await canvasShot('1-reference-view.png');
  const corner = [first.px[0], first.px[1], first.px[2]];
  results.volume_share = shareDifferent(first, corner, 24);
  check(results.volume_share > 0.05, `the canvas shows a volume (${(100 * results.volume_share).toFixed(1)}% of it differs from the background)`);
  await page.screenshot({ path: join(out, '1-page.png') });

  // The handout is Markdown rendered by markdown-it: the MIP handout's table
  // of the projection stages is a table, not its source text.
  await page.click('#tabs button[data-tab=handout]');
  const table = await page.$$eval('#handout table', (ts) => ts.map((t) => [...t.querySelectorAll('th')].map((h) => h.innerText)));
  const handoutText = await page.innerText('#handout');
  check(table.some((heads) => heads[0] === 'folder' && heads[1] === 'function') && !handoutText.includes('| folder |'),
    `the MIP handout's table is a table (${JSON.stringify(table[0] || [])})`);
  await page.screenshot({ path: join(out, '1-handout.png') });
  await page.click('#tabs button[data-tab=edit]');
  // "your files" are the pristine starter code, whatever the tree's assignments/ held at build time.
  const packed = await page.evaluate(() => Module.FS.readFile('/voxlab/assignments/mip/mip.glsl', { encoding: 'utf8' }));
  check(packed.includes('not_implemented();') && packed.includes('generated from reference/mip/mip.glsl'),
    'the page packs the pristine starter code (mip.glsl holds its stub)');

  // 2. A syntax error in the student's mip.glsl: the message names the file and line.
  await page.selectOption('#tree', '1');
  await waitFrames(2);
  const stub = await canvasShot('2-stub-view.png');
  const original = await page.inputValue('#editor');
  const lines = original.split('\n');
  const badLine = Math.min(lines.length, 12);
  lines.splice(badLine - 1, 0, 'this line is not GLSL');
  await page.fill('#editor', lines.join('\n'));
  await page.click('#compile');
  await page.waitForFunction(() => document.querySelector('#errors li'), null, { timeout: 60000 });
  const errorText = await page.innerText('#errors');
  results.compile_error = errorText.split('\n')[0];
  check(errorText.includes(`mip/mip.glsl:${badLine}`), `the compile error names mip/mip.glsl:${badLine} ("${results.compile_error}")`);
  await waitFrames(2);
  check(true, 'the view keeps drawing after the error');
  await page.screenshot({ path: join(out, '2-compile-error.png') });

  // 3. An edit that compiles changes the image: the stub's mip_ray, replaced
  //    by the reference's file (read from the page's own file system).
  const model = await page.evaluate(() => Module.FS.readFile('/voxlab/reference/mip/mip.glsl', { encoding: 'utf8' }));
  await page.fill('#editor', model);
  await page.click('#compile');
  await page.waitForFunction(() => document.querySelector('#errors li.ok'), null, { timeout: 60000 });
  await waitFrames(3);
  const edited = await canvasShot('3-edited-view.png');
  results.edit_changed_share = shareDifferent(edited, stub, 24);
  check(results.edit_changed_share > 0.02, `the edit changed the image (${(100 * results.edit_changed_share).toFixed(1)}% of pixels)`);
  await page.fill('#editor', original);  // back to the stub for step 4
  await page.click('#compile');
  await page.waitForFunction(() => document.querySelector('#errors li.ok'), null, { timeout: 60000 });

  // 4. The self-check: the reference passes, the starter's stub fails.
  await page.click('#tabs button[data-tab=check]');
  for (const [tree, name, want] of [['0', 'reference', 'passed'], ['1', 'stub', 'failed']]) {
    await page.selectOption('#tree', tree);
    await page.click('#run-check');
    await page.waitForFunction(() => document.querySelectorAll('#check-table tr').length > 1, null, { timeout: 300000 });
    const rows = await page.$$eval('#check-table tr[data-scene]', (trs) => trs.map((r) => ({
      scene: r.dataset.scene, status: r.dataset.status, verdict: r.cells[1].innerText.replace(/\s+/g, ' ') })));
    results[`self_check_${name}`] = { summary: await page.innerText('#check-summary'), scenes: rows };
    check(rows.length > 0 && rows.every((r) => r.status === want), `self-check of the ${name}: every scene ${want} (${rows.length} scenes)`);
    // Every column of the table within the bench (at 1400 px the FLIP and difference images were cut off).
    const edges = await page.evaluate(() => {
      const bench = document.querySelector('#bench').getBoundingClientRect();
      const cells = [...document.querySelectorAll('#check-table tr[data-scene] td:last-child img')];
      return { bench: bench.right, cells: cells.map((c) => c.getBoundingClientRect().right) };
    });
    check(edges.cells.length > 0 && edges.cells.every((r) => r <= edges.bench + 0.5),
      `the self-check's difference column fits the bench (${Math.max(...edges.cells).toFixed(0)} <= ${edges.bench.toFixed(0)} px)`);
    const native = { reference: nativeReference, stub: nativeStub }[name];
    if (native) {
      const report = JSON.parse(await readFile(native, 'utf8'));
      const stage = report.stages.find((s) => s.stage === 'mip');
      const same = rows.every((r) => {
        const n = stage.scenes.find((s) => s.name === r.scene);
        return n && n.status === r.status && (name === 'reference' || r.verdict.endsWith(n.message));
      });
      check(same && rows.length === stage.scenes.filter((s) => !s.hidden).length,
        `the page's verdicts on the ${name} are voxlab check's (${native})`);
    }
    await page.screenshot({ path: join(out, `4-self-check-${name}.png`) });
  }
  // 5. A NRRD file dropped on the image (a copy of the bundled fuel.nrrd,
  //    made into a File as a browser makes one from the desktop) is shown.
  await page.click('#tabs button[data-tab=edit]');
  const before = await canvasShot('5-before-drop.png');
  await page.evaluate(() => {
    const bytes = Module.FS.readFile('/voxlab/datasets/fuel.nrrd');
    const data = new DataTransfer();
    data.items.add(new File([bytes], 'my_fuel.nrrd'));
    for (const type of ['dragenter', 'dragover', 'drop'])
      Module.canvas.dispatchEvent(new DragEvent(type, { dataTransfer: data, bubbles: true, cancelable: true }));
  });
  await page.waitForFunction(() => Module.ccall('vx_dataset', 'string', [], []).endsWith('my_fuel.nrrd'), null, { timeout: 60000 })
    .catch(() => {});
  results.dropped_dataset = await page.evaluate(() => Module.ccall('vx_dataset', 'string', [], []));
  await waitFrames(3);
  const after = await canvasShot('5-after-drop.png');
  results.drop_changed_share = shareDifferent(after, before, 24);
  check(results.dropped_dataset.endsWith('my_fuel.nrrd') && results.drop_changed_share > 0.02,
    `a dropped NRRD is shown (${results.dropped_dataset}, ${(100 * results.drop_changed_share).toFixed(1)}% of pixels changed)`);
  // 6. A bundled dataset chosen in the page's list is opened.
  await page.selectOption('#dataset', '/voxlab/datasets/tooth.nrrd');
  await page.waitForFunction(() => Module.ccall('vx_dataset', 'string', [], []).endsWith('tooth.nrrd'), null, { timeout: 60000 })
    .catch(() => {});
  check((await page.evaluate(() => Module.ccall('vx_dataset', 'string', [], []))).endsWith('tooth.nrrd'),
    'a bundled dataset chosen in the list is opened (tooth.nrrd)');
  check(errors.length === 0, `no uncaught page errors${errors.length ? ': ' + errors[0] : ''}`);
  check(missing.length === 0, `every resource the page asked for was there${missing.length ? ': ' + missing.join(', ') : ''}`);
} catch (e) {
  failures.push(String(e));
  console.log('FAIL', e.message.split('\n')[0]);
} finally {
  await browser.close();
  server.close();
}
await writeFile(join(out, 'results.json'), JSON.stringify(results, null, 2));
console.log(`${failures.length ? 'FAILED' : 'passed'}: screenshots and results.json in ${out}`);
process.exit(failures.length ? 1 : 0);
