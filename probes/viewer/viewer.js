// Session viewer page: scene meshes, the device (green edges) and the
// simulated tool (orange) over time, the wrench on the device as arrows
// (force red, torque purple), contact points (yellow) with their normals.
// Data: window.SESSION (written by session_viewer). World is z-up, metres.
// URL hash options: #frame=K starts at frame K, #pause starts paused.
(function () {
  'use strict';
  const S = window.SESSION;
  const N = S.t.length;
  const log = (m) => console.log('viewer: ' + m);
  const hash = new URLSearchParams(window.location.hash.slice(1));

  const view = document.getElementById('view');
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(window.devicePixelRatio || 1);
  renderer.setSize(view.clientWidth, view.clientHeight);
  renderer.setClearColor(0x20242a);
  view.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.add(new THREE.HemisphereLight(0xffffff, 0x404048, 0.75));
  const sun = new THREE.DirectionalLight(0xffffff, 0.6);
  sun.position.set(0.4, -0.6, 1.0);
  scene.add(sun);

  function geometryOf(m) {  // flat-shaded: one normal per triangle
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.Float32BufferAttribute(m.positions, 3));
    g.setIndex(m.indices);
    const flat = g.toNonIndexed();
    flat.computeVertexNormals();
    return flat;
  }
  function setPose(obj, a, i) {  // a: flat [x y z qw qx qy qz] * N
    const k = 7 * i;
    obj.position.set(a[k], a[k + 1], a[k + 2]);
    obj.quaternion.set(a[k + 4], a[k + 5], a[k + 6], a[k + 3]);
  }

  // Scene objects, fixed.
  const bounds = new THREE.Box3();
  for (const m of S.objects) {
    let mesh;
    if (m.kind === 'plane') {
      mesh = new THREE.Mesh(new THREE.PlaneGeometry(m.size, m.size),
        new THREE.MeshLambertMaterial({ color: 0x4a90d9, transparent: true, opacity: 0.55,
                                        side: THREE.DoubleSide }));
    } else {
      mesh = new THREE.Mesh(geometryOf(m), new THREE.MeshLambertMaterial({ color: 0x4a90d9 }));
    }
    setPose(mesh, m.pose, 0);
    mesh.name = m.name;
    scene.add(mesh);
    if (m.kind !== 'plane') bounds.expandByObject(mesh);
  }
  // The tool twice, both in the tool frame T: simulated (solid orange) and
  // where the device holds it (green edges, so the tool stays visible inside).
  const toolGeometry = geometryOf(S.tool);
  const tool = new THREE.Mesh(toolGeometry, new THREE.MeshLambertMaterial({ color: 0xe8902a }));
  const device = new THREE.LineSegments(new THREE.EdgesGeometry(toolGeometry, 20),
    new THREE.LineBasicMaterial({ color: 0x3cc060 }));
  const axesSize = 1.2 * S.tool.radius;
  tool.add(new THREE.AxesHelper(axesSize));
  device.add(new THREE.AxesHelper(axesSize));
  scene.add(tool, device);
  for (let i = 0; i < N; ++i) {
    const k = 7 * i;
    bounds.expandByPoint(new THREE.Vector3(S.device[k], S.device[k + 1], S.device[k + 2]));
  }

  // Arrows: length = magnitude * scale; the session's largest force (torque)
  // is drawn `arrowMax` long, unless it is below 5% of the device's limit
  // (then 5% of the limit is: numerical noise stays invisible).
  const sphere = bounds.getBoundingSphere(new THREE.Sphere());
  const arrowMax = Math.max(0.5 * sphere.radius, 3 * S.tool.radius);
  const forceScale = arrowMax / Math.max(S.max_force, 0.05 * S.force_limit);
  const torqueScale = arrowMax / Math.max(S.max_torque, 0.05 * S.torque_limit);
  const forceArrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, 0xff3030);
  const torqueArrow = new THREE.ArrowHelper(new THREE.Vector3(0, 0, 1), new THREE.Vector3(), 1, 0xb040ff);
  for (const a of [forceArrow, torqueArrow]) {  // drawn over the meshes: the device is often inside them
    // transparent: drawn with (after) the translucent plane, not under it
    a.traverse((o) => { if (o.material) { o.material.depthTest = false; o.material.transparent = true; } o.renderOrder = 3; });
  }
  scene.add(forceArrow, torqueArrow);
  function setArrow(arrow, origin, v, scale) {
    const len = v.length() * scale;
    arrow.visible = len > 1e-6;
    if (!arrow.visible) return;
    arrow.position.copy(origin);
    arrow.setDirection(v.clone().normalize());
    arrow.setLength(len, Math.min(0.2 * len, 0.12 * arrowMax), Math.min(0.1 * len, 0.06 * arrowMax));
  }

  // Contact points and normals (their length: 0.6 tool radius).
  const maxContacts = S.max_contacts_per_frame;
  const pointGeometry = new THREE.BufferGeometry();
  pointGeometry.setAttribute('position', new THREE.Float32BufferAttribute(new Float32Array(3 * Math.max(1, maxContacts)), 3));
  const points = new THREE.Points(pointGeometry, new THREE.PointsMaterial(
    { color: 0xffe030, size: 9, sizeAttenuation: false, depthTest: false, transparent: true }));
  points.renderOrder = 2;
  const normalGeometry = new THREE.BufferGeometry();
  normalGeometry.setAttribute('position', new THREE.Float32BufferAttribute(new Float32Array(6 * Math.max(1, maxContacts)), 3));
  const normals = new THREE.LineSegments(normalGeometry, new THREE.LineBasicMaterial({ color: 0xffe030, depthTest: false, transparent: true }));
  normals.renderOrder = 2;
  scene.add(points, normals);

  const camera = new THREE.PerspectiveCamera(40, view.clientWidth / view.clientHeight, 1e-4, 100);
  camera.up.set(0, 0, 1);
  const dist = 2.6 * Math.max(sphere.radius, 1e-3);
  camera.position.copy(sphere.center).add(new THREE.Vector3(0.55 * dist, -0.8 * dist, 0.55 * dist));
  const controls = new THREE.OrbitControls(camera, renderer.domElement);
  controls.target.copy(sphere.center);
  controls.update();

  const readout = document.getElementById('readout');
  const slider = document.getElementById('slider');
  const playButton = document.getElementById('play');
  const timeLabel = document.getElementById('time');
  document.getElementById('title').textContent = 'Session: ' + S.scene;
  document.getElementById('source').textContent = S.session + ' (' + S.format + ', ' + S.session_frames +
      ' poses; ' + N + ' frames shown)';
  document.getElementById('note').textContent = S.note;
  slider.max = String(N - 1);

  const flagNames = ['force sat', 'torque sat', 'rate limited', 'watchdog', 'stale', 'engaging', 'PD invalid'];
  let frame = -1;
  function show(i) {
    frame = i;
    setPose(device, S.device, i);
    setPose(tool, S.tool_pose, i);
    const f = new THREE.Vector3().fromArray(S.force, 3 * i);
    const tau = new THREE.Vector3().fromArray(S.torque, 3 * i);
    setArrow(forceArrow, device.position, f, forceScale);
    setArrow(torqueArrow, device.position, tau, torqueScale);
    const c = S.contacts[i];
    const n = c.length / 7;
    const pp = pointGeometry.attributes.position.array, np = normalGeometry.attributes.position.array;
    const nl = 0.6 * S.tool.radius;
    for (let j = 0; j < n; ++j) {
      for (let a = 0; a < 3; ++a) {
        pp[3 * j + a] = c[7 * j + a];
        np[6 * j + a] = c[7 * j + a];
        np[6 * j + 3 + a] = c[7 * j + a] + nl * c[7 * j + 3 + a];
      }
    }
    pointGeometry.setDrawRange(0, n);
    normalGeometry.setDrawRange(0, 2 * n);
    pointGeometry.attributes.position.needsUpdate = true;
    normalGeometry.attributes.position.needsUpdate = true;
    const flags = flagNames.filter((_, b) => S.flags[i] & (1 << b)).join(', ');
    readout.textContent =
      't          ' + S.t[i].toFixed(3) + ' s   (frame ' + i + ' of ' + N + ')\n' +
      '|force|    ' + f.length().toFixed(3) + ' N   [' + f.toArray().map((v) => v.toFixed(2)).join(' ') + ']\n' +
      '|torque|   ' + (1e3 * tau.length()).toFixed(2) + ' mN·m\n' +
      'PD         ' + (1e3 * S.depth[i]).toFixed(3) + ' mm   contacts ' + S.contact_count[i] +
      ' (' + n + ' points)\n' +
      'round trip ' + (S.round_trip_us[i] >= 0 ? S.round_trip_us[i].toFixed(0) + ' us' : '-') +
      (S.answered[i] ? '' : '   (no answer: last one shown)') + '\n' +
      'flags      ' + (flags || '-');
    slider.value = String(i);
    timeLabel.textContent = S.t[i].toFixed(3) + ' / ' + S.t[N - 1].toFixed(3) + ' s';
  }
  function frameAt(t) {  // last frame with S.t <= t
    let lo = 0, hi = N - 1;
    while (lo < hi) {
      const mid = (lo + hi + 1) >> 1;
      if (S.t[mid] <= t) lo = mid; else hi = mid - 1;
    }
    return lo;
  }

  let playing = !hash.has('pause');
  let simTime = 0;
  const start = Math.min(N - 1, Math.max(0, parseInt(hash.get('frame') || '0', 10) || 0));
  simTime = S.t[start];
  show(start);
  playButton.textContent = playing ? 'Pause' : 'Play';
  playButton.onclick = () => {
    playing = !playing;
    if (playing && frame === N - 1) simTime = 0;
    playButton.textContent = playing ? 'Pause' : 'Play';
  };
  slider.oninput = () => { simTime = S.t[parseInt(slider.value, 10)]; show(parseInt(slider.value, 10)); };
  window.addEventListener('resize', () => {
    camera.aspect = view.clientWidth / view.clientHeight;
    camera.updateProjectionMatrix();
    renderer.setSize(view.clientWidth, view.clientHeight);
  });

  // Playback runs on a timer (timers also run under a headless browser's
  // virtual time, animation frames barely do); drawing on animation frames.
  let lastWall = performance.now(), lastLog = -1e9;
  function step() {
    const now = performance.now();
    if (playing) {
      simTime += 1e-3 * (now - lastWall) * parseFloat(document.getElementById('speed').value);
      if (simTime >= S.t[N - 1]) { simTime = S.t[N - 1]; playing = false; playButton.textContent = 'Play'; }
      const i = frameAt(simTime);
      if (i !== frame) { show(i); renderer.render(scene, camera); }
    }
    lastWall = now;
    if (now - lastLog >= 250) { lastLog = now; log('frame ' + frame + ' t=' + S.t[frame].toFixed(3)); }
  }
  function draw() {
    controls.update();
    renderer.render(scene, camera);
    requestAnimationFrame(draw);
  }
  setInterval(step, 20);
  log('ready frames=' + N + ' objects=' + S.objects.length + ' webgl=' + (renderer.getContext() ? 1 : 0));
  draw();
})();
