// The machine in 3D: one group per link, posed from /api/state, the model's cameras, the tool
// path trail, PathGuard's refusal and the probe's latch point.
import {el} from './api.js';
import * as THREE from './vendor/three/build/three.module.js';
// OrbitControls imports "../../../build/three.module.js": the same URL as above, so the same
// module instance (two instances of three.js would not share classes).
import {OrbitControls} from './vendor/three/examples/jsm/controls/OrbitControls.js';

// The trail keeps the last TRAIL_SEGMENTS pieces, one per state in which the tip moved more
// than TRAIL_STEP_M: a finishing pass of 100 mm at 0.2 mm is 500 of them.
const TRAIL_SEGMENTS = 20000;
const TRAIL_STEP_M = 2e-4;
const GUARD_RED = new THREE.Color(0xe53935);

export class MachineView {
  constructor(container, canvas, model) {
    this.container = container;
    this.canvas = canvas;
    this.model = model;
    this.dirty = true;
    this.framed = false;

    this.renderer = new THREE.WebGLRenderer(
        {canvas, antialias: true, alpha: true, preserveDrawingBuffer: true});
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.setClearColor(0x000000, 0);
    this.scene = new THREE.Scene();
    this.camera = new THREE.PerspectiveCamera(40, 1, 0.005, 100);
    this.scene.add(this.camera);

    this.hemi = new THREE.HemisphereLight(0xf4f7fb, 0x3a4048, 0.9);
    this.scene.add(this.hemi);
    // A key light that moves with the camera keeps every view readable, whatever the orbit.
    const key = new THREE.DirectionalLight(0xffffff, 0.75);
    key.position.set(0.6, 1.0, 0.4);
    this.camera.add(key);
    const fill = new THREE.DirectionalLight(0xffffff, 0.25);
    fill.position.set(-1, -0.3, -0.5);
    this.scene.add(fill);

    this.links = model.links.map((link) => this.buildLink(link));
    this.linkByName = new Map(this.links.map((g) => [g.name, g]));
    this.buildTrail();
    this.guardMarker = this.marker(0xff2d2d, 0.004);
    // smaller than the ruby (r 3 mm), which stands on it at the latch
    this.probeMarker = this.marker(0x32e06a, 0.0015);
    this.guardParts = [];

    this.cameras = model.cameras || [];
    this.buildToolbar();
    this.legend = el('div', {class: 'view-legend'});
    container.append(this.legend);

    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
    if (this.cameras.length) this.setCamera(this.cameras[0]);
    const loop = () => {
      if (this.dirty) {
        this.dirty = false;
        this.uploadTrail();
        this.renderer.render(this.scene, this.camera);
      }
      requestAnimationFrame(loop);
    };
    requestAnimationFrame(loop);
  }

  buildLink(link) {
    const group = new THREE.Group();
    group.name = link.name;
    group.userData.meshes = [];
    for (const v of link.visuals || []) {
      if (!v.positions || !v.positions.length) continue;
      let g = new THREE.BufferGeometry();
      g.setAttribute('position', new THREE.Float32BufferAttribute(v.positions, 3));
      if (v.indices && v.indices.length) g.setIndex(v.indices);
      if (v.normals && v.normals.length === v.positions.length) {
        g.setAttribute('normal', new THREE.Float32BufferAttribute(v.normals, 3));
      } else {
        // Without normals, machined parts look right faceted: averaging over shared vertices
        // would round every box's edges into a blob.
        if (g.index) g = g.toNonIndexed();
        g.computeVertexNormals();
      }
      const c = v.colour || [0.7, 0.7, 0.7, 1];
      const scale = Math.max(c[0], c[1], c[2]) > 1 ? 1 / 255 : 1;
      const alpha = c.length > 3 ? (c[3] > 1 ? c[3] / 255 : c[3]) : 1;
      const colour = new THREE.Color(c[0] * scale, c[1] * scale, c[2] * scale);
      const m = new THREE.MeshStandardMaterial({
        color: colour,
        metalness: 0.25,
        roughness: 0.55,
        side: THREE.DoubleSide,
        transparent: alpha < 1,
        opacity: alpha,
      });
      m.userData.colour = colour.clone();
      const mesh = new THREE.Mesh(g, m);
      mesh.userData.name = v.name || '';
      group.add(mesh);
      group.userData.meshes.push(mesh);
    }
    this.scene.add(group);
    return group;
  }

