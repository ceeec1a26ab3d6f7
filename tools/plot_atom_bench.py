#!/usr/bin/python3
"""Plots of the electron-cloud benchmarks (masav bench atom|scatter|light|raymarch).

usage: tools/plot_atom_bench.py OUT_PREFIX RECORD.json...
  reads the records (each names its benchmark: atom, scatter, light, raymarch) and writes
  OUT_PREFIX_table23.png (our times beside the thesis's Table 2.3 and its 32-37 ms raymarch)
  and OUT_PREFIX_error.png (run time against error for each accuracy knob).
Needs python3-matplotlib (tools/setup --plots).
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(paths):
    records = {}
    for path in paths:
        with open(path) as f:
            record = json.load(f)
        records[record["benchmark"]] = record
    return records


def label(row):
    return f"{row['backend']} ({row['device'][:28]})"


def plot_tables(prefix, atom, light, ray):
    panels = [p for p in (atom, light, ray) if p]
    if not panels:
        return
    fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 4.5), squeeze=False)
    axes = axes[0]
    k = 0
    if atom:
        ax = axes[k]
        k += 1
        states = [r["state"] for r in atom["rows"] if r["backend"] == atom["rows"][0]["backend"]]
        x = range(len(states))
        thesis = {r["state"]: r["thesis_creation_s"] * 1e3 for r in atom["rows"]}
        ax.plot(x, [thesis[s] for s in states], "k--o", label="thesis CPU (Core2 Duo)")
        for be in sorted({r["backend"] for r in atom["rows"]}):
            rows = {r["state"]: r for r in atom["rows"] if r["backend"] == be}
            ax.plot(x, [rows[s]["median_ms"] for s in states], "-o", label=label(rows[states[0]]))
        ax.set_xticks(list(x), [s.replace("state", "") for s in states])
        ax.set_yscale("log")
        ax.set_xlabel("state (thesis Table 2.3 particle counts)")
        ax.set_ylabel("cloud creation, ms")
        ax.set_title("cloud creation")
        ax.legend(fontsize=7)
    if light:
        ax = axes[k]
        k += 1
        states = [r["state"] for r in light["rows"] if r["backend"] == light["rows"][0]["backend"]]
        x = range(len(states))
        gpu = {r["state"]: r["thesis_gpu_s"] * 1e3 for r in light["rows"]}
        cpu = {r["state"]: r["thesis_cpu_s"] * 1e3 for r in light["rows"]}
        ax.plot(x, [cpu[s] for s in states], "k:o", label="thesis CPU")
        ax.plot(x, [gpu[s] for s in states], "k--o", label="thesis GPU (Quadro FX 5800)")
        for be in sorted({r["backend"] for r in light["rows"]}):
            rows = {r["state"]: r for r in light["rows"] if r["backend"] == be}
            ax.plot(x, [rows[s]["total_ms"] for s in states], "-o", label=label(rows[states[0]]))
        ax.set_xticks(list(x), [s.replace("state", "") for s in states])
        ax.set_yscale("log")
        ax.set_xlabel("state (thesis Table 2.3 particle counts)")
        ax.set_ylabel("nebula lighting, ms")
        ax.set_title("lighting (Eq. 2.4-2.6)")
        ax.legend(fontsize=7)
    if ray:
        ax = axes[k]
        names, values = [], []
        for r in ray["rows"]:
            names.append(f"{r['backend']}\n{r['volume']} {r['width']}x{r['height']}"
                         + ("" if r["skip_empty"] else "\nno skip"))
            values.append(r["median_ms"])
        ax.bar(range(len(values)), values)
        ax.axhspan(ray["thesis_ms_min"], ray["thesis_ms_max"], color="k", alpha=0.2,
                   label="thesis 32-37 ms (60^3)")
        ax.set_xticks(range(len(names)), names, fontsize=6)
        ax.set_yscale("log")
        ax.set_ylabel("ms per frame")
        ax.set_title("raymarch")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{prefix}_table23.png", dpi=110)
    print(f"wrote {prefix}_table23.png")


def plot_errors(prefix, atom, scatter, light, ray):
    panels = []
    if atom:
        panels.append(("cloud: particles vs |<r^2>| error", atom["sweep"], "median_ms",
                       "rel_error_r2", "particles"))
    if scatter:
        panels.append(("scatter table: photons/row vs L1 to converged", scatter["sweep"], "ms",
                       "l1_vs_converged", "photons_per_row"))
        panels.append(("scatter: photons/row vs L1 to single scattering", scatter["sweep"], "ms",
                       "l1_vs_single_scattering", "photons_per_row"))
    if light:
        panels.append(("lighting: midpoint step (cells) vs rel L2", [
            r for r in light["sweep"] if r["path"] == "midpoint"], "ms", "rel_l2", "step_cells"))
    if ray:
        panels.append(("raymarch: step (voxels) vs opacity error", ray["sweep"], "ms",
                       "max_abs_error", "step_voxels"))
    if not panels:
        return
    fig, axes = plt.subplots(1, len(panels), figsize=(4.6 * len(panels), 4), squeeze=False)
    for ax, (title, rows, tkey, ekey, knob) in zip(axes[0], panels):
        for be in sorted({r["backend"] for r in rows}):
            pts = [r for r in rows if r["backend"] == be and r[ekey] > 0]
            ax.plot([r[tkey] for r in pts], [r[ekey] for r in pts], "-o", label=be)
            for r in pts:
                ax.annotate(f"{r[knob]:g}", (r[tkey], r[ekey]), fontsize=6)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("run time, ms")
        ax.set_ylabel("error")
        ax.set_title(title, fontsize=8)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(f"{prefix}_error.png", dpi=110)
    print(f"wrote {prefix}_error.png")


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    prefix = sys.argv[1]
    records = load(sys.argv[2:])
    atom, scatter = records.get("atom"), records.get("scatter")
    light, ray = records.get("light"), records.get("raymarch")
    if not any((atom, scatter, light, ray)):
        print("no atom, scatter, light or raymarch record among the files")
        return 1
    plot_tables(prefix, atom, light, ray)
    plot_errors(prefix, atom, scatter, light, ray)
    return 0


if __name__ == "__main__":
    sys.exit(main())
