// fairgrasp replay, part 1 of 2: the episodes' data and the 3D scene.
// Runs inside one function with viewer.js (see mod.rs); THREE is the inlined three.js bundle.
// Frames: the world is z up; every recorded pose is in base_link, placed in the world by the
// episode's base pose (its mount).

const INDEX = JSON.parse(document.getElementById("replay-index").textContent);
const EPISODES = INDEX.episodes;

/** The differenced pose values of every episode, inflated by the browser (no network). */
async function inflatePoses() {
  const text = document.getElementById("replay-poses").textContent.trim();
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; i++) bytes[i] = binary.charCodeAt(i);
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream("gzip"));
  const planes = new Uint8Array(await new Response(stream).arrayBuffer());
  const n = planes.length / 2;
  const out = new Int16Array(n);
  for (let i = 0; i < n; i++) {
    const z = planes[i] | (planes[n + i] << 8);
    out[i] = (z >>> 1) ^ -(z & 1);
  }
  return out;
}

/** Poses of one episode: poses[(step * tracks + track) * 7 + k], tracks = bodies, cube, TCP. */
function decodeEpisode(ep, values) {
  const tracks = ep.bodies.length + 2;
  const steps = ep.steps;
  const poses = new Float32Array(steps * tracks * 7);
  for (let tr = 0; tr < tracks; tr++) {
    for (let k = 0; k < 7; k++) {
      const scale = k < 3 ? INDEX.positionStep : 1 / INDEX.quatScale;
      let base = ep.offset + (tr * 7 + k) * steps;
      let acc = 0;
      for (let s = 0; s < steps; s++) {
        acc = (acc + values[base + s]) << 16 >> 16; // 16-bit wrap, as written
        poses[(s * tracks + tr) * 7 + k] = acc * scale;
      }
    }
  }
  return { poses, tracks };
}

const COLOURS = {
  link: 0xdfe3e8,
  gripper: 0x3b4048,
  pad: 0xe8912d,
  padTouching: 0x2fbf71,
  cube: 0xd9534f,
  table: 0xb48a5a,
  pedestal: 0x6d7580,
  trail: 0x2a7de1,
  background: 0xf4f6f9,
};

function material(colour) {
  return new THREE.MeshLambertMaterial({ color: colour });
}

function setPose(object, p, i) {
  object.position.set(p[i], p[i + 1], p[i + 2]);
  object.quaternion.set(p[i + 3], p[i + 4], p[i + 5], p[i + 6]).normalize();
}

/** A mesh for one recorded shape, placed in its body's frame. */
function shapeMesh(shape) {
  const isPad = /pad$/.test(shape.name);
  const isGripper = isPad || /palm|finger/.test(shape.name);
  const mat = material(isPad ? COLOURS.pad : isGripper ? COLOURS.gripper : COLOURS.link);
  if (shape.kind === "capsule") {
    const a = new THREE.Vector3(...shape.a);
    const b = new THREE.Vector3(...shape.b);
    const axis = b.clone().sub(a);
    const length = axis.length();
    const mesh = new THREE.Mesh(new THREE.CapsuleGeometry(shape.radius, length, 6, 20), mat);
    mesh.position.copy(a.clone().add(b).multiplyScalar(0.5));
    if (length > 1e-9) {
      mesh.quaternion.setFromUnitVectors(new THREE.Vector3(0, 1, 0), axis.normalize());
    }
    return mesh;
  }
  const h = shape.half_extents;
  const mesh = new THREE.Mesh(new THREE.BoxGeometry(2 * h[0], 2 * h[1], 2 * h[2]), mat);
  mesh.position.set(...shape.centre);
  return mesh;
}

