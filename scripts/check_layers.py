#!/usr/bin/env python3
"""Checks the library's layers (docs/architecture.md) against the graph CMake declares.

    scripts/check_layers.py BUILD/layers/layers.json            # the sources' #includes
    scripts/check_layers.py BUILD/layers/layers.json --compile  # the include paths themselves
    scripts/check_layers.py BUILD/layers/layers.json --mermaid  # the graph, for the docs

The graph (<build>/layers/layers.json) is written by cmake/layers.cmake: each layer's USES and its
include path as compiled, and each program's (src/app, src/viewer). Each layer's public headers are
the links in <build>/layers/<layer>/penumbra/.

Without --compile, every `#include` in src/<layer>/ is read and one line is printed per include of a
layer that is not below it (`core/`, `gpu/`, ... or a public header that such a layer implements), per
Vulkan header outside gpu, and per internal header a program includes. Exit code 1 if any.

With --compile, the preprocessor runs with each layer's own include path on a one-line file per
other layer: `#include "<other>/<header>"` and `#include <penumbra/<its header>>` must fail to be
found when the other layer is not below, and must preprocess when it is; `<vulkan/vulkan.h>` must
fail outside gpu; the programs must not find an internal header. This is the enforcement the build
itself applies; the check proves it holds. ctest runs both (label unit).
"""
import json
import os
import re
import subprocess
import sys
import tempfile
from concurrent.futures import ThreadPoolExecutor

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]')
DOC = "docs/architecture.md"


def below(layers, name):
    """The layers `name` may use: its USES and theirs, transitively."""
    seen, stack = [], list(layers[name]["uses"])
    while stack:
        other = stack.pop()
        if other not in seen:
            seen.append(other)
            stack.extend(layers[other]["uses"])
    return seen


def public_headers(build_layers, name):
    folder = os.path.join(build_layers, name, "penumbra")
    headers = []
    for root, _, files in os.walk(folder):
        headers += [os.path.relpath(os.path.join(root, file), folder) for file in files]
    return sorted(headers)


def includes_of(folder):
    for root, _, files in os.walk(folder):
        for file in sorted(files):
            if not file.endswith((".h", ".cpp")):
                continue
            path = os.path.join(root, file)
            with open(path, encoding="utf-8") as text:
                for number, line in enumerate(text, 1):
                    match = INCLUDE.match(line)
                    if match:
                        yield path, number, match.group(2)


def check_sources(graph, build_layers):
    source, layers = graph["sourceDir"], graph["layers"]
    owner = {header: name for name in layers for header in public_headers(build_layers, name)}
    problems = []
    for name in layers:
        allowed = [name] + below(layers, name)
        for path, number, header in includes_of(os.path.join(source, "src", name)):
            where = "%s:%d: #include %s" % (os.path.relpath(path, source), number, header)
            first = header.split("/")[0]
            if first == "penumbra":
                layer = owner.get(header.split("/", 1)[1])
                if layer not in allowed:
                    problems.append("%s: a public header of %s; the %s layer uses only %s (%s)" % (
                        where, layer or "no layer", name, ", ".join(allowed[1:]) or "nothing", DOC))
            elif first == "vulkan" and name != "gpu":
                problems.append("%s: Vulkan is used only inside the gpu layer (%s)" % (where, DOC))
            elif first in layers and first not in allowed:
                problems.append("%s: the %s layer uses only %s (%s)" % (
                    where, name, ", ".join(allowed[1:]) or "nothing", DOC))
    for folder in graph["programs"]:
        for path, number, header in includes_of(os.path.join(source, "src", folder)):
            if header.split("/")[0] in layers:
                problems.append("%s:%d: #include %s: the programs use the public headers only (%s)" % (
                    os.path.relpath(path, source), number, header, DOC))
    return problems


