// The report's 3D views (docs/testbed-report.md): the replay of recorded
// runs, one viewport per engine on one WebGL canvas, with contacts drawn as
// points and normals; the Quickhull trace (the write-up's figure 1); the
// broad-phase funnel per step (figure 2). The replays' frames come from
// report-replay.js beside the page (window.talusReportReplays). Writes what
// it managed into #report-status, which the headless-browser test reads.
(function () {
  'use strict';
  const status = window.talusReport;
  const data = JSON.parse(document.getElementById('replay-data').textContent);
  // The replays come from report-replay.js beside the page, loaded before
  // this script; a missing file is said in the replay section and counted
  // as an error (the plots' script reports a missing report-data.js).
  const replayFileFound = Boolean(window.talusReportReplays);
  data.runs = replayFileFound ? window.talusReportReplays : [];
  if (!replayFileFound) status.errors.push('report-replay.js was not found beside the page');
  const palette = [0x1f77b4, 0xd62728, 0x2ca02c, 0xff7f0e, 0x9467bd, 0x8c564b, 0xe377c2, 0x17becf];
  const background = 0xf4f4f4;

  function el(tag, props, parent) {
    const node = document.createElement(tag);
    Object.assign(node, props || {});
    if (parent) parent.appendChild(node);
    return node;
  }

  // Orbit camera: drag turns it around the target, the wheel zooms.
  function orbit(canvas, camera, target, distance, redraw) {
    const state = {theta: 0.8, phi: 1.1, distance: distance};
    function place() {
      const s = Math.sin(state.phi);
      camera.position.set(target.x + state.distance * s * Math.sin(state.theta),
                          target.y + state.distance * Math.cos(state.phi),
                          target.z + state.distance * s * Math.cos(state.theta));
      camera.lookAt(target);
    }
    let drag = null;
    canvas.addEventListener('pointerdown', e => { drag = {x: e.clientX, y: e.clientY}; });
    window.addEventListener('pointerup', () => { drag = null; });
    canvas.addEventListener('pointermove', e => {
      if (!drag) return;
      state.theta -= (e.clientX - drag.x) * 0.01;
      state.phi = Math.min(3.1, Math.max(0.05, state.phi - (e.clientY - drag.y) * 0.01));
      drag = {x: e.clientX, y: e.clientY};
      place(); redraw();
    });
    canvas.addEventListener('wheel', e => {
      e.preventDefault();
      state.distance *= Math.exp(e.deltaY * 0.001);
      place(); redraw();
    }, {passive: false});
    place();
  }

  function lights(scene) {
    scene.add(new THREE.AmbientLight(0xffffff, 0.55));
    const sun = new THREE.DirectionalLight(0xffffff, 0.8);
    sun.position.set(3, 10, 6);
    scene.add(sun);
  }

  function geometryOf(shape) {
    if (shape.kind === 'box') {
      const h = shape.halfExtents;
      return new THREE.BoxGeometry(2 * h[0], 2 * h[1], 2 * h[2]);
    }
    if (shape.kind === 'sphere') return new THREE.SphereGeometry(shape.radius, 24, 16);
    const positions = [];
    for (const face of shape.faces) {
      for (let k = 1; k + 1 < face.length; ++k) {
        for (const i of [face[0], face[k], face[k + 1]]) positions.push(...shape.vertices[i]);
      }
    }
    const geometry = new THREE.BufferGeometry();
    geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
    geometry.computeVertexNormals();
    return geometry;
  }

  // Counts pixels that differ from the background in each viewport, so a
  // test can tell a drawn scene from an empty canvas.
  function litPixels(renderer, rects) {
    const gl = renderer.getContext();
    return rects.map(r => {
      const pixels = new Uint8Array(r.w * r.h * 4);
      gl.readPixels(r.x, r.y, r.w, r.h, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
      let lit = 0;
      for (let i = 0; i < pixels.length; i += 4) {
        if (Math.abs(pixels[i] - 0xf4) + Math.abs(pixels[i + 1] - 0xf4) + Math.abs(pixels[i + 2] - 0xf4) > 24) ++lit;
      }
      return lit;
    });
  }

  function makeRenderer(canvas) {
    try {
      const renderer = new THREE.WebGLRenderer({canvas: canvas, antialias: true, preserveDrawingBuffer: true});
      renderer.setPixelRatio(1);
      renderer.setClearColor(background);
      status.webgl = renderer.getContext() !== null;
      return renderer;
    } catch (error) {
      status.webgl = false;
      status.errors.push('WebGL: ' + error.message);
      return null;
    }
  }

  // ---- Replay ----
  function setupReplay() {
    const root = document.getElementById('replay');
    if (!replayFileFound) {
      root.textContent = 'The replay data (report-replay.js, written beside report.html) was not found: ' +
        'keep the two files together.';
      return;
    }
    if (!data.runs.length) {
      root.textContent = 'No run was recorded for replay: run with talus-testbed run --replay NAME (or all).';
      return;
    }
    const bar = el('div', {className: 'replay-controls'}, root);
    const select = el('select', {}, bar);
    data.runs.forEach((run, i) => el('option', {value: String(i), textContent: run.id}, select));
    const play = el('button', {textContent: 'Play'}, bar);
    const slider = el('input', {type: 'range', min: '0', max: '0', value: '0', step: '1'}, bar);
    const label = el('span', {className: 'replay-time'}, bar);
    const toggleLabel = el('label', {}, bar);
    const toggle = el('input', {type: 'checkbox', checked: true}, toggleLabel);
    toggleLabel.appendChild(document.createTextNode(' contact points and normals'));
    const stage = el('div', {className: 'replay-stage'}, root);
    const canvas = el('canvas', {}, stage);
    const renderer = makeRenderer(canvas);
    if (!renderer) {
      stage.textContent = 'WebGL is not available in this browser.';
      return;
    }
    const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 2000);
    let views = [], run = null, frame = 0, playing = false, clock = 0, last = 0;

    function buildView(result, index, radius) {
      const scene = new THREE.Scene();
      lights(scene);
      const bodies = run.shapes.map((shape, b) => {
        const geometry = geometryOf(shape);
        const color = shape.static ? 0xb0b0b0 : palette[(index + b) % palette.length];
        const mesh = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({color: color}));
        mesh.add(new THREE.LineSegments(new THREE.EdgesGeometry(geometry),
                                        new THREE.LineBasicMaterial({color: 0x333333})));
        scene.add(mesh);
        return mesh;
      });
      const most = Math.max(1, ...result.frames.map(f => f.c.length));
      const points = new THREE.BufferGeometry();
      points.setAttribute('position', new THREE.BufferAttribute(new Float32Array(most * 3), 3));
      const normals = new THREE.BufferGeometry();
      normals.setAttribute('position', new THREE.BufferAttribute(new Float32Array(most * 6), 3));
      const contactPoints = new THREE.Points(points, new THREE.PointsMaterial({color: 0xff0000, size: 6, sizeAttenuation: false, depthTest: false}));
      const contactNormals = new THREE.LineSegments(normals, new THREE.LineBasicMaterial({color: 0xcc0000, depthTest: false}));
      contactPoints.renderOrder = contactNormals.renderOrder = 1;
      scene.add(contactPoints, contactNormals);
      const tag = el('div', {className: 'replay-label', textContent: result.backend}, stage);
      return {result, scene, bodies, contactPoints, contactNormals, tag, normalLength: 0.15 * radius};
    }

    function layout() {
      const columns = Math.min(views.length, 3), rows = Math.ceil(views.length / columns);
      const width = Math.max(600, stage.clientWidth || 1200), cellW = Math.floor(width / columns), cellH = 320;
      renderer.setSize(cellW * columns, cellH * rows);
      views.forEach((v, i) => {
        const col = i % columns, row = Math.floor(i / columns);
        v.rect = {x: col * cellW, y: (rows - 1 - row) * cellH, w: cellW - 4, h: cellH - 4};
        v.tag.style.left = (col * cellW + 6) + 'px';
        v.tag.style.top = (row * cellH + 4) + 'px';
      });
    }

    // While playing, poses between two recorded frames are interpolated
    // (positions linearly, orientations by slerp) at the screen's rate, so
    // the display-rate frames (docs/testbed-report.md "Sizes") play
    // smoothly; contacts are those of the earlier frame.
    const qa = new THREE.Quaternion(), qb = new THREE.Quaternion();
    function showFrame(alpha) {
      views.forEach(v => {
        const lastFrame = v.result.frames.length - 1;
        const f = v.result.frames[Math.min(frame, lastFrame)];
        const g = v.result.frames[Math.min(frame + 1, lastFrame)];
        const a = alpha || 0;
        v.bodies.forEach((mesh, b) => {
          mesh.position.set(f.p[b][0] + a * (g.p[b][0] - f.p[b][0]), f.p[b][1] + a * (g.p[b][1] - f.p[b][1]),
                            f.p[b][2] + a * (g.p[b][2] - f.p[b][2]));
          qa.set(f.q[b][1], f.q[b][2], f.q[b][3], f.q[b][0]).normalize();
          qb.set(g.q[b][1], g.q[b][2], g.q[b][3], g.q[b][0]).normalize();
          mesh.quaternion.slerpQuaternions(qa, qb, a);
        });
        const p = v.contactPoints.geometry.attributes.position, n = v.contactNormals.geometry.attributes.position;
        f.c.forEach((c, k) => {
          p.setXYZ(k, c[2], c[3], c[4]);
          n.setXYZ(2 * k, c[2], c[3], c[4]);
          n.setXYZ(2 * k + 1, c[2] + v.normalLength * c[5], c[3] + v.normalLength * c[6], c[4] + v.normalLength * c[7]);
        });
        p.needsUpdate = n.needsUpdate = true;
        v.contactPoints.geometry.setDrawRange(0, f.c.length);
        v.contactNormals.geometry.setDrawRange(0, 2 * f.c.length);
        v.contactPoints.visible = v.contactNormals.visible = toggle.checked;
      });
      const first = views[0].result.frames[Math.min(frame, views[0].result.frames.length - 1)];
      label.textContent = ' t = ' + first.t.toFixed(3) + ' s, ' + first.c.length + ' contacts (' + views[0].result.backend + ')';
      draw();
    }

    function draw() {
      renderer.setScissorTest(true);
      for (const v of views) {
        renderer.setViewport(v.rect.x, v.rect.y, v.rect.w, v.rect.h);
        renderer.setScissor(v.rect.x, v.rect.y, v.rect.w, v.rect.h);
        camera.aspect = v.rect.w / v.rect.h;
        camera.updateProjectionMatrix();
        renderer.render(v.scene, camera);
      }
    }

    function load(index) {
      run = data.runs[index];
      views.forEach(v => v.tag.remove());
      // Frame the dynamic bodies over the whole run.
      const box = new THREE.Box3();
      run.results[0].frames.forEach(f => f.p.forEach((p, b) => {
        if (!run.shapes[b].static) box.expandByPoint(new THREE.Vector3(p[0], p[1], p[2]));
      }));
      if (box.isEmpty()) box.expandByPoint(new THREE.Vector3(0, 0, 0));
      const center = box.getCenter(new THREE.Vector3());
      const radius = box.getSize(new THREE.Vector3()).length() / 2 + 1;
      views = run.results.map((result, i) => buildView(result, i, radius));
      layout();
      orbit(canvas, camera, center, 2.6 * radius, draw);
      slider.max = String(run.results[0].frames.length - 1);
      frame = 0;
      slider.value = '0';
      showFrame();
    }

    function tick(now) {
      if (!playing) return;
      clock += (now - last) / 1000;
      last = now;
      const frames = views[0].result.frames;
      while (frame + 1 < frames.length && frames[frame + 1].t <= clock) ++frame;
      slider.value = String(frame);
      const next = frames[Math.min(frame + 1, frames.length - 1)];
      showFrame(next.t > frames[frame].t ? Math.min(1, (clock - frames[frame].t) / (next.t - frames[frame].t)) : 0);
      if (frame + 1 >= frames.length) { playing = false; play.textContent = 'Play'; return; }
      requestAnimationFrame(tick);
    }

    select.addEventListener('change', () => load(Number(select.value)));
    slider.addEventListener('input', () => { frame = Number(slider.value); showFrame(); });
    toggle.addEventListener('change', () => showFrame());
    play.addEventListener('click', () => {
      playing = !playing;
      play.textContent = playing ? 'Pause' : 'Play';
      if (!playing) return;
      const frames = views[0].result.frames;
      if (frame + 1 >= frames.length) frame = 0;
      clock = frames[frame].t;
      last = performance.now();
      requestAnimationFrame(tick);
    });
    load(0);
    status.replayViews = views.length;
    let meshes = 0;
    views.forEach(v => v.scene.traverse(o => { if (o.isMesh) ++meshes; }));
    status.replayMeshes = meshes;
    status.replayLitPixels = litPixels(renderer, views.map(v => v.rect));
  }

  // ---- Figure 1: Quickhull step by step ----
  function setupHullTrace() {
    const root = document.getElementById('hull-trace');
    const trace = data.hullTrace;
    const bar = el('div', {className: 'replay-controls'}, root);
    const slider = el('input', {type: 'range', min: '0', max: String(trace.steps.length), value: '0', step: '1'}, bar);
    const label = el('span', {}, bar);
    const canvas = el('canvas', {}, el('div', {className: 'replay-stage'}, root));
    const renderer = makeRenderer(canvas);
    if (!renderer) return;
    renderer.setSize(640, 420);
    const camera = new THREE.PerspectiveCamera(40, 640 / 420, 0.01, 100);
    const scene = new THREE.Scene();
    lights(scene);
    const point = i => new THREE.Vector3(...trace.points[i]);
    const cloud = new THREE.BufferGeometry().setFromPoints(trace.points.map((p, i) => point(i)));
    scene.add(new THREE.Points(cloud, new THREE.PointsMaterial({color: 0x555555, size: 4, sizeAttenuation: false})));
    let group = new THREE.Group();
    scene.add(group);
    const draw = () => renderer.render(scene, camera);

    function triangles(loops) {
      const positions = [];
      for (const loop of loops) {
        for (let k = 1; k + 1 < loop.length; ++k) for (const i of [loop[0], loop[k], loop[k + 1]]) positions.push(...trace.points[i]);
      }
      const geometry = new THREE.BufferGeometry();
      geometry.setAttribute('position', new THREE.Float32BufferAttribute(positions, 3));
      geometry.computeVertexNormals();
      return geometry;
    }
    function faceSet(loops, color, opacity) {
      const geometry = triangles(loops);
      const mesh = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({color: color, transparent: opacity < 1, opacity: opacity, side: THREE.DoubleSide}));
      const outline = [];
      for (const loop of loops) loop.forEach((a, k) => outline.push(point(a), point(loop[(k + 1) % loop.length])));
      group.add(mesh, new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(outline), new THREE.LineBasicMaterial({color: 0x222222})));
    }

    function show(index) {
      scene.remove(group);
      group = new THREE.Group();
      scene.add(group);
      if (index >= trace.steps.length) {
        faceSet(trace.finalFaces, 0x6699cc, 1);
        label.textContent = ' finished hull: ' + trace.finalFaces.length + ' faces (' + trace.steps.length + ' points added)';
      } else {
        const step = trace.steps[index];
        faceSet(step.faces.filter((f, k) => !step.visible[k]), 0x6699cc, 1);
        faceSet(step.faces.filter((f, k) => step.visible[k]), 0xd62728, 0.55);
        faceSet(step.horizon.map(e => [e[0], e[1], step.eye]), 0x2ca02c, 0.45);
        const horizon = [];
        step.horizon.forEach(e => horizon.push(point(e[0]), point(e[1])));
        group.add(new THREE.LineSegments(new THREE.BufferGeometry().setFromPoints(horizon), new THREE.LineBasicMaterial({color: 0xff7f0e})));
        const eye = new THREE.Mesh(new THREE.SphereGeometry(0.04, 12, 8), new THREE.MeshLambertMaterial({color: 0xffcc00}));
        eye.position.copy(point(step.eye));
        group.add(eye);
        const seen = step.visible.filter(v => v).length;
        label.textContent = ' step ' + (index + 1) + ' of ' + trace.steps.length + ': the eye point (yellow) sees ' + seen +
          ' of ' + step.faces.length + ' faces (red); horizon of ' + step.horizon.length + ' edges (orange); new cone (green)';
      }
      draw();
    }
    slider.addEventListener('input', () => show(Number(slider.value)));
    orbit(canvas, camera, new THREE.Vector3(0, 0, 0), 3.2, draw);
    show(0);
    let meshes = 0;
    scene.traverse(o => { if (o.isMesh) ++meshes; });
    status.hullTraceMeshes = meshes;
    status.hullTraceLitPixels = litPixels(renderer, [{x: 0, y: 0, w: 640, h: 420}])[0];
  }

  // ---- Figure 2: broad-phase funnel per step ----
  function setupFunnel() {
    const root = document.getElementById('broadphase');
    let charts = 0;
    for (const run of data.runs) {
      for (const result of run.results) {
        if (!result.counters.length) continue;
        const box = el('div', {className: 'plot'}, root);
        const canvas = el('canvas', {}, box);
        const colours = ['#7f7f7f', '#1f77b4', '#17becf', '#ff7f0e', '#d62728', '#2ca02c'];
        // "structure: ..." counters say which structure ran (1) each step: a label, not a curve.
        const prefix = 'structure: ';
        const counts = [], ran = {};
        result.counters.forEach((name, k) => {
          if (!name.startsWith(prefix)) { counts.push(k); return; }
          const steps = result.frames.slice(1).filter(f => f.n[k] > 0.5).length;
          if (steps) ran[name.slice(prefix.length)] = steps;
        });
        const structure = Object.keys(ran).map(name => name + ' (' + ran[name] + ' steps)').join(', ');
        const datasets = counts.map((k, i) => ({
          label: result.counters[k], borderColor: colours[i % colours.length], pointRadius: 0, borderWidth: 1.5, stepped: true,
          data: result.frames.slice(1).map(f => ({x: f.t, y: f.n[k]}))}));
        new Chart(canvas, {type: 'line', data: {datasets: datasets}, options: {animation: false, maintainAspectRatio: false,
          plugins: {title: {display: true, text: run.id + ' (' + result.backend + '): pairs per step' +
            (structure ? '; broad phase: ' + structure : '')}},
          scales: {x: {type: 'linear', title: {display: true, text: 'time (s)'}}, y: {title: {display: true, text: 'count'}}}}});
        ++charts;
      }
    }
    if (!charts) root.textContent = 'No replayed run with step counters (the talus backends report them; use --replay).';
    status.funnelCharts = charts;
  }

  for (const [name, setup] of [['replay', setupReplay], ['hull trace', setupHullTrace], ['funnel', setupFunnel]]) {
    if (name !== 'funnel' && typeof THREE === 'undefined') {
      status.errors.push('three.js is not inlined (run scripts/install-deps.sh)');
      continue;
    }
    if (name === 'funnel' && typeof Chart === 'undefined') continue;
    try { setup(); } catch (error) { status.errors.push(name + ': ' + error.message); }
  }
})();
