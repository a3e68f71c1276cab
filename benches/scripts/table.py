"""Turns the output of `cargo bench -p dynagen-bench` into the README's table:
median times and the ratio generic / generated, all from the same run."""
import re
import sys

UNITS = {"ns": 1.0, "µs": 1e3, "us": 1e3, "ms": 1e6}
times = {}
name = None
for line in open(sys.argv[1], encoding="utf-8"):
    m = re.match(r"^(\S+)\s+time:\s+\[\S+ \S+ (\S+) (\S+) ", line)
    if m:
        name = m.group(1)
    else:
        m = re.match(r"^\s+time:\s+\[\S+ \S+ (\S+) (\S+) ", line)
        if not m or name is None:
            if not line.startswith(" "):
                name = line.split()[0] if line.split() else None
            continue
        m = re.match(r"^\s+time:\s+\[\S+ \S+ (\S+) (\S+) ", line)
        times[name] = float(m.group(1)) * UNITS[m.group(2)]
        continue
    times[name] = float(m.group(2)) * UNITS[m.group(3)]

BASE = any(k.endswith("/gen_sc_base") for k in times)
VARIANTS = ["gen_std", "gen_sc", "gen_batched"] + (["gen_sc_base"] if BASE else [])
print("| robot | function | generic | gen_std | gen_sc (trig excluded) | gen_batched |" + (" gen_sc_base (fma and dispatch off) |" if BASE else ""))
print("| --- | --- | --- | --- | --- | --- |" + (" --- |" if BASE else ""))
for robot in ["ur5", "panda"]:
    for f, label in [("tau", "τ"), ("M", "M"), ("h", "h"), ("g", "g"), ("fd", "forward dynamics")]:
        base = times.get(f"{robot}/{f}/generic")
        if base is None:
            continue
        cells = [f"{base:.0f} ns"]
        for v in VARIANTS:
            t = times[f"{robot}/{f}/{v}"]
            cells.append(f"{t:.0f} ns ({base / t:.1f}x)")
        print(f"| {robot} | {label} | " + " | ".join(cells) + " |")
    s, b = times.get(f"{robot}/sincos/std_loop"), times.get(f"{robot}/sincos/sin_cos_all")
    if s and b:
        print(f"| {robot} | all sin/cos | loop of f64::sin_cos {s:.0f} ns | | | sin_cos_all {b:.0f} ns ({s / b:.2f}x) |")
    s, b = times.get(f"{robot}/sincos/std_loop_f32"), times.get(f"{robot}/sincos/sin_cos_all_f32")
    if s and b:
        print(f"| {robot} | all sin/cos, f32 | loop of f32::sin_cos {s:.0f} ns | | | sin_cos_array_f32 {b:.0f} ns ({s / b:.2f}x) |")
