#!/usr/bin/python3
"""Side-by-side FCLib benchmark: fracas-fclib against Siconos NSGS (Debian python3-siconos).

Every problem of the FCLib folder is solved from r = 0 by both solvers at each
tolerance on the paper error ||F(r)||/||q|| (reference/fclib_siconos.md §2.1), and
both answers are judged by the same neutral script (../shared/fclib/tools/fc_error.py,
as eval_solution.py). Siconos runs with its --paper-tol protocol (tighten its own
tolerance until the paper error meets the target; time of the final run only).

Outputs (in --out, default bench/results/fclib): runs.csv (one row per problem,
tolerance and solver), curves.csv (error after k sweeps, both solvers), and with
--plots the PNGs doc/img/bench_fclib_profile_<tol>.png, doc/img/bench_fclib_curves.png,
and with --doc the tables in doc/benchmarks.md (between the fclib markers).

  build/release/bin/fracas-python tools/bench/fclib_bench.py --fracas build/release/bin/fracas-fclib --plots --doc
  build/release/bin/fracas-python tools/bench/fclib_bench.py --ours-only --variants "plain=--accel 0" --tols 1e-8   # quick look
"""
import argparse
import csv
import glob
import math
import os
import re
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
FCLIB = os.path.normpath(os.path.join(ROOT, '..', 'shared', 'fclib'))


def load_tools(fclib_dir):
    sys.path.insert(0, os.path.join(fclib_dir, 'tools'))
    global fclib_io, fc_error
    import fclib_io  # noqa: F401
    import fc_error  # noqa: F401


def judge(d, r):
    e = fc_error.natural_map_error(d['W'], d['q'], d['mu'], r, d['dim'])
    return e['paper'], e['onepq']


# ------------------------------------------------------------------ ours

RESULT = re.compile(r'(\w+)=\s*(\S+)')


def run_ours(exe, path, tol, extra, max_sweeps, time_limit, repeat, rfile):
    cmd = [exe, '-q', '--err-tol', '%g' % tol, '--max-sweeps', str(max_sweeps), '--time-limit', '%g' % time_limit,
           '--repeat', str(repeat), '--output', rfile] + extra + [path]
    out = subprocess.run(cmd, capture_output=True, text=True, check=True).stdout
    line = [ln for ln in out.splitlines() if ln.startswith('result ')][-1]
    kv = dict(RESULT.findall(line))
    return {'iter': int(kv['sweeps']), 'time_s': float(kv['time_s']), 'own_err_paper': float(kv['err_paper'])}


def curve_ours(exe, path, extra, max_sweeps, time_limit, hfile, repeat=3):
    """Error after k sweeps from one run (errors are not timed); short runs are
    repeated and the fastest time at each k kept."""
    best = {}
    for _ in range(repeat):
        cmd = [exe, '-q', '--err-tol', '1e-12', '--max-sweeps', str(max_sweeps), '--time-limit', '%g' % time_limit,
               '--history', hfile] + extra + [path]
        subprocess.run(cmd, capture_output=True, text=True, check=True)
        pts = [(int(r['sweeps']), float(r['time_s']), float(r['err_paper'])) for r in csv.DictReader(open(hfile))]
        for k, t, e in pts:
            if k not in best or t < best[k][1]:
                best[k] = (k, t, e)
        if pts and pts[-1][1] > 1.0:
            break
    return [best[k] for k in sorted(best)]


# ------------------------------------------------------------------ Siconos

def siconos_setup():
    import warnings
    warnings.filterwarnings('ignore', message='Performance warning')
    global siconos_peer, sn
    import siconos_peer  # noqa: F401  (from ../shared/fclib/tools)
    import siconos.numerics as sn  # noqa: F401
    sn.numerics_set_verbose(0)


def run_siconos_eval(P, d, tol, itermax, repeat_below, ev):
    """Paper-tol protocol: Siconos' own tolerance is tightened until ||F||/||q|| <= tol."""
    stol = tol
    for _attempt in range(8):
        best = None
        for k in range(3):
            res = siconos_peer.solve_once(P, d, stol, itermax, ev)
            if best is None or res['time'] < best['time']:
                best = res
            if res['time'] > repeat_below:
                break
        ep, _ = judge(d, best['r'])
        if ep <= tol or best['info'] != 0 or stol < 1e-300:
            break
        stol = stol * 0.5 * tol / ep
    return {'iter': best['iter'], 'time_s': best['time'], 'r': best['r'], 'siconos_tol': stol, 'info': best['info'],
            'err': ep, 'eval': ev}


