#!/usr/bin/env python3
"""tools/check_unity_names.py BUILD_DIR: no two sources of one unity-built target define the
same file-local name.

A unity build (CMAKE_UNITY_BUILD, the ci, asan, fuzz and cross presets) compiles a target's
sources as one translation unit. A helper in one file's anonymous namespace (or a `static`
one) then shares a scope with every other file of that target: two with the same signature
stop the build, but two overloads of one name (`error_of(const std::string&)` in one test,
`error_of(std::string_view)` in another) compile, and a call in one file can silently pick the
other file's function. This check refuses the name itself, whatever the signatures.

It reads the sources each `Unity/unity_*.cxx` of BUILD_DIR includes and collects, per source,
the names defined at namespace scope inside `namespace {` or declared `static` at column 0
(the code is clang-formatted: namespaces do not indent): functions, types, constants and
aliases. Exit 0 when every name is defined by one source of its target, 1 with each clash
(target, name, files) otherwise, 2 on a bad BUILD_DIR.
"""
import collections
import pathlib
import re
import sys

TYPE = re.compile(r"^(?:struct|class|enum(?: class)?|union) (\w+)\b(?!;)")
ALIAS = re.compile(r"^using (\w+) =")
VALUE = re.compile(r"^(?:inline )?(?:static )?(?:constexpr|const) [^(=;]*?\b(\w+)\s*(?:\{|=|\[)")
FUNCTION = re.compile(r"^(?:static )?(?:inline )?(?:constexpr )?(?!return\b)[\w:<>,*&\s]+?[\s*&](\w+)\(")
NOT_A_DEFINITION = re.compile(r"^(?:[A-Z_][A-Z0-9_]*\(|#|//|\}|namespace|using (?!\w+ =)|template|return)")


# Customisation points found by argument-dependent lookup on each file's own types (GoogleTest's
# value printer), not by name: one per file is how they are used.
BY_ARGUMENT_TYPE = {"PrintTo"}


def local_names(source: pathlib.Path) -> set[str]:
    """File-local names `source` defines: column-0 definitions inside `namespace {`, and
    column-0 `static` definitions anywhere."""
    names = set()
    depth = 0  # anonymous namespaces open at this line
    for line in source.read_text(encoding="utf-8", errors="replace").splitlines():
        if re.match(r"^namespace \{", line):
            depth += 1
            continue
        if depth and re.match(r"^\}\s*// namespace\s*$", line):
            depth -= 1
            continue
        if not line or line[0].isspace() or NOT_A_DEFINITION.match(line):
            continue
        if not depth and not line.startswith("static "):
            continue
        for pattern in (TYPE, ALIAS, VALUE, FUNCTION):
            match = pattern.match(line)
            if match:
                names.add(match.group(1))
                break
    return names - BY_ARGUMENT_TYPE


def main() -> int:
    if len(sys.argv) != 2 or not pathlib.Path(sys.argv[1]).is_dir():
        print("usage: tools/check_unity_names.py BUILD_DIR", file=sys.stderr)
        return 2
    build = pathlib.Path(sys.argv[1])
    targets = collections.defaultdict(set)  # target directory -> its sources
    for unity in build.rglob("Unity/unity_*.cxx"):
        for line in unity.read_text(encoding="utf-8").splitlines():
            match = re.match(r'#include "(.+)"', line)
            if match:
                targets[unity.parent.parent].add(pathlib.Path(match.group(1)))
    if not targets:
        print(f"check_unity_names: no unity sources in {build} (configure with "
              "CMAKE_UNITY_BUILD=ON, e.g. cmake --preset ci)", file=sys.stderr)
        return 2
    clashes = 0
    for target, sources in sorted(targets.items()):
        where = collections.defaultdict(list)
        for source in sorted(sources):
            for name in local_names(source):
                where[name].append(source)
        for name, files in sorted(where.items()):
            if len(files) > 1:
                clashes += 1
                shown = ", ".join(str(f) for f in files)
                print(f"{target.name.removesuffix('.dir')}: `{name}` is file-local in {shown}")
    if clashes:
        print(f"check_unity_names: {clashes} names defined by two sources of one unity-built "
              "target; rename one (or share one in a header)", file=sys.stderr)
        return 1
    print(f"check_unity_names: {sum(len(s) for s in targets.values())} sources of "
          f"{len(targets)} targets, no file-local name defined twice")
    return 0


if __name__ == "__main__":
    sys.exit(main())
