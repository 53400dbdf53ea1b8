#!/usr/bin/env python3
"""Per-function instruction profile of a QEMU -d in_asm,exec,nochain log between the
executions of `marker_start` and `marker_end` (issue 31 investigation)."""
import sys, re, subprocess, bisect, collections
log, elf = sys.argv[1], sys.argv[2]
reps = int(sys.argv[3]) if len(sys.argv) > 3 else 1
syms = []
for line in subprocess.run(["llvm-nm", "-n", "-C", elf], capture_output=True, text=True).stdout.splitlines():
    parts = line.split(maxsplit=2)
    if len(parts) == 3 and parts[1] in "tTwW":
        syms.append((int(parts[0], 16) & ~1, parts[2]))
addrs = [a for a, _ in syms]
def sym(a):
    i = bisect.bisect_right(addrs, a) - 1
    return syms[i][1] if i >= 0 else "?"
tb = {}
pending = None
# Library routines (memcpy, memclr…) counted again under the function that called them.
callee_of = collections.Counter()
last_other = "?"
counting = False
per_addr = collections.Counter()
trace_re = re.compile(r"Trace \d+: 0x[0-9a-f]+ \[([0-9a-f]+)/([0-9a-f]+)/([0-9a-f]+)/([0-9a-f]+)\]")
with open(log) as f:
    for line in f:
        if line.startswith("IN:"):
            pending = []
            continue
        if pending is not None and line.startswith("0x"):
            pending.append(int(line.split(":")[0], 16))
            continue
        m = trace_re.match(line)
        if m:
            key = m.groups()
            if pending is not None:
                tb[key] = pending
                pending = None
            s = sym(int(key[1], 16))
            if s == "marker_start":
                counting = True
                continue
            if s == "marker_end":
                counting = False
                continue
            if counting:
                for a in tb[key]:
                    per_addr[a] += 1
                if "mem" in s and ("aeabi" in s or "compiler_builtins" in s):
                    callee_of[f"{s.split('::')[-1][:20]} <- {last_other[:90]}"] += len(tb[key])
                else:
                    last_other = s
per_fn = collections.Counter()
for a, n in per_addr.items():
    per_fn[sym(a)] += n
total = sum(per_fn.values())
print(f"total {total/reps:.0f} per evaluation ({total} over {reps})")
for name, n in per_fn.most_common(40):
    print(f"{n/reps:9.0f} {100*n/total:5.1f}%  {name[:150]}")

for name, n in callee_of.most_common(12):
    print(f"{n/reps:9.0f}  {name}")

# Per source line (innermost inlined frame) of the hottest addresses, and memcpy callers.
if len(sys.argv) > 4:
    addrs_sorted = sorted(per_addr)
    out = subprocess.run(["llvm-addr2line", "-e", elf, "-i", "-f", "-C"] + [hex(a) for a in addrs_sorted],
                         input="", capture_output=True, text=True).stdout
    # with -i, frames per address are separated ambiguously; use one call per address instead
    line_count = collections.Counter()
    for a in addrs_sorted:
        r = subprocess.run(["llvm-addr2line", "-e", elf, "-i", hex(a)], capture_output=True, text=True).stdout.split("\n")
        frames = [x for x in r if x.strip()]
        # innermost hcm-core frame, else innermost
        key = next((fr for fr in frames if "hcm-core" in fr or "hcm-firmware" in fr), frames[0] if frames else "?")
        key = re.sub(r".*/(hcm-core|hcm-firmware)/", r"\1/", key)
        key = re.sub(r" \(discriminator \d+\)", "", key)
        line_count[key] += per_addr[a]
    for k, n in line_count.most_common(int(sys.argv[4])):
        print(f"{n/reps:9.0f}  {k}")
