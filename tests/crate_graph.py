"""The workspace's crate graph drawn from the code's own imports: for every crate, the rins crates
its sources (src/, tests and comments aside) name as `rins_x::`, printed in layers from the
bottom (a crate's layer is one above the highest crate it imports). Fails when

* a crate imports one in its own layer or above (an arrow back up: cargo would refuse the
  circle, this names it from the imports),
* an import is not among the crate's [dependencies] (or a [dependencies] rins crate is never
  imported: a dependency kept for nothing),
* the Python package depends, directly or through others, on the report (`rins-report`) or the
  application (`rins-scenarios`),
* a crate is not named for its folder: crate `rins-X` lives in a folder named `X`.

docs/architecture.md shows the graph this prints. Usage: python3 tests/crate_graph.py [ROOT]
"""
import os
import re
import sys
import tomllib

# The Python package must not reach these (docs/architecture.md, "Rules the layout keeps").
PYTHON = "rins-python"
NOT_UNDER_PYTHON = ("rins-report", "rins-scenarios")


def strip(text):
    text = re.sub(r"//[^\n]*", "", text)
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    # Unit tests beside the code: their imports are dev-dependencies.
    return re.split(r"#\[cfg\(test\)\]\s*mod\s+\w+\s*\{", text)[0]


def imports(src, names):
    """The workspace crates the sources under `src` name (by their crate identifiers)."""
    found = set()
    for root, _, files in os.walk(src):
        for f in files:
            if not f.endswith(".rs"):
                continue
            with open(os.path.join(root, f), encoding="utf-8") as fh:
                text = strip(fh.read())
            for ident in re.findall(r"\b(rins_[a-z0-9_]+)\s*::", text):
                if ident in names:
                    found.add(names[ident])
            for ident in re.findall(r"\buse\s+(rins_[a-z0-9_]+)\b", text):
                if ident in names:
                    found.add(names[ident])
    return found


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else "."
    with open(os.path.join(root, "Cargo.toml"), "rb") as f:
        members = tomllib.load(f)["workspace"]["members"]
    crates, problems_early = {}, []
    for m in members:
        with open(os.path.join(root, m, "Cargo.toml"), "rb") as f:
            t = tomllib.load(f)
        name = t["package"]["name"]
        lib = t.get("lib", {}).get("name", name.replace("-", "_"))
        deps = set(t.get("dependencies", {})) | {
            d for tgt in t.get("target", {}).values() for d in tgt.get("dependencies", {})}
        crates[name] = {"dir": m, "lib": lib, "deps": deps}
        if name != "rins-" + os.path.basename(m):
            problems_early.append(f"{name} lives in {m}: a crate rins-X lives in a folder named X")
    names = {c["lib"]: n for n, c in crates.items()}
    names.update({n.replace("-", "_"): n for n in crates})
    problems = list(problems_early)
    graph = {}
    for n, c in crates.items():
        used = imports(os.path.join(root, c["dir"], "src"), names) - {n}
        declared = {d for d in c["deps"] if d in crates}
        graph[n] = used
        for d in sorted(used - declared):
            problems.append(f"{n} imports {d}, which is not among its [dependencies]")
        for d in sorted(declared - used):
            problems.append(f"{n} lists {d} in [dependencies] and never imports it")
    # Layers from the bottom; a crate left over sits on a circle of imports.
    layer, left = {}, set(graph)
    while left:
        ready = {n for n in left if graph[n] <= set(layer)}
        if not ready:
            problems.append(f"a circle of imports among: {', '.join(sorted(left))}")
            break
        for n in ready:
            layer[n] = 1 + max((layer[d] for d in graph[n]), default=-1)
        left -= ready
    for k in range(max(layer.values(), default=-1) + 1):
        row = sorted(n for n in layer if layer[n] == k)
        print(f"layer {k}:")
        for n in row:
            below = ", ".join(sorted(graph[n])) or "-"
            print(f"  {n} ({crates[n]['dir']}) <- {below}")
    # What the Python package reaches through its [dependencies].
    reach, todo = set(), [PYTHON]
    while todo:
        for d in crates[todo.pop()]["deps"]:
            if d in crates and d not in reach:
                reach.add(d)
                todo.append(d)
    for bad in NOT_UNDER_PYTHON:
        if bad in reach:
            problems.append(f"{PYTHON} depends on {bad}, directly or through another crate")
    print(f"{PYTHON} reaches: {', '.join(sorted(reach))}")
    for p in problems:
        print(f"FAIL {p}")
    print(f"{len(crates)} crates, {sum(len(g) for g in graph.values())} import arrows, "
          f"{len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
