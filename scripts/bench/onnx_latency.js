// Single-observation latency of ONNX Runtime for Node.js on an exported policy:
//   NODE_PATH=build/onnxruntime/node_modules node scripts/bench/onnx_latency.js policy.onnx N OBS_DIM
// Times N session.run calls (after 1000 warm-up calls) with one observation each and prints
// the median and 99th percentile in microseconds (scripts/bench/deploy.sh).
'use strict';
const ort = require('onnxruntime-node');

async function main() {
  const [model, n] = [process.argv[2], parseInt(process.argv[3] || '10000', 10)];
  const session = await ort.InferenceSession.create(model, {
    executionProviders: ['cpu'], intraOpNumThreads: 1, interOpNumThreads: 1,
  });
  const name = session.inputNames[0];
  const width = parseInt(process.argv[4], 10);  // floats per observation
  const obs = new Float32Array(width);
  const micros = [];
  for (let k = 0; k < n + 1000; ++k) {
    for (let i = 0; i < width; ++i) obs[i] = 0.1 * Math.sin(k + i);
    const feeds = { [name]: new ort.Tensor('float32', obs, [1, width]) };
    const start = process.hrtime.bigint();
    await session.run(feeds);
    const end = process.hrtime.bigint();
    if (k >= 1000) micros.push(Number(end - start) / 1000);
  }
  micros.sort((a, b) => a - b);
  console.log(`onnxruntime-node ${ort.env.versions.common}: p50 ${micros[Math.floor(n / 2)].toFixed(2)} us, ` +
              `p99 ${micros[Math.floor(n * 99 / 100)].toFixed(2)} us over ${n} calls`);
}

main().catch((e) => { console.error(String(e)); process.exit(1); });
