#!/usr/bin/env python3
"""Checks that src/rlrun's folders include each other only downwards (docs/architecture.md).

Every `#include "rlrun/..."` of a file under src/rlrun/ is read as text (no preprocessor: an
include inside `#if 0` still counts, which only makes the check stricter). Two rules:

1. Layers. Each folder has a floor (LAYERS below, lowest first). A file may include files of
   its own folder and of folders on lower floors; folders on one floor stand side by side and
   include none of each other. include/rlrun/ (the plugin API) is the ground.
2. No circles. Taking a .cpp and its .hpp as one room, no room reaches itself through the
   includes of runtime/ and tune/ (whose rooms sit on several floors of one folder each).

Exit status 1 with one line per break, naming both files; 0 and a summary otherwise.
Usage: check_include_layers.py [SOURCE_DIR]   (default: the checkout holding this script)
       check_include_layers.py --self-test     (the check finds breaks planted in a temp tree)
"""
import collections
import os
import re
import sys

# Lowest first. A path's folder is its longest prefix listed here.
LAYERS = [
    ["core"],
    ["nn"],
    ["env", "render"],
    ["envs/sumo"],            # the SUMO backend: processes, connection, worker, scenario files
    ["envs/traffic_network"], # the traffic-light rules and TrafficNetwork-v0 (envs/traffic on it)
    ["wrappers", "envs", "algos", "deploy"],
    ["runtime/components"],   # the registry: env, wrapper and algorithm entries, plugins
    ["runtime/experiment"],   # the experiment file's sections and the env stack built from them
    ["runtime/io"],           # model files, run directories, logs, TensorBoard
    ["runtime/run"],          # the trainer, callbacks, evaluation and recording
    ["runtime/workflows"],    # sweeps, Slurm, zoo files
    ["tune"],
]
CIRCLE_FREE = ("runtime/", "tune/")
INCLUDE = re.compile(r'^\s*#\s*include\s+"(rlrun/[^"]+)"', re.MULTILINE)


def floor_of(folder):
    for floor, folders in enumerate(LAYERS):
        if folder in folders:
            return floor
    return None


def folder_of(rel):
    """The LAYERS folder of a path relative to src/rlrun/ (None for the plugin API)."""
    best = None
    for folders in LAYERS:
        for folder in folders:
            if rel.startswith(folder + "/") and (best is None or len(folder) > len(best)):
                best = folder
    return best


def sources(root):
    base = os.path.join(root, "src", "rlrun")
    for directory, _, names in os.walk(base):
        for name in sorted(names):
            if name.endswith((".cpp", ".hpp", ".h", ".c")):
                path = os.path.join(directory, name)
                yield os.path.relpath(path, base), path


def includes(root, path):
    with open(path, encoding="utf-8", errors="replace") as f:
        for target in INCLUDE.findall(f.read()):
            rel = target[len("rlrun/"):]
            if os.path.exists(os.path.join(root, "src", "rlrun", rel)):
                yield rel  # else include/rlrun/ (the plugin API) or a generated file


def room(rel):
    return re.sub(r"\.(cpp|hpp|h|c)$", "", rel)


def circles(edges):
    """Strongly connected components of more than one room (Tarjan, iterative)."""
    index, low, stack, on_stack, found = {}, {}, [], set(), []
    counter = 0
    for start in sorted(edges):
        if start in index:
            continue
        work = [(start, iter(sorted(edges[start])))]
        index[start] = low[start] = counter
        counter += 1
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            advanced = False
            for child in children:
                if child not in index:
                    index[child] = low[child] = counter
                    counter += 1
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(edges.get(child, ())))))
                    advanced = True
                    break
                if child in on_stack:
                    low[node] = min(low[node], index[child])
            if advanced:
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                if len(component) > 1:
                    found.append(sorted(component))
    return found


def check(root):
    problems = []
    edges = collections.defaultdict(set)
    files = 0
    for rel, path in sources(root):
        files += 1
        folder = folder_of(rel)
        if folder is None:
            problems.append(f"src/rlrun/{rel}: its folder has no floor in {__file__}'s LAYERS")
            continue
        for target in includes(root, path):
            target_folder = folder_of(target)
            if target_folder == folder or target_folder is None:
                pass
            elif floor_of(target_folder) >= floor_of(folder):
                how = "beside" if floor_of(target_folder) == floor_of(folder) else "above"
                problems.append(f"src/rlrun/{rel} includes src/rlrun/{target}: "
                                f"{target_folder}/ stands {how} {folder}/")
            if rel.startswith(CIRCLE_FREE) and target.startswith(CIRCLE_FREE):
                if room(target) != room(rel):
                    edges[room(rel)].add(room(target))
    for component in circles(edges):
        ties = [f"{a} -> {b}" for a in component for b in sorted(edges[a]) if b in component]
        problems.append("include circle: " + "; ".join(ties))
    return files, problems


def self_test():
    """Plants an upward include, a sideways one and a circle; each must be reported."""
    import tempfile
    with tempfile.TemporaryDirectory() as root:
        planted = {
            "core/a.hpp": '#include "rlrun/runtime/run/t.hpp"\n',
            "runtime/run/t.hpp": "",
            "envs/x.hpp": '#include "rlrun/algos/y.hpp"\n',
            "algos/y.hpp": "",
            "tune/p.hpp": '#include "rlrun/tune/q.hpp"\n',
            "tune/q.hpp": "",
            "tune/q.cpp": '#include "rlrun/tune/p.hpp"\n',
            "runtime/io/fine.cpp": '#include "rlrun/core/a.hpp"\n',
        }
        for rel, text in planted.items():
            path = os.path.join(root, "src", "rlrun", rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as f:
                f.write(text)
        _, problems = check(root)
    expected = ["core/a.hpp includes src/rlrun/runtime/run/t.hpp",
                "envs/x.hpp includes src/rlrun/algos/y.hpp", "include circle: tune/p -> tune/q"]
    missed = [e for e in expected if not any(e in p for p in problems)]
    for e in missed:
        print("self-test: not reported:", e)
    if len(problems) != len(expected):
        print("self-test: expected", len(expected), "problems, got", problems)
        return 1
    print("self-test: the three planted breaks were reported")
    return 1 if missed else 0


def main():
    if sys.argv[1:] == ["--self-test"]:
        return self_test()
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(
        os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    files, problems = check(root)
    for problem in problems:
        print(problem)
    if problems:
        print(f"{len(problems)} include(s) against the layers of docs/architecture.md")
        return 1
    print(f"{files} files: every include runs down the layers, no circle in runtime/ or tune/")
    return 0


if __name__ == "__main__":
    sys.exit(main())
