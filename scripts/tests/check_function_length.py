#!/usr/bin/env python3
"""No C/C++ function over 80 lines (issue 42: "no function in src/ over 80 lines outside
generated code and env physics ported line for line").

    scripts/tests/check_function_length.py [--max-lines N] [PATH...]   (default: src include)
    scripts/tests/check_function_length.py --self-test

Prints one line per function longer than the limit ("LINES file:line name") and exits 1 when
there is any, or when an entry of EXEMPT no longer names such a function (so the list cannot
rot). A function's length counts its lines from the `{` opening its body to the matching `}`,
both included (a long signature or constructor initialiser list is not counted).

The heuristic (no compiler involved): comments, string and character literals (raw strings
too) and preprocessor lines are blanked out, keeping line numbers; then braces are matched.
A `{` opens a function body when the text since the previous `;`, `{` or `}` reads as a
declarator: a name, a parameter list, then only qualifiers (const, noexcept, override, final,
mutable, & or &&), a trailing return type or a constructor's initialiser list. Control
statements (if, for, while, switch, else, do, try, catch), namespaces, classes and lambdas
(`](...)`) open other blocks. Only outermost functions are measured: a lambda or a local class
counts towards the function holding it; a class's member functions are measured on their own.

Known limits: a constructor initialiser list that uses braces (`x_{1}`) hides that
constructor; a macro that expands to braces is not seen; a function-try-block is measured
from its `try`'s block only. They do not occur in src/ today; the self-test pins what is
recognised.
"""

import argparse
import os
import re
import subprocess
import sys
import tempfile

MAX_LINES = 80
SOURCE_ENDINGS = (".c", ".cc", ".cpp", ".h", ".hpp")

# Functions allowed over the limit: (path relative to the checkout, name as printed, why).
EXEMPT = [
    ("src/rlrun/envs/lunar_lander/lunar_lander.cpp", "LunarLander::reset",
     "Gymnasium's LunarLander.reset (gymnasium/envs/box2d/lunar_lander.py) ported line for "
     "line: terrain, moon, lander, legs and joints built in its order, so the Box2D world and "
     "its random draws stay comparable with the Python source"),
    ("src/rlrun/envs/bipedal_walker/bipedal_walker.cpp", "BipedalWalker::build_world",
     "Gymnasium's BipedalWalker.reset world building (gymnasium/envs/box2d/bipedal_walker.py) "
     "ported line for line: hull, legs, joints and lidar in its order"),
]

CONTROL = re.compile(r"^(if|for|while|switch|catch|do|else|try|namespace|class|struct|enum|"
                     r"union)\b|^extern\s*\"\"\s*$")
QUALIFIERS = re.compile(r"^(\s*(const|noexcept(\s*\([^()]*\))?|override|final|mutable|&&|&|"
                        r"volatile))*\s*$")
NAME_BEFORE_PAREN = re.compile(r"(~?[A-Za-z_][\w:<>,\s]*?~?[A-Za-z_]\w*|operator\s*\S+)\s*$")


def blank_out(text):
    """The text with comments, literals and preprocessor lines replaced by blanks; newlines kept."""
    out = []
    i, n = 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == "#":
            j = i
            while True:  # a directive with its backslash continuations
                k = text.find("\n", j)
                if k < 0:
                    k = n
                if k > 0 and text[k - 1] == "\\" and k < n:
                    j = k + 1
                    continue
                break
            out.append("\n" * text.count("\n", i, k))
            i = k
            continue
        if c == "\n":
            at_line_start = True
            out.append(c)
            i += 1
            continue
        if not c.isspace():
            at_line_start = False
        if text.startswith("//", i):
            k = text.find("\n", i)
            i = n if k < 0 else k
            continue
        if text.startswith("/*", i):
            k = text.find("*/", i + 2)
            k = n if k < 0 else k + 2
            out.append("\n" * text.count("\n", i, k))
            i = k
            continue
        raw = re.match(r'(?:u8|u|U|L)?R"([^()\\\s]{0,16})\(', text[i:i + 24])
        if raw and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")):
            end = ")" + raw.group(1) + '"'
            k = text.find(end, i + raw.end())
            k = n if k < 0 else k + len(end)
            out.append('""' + "\n" * text.count("\n", i, k))
            i = k
            continue
        # A quote, unless it is a digit separator (1'000'000).
        if c == '"' or (c == "'" and not (i > 0 and text[i - 1].isalnum())):
            k = i + 1
            while k < n and text[k] != c and text[k] != "\n":
                k += 2 if text[k] == "\\" else 1
            out.append(c + c)
            i = k + 1
            continue
        out.append(c)
        i += 1
    return "".join(out)


