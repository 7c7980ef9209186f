#!/usr/bin/python3
"""fracas-fclib checks against the neutral Python judge and on rewritten files.

  check_fclib.py evaluator FRACAS_FCLIB PROBLEM FCLIB_TOOLS WORKDIR
      solve 20 sweeps (an unconverged r, so the error is far from round-off), write r;
      our printed errors (solve and --evaluate) must equal fc_error.py's to 1e-10 (and
      eval_solution.py's, which prints 7 digits, to 1e-6).
  check_fclib.py storage FRACAS_FCLIB PROBLEM WORKDIR
      W rewritten as CSC and as shuffled triplets with split duplicate entries:
      the result line (sweeps, errors) must be the same as with the original CSR.
  check_fclib.py errors FRACAS_FCLIB GLOBAL_PROBLEM WORKDIR
      bad inputs stop with status 1 and a message naming the file and what was expected.
"""
import os
import re
import subprocess
import sys

import numpy as np

RESULT = re.compile(r'(\w+)=\s*(\S+)')


def result(exe, args):
    out = subprocess.run([exe, '-q'] + args, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit('fracas-fclib failed: %s\n%s' % (' '.join(args), out.stderr))
    line = [ln for ln in out.stdout.splitlines() if ln.startswith(('result ', 'evaluate '))][-1]
    return dict(RESULT.findall(line))


def close(name, a, b, rtol):
    ok = abs(a - b) <= rtol * max(abs(a), abs(b), 1e-300)
    print('%s %s: fracas %.15e python %.15e (rtol %g)' % ('PASS' if ok else 'FAIL', name, a, b, rtol))
    return ok


def evaluator(exe, prob, tools, work):
    rfile = os.path.join(work, 'r_eval.txt')
    ours = result(exe, ['--err-tol', '0', '--max-sweeps', '20', '--output', rfile, prob])
    ev = result(exe, ['--evaluate', rfile, prob])
    # eval_solution.py prints 7 significant digits; fc_error.py (what it calls) gives all of them
    out = subprocess.run([sys.executable, os.path.join(tools, 'eval_solution.py'), prob, rfile],
                         capture_output=True, text=True, check=True).stdout
    py = dict(RESULT.findall(out))
    sys.path.insert(0, tools)
    import fclib_io
    import fc_error
    d = fclib_io.read(prob)
    full = fc_error.natural_map_error(d['W'], d['q'], d['mu'], np.loadtxt(rfile).ravel(), d['dim'])
    ok = True
    for k in ('abs', 'paper', 'onepq'):
        ok &= close('err_%s (solve) vs eval_solution.py' % k, float(ours['err_' + k]), float(py[k]), 1e-6)
        ok &= close('err_%s (solve) vs fc_error.py' % k, float(ours['err_' + k]), full[k], 1e-10)
        ok &= close('err_%s (--evaluate) vs fc_error.py' % k, float(ev['err_' + k]), full[k], 1e-10)
    return ok


def storage(exe, prob, work):
    import h5py
    base = result(exe, ['--err-tol', '1e-8', '--max-sweeps', '5000', prob])
    with h5py.File(prob, 'r') as h:
        g = h['fclib_local']
        m = int(g['W/m'][0])
        p, i, x = g['W/p'][:], g['W/i'][:], g['W/x'][:]
        assert int(g['W/nz'][0]) == -2, 'expected a CSR problem to rewrite'
        dim = g['spacedim'][:]
        q, mu = g['vectors/q'][:], g['vectors/mu'][:]
    rows = np.repeat(np.arange(m), np.diff(p))
    cols = i[:p[m]]
    vals = x[:p[m]]
    # CSC
    order = np.lexsort((rows, cols))
    cp = np.zeros(m + 1, dtype=np.int32)
    np.add.at(cp, cols + 1, 1)
    cp = np.cumsum(cp).astype(np.int32)
    # triplets: shuffled, the first 10 entries split in two halves (duplicates add up)
    rng = np.random.default_rng(3)
    perm = rng.permutation(len(vals))
    tr, tc, tv = rows[perm], cols[perm], vals[perm].copy()
    half = tv[:10] / 2
    tv[:10] -= half
    tr, tc, tv = np.concatenate([tr, tr[:10]]), np.concatenate([tc, tc[:10]]), np.concatenate([tv, half])
    variants = {'csc': (-1, cp, rows[order], vals[order]), 'triplet': (len(tv), tc, tr, tv)}
    ok = True
    for name, (nz, pp, ii, xx) in variants.items():
        path = os.path.join(work, 'W_%s.hdf5' % name)
        with h5py.File(path, 'w') as h:
            g = h.create_group('fclib_local')
            g['spacedim'] = dim
            w = g.create_group('W')
            for k, v in (('m', m), ('n', m), ('nz', nz), ('nzmax', len(xx))):
                w[k] = np.array([v], dtype=np.int32)
            w['p'] = np.asarray(pp, dtype=np.int32)
            w['i'] = np.asarray(ii, dtype=np.int32)
            w['x'] = np.asarray(xx, dtype=np.float64)
            g['vectors/q'] = q
            g['vectors/mu'] = mu
        res = result(exe, ['--err-tol', '1e-8', '--max-sweeps', '5000', path])
        same = res['sweeps'] == base['sweeps'] and res['converged'] == base['converged']
        print('%s %s: sweeps %s (CSR %s)' % ('PASS' if same else 'FAIL', name, res['sweeps'], base['sweeps']))
        ok &= same
        ok &= close('%s err_paper' % name, float(res['err_paper']), float(base['err_paper']), 1e-6)
    return ok


def errors(exe, global_prob, work):
    text = os.path.join(work, 'not_hdf5.hdf5')
    open(text, 'w').write('this is not HDF5\n')
    cases = [(global_prob, 'fclib_global'), (text, 'not an HDF5 file'),
             (os.path.join(work, 'missing.hdf5'), 'no such file')]
    ok = True
    for path, want in cases:
        out = subprocess.run([exe, path], capture_output=True, text=True)
        good = out.returncode == 1 and path in out.stderr and want in out.stderr
        print('%s bad input %s: status %d, message: %s' % ('PASS' if good else 'FAIL', os.path.basename(path),
                                                           out.returncode, out.stderr.strip()))
        ok &= good
    return ok


def main():
    what = sys.argv[1]
    work = sys.argv[-1]
    os.makedirs(work, exist_ok=True)
    if what == 'evaluator':
        ok = evaluator(sys.argv[2], sys.argv[3], sys.argv[4], work)
    elif what == 'storage':
        ok = storage(sys.argv[2], sys.argv[3], work)
    else:
        ok = errors(sys.argv[2], sys.argv[3], work)
    sys.exit(0 if ok else 1)


if __name__ == '__main__':
    main()
