// Runs the Khronos glTF-Validator (npm package gltf-validator) over glTF files and prints one
// JSON line per file: {"file": ..., "errors": N, "issues": [{"code", "pointer", "message"}]}
// listing the issues of severity Error only. External resources (buffers, images) resolve
// against the file's directory, as conegraph resolves them.
//
// usage: node gltf_validate.js VALIDATOR_DIR FILE...   (VALIDATOR_DIR holds node_modules/)
'use strict';
const fs = require('fs');
const path = require('path');

const [validatorDir, ...files] = process.argv.slice(2);
const validator = require(path.join(path.resolve(validatorDir), 'node_modules', 'gltf-validator'));

async function validate(file) {
  const bytes = fs.readFileSync(file);
  const report = await validator.validateBytes(new Uint8Array(bytes), {
    uri: path.basename(file),
    maxIssues: 0, // no limit
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        const where = path.resolve(path.dirname(file), decodeURIComponent(uri));
        fs.readFile(where, (err, data) => (err ? reject(err.toString()) : resolve(new Uint8Array(data))));
      }),
  });
  const issues = report.issues.messages
    .filter((m) => m.severity === 0)
    .map((m) => ({ code: m.code, pointer: m.pointer || '', message: m.message }));
  return { file, errors: report.issues.numErrors, issues };
}

(async () => {
  for (const file of files) {
    try {
      console.log(JSON.stringify(await validate(file)));
    } catch (e) {
      // The validator throws only on inputs it cannot read at all; that is an error too.
      console.log(JSON.stringify({ file, errors: 1, issues: [{ code: 'VALIDATOR_EXCEPTION', pointer: '', message: String(e) }] }));
    }
  }
})();