def matching_paren(head, open_at):
    depth = 0
    for k in range(open_at, len(head)):
        if head[k] == "(":
            depth += 1
        elif head[k] == ")":
            depth -= 1
            if depth == 0:
                return k
    return -1


def function_name(head):
    """The function's name when `head` (the text before a `{`) declares one, else None."""
    head = " ".join(head.split())
    head = re.sub(r"^((public|private|protected)\s*:\s*)+", "", head)
    head = re.sub(r"^template\s*<.*?>\s*(?=[A-Za-z_])", "", head)
    if not head or CONTROL.match(head):
        return None
    # operator() has its parameter list after its own parentheses.
    head = re.sub(r"operator\s*\(\s*\)", "operator_call", head)
    open_at = head.find("(")
    if open_at <= 0:
        return None
    before = head[:open_at].rstrip()
    if before.endswith("]") or "=" in before.replace("operator=", "").replace("operator==", ""):
        return None  # a lambda, or an initialiser
    close_at = matching_paren(head, open_at)
    if close_at < 0:
        return None
    rest = head[close_at + 1:]
    if "->" in rest:
        rest = rest[:rest.index("->")]  # a trailing return type
    elif re.match(r"^[\s\w&()]*?:(?!:)", rest):
        rest = rest[:re.match(r"^[\s\w&()]*?:(?!:)", rest).end() - 1]  # an initialiser list
    if not QUALIFIERS.match(rest):
        return None
    name = NAME_BEFORE_PAREN.search(before)
    if not name:
        return None
    return name.group(1).split()[-1].replace("operator_call", "operator()")


def functions(text):
    """(first line, last line, name) of each outermost function body in C/C++ source text."""
    text = blank_out(text)
    found = []
    stack = []  # (is_function, line, name, inside parentheses) per open brace
    line = 1
    statement_start = 0
    parens = 0
    for i, c in enumerate(text):
        if c == "\n":
            line += 1
        elif c == "(":
            parens += 1
        elif c == ")":
            parens = max(parens - 1, 0)
        elif c == "{":
            if parens:  # braces in an argument list (`v = {}`, a lambda argument)
                stack.append((False, line, None, True))
                continue
            name = function_name(text[statement_start:i])
            stack.append((name is not None, line, name, False))
            statement_start = i + 1
        elif c == "}":
            if stack:
                is_function, first, name, in_parens = stack.pop()
                if is_function and not any(entry[0] for entry in stack):
                    found.append((first, line, name))
                if in_parens:
                    continue
            statement_start = i + 1
        elif c == ";" and not parens:
            statement_start = i + 1
    return found


def source_files(paths):
    for path in paths:
        if os.path.isfile(path):
            yield path
            continue
        for root, dirs, files in os.walk(path):
            dirs.sort()
            for f in sorted(files):
                if f.endswith(SOURCE_ENDINGS):
                    yield os.path.join(root, f)


def check(paths, max_lines, root, exempt):
    """Returns the problems found (lines to print); empty when every function fits."""
    problems = []
    exempt_seen = set()
    exempt_keys = {(path, name) for path, name, _ in exempt}
    for path in source_files(paths):
        with open(path, encoding="utf-8", errors="replace") as f:
            text = f.read()
        relative = os.path.relpath(os.path.abspath(path), root)
        for first, last, name in functions(text):
            length = last - first + 1
            if length <= max_lines:
                continue
            if (relative, name) in exempt_keys:
                exempt_seen.add((relative, name))
                continue
            problems.append(f"{length:5d} {relative}:{first} {name}")
    for path, name, _ in exempt:
        scanned = any(os.path.abspath(os.path.join(root, path)).startswith(os.path.abspath(p))
                      for p in paths)
        if scanned and (path, name) not in exempt_seen:
            problems.append(f"stale exemption: {path} {name} is no longer a function over "
                            f"{max_lines} lines; remove it from EXEMPT in {__file__}")
    return problems


