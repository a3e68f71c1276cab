#!/usr/bin/env python3
"""The compiled size of generated bodies, and where their bytes go.

A generated body longer than the core's micro-op cache runs at the rate the
decoders take bytes (about 67 bytes a ns on the EPYC VM; docs/performance.md,
"Long bodies: the front end"), so its size in bytes bounds its time, and is
deterministic where a timing is not.

    body_bytes.py BINARY [PATTERN]     sizes of the functions whose (mangled)
                                       name contains PATTERN (default
                                       avx2_fma), largest last
    body_bytes.py BINARY --breakdown SYMBOL
                                       one function's instructions by kind:
                                       spill stores and reloads (stack
                                       pointer), constants (rip-relative),
                                       stores and loads through other
                                       pointers, register arithmetic

BINARY is e.g. target/release/examples/floating after `cargo build --release
-p dynagen-bench --example floating`. Needs binutils (`nm`, `objdump`).
Not run in CI.
"""

import collections
import re
import subprocess
import sys


def sizes(binary, pattern):
    out = subprocess.run(["nm", "-S", "--size-sort", binary], capture_output=True, text=True, check=True).stdout
    for line in out.splitlines():
        parts = line.split()
        if len(parts) == 4 and pattern in parts[3]:
            print(f"{int(parts[1], 16):8d} {parts[3]}")


def kind(ins):
    stack_store = r"vmov\w*\s+%[xy]mm\d+,\s*-?(0x[0-9a-f]+)?\(%rsp\)"
    if re.match(stack_store, ins):
        return "spill store"
    if re.match(r"vmov\w*\s+-?(0x[0-9a-f]+)?\(%rsp\),\s*%[xy]mm", ins):
        return "reload"
    if "(%rsp)" in ins:
        return "arithmetic reading the stack"
    if "(%rip)" in ins:
        return "constant load" if ins.startswith("vmov") else "arithmetic reading a constant"
    if re.match(r"vmov\w*\s+%[xy]mm\d+,\s*-?(0x[0-9a-f]+)?\(%r\w+", ins):
        return "store (output, carry)"
    if re.search(r"\(%r\w+", ins):
        return "load or arithmetic reading an input"
    if ins.startswith("v"):
        return "register arithmetic"
    return "other"


def breakdown(binary, symbol):
    out = subprocess.run(
        ["objdump", "-d", "--no-show-raw-insn", "-M", "att", f"--disassemble={symbol}", binary],
        capture_output=True,
        text=True,
        check=True,
    ).stdout
    lines = [l for l in out.splitlines() if re.match(r"\s+[0-9a-f]+:\t", l)]
    addresses = [int(l.split(":")[0], 16) for l in lines]
    count, size = collections.Counter(), collections.Counter()
    for i, line in enumerate(lines[:-1]):
        k = kind(line.split("\t", 1)[1].strip())
        count[k] += 1
        size[k] += addresses[i + 1] - addresses[i]
    total = sum(size.values())
    print(f"{symbol}: {sum(count.values())} instructions, {total} bytes")
    for k, b in size.most_common():
        print(f"  {k:38s} {count[k]:6d} instructions {b:7d} bytes {b / count[k]:4.1f} a instruction {100 * b / total:3.0f} %")


def main():
    args = sys.argv[1:]
    if len(args) == 3 and args[1] == "--breakdown":
        breakdown(args[0], args[2])
    elif len(args) in (1, 2):
        sizes(args[0], args[1] if len(args) == 2 else "avx2_fma")
    else:
        sys.exit(__doc__)


if __name__ == "__main__":
    main()
