#!/usr/bin/env bash
# Runs the pd_core example (built against the staged install) on two copies
# of the installed hexagonal prism (30 mm tall, flat top and bottom), lowered
# face-on onto each other. Reference, from the mesh file alone: while the
# overlap is below the prism's width (34.6 mm) the shortest way out is
# straight up, so the PD equals the overlap along +z, and there is no
# collision before the faces meet.
#   run_pd_example.sh EXAMPLE_BIN MESH WORK_DIR
set -euo pipefail
exe="$1" mesh="$2" work="$3"
fail() { echo "run_pd_example: FAIL: $1" >&2; exit 1; }
mkdir -p "$work"
"$exe" "$mesh" "$mesh" 0.001 | tee "$work/pd_two_meshes.csv"
# Height of the prism in m, from the file (units mm).
height=$(awk '$1 == "v" { if (n++ == 0 || $4 < lo) lo = $4; if ($4 > hi) hi = $4 } END { print (hi - lo) / 1000 }' "$mesh")
awk -F, -v h="$height" '
  NR == 1 { next }
  { i = NR - 4; overlap = 0.05 * i * h; rows++
    if ($1 - overlap > 1e-9 || overlap - $1 > 1e-9) { printf "row %d: overlap %s, expected %.6f\n", NR, $1, overlap; bad = 1 }
    if (overlap < -1e-9 && $2 != 0) { printf "row %d: collision reported %.4f m apart\n", NR, -overlap; bad = 1 }
    if (overlap > 1e-9) {
      err = $3 - overlap; if (err < 0) err = -err
      if ($2 != 1) { printf "row %d: no collision at overlap %s\n", NR, $1; bad = 1 }
      if (err > 1e-6 + 1e-3 * overlap) { printf "row %d: depth %s, expected %.6f\n", NR, $3, overlap; bad = 1 }
      if ($6 < 0.999) { printf "row %d: normal z %s, expected +1 (straight up)\n", NR, $6; bad = 1 }
    } }
  END { if (rows != 13) { printf "%d rows, expected 13\n", rows; bad = 1 } exit bad }' "$work/pd_two_meshes.csv" ||
  fail "PD of the stacked prisms differs from the overlap (see above)"
echo "run_pd_example: PASS (13 poses, PD = overlap within 0.1%)"
