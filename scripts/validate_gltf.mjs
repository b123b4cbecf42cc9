// Validates glTF 2.0 files (.glb or .gltf) with the Khronos glTF Validator (npm gltf-validator):
// prints a summary and every issue, and exits 1 when any file has errors (warnings, infos and
// hints are printed but pass). The package is found from the current folder or NODE_PATH:
//
//   npm install --prefix /work/tools/gltf-validator gltf-validator
//   NODE_PATH=/work/tools/gltf-validator/node_modules node scripts/validate_gltf.mjs scenes/blender_room.glb
import { readFile } from "node:fs/promises";
import { createRequire } from "node:module";
import path from "node:path";

const severities = ["error", "warning", "info", "hint"];

const require = createRequire(path.join(process.cwd(), "validate_gltf.mjs"));
const validator = require("gltf-validator");

async function validate(file) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,
    writeTimestamp: false,
    // External buffers of a .gltf are read from beside it.
    externalResourceFunction: (uri) =>
      readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((d) => new Uint8Array(d)),
  });
  const { issues, info } = report;
  console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
              `${issues.numInfos} infos, ${issues.numHints} hints (glTF Validator ${report.validatorVersion})`);
  if (info) {
    console.log(`  generator: ${info.generator}; extensions used: ${(info.extensionsUsed || []).join(", ") || "none"}`);
    console.log(`  ${info.totalTriangleCount} triangles, ${info.totalVertexCount} vertices, ` +
                `${info.drawCallCount} draw calls, ${info.animationCount} animations, ${info.materialCount} materials`);
  }
  for (const m of issues.messages)
    console.log(`  ${severities[m.severity]} ${m.code} at ${m.pointer ?? m.offset ?? "?"}: ${m.message}`);
  return issues.numErrors;
}

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error("usage: node scripts/validate_gltf.mjs FILE.glb|FILE.gltf...");
  process.exit(2);
}
let errors = 0;
for (const file of files) errors += await validate(file);
process.exit(errors > 0 ? 1 : 0);
