#!/usr/bin/python3
"""Plot the NLGS kernel micro-benchmark (bench/kernel_bench.f90).

  build/release/bin/fracas-kernel-bench --csv bench/results/kernel_1.csv   # (a few times)
  build/release/bin/fracas-python tools/bench/kernel_plot.py doc/img/bench_kernel.png bench/results/kernel_*.csv

Several CSVs (runs at different moments) are merged keeping the fastest figure of each
configuration (other jobs on a shared machine only slow a run down); the merged table
is printed in markdown.

Updates per second per core against the number of contacts, one curve per
kernel and contact order; the anchors of reference/nscd_validation.md §4.2
(1.5e8 2D, 3.5e7 3D, ordered, another machine) as dashed lines.
"""
import csv
import sys

import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402


def main():
    png, srcs = sys.argv[1], sys.argv[2:]
    best = {}
    for src in srcs:
        for r in csv.DictReader(open(src)):
            key = (r['dim'], r['kernel'], r['order'], r['contacts'])
            if key not in best or float(r['updates_per_s']) > float(best[key]['updates_per_s']):
                best[key] = r
    rows = [best[k] for k in sorted(best, key=lambda k: (k[0], k[1], int(k[3]), k[2]))]
    print('| dim | kernel | contacts | order | ns/update | updates/s | data (MB) |')
    print('|---|---|---|---|---|---|---|')
    for r in rows:
        print('| %s | %s | %s | %s | %.1f | %.2e | %s |' % (r['dim'], r['kernel'], r['contacts'], r['order'],
                                                          float(r['ns_per_update']), float(r['updates_per_s']),
                                                          r['data_mb']))
    fig, axes = plt.subplots(1, 2, figsize=(11, 4), sharey=True)
    style = {'ordered': '-o', 'coloured': '-s', 'shuffled': '--^'}
    colour = {'gs_sweep_2d': 'C0', 'packed_2d': 'C2', 'gs3d': 'C1'}
    for ax, dim, anchor in ((axes[0], '2', 1.5e8), (axes[1], '3', 3.5e7)):
        for kernel in sorted({r['kernel'] for r in rows if r['dim'] == dim}):
            for order in ('ordered', 'coloured', 'shuffled'):
                pts = sorted((int(r['contacts']), float(r['updates_per_s'])) for r in rows
                             if r['dim'] == dim and r['kernel'] == kernel and r['order'] == order)
                if pts:
                    ax.loglog([p[0] for p in pts], [p[1] for p in pts], style[order], color=colour.get(kernel, 'C4'),
                              label='%s, %s' % (kernel, order), ms=4)
        ax.axhline(anchor, color='grey', ls=':', label='anchor §4.2 (ordered, other machine)')
        ax.set_title('%sD lattice (%s)' % (dim, 'triangular, disks' if dim == '2' else 'simple cubic, spheres'))
        ax.set_xlabel('contacts')
        ax.grid(True, which='both', alpha=0.3)
        ax.legend(fontsize=7)
    axes[0].set_ylabel('contact updates per second (one core)')
    fig.tight_layout()
    fig.savefig(png, dpi=100)


if __name__ == '__main__':
    main()
