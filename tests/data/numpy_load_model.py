"""Opens an rlrun model file with numpy.load (a zip of .npy members) and prints each array's
name, dtype and shape. Non-.npy members (config.yaml, meta.json) come back as raw bytes, as
numpy does for any npz member that is not an array."""
import sys

import numpy

with numpy.load(sys.argv[1]) as archive:
    for name in sorted(archive.files):
        array = archive[name]
        if isinstance(array, bytes):
            print(f"{name} bytes {len(array)}")
        else:
            print(f"{name} {array.dtype} {array.shape}")