  // Separate segments rather than one polyline: the trail breaks where no cutting tool faces
  // the spindle (state.tool_tip null), and a full ring overwrites its oldest segment in place.
  buildTrail() {
    this.trailPositions = new Float32Array(TRAIL_SEGMENTS * 6);
    this.trailCount = 0;     // segments written since the last clear
    this.trailDirty = null;  // [first, last] segment not yet uploaded
    const g = new THREE.BufferGeometry();
    const attribute = new THREE.BufferAttribute(this.trailPositions, 3);
    attribute.setUsage(THREE.DynamicDrawUsage);
    g.setAttribute('position', attribute);
    g.setDrawRange(0, 0);
    this.trail = new THREE.Group();
    // The path runs inside the (uncut) workpiece: a faint copy drawn through the parts shows
    // where it is hidden, the bright one where it is in sight.
    const hidden = new THREE.LineSegments(
        g,
        new THREE.LineBasicMaterial(
            {color: 0x2fd4ff, transparent: true, opacity: 0.35, depthTest: false}));
    const seen = new THREE.LineSegments(g, new THREE.LineBasicMaterial({color: 0x2fd4ff}));
    for (const line of [hidden, seen]) {
      // The trail's bounding sphere would have to be recomputed on every point.
      line.frustumCulled = false;
      this.trail.add(line);
    }
    hidden.renderOrder = 5;
    this.trailGeometry = g;
    this.scene.add(this.trail);
    this.lastTip = null;
    this.lastT = -Infinity;
  }

  marker(colour, radius) {
    // Drawn over everything: a refusal point inside a part must still be seen.
    const m = new THREE.Mesh(
        new THREE.SphereBufferGeometry(radius, 20, 14),
        new THREE.MeshBasicMaterial(
            {color: colour, depthTest: false, transparent: true, opacity: 0.95}));
    m.renderOrder = 10;
    m.visible = false;
    this.scene.add(m);
    return m;
  }

  buildToolbar() {
    const bar = el('div', {class: 'view-toolbar'});
    this.cameraButtons = this.cameras.map((cam) => {
      const b = el('button', {
        class: 'tb',
        text: cam.name,
        title: `camera ${cam.name}`,
        onclick: () => this.setCamera(cam)
      });
      bar.append(b);
      return b;
    });
    bar.append(el('button', {
      class: 'tb',
      text: 'Fit',
      title: 'fit the machine in the view',
      onclick: () => this.fit()
    }));
    bar.append(el('span', {class: 'tb-sep'}));
    this.trailToggle = el('button', {
      class: 'tb on',
      text: 'Path',
      title: 'show the tool path trail',
      onclick: () => {
        this.trail.visible = !this.trail.visible;
        this.trailToggle.classList.toggle('on', this.trail.visible);
        this.dirty = true;
      }
    });
    bar.append(this.trailToggle);
    bar.append(el('button', {
      class: 'tb',
      text: 'Clear',
      title: 'clear the tool path trail',
      onclick: () => this.clearTrail()
    }));
    this.container.append(bar);
  }

  setCamera(cam) {
    const v = (a) => new THREE.Vector3(a[0], a[1], a[2]);
    this.camera.position.copy(v(cam.eye));
    this.camera.up.copy(v(cam.up || [0, 1, 0])).normalize();
    this.camera.fov = cam.fov_deg || 40;
    this.camera.updateProjectionMatrix();
    this.resetControls(v(cam.target));
    this.cameraButtons.forEach((b, i) => b.classList.toggle('on', this.cameras[i] === cam));
    this.orientGround();
  }

  // OrbitControls takes the camera's up once, when it is made: a camera with another up
  // needs new controls.
  resetControls(target) {
    if (this.controls) this.controls.dispose();
    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.screenSpacePanning = true;
    // r111 listens for the arrow keys on the whole window: typing in a filter would pan.
    this.controls.enableKeys = false;
    this.controls.target.copy(target);
    this.controls.addEventListener('change', () => {
      this.dirty = true;
      this.cameraButtons.forEach((b) => b.classList.remove('on'));
    });
    this.controls.update();
    this.dirty = true;
  }

