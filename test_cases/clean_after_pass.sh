#!/bin/sh
# clean_after_pass.sh OUT... -- COMMAND [ARGS...]: run a test's check of the runs written
# in the folders OUT. It passes: their results (OUTBOX, DISPLAY, POSTPRO) are removed, so
# that the suite leaves little on disk (README: the suite's disk); it fails: everything is
# kept to look at. FRACAS_KEEP_TEST_RESULTS=1 in the environment keeps them either way
# (rerun the check: ctest runs the run it needs again).
outs=""
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do
  outs="$outs $1"
  shift
done
[ "$#" -gt 0 ] || { echo "clean_after_pass.sh: no -- COMMAND" >&2; exit 2; }
shift
"$@"
status=$?
if [ "$status" -eq 0 ] && [ -z "${FRACAS_KEEP_TEST_RESULTS:-}" ]; then
  for out in $outs; do
    rm -rf "$out/OUTBOX" "$out/DISPLAY" "$out/POSTPRO"
    echo "results removed after the checks passed (FRACAS_KEEP_TEST_RESULTS=1 keeps them)" > "$out/REMOVED.txt"
  done
fi
exit "$status"
