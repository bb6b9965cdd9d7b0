#!/usr/bin/env python3
"""Import circles between the files of each crate of the workspace.

File A imports file B when A names a path into B's module (`crate::x::y`, `super::y`,
`self::y`, also inside `use ...::{...}` groups). Each strongly connected component of that graph
with more than one file is a circle: no file of it can be read, moved or tested without the
others. Accidental circles come from shared types living in one of their users, or from an impl
kept away from its type's file; they are fixed by moving the types down and the impls home.

Some circles are one concept split across files (a type and its private helpers); those are
listed in ALLOWED below, each with its reason, and docs/architecture.md ("Import circles") names
them too. Entries whose reason starts with TODO are circles being untangled: any circle made of
their files only passes. Any other circle fails: the script prints it with the imports that close
it and exits 1, so a new accidental circle fails the suite.

Not counted: comments, everything after the first `#[cfg(test)]` of a file (tests may import
anything), and files under src/bin/ (binaries are leaves).

Python 3.11 standard library only.

Usage: python3 tests/import_cycles.py [ROOT] [--allow CRATE:FILE,FILE,...]... [--edges]
"""
import argparse
import os
import re
import sys
import tomllib

# Circles that are one concept: (crate folder, sorted module paths as printed) -> why. Each is
# named in docs/architecture.md ("Import circles") too. None today.
ALLOWED = {}


def module_of(src, path):
    """The module path of a source file under src/ as a tuple, () for the crate root, None for
    a binary under src/bin/."""
    rel = os.path.relpath(path, src)[:-3].split(os.sep)
    if rel[0] == "bin":
        return None
    if len(rel) == 1 and rel[0] in ("lib", "main"):
        return ()
    if rel[-1] == "mod":
        rel = rel[:-1]
    return tuple(rel)


def strip_comments(text):
    text = re.sub(r"//[^\n]*", "", text)
    return re.sub(r"/\*.*?\*/", "", text, flags=re.S)


def named_paths(text):
    """Yields (head, segments) for each `crate::`/`super::`/`self::` path in the text; a brace
    group yields one path per item (and the item's second segment when it has one)."""
    for mt in re.finditer(r"\b(crate|super|self)((?:::\w+)+|::\{)", text):
        head, rest = mt.group(1), mt.group(2)
        segs = tuple(re.findall(r"::(\w+)", rest))
        if not rest.endswith("{"):
            yield head, segs
            continue
        k, depth = mt.end(), 1
        while k < len(text) and depth:
            depth += {"{": 1, "}": -1}.get(text[k], 0)
            k += 1
        for item in text[mt.end():k - 1].split(","):
            words = re.findall(r"\w+", item)
            if words:
                yield head, segs + (words[0],)
            pair = re.findall(r"(\w+)(?:::(\w+))?", item)
            if pair and pair[0][1]:
                yield head, segs + pair[0]


def crate_graph(src):
    """The files of one crate's src/ as module paths, and which modules each one imports."""
    files = {}
    for d, _, names in os.walk(src):
        for name in names:
            if name.endswith(".rs"):
                path = os.path.join(d, name)
                m = module_of(src, path)
                if m is not None:
                    files[m] = path
    mods = set(files)
    edges = {m: {} for m in mods}  # module -> {imported module: first path naming it}
    for m, path in files.items():
        with open(path, encoding="utf-8") as f:
            text = strip_comments(f.read())
        i = text.find("#[cfg(test)]")
        if i >= 0:
            text = text[:i]
        for head, segs in named_paths(text):
            base = {"crate": (), "self": m, "super": m[:-1]}[head]
            full = base + segs
            target = next((full[:n] for n in range(len(full), -1, -1) if full[:n] in mods), ())
            # the crate root, the file itself and its own parents are not imports of a file
            if target != () and target != m and m[:len(target)] != target:
                edges[m].setdefault(target, f"{head}::{'::'.join(segs)}")
    return edges


def circles(edges):
    """The strongly connected components of more than one module (Tarjan), each sorted."""
    index, low, stack, on_stack, out = {}, {}, [], set(), []
    counter = [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in edges[v]:
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    sys.setrecursionlimit(10000)
    for v in sorted(edges):
        if v not in index:
            visit(v)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("root", nargs="?", default=os.path.join(os.path.dirname(__file__), ".."),
                    help="the workspace root (default: this repository)")
    ap.add_argument("--allow", action="append", default=[], metavar="CRATE:FILE,FILE,...",
                    help="allow one more circle, e.g. mvm:a,b (module paths as printed)")
    ap.add_argument("--edges", action="store_true",
                    help="print the imports inside each circle")
    args = ap.parse_args()

    allowed = dict(ALLOWED)
    for spec in args.allow:
        crate, _, names = spec.partition(":")
        allowed[(crate, tuple(sorted(names.split(","))))] = "--allow"

    def why_allowed(key):
        """The reason a circle is allowed: listed as it is, or (a TODO entry, being untangled)
        made of files of a listed circle only, so that partial progress passes."""
        if key in allowed:
            return allowed[key]
        member, names = key
        for (m, listed), why in allowed.items():
            if m == member and why.startswith("TODO") and set(names) <= set(listed):
                return why
        return None

    with open(os.path.join(args.root, "Cargo.toml"), "rb") as f:
        members = tomllib.load(f)["workspace"]["members"]
    found, unexpected = set(), []
    for member in members:
        src = os.path.join(args.root, member, "src")
        if not os.path.isdir(src):
            continue
        edges = crate_graph(src)
        for comp in circles(edges):
            names = tuple("::".join(m) for m in comp)
            key = (member, names)
            found.add(key)
            why = why_allowed(key)
            mark = f"allowed: {why}" if why else "NOT ALLOWED"
            print(f"{member}: {len(comp)} files: {', '.join(names)}  [{mark}]")
            if args.edges or not why:
                for m in comp:
                    for t, via in sorted(edges[m].items()):
                        if t in comp:
                            print(f"    {'::'.join(m)} -> {'::'.join(t)}  ({via})")
            if not why:
                unexpected.append(key)
    stale = [k for k in ALLOWED if not any(m == k[0] and set(n) <= set(k[1]) for m, n in found)]
    for member, names in stale:
        print(f"note: allowed circle no longer found (remove it from ALLOWED): "
              f"{member}: {', '.join(names)}")
    print(f"{len(found)} circles, {len(unexpected)} not allowed")
    return 1 if unexpected else 0


if __name__ == "__main__":
    sys.exit(main())
