"""Lists the non-test Rust functions over 80 lines, longest first, then how many there are.

Run from the repository root: `python3 docs/long_functions.py`. A function runs from its
`fn` line to its closing brace; a file's code from its first `#[cfg(test)]` line on is left
out, and so are `tests/`, `benches/`, `examples/` and build output. ARCHITECTURE.md
("Long functions, and why") gives the reason each one listed stays long.
"""

import pathlib
import re

LIMIT = 80


def long_functions(root="."):
    """(lines, file, name) of every function over LIMIT lines under `root`."""
    found = []
    for f in pathlib.Path(root).rglob("*.rs"):
        p = str(f)
        if (
            p.startswith(("target", "bench/knossos/target"))
            or "/tests/" in p
            or p.startswith("tests")
            or p.startswith("benches")
            or p.startswith("examples")
        ):
            continue
        lines = f.read_text().split("\n")
        # the test module and everything after it
        cut = len(lines)
        for i, line in enumerate(lines):
            if line.strip() == "#[cfg(test)]":
                cut = i
                break
        i = 0
        while i < cut:
            line = lines[i]
            m = re.match(
                r"\s*(pub(\([^)]*\))?\s+)?(const\s+)?(async\s+)?(unsafe\s+)?fn\s+(\w+)", line
            )
            if m and not line.strip().endswith(";"):
                depth, started, j = 0, False, i
                while j < cut:
                    s = re.sub(r'"(\\.|[^"\\])*"', '""', lines[j])
                    s = re.sub(r"'(\\.|[^'\\])'", "''", s)
                    s = s.split("//")[0]
                    depth += s.count("{") - s.count("}")
                    if "{" in s:
                        started = True
                    if started and depth <= 0:
                        break
                    j += 1
                n = j - i + 1
                if n > LIMIT:
                    found.append((n, p, m.group(6)))
                i = j + 1 if started else i + 1
            else:
                i += 1
    return sorted(found, reverse=True)


if __name__ == "__main__":
    functions = long_functions()
    for function in functions:
        print(*function)
    print(len(functions))
