"""What the benchmark plots (tools/plot_*_bench.py) share: reading the records, grouping rows,
labelling the axes and saving a figure, so every plot reads the records and looks the same way.
Needs python3-matplotlib (tools/setup --plots).
"""
import json

import matplotlib

matplotlib.use("Agg")  # files only: no display needed
import matplotlib.pyplot as plt  # noqa: E402

# plt too: the plot scripts draw with the pyplot set up here, after the backend is chosen.
__all__ = ["groups", "label_axes", "load_records", "plt", "save"]


def load_records(paths):
    """The records of each benchmark (the name each record gives), in the order of `paths`."""
    records = {}
    for path in paths:
        with open(path) as f:
            record = json.load(f)
        records.setdefault(record["benchmark"], []).append(record)
    return records


def groups(rows, *keys):
    """(values of `keys`, the rows that have them) for each combination present, sorted."""
    values = sorted({tuple(r[k] for k in keys) for r in rows})
    return [(v, [r for r in rows if tuple(r[k] for k in keys) == v]) for v in values]


def label_axes(ax, xlabel, ylabel, title, log_x=True, log_y=True, title_size=None):
    """Log scales (unless told otherwise), the labels, the title and a small legend."""
    if log_x:
        ax.set_xscale("log")
    if log_y:
        ax.set_yscale("log")
    if xlabel:
        ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    # The title keeps matplotlib's own size unless one is asked for.
    ax.set_title(title, **({"fontsize": title_size} if title_size else {}))
    ax.legend(fontsize=7)


def save(fig, path, dpi):
    fig.tight_layout()
    fig.savefig(path, dpi=dpi)