def preprocess(compiler, include_dirs, line, workdir):
    """(found, output): whether `line` preprocesses with this include path."""
    flags = ["-I" + d for d in include_dirs if d not in ("/usr/include", "/usr/local/include")]
    command = [compiler, "-std=c++20", "-x", "c++", "-E", "-o", os.devnull,
               "-DGLM_FORCE_DEPTH_ZERO_TO_ONE", "-DGLM_FORCE_RADIANS", "-DGLM_ENABLE_EXPERIMENTAL"] + flags + ["-"]
    run = subprocess.run(command, input=line + "\n", capture_output=True, text=True, cwd=workdir)
    return run.returncode == 0, run.stderr


def probes(graph, build_layers):
    """(who, include line, whether it must be found) for every layer and program."""
    source, layers = graph["sourceDir"], graph["layers"]
    internal = {}
    for name in layers:
        headers = sorted(f for f in os.listdir(os.path.join(source, "src", name)) if f.endswith(".h"))
        internal[name] = headers[0] if headers else None
    for name in layers:
        allowed = below(layers, name)
        for other in layers:
            if other == name:
                continue
            if internal[other]:
                yield name, '#include "%s/%s"' % (other, internal[other]), other in allowed
            for header in public_headers(build_layers, other)[:1]:
                yield name, "#include <penumbra/%s>" % header, other in allowed
        yield name, "#include <vulkan/vulkan.h>", name == "gpu"
    for folder in graph["programs"]:
        for other in layers:
            if internal[other]:
                yield folder, '#include "%s/%s"' % (other, internal[other]), False
        yield folder, "#include <penumbra/penumbra.h>", True


def refused(line, output):
    """Whether the probe failed on its own #include: not found (gcc or clang), or Vulkan's #error."""
    header = line.split()[1][1:-1]
    missing = re.search(r"<stdin>:1:\d+: fatal error: '?%s'?(: No such file| file not found)" % re.escape(header), output)
    return bool(missing) or "Vulkan is used only inside the gpu layer" in output


def check_compile(graph, build_layers):
    entries = dict(graph["layers"], **graph["programs"])
    work = tempfile.mkdtemp()
    cases = list(probes(graph, build_layers))

    def run(case):
        who, line, must_find = case
        found, output = preprocess(graph["compiler"], entries[who]["includeDirs"], line, work)
        if must_find:
            return None if found else "%s: `%s` does not preprocess with its include path:\n%s" % (
                who, line, output.strip())
        if not found and refused(line, output):
            return None
        return "%s: `%s` is found, but %s is not below it (%s)%s" % (
            who, line, line.split()[1], DOC, "" if found else ":\n" + output.strip())

    with ThreadPoolExecutor(max_workers=2) as pool:
        problems = [p for p in pool.map(run, cases) if p]
    os.rmdir(work)
    print("%d include probes run" % len(cases))
    return problems


def mermaid(graph):
    """The layer targets and what each USES, as a Mermaid flowchart (docs/architecture.md)."""
    lines = ["```mermaid", "flowchart BT"]
    for name, layer in graph["layers"].items():
        lines.append("    %s[penumbra_%s]" % (name, name))
        lines.extend("    %s --> %s" % (name, used) for used in layer["uses"])
    lines.append("    lib[[libpenumbra: include/penumbra/]]")
    lines.extend("    %s([src/%s]) --> lib" % (folder, folder) for folder in graph["programs"])
    lines.append("    lib -. archives .-> %s" % " & ".join(graph["layers"]))
    lines.append("```")
    return "\n".join(lines)


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    with open(sys.argv[1], encoding="utf-8") as text:
        graph = json.load(text)
    build_layers = os.path.dirname(os.path.abspath(sys.argv[1]))
    if "--mermaid" in sys.argv[2:]:
        print(mermaid(graph))
        return 0
    compile_mode = "--compile" in sys.argv[2:]
    problems = check_compile(graph, build_layers) if compile_mode else check_sources(graph, build_layers)
    for problem in problems:
        print(problem)
    if not problems:
        print("layers: every include follows the graph" + (" (checked by the preprocessor)" if compile_mode else ""))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
