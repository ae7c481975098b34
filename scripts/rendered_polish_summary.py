#!/usr/bin/env python3
# The summary table of bench_rendered_polish output (docs/accuracy.md, "The rendered polish"):
#   scripts/rendered_polish_summary.py OUTPUT.txt
import re,sys
rows=[]
for l in open(sys.argv[1]):
    m=re.search(r'^(\S+)\s+(\S+)\s+(\S+)\s+S\s+([\d.-]+) ->\s+([\d.-]+) \(\s*([\d.]+) dB\s+([\d.]+)% ->\s+([\d.]+) dB\s+([\d.]+)%\)\s+hold S\s+([\d.-]+) ->\s+([\d.-]+).*solve cpu (\d+) -> (\d+)',l)
    if m: rows.append([m.group(1),m.group(2),m.group(3)]+[float(x) for x in m.groups()[3:]])
n=len(rows)
def col(i): return [r[i] for r in rows]
S0,S1,P0,M0,P1,M1,H0,H1,c0,c1=[col(i) for i in range(3,13)]
import statistics as st
print(f"n={n}")
print(f"S mean {st.mean(S0):.2f} -> {st.mean(S1):.2f}; holdout S {st.mean(H0):.2f} -> {st.mean(H1):.2f}")
print(f"PSNR mean {st.mean(P0):.2f} -> {st.mean(P1):.2f}; min {min(P0):.2f} -> {min(P1):.2f}")
print(f"median lum: median {st.median(M0):.1f} -> {st.median(M1):.1f}; worst {max(M0):.1f} -> {max(M1):.1f}")
print(f">=30 dB {sum(p>=30 for p in P0)} -> {sum(p>=30 for p in P1)}; <=15% {sum(m<=15 for m in M0)} -> {sum(m<=15 for m in M1)}")
print(f"S lower: {sum(b<a-1e-9 for a,b in zip(S0,S1))}; holdout S lower by >0.1: {sum(b<a-0.1 for a,b in zip(H0,H1))}, min holdout gain {min(b-a for a,b in zip(H0,H1)):.2f}")
print(f"solve cpu per table (all candidates) median {st.median(c0):.0f} -> {st.median(c1):.0f} ms")
from collections import Counter
print("chosen plain", Counter(r[1] for r in rows).most_common())
print("chosen polished", Counter(r[2] for r in rows).most_common())
