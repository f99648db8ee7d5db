// Runs an ONNX model with ONNX Runtime for Node.js (the npm package onnxruntime-node, which
// scripts/setup.sh installs into build/onnxruntime for the tests):
//   node onnx_run.js MODEL.onnx INPUT.json OUTPUT.json
// INPUT.json: {"batch": N, "inputs": {"<name>": [N * width floats, row-major], ...}}
// OUTPUT.json: {"<output name>": {"dims": [...], "data": [...]}, ..., "metadata": {...}}
'use strict';
const fs = require('fs');
const ort = require('onnxruntime-node');

async function main() {
  const [modelPath, inputPath, outputPath] = process.argv.slice(2);
  const request = JSON.parse(fs.readFileSync(inputPath, 'utf8'));
  const session = await ort.InferenceSession.create(modelPath, { executionProviders: ['cpu'] });
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

main().catch((e) => {
  console.error(String(e && e.stack ? e.stack : e));
  process.exit(1);
});
