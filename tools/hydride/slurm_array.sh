#!/bin/bash
# The hydrided-plate campaign as a SLURM job array: one task per case of the grid
# seeds x bonding x element size (tools/hydride/campaign.py list prints it: 20 cases
# for 5 seeds, 2 bondings, 2 element sizes; indices 0-19, element size slowest).
#
#   sbatch tools/hydride/slurm_array.sh                    # from the Fracas checkout
#   sbatch --export=ALL,ROOT=$SCRATCH/hydride tools/hydride/slurm_array.sh
#   # when all tasks are done (or with --dependency=afterany:<jobid>):
#   python3 tools/hydride/gather.py $ROOT --out $ROOT/summary
#
# Adapt to the cluster: partition/account lines, the module loads (a Fortran runtime,
# HDF5, SuiteSparse, LAPACK as the build used; Python 3 with numpy, scipy, h5py,
# matplotlib and gmsh), and the time limit. One case is one serial fracas run: on
# this project's workstation a 2650-element plate (h = 1 um, 812 steps) took 44-78 s
# of processor time and a 5200-element one (h = 0.7 um, 1160 steps) 132-202 s
# (doc/hydrided_zircaloy.md §7); 1 hour per task leaves a wide margin. Memory stays
# about 80 MB at 5200 elements.
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
# module load gcc hdf5 suitesparse python        # as your site names them

FRACAS_SRC=${FRACAS_SRC:-$(pwd)}
ROOT=${ROOT:-$FRACAS_SRC/runs/hydride}
FRACAS_BIN=${FRACAS_BIN:-$FRACAS_SRC/build/release/bin/fracas}
export FRACAS_BIN OMP_NUM_THREADS=1 HDF5_USE_FILE_LOCKING=FALSE

# Same grid as `campaign.py all`: change it here and in the gather step together.
python3 "$FRACAS_SRC/tools/hydride/campaign.py" one --root "$ROOT" --index "$SLURM_ARRAY_TASK_ID" \
    --seeds 1 2 3 4 5 --bondings weak strong --sizes 1.0e-6 0.7e-6