/** The table, its legs and the floor, in the world (or, for older files, under the base). */
function addTable(ep, world, baseGroup) {
  const grid = new THREE.GridHelper(3, 30, 0xb9c0c8, 0xd6dbe1);
  grid.rotation.x = Math.PI / 2;
  world.add(grid);
  const tableMat = material(COLOURS.table);
  if (ep.table) {
    const c = ep.table.centre;
    const h = ep.table.half_extents;
    const top = new THREE.Mesh(new THREE.BoxGeometry(2 * h[0], 2 * h[1], 2 * h[2]), tableMat);
    top.position.set(c[0], c[1], c[2]);
    world.add(top);
    const legHeight = c[2] - h[2];
    if (legHeight > 0.01) {
      for (const [sx, sy] of [[-1, -1], [1, -1], [1, 1], [-1, 1]]) {
        const leg = new THREE.Mesh(new THREE.BoxGeometry(0.05, 0.05, legHeight), tableMat);
        leg.position.set(c[0] + sx * (h[0] - 0.05), c[1] + sy * (h[1] - 0.05), legHeight / 2);
        world.add(leg);
      }
    }
    return c[2] + h[2];
  }
  const xs = ep.tableCorners.map((p) => p[0]);
  const ys = ep.tableCorners.map((p) => p[1]);
  const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
  const top = new THREE.Mesh(new THREE.BoxGeometry(x1 - x0, y1 - y0, 0.1), tableMat);
  top.position.set((x0 + x1) / 2, (y0 + y1) / 2, ep.tableTopZ - 0.05);
  baseGroup.add(top);
  return null;
}

/** The mount: a pedestal from the table top (or the floor) to the base, a plate under the
 *  base that tilts with it, and the base's axes (x red: its heading). */
function addMount(ep, world, baseGroup, tableTop) {
  const b = ep.base;
  const from = tableTop !== null && b[2] > tableTop ? tableTop : 0;
  const height = b[2] - from;
  if (height > 0.005) {
    const column = new THREE.Mesh(
      new THREE.CylinderGeometry(0.07, 0.08, height, 32),
      material(COLOURS.pedestal),
    );
    column.rotation.x = Math.PI / 2;
    column.position.set(b[0], b[1], from + height / 2);
    world.add(column);
  }
  const plate = new THREE.Mesh(new THREE.CylinderGeometry(0.1, 0.1, 0.012, 32), material(COLOURS.pedestal));
  plate.rotation.x = Math.PI / 2;
  plate.position.z = -0.007;
  baseGroup.add(plate);
  baseGroup.add(new THREE.AxesHelper(0.18));
}

/** One episode's scene: meshes for every body, the cube, the TCP's path; `show(t)` poses them
 *  at time t [s] (interpolated between steps). */