def run_siconos(P, d, tol, itermax, repeat_below):
    """Siconos' best configuration: in 3-D both error evaluations (FULL, the peer's
    default, and LIGHT_WITH_FULL_FINAL, Siconos' own default) are run and the
    faster one that meets tol kept (else the more accurate one); 2-D has only the latter."""
    evals = ['full', 'lightfull'] if d['dim'] == 3 else ['lightfull']
    runs = [run_siconos_eval(P, d, tol, itermax, repeat_below, ev) for ev in evals]
    ok = [r for r in runs if r['err'] <= tol]
    if ok:
        return min(ok, key=lambda r: r['time_s'])
    return min(runs, key=lambda r: r['err'])


def curve_siconos(P, d, itermax):
    """Siconos runs exactly k sweeps (tol 0, light evaluation) for k = 1, 2, 5, 10, ...;
    runs shorter than 0.1 s are repeated (best of 3)."""
    pts, k = [], 1
    ks = []
    while k <= itermax:
        for m in (1, 2, 5):
            if m * k <= itermax:
                ks.append(m * k)
        k *= 10
    for k in ks:
        best = None
        for _ in range(3):
            res = siconos_peer.solve_once(P, d, 0.0, k, 'light')
            if best is None or res['time'] < best['time']:
                best = res
            if res['time'] > 0.1:
                break
        ep, _ = judge(d, best['r'])
        pts.append((k, best['time'], ep))
        if ep < 1e-12:
            break
    return pts


# ------------------------------------------------------------------ main

