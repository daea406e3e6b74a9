// Validate glTF files with the Khronos glTF-Validator (npm gltf-validator).
//   node validate.mjs FILE...                    every file must have no error (warnings allowed)
//   node validate.mjs --expect-errors FILE...    every file must have at least one error
// Prints one line per file: its error and warning counts and the first error's code and pointer.
import { readFile } from "node:fs/promises";
import path from "node:path";
import validator from "gltf-validator";

const args = process.argv.slice(2);
const expectErrors = args[0] === "--expect-errors";
const files = expectErrors ? args.slice(1) : args;
if (files.length === 0) {
  console.error("usage: node validate.mjs [--expect-errors] FILE...");
  process.exit(2);
}
let failed = 0;
for (const file of files) {
  let report;
  try {
    const bytes = new Uint8Array(await readFile(file));
    report = await validator.validateBytes(bytes, {
      uri: path.basename(file),
      externalResourceFunction: (uri) =>
        readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((b) => new Uint8Array(b)),
    });
  } catch (e) {
    report = { issues: { numErrors: 1, numWarnings: 0, messages: [{ code: "EXCEPTION", pointer: String(e) }] } };
  }
  const { numErrors, numWarnings, messages } = report.issues;
  const first = messages.find((m) => m.severity === 0) || messages[0];
  const ok = expectErrors ? numErrors > 0 : numErrors === 0;
  console.log(`${ok ? "ok  " : "FAIL"} ${path.basename(file)}: ${numErrors} errors, ${numWarnings} warnings` +
              (first ? ` (first: ${first.code} ${first.pointer || ""})` : ""));
  if (!ok) failed++;
}
console.log(`${files.length - failed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
