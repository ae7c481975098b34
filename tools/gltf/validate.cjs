// Validates glTF 2.0 files (.gltf with its external .bin, or .glb) with the Khronos
// glTF-Validator (npm gltf-validator, pinned in package-lock.json). Prints each file's error,
// warning and info counts and every error; exits 1 if any file has an error, 2 on a usage or
// read problem. Usage: node validate.cjs FILE...
'use strict';
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

async function validate(file) {
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 100,
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        fs.readFile(path.join(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
          err ? reject(err.toString()) : resolve(new Uint8Array(data)));
      }),
  });
  const i = report.issues;
  console.log(`${file}: ${i.numErrors} errors, ${i.numWarnings} warnings, ${i.numInfos} infos` +
              ` (glTF-Validator ${report.validatorVersion})`);
  for (const m of i.messages) {
    if (m.severity === 0 || m.severity === 1) {
      console.log(`  ${m.severity === 0 ? 'error' : 'warning'} ${m.code}: ${m.message} ${m.pointer || ''}`);
    }
  }
  return i.numErrors;
}

(async () => {
  const files = process.argv.slice(2);
  if (files.length === 0) {
    console.error('usage: node validate.cjs FILE...');
    process.exit(2);
  }
  let errors = 0;
  for (const f of files) {
    try {
      errors += await validate(f);
    } catch (e) {
      console.error(`${f}: cannot validate: ${e}`);
      process.exit(2);
    }
  }
  process.exit(errors > 0 ? 1 : 0);
})();