  fit() {
    const box = new THREE.Box3();
    for (const g of this.links) box.expandByObject(g);
    if (box.isEmpty()) return;
    const centre = box.getCenter(new THREE.Vector3());
    const radius = box.getSize(new THREE.Vector3()).length() / 2;
    const dir = this.camera.position.clone().sub(this.controls ? this.controls.target : centre);
    if (dir.lengthSq() < 1e-12) dir.set(-1, 0.8, 1.2);
    const distance = radius / Math.sin(THREE.Math.degToRad(this.camera.fov) / 2);
    this.camera.position.copy(centre).add(dir.normalize().multiplyScalar(distance));
    this.resetControls(centre);
    this.cameraButtons.forEach((b) => b.classList.remove('on'));
  }

  // A floor grid under the machine, square to the camera's up (the model's world frame is the
  // URDF's, whatever axis is up).
  orientGround() {
    const box = new THREE.Box3();
    for (const g of this.links) box.expandByObject(g);
    if (box.isEmpty()) return;
    if (this.ground) this.scene.remove(this.ground);
    const size = box.getSize(new THREE.Vector3()).length() * 1.6;
    const grid = new THREE.GridHelper(size, 24, 0x56606c, 0x3a424c);
    grid.material.transparent = true;
    grid.material.opacity = 0.55;
    const up = this.camera.up.clone();
    grid.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), up);
    const centre = box.getCenter(new THREE.Vector3());
    // the lowest corner of the box along up
    let low = Infinity;
    for (const x of [box.min.x, box.max.x])
      for (const y of [box.min.y, box.max.y])
        for (const z of [box.min.z, box.max.z]) {
          low = Math.min(low, up.x * x + up.y * y + up.z * z);
        }
    const along = up.dot(centre) - low;
    grid.position.copy(centre).addScaledVector(up, -along - 0.002);
    this.ground = grid;
    this.scene.add(grid);
    this.dirty = true;
  }

  resize() {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.dirty = true;
  }

  clearTrail() {
    this.trailCount = 0;
    this.lastTip = null;
    this.trailDirty = null;
    this.trailGeometry.setDrawRange(0, 0);
    this.dirty = true;
  }

  // The tip's world position (m), or null where no cutting tool faces the spindle.
  addTip(p) {
    if (!Array.isArray(p) || p.length !== 3) {
      this.lastTip = null;
      return;
    }
    const last = this.lastTip;
    if (!last) {
      this.lastTip = p;
      return;
    }
    const dx = p[0] - last[0], dy = p[1] - last[1], dz = p[2] - last[2];
    if (dx * dx + dy * dy + dz * dz < TRAIL_STEP_M * TRAIL_STEP_M) return;
    const i = this.trailCount % TRAIL_SEGMENTS;
    this.trailPositions.set(last, i * 6);
    this.trailPositions.set(p, i * 6 + 3);
    this.trailCount++;
    this.lastTip = p;
    this.trailDirty = this.trailDirty ?
        [Math.min(this.trailDirty[0], i), Math.max(this.trailDirty[1], i)] :
        [i, i];
    this.trailGeometry.setDrawRange(0, Math.min(this.trailCount, TRAIL_SEGMENTS) * 2);
  }

  // Only the segments written since the last frame go to the GPU.
  uploadTrail() {
    if (!this.trailDirty) return;
    const [first, last] = this.trailDirty;
    const attribute = this.trailGeometry.attributes.position;
    attribute.updateRange.offset = first * 6;
    attribute.updateRange.count = (last - first + 1) * 6;
    attribute.needsUpdate = true;
    this.trailDirty = null;
  }

  update(state) {
    const poses = state.poses || [];
    for (let i = 0; i < this.links.length && i < poses.length; i++) {
      const p = poses[i];
      if (!p || p.length < 7) continue;
      this.links[i].position.set(p[0], p[1], p[2]);
      this.links[i].quaternion.set(p[3], p[4], p[5], p[6]);
    }
    if (!this.framed && poses.length) {
      this.framed = true;
      if (!this.cameras.length) {
        this.camera.position.set(-1, 0.8, 1.2);
        this.fit();
      }
      this.orientGround();
    }
    if (state.t < this.lastT) this.clearTrail();  // a replay went back (seek), or a new run
    this.lastT = state.t;
    this.addTip(state.tool_tip);
    this.updateGuard(state.guard);
    if (typeof state.stock === 'number' && state.stock !== this.stockVersion) this.loadStock();
    this.updateMarker(this.probeMarker, state.probe && state.probe.point);
    this.updateLegend(state);
    this.dirty = true;
  }

  // The workpiece as turned: cylinders along its link's z axis replace the stock's visuals.
  // One request at a time; a newer version seen meanwhile is fetched after it.
  async loadStock() {
    if (this.stockLoading) return;
    this.stockLoading = true;
    try {
      const r = await fetch('api/stock', {cache: 'no-store'});
      const stock = await r.json();
      this.showStock(stock);
      this.stockVersion = stock.version;
    } catch (e) {
      // the state poll reports the connection; the next state asks again
    } finally {
      this.stockLoading = false;
    }
  }

  showStock(stock) {
    const group = this.linkByName.get(stock.link);
    if (!group || !Array.isArray(stock.cylinders)) return;
    if (this.stockGroup) {
      this.stockGroup.parent.remove(this.stockGroup);
      for (const m of this.stockGroup.children) m.geometry.dispose();
    }
    const original = group.userData.meshes.find((m) => m.userData.name === 'workpiece');
    const material =
        original ? original.material : new THREE.MeshStandardMaterial({color: 0xc7c9cc});
    for (const m of group.userData.meshes)
      if (m.userData.name === 'workpiece') m.visible = false;
    this.stockGroup = new THREE.Group();
    for (const [z0, length, radius, inner] of stock.cylinders) {
      if (!(length > 0 && radius > 0)) continue;
      // the profile of one run: a ring (or a disc) swept about the axis
      const pts = inner > 0 ?
          [
            new THREE.Vector2(inner, 0), new THREE.Vector2(radius, 0),
            new THREE.Vector2(radius, length), new THREE.Vector2(inner, length),
            new THREE.Vector2(inner, 0)
          ] :
          [
            new THREE.Vector2(0, 0), new THREE.Vector2(radius, 0),
            new THREE.Vector2(radius, length), new THREE.Vector2(0, length)
          ];
      const g = new THREE.LatheGeometry(pts, 96);
      const mesh = new THREE.Mesh(g, material);
      // LatheGeometry turns about y; the spindle's axis is the link's z
      mesh.rotation.x = Math.PI / 2;
      mesh.position.z = z0;
      this.stockGroup.add(mesh);
    }
    group.add(this.stockGroup);
    this.dirty = true;
  }

  updateGuard(guard) {
    const parts = guard && Array.isArray(guard.parts) ? guard.parts : [];
    if (parts.join('\n') !== this.guardParts.join('\n')) {
      for (const g of this.links) {
        for (const mesh of g.userData.meshes) {
          // PathGuard names the collision parts; a model's visuals carry the same names
          const red = parts.includes(g.name) || parts.includes(mesh.userData.name);
          mesh.material.color.copy(red ? GUARD_RED : mesh.material.userData.colour);
          mesh.material.emissive.setHex(red ? 0x4a0000 : 0x000000);
        }
      }
      this.guardParts = parts;
    }
    this.updateMarker(this.guardMarker, guard && guard.point);
  }

  updateMarker(m, point) {
    m.visible = Array.isArray(point) && point.length === 3;
    if (m.visible) m.position.set(point[0], point[1], point[2]);
  }

  updateLegend(state) {
    const parts = [];
    const g = state.guard;
    if (g) {
      const who = (g.parts || []).join(' \u2194 ');
      const move = g.move ? ` (${g.move})` : '';
      parts.push(`<span class="lg guard">PathGuard refused${escapeHtml(move)}: ${escapeHtml(who)}${
          pointText(g.point)}</span>`);
    }
    const p = state.probe;
    if (p && p.point) {
      parts.push(`<span class="lg probe">Probe latched${pointText(p.point)}</span>`);
    } else if (p) {
      // a latch without a point: the drive's latched position
      const value = typeof p.value === 'number' ? ` ${p.drive || ''} = ${p.value.toFixed(3)}` : '';
      const at = typeof p.t === 'number' ? ` at t = ${p.t.toFixed(3)} s` : '';
      parts.push(`<span class="lg probe">Probe latched${escapeHtml(value + at)}</span>`);
    }
    const html = parts.join('');
    if (this.legendHtml !== html) {
      this.legendHtml = html;
      this.legend.innerHTML = html;
    }
  }
}

function pointText(p) {
  if (!Array.isArray(p)) return '';
  return ' at (' + p.map((c) => (c * 1000).toFixed(2)).join(', ') + ') mm';
}

function escapeHtml(s) {
  return String(s).replace(
      /[&<>"]/g, (c) => ({'&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;'}[c]));
}
