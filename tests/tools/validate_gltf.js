#!/usr/bin/env node
// Validates a glTF 2.0 file (.glb or .gltf) with the Khronos validator (npm package gltf-validator,
// installed by scripts/setup.sh into tests/tools/node_modules).
//   node tests/tools/validate_gltf.js FILE
// Prints numErrors, numWarnings, numInfos, numHints and every message; exits 0 when there are no
// errors, 1 when there are, 2 when the file cannot be read or the validator is missing.
'use strict';

const fs = require('fs');
const path = require('path');

const SEVERITY = ['error', 'warning', 'info', 'hint'];

function fail(message) {
  console.error('validate_gltf: ' + message);
  process.exit(2);
}

function loadValidator() {
  try {
    return require('gltf-validator');
  } catch (e) {
    fail('the npm package gltf-validator is not installed (run scripts/setup.sh, or ' +
         '`npm install --prefix tests/tools`): ' + e.message);
  }
  return null;
}

async function main() {
  const args = process.argv.slice(2);
  if (args.length !== 1 || args[0] === '-h' || args[0] === '--help') {
    console.error('usage: node tests/tools/validate_gltf.js FILE');
    process.exit(2);
  }
  const file = path.resolve(args[0]);
  let bytes;
  try {
    bytes = new Uint8Array(fs.readFileSync(file));
  } catch (e) {
    fail('cannot read ' + file + ': ' + e.message);
  }
  const validator = loadValidator();
  const options = {
    uri: path.basename(file),
    maxIssues: 0,  // report every issue
    externalResourceFunction: (uri) => new Promise((resolve, reject) => {
      fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) => {
        if (err) reject(err.toString());
        else resolve(new Uint8Array(data));
      });
    }),
  };
  let report;
  try {
    report = await validator.validateBytes(bytes, options);
  } catch (e) {
    fail('the validator could not read ' + file + ': ' + e);
  }
  const issues = report.issues;
  console.log('file: ' + file);
  console.log('validator: ' + report.validatorVersion);
  console.log('numErrors: ' + issues.numErrors);
  console.log('numWarnings: ' + issues.numWarnings);
  console.log('numInfos: ' + issues.numInfos);
  console.log('numHints: ' + issues.numHints);
  for (const m of issues.messages) {
    const where = m.pointer !== undefined ? ' at ' + m.pointer : (m.offset !== undefined ? ' at byte ' + m.offset : '');
    console.log((SEVERITY[m.severity] || 'severity ' + m.severity) + ' ' + m.code + where + ': ' + m.message);
  }
  process.exit(issues.numErrors > 0 ? 1 : 0);
}

main();
