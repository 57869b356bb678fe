// Bundles the viewer (three.js included) into dist/: index.html, viewer.js and
// SOURCE_HASH (sha256 of the sources and the bundled package versions, so a
// test without node can tell whether dist/ was built from the current
// sources). dist/ is committed: `cargo build` embeds it into the `septa`
// binary and `pip install .` into the Python package, so neither needs node.
//
//   node build.mjs          rebuild dist/
//   node build.mjs --check  rebuild into a temporary folder, fail if dist/ differs
import { build } from 'esbuild';
import { createHash } from 'node:crypto';
import { mkdtempSync, readdirSync, readFileSync, writeFileSync, copyFileSync, mkdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const src = join(here, 'src');
const dist = join(here, 'dist');

/** Same algorithm as tests/python/test_viewer_bundle.py. */
export function sourceHash() {
  const h = createHash('sha256');
  for (const name of readdirSync(src).sort()) {
    h.update(name + '\0');
    h.update(readFileSync(join(src, name)));
    h.update('\0');
  }
  const lock = JSON.parse(readFileSync(join(here, 'package-lock.json'), 'utf8'));
  for (const pkg of ['three', 'esbuild']) h.update(`${pkg}@${lock.packages[`node_modules/${pkg}`].version}\0`);
  return h.digest('hex');
}

async function buildInto(out) {
  mkdirSync(out, { recursive: true });
  await build({
    entryPoints: [join(src, 'main.js')],
    bundle: true,
    format: 'iife', // a classic script: ES modules are blocked on file:// pages
    minify: true,
    target: ['es2020'],
    legalComments: 'eof',
    outfile: join(out, 'viewer.js'),
    logLevel: 'warning',
  });
  copyFileSync(join(src, 'index.html'), join(out, 'index.html'));
  writeFileSync(join(out, 'SOURCE_HASH'), sourceHash() + '\n');
}

const files = ['index.html', 'viewer.js', 'SOURCE_HASH'];
if (process.argv.includes('--check')) {
  const tmp = mkdtempSync(join(tmpdir(), 'septa-viewer-'));
  await buildInto(tmp);
  const stale = files.filter((f) => {
    try {
      return !readFileSync(join(tmp, f)).equals(readFileSync(join(dist, f)));
    } catch {
      return true;
    }
  });
  rmSync(tmp, { recursive: true, force: true });
  if (stale.length) {
    console.error(`viewer/dist is stale (${stale.join(', ')}): run \`npm run build\` in viewer/ and commit dist/`);
    process.exit(1);
  }
  console.log('viewer/dist matches a fresh build of viewer/src');
} else {
  await buildInto(dist);
  console.log(`built ${dist}: ${files.join(', ')}`);
}