def short(name):
    return re.sub(r'\.(dat|cond)$', '', name.replace('.hdf5', ''))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--fracas', default=os.path.join(ROOT, 'build', 'release', 'bin', 'fracas-fclib'))
    ap.add_argument('--fclib', default=FCLIB, help='folder holding local/ and tools/')
    ap.add_argument('--problems', nargs='*', help='problem files (default: every local/*.hdf5)')
    ap.add_argument('--tols', default='1e-4,1e-8')
    ap.add_argument('--variants', default='fracas=;fracas-plain=--accel 0',
                    help='our solver variants, "label=options;label=options" (first one is compared in the tables)')
    ap.add_argument('--max-sweeps', type=int, default=100000)
    ap.add_argument('--time-limit', type=float, default=30.0, help='per run, both solvers (s)')
    ap.add_argument('--repeat', type=int, default=3, help='best of N for runs shorter than 1 s')
    ap.add_argument('--ours-only', action='store_true')
    ap.add_argument('--no-curves', action='store_true')
    ap.add_argument('--out', default=os.path.join(ROOT, 'bench', 'results', 'fclib'))
    ap.add_argument('--plots', action='store_true', help='write doc/img/bench_fclib_*.png')
    ap.add_argument('--doc', action='store_true', help='update the tables of doc/benchmarks.md')
    a = ap.parse_args()
    load_tools(a.fclib)
    if not a.ours_only:
        siconos_setup()
    os.makedirs(a.out, exist_ok=True)
    tols = [float(t) for t in a.tols.split(',')]
    files = a.problems or sorted(glob.glob(os.path.join(a.fclib, 'local', '*.hdf5')))
    variants = [(v.split('=', 1)[0], v.split('=', 1)[1].split()) for v in a.variants.split(';') if v]
    tmp = tempfile.mkdtemp(prefix='fclib_bench_')
    rows, curves = [], []
    t_start = time.time()
    for f in files:
        name = os.path.basename(f)
        d = fclib_io.read(f)
        P = None if a.ours_only else siconos_peer.build_problem(d)
        # Siconos: sweeps allowed within the time limit (estimated from a short run)
        sic_itermax = a.max_sweeps
        if P is not None:
            probe = siconos_peer.solve_once(P, d, 0.0, 50, 'full')
            per_it = max(probe['time'] / max(1, probe['iter']), 1e-9)
            sic_itermax = int(min(a.max_sweeps, a.time_limit / per_it))
        for tol in tols:
            rfile = os.path.join(tmp, 'r.txt')
            line = '%-44s tol=%.0e' % (short(name), tol)
            for label, extra in variants:
                # a quick run decides whether repeats are worth it
                o = run_ours(a.fracas, f, tol, extra, a.max_sweeps, a.time_limit, 1, rfile)
                if o['time_s'] < 1.0 and a.repeat > 1:
                    o = run_ours(a.fracas, f, tol, extra, a.max_sweeps, a.time_limit, a.repeat, rfile)
                ep, eo = judge(d, np.loadtxt(rfile).ravel())
                rows.append({'file': name, 'dim': d['dim'], 'nc': d['nc'], 'tol': tol, 'solver': label,
                             'iter': o['iter'], 'time_s': o['time_s'], 'err_paper': ep, 'err_onepq': eo,
                             'solved': int(ep <= tol), 'siconos_eval': ''})
                line += ' | %s it=%6d t=%.2e err=%.1e' % (label, o['iter'], o['time_s'], ep)
            if P is not None:
                s = run_siconos(P, d, tol, sic_itermax, 1.0)
                ep2, eo2 = judge(d, s['r'])
                rows.append({'file': name, 'dim': d['dim'], 'nc': d['nc'], 'tol': tol, 'solver': 'siconos',
                             'iter': s['iter'], 'time_s': s['time_s'], 'err_paper': ep2, 'err_onepq': eo2,
                             'solved': int(ep2 <= tol), 'siconos_eval': s['eval']})
                line += ' | siconos(%s) it=%6d t=%.2e err=%.1e' % (s['eval'], s['iter'], s['time_s'], ep2)
            print(line, flush=True)
        if not a.no_curves:
            hfile = os.path.join(tmp, 'h.csv')
            for label, extra in variants:
                for k, t, e in curve_ours(a.fracas, f, extra, 20000, min(10.0, a.time_limit), hfile):
                    curves.append({'file': name, 'solver': label, 'sweeps': k, 'time_s': t, 'err_paper': e})
            if P is not None:
                for k, t, e in curve_siconos(P, d, min(20000, max(10, sic_itermax // 3))):
                    curves.append({'file': name, 'solver': 'siconos', 'sweeps': k, 'time_s': t, 'err_paper': e})
    print('total benchmark time %.0f s' % (time.time() - t_start))
    write_csv(os.path.join(a.out, 'runs.csv'), rows)
    if curves:
        write_csv(os.path.join(a.out, 'curves.csv'), curves)
    if a.plots:
        plots(rows, curves, tols)
    if a.doc:
        doc_tables(rows, tols, [v[0] for v in variants])


def write_csv(path, rows):
    keys = list(rows[0].keys())
    with open(path, 'w', newline='') as fh:
        w = csv.DictWriter(fh, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)


def by_key(rows):
    t = {}
    for r in rows:
        t[(r['file'], float(r['tol']), r['solver'])] = r
    return t


def ratio_stats(rows, tol, label='fracas'):
    """Time ratio label / Siconos on the problems both solve at tol."""
    t = by_key(rows)
    ratios = []
    for (f, tl, s), r in t.items():
        if s != label or tl != tol:
            continue
        o = t.get((f, tl, 'siconos'))
        if o and int(r['solved']) and int(o['solved']) and float(o['time_s']) > 0:
            ratios.append((float(r['time_s']) / float(o['time_s']), f))
    return sorted(ratios)


COLORS = {'fracas': 'C0', 'fracas-plain': 'C1', 'siconos': 'C3'}


def plots(rows, curves, tols):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    img = os.path.join(ROOT, 'doc', 'img')
    os.makedirs(img, exist_ok=True)
    t = by_key(rows)
    files = sorted({r['file'] for r in rows})
    solvers = sorted({r['solver'] for r in rows})
    for tol in tols:
        fig, ax = plt.subplots(figsize=(6, 4))
        times = {s: {f: (float(t[(f, tol, s)]['time_s']) if int(t[(f, tol, s)]['solved']) else math.inf)
                     for f in files} for s in solvers}
        best = {f: min(times[s][f] for s in solvers) for f in files}
        taus = np.logspace(0, 3, 400)
        for s in solvers:
            rho = [sum(1 for f in files if math.isfinite(best[f]) and times[s][f] <= tau * max(best[f], 1e-12))
                   / len(files) for tau in taus]
            ax.step(taus, rho, where='post', label=s, color=COLORS.get(s, 'C2'))
        ax.set_xscale('log')
        ax.set_ylim(0, 1.02)
        ax.set_xlabel('τ (time / best time)')
        ax.set_ylabel('ρ(τ): share of problems solved within τ·best')
        ax.set_title('Dolan–Moré profile, %d FCLib problems, ‖F‖/‖q‖ ≤ %g' % (len(files), tol))
        ax.grid(True, which='both', alpha=0.3)
        ax.legend(loc='lower right')
        fig.tight_layout()
        fig.savefig(os.path.join(img, 'bench_fclib_profile_%s.png' % tol_tag(tol)), dpi=110)
        plt.close(fig)
    if curves:
        cf = sorted({c['file'] for c in curves})
        ncol = 4
        nrow = (len(cf) + ncol - 1) // ncol
        fig, axes = plt.subplots(nrow, ncol, figsize=(4 * ncol, 2.8 * nrow))
        for ax, f in zip(axes.ravel(), cf):
            for s in solvers:
                pts = sorted((float(c['time_s']), max(float(c['err_paper']), 1e-17))
                             for c in curves if c['file'] == f and c['solver'] == s)
                if pts:
                    ax.loglog([p[0] for p in pts], [p[1] for p in pts], '.-', ms=3, lw=1,
                              label=s, color=COLORS.get(s, 'C2'))
            for tol in tols:
                ax.axhline(tol, color='grey', lw=0.6, ls=':')
            ax.set_title(short(f), fontsize=8)
            ax.tick_params(labelsize=7)
            ax.grid(True, which='major', alpha=0.3)
        for ax in axes.ravel()[len(cf):]:
            ax.axis('off')
        axes.ravel()[0].legend(fontsize=7)
        fig.supxlabel('solve time (s)')
        fig.supylabel('‖F(r)‖/‖q‖')
        fig.tight_layout()
        fig.savefig(os.path.join(img, 'bench_fclib_curves.png'), dpi=90)
        plt.close(fig)


def tol_tag(tol):
    return ('%.0e' % tol).replace('-0', 'm').replace('-', 'm')


def fmt_t(x):
    return '%.2e' % x


def doc_tables(rows, tols, labels):
    t = by_key(rows)
    files = sorted({r['file'] for r in rows})
    solvers = labels + ['siconos']
    out = []
    for tol in tols:
        out.append('\n#### ‖F‖/‖q‖ ≤ %.0e\n' % tol)
        head = '| problem | dim | nc |'
        for s in solvers:
            head += ' %s sweeps | time (s) | error |' % s
        for s in labels:
            head += ' %s / Siconos |' % s
        out.append(head)
        out.append('|' + '---|' * (3 + 3 * len(solvers) + len(labels)))
        for f in files:
            o = t[(f, tol, labels[0])]
            cells = [short(f), str(o['dim']), str(o['nc'])]
            for s in solvers:
                r = t.get((f, tol, s))
                if r is None:
                    cells += ['', '', '']
                    continue
                mark = '' if int(r['solved']) else ' ✗'
                it = str(r['iter'])
                if s == 'siconos' and r.get('siconos_eval') == 'lightfull' and str(r['dim']) == '3':
                    it += ' L'
                cells += [it, fmt_t(float(r['time_s'])), '%.1e%s' % (float(r['err_paper']), mark)]
            sic = t.get((f, tol, 'siconos'))
            for s in labels:
                r = t[(f, tol, s)]
                if sic and int(r['solved']) and int(sic['solved']):
                    cells.append('%.2f' % (float(r['time_s']) / max(float(sic['time_s']), 1e-12)))
                elif int(r['solved']):
                    cells.append('only %s' % s)
                elif sic and int(sic['solved']):
                    cells.append('only Siconos')
                else:
                    cells.append('neither')
            out.append('| ' + ' | '.join(cells) + ' |')
        out.append('')
        for s in labels:
            rs = ratio_stats(rows, tol, s)
            solved = sum(int(t[(f, tol, s)]['solved']) for f in files)
            sic = sum(int(t[(f, tol, 'siconos')]['solved']) for f in files if (f, tol, 'siconos') in t)
            if rs:
                out.append('- %s / Siconos time ratio over the %d problems both solve: **median %.2f**, '
                           'worst %.2f (%s), best %.3f (%s). Solved: %s %d/%d, Siconos %d/%d.'
                           % (s, len(rs), statistics.median([x for x, _ in rs]), rs[-1][0], short(rs[-1][1]),
                              rs[0][0], short(rs[0][1]), s, solved, len(files), sic, len(files)))
        if len(labels) > 1:
            slower = [(float(t[(f, tol, labels[0])]['time_s']) / float(t[(f, tol, labels[1])]['time_s']), f)
                      for f in files if int(t[(f, tol, labels[0])]['solved']) and int(t[(f, tol, labels[1])]['solved'])
                      and float(t[(f, tol, labels[0])]['time_s']) > float(t[(f, tol, labels[1])]['time_s'])]
            if slower:
                out.append('- %s slower than %s on: %s.' % (labels[0], labels[1], ', '.join(
                    '%s (×%.2f)' % (short(f), x) for x, f in sorted(slower, reverse=True))))
    text = '\n'.join(out)
    path = os.path.join(ROOT, 'doc', 'benchmarks.md')
    doc = open(path).read()
    b, e = '<!-- fclib-tables:begin -->', '<!-- fclib-tables:end -->'
    i, j = doc.index(b) + len(b), doc.index(e)
    open(path, 'w').write(doc[:i] + '\n' + text + '\n' + doc[j:])


if __name__ == '__main__':
    main()
