// fairgrasp replay, part 2 of 2: selector, side-by-side view, timeline, URL fragment, and the
// state the browser test reads (window.fairgraspReplay).

const SPEEDS = [0.25, 0.5, 1, 2, 4];
const PHASE_COLOURS = {
  plan: "#9aa5b1", approach: "#5b8def", descend: "#8a63d2", close: "#e8912d",
  lift: "#2fbf71", hold: "#1b9e5a", failed: "#d9534f", reopen: "#f2c94c", "": "#c9ced6",
};

function el(tag, attrs, ...children) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs || {})) e.setAttribute(k, v);
  for (const c of children) e.append(c);
  return e;
}

function label(i) {
  const e = EPISODES[i];
  return `${i}: ${e.method} · ${e.preset} #${e.episode} · ${e.outcome || "?"}`;
}

/** Entries showing the same scenario as entry i by another method. */
function partnersOf(i) {
  const e = EPISODES[i];
  return EPISODES.map((x, j) => j)
    .filter((j) => j !== i && EPISODES[j].preset === e.preset && EPISODES[j].episode === e.episode);
}

function parseFragment() {
  const out = {};
  for (const part of location.hash.replace(/^#/, "").split("&")) {
    const [k, v] = part.split("=");
    if (k) out[decodeURIComponent(k)] = decodeURIComponent(v || "");
  }
  return out;
}

async function main() {
  const app = document.getElementById("app");
  const title = el("h1", {}, INDEX.title);
  const pick = el("select", { id: "episode", title: "method and episode" });
  EPISODES.forEach((_, i) => pick.append(el("option", { value: String(i) }, label(i))));
  const partner = el("select", { id: "partner", title: "the same scenario by another method" });
  const views = el("div", { id: "views" });
  const canvas = el("canvas", { id: "scene" });
  const banners = [el("div", { class: "banner" }), el("div", { class: "banner right" })];
  views.append(canvas, ...banners);
  const play = el("button", { id: "play", title: "play / pause (space)" }, "▶");
  const back = el("button", { id: "back", title: "one step back (←)" }, "◀|");
  const fwd = el("button", { id: "forward", title: "one step forward (→)" }, "|▶");
  const speed = el("select", { id: "speed", title: "speed" });
  SPEEDS.forEach((s) => speed.append(el("option", { value: String(s) }, `${s}×`)));
  speed.value = "1";
  const scrub = el("input", { id: "scrub", type: "range", min: "0", max: "1000", value: "0" });
  const clock = el("span", { id: "clock" });
  const timeline = el("canvas", { id: "timeline" });
  const info = el("div", { id: "info" });
  app.append(
    el("header", {}, title, pick, el("label", {}, "side by side with ", partner)),
    views,
    el("div", { id: "controls" }, back, play, fwd, speed, scrub, clock),
    timeline,
    info,
    el("p", { class: "help" }, "Drag to orbit, right-drag (or shift-drag) to pan, wheel to zoom. " +
      `Link to this moment: the address ends in #episode=N&t=SECONDS. three.js ${INDEX.three}.`),
  );

  const renderer = new THREE.WebGLRenderer({ canvas, antialias: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 30);
  let dirty = true;
  const controls = orbitControls(canvas, camera, () => (dirty = true));
  const values = await inflatePoses();
  const cache = new Map();
  const view = (i) => {
    if (!cache.has(i)) cache.set(i, buildView(i, values));
    return cache.get(i);
  };

  const s = { current: 0, partner: -1, time: 0, playing: false, speed: 1, steps: [0, 0] };
  const shown = () => [view(s.current)].concat(s.partner >= 0 ? [view(s.partner)] : []);
  const duration = () => Math.max(...shown().map((v) => v.duration));

  function fillPartners() {
    partner.replaceChildren(el("option", { value: "-1" }, "(none)"));
    for (const j of partnersOf(s.current)) partner.append(el("option", { value: String(j) }, label(j)));
    partner.value = String(s.partner);
  }
  function select(i, j, keepTime) {
    s.current = Math.min(Math.max(i | 0, 0), EPISODES.length - 1);
    s.partner = partnersOf(s.current).includes(j) ? j : -1;
    pick.value = String(s.current);
    fillPartners();
    view(s.current).show(s.time);
    const cube = view(s.current).cubeWorld();
    controls.state.target.set((cube[0] + EPISODES[s.current].base[0]) / 2, cube[1] / 2, cube[2] + 0.1);
    controls.update();
    if (!keepTime) s.time = 0;
    seek(s.time);
  }
  function seek(t) {
    s.time = Math.min(Math.max(Number(t) || 0, 0), duration());
    dirty = true;
  }
  function writeFragment() {
    const w = s.partner >= 0 ? `&with=${s.partner}` : "";
    history.replaceState(null, "", `#episode=${s.current}&t=${s.time.toFixed(2)}${w}`);
  }
  function applyFragment() {
    const f = parseFragment();
    select(f.episode !== undefined ? Number(f.episode) : 0, f.with !== undefined ? Number(f.with) : -1, true);
    seek(f.t !== undefined ? Number(f.t) : 0);
  }

  function resize() {
    const w = views.clientWidth;
    const h = Math.max(260, Math.round(Math.min(window.innerHeight * 0.62, w * 0.62)));
    renderer.setSize(w, h, false);
    canvas.style.width = `${w}px`;
    canvas.style.height = `${h}px`;
    timeline.width = w;
    timeline.height = 96 * shown().length + 14;
    dirty = true;
  }

  function drawFrame() {
    const vs = shown();
    const size = renderer.getSize(new THREE.Vector2());
    const w = size.x / vs.length;
    camera.aspect = w / size.y;
    camera.updateProjectionMatrix();
    renderer.setScissorTest(true);
    vs.forEach((v, k) => {
      s.steps[k] = v.show(s.time);
      renderer.setViewport(k * w, 0, w, size.y);
      renderer.setScissor(k * w, 0, w, size.y);
      renderer.render(v.scene, camera);
      const ended = s.time >= v.duration - 1e-9;
      const ep = v.ep;
      banners[k].className = `banner${k ? " right" : ""}${vs.length > 1 ? " half" : ""}`;
      banners[k].textContent = `${ep.method} · ${ep.preset} #${ep.episode}` +
        (ended ? ` — outcome: ${ep.outcome || "?"}` : "");
      banners[k].dataset.outcome = ended ? ep.outcome || "" : "";
    });
    banners[1].style.display = vs.length > 1 ? "" : "none";
    scrub.value = String(Math.round((1000 * s.time) / Math.max(duration(), 1e-9)));
    clock.textContent = `${s.time.toFixed(2)} s / ${duration().toFixed(2)} s · step ${s.steps[0]}`;
    drawTimeline(timeline, vs, s.time, duration());
    info.replaceChildren(...vs.map((v, k) => stepInfo(v.ep, s.steps[k])));
  }

  let last = null;
  function loop(now) {
    if (s.playing && last !== null) {
      s.time += ((now - last) / 1000) * s.speed;
      if (s.time >= duration()) {
        s.time = duration();
        s.playing = false;
        play.textContent = "▶";
        writeFragment();
      }
      dirty = true;
    }
    last = now;
    if (dirty) {
      dirty = false;
      drawFrame();
    }
    requestAnimationFrame(loop);
  }

  const stepBy = (n) => {
    const dt = EPISODES[s.current].dt || 0.1;
    s.playing = false;
    play.textContent = "▶";
    seek((Math.round(s.time / dt) + n) * dt);
    writeFragment();
  };
  const togglePlay = () => {
    if (!s.playing && s.time >= duration()) s.time = 0;
    s.playing = !s.playing;
    play.textContent = s.playing ? "❚❚" : "▶";
    if (!s.playing) writeFragment();
  };
  play.addEventListener("click", togglePlay);
  back.addEventListener("click", () => stepBy(-1));
  fwd.addEventListener("click", () => stepBy(1));
  speed.addEventListener("change", () => (s.speed = Number(speed.value)));
  scrub.addEventListener("input", () => seek((Number(scrub.value) / 1000) * duration()));
  scrub.addEventListener("change", writeFragment);
  pick.addEventListener("change", () => {
    select(Number(pick.value), -1, false);
    resize();
    writeFragment();
  });
  partner.addEventListener("change", () => {
    select(s.current, Number(partner.value), true);
    resize();
    writeFragment();
  });
  const scrubTimeline = (e) => {
    const r = timeline.getBoundingClientRect();
    seek(((e.clientX - r.left - GUTTER) / (r.width - GUTTER - 8)) * duration());
  };
  timeline.addEventListener("pointerdown", (e) => {
    timeline.setPointerCapture(e.pointerId);
    scrubTimeline(e);
    timeline.onpointermove = scrubTimeline;
  });
  timeline.addEventListener("pointerup", () => {
    timeline.onpointermove = null;
    writeFragment();
  });
  document.addEventListener("keydown", (e) => {
    if (e.target.tagName === "SELECT" || e.target.tagName === "INPUT") return;
    if (e.key === " ") (e.preventDefault(), togglePlay());
    if (e.key === "ArrowLeft") stepBy(-1);
    if (e.key === "ArrowRight") stepBy(1);
  });
  window.addEventListener("resize", resize);
  window.addEventListener("hashchange", () => (applyFragment(), resize()));

  applyFragment();
  resize();
  drawFrame();
  requestAnimationFrame(loop);

  window.fairgraspReplay = {
    ready: true,
    count: EPISODES.length,
    select: (i, j) => (select(i, j === undefined ? -1 : j, false), resize(), drawFrame()),
    seek: (t) => (seek(t), drawFrame()),
    play: () => s.playing || togglePlay(),
    pause: () => s.playing && togglePlay(),
    state: () => {
      // The poses below are the scene's: bring it to the current time first (the animation
      // loop may not have drawn since the last seek, e.g. on a busy machine).
      if (dirty) {
        dirty = false;
        drawFrame();
      }
      const v = view(s.current);
      return {
        episode: s.current, partner: s.partner, label: label(s.current), time: s.time,
        duration: duration(), step: s.steps[0], playing: s.playing,
        tcp: v.tcpWorld(), palm: v.palmWorld(), cube: v.cubeWorld(),
        banner: banners[0].textContent, fragment: location.hash,
      };
    },
    /** Renders now and reads the pixels back: size, distinct colours, share not background,
     *  and a hash of the image. */
    pixels: () => {
      drawFrame();
      const gl = renderer.getContext();
      const [w, h] = [gl.drawingBufferWidth, gl.drawingBufferHeight];
      const px = new Uint8Array(w * h * 4);
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
      const colours = new Set();
      let other = 0;
      let hash = 2166136261;
      const bg = new THREE.Color(COLOURS.background);
      const [br, bgc, bb] = [bg.r, bg.g, bg.b].map((c) => Math.round(c * 255));
      for (let i = 0; i < px.length; i += 4) {
        colours.add((px[i] << 16) | (px[i + 1] << 8) | px[i + 2]);
        const d = Math.abs(px[i] - br) + Math.abs(px[i + 1] - bgc) + Math.abs(px[i + 2] - bb);
        if (d > 24) other++;
        hash = Math.imul(hash ^ px[i] ^ (px[i + 1] << 8) ^ (px[i + 2] << 16), 16777619) >>> 0;
      }
      return { width: w, height: h, colours: colours.size, notBackground: other / (w * h), hash };
    },
  };
}

const GUTTER = 74;

/** The timeline of each shown episode: phase, reward, gripper command, pad contacts, events,
 *  and the outcome at the end; a cursor at time t. */
function drawTimeline(canvas, vs, t, duration) {
  const g = canvas.getContext("2d");
  const W = canvas.width;
  const x = (time) => GUTTER + ((W - GUTTER - 8) * time) / Math.max(duration, 1e-9);
  g.clearRect(0, 0, W, canvas.height);
  g.font = "11px sans-serif";
  vs.forEach((v, k) => {
    const ep = v.ep;
    const top = 6 + k * 96;
    const at = (step) => x(step * ep.dt);
    const lane = (row, name) => {
      g.fillStyle = "#4a5260";
      g.fillText(name, 4, top + row * 18 + 12);
      return top + row * 18;
    };
    let y = lane(0, k ? "phase (2)" : "phase");
    ep.phases.forEach(([from, name], i) => {
      const to = i + 1 < ep.phases.length ? ep.phases[i + 1][0] : ep.steps - 1;
      g.fillStyle = PHASE_COLOURS[name] || "#c9ced6";
      g.fillRect(at(from), y + 2, Math.max(at(to) - at(from), 1), 13);
      g.fillStyle = "#fff";
      if (at(to) - at(from) > 40) g.fillText(name, at(from) + 3, y + 12);
    });
    const plot = (row, name, series, lo, hi, colour) => {
      const y0 = lane(row, name);
      g.strokeStyle = colour;
      g.beginPath();
      series.forEach((val, i) => {
        const yy = y0 + 15 - (13 * (val - lo)) / Math.max(hi - lo, 1e-9);
        i ? g.lineTo(at(i), yy) : g.moveTo(at(i), yy);
      });
      g.stroke();
    };
    plot(1, "reward", ep.reward, Math.min(0, ...ep.reward), Math.max(0, ...ep.reward), "#2a7de1");
    plot(2, "gripper cmd", ep.gripper, -1, 1, "#8a63d2");
    y = lane(3, "pad contact");
    ep.contacts.forEach((c, i) => {
      g.fillStyle = "#2fbf71";
      if (c & 1) g.fillRect(at(i), y + 3, Math.max(at(i + 1) - at(i), 1), 5);
      if (c & 2) g.fillRect(at(i), y + 10, Math.max(at(i + 1) - at(i), 1), 5);
    });
    g.fillStyle = "#d9534f";
    for (const [step] of ep.events) g.fillRect(at(step) - 1, top, 3, 4 * 18);
    const end = at(ep.steps - 1);
    g.fillStyle = ep.outcome === "success" ? "#1b9e5a" : "#d9534f";
    g.fillRect(end - 3, top, 3, 4 * 18);
    g.fillText(ep.outcome || "?", Math.min(end - 4 - g.measureText(ep.outcome || "?").width, W - 60), top + 4 * 18 + 11);
  });
  g.strokeStyle = "#111";
  g.beginPath();
  g.moveTo(x(t), 0);
  g.lineTo(x(t), canvas.height);
  g.stroke();
}

/** The values at one step of one episode, and the events so far. */
function stepInfo(ep, step) {
  let phase = "";
  for (const [from, name] of ep.phases) if (from <= step) phase = name;
  const c = ep.contacts[step] || 0;
  const events = ep.events.filter(([at]) => at <= step).map(([at, text]) => `step ${at}: ${text}`);
  return el(
    "div",
    { class: "step" },
    el("b", {}, `${ep.method} (${ep.preset} #${ep.episode})`),
    ` step ${step}: phase ${phase || "–"}, reward ${ep.reward[step]}, gripper command ${ep.gripper[step]}, ` +
      `pads ${c & 1 ? "L" : "–"}${c & 2 ? "R" : "–"}` + (events.length ? ` · ${events.join(" · ")}` : ""),
  );
}

main().catch((e) => {
  document.getElementById("app").textContent = `The replay could not start: ${e && e.message}`;
  window.fairgraspReplay = { ready: false, error: String(e && e.message) };
});
