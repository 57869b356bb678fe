// Loads a written viewer folder in real headless Chromium (Debian's
// `chromium`), waits for the first frame, takes screenshots and checks them:
// not blank, the expected number of distinct patch colours on screen, the
// exploded view changes the image, picking names a patch.
//
//   node test/browser.mjs VIEWER_DIR ARTIFACT_DIR --label-colours N --patch-colours M
//                         [--guide-image PATH]
//
// --guide-image PATH also writes the whole page as a person first sees it to
// PATH (the user guide's picture of this result; scripts/guide_images.sh).
//
// Prints 'N passed, N failed' and exits non-zero on any failure.
import { chromium } from 'playwright-core';
import { PNG } from 'pngjs';
import { copyFileSync, mkdtempSync, mkdirSync, rmSync, writeFileSync, existsSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

const argv = process.argv.slice(2);
const opt = (name, def) => {
  const i = argv.indexOf(name);
  return i >= 0 ? argv[i + 1] : def;
};
const viewerDir = resolve(argv[0] || '');
const artifacts = resolve(argv[1] || 'test-artifacts');
const expectLabel = Number(opt('--label-colours', 'NaN'));
const expectPatch = Number(opt('--patch-colours', 'NaN'));
const guideImage = opt('--guide-image', null);
const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';
if (!existsSync(join(viewerDir, 'index.html'))) {
  console.error(`usage: node test/browser.mjs VIEWER_DIR ARTIFACT_DIR ...: ${viewerDir}/index.html not found`);
  process.exit(2);
}
mkdirSync(artifacts, { recursive: true });

let passed = 0;
let failed = 0;
function check(name, ok, detail = '') {
  if (ok) passed++;
  else failed++;
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${name}${detail ? `: ${detail}` : ''}`);
}

/** Decoded PNG as {width, height, data (RGBA)}. */
const decode = (buf) => PNG.sync.read(buf);

/** Fraction of pixels that differ from the background (the corner pixel). */
function nonBackground(img) {
  const d = img.data;
  const bg = [d[0], d[1], d[2]];
  let n = 0;
  for (let i = 0; i < d.length; i += 4) {
    if (Math.abs(d[i] - bg[0]) + Math.abs(d[i + 1] - bg[1]) + Math.abs(d[i + 2] - bg[2]) > 12) n++;
  }
  return n / (img.width * img.height);
}

/** How many palette entries show on screen (front or back shade, at least
 * `minPixels` pixels within a small tolerance), and where one of each is. */
function coloursOnScreen(img, palette, minPixels = 150) {
  const d = img.data;
  const found = [];
  for (const entry of palette) {
    let n = 0;
    let at = null;
    for (let i = 0; i < d.length; i += 4) {
      for (const c of [entry.front, entry.back]) {
        if (Math.abs(d[i] - c[0]) <= 3 && Math.abs(d[i + 1] - c[1]) <= 3 && Math.abs(d[i + 2] - c[2]) <= 3) {
          n++;
          if (!at || n === 40) at = [(i / 4) % img.width, Math.floor(i / 4 / img.width)];
        }
      }
    }
    if (n >= minPixels) found.push({ label: entry.label, pixels: n, at });
  }
  return found;
}

/** A pixel well inside something drawn (its 7x7 neighbourhood all off the
 * background), scanning from the image's centre outwards; null if none. */
function insidePixel(img) {
  const d = img.data;
  const bg = [d[0], d[1], d[2]];
  const off = (x, y) => {
    const i = 4 * (y * img.width + x);
    return Math.abs(d[i] - bg[0]) + Math.abs(d[i + 1] - bg[1]) + Math.abs(d[i + 2] - bg[2]) > 12;
  };
  const cx = Math.floor(img.width / 2);
  const cy = Math.floor(img.height / 2);
  for (let r = 0; r < Math.max(cx, cy); r += 2) {
    for (let y = Math.max(3, cy - r); y <= Math.min(img.height - 4, cy + r); y += 2) {
      for (let x = Math.max(3, cx - r); x <= Math.min(img.width - 4, cx + r); x += 2) {
        if (Math.max(Math.abs(x - cx), Math.abs(y - cy)) !== r && r > 0) continue;
        let all = true;
        for (let dy = -3; dy <= 3 && all; dy++) for (let dx = -3; dx <= 3 && all; dx++) all = off(x + dx, y + dy);
        if (all) return [x, y];
      }
    }
  }
  return null;
}

function changedFraction(a, b) {
  let n = 0;
  for (let i = 0; i < a.data.length; i += 4) {
    if (Math.abs(a.data[i] - b.data[i]) + Math.abs(a.data[i + 1] - b.data[i + 1]) + Math.abs(a.data[i + 2] - b.data[i + 2]) > 12) n++;
  }
  return n / (a.width * a.height);
}

const profile = mkdtempSync(join(tmpdir(), 'septa-chromium-'));
const context = await chromium.launchPersistentContext(profile, {
  executablePath,
  headless: true,
  viewport: { width: 1000, height: 700 },
  args: [
    '--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
    '--disable-background-networking', '--disable-component-update', '--disable-sync',
    '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
  ],
});
const errors = [];
const requests = [];
try {
  const page = context.pages()[0] || (await context.newPage());
  page.on('pageerror', (e) => errors.push(String(e)));
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('request', (r) => { if (!r.url().startsWith('file:')) requests.push(r.url()); });
  const url = pathToFileURL(join(viewerDir, 'index.html')).href;
  const frames = () => page.evaluate(() => window.__septaFrames || 0);
  // Runs a UI action and waits until the viewer has drawn a frame after it.
  const act = async (action) => {
    const f = await frames();
    await action();
    await page.waitForFunction((n) => (window.__septaFrames || 0) > n, f, { timeout: 20000 });
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  };
  const shot = async (name) => {
    const buf = await page.locator('#view').screenshot();
    writeFileSync(join(artifacts, name), buf);
    return decode(buf);
  };

  // 1. Lit view as a person sees it.
  await page.goto(url);
  await page.waitForFunction(() => window.__septaReady === true, null, { timeout: 30000 });
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  await page.screenshot({ path: join(artifacts, 'viewer-page.png') });
  if (guideImage) {
    mkdirSync(dirname(resolve(guideImage)), { recursive: true });
    copyFileSync(join(artifacts, 'viewer-page.png'), resolve(guideImage));
  }
  const lit = await shot('viewer-lit.png');
  check('first frame is not blank', nonBackground(lit) > 0.02, `${(100 * nonBackground(lit)).toFixed(1)}% non-background`);

  // 2. Unlit (flat) view: colours on screen equal the palette exactly.
  await page.goto(`${url}?flat=1`);
  await page.waitForFunction(() => window.__septaReady === true, null, { timeout: 30000 });
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  const byLabel = await shot('viewer-flat-by-label.png');
  const labelPalette = await page.evaluate(() => window.__septa.palette());
  const labelFound = coloursOnScreen(byLabel, labelPalette);
  // Without an expected count (a real result, not the hand-made fixture),
  // at least one palette colour must show.
  const want = (n, found) => (Number.isNaN(n) ? found > 0 : found === n);
  check('distinct label colours on screen', want(expectLabel, labelFound.length),
    `${labelFound.length} of ${labelPalette.length} (expected ${expectLabel}): ${labelFound.map((f) => `${f.label}=${f.pixels}px`).join(' ')}`);

  await act(() => page.selectOption('#color-by', 'patch'));
  const byPatch = await shot('viewer-flat-by-patch.png');
  const patchPalette = await page.evaluate(() => window.__septa.palette());
  const patchFound = coloursOnScreen(byPatch, patchPalette);
  check('distinct patch colours on screen', want(expectPatch, patchFound.length),
    `${patchFound.length} of ${patchPalette.length} (expected ${expectPatch})`);

  // 3. Picking: click on a pixel of the first patch colour found.
  if (patchFound.length) {
    const box = await page.locator('#view').boundingBox();
    const [x, y] = patchFound[0].at;
    await page.mouse.click(box.x + x, box.y + y);
    const info = await page.locator('#info').textContent();
    check('picking names a patch and its cells', /^patch \d+ label/.test(info) && /cell/.test(info), JSON.stringify(info));
    // The picked cell is a real cell, and its label agrees with the face's
    // label on the side clicked (MI: the material; regions: the region).
    const p = await page.evaluate(([cx, cy]) => {
      const q = window.__septa.pick(cx, cy);
      return q && { ...q, mode: window.__septa.net.mode, ncells: window.__septa.net.cells.length };
    }, [box.x + x, box.y + y]);
    const inRange = p && p.faceCells.every((c) => c >= -1 && c < p.ncells);
    check('picked face names real cells', inRange, JSON.stringify(p && p.faceCells));
    if (p && (p.mode === 'regions' || p.mode === 'mi') && p.cell >= 0 && p.side) {
      const want = p.patchLabel[p.side === '+' ? 0 : 1];
      check('picked cell has the label of the side clicked', Array.isArray(p.cellLabel) && p.cellLabel[0] === want,
        `side ${p.side}, face label ${JSON.stringify(p.patchLabel)}, cell ${p.cell} label ${JSON.stringify(p.cellLabel)}`);
    }
    // Names: a named region (label, material) is named in the pick text.
    const named = await page.evaluate((q) => {
      const names = window.__septa.net.names;
      const r = q && Array.isArray(q.cellLabel) ? q.cellLabel[0] : undefined;
      return names && names.regions && r !== undefined ? names.regions[String(r)] ?? null : null;
    }, p);
    if (named) check('pick text names the region', info.includes(`(${named})`), JSON.stringify(info));
  } else {
    check('picking names a patch and its cells', false, 'no patch colour found to click');
  }

  // 4. Exploded view through the real slider.
  await act(() => page.locator('#explode').fill('0.6'));
  const exploded = await shot('viewer-flat-exploded.png');
  const change = changedFraction(byPatch, exploded);
  check('exploded view changes the image', change > 0.02, `${(100 * change).toFixed(1)}% of pixels changed`);
  check('exploded view is not blank', nonBackground(exploded) > 0.02);
  // Exploding moves the cells apart; it does not make them vanish.
  check('exploded view keeps the cells', nonBackground(exploded) > 0.4 * nonBackground(byPatch),
    `${(100 * nonBackground(exploded)).toFixed(1)}% vs ${(100 * nonBackground(byPatch)).toFixed(1)}% non-background`);
  // Picking in the exploded view names a cell the picked face bounds.
  const at = insidePixel(exploded);
  if (at) {
    const box = await page.locator('#view').boundingBox();
    const [x, y] = at;
    const q = await page.evaluate(([cx, cy]) => {
      const r = window.__septa.pick(cx, cy);
      return r && { cell: r.cell, faceCells: r.faceCells, ncells: window.__septa.net.cells.length };
    }, [box.x + x, box.y + y]);
    check('exploded pick names a cell of the picked face', q && q.cell >= 0 && q.cell < q.ncells && q.faceCells.includes(q.cell),
      JSON.stringify(q));
  } else {
    check('exploded pick names a cell of the picked face', false, 'nothing drawn to click');
  }

  // 5. Lit exploded view and clipping, for people to look at.
  await page.goto(url);
  await page.waitForFunction(() => window.__septaReady === true, null, { timeout: 30000 });
  await act(() => page.locator('#explode').fill('0.5'));
  await shot('viewer-lit-exploded.png');
  await act(() => page.locator('#explode').fill('0'));
  await act(() => page.locator('#clip-on').check());
  const clipped = await shot('viewer-lit-clipped.png');
  check('clipping plane changes the image', changedFraction(lit, clipped) > 0.01);

  check('no page errors', errors.length === 0, errors.join(' | '));
  check('no network requests', requests.length === 0, requests.join(' '));
} finally {
  await context.close();
  rmSync(profile, { recursive: true, force: true });
}
console.log(`screenshots in ${artifacts}`);
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
