#!/usr/bin/env python3
"""Who calls __aeabi_memcpy*/memcpy between marker_start and marker_end, and how many
instructions those copies cost (issue 31)."""
import sys, re, subprocess, bisect, collections
log, elf, reps = sys.argv[1], sys.argv[2], int(sys.argv[3])
syms = []
for line in subprocess.run(["llvm-nm", "-n", elf], capture_output=True, text=True).stdout.splitlines():
    p = line.split(maxsplit=2)
    if len(p) == 3 and p[1] in "tTwW":
        syms.append((int(p[0], 16) & ~1, p[2]))
addrs = [a for a, _ in syms]
sym = lambda a: syms[bisect.bisect_right(addrs, a) - 1][1]
tb, pending, counting, prev = {}, None, False, None
cost = collections.Counter(); calls = collections.Counter()
caller = None
trace_re = re.compile(r"Trace \d+: 0x[0-9a-f]+ \[([0-9a-f]+)/([0-9a-f]+)/([0-9a-f]+)/([0-9a-f]+)\]")
for line in open(log):
    if line.startswith("IN:"): pending = []; continue
    if pending is not None and line.startswith("0x"): pending.append(int(line.split(":")[0], 16)); continue
    m = trace_re.match(line)
    if not m: continue
    key = m.groups()
    if pending is not None: tb[key] = pending; pending = None
    s = sym(int(key[1], 16))
    if s == "marker_start": counting = True; continue
    if s == "marker_end": counting = False; continue
    if not counting: prev = key; continue
    if "memcpy" in s:
        if prev and "memcpy" not in sym(int(prev[1], 16)):
            last = tb[prev][-1]
            caller = subprocess.run(["llvm-addr2line", "-e", elf, "-i", hex(last)], capture_output=True, text=True).stdout.split("\n")
            caller = " <- ".join(re.sub(r".*/(hcm-core|hcm-firmware|library)/", r"\1/", c) for c in caller[:3] if c.strip())
            calls[caller] += 1
        cost[caller] += len(tb[key])
    prev = key
for c, n in cost.most_common(12):
    print(f"{n/reps:7.0f} instr {calls[c]/reps:5.1f} calls  {c}")
