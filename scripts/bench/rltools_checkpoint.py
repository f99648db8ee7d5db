"""RLtools' actor code export, the `checkpoint.h` its zoo writes (rl/loop/steps/checkpoint,
`save_code`): every parameter as `constexpr float memory[] = {...}` of hex floats, in the
actor's layer order, then the namespaces `rl_tools::checkpoint::example::input` and `::output`
with an example batch and the actor's output for it. Shared by rltools_cross_eval.py (Pendulum)
and rltools_cross_eval_ant.py (Ant-v4)."""
import re
from dataclasses import dataclass
from typing import Optional, Tuple

import numpy as np


def memory_arrays(text):
    """Every `constexpr float|double memory[] = {...}` array in `text`, in order, as float32."""
    return [np.array([float.fromhex(v.strip().rstrip("fF")) for v in body.split(",")],
                     dtype=np.float32)
            for body in re.findall(r"constexpr (?:float|double) memory\[\] = \{([^}]*)\}", text)]


def fast_tanh(x):
    """RLtools' FAST_TANH (include/rl_tools/math/operations_generic.h, `fast_tanh`)."""
    x = np.clip(x, -3.0, 3.0)
    x2 = x * x
    return x * (27 + x2) / (27 + 9 * x2)


@dataclass
class ActorExport:
    text: str                                       # the actor's part of the file
    standardize: Optional[Tuple[np.ndarray, np.ndarray]]  # (mean, precision) of its first layer
    arrays: list                                    # the parameters after the standardize layer
    example_in: np.ndarray                          # flat, as stored
    example_out: np.ndarray


def read_actor_export(path):
    """The parts of a checkpoint.h; SystemExit with the reason when it is not one."""
    with open(path) as f:
        text = f.read()
    parts = text.split("namespace rl_tools::checkpoint::example")
    if len(parts) != 3:
        raise SystemExit(f"{path}: not an RLtools checkpoint.h (no example input/output)")
    examples = [memory_arrays(part) for part in parts[1:]]
    if not all(examples):
        raise SystemExit(f"{path}: not an RLtools checkpoint.h (empty example input/output)")
    arrays = memory_arrays(parts[0])
    standardize = None
    if "layers::standardize::" in parts[0]:
        standardize, arrays = (arrays[0], arrays[1]), arrays[2:]
    return ActorExport(parts[0], standardize, arrays, examples[0][0], examples[1][0])
