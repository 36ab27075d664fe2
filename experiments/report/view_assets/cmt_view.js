// The 3-D page of `cmt view` and `cmt report` (docs/viewer.md): renders the layers of window.CMT_VIEW_DATA
// with three.js (THREE, THREE.OrbitControls loaded before this file). A layer is a named set of polygons,
// segments, points, polylines and spheres with one style; the panel toggles layers and groups, a click on
// an item shows its info. Test hooks: #status ("ready" or "error"), #errors (every uncaught error and
// console.error, data-count), #layers li[data-layer] (data-items, data-visible); the URL hash
// "#hide=ID,ID" hides layers at load.
(function () {
  'use strict';

  const errors = [];
  function recordError(text) {
    errors.push(String(text));
    const box = document.getElementById('errors');
    if (!box) return;
    box.dataset.count = String(errors.length);
    const line = document.createElement('div');
    line.textContent = String(text);
    box.appendChild(line);
    box.hidden = false;
  }
  window.addEventListener('error', (e) => recordError(e.message || e));
  const consoleError = console.error.bind(console);
  console.error = function (...args) {
    recordError(args.join(' '));
    consoleError(...args);
  };

  const vec = (p) => new THREE.Vector3(p[0], p[1], p[2]);

  // Newell's normal of a polygon loop (any orientation, tolerant of collinear points).
  function newellNormal(points) {
    const n = new THREE.Vector3();
    for (let i = 0; i < points.length; ++i) {
      const a = points[i], b = points[(i + 1) % points.length];
      n.x += (a.y - b.y) * (a.z + b.z);
      n.y += (a.z - b.z) * (a.x + b.x);
      n.z += (a.x - b.x) * (a.y + b.y);
    }
    return n.lengthSq() > 0 ? n.normalize() : null;
  }

  // Triangles of a planar polygon with holes, in 3-D: project on the polygon's plane, triangulate there.
  function polygonTriangles(outer, holes) {
    const pts = outer.map(vec);
    const n = newellNormal(pts);
    if (!n || pts.length < 3) return [];
    const u = new THREE.Vector3().crossVectors(n, Math.abs(n.x) < 0.9 ? new THREE.Vector3(1, 0, 0)
                                                                        : new THREE.Vector3(0, 1, 0)).normalize();
    const v = new THREE.Vector3().crossVectors(n, u);
    const flat = (p) => new THREE.Vector2(p.dot(u), p.dot(v));
    const holePts = (holes || []).map((h) => h.map(vec));
    const faces = THREE.ShapeUtils.triangulateShape(pts.map(flat), holePts.map((h) => h.map(flat)));
    const all = pts.concat(...holePts);
    const out = [];
    for (const f of faces) out.push(all[f[0]], all[f[1]], all[f[2]]);
    return out;
  }

  function meshOfTriangles(triangles, style) {
    const g = new THREE.BufferGeometry();
    const a = new Float32Array(triangles.length * 3);
    triangles.forEach((p, i) => a.set([p.x, p.y, p.z], 3 * i));
    g.setAttribute('position', new THREE.BufferAttribute(a, 3));
    g.computeVertexNormals();
    const m = new THREE.MeshBasicMaterial({
      color: style.color, transparent: style.opacity < 1, opacity: style.opacity,
      side: THREE.DoubleSide, depthWrite: style.opacity >= 1,
      polygonOffset: true, polygonOffsetFactor: style.offset || 0, polygonOffsetUnits: style.offset || 0,
    });
    return new THREE.Mesh(g, m);
  }

  function lineOf(points, style, closed) {
    const g = new THREE.BufferGeometry().setFromPoints(points.map(vec));
    const m = new THREE.LineBasicMaterial({color: style.color, transparent: style.opacity < 1,
                                           opacity: Math.max(style.opacity, 0.6)});
    return closed ? new THREE.LineLoop(g, m) : new THREE.Line(g, m);
  }

  function sphereOf(center, radius, style, wire) {
    const g = new THREE.SphereGeometry(radius, wire ? 16 : 10, wire ? 12 : 8);
    const m = new THREE.MeshBasicMaterial({color: style.color, wireframe: !!wire,
                                           transparent: style.opacity < 1, opacity: style.opacity});
    const s = new THREE.Mesh(g, m);
    s.position.copy(vec(center));
    return s;
  }

  // One THREE.Group per layer; every pickable object carries the item's info in userData. An item's own
  // `style` (e.g. the opacity of a predicted piece by its stick class) overrides the layer's.
  function buildLayer(layer, pointRadius) {
    const group = new THREE.Group();
    const style = Object.assign({color: '#888888', opacity: 1}, layer.style || {});
    const pick = (obj, info) => { obj.userData = {layer: layer.name, info: info || {}}; return obj; };
    const own = (item) => (item.style ? Object.assign({}, style, item.style) : style);  // per-item override
    for (const poly of layer.polygons || []) {
      const tris = polygonTriangles(poly.points, poly.holes);
      if (tris.length) group.add(pick(meshOfTriangles(tris, own(poly)), poly.info));
      if (style.outline !== false) group.add(pick(lineOf(poly.points, own(poly), true), poly.info));
    }
    for (const seg of layer.segments || []) group.add(pick(lineOf(seg.points, own(seg), false), seg.info));
    for (const line of layer.polylines || []) group.add(pick(lineOf(line.points, own(line), false), line.info));
    for (const pt of layer.points || []) {
      const s = own(pt);
      group.add(pick(sphereOf(pt.point, pointRadius * (s.size || 1), s, false), pt.info));
    }
    for (const sp of layer.spheres || []) group.add(pick(sphereOf(sp.center, sp.radius, own(sp), true), sp.info));
    return group;
  }

  function itemCount(layer) {
    return ['polygons', 'segments', 'points', 'polylines', 'spheres']
        .reduce((n, k) => n + (layer[k] ? layer[k].length : 0), 0);
  }

  function hiddenFromHash() {
    const m = /(?:^#|&)hide=([^&]*)/.exec(window.location.hash);
    return new Set(m ? decodeURIComponent(m[1]).split(',').filter((s) => s) : []);
  }

  function showInfo(userData) {
    const box = document.getElementById('info');
    box.innerHTML = '';
    if (!userData) {
      box.textContent = 'Click a piece for its atom, kind, area and ends.';
      return;
    }
    const title = document.createElement('div');
    title.className = 'info-title';
    title.textContent = userData.layer;
    box.appendChild(title);
    for (const [k, v] of Object.entries(userData.info)) {
      const row = document.createElement('div');
      row.textContent = k + ': ' + (typeof v === 'number' ? +v.toPrecision(6) : JSON.stringify(v));
      box.appendChild(row);
    }
  }

  function buildPanel(data, groups, render) {
    const list = document.getElementById('layers');
    const byGroup = new Map();
    data.layers.forEach((layer, i) => {
      const key = layer.group || 'scene';
      if (!byGroup.has(key)) byGroup.set(key, []);
      byGroup.get(key).push(i);
    });
    for (const [name, indices] of byGroup) {
      const head = document.createElement('li');
      head.className = 'group';
      const box = document.createElement('input');
      box.type = 'checkbox';
      box.checked = indices.some((i) => groups[i].visible);
      box.dataset.group = name;
      head.append(box, ' ' + name);
      list.appendChild(head);
      const boxes = [];
      for (const i of indices) {
        const layer = data.layers[i];
        const li = document.createElement('li');
        li.dataset.layer = layer.id;
        li.dataset.items = String(itemCount(layer));
        li.dataset.visible = String(groups[i].visible);
        const cb = document.createElement('input');
        cb.type = 'checkbox';
        cb.checked = groups[i].visible;
        cb.addEventListener('change', () => {
          groups[i].visible = cb.checked;
          li.dataset.visible = String(cb.checked);
          render();
        });
        boxes.push(cb);
        const swatch = document.createElement('span');
        swatch.className = 'swatch';
        swatch.style.background = (layer.style && layer.style.color) || '#888';
        li.append(cb, swatch, ' ' + layer.name + ' (' + itemCount(layer) + ')');
        list.appendChild(li);
      }
      box.addEventListener('change', () => {
        for (const cb of boxes) {
          cb.checked = box.checked;
          cb.dispatchEvent(new Event('change'));
        }
      });
    }
  }

  // Size of the focus box (start, goal, prediction, ends), at least a hundredth of the scene across: the
  // camera's first view and the size of point balls.
  function focusSize(data) {
    const box = data.focus || data.bounds;
    const scene = vec(data.bounds.max).sub(vec(data.bounds.min)).length() || 1;
    return Math.max(vec(box.max).sub(vec(box.min)).length(), 0.01 * scene);
  }

  function fitCamera(camera, controls, data) {
    const box = data.focus || data.bounds;
    const lo = vec(box.min), hi = vec(box.max);
    const center = lo.clone().add(hi).multiplyScalar(0.5);
    const scene = vec(data.bounds.max).sub(vec(data.bounds.min)).length() || 1;
    const size = focusSize(data);
    camera.near = size / 1000;
    camera.far = (size + scene) * 100;
    camera.position.copy(center).add(new THREE.Vector3(0.9, -1.3, 0.8).multiplyScalar(size));
    camera.updateProjectionMatrix();
    controls.target.copy(center);
    controls.update();
  }

  function start() {
    const data = window.CMT_VIEW_DATA;
    document.getElementById('title').textContent = data.title;
    document.getElementById('units').textContent = 'units: ' + data.units;
    const view = document.getElementById('view');
    const renderer = new THREE.WebGLRenderer({antialias: true, preserveDrawingBuffer: true});
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setClearColor(0xffffff);
    view.appendChild(renderer.domElement);
    const scene = new THREE.Scene();
    const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
    camera.up.set(0, 0, 1);  // task coordinates: z up
    const controls = new THREE.OrbitControls(camera, renderer.domElement);
    const size = focusSize(data);
    const hidden = hiddenFromHash();
    const groups = data.layers.map((layer) => {
      const g = buildLayer(layer, size * 0.006);
      g.visible = layer.visible !== false && !hidden.has(layer.id);
      scene.add(g);
      return g;
    });
    const render = () => renderer.render(scene, camera);
    const resize = () => {
      const w = view.clientWidth || 800, h = view.clientHeight || 600;
      renderer.setSize(w, h);
      camera.aspect = w / h;
      camera.updateProjectionMatrix();
      render();
    };
    controls.addEventListener('change', render);
    window.addEventListener('resize', resize);
    buildPanel(data, groups, render);
    fitCamera(camera, controls, data);
    resize();

    const raycaster = new THREE.Raycaster();
    raycaster.params.Line.threshold = size * 0.005;
    renderer.domElement.addEventListener('click', (e) => {
      const r = renderer.domElement.getBoundingClientRect();
      const mouse = new THREE.Vector2(((e.clientX - r.left) / r.width) * 2 - 1,
                                      -((e.clientY - r.top) / r.height) * 2 + 1);
      raycaster.setFromCamera(mouse, camera);
      const targets = groups.filter((g) => g.visible).flatMap((g) => g.children);
      const hit = raycaster.intersectObjects(targets, false)[0];
      showInfo(hit ? hit.object.userData : null);
    });
    showInfo(null);
    window.cmtView = {renderer, scene, camera, groups, data, render};
  }

  window.addEventListener('load', () => {
    const status = document.getElementById('status');
    try {
      start();
      status.textContent = errors.length ? 'error' : 'ready';
    } catch (e) {
      recordError(e && e.stack ? e.stack : e);
      status.textContent = 'error';
    }
  });
})();
