// Builds the studio's page into epuckc/studio/static (docs/studio.md):
// `npm ci && node build.mjs` here, or `node build.mjs --outdir DIR`.
// The output is deterministic: the same sources and the locked packages
// give the same bytes (tests/studio/test_bundle.py rebuilds and compares).
import * as esbuild from "esbuild";
import { copyFileSync, mkdirSync } from "node:fs";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const flag = process.argv.indexOf("--outdir");
const outdir = flag > 0 ? resolve(process.argv[flag + 1])
  : join(here, "..", "epuckc", "studio", "static");
mkdirSync(outdir, { recursive: true });
await esbuild.build({
  entryPoints: [join(here, "src", "main.ts")],
  bundle: true,
  minify: true,
  format: "iife",
  target: "es2020",
  charset: "utf8",
  legalComments: "eof",
  sourcemap: false,
  outfile: join(outdir, "studio.js"),
  absWorkingDir: here,
  logLevel: "warning",
});
for (const name of ["index.html", "studio.css"])
  copyFileSync(join(here, "src", name), join(outdir, name));
