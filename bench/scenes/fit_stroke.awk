# Places a mesh for a loop-benchmark scene and finds a slide stroke for a
# ball tool on its top surface. Used once per scene to write the numbers in
# bench/scenes/<scene>.yaml and <scene>.params.yaml (see bench/scenes/README.md).
#
#   awk -v size=0.15 -v up=y -v r=0.005 -v half=0.015 -f fit_stroke.awk MESH.off
#
# size: largest bounding-box extent after scaling (m); up: the mesh axis
# that becomes world +z (z, y or x); r: ball tool radius (m); half: half the
# stroke length (m). The mesh is scaled, rotated, centred on its bounding
# box in x and y, and shifted in z so that the ball touches the middle of the
# best stroke with its centre at z = 0.01. The ball's touching height at a
# point (x, y) is max over vertices v within r of v.z + sqrt(r^2 - d^2)
# (vertices only: fine for dense meshes). The best stroke, along x or y on a
# 2 mm grid, is the one whose touching height varies least.
# Prints the scene's mesh scale, pose and the slide centre and direction.
/^[[:space:]]*#/ { next }
NF == 0 { next }
state == 0 { if ($1 ~ /OFF$/) { if (NF >= 3) { nv = $2; state = 2 } else state = 1; next } }
state == 1 { nv = $1; state = 2; next }
state == 2 {
  if (up == "y") { x = $1; y = -$3; z = $2 } else if (up == "x") { x = $2; y = $3; z = $1 }
  else { x = $1; y = $2; z = $3 }
  X[n] = x; Y[n] = y; Z[n] = z
  if (n == 0) { x0 = x1 = x; y0 = y1 = y; z0 = z1 = z }
  if (x < x0) x0 = x; if (x > x1) x1 = x; if (y < y0) y0 = y; if (y > y1) y1 = y
  if (z < z0) z0 = z; if (z > z1) z1 = z
  if (++n == nv) state = 3
  next
}
END {
  ext = x1 - x0; if (y1 - y0 > ext) ext = y1 - y0; if (z1 - z0 > ext) ext = z1 - z0
  s = size / ext; cx = (x0 + x1) / 2; cy = (y0 + y1) / 2
  for (i = 0; i < n; i++) {  # scaled, centred in x and y (z shifted later)
    X[i] = (X[i] - cx) * s; Y[i] = (Y[i] - cy) * s; Z[i] = Z[i] * s
    key = int(X[i] / r + 1000) "," int(Y[i] / r + 1000)
    cell[key] = cell[key] " " i
  }
  g = 0.002; m = int(size / 2 / g)
  for (a = -m; a <= m; a++) for (b = -m; b <= m; b++) {
    qx = a * g; qy = b * g; best = "none"
    ci = int(qx / r + 1000); cj = int(qy / r + 1000)
    for (di = -1; di <= 1; di++) for (dj = -1; dj <= 1; dj++) {
      k = (ci + di) "," (cj + dj)
      if (!(k in cell)) continue
      c = split(cell[k], ids, " ")
      for (t = 1; t <= c; t++) {
        v = ids[t]; d2 = (X[v] - qx) ^ 2 + (Y[v] - qy) ^ 2
        if (d2 > r * r) continue
        h = Z[v] + sqrt(r * r - d2)
        if (best == "none" || h > best) best = h
      }
    }
    if (best != "none") H[a "," b] = best
  }
  steps = int(half / g); bestr = -1
  for (a = -m; a <= m; a++) for (b = -m; b <= m; b++) for (dir = 0; dir < 2; dir++) {
    lo = 1e9; hi = -1e9; ok = 1; sum = 0
    for (t = -steps; t <= steps; t++) {
      k = dir == 0 ? (a + t) "," b : a "," (b + t)
      if (!(k in H)) { ok = 0; break }
      h = H[k]; if (h < lo) lo = h; if (h > hi) hi = h; sum += h
    }
    if (!ok) continue
    if (bestr < 0 || hi - lo < bestr - 1e-6 || (hi - lo < bestr + 1e-6 && sum > bests)) {
      bestr = hi - lo; bests = sum; ba = a; bb = b; bdir = dir; bmid = H[a "," b]
    }
  }
  if (bestr < 0) { print "fit_stroke: no stroke fits" > "/dev/stderr"; exit 1 }
  dz = 0.01 - bmid
  printf "scale %.6g (mesh units to m); up %s\n", s, up
  printf "mesh position (after the rotation): [%.5f, %.5f, %.5f]\n", -cx * s, -cy * s, dz
  printf "world z range of the mesh: [%.4f, %.4f]\n", z0 * s + dz, z1 * s + dz
  printf "stroke centre [%.4f, %.4f, 0.01], direction %s, touching height range %.2f mm\n",
         ba * g, bb * g, bdir == 0 ? "[1, 0, 0]" : "[0, 1, 0]", bestr * 1000
  for (t = -steps; t <= steps; t++) {
    k = bdir == 0 ? (ba + t) "," bb : ba "," (bb + t)
    printf "  %+.3f m: touching z %.4f\n", t * g, H[k] + dz
  }
}
