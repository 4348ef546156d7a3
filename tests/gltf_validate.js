// Runs the Khronos glTF-Validator on one file and prints a one-line JSON summary:
//   {"numErrors": N, "numWarnings": M, "errors": [first error messages], "warnings": [the distinct warning codes]}
// Usage: NODE_PATH=<checkout>/.cache/node/node_modules node tests/gltf_validate.js FILE.glb|FILE.gltf
const fs = require('fs');
const path = require('path');
const validator = require('gltf-validator');

const file = process.argv[2];
const dir = path.dirname(file);
const bytes = new Uint8Array(fs.readFileSync(file));
validator
  .validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,  // unlimited: a source with many errors still shows its warnings
    externalResourceFunction: (uri) =>
      new Promise((resolve, reject) => {
        try {
          resolve(new Uint8Array(fs.readFileSync(path.join(dir, decodeURIComponent(uri)))));
        } catch (e) {
          reject(e.toString());
        }
      }),
  })
  .then((report) => {
    const errors = report.issues.messages.filter((m) => m.severity === 0).map((m) => m.code + ' ' + m.pointer + ': ' + m.message);
    const warnings = [...new Set(report.issues.messages.filter((m) => m.severity === 1).map((m) => m.code))];
    console.log(JSON.stringify({ numErrors: report.issues.numErrors, numWarnings: report.issues.numWarnings, errors: errors.slice(0, 10), warnings: warnings }));
  })
  .catch((e) => {
    console.log(JSON.stringify({ numErrors: -1, errors: [String(e)] }));
    process.exit(2);
  });
