#!/bin/bash
# The hydrided-plate campaign as a SLURM job array: one task per case of the grid
# seeds x bonding x element size (campaign.py list prints it: 20 cases for 5 seeds,
# 2 bondings, 2 element sizes; indices 0-19, element size slowest).
#
# FRACAS_PREFIX is where Fracas is: an install prefix (cmake --install build/release
# --prefix PREFIX: PREFIX/bin/fracas, PREFIX/bin/fracas-python, the scripts under
# PREFIX/share/fracas/python) or a build tree of a checkout (build/release: bin/fracas and
# bin/fracas-python, the scripts in the sources' tools/). Python is bin/fracas-python,
# the interpreter the build was configured with (numpy, h5py, matplotlib, gmsh), never a
# python3 that happens to be first on PATH.
#
#   sbatch --export=ALL,FRACAS_PREFIX=$HOME/fracas,ROOT=$SCRATCH/hydride tools/hydride/slurm_array.sh
#   sbatch tools/hydride/slurm_array.sh             # from a checkout with build/release built
#   # when all tasks are done (or with --dependency=afterany:<jobid>):
#   $FRACAS_PREFIX/bin/fracas-python $TOOLS/hydride/gather.py $ROOT --out $ROOT/summary
#
# Dry run on the login node or a workstation, before submitting: one task's deck is
# generated and checked (fracas --check), nothing runs (a few seconds):
#   DRY_RUN=1 SLURM_ARRAY_TASK_ID=19 ROOT=/tmp/dry bash tools/hydride/slurm_array.sh
#
# Adapt to the cluster: partition/account lines, the module loads (a Fortran runtime,
# HDF5, SuiteSparse, LAPACK as the build used), and the time limit. One case is one
# serial fracas run: on this project's workstation a 2650-element plate (h = 1 um, 812
# steps) took 44-78 s of processor time and a 5200-element one (h = 0.7 um, 1160 steps)
# 132-202 s (doc/hydrided_zircaloy.md §7); 1 hour per task leaves a wide margin. Memory
# stays about 80 MB at 5200 elements. Disk per case (measured, weak bonding, seed 1):
# 80 MB at h = 1 um (fracas.h5 61 MB, DISPLAY 6 MB) and 156 MB at h = 0.7 um (fracas.h5
# 120 MB, DISPLAY 13 MB): about 2.4 GB under ROOT for the 20 cases.
#
#SBATCH --job-name=fracas-hydride
#SBATCH --array=0-19
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --mem=1G
#SBATCH --time=01:00:00
#SBATCH --output=slurm-%A_%a.out
##SBATCH --partition=<partition>
##SBATCH --account=<account>

set -euo pipefail
# module load gcc hdf5 suitesparse                # as your site names them

FRACAS_PREFIX=${FRACAS_PREFIX:-$(pwd)/build/release}
if [ -d "$FRACAS_PREFIX/share/fracas/python/hydride" ]; then
  TOOLS=$FRACAS_PREFIX/share/fracas/python          # installed
else
  TOOLS=${TOOLS:-$(pwd)/tools}                      # a checkout's build tree
fi
PY=$FRACAS_PREFIX/bin/fracas-python
for f in "$FRACAS_PREFIX/bin/fracas" "$PY" "$TOOLS/hydride/campaign.py"; do
  [ -e "$f" ] || { echo "slurm_array.sh: $f not found (set FRACAS_PREFIX to an install prefix or build/release)" >&2; exit 1; }
done
ROOT=${ROOT:-$(pwd)/runs/hydride}
export FRACAS_BIN=$FRACAS_PREFIX/bin/fracas OMP_NUM_THREADS=1 HDF5_USE_FILE_LOCKING=FALSE
DRY=()
[ -n "${DRY_RUN:-}" ] && DRY=(--dry-run)

# Same grid as `campaign.py all`: change it here and in the gather step together.
"$PY" "$TOOLS/hydride/campaign.py" one --root "$ROOT" --index "$SLURM_ARRAY_TASK_ID" "${DRY[@]}" \
    --seeds 1 2 3 4 5 --bondings weak strong --sizes 1.0e-6 0.7e-6
