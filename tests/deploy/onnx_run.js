// Runs an ONNX model with ONNX Runtime for Node.js (the npm package onnxruntime-node, which
// scripts/setup.sh installs into build/onnxruntime for the tests):
//   node onnx_run.js MODEL.onnx INPUT.json OUTPUT.json
// INPUT.json: {"batch": N, "inputs": {"<name>": [N * width floats, row-major], ...}}
// OUTPUT.json: {"<output name>": {"dims": [...], "data": [...]}, ..., "metadata": {...}}
// A recurrent model (inputs state_in, outputs state_out) with "starts": [N flags] and
// "state_width" in INPUT.json runs one step at a time: state_in starts at zeros, is zeroed where
// a flag is 1, and is the previous step's state_out otherwise; each output is its N steps' rows.
'use strict';
const fs = require('fs');
const ort = require('onnxruntime-node');

async function main() {
  const [modelPath, inputPath, outputPath] = process.argv.slice(2);
  const request = JSON.parse(fs.readFileSync(inputPath, 'utf8'));
  const session = await ort.InferenceSession.create(modelPath, { executionProviders: ['cpu'] });
  if (request.starts) return runSequence(session, request, outputPath);
  const feeds = {};
  for (const name of session.inputNames) {
    const data = Float32Array.from(request.inputs[name]);
    feeds[name] = new ort.Tensor('float32', data, [request.batch, data.length / request.batch]);
  }
  const results = await session.run(feeds);
  const out = {};
  for (const name of session.outputNames)
    out[name] = { dims: results[name].dims, data: Array.from(results[name].data) };
  out.ort_version = ort.env.versions.common;
  fs.writeFileSync(outputPath, JSON.stringify(out));
}

async function runSequence(session, request, outputPath) {
  const n = request.starts.length;
  const width = request.state_width;
  let state = new Float32Array(width);
  const rows = {};
  for (const name of session.outputNames) rows[name] = [];
  for (let t = 0; t < n; ++t) {
    if (request.starts[t]) state = new Float32Array(width);
    const feeds = {};
    for (const name of session.inputNames) {
      if (name === 'state_in') {
        feeds[name] = new ort.Tensor('float32', state, [1, width]);
        continue;
      }
      const all = request.inputs[name];
      const w = all.length / n;
      feeds[name] = new ort.Tensor('float32', Float32Array.from(all.slice(t * w, (t + 1) * w)), [1, w]);
    }
    const results = await session.run(feeds);
    state = Float32Array.from(results.state_out.data);
    for (const name of session.outputNames) rows[name].push(...results[name].data);
  }
  const out = {};
  for (const name of session.outputNames)
    out[name] = { dims: [n, rows[name].length / n], data: rows[name] };
  out.ort_version = ort.env.versions.common;
  fs.writeFileSync(outputPath, JSON.stringify(out));
}

main().catch((e) => {
  console.error(String(e && e.stack ? e.stack : e));
  process.exit(1);
});
