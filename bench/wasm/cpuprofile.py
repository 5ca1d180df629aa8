#!/usr/bin/env python3
"""Sums a V8 CPU profile (`node --cpu-prof`) of the viewer's WebAssembly by function.

    python3 bench/wasm/cpuprofile.py PROFILE.cpuprofile [TOP]

Prints the TOP (25) functions by their own samples, as a share of all samples, with
the Rust names demangled (legacy `_ZN…17h<hash>E` symbols, the hash dropped) and
under the nearest caller that is neither rayon's plumbing nor a generic `dispatch`:
the module has several `simd::dispatch` instances (setup's, the bands'), and the
caller tells them apart. Used by profile.sh; needs a module built with its names.
"""

import collections
import json
import re
import sys

ESCAPES = {
    "$SP$": "@", "$BP$": "*", "$RF$": "&", "$LT$": "<", "$GT$": ">", "$LP$": "(",
    "$RP$": ")", "$C$": ",", "$u20$": " ", "$u27$": "'", "$u5b$": "[", "$u5d$": "]",
    "$u7b$": "{", "$u7d$": "}", "$u7e$": "~",
}


def demangle(symbol):
    """The path of a legacy-mangled Rust symbol, or the symbol as given."""
    if not (symbol.startswith("_ZN") and symbol.endswith("E")):
        return symbol
    body, parts, i = symbol[3:-1], [], 0
    while i < len(body) and body[i].isdigit():
        j = i
        while body[j].isdigit():
            j += 1
        n = int(body[i:j])
        parts.append(body[j:j + n])
        i = j + n
    if parts and re.fullmatch(r"h[0-9a-f]{16}", parts[-1]):
        parts.pop()
    out = []
    for part in parts:
        if part.startswith("_$"):
            part = part[1:]
        for code, text in ESCAPES.items():
            part = part.replace(code, text)
        out.append(part.replace("..", "::"))
    return "::".join(out)


def uninformative(name):
    return name.startswith(("rayon", "rayon_core")) or name.endswith("simd::dispatch") or not name


def main():
    profile = json.load(open(sys.argv[1]))
    top = int(sys.argv[2]) if len(sys.argv) > 2 else 25
    nodes = {n["id"]: n for n in profile["nodes"]}
    parent = {c: n["id"] for n in profile["nodes"] for c in n.get("children", [])}
    name = {i: demangle(n["callFrame"]["functionName"]) for i, n in nodes.items()}
    own = collections.Counter()
    total = 0
    for i, n in nodes.items():
        hits = n.get("hitCount", 0)
        total += hits
        if not hits:
            continue
        caller = parent.get(i)
        while caller is not None and uninformative(name[caller]):
            caller = parent.get(caller)
        under = name[caller] if caller is not None else ""
        own[(name[i] or "(" + n["callFrame"]["url"][-40:] + ")", under)] += hits
    print(f"{total} samples; own share, function, and the nearest informative caller")
    for (function, under), hits in own.most_common(top):
        print(f"{100 * hits / total:5.1f} %  {function[:90]}" + (f"\n          under {under[:100]}" if under else ""))


if __name__ == "__main__":
    main()
