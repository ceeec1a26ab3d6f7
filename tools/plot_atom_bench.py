#!/usr/bin/python3
"""Plots of the electron-cloud benchmarks (masav bench atom|scatter|light|raymarch).

usage: tools/plot_atom_bench.py OUT_PREFIX RECORD.json...
  reads the records (each names its benchmark: atom, scatter, light, raymarch) and writes
  OUT_PREFIX_table23.png (our times beside the thesis's Table 2.3 and its 32-37 ms raymarch)
  and OUT_PREFIX_error.png (run time against error for each accuracy knob).
Needs python3-matplotlib (tools/setup --plots).
"""
import sys

from plot_common import groups, label_axes, load_records, plt, save


def label(row):
    return f"{row['backend']} ({row['device'][:28]})"


def plot_states(ax, rows, thesis, key, ylabel, title):
    """Our times (`key`, ms) per Table 2.3 state, a line per backend, beside the thesis's
    (`thesis`: its seconds' key, line style and label for each)."""
    states = [r["state"] for r in rows if r["backend"] == rows[0]["backend"]]
    x = range(len(states))
    for seconds, style, name in thesis:
        ms = {r["state"]: r[seconds] * 1e3 for r in rows}
        ax.plot(x, [ms[s] for s in states], style, label=name)
    for _, be_rows in groups(rows, "backend"):
        by_state = {r["state"]: r for r in be_rows}
        ax.plot(x, [by_state[s][key] for s in states], "-o", label=label(by_state[states[0]]))
    ax.set_xticks(list(x), [s.replace("state", "") for s in states])
    label_axes(ax, "state (thesis Table 2.3 particle counts)", ylabel, title, log_x=False)


def plot_tables(prefix, atom, light, ray):
    panels = [p for p in (atom, light, ray) if p]
    if not panels:
        return
    fig, axes = plt.subplots(1, len(panels), figsize=(6 * len(panels), 4.5), squeeze=False)
    axes = iter(axes[0])
    if atom:
        plot_states(next(axes), atom["rows"],
                    [("thesis_creation_s", "k--o", "thesis CPU (Core2 Duo)")], "median_ms",
                    "cloud creation, ms", "cloud creation")
    if light:
        plot_states(next(axes), light["rows"],
                    [("thesis_cpu_s", "k:o", "thesis CPU"),
                     ("thesis_gpu_s", "k--o", "thesis GPU (Quadro FX 5800)")],
                    "total_ms", "nebula lighting, ms", "lighting (Eq. 2.4-2.6)")
    if ray:
        ax = next(axes)
        names, values = [], []
        for r in ray["rows"]:
            names.append(f"{r['backend']}\n{r['volume']} {r['width']}x{r['height']}"
                         + ("" if r["skip_empty"] else "\nno skip"))
            values.append(r["median_ms"])
        ax.bar(range(len(values)), values)
        ax.axhspan(ray["thesis_ms_min"], ray["thesis_ms_max"], color="k", alpha=0.2,
                   label="thesis 32-37 ms (60^3)")
        ax.set_xticks(range(len(names)), names, fontsize=6)
        label_axes(ax, None, "ms per frame", "raymarch", log_x=False)
    save(fig, f"{prefix}_table23.png", 110)
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
        for (be,), be_rows in groups(rows, "backend"):
            pts = [r for r in be_rows if r[ekey] > 0]
            ax.plot([r[tkey] for r in pts], [r[ekey] for r in pts], "-o", label=be)
            for r in pts:
                ax.annotate(f"{r[knob]:g}", (r[tkey], r[ekey]), fontsize=6)
        label_axes(ax, "run time, ms", "error", title, title_size=8)
    save(fig, f"{prefix}_error.png", 110)
    print(f"wrote {prefix}_error.png")


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    prefix = sys.argv[1]
    # The latest record of each benchmark.
    records = {name: recs[-1] for name, recs in load_records(sys.argv[2:]).items()}
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