def self_test():
    """The checker on made-up sources: what it must find, and what it must not take for one."""
    def body(n):  # a body of n lines from `{` to `}`
        return "{\n" + "  x += 1;\n" * (n - 2) + "}\n"

    source = (
        "#include <vector>\n"
        "#define BLOCK(x) { x; }\n"
        "namespace demo {\n"
        "extern \"C\" {\nint inside_extern_c() " + body(81) + "}\n"
        "// void commented_out() " + body(90).replace("\n", "\n// ") + "\n"
        "int long_one(int x) " + body(81) +
        "int fits(int x) " + body(80) +
        "extern \"C\" [[nodiscard]] int c_entry(const char* p) " + body(81) +
        "int defaulted(std::vector<int> v = {}, int w = int{1}) " + body(81) +
        "class Holder {\n public:\n  void member() const " + body(85) +
        "  Holder(int a) : a_(a), b_(a) " + body(82) + " private:\n  int a_, b_;\n};\n"
        "auto lambda = [](int x) " + body(90) + ";\n"
        "bool Holder::operator()(int x) const noexcept " + body(83) +
        "auto trailing(int x) -> int " + body(84) +
        "const char* text() { return \"}\" \"{\"; }\n"
        "const char* raw() { return R\"(}})\"; }\n"
        "int with_lambda(int x) {\n  auto f = [&](int y) " + body(40) + ";\n"
        "  if (x) " + body(20) + "  return f(x);\n}\n"
        "}  // namespace demo\n")
    expected = {("long_one", 81), ("defaulted", 81), ("c_entry", 81), ("inside_extern_c", 81),
                ("member", 85), ("Holder", 82), ("Holder::operator()", 83), ("trailing", 84)}
    with tempfile.TemporaryDirectory() as scratch:
        path = os.path.join(scratch, "demo.cpp")
        with open(path, "w") as f:
            f.write(source)
        problems = check([scratch], MAX_LINES, scratch, [])
        found = {(p.split()[-1], int(p.split()[0])) for p in problems}
        stale = check([scratch], MAX_LINES, scratch, [("demo.cpp", "gone", "")])
        exempted = check([scratch], MAX_LINES, scratch, [("demo.cpp", "long_one", "")])
        command = subprocess.run([sys.executable, os.path.abspath(__file__), scratch],
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    lengths = {name: last - first + 1 for first, last, name in functions(source)}
    names = set(lengths)
    failures = []
    if found != expected:
        failures.append(f"over-long functions found {sorted(found)}, expected {sorted(expected)}")
    if not {"fits", "text", "raw", "with_lambda"} <= names:
        failures.append(f"functions seen {sorted(names)} miss fits/text/raw/with_lambda")
    if lengths.get("with_lambda", 0) < 60:  # its lambda's 40 lines and its if's 20 count
        failures.append(f"with_lambda measured {lengths.get('with_lambda')} lines, not 64")
    if "commented_out" in names:
        failures.append("a commented-out function was measured")
    if not any(p.startswith("stale exemption: demo.cpp gone") for p in stale):
        failures.append("a stale exemption was not reported")
    if any(p.endswith(" long_one") for p in exempted) or len(exempted) != len(expected) - 1:
        failures.append(f"an exemption was not applied: {exempted}")
    if command.returncode != 1 or "demo.cpp" not in command.stdout:
        failures.append(f"the command exited {command.returncode} on over-long functions")
    for failure in failures:
        print("self-test:", failure)
    print("self-test:", "FAILED" if failures else "passed")
    return 1 if failures else 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("paths", nargs="*", help="files or folders (default: src include)")
    parser.add_argument("--max-lines", type=int, default=MAX_LINES)
    parser.add_argument("--self-test", action="store_true",
                        help="check the checker on made-up sources")
    args = parser.parse_args()
    if args.self_test:
        return self_test()
    root = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
    paths = args.paths or [os.path.join(root, "src"), os.path.join(root, "include")]
    problems = check(paths, args.max_lines, root, EXEMPT)
    for problem in problems:
        print(problem)
    if problems:
        print(f"{len(problems)} problem(s): split functions over {args.max_lines} lines into "
              "named pieces (docs: scripts/tests/check_function_length.py)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
