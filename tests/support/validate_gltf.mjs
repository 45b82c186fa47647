// Runs the Khronos glTF-Validator (npm package gltf-validator) on glTF files and prints a one-line JSON
// array with one summary per file, in order:
//   {"file": f, "errors": n, "warnings": n, "infos": n, "hints": n, "issues": [first errors/warnings]}.
// Usage: node validate_gltf.mjs PATH/TO/node_modules/gltf-validator FILE.glb [FILE.glb ...]
// Exit code 0 when the validator ran (whatever it found), 3 when it could not run.
import { readFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { basename, resolve } from 'node:path';

const [, , validatorDir, ...files] = process.argv;
if (!validatorDir || files.length === 0) {
  console.error('usage: node validate_gltf.mjs VALIDATOR_DIR FILE.glb [FILE.glb ...]');
  process.exit(3);
}
try {
  const validator = createRequire(import.meta.url)(resolve(validatorDir));
  const summaries = [];
  for (const file of files) {
    const report = await validator.validateBytes(new Uint8Array(readFileSync(file)), {
      uri: basename(file),
      maxIssues: 1000,
    });
    const i = report.issues;
    summaries.push({
      file,
      errors: i.numErrors,
      warnings: i.numWarnings,
      infos: i.numInfos,
      hints: i.numHints,
      issues: i.messages.filter((m) => m.severity <= 1).slice(0, 20)
        .map((m) => `${m.severity === 0 ? 'ERROR' : 'WARNING'} ${m.code} ${m.pointer ?? ''}: ${m.message}`),
    });
  }
  console.log(JSON.stringify(summaries));
} catch (e) {
  console.error(`validate_gltf: ${e}`);
  process.exit(3);
}
