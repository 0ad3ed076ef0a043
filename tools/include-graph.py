#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""include-graph.py [ROOT] [--list]: counts the circles between files of host/ (issue 33).

A module is a .c or .cc with the .h of the same name in the same folder (a lone .h is a module
too). Module A depends on module B when any file of A includes B's header (#include "dir/b.h").
A circle is a set of modules that reach each other through these arrows: each strongly connected
component of more than one module counts once, and the pairs that include each other directly
are counted apart ("2-circles"), since those are the ones a reader meets first. Prints the counts;
--list also prints each component and each pair. Exit 0 always: this measures, check-layers.sh
refuses."""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*"([^"]+)"', re.M)


def modules(root):
    """Maps each module name ("scene/scene") to the files it is made of."""
    mods = {}
    for folder, _, files in os.walk(os.path.join(root, "host")):
        for name in files:
            stem, ext = os.path.splitext(name)
            if ext not in (".c", ".cc", ".h"):
                continue
            rel = os.path.relpath(os.path.join(folder, stem), os.path.join(root, "host"))
            mods.setdefault(rel, []).append(os.path.join(folder, name))
    return mods


def edges(mods):
    """Module -> the set of other modules whose header it includes."""
    graph = {}
    for mod, files in mods.items():
        deps = set()
        for path in files:
            with open(path, encoding="utf-8", errors="replace") as f:
                for inc in INCLUDE.findall(f.read()):
                    dep = os.path.splitext(inc)[0]
                    if dep in mods and dep != mod:
                        deps.add(dep)
        graph[mod] = deps
    return graph


def components(graph):
    """Tarjan's strongly connected components, iterative (no recursion limit to meet)."""
    index, low, on_stack, stack, out = {}, {}, set(), [], []
    counter = [0]
    for start in sorted(graph):
        if start in index:
            continue
        work = [(start, iter(sorted(graph[start])))]
        index[start] = low[start] = counter[0]; counter[0] += 1
        stack.append(start); on_stack.add(start)
        while work:
            node, it = work[-1]
            nxt = next(it, None)
            if nxt is not None:
                if nxt not in index:
                    index[nxt] = low[nxt] = counter[0]; counter[0] += 1
                    stack.append(nxt); on_stack.add(nxt)
                    work.append((nxt, iter(sorted(graph[nxt]))))
                elif nxt in on_stack:
                    low[node] = min(low[node], index[nxt])
                continue
            work.pop()
            if work:
                low[work[-1][0]] = min(low[work[-1][0]], low[node])
            if low[node] == index[node]:
                comp = []
                while True:
                    top = stack.pop(); on_stack.discard(top); comp.append(top)
                    if top == node:
                        break
                out.append(sorted(comp))
    return out


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    root = args[0] if args else "."
    graph = edges(modules(root))
    circles = [c for c in components(graph) if len(c) > 1]
    pairs = sorted({tuple(sorted((a, b))) for a in graph for b in graph[a] if a in graph[b]})
    if "--list" in sys.argv:
        for comp in sorted(circles):
            print("circle of %d: %s" % (len(comp), " ".join(comp)))
        for a, b in pairs:
            print("2-circle: %s <-> %s" % (a, b))
    print("include-graph: %d modules, %d circles (%d modules in them), %d 2-circles"
          % (len(graph), len(circles), sum(len(c) for c in circles), len(pairs)))


if __name__ == "__main__":
    main()
