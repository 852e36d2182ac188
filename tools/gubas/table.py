"""Markdown tables from results/surfgrav_exact.csv and results/gubas.csv (tools/gubas/run.sh).

python3 tools/gubas/table.py tools/gubas/results > tools/gubas/results/tables.md
"""
import csv
import sys
from pathlib import Path

results = Path(sys.argv[1])
exact = {r["config"]: r for r in csv.DictReader(open(results / "surfgrav_exact.csv"))}
rows = list(csv.DictReader(open(results / "gubas.csv")))
orders = sorted({int(r["order"]) for r in rows})


def us(seconds):
    return f"{float(seconds) * 1e6:.1f}"


def sci(x):
    return f"{float(x):.1e}"


print("## Relative error of GUBAS-RS against surfgrav's exact values\n")
print("Force: |ΔF|/|F|; torques: |ΔM|/max(|M|, |V|) (surfgrav's measure: an aligned pair has M = 0);"
      " energy: |ΔV|/|V|. At order 8 an ellipsoid pair has a second line: the same series with"
      " complete inertia integrals (`complete T`).\n")
head = "| configuration | surfgrav certified, agreement | " + " | ".join(
    f"order {n}: F / M_A / M_B / V" for n in orders) + " |"
print(head)
print("|" + "---|" * (2 + len(orders)))
for name, e in exact.items():
    cells = []
    for n in orders:
        got = [r for r in rows if r["config"] == name and int(r["order"]) == n]
        cell = []
        for r in got:
            tag = " (complete T)" if r["integrals"] == "complete" else ""
            cell.append(" / ".join(sci(r[k]) for k in (
                "force_error", "torque_a_error", "torque_b_error", "energy_error")) + tag)
        cells.append("<br>".join(cell) if cell else "—")
    print(f"| {name} | {e['certified']}, {sci(e['agreement'])} | " + " | ".join(cells) + " |")

print("\n## Time per evaluation (force + both torques + energy), one thread\n")
print("CPU time per evaluation, best of several batches (surfgrav: every thread of the process,"
      " with one rayon worker; GUBAS-RS: its one thread), wall time in parentheses: on a shared"
      " machine the wall time also counts the waits for a core.\n")
print("| configuration | surfgrav µs (1e-12; evaluations) | "
      + " | ".join(f"GUBAS order {n} µs" for n in orders) + " |")
print("|" + "---|" * (2 + len(orders)))
for name, e in exact.items():
    cells = []
    for n in orders:
        got = [r for r in rows if r["config"] == name and int(r["order"]) == n
               and r["integrals"] == "shipped"]
        cells.append(f"{us(got[0]['gubas_cpu_seconds'])} ({us(got[0]['gubas_seconds'])})"
                     if got else "—")
    print(f"| {name} | {us(e['cpu_seconds'])} ({us(e['seconds'])}); {e['evaluations']} | "
          + " | ".join(cells) + " |")
