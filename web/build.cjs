// node build.cjs OUT.js: bundles the report viewer (src/main.js with three.js, uPlot and the page's CSS) into one
// minified, ASCII-only script for an inline <script> element. Modules resolve from NODE_PATH (the build tree's
// node_modules, installed by `npm ci`).
'use strict';
const path = require('path');
const esbuild = require('esbuild');

const out = process.argv[2];
if (!out) {
  console.error('usage: node build.cjs OUT.js');
  process.exit(2);
}
esbuild.buildSync({
  entryPoints: [path.join(__dirname, 'src', 'main.js')],
  bundle: true,
  minify: true,
  format: 'iife',
  target: 'es2020',
  charset: 'ascii',
  legalComments: 'eof',
  loader: { '.css': 'text' },
  nodePaths: (process.env.NODE_PATH || '').split(path.delimiter).filter(Boolean),
  outfile: out,
  logLevel: 'warning',
});
