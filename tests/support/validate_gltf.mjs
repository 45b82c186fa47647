// Runs the Khronos glTF-Validator (npm package gltf-validator) on one file and prints a one-line JSON
// summary: {"errors": n, "warnings": n, "infos": n, "hints": n, "issues": [first errors and warnings]}.
// Usage: node validate_gltf.mjs PATH/TO/node_modules/gltf-validator FILE.glb
// Exit code 0 when the validator ran (whatever it found), 3 when it could not run.
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { basename, resolve } from 'node:path';

const [, , validatorDir, file] = process.argv;
if (!validatorDir || !file) {
  console.error('usage: node validate_gltf.mjs VALIDATOR_DIR FILE.glb');
  process.exit(3);
}
try {
  const validator = createRequire(import.meta.url)(resolve(validatorDir));
  const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), {
    uri: basename(file),
    maxIssues: 1000,
  });
  const i = report.issues;
  console.log(JSON.stringify({
    errors: i.numErrors,
    warnings: i.numWarnings,
    infos: i.numInfos,
    hints: i.numHints,
    issues: i.messages.filter((m) => m.severity <= 1).slice(0, 20)
      .map((m) => `${m.severity === 0 ? 'ERROR' : 'WARNING'} ${m.code} ${m.pointer ?? ''}: ${m.message}`),
  }));
} catch (e) {
  console.error(`validate_gltf: ${e}`);
  process.exit(3);
}
