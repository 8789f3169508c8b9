// The ikarus playground: draws the arm on a canvas and asks the JSON API (same origin) to
// solve, animate, sample the workspace and render pictures. Plain ES2020, no dependencies.
"use strict";

(() => {
  const COLORS = {
    page: "#fbfaf7",
    plot: "#ffffff",
    grid: "#e7eaee",
    axis: "#b9c0cb",
    label: "#5b6478",
    ink: "#26324a",
    reach: "#5f9e77",
    goal: "#d62728",
    path: "#ec7f2d",
    trace: "#8a9bb8",
    area: "rgba(95, 158, 119, 0.18)",
  };
  const PLAYBACK_MS = 1000;
  const FOLLOW_RECORD_EVERY = 100000;
  const WORKSPACE_RESOLUTION = 160;
  const DRAG_PIXELS = 4;

  const $ = (id) => document.getElementById(id);
  const canvas = $("plot");
  const ctx = canvas.getContext("2d");

  const state = {
    arm: null, // the arm file as JSON: {name, base, links: [{length, angle_deg, limits_deg}]}
    initialArm: null,
    pose_deg: [],
    joints: [], // [[x, y], …] of the current pose, base first
    goal: null, // {x, y}
    options: {},
    ease: { kind: "sine" },
    frames: 60,
    follow: false,
    showGhosts: true,
    showTraces: true,
    showWorkspace: false,
    workspace: null,
    animation: null, // the last /api/animate answer
    animationRequest: null,
    playing: null, // {start, frames, duration, index}
    lastResponse: null,
    status: "loading",
    error: null,
  };

  // ---- HTTP ---------------------------------------------------------------------------------

  async function post(path, body, as = "json") {
    const res = await fetch(path, {
      method: "POST",
      headers: { "content-type": "application/json" },
      body: JSON.stringify(body),
    });
    if (!res.ok) {
      let message = `${path}: HTTP ${res.status}`;
      try {
        const e = await res.json();
        if (e && e.error) message = e.error;
      } catch (_) {
        /* not JSON: keep the status line */
      }
      const err = new Error(message);
      err.api = true;
      throw err;
    }
    return as === "blob" ? res.blob() : res.json();
  }

  function showError(e) {
    const el = $("error");
    if (!e) {
      el.hidden = true;
      el.textContent = "";
      state.error = null;
      return;
    }
    state.error = e.message || String(e);
    el.textContent = state.error;
    el.hidden = false;
    if (!e.api) console.warn("ikarus:", e);
  }

  function setStatus(status) {
    state.status = status;
    document.body.dataset.status = status;
    if (status === "error") $("stats").textContent = "status error · see the message below";
  }

  // ---- Geometry -----------------------------------------------------------------------------

  const DEG = Math.PI / 180;

  function forward(arm, pose) {
    const [bx, by] = arm.base || [0, 0];
    const joints = [[bx, by]];
    let x = bx;
    let y = by;
    let a = 0;
    arm.links.forEach((link, i) => {
      a += (pose[i] ?? link.angle_deg) * DEG;
      x += link.length * Math.cos(a);
      y += link.length * Math.sin(a);
      joints.push([x, y]);
    });
    return joints;
  }

  const maxReach = () => state.arm.links.reduce((s, l) => s + Math.max(0, Number(l.length) || 0), 0);

  let view = { cx: 0, cy: 0, scale: 1, w: 1, h: 1 };

  function updateView() {
    const w = canvas.clientWidth;
    const h = canvas.clientHeight;
    const [bx, by] = state.arm.base || [0, 0];
    const half = Math.max(maxReach(), 1e-3) * 1.12;
    const scale = Math.min(w, h) / (2 * half);
    view = { cx: w / 2 - bx * scale, cy: h / 2 + by * scale, scale, w, h };
  }

  const toCanvas = (x, y) => [view.cx + x * view.scale, view.cy - y * view.scale];
  const toWorld = (px, py) => [(px - view.cx) / view.scale, (view.cy - py) / view.scale];

  function niceStep(span) {
    const raw = span / 8;
    const p = 10 ** Math.floor(Math.log10(raw));
    const m = raw / p;
    return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
  }

  // ---- Drawing ------------------------------------------------------------------------------

  function resize() {
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, canvas.clientWidth);
    const h = Math.max(1, canvas.clientHeight);
    if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
      canvas.width = Math.round(w * dpr);
      canvas.height = Math.round(h * dpr);
    }
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    if (state.arm) updateView();
  }

  function drawGrid() {
    const { w, h } = view;
    ctx.fillStyle = COLORS.plot;
    ctx.fillRect(0, 0, w, h);
    const [x0, y1] = toWorld(0, 0);
    const [x1, y0] = toWorld(w, h);
    const step = niceStep(Math.min(x1 - x0, y1 - y0));
    const decimals = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
    ctx.lineWidth = 1;
    ctx.strokeStyle = COLORS.grid;
    ctx.beginPath();
    for (let gx = Math.ceil(x0 / step) * step; gx <= x1; gx += step) {
      const [px] = toCanvas(gx, 0);
      ctx.moveTo(Math.round(px) + 0.5, 0);
      ctx.lineTo(Math.round(px) + 0.5, h);
    }
    for (let gy = Math.ceil(y0 / step) * step; gy <= y1; gy += step) {
      const [, py] = toCanvas(0, gy);
      ctx.moveTo(0, Math.round(py) + 0.5);
      ctx.lineTo(w, Math.round(py) + 0.5);
    }
    ctx.stroke();
    // Axes through the origin (or along the edges when the origin is out of view).
    const [ox, oy] = toCanvas(0, 0);
    const ax = Math.min(Math.max(ox, 0), w);
    const ay = Math.min(Math.max(oy, 0), h);
    ctx.strokeStyle = COLORS.axis;
    ctx.beginPath();
    ctx.moveTo(0, Math.round(ay) + 0.5);
    ctx.lineTo(w, Math.round(ay) + 0.5);
    ctx.moveTo(Math.round(ax) + 0.5, 0);
    ctx.lineTo(Math.round(ax) + 0.5, h);
    ctx.stroke();
    ctx.fillStyle = COLORS.label;
    ctx.font = "11px system-ui, sans-serif";
    ctx.textAlign = "center";
    ctx.textBaseline = "top";
    for (let gx = Math.ceil(x0 / step) * step; gx <= x1; gx += step) {
      if (Math.abs(gx) < step / 2) continue;
      const [px] = toCanvas(gx, 0);
      ctx.fillText(gx.toFixed(decimals), px, Math.min(ay + 3, h - 14));
    }
    ctx.textAlign = "right";
    ctx.textBaseline = "middle";
    for (let gy = Math.ceil(y0 / step) * step; gy <= y1; gy += step) {
      if (Math.abs(gy) < step / 2) continue;
      const [, py] = toCanvas(0, gy);
      ctx.fillText(gy.toFixed(decimals), Math.max(ax - 4, 28), py);
    }
    ctx.textAlign = "left";
    ctx.textBaseline = "top";
    ctx.fillText("x", w - 12, ay + 3);
    ctx.fillText("y", ax + 5, 4);
  }

  let areaImage = null; // an offscreen canvas with one pixel per workspace cell

  function buildAreaImage(ws) {
    const n = ws.resolution;
    const off = document.createElement("canvas");
    off.width = n;
    off.height = n;
    const octx = off.getContext("2d");
    const img = octx.createImageData(n, n);
    // grid[iy] runs from the lowest row (y = origin) up; the image runs from the top down.
    ws.grid.forEach((row, iy) => {
      const py = n - 1 - iy;
      for (let ix = 0; ix < n; ix++) {
        if (row.charCodeAt(ix) === 49) {
          const k = (py * n + ix) * 4;
          img.data[k] = 95;
          img.data[k + 1] = 158;
          img.data[k + 2] = 119;
          img.data[k + 3] = 56;
        }
      }
    });
    octx.putImageData(img, 0, 0);
    return off;
  }

  function drawArea() {
    const ws = state.workspace;
    if (!state.showWorkspace || !ws || !areaImage) return;
    const side = ws.resolution * ws.cell_size;
    const [px, py] = toCanvas(ws.origin[0], ws.origin[1] + side);
    ctx.imageSmoothingEnabled = false;
    ctx.drawImage(areaImage, px, py, side * view.scale, side * view.scale);
    ctx.imageSmoothingEnabled = true;
  }

  function drawReach() {
    const [bx, by] = toCanvas(...(state.arm.base || [0, 0]));
    ctx.setLineDash([6, 5]);
    ctx.strokeStyle = COLORS.reach;
    ctx.lineWidth = 1.5;
    ctx.beginPath();
    ctx.arc(bx, by, maxReach() * view.scale, 0, 2 * Math.PI);
    ctx.stroke();
    ctx.setLineDash([]);
  }

  function polyline(points) {
    ctx.beginPath();
    points.forEach(([x, y], i) => {
      const [px, py] = toCanvas(x, y);
      if (i === 0) ctx.moveTo(px, py);
      else ctx.lineTo(px, py);
    });
  }

  function drawArm(joints, alpha = 1, width = 7) {
    ctx.globalAlpha = alpha;
    ctx.lineCap = "round";
    ctx.lineJoin = "round";
    ctx.strokeStyle = COLORS.ink;
    ctx.lineWidth = width;
    polyline(joints);
    ctx.stroke();
    if (alpha === 1) {
      joints.forEach(([x, y], i) => {
        const [px, py] = toCanvas(x, y);
        ctx.beginPath();
        ctx.arc(px, py, i === joints.length - 1 ? 4 : 5, 0, 2 * Math.PI);
        ctx.fillStyle = "#fff";
        ctx.fill();
        ctx.lineWidth = 2;
        ctx.strokeStyle = COLORS.ink;
        ctx.stroke();
      });
    }
    ctx.globalAlpha = 1;
  }

  function drawBase() {
    const [px, py] = toCanvas(...(state.arm.base || [0, 0]));
    ctx.fillStyle = COLORS.ink;
    ctx.beginPath();
    ctx.moveTo(px, py);
    ctx.lineTo(px - 11, py + 15);
    ctx.lineTo(px + 11, py + 15);
    ctx.closePath();
    ctx.globalAlpha = 0.85;
    ctx.fill();
    ctx.globalAlpha = 1;
    ctx.fillRect(px - 16, py + 15, 32, 3);
  }

  function drawGoal() {
    if (!state.goal) return;
    const [px, py] = toCanvas(state.goal.x, state.goal.y);
    ctx.strokeStyle = COLORS.goal;
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.arc(px, py, 8, 0, 2 * Math.PI);
    ctx.moveTo(px - 13, py);
    ctx.lineTo(px + 13, py);
    ctx.moveTo(px, py - 13);
    ctx.lineTo(px, py + 13);
    ctx.stroke();
  }

  function drawMotion() {
    const p = state.playing;
    const anim = state.animation;
    if (!anim || !anim.frames || anim.frames.length === 0) return;
    const last = p ? p.index : anim.frames.length - 1;
    const frames = anim.frames.slice(0, last + 1);
    if (state.showGhosts) {
      const every = Math.max(1, Math.round(anim.frames.length / 12));
      for (let i = 0; i < frames.length - 1; i += every) {
        const age = (frames.length - 1 - i) / Math.max(1, anim.frames.length - 1);
        drawArm(frames[i].joints, 0.06 + 0.16 * (1 - age), 5);
      }
    }
    if (state.showTraces && frames.length > 1) {
      const nj = frames[0].joints.length;
      ctx.lineWidth = 1.5;
      ctx.lineCap = "round";
      for (let j = 1; j < nj; j++) {
        const tip = j === nj - 1;
        ctx.strokeStyle = tip ? COLORS.path : COLORS.trace;
        ctx.globalAlpha = tip ? 1 : 0.7;
        ctx.lineWidth = tip ? 2.5 : 1.5;
        polyline(frames.map((f) => f.joints[j]));
        ctx.stroke();
      }
      ctx.globalAlpha = 1;
    }
  }

  function draw() {
    if (!state.arm) return;
    resize();
    drawGrid();
    drawArea();
    drawReach();
    drawMotion();
    drawBase();
    drawArm(state.joints);
    drawGoal();
  }

  let drawQueued = false;
  function requestDraw() {
    if (drawQueued) return;
    drawQueued = true;
    requestAnimationFrame(() => {
      drawQueued = false;
      draw();
    });
  }

  // ---- Requests built from the controls -----------------------------------------------------

  function armForRequest() {
    return {
      name: state.arm.name,
      base: state.arm.base,
      links: state.arm.links.map((l) => ({
        length: l.length,
        angle_deg: l.angle_deg,
        ...(l.limits_deg ? { limits_deg: l.limits_deg } : {}),
      })),
    };
  }

  function setPose(pose, joints) {
    state.pose_deg = pose.slice();
    state.joints = joints || forward(state.arm, state.pose_deg);
  }

  function setStats(s) {
    const parts = [`status ${s.status}`];
    if (s.iterations !== undefined) parts.push(`${s.iterations} iterations`);
    if (s.restarts) parts.push(`${s.restarts} restart${s.restarts === 1 ? "" : "s"}`);
    if (s.error !== undefined) parts.push(`error ${Number(s.error).toExponential(2)}`);
    if (s.solve_us !== undefined) parts.push(`${(s.solve_us / 1000).toFixed(3)} ms`);
    $("stats").textContent = parts.join(" · ");
  }

  // ---- Click: animate -----------------------------------------------------------------------

  let animateSeq = 0;

  async function animateTo(x, y) {
    stopPlayback();
    state.goal = { x, y };
    const seq = ++animateSeq;
    const base = {
      arm: armForRequest(),
      start_deg: state.pose_deg.slice(),
      goal: { x, y },
      options: state.options,
    };
    const animReq = { ...base, ease: state.ease, frames: state.frames };
    setStatus("solving");
    requestDraw();
    try {
      const [solved, anim] = await Promise.all([post("/api/solve", base), post("/api/animate", animReq)]);
      if (seq !== animateSeq) return;
      showError(null);
      state.lastResponse = solved;
      state.animation = anim;
      state.animationRequest = animReq;
      setStats(solved);
      await play(anim);
      if (seq !== animateSeq) return;
      setStatus(solved.status);
    } catch (e) {
      if (seq !== animateSeq) return;
      showError(e);
      setStatus("error");
      requestDraw();
    }
  }

  function stopPlayback() {
    if (state.playing) {
      state.playing.resolve();
      state.playing = null;
    }
  }

  function play(anim) {
    const frames = anim.frames || [];
    if (frames.length === 0) return Promise.resolve();
    const duration = frames[frames.length - 1].time || 1;
    return new Promise((resolve) => {
      const p = { start: performance.now(), index: 0, resolve };
      state.playing = p;
      const tick = (now) => {
        if (state.playing !== p) return;
        const t = ((now - p.start) / PLAYBACK_MS) * duration;
        while (p.index < frames.length - 1 && frames[p.index + 1].time <= t) p.index++;
        const f = frames[p.index];
        setPose(f.angles_deg, f.joints);
        draw();
        if (p.index >= frames.length - 1) {
          state.playing = null;
          resolve();
        } else {
          requestAnimationFrame(tick);
        }
      };
      requestAnimationFrame(tick);
    });
  }

  // ---- Follow: one solve in flight, always the latest goal ----------------------------------

  let followPending = null;
  let followInFlight = false;

  function followTo(x, y) {
    state.goal = { x, y };
    followPending = { x, y };
    requestDraw();
    pumpFollow();
  }

  async function pumpFollow() {
    if (followInFlight || !followPending) return;
    const goal = followPending;
    followPending = null;
    followInFlight = true;
    try {
      const res = await post("/api/solve", {
        arm: armForRequest(),
        start_deg: state.pose_deg.slice(),
        goal,
        options: { ...state.options, record_every: FOLLOW_RECORD_EVERY },
      });
      if (!state.playing) {
        showError(null);
        state.lastResponse = res;
        setPose(res.angles_deg, res.joints);
        setStats(res);
        setStatus(res.status);
        draw();
      }
    } catch (e) {
      showError(e);
      setStatus("error");
    } finally {
      followInFlight = false;
      if (followPending) pumpFollow();
    }
  }

  // ---- Workspace ----------------------------------------------------------------------------

  let workspaceSeq = 0;
  let workspaceTimer = 0;

  function refreshWorkspace() {
    clearTimeout(workspaceTimer);
    if (!state.showWorkspace) return;
    workspaceTimer = setTimeout(async () => {
      const seq = ++workspaceSeq;
      try {
        const ws = await post("/api/workspace", {
          arm: armForRequest(),
          limits: !!state.options.limits,
          resolution: WORKSPACE_RESOLUTION,
        });
        if (seq !== workspaceSeq) return;
        state.workspace = ws;
        areaImage = buildAreaImage(ws);
        requestDraw();
      } catch (e) {
        if (seq === workspaceSeq) showError(e);
      }
    }, 120);
  }

  // ---- Controls -----------------------------------------------------------------------------

  const num = (id) => {
    const v = $(id).value.trim();
    return v === "" ? undefined : Number(v);
  };

  function readOptions() {
    const o = { method: $("method").value, limits: $("limits").checked };
    if (o.limits) o.limit_mode = $("limit-mode").value;
    const fields = [
      ["restarts", "restarts"],
      ["lambda", "lambda"],
      ["tolerance", "tolerance"],
      ["max_iterations", "max-iterations"],
      ["record_every", "record-every"],
    ];
    for (const [key, id] of fields) {
      const v = num(id);
      if (v !== undefined) o[key] = v;
    }
    o.rates = state.arm.links.map((l) => (l.rate === undefined ? 1 : l.rate));
    state.options = o;
    const kind = $("ease").value;
    state.ease = { kind };
    $("k1").disabled = kind !== "parent";
    $("k2").disabled = kind !== "parent";
    if (kind === "parent") {
      const k1 = num("k1");
      const k2 = num("k2");
      if (k1 !== undefined) state.ease.k1 = k1;
      if (k2 !== undefined) state.ease.k2 = k2;
    }
    const frames = num("frames");
    state.frames = frames === undefined ? 60 : frames;
    $("lambda").disabled = o.method !== "dls" && o.method !== "lm";
    $("limit-mode").disabled = !o.limits;
  }

  function cellInput(value, label, onChange, step = "any") {
    const input = document.createElement("input");
    input.type = "number";
    input.step = step;
    input.value = value === undefined || value === null ? "" : String(value);
    input.setAttribute("aria-label", label);
    input.addEventListener("change", () => onChange(input.value.trim()));
    const td = document.createElement("td");
    td.append(input);
    return td;
  }

  function renderLinks() {
    const body = $("links-body");
    body.textContent = "";
    state.arm.links.forEach((link, i) => {
      const tr = document.createElement("tr");
      const n = document.createElement("td");
      n.textContent = String(i + 1);
      tr.append(n);
      const lim = link.limits_deg || [null, null];
      const setLimit = (k) => (v) => {
        const cur = link.limits_deg ? link.limits_deg.slice() : [-180, 180];
        if (v === "") {
          link.limits_deg = null;
        } else {
          cur[k] = Number(v);
          link.limits_deg = cur;
        }
        renderLinks();
        armChanged();
      };
      tr.append(
        cellInput(link.length, `Link ${i + 1} length`, (v) => {
          link.length = v === "" ? 0 : Number(v);
          armChanged();
        }, "0.1"),
        cellInput(lim[0], `Link ${i + 1} minimum angle, degrees`, setLimit(0), "1"),
        cellInput(lim[1], `Link ${i + 1} maximum angle, degrees`, setLimit(1), "1"),
        cellInput(link.rate === undefined ? 1 : link.rate, `Joint ${i + 1} rate`, (v) => {
          link.rate = v === "" ? 1 : Number(v);
          controlsChanged();
        }, "0.1"),
      );
      const td = document.createElement("td");
      const rm = document.createElement("button");
      rm.type = "button";
      rm.textContent = "×";
      rm.setAttribute("aria-label", `Remove link ${i + 1}`);
      rm.disabled = state.arm.links.length <= 1;
      rm.addEventListener("click", () => {
        state.arm.links.splice(i, 1);
        state.pose_deg.splice(i, 1);
        renderLinks();
        armChanged();
      });
      td.append(rm);
      tr.append(td);
      body.append(tr);
    });
  }

  function armChanged() {
    // The pose keeps one angle per link; a new link starts straight.
    while (state.pose_deg.length < state.arm.links.length) state.pose_deg.push(0);
    state.pose_deg.length = state.arm.links.length;
    state.animation = null;
    state.workspace = null;
    areaImage = null;
    readOptions();
    setPose(state.pose_deg);
    requestDraw();
    refreshWorkspace();
  }

  function controlsChanged() {
    readOptions();
    requestDraw();
  }

  function resetPose() {
    stopPlayback();
    animateSeq++;
    state.animation = null;
    setPose(state.arm.links.map((l) => l.angle_deg));
    setStatus("ready");
    $("stats").textContent = "—";
    showError(null);
    requestDraw();
  }

  // ---- Downloads ----------------------------------------------------------------------------

  function saveBlob(blob, name) {
    const url = URL.createObjectURL(blob);
    const a = document.createElement("a");
    a.href = url;
    a.download = name;
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(url), 1000);
  }

  function framesOrSay() {
    if (state.animation) return state.animation;
    const e = new Error("No motion yet: click on the canvas to make one.");
    e.api = true; // a message for the reader, not a fault
    showError(e);
    return null;
  }

  function framesCsv(anim) {
    const nj = anim.frames[0] ? anim.frames[0].angles_deg.length : 0;
    const head = ["time"];
    for (let i = 0; i < nj; i++) head.push(`angle${i + 1}_deg`);
    for (let i = 0; i <= nj; i++) head.push(`x${i}`, `y${i}`);
    const rows = anim.frames.map((f) => [f.time, ...f.angles_deg, ...f.joints.flat()].join(","));
    return [head.join(","), ...rows].join("\n") + "\n";
  }

  async function renderFigure(format) {
    const [w, h] = [800, 800];
    const button = $(`dl-${format}`);
    const label = button.textContent;
    try {
      let body;
      if (format === "gif") {
        if (!framesOrSay()) return;
        body = { figure: "motion", format, width: 480, height: 480, ...state.animationRequest };
      } else {
        body = {
          figure: "arm",
          format,
          width: w,
          height: h,
          arm: armForRequest(),
          pose_deg: state.pose_deg.slice(),
          ...(state.goal ? { goal: state.goal } : {}),
          ...(state.showWorkspace ? { workspace: true, limits: !!state.options.limits } : {}),
        };
      }
      button.disabled = true;
      button.textContent = "Rendering…";
      const blob = await post("/api/render", body, "blob");
      showError(null);
      saveBlob(blob, `ikarus-${format === "gif" ? "motion" : "arm"}.${format}`);
    } catch (e) {
      showError(e);
    } finally {
      button.disabled = false;
      button.textContent = label;
    }
  }

  // ---- Pointer and keyboard -----------------------------------------------------------------

  let press = null; // {x, y, dragging}

  function eventWorld(ev) {
    const r = canvas.getBoundingClientRect();
    return toWorld(ev.clientX - r.left, ev.clientY - r.top);
  }

  canvas.addEventListener("pointerdown", (ev) => {
    if (!state.arm || ev.button !== 0) return;
    press = { x: ev.clientX, y: ev.clientY, dragging: false };
    canvas.setPointerCapture(ev.pointerId);
  });

  canvas.addEventListener("pointermove", (ev) => {
    if (!state.arm) return;
    if (press && !press.dragging && Math.hypot(ev.clientX - press.x, ev.clientY - press.y) > DRAG_PIXELS) {
      press.dragging = true;
      stopPlayback();
      animateSeq++;
    }
    if (state.follow || (press && press.dragging)) {
      const [x, y] = eventWorld(ev);
      followTo(x, y);
    }
  });

  canvas.addEventListener("pointerup", (ev) => {
    if (!press) return;
    const wasDrag = press.dragging;
    press = null;
    if (!wasDrag && !state.follow) {
      const [x, y] = eventWorld(ev);
      animateTo(x, y);
    }
  });

  canvas.addEventListener("pointercancel", () => {
    press = null;
  });

  canvas.addEventListener("keydown", (ev) => {
    if (!state.arm) return;
    const step = maxReach() / 40;
    const g = state.goal || { x: state.joints[state.joints.length - 1][0], y: state.joints[state.joints.length - 1][1] };
    const moves = { ArrowLeft: [-step, 0], ArrowRight: [step, 0], ArrowUp: [0, step], ArrowDown: [0, -step] };
    if (moves[ev.key]) {
      ev.preventDefault();
      const [dx, dy] = moves[ev.key];
      if (state.follow) followTo(g.x + dx, g.y + dy);
      else {
        state.goal = { x: g.x + dx, y: g.y + dy };
        requestDraw();
      }
    } else if (ev.key === "Enter" && state.goal) {
      ev.preventDefault();
      animateTo(state.goal.x, state.goal.y);
    }
  });

  // ---- Wiring -------------------------------------------------------------------------------

  function wire() {
    for (const id of ["method", "limit-mode", "restarts", "lambda", "tolerance", "max-iterations", "record-every", "ease", "k1", "k2", "frames"]) {
      $(id).addEventListener("change", controlsChanged);
    }
    $("limits").addEventListener("change", () => {
      controlsChanged();
      refreshWorkspace();
    });
    $("follow").addEventListener("change", (ev) => {
      state.follow = ev.target.checked;
    });
    $("show-ghosts").addEventListener("change", (ev) => {
      state.showGhosts = ev.target.checked;
      requestDraw();
    });
    $("show-traces").addEventListener("change", (ev) => {
      state.showTraces = ev.target.checked;
      requestDraw();
    });
    $("show-workspace").addEventListener("change", (ev) => {
      state.showWorkspace = ev.target.checked;
      if (state.showWorkspace) refreshWorkspace();
      requestDraw();
    });
    $("add-link").addEventListener("click", () => {
      if (state.arm.links.length >= 64) return;
      const last = state.arm.links[state.arm.links.length - 1];
      state.arm.links.push({ length: last ? last.length : 1, angle_deg: 0, limits_deg: [-170, 170] });
      renderLinks();
      armChanged();
    });
    $("reset").addEventListener("click", resetPose);
    $("dl-json").addEventListener("click", () => {
      const anim = framesOrSay();
      if (anim) saveBlob(new Blob([JSON.stringify(anim, null, 2)], { type: "application/json" }), "ikarus-frames.json");
    });
    $("dl-csv").addEventListener("click", () => {
      const anim = framesOrSay();
      if (anim) saveBlob(new Blob([framesCsv(anim)], { type: "text/csv" }), "ikarus-frames.csv");
    });
    $("dl-png").addEventListener("click", () => renderFigure("png"));
    $("dl-svg").addEventListener("click", () => renderFigure("svg"));
    $("dl-gif").addEventListener("click", () => renderFigure("gif"));
    const narrow = window.matchMedia("(max-width: 720px)");
    const toggle = $("panel-toggle");
    const setCollapsed = (c) => {
      document.body.classList.toggle("collapsed", c);
      toggle.setAttribute("aria-expanded", String(!c));
      toggle.textContent = c ? "Show controls" : "Hide controls";
      requestDraw();
    };
    toggle.addEventListener("click", () => setCollapsed(!document.body.classList.contains("collapsed")));
    if (narrow.matches) setCollapsed(true);
    new ResizeObserver(requestDraw).observe(canvas);
    window.addEventListener("resize", requestDraw);
  }

  async function init() {
    wire();
    try {
      const res = await fetch("/api/arm/default");
      if (!res.ok) throw new Error(`/api/arm/default: HTTP ${res.status}`);
      const arm = await res.json();
      state.initialArm = JSON.parse(JSON.stringify(arm));
      state.arm = arm;
      renderLinks();
      readOptions();
      setPose(arm.links.map((l) => l.angle_deg));
      setStatus("ready");
      window.ikarus.ready = true;
      draw();
    } catch (e) {
      showError(e);
      setStatus("error");
    }
  }

  // For scripts and browser tests: the page's state and a few actions.
  window.ikarus = {
    state,
    ready: false,
    animateTo,
    followTo,
    resetPose,
    // Client coordinates of a world point, for clicking on it.
    toClient(x, y) {
      const r = canvas.getBoundingClientRect();
      const [px, py] = toCanvas(x, y);
      return [r.left + px, r.top + py];
    },
  };

  init();
})();