function buildView(index, values) {
  const ep = EPISODES[index];
  const { poses, tracks } = decodeEpisode(ep, values);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(COLOURS.background);
  scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8f96, 2.2));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(1.5, -1.0, 3.0);
  scene.add(sun);
  const world = new THREE.Group();
  scene.add(world);
  const baseGroup = new THREE.Group();
  setPose(baseGroup, ep.base, 0);
  world.add(baseGroup);
  const tableTop = addTable(ep, world, baseGroup);
  addMount(ep, world, baseGroup, tableTop);

  const bodies = ep.bodies.map(() => new THREE.Group());
  bodies.forEach((g) => baseGroup.add(g));
  const pads = [];
  for (const shape of ep.shapes) {
    const mesh = shapeMesh(shape);
    bodies[shape.body].add(mesh);
    if (/left_pad$/.test(shape.name)) pads[0] = mesh;
    if (/right_pad$/.test(shape.name)) pads[1] = mesh;
  }
  const cube = new THREE.Mesh(new THREE.BoxGeometry(ep.cube, ep.cube, ep.cube), material(COLOURS.cube));
  baseGroup.add(cube);
  const tcp = new THREE.Group();
  baseGroup.add(tcp);
  const path = new Float32Array(ep.steps * 3);
  const tcpTrack = tracks - 1;
  for (let s = 0; s < ep.steps; s++) {
    for (let k = 0; k < 3; k++) path[s * 3 + k] = poses[(s * tracks + tcpTrack) * 7 + k];
  }
  const trailGeometry = new THREE.BufferGeometry();
  trailGeometry.setAttribute("position", new THREE.Float32BufferAttribute(path, 3));
  const trail = new THREE.Line(trailGeometry, new THREE.LineBasicMaterial({ color: COLOURS.trail }));
  baseGroup.add(trail);

  const qa = new THREE.Quaternion();
  const qb = new THREE.Quaternion();
  const duration = (ep.steps - 1) * ep.dt;
  function place(object, track, s0, s1, f) {
    const i = (s0 * tracks + track) * 7;
    const j = (s1 * tracks + track) * 7;
    object.position.set(
      poses[i] + f * (poses[j] - poses[i]),
      poses[i + 1] + f * (poses[j + 1] - poses[i + 1]),
      poses[i + 2] + f * (poses[j + 2] - poses[i + 2]),
    );
    qa.set(poses[i + 3], poses[i + 4], poses[i + 5], poses[i + 6]).normalize();
    qb.set(poses[j + 3], poses[j + 4], poses[j + 5], poses[j + 6]).normalize();
    object.quaternion.slerpQuaternions(qa, qb, f);
  }
  /** The step shown at time t (nearest) and the pose interpolation between steps. */
  function show(t) {
    const s = ep.dt > 0 ? Math.min(Math.max(t, 0), duration) / ep.dt : 0;
    const s0 = Math.min(Math.floor(s), ep.steps - 1);
    const s1 = Math.min(s0 + 1, ep.steps - 1);
    const f = s - s0;
    bodies.forEach((g, b) => place(g, b, s0, s1, f));
    place(cube, tracks - 2, s0, s1, f);
    place(tcp, tracks - 1, s0, s1, f);
    const step = Math.min(Math.round(s), ep.steps - 1);
    const touching = ep.contacts[step] || 0;
    pads.forEach((m, k) => {
      if (m) m.material.color.setHex(touching & (1 << k) ? COLOURS.padTouching : COLOURS.pad);
    });
    trailGeometry.setDrawRange(0, step + 1);
    return step;
  }
  /** World position of a thing of the scene. */
  function worldPosition(object) {
    scene.updateMatrixWorld(true);
    return object.getWorldPosition(new THREE.Vector3()).toArray();
  }
  const palm = bodies[ep.bodies.indexOf("palm")] || bodies[bodies.length - 1];
  return {
    index,
    ep,
    scene,
    duration,
    show,
    tcpWorld: () => worldPosition(tcp),
    palmWorld: () => worldPosition(palm),
    cubeWorld: () => worldPosition(cube),
  };
}

/** Orbit (left drag), pan (right drag or shift + drag) and zoom (wheel) of one camera, z up. */
function orbitControls(element, camera, onChange) {
  const o = { target: new THREE.Vector3(0.3, 0, 0.65), radius: 1.7, theta: -1.1, phi: 1.05 };
  function update() {
    const sp = Math.sin(o.phi);
    camera.up.set(0, 0, 1);
    camera.position.set(
      o.target.x + o.radius * sp * Math.cos(o.theta),
      o.target.y + o.radius * sp * Math.sin(o.theta),
      o.target.z + o.radius * Math.cos(o.phi),
    );
    camera.lookAt(o.target);
    onChange();
  }
  let drag = null;
  element.addEventListener("contextmenu", (e) => e.preventDefault());
  element.addEventListener("pointerdown", (e) => {
    drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey };
    element.setPointerCapture(e.pointerId);
  });
  element.addEventListener("pointerup", () => (drag = null));
  element.addEventListener("pointermove", (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x;
    const dy = e.clientY - drag.y;
    drag.x = e.clientX;
    drag.y = e.clientY;
    if (drag.pan) {
      const right = new THREE.Vector3().setFromMatrixColumn(camera.matrix, 0);
      const up = new THREE.Vector3().setFromMatrixColumn(camera.matrix, 1);
      const k = (o.radius * 1.2) / element.clientHeight;
      o.target.addScaledVector(right, -dx * k).addScaledVector(up, dy * k);
    } else {
      o.theta -= dx * 0.008;
      o.phi = Math.min(Math.max(o.phi - dy * 0.008, 0.05), Math.PI - 0.05);
    }
    update();
  });
  element.addEventListener(
    "wheel",
    (e) => {
      e.preventDefault();
      o.radius = Math.min(Math.max(o.radius * Math.exp(e.deltaY * 0.001), 0.2), 8);
      update();
    },
    { passive: false },
  );
  return { state: o, update };
}
