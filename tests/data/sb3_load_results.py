"""Reads a run directory's monitor files the way SB3's
stable_baselines3.common.monitor.load_results does (glob *monitor.csv, a JSON header line
after '#', then pandas.read_csv; t shifted by t_start), and prints episodes and mean return.
Exit code 1 if the files are not in that format."""
import glob
import json
import os
import sys

import pandas

frames, headers = [], []
for name in sorted(glob.glob(os.path.join(sys.argv[1], "*monitor.csv"))):
    with open(name) as f:
        first = f.readline()
        assert first[0] == "#", name
        header = json.loads(first[1:])
        frame = pandas.read_csv(f, index_col=None)
        headers.append(header)
        frame["t"] += header["t_start"]
    frames.append(frame)
if not frames:
    sys.exit("no monitor files")
df = pandas.concat(frames)
df.sort_values("t", inplace=True)
df.reset_index(inplace=True)
df["t"] -= min(h["t_start"] for h in headers)
assert list(df.columns[1:4]) == ["r", "l", "t"], df.columns
assert headers[0]["env_id"], headers[0]
print(f"episodes={len(df)} mean_r={df['r'].mean():.3f} env_id={headers[0]['env_id']}")
