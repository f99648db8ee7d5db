#!/usr/bin/env python3
"""Catch2 test names that ctest can register (tests/CMakeLists.txt discovers every TEST_CASE as
a ctest test of the same name): no semicolon — CMake's list separator splits such a name into
two tests that match nothing and fail — and no name used twice.

    scripts/tests/check_test_names.py [DIR...]   (default: tests)
    scripts/tests/check_test_names.py --self-test

Prints one line per bad name ("file:line: reason: name") and exits 1 when there is any. A name
is the TEST_CASE's first argument: adjacent string literals joined, as the compiler joins them.
"""
import pathlib
import re
import sys

NAME = re.compile(r'\bTEST_CASE\s*\(\s*((?:"(?:[^"\\\n]|\\.)*"\s*)+)')
LITERAL = re.compile(r'"((?:[^"\\\n]|\\.)*)"')


def names(text):
    """(line, name) of every TEST_CASE in C++ source text."""
    for match in NAME.finditer(text):
        joined = "".join(LITERAL.findall(match.group(1)))
        yield text.count("\n", 0, match.start()) + 1, joined.replace('\\"', '"')


def problems(files):
    seen = {}
    for path, text in files:
        for line, name in names(text):
            where = f"{path}:{line}"
            if ";" in name:
                yield f"{where}: a semicolon splits the ctest name: {name}"
            if name in seen:
                yield f"{where}: also the name of {seen[name]}: {name}"
            seen.setdefault(name, where)


def self_test():
    files = [("a.cpp", 'TEST_CASE("good one", "[x]") {}\nTEST_CASE(\n    "split; "\n    "name") {}\n'),
             ("b.cpp", 'TEST_CASE("good one") {}\nTEST_CASE("fine, with \\"quotes\\"") {}\n')]
    found = list(problems(files))
    expected = ["a.cpp:2: a semicolon splits the ctest name: split; name",
                "b.cpp:1: also the name of a.cpp:1: good one"]
    if found != expected:
        print("self-test failed:", found)
        return 1
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    roots = [pathlib.Path(a) for a in argv[1:]] or [pathlib.Path("tests")]
    files = [(str(p), p.read_text(encoding="utf-8", errors="replace"))
             for root in roots for p in sorted(root.rglob("*.cpp"))]
    bad = list(problems(files))
    for line in bad:
        print(line)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
